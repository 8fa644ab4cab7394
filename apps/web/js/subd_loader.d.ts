// Types of subd_loader.mjs: asset.subd in three.js.
import { BufferGeometry, Loader, LoadingManager, Mesh, MeshStandardMaterial } from 'three';

export class SubdLoader extends Loader<Mesh<BufferGeometry, MeshStandardMaterial>> {
  constructor(manager?: LoadingManager);
  /** The folder of subd_decoder_wasm.wasm and subd_worker.mjs (default: subd_loader.mjs's). */
  setDecoderPath(path: string): this;
  /** The most files decoded at once (default 4). */
  setWorkerLimit(limit: number): this;
  /** About how many triangles (0: the density `subdfit decode` uses by default). */
  setTriangles(triangles: number): this;
  load(
    url: string,
    onLoad: (mesh: Mesh<BufferGeometry, MeshStandardMaterial>) => void,
    onProgress?: (event: ProgressEvent) => void,
    onError?: (error: unknown) => void,
  ): void;
  /**
   * Draws the asset as its bytes arrive: the Mesh is made once the file's cage is in and refined
   * in place (geometry, and material where the images change) as more arrives; resolves with it
   * once the whole file is in and decoded as parse() decodes it.
   */
  loadStreaming(
    url: string,
    onUpdate?: (
      mesh: Mesh<BufferGeometry, MeshStandardMaterial>,
      progress: { bytes: number; total: number; complete: boolean },
    ) => void,
  ): Promise<Mesh<BufferGeometry, MeshStandardMaterial>>;
  /** An asset.subd's bytes to a Mesh; `name` names the file in errors. */
  parse(buffer: ArrayBuffer, name?: string): Promise<Mesh<BufferGeometry, MeshStandardMaterial>>;
  dispose(): this;
}
