// A decoding thread of SubdDecoder (subd_decoder.mjs): one decoder instance, made from the
// compiled module the page sends, decoding one file at a time.
import { createDecoderInstance, transferablesOf } from './subd_core.mjs';

let instance = null;

self.onmessage = async ({ data }) => {
  if (data.type === 'init') {
    instance = createDecoderInstance(data.wasm);
    return;
  }
  if (data.type !== 'decode') return;
  try {
    const decoder = await instance;
    const decoded = decoder.decode(new Uint8Array(data.bytes), data.options);
    self.postMessage({ type: 'decoded', id: data.id, decoded }, transferablesOf(decoded));
  } catch (error) {
    self.postMessage({ type: 'error', id: data.id, message: String(error?.message ?? error) });
  }
};
