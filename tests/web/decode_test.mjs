// The web decoder in Node (ctest -L web): decode.mjs writes the triangles `subdfit decode
// --uncompressed` writes for each kind of asset, and refuses damaged or hostile files in one
// line, quickly and within a bounded memory.
//   WEB=<build/web> ASSETS=<fixture dir> HOSTILE=<dir> SUBDFIT=<subdfit> NODE_MODULES=<apps/web/node_modules>
//   [DEMO=<README demo's asset.subd>] node --test decode_test.mjs
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { readTriangles, threeMeshoptDecoder, triangleDistance } from './glb.mjs';

const { WEB, ASSETS, HOSTILE, SUBDFIT, DEMO, NODE_MODULES } = process.env;
// three's meshopt decoder, for a glb `subdfit decode` writes with EXT_meshopt_compression.
const meshopt = threeMeshoptDecoder(NODE_MODULES);
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
    const webDense = path.join(scratch, `${kind}_50000.glb`);
    const dense = decode(path.join(dir, 'asset.subd'), webDense, '--triangles', '50000');
    assert.equal(dense.status, 0, dense.stderr);
    await expectSameTriangles(path.join(dir, 'native_50000.glb'), webDense);
    assert.notEqual((await readTriangles(webDense)).indices.length, (await readTriangles(web)).indices.length,
                    '--triangles changed nothing');
  });
}

test('the README demo: the same triangles as subdfit decode', { skip: !DEMO || !fs.existsSync(DEMO) ? 'no README demo result (README command 1 makes out/relief_spot/asset.subd)' : false }, async () => {
  const native = path.join(scratch, 'demo_native.glb'), web = path.join(scratch, 'demo_web.glb');
  const run = spawnSync(SUBDFIT, ['decode', DEMO, '--out', native, '--uncompressed'], { encoding: 'utf8' });
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
  // tests/data/hostile-subd (its README says what each states): the decode budget, the section
  // sizes their counts allow, the node counts the cage allows, checked before anything is built.
  const refusals = {
    'plain_2m_quads.subd': 'a cage of 2002225 faces would take about \\d+ MB to decode, more than the 768 MB',
    'zstd_bomb.subd': 'section CAGE holds \\d+ bytes, more than its counts allow',
    'one_node_at_resolution_64.subd': 'node count',
  };
  for (const [name, expected] of Object.entries(refusals)) expectRefused(path.join(HOSTILE, name), expected);
  // Refused once its (legitimately decoded) million-quad cage prices its map lattice.
  expectRefused(path.join(HOSTILE, 'heights_on_1m_faces.subd'), 'MB a decode may use');
  const bare = path.join(ASSETS, 'bare', 'asset.subd');
  expectRefused(bare, '--triangles: must be a whole number', '--triangles', '-5');
  expectRefused(bare, 'triangles: must be in 0\\.\\.4194304', '--triangles', '99999999');

  // In one instance: each refusal leaves the WebAssembly memory as it was (nothing allocated
  // for what the file asked), and the instance decodes the next file.
  const { createDecoderInstance } = await import(path.join(WEB, 'subd_core.mjs'));
  const decoder = await createDecoderInstance(fs.readFileSync(path.join(WEB, 'subd_decoder_wasm.wasm')));
  const memory = () => decoder.memoryBytes();
  const start = memory();
  for (const name of Object.keys(refusals)) {
    assert.throws(() => decoder.decode(fs.readFileSync(path.join(HOSTILE, name)), { name }), new RegExp(`^Error: ${name}: `));
    assert.ok(memory() <= Math.max(start, 64 << 20), `${name}: the memory grew to ${memory()} bytes`);
  }
  const decoded = decoder.decode(fs.readFileSync(bare), { name: 'bare.subd' });
  assert.equal(decoded.indices.length, (await readTriangles(path.join(ASSETS, 'bare', 'native.glb'), meshopt)).indices.length);
});
