// The page's Web Worker: runs coinroll's core (the WebAssembly module, whose script precedes this one
// in the worker's Blob, so createCoinrollCore is a global here) off the page's thread. One message
// in, {id, sceneText, sourceName, steady}: one run on the renderer's grid with its visual track (the
// coin's triangles, the overlay and the playback rate: the core's visualRun), and `coinroll steady`
// for each of the `steady` requests on the same scene; out, its progress, then its columns and track
// (their buffers transferred, not copied) with the steady reports, or the core's refusal with the
// program's message.
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
  const picture = core.picture('classic', 512);
  postMessage({ type: 'ready', version: core.version(), defaultScene: core.defaultSceneJson(), picture,
                loadMs: performance.now() - started }, [picture.floorTile.buffer]);
  return core;
});
ready.catch((e) => postMessage({ type: 'failed', message: `the WebAssembly core did not start: ${e && e.message ? e.message : e}` }));

onmessage = async (event) => {
  const core = await ready;
  const { id, sceneText, sourceName, steady: requests } = event.data;
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
    const result = core.visualRun(sceneText, [], {
      sourceName,
      onProgress: (rows, expected) => { postMessage({ type: 'progress', id, rows, expected }); return true; },
    });
    const { names, columns, rows, sampleDt, end, events, report, stats, visual } = result;
    const buffers = [...Object.values(columns), ...Object.values(visual.coin), ...Object.values(visual.cameras), visual.clock.times, visual.clock.playbackRates].map((array) => array.buffer);
    postMessage({ type: 'result', id, names, columns, rows, sampleDt, end, events, report, stats, visual, steady,
                  ms: performance.now() - start }, buffers);
  } catch (e) {
    postMessage({ type: 'error', id, message: e.message, kind: e.kind, exitCode: e.exitCode });
  }
};
