// The page's probe (docs/contract.md "Web page"): opened as page.html#probe=T1,T2,..., it runs the
// scene on its own thread while it loads and writes the CSV's columns at those simulated times into
// <pre id="coinroll-probe">, so that a headless browser's DOM dump (chromium --headless --dump-dom)
// can be held against `coinroll simulate` with no driver. Everything here is synchronous: the DOM is
// dumped once the page has loaded, and a promise or a stream would finish after that.
/* global createCoinrollCore */
import { gunzipSync } from 'fflate';

// The columns the probe reports, the CSV's names and units.
const kProbeColumns = ['theta', 'x', 'y', 'z', 'energy'];
// Each time is its own run's sample step: a time this many times shorter than the run is refused
// (by the core, naming the limit) rather than holding a page's memory.
const kMaxProbeRows = 1e6;

// The times asked for by `#probe=...`, or null for a page opened without it. Throws on a list that
// is not numbers, so that the probe says so instead of reporting something else.
export function probeTimes(hash) {
  const match = /^#probe=(.*)$/.exec(hash);
  if (!match) return null;
  const times = decodeURIComponent(match[1]).split(',').map((item) => Number(item.trim()));
  if (times.length === 0 || times.some((t) => !Number.isFinite(t) || t < 0)) {
    throw new Error(`#probe=${match[1]}: expected simulated times in seconds, each 0 or more, separated by commas`);
  }
  return times;
}

// The core on the page's thread, started synchronously: the WebAssembly unpacked by fflate and
// compiled by WebAssembly.Module (a page's thread may compile up to 8 MB so), handed to the module
// through instantiateWasm, after which Emscripten initialises its runtime before returning.
export function mainThreadCore(coreSource, wasmGzipBase64) {
  const createCore = new Function(`${coreSource};\nreturn createCoinrollCore;`)();
  const binary = gunzipSync(Uint8Array.from(atob(wasmGzipBase64), (c) => c.charCodeAt(0)));
  const core = {
    instantiateWasm(imports, receive) {
      const module = new WebAssembly.Module(binary);
      const instance = new WebAssembly.Instance(module, imports);
      receive(instance, module);
      return instance.exports;
    },
  };
  createCore(core);
  if (!core.calledRun) throw new Error('the WebAssembly core did not start on the page\'s thread');
  return core;
}

// The probe's JSON: {t: [...], theta: [...], ...} at `times`, each value the run's row at exactly
// that time (a run whose sample step is the time itself, so its row 1 is there, as `coinroll
// simulate`'s row is on its own grid); null where the run ended before it. A refused scene gives
// {error, kind}, with the command's message.
export function probe(core, sceneText, sourceName, times) {
  const result = { t: times };
  kProbeColumns.forEach((name) => { result[name] = []; });
  try {
    for (const t of times) {
      let run;
      try {
        run = core.simulate(sceneText, [], { sampleDt: t > 0 ? t : 1, sourceName, maxRows: kMaxProbeRows });
      } catch (e) {
        if (e.kind !== 'request') throw e;
        return { error: `#probe time ${t} s is too short: the page runs the scene with each time as its sample step (${e.message})`,
                 kind: e.kind };
      }
      const row = t > 0 ? 1 : 0;
      for (const name of kProbeColumns) result[name].push(row < run.rows ? run.columns[name][row] : null);
    }
  } catch (e) {
    return { error: e.message, kind: e.kind };
  }
  return result;
}

export function writeProbe(json) {
  let element = document.getElementById('coinroll-probe');
  if (!element) {
    element = document.createElement('pre');
    element.id = 'coinroll-probe';
    element.hidden = true;
    document.body.append(element);
  }
  element.textContent = JSON.stringify(json);
}
