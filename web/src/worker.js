// The page's Web Worker: runs coinroll's core off the page's thread. The worker's Blob holds the
// core's script, then this (runner.js), so createCoinrollCore is a global here. Its first message is
// the core's compiled WebAssembly.Module (and whether to say what the core is), which the page compiles once and hands to every worker, so
// that a spare starts in milliseconds and runs code V8 has already optimised in another. Then one
// message in, {id, sceneText, sourceName, steady}: out, its progress, then the run's columns and
// visual track (their buffers transferred, not copied) with the steady reports, or the core's refusal
// with the program's message.
/* global createCoinrollCore */
import { buffersOf, readyAnswer, runRequest } from './core_requests.js';

let receiveModule;
const compiled = new Promise((resolve) => { receiveModule = resolve; });
const started = performance.now();
const ready = compiled.then(({ module }) => createCoinrollCore({
  instantiateWasm(imports, receive) {
    WebAssembly.instantiate(module, imports).then((instance) => receive(instance, module));
    return {};
  },
}));
// The first worker tells the page what the core is (its version, default scene and picture); a spare
// only that it is ready.
Promise.all([compiled, ready]).then(([{ answer }, core]) => {
  const message = { type: 'ready', loadMs: performance.now() - started };
  if (!answer) return postMessage(message);
  const about = readyAnswer(core);
  return postMessage(Object.assign(message, about), [about.picture.floorTile.buffer]);
}).catch((e) => postMessage({ type: 'failed', message: `the WebAssembly core did not start: ${e && e.message ? e.message : e}` }));

// ms between progress reports: enough for a smooth bar and for the runner to judge how soon a run
// ends; the core reports every half per cent of a run, which for a 20 ms run was 200 messages.
const kProgressEveryMs = 8;

onmessage = async (event) => {
  if (event.data.type === 'module') {
    receiveModule(event.data);
    return;
  }
  const core = await ready;
  const { id } = event.data;
  const start = performance.now();
  try {
    let reported = start;
    const result = runRequest(core, event.data, (rows, expected) => {
      const now = performance.now();
      if (now - reported < kProgressEveryMs) return;
      reported = now;
      postMessage({ type: 'progress', id, rows, expected });
    });
    postMessage(Object.assign({ type: 'result', id, ms: performance.now() - start }, result), buffersOf(result));
  } catch (e) {
    postMessage({ type: 'error', id, message: e.message, kind: e.kind, exitCode: e.exitCode });
  }
};
