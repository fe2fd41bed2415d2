// Runs scenes in Web Workers, each holding the WebAssembly core (src/worker.js), made from a Blob of
// the core's script and the worker's script, since a file:// page can load no other file; the core's
// WebAssembly is compiled once here and its Module handed to each worker. A run is synchronous inside its worker, so no message can stop it part-way (a shared cancel
// flag needs SharedArrayBuffer, which a file:// page lacks). A newer request therefore waits for a
// run that will soon end, in the same warm worker, where its code is already optimised; a run that
// will not (by its progress) is terminated and the request goes to a spare worker that has already
// loaded the core, and a new spare starts loading. Only the newest waiting request is kept: a burst
// of slider moves runs its last value next. LocalRunner runs them on the page's own thread instead
// (#probe: probe.js).
import { readyAnswer, runRequest } from './core_requests.js';

export class Cancelled extends Error {}

// The core's refusal, with the message `coinroll simulate` prints after "coinroll: error: ".
export class RunError extends Error {
  constructor(data) {
    super(data.message);
    Object.assign(this, { kind: data.kind, exitCode: data.exitCode });
  }
}

// ms: a busy run expected to end within this is waited for. Terminating it costs more: the new spare
// made in its place takes a core while it starts.
const kWaitForMs = 40;

// The core's WebAssembly, unpacked by the browser's own gzip and compiled off the page's thread.
async function compiledCore(wasmGzipBase64) {
  const packed = Uint8Array.from(atob(wasmGzipBase64), (c) => c.charCodeAt(0));
  const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream('gzip'));
  return WebAssembly.compile(await new Response(stream).arrayBuffer());
}

export class Runner {
  constructor(coreSource, wasmGzipBase64, workerSource) {
    this.url = URL.createObjectURL(new Blob([coreSource, ';\n', workerSource], { type: 'text/javascript' }));
    this.module = compiledCore(wasmGzipBase64);
    this.idle = this.spawn(true);
    this.spare = null;  // made once the first worker is up, so that the two do not share the first second
    this.busy = null;
    this.waiting = null;  // the newest request that waits for the busy run: {resolve, reject}
    this.ready = this.idle.ready;
  }

  // A worker, once its core has started; the first (`answer`) also reports the core's version,
  // default scene and picture (core_requests.js readyAnswer).
  spawn(answer = false) {
    const worker = new Worker(this.url);
    const ready = new Promise((resolve, reject) => {
      worker.onmessage = (event) => {
        if (event.data.type === 'ready') resolve(event.data);
        else if (event.data.type === 'failed') reject(new Error(event.data.message));
      };
      worker.onerror = (event) => reject(new Error(`the worker failed: ${event.message}`));
      this.module.then((module) => worker.postMessage({ type: 'module', module, answer }), reject);
    });
    return { worker, ready };
  }

  // Whether the busy run will end within kWaitForMs: by the rate of its rows so far, or before its
  // first progress report has been read (the page's thread may be drawing), by the last run's time.
  busyEndsSoon() {
    const { startedAt, rows, expected } = this.busy;
    const elapsed = performance.now() - startedAt;
    if (rows > 0 && expected > 0) return elapsed * Math.max(expected - rows, 0) / rows < kWaitForMs;
    return (this.lastRunMs || 0) - elapsed < kWaitForMs;
  }

  abandonBusy() {
    this.busy.worker.terminate();
    this.busy.cancel(new Cancelled('a newer run took over'));
    this.busy = null;
    this.wake();
  }

  wake() {
    const waiting = this.waiting;
    this.waiting = null;
    if (waiting) waiting.resolve();
  }

  // The run of `sceneText` on the renderer's grid: resolves to the worker's result, rejects with
  // RunError for a refusal, Cancelled when a later run() took over. `steady`: `coinroll steady`'s
  // requests ({kind, theta, omega_Z, branch}) of the same scene, answered in the result's `steady`.
  async run(sceneText, sourceName, onProgress, steady = []) {
    const id = (this.nextId = (this.nextId || 0) + 1);
    if (this.waiting) {
      this.waiting.reject(new Cancelled('a newer run took over'));
      this.waiting = null;
    }
    if (this.busy && !this.busyEndsSoon()) this.abandonBusy();
    if (this.busy) await new Promise((resolve, reject) => { this.waiting = { resolve, reject }; });
    let slot = this.idle;
    this.idle = null;
    if (!slot) {
      slot = this.spare || this.spawn();
      this.spare = null;
    }
    await slot.ready;
    if (!this.spare) this.spare = this.spawn();
    if (id !== this.nextId) {  // a newer run came while this one waited for its worker
      if (this.idle) slot.worker.terminate();
      else this.idle = slot;
      throw new Cancelled('a newer run took over');
    }
    return new Promise((resolve, reject) => {
      this.busy = Object.assign(slot, { cancel: reject, startedAt: performance.now(), rows: 0, expected: 0 });
      slot.worker.onmessage = (event) => {
        const data = event.data;
        if (data.id !== id) return;
        if (data.type === 'progress') {
          Object.assign(slot, { rows: data.rows, expected: data.expected });
          if (this.waiting && !this.busyEndsSoon()) this.abandonBusy();
          else onProgress(data.rows, data.expected);
          return;
        }
        if (this.busy === slot) this.busy = null;
        this.idle = slot;
        if (data.type === 'result') {
          this.lastRunMs = data.ms;
          resolve(data);
        }
        else reject(new RunError(data));
        this.wake();
      };
      slot.worker.postMessage({ id, sceneText, sourceName, steady });
    });
  }
}

// The same requests answered by a core on the page's thread, each to its end before the next: the
// page with #probe, whose numbers must be in the DOM by the time the page has loaded.
export class LocalRunner {
  constructor(core) {
    this.core = core;
    this.ready = Promise.resolve(readyAnswer(core));
  }

  async run(sceneText, sourceName, onProgress, steady = []) {
    try {
      return runRequest(this.core, { sceneText, sourceName, steady }, onProgress);
    } catch (e) {
      throw new RunError(e);
    }
  }
}
