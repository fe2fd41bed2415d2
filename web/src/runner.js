// Runs scenes in Web Workers, each holding the WebAssembly core (src/worker.js), made from a Blob of
// the core's script, its WebAssembly and the worker's script, since a file:// page can load no other
// file. A run is synchronous inside its worker, so a newer request cannot reach it: the newer request
// terminates it and goes to a spare worker that has already loaded the core, and a new spare starts
// loading. LocalRunner runs them on the page's own thread instead (#probe: probe.js).
import { readyAnswer, runRequest } from './core_requests.js';

export class Cancelled extends Error {}

// The core's refusal, with the message `coinroll simulate` prints after "coinroll: error: ".
export class RunError extends Error {
  constructor(data) {
    super(data.message);
    Object.assign(this, { kind: data.kind, exitCode: data.exitCode });
  }
}

export class Runner {
  constructor(coreSource, wasmGzipBase64, workerSource) {
    const parts = [coreSource, `;\nconst coinrollWasm = ${JSON.stringify(wasmGzipBase64)};\n`, workerSource];
    this.url = URL.createObjectURL(new Blob(parts, { type: 'text/javascript' }));
    this.idle = this.spawn();
    this.spare = null;  // made once the first worker is up, so that the two do not share the first second
    this.busy = null;
    this.ready = this.idle.ready;
  }

  spawn() {
    const worker = new Worker(this.url);
    const ready = new Promise((resolve, reject) => {
      worker.onmessage = (event) => {
        if (event.data.type === 'ready') resolve(event.data);
        else if (event.data.type === 'failed') reject(new Error(event.data.message));
      };
      worker.onerror = (event) => reject(new Error(`the worker failed: ${event.message}`));
    });
    return { worker, ready };
  }

  // The run of `sceneText` on the renderer's grid: resolves to the worker's result, rejects with
  // RunError for a refusal, Cancelled when a later run() took over. `steady`: `coinroll steady`'s
  // requests ({kind, theta, omega_Z, branch}) of the same scene, answered in the result's `steady`.
  async run(sceneText, sourceName, onProgress, steady = []) {
    const id = (this.nextId = (this.nextId || 0) + 1);
    if (this.busy) {
      this.busy.worker.terminate();
      this.busy.cancel(new Cancelled('a newer run took over'));
      this.busy = null;
    }
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
      this.busy = Object.assign(slot, { cancel: reject });
      slot.worker.onmessage = (event) => {
        const data = event.data;
        if (data.id !== id) return;
        if (data.type === 'progress') { onProgress(data.rows, data.expected); return; }
        if (this.busy === slot) this.busy = null;
        this.idle = slot;
        if (data.type === 'result') resolve(data);
        else reject(new RunError(data));
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
