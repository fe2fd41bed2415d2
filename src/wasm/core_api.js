// The module's documented functions (docs/web.md "The JavaScript surface"), added to the module
// that createCoinrollCore() resolves to; em++ appends this file to the module (--post-js). They
// check their arguments here, where a mistake can be named in JavaScript's terms, and turn the
// core's refusals into CoinrollError. All in a function of its own: Emscripten's code around it
// has names of its own (run, out, err) that a declaration here would replace.

(() => {
  class CoinrollError extends Error {
    constructor(kind, exitCode, message) {
      super(message);
      this.name = 'CoinrollError';
      this.kind = kind;          // "scene", "request", "cancelled" or "failure"
      this.exitCode = exitCode;  // what `coinroll simulate` (or `steady`) exits with for the same input
    }
  }

  const kSimulateOptions = ['sampleDt', 'sourceName', 'maxRows', 'onProgress'];

  function describeValue(value) {
    if (value === null) return 'null';
    if (Array.isArray(value)) return 'an array';
    return typeof value === 'object' ? `a ${value.constructor ? value.constructor.name : 'object'}` : `${typeof value} ${String(value)}`;
  }

  // [bytes or text, given]: null or undefined is the built-in default scene, as `coinroll simulate`
  // without a scene file; an object is a scene document, as its JSON text.
  function sceneArgument(scene) {
    if (scene === undefined || scene === null) return ['', false];
    if (typeof scene === 'string' || scene instanceof Uint8Array) return [scene, true];
    if (scene instanceof ArrayBuffer) return [new Uint8Array(scene), true];
    if (typeof scene === 'object' && !Array.isArray(scene)) return [JSON.stringify(scene), true];
    throw new TypeError(`scene: expected the scene's JSON text (a string or bytes), a scene object, or null for the built-in ` +
                        `default scene; got ${describeValue(scene)}`);
  }

  function overridesArgument(overrides) {
    if (overrides === undefined || overrides === null) return [];
    if (!Array.isArray(overrides) || !overrides.every((o) => typeof o === 'string')) {
      throw new TypeError(`overrides: expected an array of "KEY.PATH=VALUE" strings, as --set takes them; got ${describeValue(overrides)}`);
    }
    return overrides;
  }

  // `allowed`: the options the function takes (visualRun chooses its own sample step).
  function simulateOptions(options, allowed = kSimulateOptions) {
    if (options === undefined || options === null) options = {};
    if (typeof options !== 'object') throw new TypeError(`options: expected an object; got ${describeValue(options)}`);
    const unknown = Object.keys(options).filter((key) => !allowed.includes(key));
    if (unknown.length) throw new TypeError(`options: unknown ${unknown.join(', ')}; the options are ${allowed.join(', ')}`);
    const { sampleDt = 0.01, sourceName = 'scene JSON', maxRows = 1e9, onProgress } = options;
    if (typeof sampleDt !== 'number') throw new TypeError(`options.sampleDt: expected a number of seconds; got ${describeValue(sampleDt)}`);
    if (typeof sourceName !== 'string') throw new TypeError(`options.sourceName: expected a string; got ${describeValue(sourceName)}`);
    if (typeof maxRows !== 'number' || !(maxRows >= 1)) {
      throw new TypeError(`options.maxRows: expected a number >= 1; got ${describeValue(maxRows)}`);
    }
    if (onProgress !== undefined && typeof onProgress !== 'function') {
      throw new TypeError(`options.onProgress: expected a function (rowsWritten, rowsExpected); got ${describeValue(onProgress)}`);
    }
    return { sampleDt, sourceName, maxRows, onProgress };
  }

  // Texts the core packed into one buffer, each ended by a NUL (core.cpp textsOut).
  const textsOf = (bytes) => new TextDecoder().decode(bytes).split('\0').slice(0, -1);

  // asColumns: the rows as Float64Array columns instead of the CSV's text. visual: on the renderer's
  // trace grid, with the visual track (what the picture shows besides the columns).
  function simulateRun(scene, overrides, options, asColumns, visual = false) {
    const [sceneText, hasScene] = sceneArgument(scene);
    const list = overridesArgument(overrides);
    const { sampleDt, sourceName, maxRows, onProgress } =
      simulateOptions(options, visual ? kSimulateOptions.filter((o) => o !== 'sampleDt') : kSimulateOptions);
    // An exception thrown by the callback stops the run as `false` does, and is thrown once the run
    // has unwound: passing through the WebAssembly it would skip the C++ destructors (the run's
    // memory would stay taken).
    let thrown = null;
    const progress = onProgress && ((rows, expected) => {
      try {
        return onProgress(rows, expected);
      } catch (e) {
        thrown = { e };
        return false;
      }
    });
    const result = Module['coreSimulate'](sceneText, hasScene, list, sourceName, sampleDt, maxRows, progress, asColumns, visual);
    if (thrown) throw thrown.e;
    if (result.error) throw new CoinrollError(result.error.kind, result.error.exitCode, result.error.message);
    if (asColumns) {
      result.columns = Object.fromEntries(result.names.map((name, i) => [name, result.columnValues[i]]));
      delete result.columnValues;
    } else {
      result.csv = new TextDecoder().decode(result.csvBytes);
      delete result.csvBytes;
    }
    if (visual) {
      const track = result.visual;
      track.overlay = { si: textsOf(track.overlaySiBytes), seed: textsOf(track.overlaySeedBytes) };
      delete track.overlaySiBytes;
      delete track.overlaySeedBytes;
    }
    return result;
  }

  const kSteadyOptions = ['kind', 'theta', 'omega_Z', 'branch', 'sourceName'];

  // `coinroll steady`'s --kind, --theta (degrees), --omega-Z (rad/s) and --branch, each optional as there.
  function steadyOptions(options) {
    if (options === undefined || options === null) options = {};
    if (typeof options !== 'object') throw new TypeError(`options: expected an object; got ${describeValue(options)}`);
    const unknown = Object.keys(options).filter((key) => !kSteadyOptions.includes(key));
    if (unknown.length) throw new TypeError(`options: unknown ${unknown.join(', ')}; the options are ${kSteadyOptions.join(', ')}`);
    const { kind, theta, omega_Z, branch, sourceName = 'scene JSON' } = options;
    if (kind !== undefined && !['straight', 'circle', 'spin-in-place'].includes(kind)) {
      throw new TypeError(`options.kind: expected "straight", "circle" or "spin-in-place"; got ${describeValue(kind)}`);
    }
    for (const [name, value] of [['theta', theta], ['omega_Z', omega_Z]]) {
      if (value !== undefined && typeof value !== 'number') throw new TypeError(`options.${name}: expected a number; got ${describeValue(value)}`);
    }
    if (branch !== undefined && branch !== '+' && branch !== '-') throw new TypeError(`options.branch: expected "+" or "-"; got ${describeValue(branch)}`);
    if (typeof sourceName !== 'string') throw new TypeError(`options.sourceName: expected a string; got ${describeValue(sourceName)}`);
    return { kind: kind || '', theta, omega_Z, branch: branch || '', sourceName };
  }

  function steady(scene, overrides, options) {
    const [sceneText, hasScene] = sceneArgument(scene);
    const list = overridesArgument(overrides);
    const { kind, theta, omega_Z, branch, sourceName } = steadyOptions(options);
    const result = Module['coreSteady'](sceneText, hasScene, list, sourceName, kind, theta, omega_Z, branch);
    if (result.error) throw new CoinrollError(result.error.kind, result.error.exitCode, result.error.message);
    return result;
  }

  Module['CoinrollError'] = CoinrollError;
  // The bindings (core.cpp) exist once the WebAssembly has started, after this file ran: looked up when called.
  Module['version'] = () => Module['coreVersion'];
  Module['defaultSceneJson'] = () => Module['coreDefaultSceneJson']();
  Module['simulateCsv'] = (scene, overrides, options) => simulateRun(scene, overrides, options, false);
  Module['simulate'] = (scene, overrides, options) => simulateRun(scene, overrides, options, true);
  Module['steady'] = steady;
  // What the renderer draws a picture in for render.theme `theme` ("classic" or "paper"): the sky,
  // the trace's colours and the floor's grid tile, `tilePixels` square.
  Module['picture'] = (theme = 'classic', tilePixels = 512) => {
    if (theme !== 'classic' && theme !== 'paper') throw new TypeError(`theme: expected "classic" or "paper"; got ${describeValue(theme)}`);
    if (!Number.isInteger(tilePixels) || tilePixels < 1 || tilePixels > 4096) {
      throw new TypeError(`tilePixels: expected a whole number from 1 to 4096; got ${describeValue(tilePixels)}`);
    }
    return Module['corePicture'](theme, tilePixels);
  };
  // simulate on the renderer's trace grid with the visual track: what a page needs to draw the run
  // as `coinroll render` does (its coin, overlay and clock), besides the columns.
  Module['visualRun'] = (scene, overrides, options) => simulateRun(scene, overrides, options, true, true);
})();
