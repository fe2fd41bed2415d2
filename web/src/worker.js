// The page's Web Worker: runs coinroll's core (the WebAssembly module, whose script precedes this one
// in the worker's Blob, so createCoinrollCore is a global here) off the page's thread. One message
// in, {id, sceneText, sampleDt, sourceName, steady}: one run, and `coinroll steady` for each of the
// `steady` requests on the same scene; out, its progress, then its columns (their buffers
// transferred, not copied) with the steady reports, or the core's refusal with the program's message.
/* global createCoinrollCore */
import wasmGzipBase64 from 'inline:wasm';

// The module's WebAssembly, gzipped at build time (web/build.mjs), unpacked here and handed to the
// module as wasmBinary, so that it neither parses a base64 copy nor fetches anything.
async function wasmBinary() {
  const packed = Uint8Array.from(atob(wasmGzipBase64), (c) => c.charCodeAt(0));
  return new Response(new Blob([packed]).stream().pipeThrough(new DecompressionStream('gzip'))).arrayBuffer();
}

const started = performance.now();
const ready = wasmBinary().then((binary) => createCoinrollCore({ wasmBinary: binary })).then((core) => {
  postMessage({ type: 'ready', version: core.version(), defaultScene: core.defaultSceneJson(), loadMs: performance.now() - started });
  return core;
});
ready.catch((e) => postMessage({ type: 'failed', message: `the WebAssembly core did not start: ${e && e.message ? e.message : e}` }));

onmessage = async (event) => {
  const core = await ready;
  const { id, sceneText, sampleDt, sourceName, steady: requests } = event.data;
  const start = performance.now();
  try {
    // Before the run, so that a refused steady start does not wait for a long run; each answered
    // alone, since one motion refused (no spin in place upright) leaves the others.
    const steady = requests.map((request) => {
      try {
        return { report: core.steady(sceneText, [], Object.assign({ sourceName }, request)) };
      } catch (e) {
        return { error: { message: e.message, kind: e.kind } };
      }
    });
    const result = core.simulate(sceneText, [], {
      sampleDt, sourceName,
      onProgress: (rows, expected) => { postMessage({ type: 'progress', id, rows, expected }); return true; },
    });
    const { names, columns, rows, end, events, impacts, report, stats } = result;
    postMessage({ type: 'result', id, names, columns, rows, end, events, impacts, report, stats, steady, ms: performance.now() - start },
                Object.values(columns).map((column) => column.buffer));
  } catch (e) {
    postMessage({ type: 'error', id, message: e.message, kind: e.kind, exitCode: e.exitCode });
  }
};
