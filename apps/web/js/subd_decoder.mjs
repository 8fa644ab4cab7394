// asset.subd -> the arrays of its surface, decoded off the main thread. The one call:
//
//   import { decodeSubd } from './subd_decoder.mjs';
//   const surface = await decodeSubd(bytes, { triangles: 200000 });
//
// Like three's DRACOLoader, a SubdDecoder compiles the WebAssembly once and runs it in a few
// module workers; where there are no workers (Node), it decodes on the calling thread.
import { createDecoderInstance } from './subd_core.mjs';

const WASM_FILE = 'subd_decoder_wasm.wasm';
const KEEP_BYTES = 256 << 20;  // as subd_worker.mjs

export class SubdDecoder {
  // decoderPath: the folder of subd_decoder_wasm.wasm and subd_worker.mjs (default: this
  // module's); workerLimit: the most decodes at once; wasmBinary: the .wasm's bytes, when the
  // caller has them (no fetch).
  constructor({ decoderPath = new URL('./', import.meta.url).href, workerLimit = 4, wasmBinary = null } = {}) {
    this.decoderPath = decoderPath;
    this.workerLimit = Math.max(1, workerLimit);
    this.wasmBinary = wasmBinary;
    this.module = null;   // Promise<WebAssembly.Module>
    this.workers = [];    // { worker, pending }
    this.tasks = new Map();
    this.nextId = 0;
    this.local = null;    // Promise<instance> where there are no workers
  }

  setDecoderPath(path) {
    this.decoderPath = path;
    return this;
  }

  setWorkerLimit(limit) {
    this.workerLimit = Math.max(1, limit);
    return this;
  }

  // bytes: ArrayBuffer or Uint8Array of an asset.subd (an ArrayBuffer is transferred to the
  // worker, so the caller's copy is emptied). options.triangles: about how many triangles (0 or
  // absent: decode's default density); options.name: names the file in errors; options.prefix:
  // the bytes are the file's first, as a download delivers them (a coarser asset).
  async decode(bytes, { triangles = 0, name = 'asset.subd', prefix = false } = {}) {
    if (!Number.isInteger(triangles) || triangles < 0) throw new Error(`${name}: triangles must be a whole number >= 0`);
    const options = { triangles, name, prefix };
    if (typeof Worker === 'undefined') {
      this.local ??= this.#compile().then(createDecoderInstance);
      const instance = await this.local;
      try {
        return instance.decode(bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes), options);
      } finally {
        // WebAssembly memory only grows: a large decode's is let go with its instance.
        if (instance.broken || instance.memoryBytes() > KEEP_BYTES) this.local = null;
      }
    }
    const buffer = bytes instanceof ArrayBuffer ? bytes : bytes.slice().buffer;
    const worker = await this.#worker();
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.tasks.set(id, { resolve, reject, worker });
      ++worker.pending;
      worker.worker.postMessage({ type: 'decode', id, bytes: buffer, options }, [buffer]);
    });
  }

  dispose() {
    for (const { worker } of this.workers) worker.terminate();
    for (const task of this.tasks.values()) task.reject(new Error('the decoder was disposed'));
    this.workers = [];
    this.tasks.clear();
  }

  #compile() {
    this.module ??= (async () => {
      if (this.wasmBinary) return WebAssembly.compile(this.wasmBinary);
      const response = await fetch(new URL(WASM_FILE, this.decoderPath));
      if (!response.ok) throw new Error(`${WASM_FILE}: HTTP ${response.status}`);
      return WebAssembly.compile(await response.arrayBuffer());
    })();
    return this.module;
  }

  // The least busy worker, a new one while under the limit.
  async #worker() {
    const module = await this.#compile();
    this.workers.sort((a, b) => a.pending - b.pending);
    if (this.workers.length > 0 && (this.workers[0].pending === 0 || this.workers.length >= this.workerLimit))
      return this.workers[0];
    const worker = new Worker(new URL('subd_worker.mjs', this.decoderPath), { type: 'module' });
    const entry = { worker, pending: 0 };
    worker.onmessage = ({ data }) => {
      const task = this.tasks.get(data.id);
      if (!task) return;
      this.tasks.delete(data.id);
      --entry.pending;
      if (data.type === 'decoded') task.resolve(data.decoded);
      else task.reject(new Error(data.message));
    };
    worker.onerror = (event) => {
      for (const [id, task] of this.tasks)
        if (task.worker === entry) {
          this.tasks.delete(id);
          task.reject(new Error(`the decoder's worker failed: ${event.message ?? 'unknown error'}`));
        }
    };
    worker.postMessage({ type: 'init', wasm: module });
    this.workers.push(entry);
    return entry;
  }
}

let shared = null;

// The one call: decodes with a SubdDecoder shared by the page (its files beside this module).
export function decodeSubd(bytes, options = {}) {
  shared ??= new SubdDecoder();
  return shared.decode(bytes, options);
}
