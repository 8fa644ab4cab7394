// What the web tests read from a .glb: every triangle of every mesh primitive in world space
// (node transforms applied), from plain accessors, normalised integer ones (KHR_mesh_quantization)
// and EXT_meshopt_compression buffer views, so the comparison does not depend on how `subdfit
// decode` chooses to pack its output.
import fs from 'node:fs';

const COMPONENTS = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT4: 16 };
const TYPES = {
  5120: [Int8Array, 127], 5121: [Uint8Array, 255], 5122: [Int16Array, 32767], 5123: [Uint16Array, 65535],
  5125: [Uint32Array, 0], 5126: [Float32Array, 0],
};

export function parseGlb(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint32(0, true) !== 0x46546c67) throw new Error('not a glb');
  let json = null, bin = null;
  for (let at = 12; at < view.getUint32(8, true);) {
    const length = view.getUint32(at, true), type = view.getUint32(at + 4, true);
    const chunk = bytes.subarray(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else if (type === 0x004e4942) bin = chunk;
    at += 8 + length;
  }
  return { json, bin };
}

async function viewBytes(glb, index, meshopt) {
  const bufferView = glb.json.bufferViews[index];
  const ext = bufferView.extensions?.EXT_meshopt_compression;
  if (!ext) return glb.bin.subarray(bufferView.byteOffset ?? 0, (bufferView.byteOffset ?? 0) + bufferView.byteLength);
  const decoder = await meshopt();
  const source = glb.bin.subarray(ext.byteOffset ?? 0, (ext.byteOffset ?? 0) + ext.byteLength);
  const out = new Uint8Array(ext.count * ext.byteStride);
  decoder.decodeGltfBuffer(out, ext.count, ext.byteStride, source, ext.mode, ext.filter ?? 'NONE');
  return out;
}

async function accessorValues(glb, index, meshopt) {
  const a = glb.json.accessors[index];
  const [Type, scale] = TYPES[a.componentType];
  const n = COMPONENTS[a.type];
  const bytes = await viewBytes(glb, a.bufferView, meshopt);
  const stride = glb.json.bufferViews[a.bufferView].byteStride ?? n * Type.BYTES_PER_ELEMENT;
  const out = new Float64Array(a.count * n);
  const data = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const read = {
    5120: (o) => data.getInt8(o), 5121: (o) => data.getUint8(o), 5122: (o) => data.getInt16(o, true),
    5123: (o) => data.getUint16(o, true), 5125: (o) => data.getUint32(o, true), 5126: (o) => data.getFloat32(o, true),
  }[a.componentType];
  for (let i = 0; i < a.count; ++i)
    for (let c = 0; c < n; ++c) {
      const v = read((a.byteOffset ?? 0) + i * stride + c * Type.BYTES_PER_ELEMENT);
      out[i * n + c] = a.normalized && scale ? Math.max(v / scale, -1) : v;
    }
  return out;
}

function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let r = 0; r < 4; ++r) for (let c = 0; c < 4; ++c) for (let k = 0; k < 4; ++k) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return out;
}

function localMatrix(node) {
  if (node.matrix) return node.matrix;
  const [tx, ty, tz] = node.translation ?? [0, 0, 0], [x, y, z, w] = node.rotation ?? [0, 0, 0, 1];
  const [sx, sy, sz] = node.scale ?? [1, 1, 1];
  return [(1 - 2 * (y * y + z * z)) * sx, 2 * (x * y + z * w) * sx, 2 * (x * z - y * w) * sx, 0,
          2 * (x * y - z * w) * sy, (1 - 2 * (x * x + z * z)) * sy, 2 * (y * z + x * w) * sy, 0,
          2 * (x * z + y * w) * sz, 2 * (y * z - x * w) * sz, (1 - 2 * (x * x + y * y)) * sz, 0, tx, ty, tz, 1];
}

// { positions: Float64Array (xyz per vertex), indices: Uint32Array (3 per triangle) } of the
// default scene. `meshopt`: () => Promise<MeshoptDecoder>, asked for only when needed.
export async function readTriangles(path, meshopt = async () => { throw new Error('EXT_meshopt_compression needs a decoder'); }) {
  const glb = parseGlb(new Uint8Array(fs.readFileSync(path)));
  const positions = [], indices = [];
  const visit = async (nodeIndex, parent) => {
    const node = glb.json.nodes[nodeIndex];
    const world = multiply(parent, localMatrix(node));
    if (node.mesh !== undefined)
      for (const primitive of glb.json.meshes[node.mesh].primitives) {
        const p = await accessorValues(glb, primitive.attributes.POSITION, meshopt);
        const base = positions.length / 3;
        for (let v = 0; v < p.length; v += 3)
          for (let r = 0; r < 3; ++r)
            positions.push(world[r] * p[v] + world[4 + r] * p[v + 1] + world[8 + r] * p[v + 2] + world[12 + r]);
        const order = primitive.indices !== undefined ? await accessorValues(glb, primitive.indices, meshopt)
                                                      : Float64Array.from({ length: p.length / 3 }, (_, k) => k);
        for (const i of order) indices.push(base + i);
      }
    for (const child of node.children ?? []) await visit(child, world);
  };
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  for (const root of glb.json.scenes[glb.json.scene ?? 0].nodes) await visit(root, identity);
  return { positions: Float64Array.from(positions), indices: Uint32Array.from(indices), json: glb.json };
}

// The largest distance between matching triangle corners of `a` and `b`, over the bounding box
// diagonal of `a`; Infinity when their triangle counts differ or a triangle of `a` has no
// counterpart. Triangles are matched in order, or (when the order differs) by their centroids.
export function triangleDistance(a, b) {
  const count = a.indices.length / 3;
  if (count !== b.indices.length / 3 || count === 0) return Infinity;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < a.positions.length; v += 3)
    for (let c = 0; c < 3; ++c) {
      lo[c] = Math.min(lo[c], a.positions[v + c]);
      hi[c] = Math.max(hi[c], a.positions[v + c]);
    }
  const diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const corner = (m, t, k) => m.indices[3 * t + k] * 3;
  // The largest corner distance of triangle t of a and u of b, over rotations of b's corners.
  const distance = (t, u) => {
    let best = Infinity;
    for (let r = 0; r < 3; ++r) {
      let worst = 0;
      for (let k = 0; k < 3; ++k) {
        const p = corner(a, t, k), q = corner(b, u, (k + r) % 3);
        worst = Math.max(worst, Math.hypot(a.positions[p] - b.positions[q], a.positions[p + 1] - b.positions[q + 1],
                                           a.positions[p + 2] - b.positions[q + 2]));
      }
      best = Math.min(best, worst);
    }
    return best;
  };
  let worst = 0, inOrder = true;
  for (let t = 0; t < count && inOrder; ++t) {
    const d = distance(t, t);
    if (d > 1e-4 * diagonal) inOrder = false;
    worst = Math.max(worst, d);
  }
  if (inOrder) return worst / diagonal;
  // Matched by centroid on a grid of cells a thousandth of the diagonal.
  const cell = diagonal * 1e-3, key = (m, t) => {
    const c = [0, 1, 2].map((axis) => (m.positions[corner(m, t, 0) + axis] + m.positions[corner(m, t, 1) + axis] +
                                       m.positions[corner(m, t, 2) + axis]) / 3);
    return c.map((v) => Math.floor(v / cell));
  };
  const grid = new Map();
  for (let u = 0; u < count; ++u) {
    const k = key(b, u).join(',');
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(u);
  }
  worst = 0;
  for (let t = 0; t < count; ++t) {
    const [x, y, z] = key(a, t);
    let best = Infinity;
    for (let dx = -1; dx <= 1; ++dx) for (let dy = -1; dy <= 1; ++dy) for (let dz = -1; dz <= 1; ++dz)
      for (const u of grid.get(`${x + dx},${y + dy},${z + dz}`) ?? []) best = Math.min(best, distance(t, u));
    worst = Math.max(worst, best);
  }
  return worst / diagonal;
}
