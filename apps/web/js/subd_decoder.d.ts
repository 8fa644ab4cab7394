// Types of subd_decoder.mjs: asset.subd bytes -> the arrays of its surface.

/** An image of the material: the JPEG the file carries (the browser decodes it), or pixels. */
export interface SubdImage {
  width: number;
  height: number;
  /** 'image/jpeg' when `bytes` holds the encoded image. */
  mimeType?: string;
  bytes?: Uint8Array;
  /** 8-bit RGBA, rows top first (the fitted normal map). */
  pixels?: Uint8Array;
}

/** glTF's metallic-roughness material, as `subdfit decode` writes it for the same file. */
export interface SubdMaterial {
  /** Linear RGBA. */
  baseColorFactor: [number, number, number, number];
  metallicFactor: number;
  roughnessFactor: number;
  emissiveFactor: [number, number, number];
  /** The metallic-roughness image's red channel is the ambient occlusion (glTF's ORM packing). */
  occlusionInMetallicRoughness: boolean;
}

/** The displaced limit surface: the triangles `subdfit decode` writes, glTF conventions. */
export interface DecodedSubd {
  /** xyz per vertex. */
  positions: Float32Array;
  /** Unit normals, xyz per vertex. */
  normals: Float32Array;
  /** glTF TANGENT (xyz, w = ±1) per vertex; null where the material needs none. */
  tangents: Float32Array | null;
  /** Texture coordinates of the images, v down the image (three: texture.flipY = false). */
  uvs: Float32Array;
  /** Triangles, counter-clockwise seen from outside. */
  indices: Uint32Array;
  /** Segments per ptex-face edge the density chose. */
  segments: number;
  material: SubdMaterial;
  /** Images sampled linearly without mipmaps, clamped to the edge; sRGB: baseColor, emissive. */
  images: { baseColor?: SubdImage; metallicRoughness?: SubdImage; normal?: SubdImage; emissive?: SubdImage };
  /** Inputs used, but not quite as written (one line each). */
  warnings: string[];
}

export interface DecodeOptions {
  /** About how many triangles: the nearest density (`subdfit decode --triangles`); 0 or absent: decode's default. */
  triangles?: number;
  /** Names the file in error messages. */
  name?: string;
  /** The bytes are the file's first, as a download delivers them: the cage and the levels in them (`subdfit decode --bytes`). */
  prefix?: boolean;
}

export interface SubdDecoderOptions {
  /** The folder of subd_decoder_wasm.wasm and subd_worker.mjs (default: subd_decoder.mjs's). */
  decoderPath?: string;
  /** The most files decoded at once, each in its own worker (default 4). */
  workerLimit?: number;
  /** The .wasm's bytes, when the caller has them (nothing is fetched). */
  wasmBinary?: ArrayBuffer | Uint8Array | null;
}

export class SubdDecoder {
  constructor(options?: SubdDecoderOptions);
  setDecoderPath(path: string): this;
  setWorkerLimit(limit: number): this;
  /** Rejects with an Error of one line naming the file for anything that is not a sound asset.subd. An ArrayBuffer is transferred to the worker. */
  decode(bytes: ArrayBuffer | Uint8Array, options?: DecodeOptions): Promise<DecodedSubd>;
  dispose(): void;
}

/** The one call, with a SubdDecoder shared by the page. */
export function decodeSubd(bytes: ArrayBuffer | Uint8Array, options?: DecodeOptions): Promise<DecodedSubd>;
