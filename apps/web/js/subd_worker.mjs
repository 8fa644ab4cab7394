// A decoding thread of SubdDecoder (subd_decoder.mjs): one decoder instance, made from the
// compiled module the page sends, decoding one file at a time.
import { createDecoderInstance, transferablesOf } from './subd_core.mjs';

// WebAssembly memory only grows: after a decode that needed more than this, the instance is
// replaced by a fresh one, so an idle worker does not keep a large asset's working memory.
const KEEP_BYTES = 256 << 20;

let module = null, instance = null;

self.onmessage = async ({ data }) => {
  if (data.type === 'init') {
    module = data.wasm;
    instance = createDecoderInstance(module);
    return;
  }
  if (data.type !== 'decode') return;
  try {
    const decoder = await instance;
    try {
      const decoded = decoder.decode(new Uint8Array(data.bytes), data.options);
      self.postMessage({ type: 'decoded', id: data.id, decoded }, transferablesOf(decoded));
    } finally {
      if (decoder.broken || decoder.memoryBytes() > KEEP_BYTES) instance = createDecoderInstance(module);
    }
  } catch (error) {
    self.postMessage({ type: 'error', id: data.id, message: String(error?.message ?? error) });
  }
};
