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

test('a prefix: the same triangles as subdfit decode --bytes', async () => {
  const subd = path.join(ASSETS, 'spot', 'asset.subd');
  const file = fs.readFileSync(subd);
  const cageEnd = 28 + file.readUInt32LE(20);  // the first section's end
  const bytes = String(cageEnd + Math.floor((file.length - cageEnd) / 2));
  const native = path.join(scratch, 'prefix_native.glb'), web = path.join(scratch, 'prefix_web.glb');
  const run = spawnSync(SUBDFIT, ['decode', subd, '--out', native, '--uncompressed', '--bytes', bytes], { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr);
  const webRun = decode(subd, web, '--bytes', bytes);
  assert.equal(webRun.status, 0, webRun.stderr);
  await expectSameTriangles(native, web);
  expectRefused(subd, 'end before the cage does', '--bytes', String(cageEnd - 1));
});

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
  expectRefused(variant('version.subd', (b) => { b[4] = 200; }), '\\.subd version 200, this subdfit reads version');
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

test('only a regular file within the limit is read, and only a regular file is replaced', () => {
  // A symlink to /dev/zero would never end; a FIFO would block forever; a folder is no file.
  const zero = path.join(scratch, 'zero.subd');
  fs.rmSync(zero, { force: true });
  fs.symlinkSync('/dev/zero', zero);
  expectRefused(zero, 'is not a regular file');
  const fifo = path.join(scratch, 'fifo.subd');
  fs.rmSync(fifo, { force: true });
  spawnSync('mkfifo', [fifo]);
  expectRefused(fifo, 'is not a regular file');
  const folder = path.join(scratch, 'folder.subd');
  fs.mkdirSync(folder, { recursive: true });
  expectRefused(folder, 'is a folder');

  // OUT a symlink to a regular file, a folder, a FIFO, the input by another name, a name past
  // 255 bytes: refused before any work, nothing replaced.
  const good = path.join(ASSETS, 'bare', 'asset.subd');
  const target = path.join(scratch, 'target.glb');
  fs.writeFileSync(target, 'keep');
  const refusedOut = (output, expected) => {
    const run = decode(good, output);
    assert.equal(run.status, 1, `${output}: exit ${run.status}`);
    assert.match(run.stderr.trim(), new RegExp(`^decode\\.mjs: .*${expected}`));
  };
  const link = path.join(scratch, 'link.glb');
  fs.rmSync(link, { force: true });
  fs.symlinkSync(target, link);
  refusedOut(link, 'is a symlink');
  assert.equal(fs.readFileSync(target, 'utf8'), 'keep');
  refusedOut(folder, 'is a folder');
  refusedOut(fifo, 'is not a regular file');
  const hardlink = path.join(scratch, 'same.subd');
  fs.rmSync(hardlink, { force: true });
  fs.copyFileSync(good, path.join(scratch, 'input.subd'));
  fs.linkSync(path.join(scratch, 'input.subd'), hardlink);
  const run = decode(path.join(scratch, 'input.subd'), hardlink);
  assert.equal(run.status, 1);
  assert.match(run.stderr, /is the input/);
  refusedOut(path.join(scratch, `${'a'.repeat(252)}.glb`), 'more than the 255 a file name may have');
  assert.deepEqual(fs.readdirSync(scratch).filter((name) => name.endsWith('.partial')), []);
});

test('damage inside a section is refused as subdfit decode refuses it', () => {
  // tests/data/damaged-subd (its README): a flipped bit inside a zstd frame, an unsound JPEG.
  const damaged = path.join(HOSTILE, '..', 'damaged-subd');
  for (const [name, expected] of [['section_bit_flipped.subd', 'section DISP fails its checksum \\(damaged\\)'],
                                  ['jpeg_huffman_table_damaged.subd', 'BCOL section: a damaged JPEG \\(a bad Huffman table\\)']]) {
    expectRefused(path.join(damaged, name), expected);
    const native = spawnSync(SUBDFIT, ['decode', path.join(damaged, name), '--out', path.join(scratch, 'native_damaged.glb')],
                             { encoding: 'utf8' });
    assert.equal(native.status, 1);
    assert.match(native.stderr.trim(), new RegExp(`^subdfit: error: .*${expected}$`));
  }
  const box = decode(path.join(damaged, 'box.subd'), path.join(scratch, 'box.glb'));
  assert.equal(box.status, 0, box.stderr);
});

test('mutated files decode or are refused in one line, in one instance, within its memory', async () => {
  // Seeded byte mutations and truncations of each kind of asset through one instance: nearly all
  // stop at the file's checksum, so this checks the module's refusal path and its memory over many
  // refusals; hostile contents behind a valid checksum are fuzzed natively (tests/fuzz/fuzz_web.cpp,
  // the same C++). Every answer must be a decode or one Error line naming the file.
  const { createDecoderInstance } = await import(path.join(WEB, 'subd_core.mjs'));
  const decoder = await createDecoderInstance(fs.readFileSync(path.join(WEB, 'subd_decoder_wasm.wasm')));
  let seed = 12345;
  const random = () => (seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32;
  let decoded = 0, refused = 0;
  for (const kind of kinds) {
    const good = fs.readFileSync(path.join(ASSETS, kind, 'asset.subd'));
    for (let k = 0; k < 40; ++k) {
      const bytes = Buffer.from(good);
      const edits = 1 + Math.floor(random() * 4);
      for (let e = 0; e < edits; ++e) {
        const at = Math.floor(random() * bytes.length);
        if (random() < 0.5) bytes[at] ^= 1 << Math.floor(random() * 8);
        else bytes[at] = Math.floor(random() * 256);
      }
      const cut = random() < 0.2 ? bytes.subarray(0, Math.floor(random() * bytes.length)) : bytes;
      try {
        decoder.decode(new Uint8Array(cut.buffer, cut.byteOffset, cut.byteLength), { name: `${kind}_${k}.subd` });
        ++decoded;
      } catch (error) {
        assert.match(String(error), new RegExp(`^Error: ${kind}_${k}\\.subd: [^\\n]+$`));
        ++refused;
      }
      assert.ok(decoder.memoryBytes() <= 1024 * 2 ** 20, `${kind}_${k}: the memory grew to ${decoder.memoryBytes()} bytes`);
    }
  }
  assert.equal(decoded + refused, 40 * kinds.length);
});
