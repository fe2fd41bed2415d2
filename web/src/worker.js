// The page's Web Worker: runs coinroll's core off the page's thread. The worker's Blob holds the
// core's script, then the module's WebAssembly as `coinrollWasm` (gzipped, base64), then this
// (runner.js), so createCoinrollCore is a global here. One message in, {id, sceneText, sourceName,
// steady}: out, its progress, then the run's columns and visual track (their buffers transferred,
// not copied) with the steady reports, or the core's refusal with the program's message.
/* global createCoinrollCore, coinrollWasm */
import { buffersOf, readyAnswer, runRequest } from './core_requests.js';

// Unpacked by the browser's own gzip and handed to the module as wasmBinary, so that it neither
// parses a base64 copy nor fetches anything.
async function wasmBinary() {
  const packed = Uint8Array.from(atob(coinrollWasm), (c) => c.charCodeAt(0));
  return new Response(new Blob([packed]).stream().pipeThrough(new DecompressionStream('gzip'))).arrayBuffer();
}

const started = performance.now();
const ready = wasmBinary().then((binary) => createCoinrollCore({ wasmBinary: binary })).then((core) => {
  const answer = readyAnswer(core);
  postMessage(Object.assign({ type: 'ready', loadMs: performance.now() - started }, answer), [answer.picture.floorTile.buffer]);
  return core;
});
ready.catch((e) => postMessage({ type: 'failed', message: `the WebAssembly core did not start: ${e && e.message ? e.message : e}` }));

onmessage = async (event) => {
  const core = await ready;
  const { id } = event.data;
  const start = performance.now();
  try {
    const result = runRequest(core, event.data, (rows, expected) => postMessage({ type: 'progress', id, rows, expected }));
    postMessage(Object.assign({ type: 'result', id, ms: performance.now() - start }, result), buffersOf(result));
  } catch (e) {
    postMessage({ type: 'error', id, message: e.message, kind: e.kind, exitCode: e.exitCode });
  }
};
