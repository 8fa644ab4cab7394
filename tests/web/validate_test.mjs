// What `subdfit decode` writes for engines, checked with the Khronos glTF validator
// (npm gltf-validator, pinned in apps/web/package.json) and three's meshopt decoder (ctest -L web):
// for each kind of asset, the default (KHR_mesh_quantization alone: read with no decoder), a chain
// of levels, the --meshopt file and the --uncompressed one validate with no error and no warning;
// the quantised files hold the --uncompressed one's triangles within their quantisation, every
// index in range; a material, texture coordinates and tangents only where an image reads them.
//   ASSETS=<fixture dir> SUBDFIT=<subdfit> NODE_MODULES=<apps/web/node_modules> node --test validate_test.mjs
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { readTriangles, threeMeshoptDecoder, triangleDistance } from './glb.mjs';

const { ASSETS, SUBDFIT, NODE_MODULES } = process.env;
const validator = await import(path.join(NODE_MODULES, 'gltf-validator/module.mjs'));
const meshopt = threeMeshoptDecoder(NODE_MODULES);
const scratch = path.join(path.dirname(ASSETS), 'validate-test');
fs.rmSync(scratch, { recursive: true, force: true });
fs.mkdirSync(scratch, { recursive: true });

function decode(input, output, ...extra) {
  const run = spawnSync(SUBDFIT, ['decode', input, '--out', output, ...extra], { encoding: 'utf8', timeout: 300_000 });
  assert.equal(run.status, 0, run.stderr);
}

async function expectValid(file) {
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 50 });
  const problems = report.issues.messages.filter((m) => m.severity <= 1).map((m) => `${m.code} ${m.pointer}: ${m.message}`);
  assert.deepEqual(problems, [], `${path.basename(file)}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings`);
}

const kinds = fs.readdirSync(ASSETS).filter((name) => fs.existsSync(path.join(ASSETS, name, 'asset.subd')));
for (const kind of kinds) {
  test(`${kind}: decode's files validate, and the compact one holds the float one's triangles`, async () => {
    const subd = path.join(ASSETS, kind, 'asset.subd');
    const compact = path.join(scratch, `${kind}.glb`), plain = path.join(scratch, `${kind}_float.glb`);
    const packed = path.join(scratch, `${kind}_meshopt.glb`);
    decode(subd, compact, '--lods', '2');
    decode(subd, packed, '--meshopt');
    decode(subd, plain, '--uncompressed');
    for (const file of [compact, path.join(scratch, `${kind}_lod1.glb`), packed, plain]) await expectValid(file);
    const a = await readTriangles(plain);
    // The default needs no decoder: readTriangles without one throws on EXT_meshopt_compression.
    const b = await readTriangles(compact), c = await readTriangles(packed, meshopt);
    assert.deepEqual(b.json.extensionsRequired, ['KHR_mesh_quantization']);
    assert.deepEqual(c.json.extensionsRequired, ['EXT_meshopt_compression', 'KHR_mesh_quantization']);
    for (const q of [b, c]) {
      const vertices = q.positions.length / 3;
      assert.ok(q.indices.every((i) => i < vertices), 'an index past the vertices');
      assert.ok(q.positions.every(Number.isFinite), 'a position that is not finite');
      // 14-bit positions over the bounding cube: half a step on each axis at most.
      const distance = triangleDistance(a, q);
      assert.ok(distance <= Math.sqrt(3) * 0.5 / ((1 << 14) - 1) + 1e-6, `positions differ by ${distance} of the diagonal`);
    }
    // An asset without an appearance has no material (drawn as its reference, which had none),
    // no texture coordinates and no tangents, in every coding.
    for (const q of [a, b, c]) {
      const attributes = q.json.meshes[0].primitives[0].attributes;
      const images = (q.json.images ?? []).length > 0;
      if (kind === 'creased' || kind === 'bare') assert.equal(images, false, 'heights alone make no image');
      assert.equal(q.json.materials !== undefined, images, 'a material');
      assert.equal('TEXCOORD_0' in attributes, images, 'texture coordinates');
      if ('TANGENT' in attributes) assert.ok(q.json.materials[0].normalTexture, 'tangents with no normal texture');
    }
  });
}
