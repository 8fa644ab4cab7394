#!/usr/bin/env node
// `subdfit decode` in Node, through the web decoder: asset.subd -> .glb of the same triangles.
//   node decode.mjs IN.subd OUT.glb [--triangles N] [--bytes B]
// One line on stderr and exit status 1 for anything it refuses; OUT is written whole or not at all.
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { createDecoderInstance } from './subd_core.mjs';

const USAGE = 'usage: node decode.mjs IN.subd OUT.glb [--triangles N] [--bytes B]';

function wholeNumber(option, text) {
  if (text === undefined || !/^[0-9]+$/.test(text) || Number(text) < 1 || !Number.isSafeInteger(Number(text)))
    throw new Error(`${option}: must be a whole number >= 1, got ${text ?? 'nothing'}`);
  return Number(text);
}

function parseArguments(args) {
  const positional = [];
  let triangles = 0, bytes = Infinity;
  for (let k = 0; k < args.length; ++k) {
    if (args[k] === '--triangles') {
      triangles = wholeNumber('--triangles', args[++k]);
    } else if (args[k] === '--bytes') {
      bytes = wholeNumber('--bytes', args[++k]);
    } else if (args[k].startsWith('-')) {
      throw new Error(`unknown option ${args[k]} (${USAGE})`);
    } else {
      positional.push(args[k]);
    }
  }
  if (positional.length !== 2) throw new Error(USAGE);
  return { input: positional[0], output: positional[1], triangles, bytes };
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
  // As `subdfit decode` writes it: no TANGENT that no normal texture reads, no TEXCOORD_0 and no
  // material where there is no image (a reference without an appearance is drawn as the reader
  // draws a mesh without a material).
  const images = decoded.images;
  const textured = Object.keys(images).length > 0;
  addAccessor('POSITION', decoded.positions, 'VEC3');
  Object.assign(accessors[0], { min, max });
  addAccessor('NORMAL', decoded.normals, 'VEC3');
  if (decoded.tangents && images.normal) addAccessor('TANGENT', decoded.tangents, 'VEC4');
  if (textured) addAccessor('TEXCOORD_0', decoded.uvs, 'VEC2');
  accessors.push({ bufferView: addView(decoded.indices, 34963), componentType: 5125, count: decoded.indices.length, type: 'SCALAR' });

  const m = decoded.material;
  const doc = {
    asset: { version: '2.0', generator: 'subdfit decode.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name: 'fitted' }],
    meshes: [{ name: 'fitted', primitives: [{ attributes, indices: accessors.length - 1, mode: 4 }] }],
    accessors,
  };
  if (textured) doc.meshes[0].primitives[0].material = 0;
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
  if (textured) doc.materials = [material];
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

// What `subdfit decode` reads and writes, by the same rules (src/io/input_file.h,
// src/io/atomic_file.h): keep the two in step.
const MAX_INPUT_BYTES = 2 ** 31;  // io::kMaxInputBytes
const MAX_FILE_NAME = 255;        // bytes of a file name

function kindProblem(stats) {
  if (stats.isDirectory()) return 'is a folder, not a file';
  if (!stats.isFile()) return 'is not a regular file (a FIFO, device or socket)';
  return '';
}

// The input, read only when it is a regular file within the limit, checked on the open
// descriptor (a symlink swapped after a check cannot slip past; a FIFO opened without blocking).
function readInput(input) {
  let fd;
  try {
    fd = fs.openSync(input, fs.constants.O_RDONLY | fs.constants.O_NONBLOCK);
  } catch (error) {
    throw new Error(`${input}: ${error.code === 'ENOENT' ? 'no such file' : `cannot open: ${error.message}`}`);
  }
  try {
    const stats = fs.fstatSync(fd);
    const problem = kindProblem(stats);
    if (problem) throw new Error(`${input}: ${problem}`);
    if (stats.size > MAX_INPUT_BYTES)
      throw new Error(`${input}: is ${stats.size} bytes, more than the ${MAX_INPUT_BYTES}-byte input limit`);
    const bytes = Buffer.alloc(stats.size);
    let read = 0;
    while (read < bytes.length) {
      const n = fs.readSync(fd, bytes, read, bytes.length - read, read);
      if (n === 0) throw new Error(`${input}: shrank while it was read`);
      read += n;
    }
    if (fs.readSync(fd, Buffer.alloc(1), 0, 1, read) !== 0) throw new Error(`${input}: grew while it was read`);
    return bytes;
  } finally {
    fs.closeSync(fd);
  }
}

// Why OUT may not be written ("" when it may): an output replaces nothing but a regular file (not
// a folder, a FIFO, a device, a socket or a symlink, which lstat sees as itself), nor the input.
function outputProblem(output, input) {
  if (!output) return 'the output path is empty';
  const name = Buffer.byteLength(path.basename(output));
  if (name > MAX_FILE_NAME) return `its name is ${name} bytes, more than the ${MAX_FILE_NAME} a file name may have`;
  const existing = fs.lstatSync(output, { throwIfNoEntry: false });
  if (!existing) return '';
  if (existing.isSymbolicLink()) return 'is a symlink: the decoder replaces only regular files';
  const problem = kindProblem(existing);
  if (problem) return problem === 'is a folder, not a file' ? problem : `${problem}: the decoder replaces only regular files`;
  const source = fs.statSync(input, { throwIfNoEntry: false });
  if (source && source.dev === existing.dev && source.ino === existing.ino) return `is the input ${input}: write the output elsewhere`;
  return '';
}

// Written to a temporary file beside OUT (its name cut to fit), then renamed over it: never half
// a file, and never over anything but a regular file (checked again just before the rename).
function writeAtomically(output, input, bytes) {
  const tag = `.${process.pid}.partial`;
  const stem = Buffer.from(path.basename(output)).subarray(0, MAX_FILE_NAME - 1 - tag.length).toString();
  const temporary = path.join(path.dirname(output), `.${stem}${tag}`);
  try {
    fs.writeFileSync(temporary, bytes, { flag: 'wx' });
    const problem = outputProblem(output, input);
    if (problem) throw new Error(problem);
    fs.renameSync(temporary, output);
  } catch (error) {
    fs.rmSync(temporary, { force: true });
    throw new Error(`${output}: ${error.code === 'ENOENT' ? 'no such folder' : error.message}`);
  }
}

async function main() {
  const { input, output, triangles, bytes: firstBytes } = parseArguments(process.argv.slice(2));
  // The output is checked before any work, as `subdfit decode` checks it.
  const problem = outputProblem(output, input);
  if (problem) throw new Error(`${output}: ${problem}`);
  const bytes = readInput(input);
  const wasm = fs.readFileSync(new URL('./subd_decoder_wasm.wasm', import.meta.url));
  const decoder = await createDecoderInstance(wasm);
  // --bytes: the file's first bytes, as a download delivers them (`subdfit decode --bytes`).
  const prefix = firstBytes < bytes.byteLength;
  const length = prefix ? firstBytes : bytes.byteLength;
  const decoded = decoder.decode(new Uint8Array(bytes.buffer, bytes.byteOffset, length), { triangles, name: input, prefix });
  for (const warning of decoded.warnings) process.stderr.write(`decode.mjs: warning: ${warning}\n`);
  writeAtomically(output, input, glbOf(decoded));
  process.stdout.write(`${output}\n`);
}

main().catch((error) => {
  process.stderr.write(`decode.mjs: ${String(error?.message ?? error).split('\n')[0]}\n`);
  process.exitCode = 1;
});
