#!/usr/bin/env node
// `subdfit decode` in Node, through the web decoder: asset.subd -> .glb of the same triangles.
//   node decode.mjs IN.subd OUT.glb [--triangles N]
// One line on stderr and exit status 1 for anything it refuses; OUT is written whole or not at all.
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { createDecoderInstance } from './subd_core.mjs';

const USAGE = 'usage: node decode.mjs IN.subd OUT.glb [--triangles N]';

function parseArguments(args) {
  const positional = [];
  let triangles = 0;
  for (let k = 0; k < args.length; ++k) {
    if (args[k] === '--triangles') {
      const text = args[++k];
      if (text === undefined || !/^[0-9]+$/.test(text) || Number(text) < 1 || !Number.isSafeInteger(Number(text)))
        throw new Error(`--triangles: must be a whole number >= 1, got ${text ?? 'nothing'}`);
      triangles = Number(text);
    } else if (args[k].startsWith('-')) {
      throw new Error(`unknown option ${args[k]} (${USAGE})`);
    } else {
      positional.push(args[k]);
    }
  }
  if (positional.length !== 2) throw new Error(USAGE);
  return { input: positional[0], output: positional[1], triangles };
}

// PNG of 8-bit RGBA rows, top first (PNG 1.2: signature, IHDR, one IDAT, IEND).
function encodePng(width, height, rgba) {
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc32 = (bytes) => {
    let c = 0xffffffff;
    for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
  };
  const chunk = (type, data) => {
    const out = Buffer.alloc(12 + data.length);
    out.writeUInt32BE(data.length, 0);
    out.write(type, 4, 'ascii');
    data.copy(out, 8);
    out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
    return out;
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header.set([8, 6, 0, 0, 0], 8);  // 8-bit RGBA, deflate, no filter method, no interlace
  const rows = Buffer.alloc(height * (1 + 4 * width));
  for (let y = 0; y < height; ++y) rows.set(rgba.subarray(4 * width * y, 4 * width * (y + 1)), y * (1 + 4 * width) + 1);
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', header),
                        chunk('IDAT', zlib.deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
}

// The glb `subdfit decode` writes for the same surface: one mesh, the material and its images.
function glbOf(decoded) {
  const views = [], chunks = [];
  let length = 0;
  const addView = (bytes, target) => {
    const padding = (4 - (length % 4)) % 4;
    if (padding) chunks.push(Buffer.alloc(padding));
    length += padding;
    const view = { buffer: 0, byteOffset: length, byteLength: bytes.byteLength };
    if (target) view.target = target;
    chunks.push(Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength));
    length += bytes.byteLength;
    views.push(view);
    return views.length - 1;
  };
  const vertexCount = decoded.positions.length / 3;
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < vertexCount; ++v)
    for (let a = 0; a < 3; ++a) {
      min[a] = Math.min(min[a], decoded.positions[3 * v + a]);
      max[a] = Math.max(max[a], decoded.positions[3 * v + a]);
    }
  const accessors = [], attributes = {};
  const addAccessor = (name, array, type) => {
    attributes[name] = accessors.length;
    accessors.push({ bufferView: addView(array, 34962), componentType: 5126, count: vertexCount, type });
  };
  addAccessor('POSITION', decoded.positions, 'VEC3');
  Object.assign(accessors[0], { min, max });
  addAccessor('NORMAL', decoded.normals, 'VEC3');
  if (decoded.tangents) addAccessor('TANGENT', decoded.tangents, 'VEC4');
  addAccessor('TEXCOORD_0', decoded.uvs, 'VEC2');
  accessors.push({ bufferView: addView(decoded.indices, 34963), componentType: 5125, count: decoded.indices.length, type: 'SCALAR' });

  const m = decoded.material;
  const doc = {
    asset: { version: '2.0', generator: 'subdfit decode.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name: 'fitted' }],
    meshes: [{ name: 'fitted', primitives: [{ attributes, indices: accessors.length - 1, mode: 4, material: 0 }] }],
    accessors,
  };
  const pbr = { baseColorFactor: m.baseColorFactor, metallicFactor: m.metallicFactor, roughnessFactor: m.roughnessFactor };
  const material = { name: 'subdfit', pbrMetallicRoughness: pbr };
  const texture = (image, name) => {
    doc.images ??= [];
    doc.textures ??= [];
    doc.samplers ??= [{ magFilter: 9729, minFilter: 9729, wrapS: 33071, wrapT: 33071 }];
    const bytes = image.bytes ?? encodePng(image.width, image.height, image.pixels);
    doc.images.push({ bufferView: addView(bytes), mimeType: image.bytes ? image.mimeType : 'image/png', name });
    doc.textures.push({ sampler: 0, source: doc.images.length - 1 });
    return { index: doc.textures.length - 1 };
  };
  const images = decoded.images;
  if (images.baseColor) pbr.baseColorTexture = texture(images.baseColor, 'base_color');
  if (images.metallicRoughness) {
    pbr.metallicRoughnessTexture = texture(images.metallicRoughness, 'metallic_roughness');
    if (m.occlusionInMetallicRoughness) material.occlusionTexture = pbr.metallicRoughnessTexture;
  }
  if (images.normal) material.normalTexture = texture(images.normal, 'normal');
  if (images.emissive) {
    material.emissiveTexture = texture(images.emissive, 'emissive');
    material.emissiveFactor = m.emissiveFactor;
  }
  doc.materials = [material];
  doc.bufferViews = views;
  doc.buffers = [{ byteLength: length }];

  const json = Buffer.from(JSON.stringify(doc));
  const jsonChunk = Buffer.concat([json, Buffer.alloc((4 - (json.length % 4)) % 4, 0x20)]);
  const binChunk = Buffer.concat([...chunks, Buffer.alloc((4 - (length % 4)) % 4)]);
  const header = Buffer.alloc(12);
  header.writeUInt32LE(0x46546c67, 0);  // "glTF"
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonChunk.length + 8 + binChunk.length, 8);
  const chunkHeader = (size, type) => {
    const out = Buffer.alloc(8);
    out.writeUInt32LE(size, 0);
    out.writeUInt32LE(type, 4);
    return out;
  };
  return Buffer.concat([header, chunkHeader(jsonChunk.length, 0x4e4f534a), jsonChunk,
                        chunkHeader(binChunk.length, 0x004e4942), binChunk]);
}

// Written to a temporary file beside OUT, then renamed over it: never half a file, and never
// over anything but a regular file.
function writeAtomically(output, bytes) {
  const existing = fs.statSync(output, { throwIfNoEntry: false });
  if (existing && !existing.isFile()) throw new Error(`${output}: not a regular file`);
  const temporary = path.join(path.dirname(output), `.${path.basename(output)}.${process.pid}.partial`);
  try {
    fs.writeFileSync(temporary, bytes, { flag: 'wx' });
    fs.renameSync(temporary, output);
  } catch (error) {
    fs.rmSync(temporary, { force: true });
    throw new Error(`${output}: ${error.code === 'ENOENT' ? 'no such folder' : error.message}`);
  }
}

async function main() {
  const { input, output, triangles } = parseArguments(process.argv.slice(2));
  if (path.resolve(input) === path.resolve(output)) throw new Error(`${output}: the output would replace the input`);
  let bytes;
  try {
    bytes = fs.readFileSync(input);
  } catch (error) {
    throw new Error(`${input}: ${error.code === 'ENOENT' ? 'no such file' : error.code === 'EISDIR' ? 'a folder, not a file' : error.message}`);
  }
  const wasm = fs.readFileSync(new URL('./subd_decoder_wasm.wasm', import.meta.url));
  const decoder = await createDecoderInstance(wasm);
  const decoded = decoder.decode(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength), { triangles, name: input });
  for (const warning of decoded.warnings) process.stderr.write(`decode.mjs: warning: ${warning}\n`);
  writeAtomically(output, glbOf(decoded));
  process.stdout.write(`${output}\n`);
}

main().catch((error) => {
  process.stderr.write(`decode.mjs: ${String(error?.message ?? error).split('\n')[0]}\n`);
  process.exitCode = 1;
});
