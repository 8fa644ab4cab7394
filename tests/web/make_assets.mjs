// CTest fixture of the web tests: small asset.subd files of each kind the decoder reads, made
// by this build's subdfit in seconds, with `subdfit decode --uncompressed`'s glb of each (default
// density and --triangles): float positions, as the web decoder's decode.mjs writes them. Files
// already there are kept unless this subdfit is newer.
//   SUBDFIT=<subdfit> node make_assets.mjs SOURCE_DIR OUT_DIR
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const [source, out] = process.argv.slice(2);
const subdfit = process.env.SUBDFIT;
if (!source || !out || !subdfit) throw new Error('usage: SUBDFIT=<subdfit> node make_assets.mjs SOURCE_DIR OUT_DIR');
const shapes = path.join(source, 'assets/osd-shapes');
const quick = ['--steps', '20', '--res', '64', '--views', '4', '--holdout-views', '1'];

// name -> the subdfit command that writes <name>/asset.subd
const ASSETS = {
  // A simplified mesh with heights and a normal map: the README demo's kind of result, smaller.
  spot: ['simplify', path.join(source, 'assets/spot/spot_triangulated.obj'), '--faces', '200',
         '--maps', 'displacement,normal', ...quick],
  // Semi-sharp creases and heights.
  creased: ['fit', '--cage', path.join(shapes, 'catmark_torus_creases1.obj'), '--reference',
            path.join(source, 'assets/spot/spot_triangulated.obj'), '--maps', 'displacement', '--map-res', '3', ...quick],
  // A base colour on tiles, and one in the reference's own texture atlas.
  textured: ['simplify', path.join(source, 'assets/gltf/Duck/Duck.glb'), '--faces', '150', ...quick],
  textured_atlas: ['simplify', path.join(source, 'assets/gltf/Duck/Duck.glb'), '--faces', '150',
                   '--appearance-atlas', '64', ...quick],
  // A cage alone (CAGE only), with holes.
  bare: ['fit', '--cage', path.join(shapes, 'catmark_hole_test1.obj'), '--reference',
         path.join(source, 'assets/spot/spot_triangulated.obj'), '--maps', 'none', ...quick],
};

function run(args) {
  const result = spawnSync(subdfit, args, { encoding: 'utf8', timeout: 300_000 });
  if (result.status !== 0) throw new Error(`subdfit ${args.join(' ')}: ${result.error ?? result.stderr.trim().split('\n').pop()}`);
}

const built = fs.statSync(subdfit).mtimeMs;
const current = (file) => fs.existsSync(file) && fs.statSync(file).mtimeMs >= built;

for (const [name, command] of Object.entries(ASSETS)) {
  const dir = path.join(out, name);
  if (!current(path.join(dir, 'asset.subd'))) {
    fs.rmSync(dir, { recursive: true, force: true });
    run([...command, '--out', dir]);
  }
  for (const [glb, extra] of [['native.glb', []], ['native_50000.glb', ['--triangles', '50000']]])
    if (!current(path.join(dir, glb)))
      run(['decode', path.join(dir, 'asset.subd'), '--out', path.join(dir, glb), '--uncompressed', ...extra]);
  process.stdout.write(`${name}: ${fs.statSync(path.join(dir, 'asset.subd')).size} bytes\n`);
}
