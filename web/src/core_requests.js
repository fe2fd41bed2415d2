// What the page asks of coinroll's core, in one place for both of its homes: the Web Worker
// (worker.js) and, with #probe, the page's own thread (probe.js). The module's WebAssembly travels
// gzipped and base64-encoded (web/build.mjs), so that the page stays under 2 MB.

// The core's startup answer: its version, the built-in default scene and the picture's colours and
// floor tile (core.picture).
export function readyAnswer(core) {
  return { version: core.version(), defaultScene: core.defaultSceneJson(), picture: core.picture('classic', 512) };
}

// One run on the renderer's grid with its visual track (core.visualRun), and `coinroll steady` for
// each of the `steady` requests on the same scene. Throws the core's refusal (CoinrollError).
export function runRequest(core, { sceneText, sourceName, steady: requests }, onProgress) {
  // Before the run, so that a refused steady start does not wait for a long run; each answered
  // alone, since one motion refused (no spin in place upright) leaves the others.
  const steady = requests.map((request) => {
    try {
      return { report: core.steady(sceneText, [], Object.assign({ sourceName }, request)) };
    } catch (e) {
      return { error: { message: e.message, kind: e.kind } };
    }
  });
  const { names, columns, rows, sampleDt, end, events, report, stats, visual } =
    core.visualRun(sceneText, [], { sourceName, onProgress: (done, expected) => { onProgress(done, expected); return true; } });
  return { names, columns, rows, sampleDt, end, events, report, stats, visual, steady };
}

// The typed arrays of a run's result, whose buffers a worker hands over instead of copying.
export function buffersOf({ columns, visual }) {
  return [...Object.values(columns), ...Object.values(visual.coin), ...Object.values(visual.cameras),
          visual.clock.times, visual.clock.playbackRates].map((array) => array.buffer);
}
