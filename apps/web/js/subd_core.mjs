// One WebAssembly instance of the decoder (subd_decoder_wasm.mjs/.wasm, built from
// apps/web/wasm/subd_web.cpp), used on the thread that made it: a worker of SubdDecoder, or
// Node (decode.mjs). Copies the decoded arrays out of the instance's memory.
import createSubdWasm from './subd_decoder_wasm.mjs';

const ROLES = ['baseColor', 'metallicRoughness', 'normal', 'emissive'];
const IMAGE_WORDS = 6;  // subd_web.cpp's Image; its Result is 21 words, read below one by one
const TANGENTS = 1, OCCLUSION = 2;

// `wasm`: the decoder's .wasm as bytes or as a compiled WebAssembly.Module.
export async function createDecoderInstance(wasm) {
  const instance = await createSubdWasm({
    instantiateWasm(imports, receive) {
      WebAssembly.instantiate(wasm, imports).then((made) => receive(made.instance ?? made));
      return {};
    },
    print: () => {},
    printErr: () => {},
  });
  return new DecoderInstance(instance);
}

class DecoderInstance {
  constructor(wasm) {
    this.wasm = wasm;
    this.broken = false;  // after a trap the instance is not used again
  }

  // The instance's WebAssembly memory: it grows with what a decode needs and never shrinks.
  memoryBytes() {
    return this.wasm.HEAPU8.length;
  }

  // bytes: Uint8Array of an asset.subd (with `prefix`, its first bytes, as they arrive). Returns
  // the decoded surface (see subd_decoder.d.ts) or throws an Error whose message is one line
  // naming `name`.
  decode(bytes, { triangles = 0, name = 'asset.subd', prefix = false } = {}) {
    if (this.broken) throw new Error(`${name}: the decoder stopped after an earlier failure`);
    const w = this.wasm;
    const nameBytes = new TextEncoder().encode(`${name}\0`);
    const input = w._malloc(Math.max(1, bytes.length));
    const namePtr = w._malloc(nameBytes.length);
    if (!input || !namePtr) throw new Error(`${name}: out of memory`);
    w.HEAPU8.set(bytes, input);
    w.HEAPU8.set(nameBytes, namePtr);
    let result;
    try {
      result = w._subd_decode(input, bytes.length, triangles, namePtr, prefix ? 1 : 0);
    } catch (error) {
      this.broken = true;
      throw new Error(`${name}: the decoder failed (${error.message ?? error})`);
    } finally {
      if (!this.broken) {
        w._free(input);
        w._free(namePtr);
      }
    }
    if (!result) throw new Error(readString(w.HEAPU8, w._subd_error()));
    try {
      return readResult(w, result);
    } finally {
      w._subd_free(result);
    }
  }
}

function readString(heap, pointer) {
  let end = pointer;
  while (heap[end] !== 0) ++end;
  return new TextDecoder().decode(heap.subarray(pointer, end));
}

// Copies of the instance's arrays (its memory may grow, and is reused by the next decode).
function readResult(w, pointer) {
  const u32 = w.HEAPU32, f32 = w.HEAPF32, u8 = w.HEAPU8;
  const word = (k) => u32[(pointer >> 2) + k];
  const float = (k) => f32[(pointer >> 2) + k];
  const vertexCount = word(0), indexCount = word(1), flags = word(3);
  const floats = (at, n) => f32.slice(at >> 2, (at >> 2) + n);
  const decoded = {
    positions: floats(word(4), 3 * vertexCount),
    normals: floats(word(5), 3 * vertexCount),
    tangents: flags & TANGENTS ? floats(word(6), 4 * vertexCount) : null,
    uvs: floats(word(7), 2 * vertexCount),
    indices: u32.slice(word(8) >> 2, (word(8) >> 2) + indexCount),
    segments: word(2),
    material: {
      baseColorFactor: [float(9), float(10), float(11), float(12)],
      metallicFactor: float(13),
      roughnessFactor: float(14),
      emissiveFactor: [float(15), float(16), float(17)],
      occlusionInMetallicRoughness: (flags & OCCLUSION) !== 0,
    },
    images: {},
    warnings: [],
  };
  const imageCount = word(18), images = word(19) >> 2;
  for (let i = 0; i < imageCount; ++i) {
    const at = images + i * IMAGE_WORDS;
    const [role, encoding, width, height, data, size] = u32.slice(at, at + IMAGE_WORDS);
    const bytes = u8.slice(data, data + size);
    decoded.images[ROLES[role]] = encoding === 1 ? { width, height, mimeType: 'image/jpeg', bytes }
                                                 : { width, height, pixels: bytes };
  }
  const warnings = readString(u8, word(20));
  if (warnings) decoded.warnings = warnings.trimEnd().split('\n');
  return decoded;
}

// The ArrayBuffers a decoded surface holds (to transfer it between threads).
export function transferablesOf(decoded) {
  const buffers = [decoded.positions, decoded.normals, decoded.tangents, decoded.uvs, decoded.indices];
  for (const image of Object.values(decoded.images)) buffers.push(image.bytes ?? image.pixels);
  return buffers.filter(Boolean).map((array) => array.buffer);
}
