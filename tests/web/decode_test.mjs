// The web decoder in Node (ctest -L web): decode.mjs writes the triangles `subdfit decode`
// writes for each kind of asset, and refuses damaged or hostile files in one line, quickly and
// within a bounded memory.
//   WEB=<build/web> ASSETS=<fixture dir> HOSTILE=<dir> SUBDFIT=<subdfit> NODE_MODULES=<apps/web/node_modules>
//   [DEMO=<README demo's asset.subd>] node --test decode_test.mjs
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { readTriangles, triangleDistance } from './glb.mjs';

const { WEB, ASSETS, HOSTILE, SUBDFIT, DEMO, NODE_MODULES } = process.env;
// three's meshopt decoder, for a glb `subdfit decode` writes with EXT_meshopt_compression.
const meshopt = async () => {
  const { MeshoptDecoder } = await import(path.join(NODE_MODULES, 'three/examples/jsm/libs/meshopt_decoder.module.js'));
  await MeshoptDecoder.ready;
  return MeshoptDecoder;
};
const scratch = path.join(path.dirname(ASSETS), 'decode-test');
fs.rmSync(scratch, { recursive: true, force: true });
fs.mkdirSync(scratch, { recursive: true });
const decodeMjs = path.join(WEB, 'decode.mjs');

function decode(input, output, ...extra) {
  return spawnSync(process.execPath, [decodeMjs, input, output, ...extra], { encoding: 'utf8', timeout: 120_000 });
}

async function expectSameTriangles(native, web) {
  const [a, b] = [await readTriangles(native, meshopt), await readTriangles(web)];
  assert.equal(b.indices.length, a.indices.length, 'triangle count');
  assert.equal(b.positions.length, a.positions.length, 'vertex count');
  const distance = triangleDistance(a, b);
  assert.ok(distance <= 1e-5, `positions differ by ${distance} of the bounding box diagonal`);
}

const kinds = fs.readdirSync(ASSETS).filter((name) => fs.existsSync(path.join(ASSETS, name, 'asset.subd')));
test('the fixture made every kind of asset', () => {
  assert.deepEqual(kinds.sort(), ['bare', 'creased', 'spot', 'textured', 'textured_atlas']);
});

for (const kind of kinds) {
  const dir = path.join(ASSETS, kind);
  test(`${kind}: the same triangles as subdfit decode, by default and with --triangles`, async () => {
    const web = path.join(scratch, `${kind}.glb`);
    const run = decode(path.join(dir, 'asset.subd'), web);
    assert.equal(run.status, 0, run.stderr);
    await expectSameTriangles(path.join(dir, 'native.glb'), web);
    const web5000 = path.join(scratch, `${kind}_5000.glb`);
    const dense = decode(path.join(dir, 'asset.subd'), web5000, '--triangles', '5000');
    assert.equal(dense.status, 0, dense.stderr);
    await expectSameTriangles(path.join(dir, 'native_5000.glb'), web5000);
    assert.notEqual((await readTriangles(web5000)).indices.length, (await readTriangles(web)).indices.length,
                    '--triangles changed nothing');
  });
}

test('the README demo: the same triangles as subdfit decode', { skip: !DEMO || !fs.existsSync(DEMO) ? 'no README demo result (README command 1 makes out/relief_spot/asset.subd)' : false }, async () => {
  const native = path.join(scratch, 'demo_native.glb'), web = path.join(scratch, 'demo_web.glb');
  const run = spawnSync(SUBDFIT, ['decode', DEMO, '--out', native], { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr);
  assert.equal(decode(DEMO, web).status, 0);
  await expectSameTriangles(native, web);
});

// One stderr line that says `expected` (and names the file, for a file's problem), a failed
// exit, no output.
function expectRefused(input, expected, ...extra) {
  const output = path.join(scratch, `refused_${path.basename(input)}.glb`);
  const run = decode(input, output, ...extra);
  assert.notEqual(run.error?.code, 'ETIMEDOUT', `${input}: no answer in 120 s`);
  assert.equal(run.status, 1, `${input}: exit ${run.status}`);
  const lines = run.stderr.trimEnd().split('\n');
  assert.equal(lines.length, 1, run.stderr);
  assert.match(lines[0], new RegExp(`^decode\\.mjs: .*${expected}`), lines[0]);
  if (extra.length === 0) assert.ok(lines[0].includes(input), `the message names the file: ${lines[0]}`);
  assert.equal(fs.existsSync(output), false, 'a refused file leaves no output');
  assert.deepEqual(fs.readdirSync(scratch).filter((name) => name.endsWith('.partial')), []);
}

test('damaged files are refused in one line', () => {
  const good = fs.readFileSync(path.join(ASSETS, 'spot', 'asset.subd'));
  const variant = (name, change) => {
    const bytes = Buffer.from(good);
    const changed = change(bytes) ?? bytes;
    fs.writeFileSync(path.join(scratch, name), changed);
    return path.join(scratch, name);
  };
  expectRefused(variant('flipped.subd', (b) => { b[b.length >> 1] ^= 0x40; }), 'checksum mismatch');
  expectRefused(variant('truncated.subd', (b) => b.subarray(0, b.length >> 1)), 'checksum mismatch \\(damaged or truncated\\)');
  expectRefused(variant('header_only.subd', (b) => b.subarray(0, 10)), 'truncated');
  expectRefused(variant('version.subd', (b) => { b[4] = 9; }), '\\.subd version 9, this subdfit reads version');
  expectRefused(variant('empty.subd', () => Buffer.alloc(0)), 'not a \\.subd file');
  expectRefused(variant('not_subd.subd', () => fs.readFileSync(path.join(ASSETS, 'spot', 'native.glb'))), 'not a \\.subd file');
  expectRefused(path.join(scratch, 'missing.subd'), 'no such file');
});

test('hostile files are refused quickly, within a bounded memory', async () => {
  expectRefused(path.join(HOSTILE, 'too_many_triangles.subd'), 'triangles, more than decode writes');
  expectRefused(path.join(HOSTILE, 'zstd_bomb.subd'), 'section CAGE too large');
  expectRefused(path.join(HOSTILE, 'raw_size_lie.subd'), 'does not decompress to its stated size');
  expectRefused(path.join(HOSTILE, 'one_quad.subd'), '--triangles: must be a whole number', '--triangles', '-5');
  assert.equal(decode(path.join(HOSTILE, 'one_quad.subd'), path.join(scratch, 'one_quad.glb')).status, 0);

  // In one instance: each refusal leaves the WebAssembly memory as it was (nothing allocated
  // for what the file asked), and the instance decodes the next file.
  const { createDecoderInstance } = await import(path.join(WEB, 'subd_core.mjs'));
  const decoder = await createDecoderInstance(fs.readFileSync(path.join(WEB, 'subd_decoder_wasm.wasm')));
  const memory = () => decoder.memoryBytes();
  const start = memory();
  for (const name of ['too_many_triangles.subd', 'zstd_bomb.subd', 'raw_size_lie.subd']) {
    assert.throws(() => decoder.decode(fs.readFileSync(path.join(HOSTILE, name)), { name }), new RegExp(`^Error: ${name}: `));
    assert.ok(memory() <= Math.max(start, 64 << 20), `${name}: the memory grew to ${memory()} bytes`);
  }
  const quad = decoder.decode(fs.readFileSync(path.join(HOSTILE, 'one_quad.subd')), { name: 'one_quad.subd' });
  assert.equal(quad.indices.length / 3, 2 * 8 * 8);
});
