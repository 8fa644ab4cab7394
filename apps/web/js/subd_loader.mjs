// A three.js loader for asset.subd, shaped as three's own (DRACOLoader, GLTFLoader):
//
//   const loader = new SubdLoader().setDecoderPath('/subdfit/');
//   scene.add(await loader.loadAsync('asset.subd'));
//
// or, drawn from its first bytes on and refined as the rest arrives:
//
//   await loader.loadStreaming('asset.subd', (mesh, { complete }) => { if (!scene.children.includes(mesh)) scene.add(mesh); });
//
// It builds the Mesh and MeshStandardMaterial that three's GLTFLoader builds from the glb of
// `subdfit decode` for the same file: the same triangles, the same material factors, the same
// textures (the JPEGs the file carries, decoded by the browser as GLTFLoader decodes images).
import {
  BufferAttribute, BufferGeometry, ClampToEdgeWrapping, DataTexture, FileLoader, ImageBitmapLoader, LinearFilter,
  LinearSRGBColorSpace, Loader, Mesh, MeshStandardMaterial, RGBAFormat, SRGBColorSpace, Texture, TextureLoader,
  UnsignedByteType,
} from 'three';
import { SubdDecoder } from './subd_decoder.mjs';

export class SubdLoader extends Loader {
  constructor(manager) {
    super(manager);
    this.decoderPath = new URL('./', import.meta.url).href;
    this.workerLimit = 4;
    this.triangles = 0;
    this.decoder = null;
  }

  // The folder of subd_decoder_wasm.wasm and subd_worker.mjs (default: this module's).
  setDecoderPath(path) {
    this.decoderPath = path;
    return this;
  }

  setWorkerLimit(limit) {
    this.workerLimit = limit;
    return this;
  }

  // About how many triangles to decode (0: the density `subdfit decode` uses by default).
  setTriangles(triangles) {
    this.triangles = triangles;
    return this;
  }

  load(url, onLoad, onProgress, onError) {
    const fail = (error) => {
      if (onError) onError(error);
      else console.error(error);
      this.manager.itemError(url);
    };
    const file = new FileLoader(this.manager);
    file.setPath(this.path);
    file.setResponseType('arraybuffer');
    file.setRequestHeader(this.requestHeader);
    file.setWithCredentials(this.withCredentials);
    file.load(url, (buffer) => {
      this.parse(buffer, url.split('/').pop() || url).then(onLoad, fail);
    }, onProgress, onError);
  }

  // An asset.subd's bytes to a Mesh. `name` names the file in errors.
  async parse(buffer, name = 'asset.subd') {
    const mesh = new Mesh();
    mesh.name = name;
    await refine(mesh, await this.#decoder().decode(buffer, { triangles: this.triangles, name }), this);
    return mesh;
  }

  // Draws the asset as its bytes arrive: the file's first bytes decode to a coarser asset (the
  // cage, then its maps level by level), so the Mesh is made once the cage is in and refined in
  // place as more arrives. onUpdate(mesh, { bytes, total, complete }) after each refinement
  // (total: the file's bytes, 0 where the server does not say); resolves with the Mesh once the
  // whole file is in and decoded, exactly as parse() decodes it.
  async loadStreaming(url, onUpdate = () => {}) {
    const name = url.split('/').pop().split('?')[0] || url;
    const response = await fetch(this.manager.resolveURL((this.path ?? '') + url), {
      headers: this.requestHeader, credentials: this.withCredentials ? 'include' : 'same-origin' });
    if (!response.ok) throw new Error(`${name}: HTTP ${response.status}`);
    const total = Number(response.headers.get('content-length')) || 0;
    const bytes = new ArrivingBytes(total);
    const mesh = new Mesh();
    mesh.name = name;
    let decoding = null, decodedAt = 0, failure = null;
    // One prefix decode at a time, each once the bytes have grown by half since the last.
    const decodeMore = () => {
      if (decoding || failure || bytes.length < Math.max(kFirstPrefixBytes, 1.5 * decodedAt)) return;
      const at = bytes.length;
      decoding = this.#decoder().decode(bytes.first(at), { triangles: this.triangles, name, prefix: true })
        .then((decoded) => refine(mesh, decoded, this))
        .then(() => onUpdate(mesh, { bytes: at, total, complete: false }))
        .catch((error) => { if (!kBeforeTheCage.test(error?.message)) failure = error; })
        .finally(() => {
          decoding = null;
          decodedAt = at;
          decodeMore();
        });
    };
    for (const reader = response.body.getReader();;) {
      const { done, value } = await reader.read();
      if (done) break;
      bytes.append(value);
      decodeMore();
      if (failure) {
        reader.cancel();
        throw failure;
      }
    }
    while (decoding) await decoding;
    if (failure) throw failure;
    await refine(mesh, await this.#decoder().decode(bytes.first(bytes.length), { triangles: this.triangles, name }), this);
    onUpdate(mesh, { bytes: bytes.length, total, complete: true });
    return mesh;
  }

  dispose() {
    this.decoder?.dispose();
    this.decoder = null;
    return this;
  }

  #decoder() {
    this.decoder ??= new SubdDecoder({ decoderPath: this.decoderPath, workerLimit: this.workerLimit });
    return this.decoder;
  }
}

// No prefix shorter than this is tried: a file's header and cage take more.
const kFirstPrefixBytes = 256;
// The one refusal a prefix decode makes for want of bytes (subdfit decode --bytes's message).
const kBeforeTheCage = / bytes end before the cage does$/;

// A download's bytes so far, in one buffer grown as they arrive.
class ArrivingBytes {
  constructor(total) {
    this.buffer = new Uint8Array(Math.max(total, 1 << 16));
    this.length = 0;
  }

  append(chunk) {
    if (this.length + chunk.length > this.buffer.length) {
      const grown = new Uint8Array(Math.max(2 * this.buffer.length, this.length + chunk.length));
      grown.set(this.buffer.subarray(0, this.length));
      this.buffer = grown;
    }
    this.buffer.set(chunk, this.length);
    this.length += chunk.length;
  }

  // A copy of the first n bytes (the decoder takes its input's buffer).
  first(n) {
    return this.buffer.slice(0, n);
  }
}

// `mesh` made to show `decoded`: its geometry replaced, its material made again where the
// images it has changed (a prefix may end before the appearance does).
async function refine(mesh, decoded, loader) {
  const images = Object.keys(decoded.images).sort().join();
  const old = mesh.geometry;
  mesh.geometry = geometryOf(decoded);
  old?.dispose();
  if (mesh.userData.subd?.images !== images) {
    mesh.material?.dispose?.();
    mesh.material = await materialOf(decoded, loader);
  }
  mesh.userData.subd = { segments: decoded.segments, triangles: decoded.indices.length / 3, warnings: decoded.warnings,
                         images };
}

function geometryOf(decoded) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(decoded.positions, 3));
  geometry.setAttribute('normal', new BufferAttribute(decoded.normals, 3));
  if (decoded.tangents) geometry.setAttribute('tangent', new BufferAttribute(decoded.tangents, 4));
  geometry.setAttribute('uv', new BufferAttribute(decoded.uvs, 2));
  geometry.setIndex(new BufferAttribute(decoded.indices, 1));
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  return geometry;
}

async function materialOf(decoded, loader) {
  // No image: decode's glb has no material (its reference had none), and GLTFLoader draws such a
  // primitive in glTF's default material (white, fully metallic, fully rough): so does this.
  if (Object.keys(decoded.images).length === 0)
    return new MeshStandardMaterial({ color: 0xffffff, emissive: 0x000000, metalness: 1, roughness: 1 });
  const m = decoded.material;
  const material = new MeshStandardMaterial({
    metalness: m.metallicFactor,
    roughness: m.roughnessFactor,
  });
  material.name = 'subdfit';
  material.color.setRGB(m.baseColorFactor[0], m.baseColorFactor[1], m.baseColorFactor[2], LinearSRGBColorSpace);
  material.opacity = m.baseColorFactor[3];
  material.emissive.setRGB(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2], LinearSRGBColorSpace);
  const images = decoded.images;
  const [baseColor, metallicRoughness, normal, emissive] = await Promise.all(
    [images.baseColor, images.metallicRoughness, images.normal, images.emissive].map((image) => textureOf(image, loader)));
  if (baseColor) {
    baseColor.colorSpace = SRGBColorSpace;
    material.map = baseColor;
  }
  if (metallicRoughness) {
    material.metalnessMap = material.roughnessMap = metallicRoughness;
    if (m.occlusionInMetallicRoughness) material.aoMap = metallicRoughness;
  }
  if (normal) material.normalMap = normal;
  if (emissive) {
    emissive.colorSpace = SRGBColorSpace;
    material.emissiveMap = emissive;
  }
  material.needsUpdate = true;
  return material;
}

// A texture as GLTFLoader makes one for the glb's images: an ImageBitmap where the browser has
// createImageBitmap (a plain image elsewhere), not flipped, sampled linearly without mipmaps
// and clamped (each atlas tile is its own chart).
async function textureOf(image, loader) {
  if (!image) return null;
  let texture;
  if (image.pixels) {
    texture = new DataTexture(image.pixels, image.width, image.height, RGBAFormat, UnsignedByteType);
  } else {
    const url = URL.createObjectURL(new Blob([image.bytes], { type: image.mimeType }));
    try {
      const images = typeof createImageBitmap === 'undefined' ? new TextureLoader(loader.manager)
                                                               : new ImageBitmapLoader(loader.manager);
      const loaded = await images.loadAsync(url);
      texture = loaded.isTexture ? loaded : new Texture(loaded);
    } finally {
      URL.revokeObjectURL(url);
    }
    if (texture.image.width !== image.width || texture.image.height !== image.height)
      throw new Error(`an image of ${texture.image.width} x ${texture.image.height}, not ${image.width} x ${image.height}`);
  }
  texture.flipY = false;
  texture.magFilter = texture.minFilter = LinearFilter;
  texture.wrapS = texture.wrapT = ClampToEdgeWrapping;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  return texture;
}
