// The page (docs/web.md "The page"): controls built from the scene schema edit a scene, the
// WebAssembly core runs it in a worker, and three.js plays the run back as the program draws it.
import { coreSource, workerSource } from 'inline:worker';
import examples from 'inline:examples';
import wasmGzipBase64 from 'inline:wasm';
import { Controls, fitScene, suggestedValue } from './controls.js';
import { Legend } from './legend.js';
import { Plots } from './plots.js';
import { mainThreadCore, probe, probeTimes, writeProbe } from './probe.js';
import { Cancelled, LocalRunner, Runner } from './runner.js';
import { defaultOf } from './schema.js';
import { SteadyPanel, steadyRequests } from './steady_panel.js';
import { Trajectory } from './trajectory.js';
import { basisOf, formatG, Units } from './units.js';
import { View } from './view.js';

const $ = (id) => document.getElementById(id);

// The scene's render settings that the camera and the view read, with the schema's defaults.
function renderSpec(scene) {
  const render = scene.render || {}, camera = render.camera || {};
  const or = (value, path) => (value !== undefined ? value : defaultOf(path));
  return {
    trace: or(render.trace, 'render.trace'),
    hud: or(render.hud, 'render.hud'),
    camera: {
      mode: or(camera.mode, 'render.camera.mode'),
      aspect: or(render.width, 'render.width') / or(render.height, 'render.height'),
    },
  };
}

// What the steady-motion panel asks the core of a scene's text: none where it is no scene with a
// start (the core then refuses the run and says why).
function steadyRequestsOf(text) {
  try {
    const initial = JSON.parse(text).initial;
    return initial !== null && typeof initial === 'object' && !Array.isArray(initial) ? steadyRequests(initial) : [];
  } catch (e) {
    return [];
  }
}

const page = {
  scene: null,          // the scene the controls edit
  trajectory: null,     // the run on screen
  run: null,            // {text, sourceName, sampleDt} of that run, what "download scene" writes
  runRequest: 0,        // the request that made it
  t: 0, playing: true, speed: 1, holdUntil: 0,
  system: 'si',         // the units numbers show in: 'si' or 'seed' (units.js)
  units: (scene) => new Units(page.system, basisOf(scene)),
  changed: (path) => onControl(path),
  suggestedValue,
  showRunning: () => { if (page.run) showSceneText(page.run.text); },
};

// `coinroll export`'s choices for a course page (docs/web.md "A page for a course"): its title and
// caption, the controls a student sees, the researcher's details folded or shown; null: the page as built.
const pageOptions = JSON.parse($('coinroll-page-options').textContent) || { details: 'shown' };
showPageOptions(pageOptions);

// The scene `coinroll export` put in the page, or null: the built-in default scene.
const exportedScene = JSON.parse($('coinroll-scene').textContent);
const exportedSourceName = exportedScene === null ? 'built-in default scene' : 'exported scene';

// Workers, or with #probe=T1,T2,... the page's own thread: the probe is written before the page has
// loaded (probe.js), and the page then plays the same core's runs.
function makeRunner() {
  let times = null;
  try {
    times = probeTimes(window.location.hash);
  } catch (e) {
    writeProbe({ error: e.message });
  }
  if (!times) return new Runner(coreSource, wasmGzipBase64, workerSource);
  const core = mainThreadCore(coreSource, wasmGzipBase64);
  const sceneText = exportedScene === null ? core.defaultSceneJson() : JSON.stringify(exportedScene);
  writeProbe(probe(core, sceneText, exportedSourceName, times));
  return new LocalRunner(core);
}
const runner = makeRunner();
const view = new View($('canvas'));
const controls = new Controls($('controls'), page, pageOptions.controls || null);
// A steady motion's button starts it as the start menu does, and a refusal shows at that menu.
const steadyPanel = new SteadyPanel($('steady'), (initial) => {
  page.scene.initial = initial;
  onControl('initial[steady].steady');
});
let legend = null;  // made once the core says what the picture is drawn in
// The plots open where they leave the picture room: a phone scrolls to them, a short window (an
// 800x600 iframe) keeps them a click away.
$('plots').open = window.innerHeight >= 700 || window.innerWidth < 720;
// A press on a plot stops playback there, as a student points at a moment to look at it.
const plots = new Plots($('plots'), (t) => {
  setPlaying(false);
  page.t = t;
  page.holdUntil = 0;
  view.dirty = true;
});
let fixedSize = null, lastFrameTime, request = 0;
// Whether the latest request is still to be drawn (or refused), and who waits for it (the test hook).
let pending = true;
let waiters = [];
function settle() {
  pending = false;
  for (const resolve of waiters) resolve();
  waiters = [];
}
const timing = { firstFrameAt: undefined, last: undefined };
// ms the picture holds still while a newer run is on its way: the CPU goes to that run rather than
// to frames of the run it replaces (in software WebGL a frame costs as much as a default-scene run);
// a longer run lets the old one play on, under the busy sign.
const kHoldForRunMs = 250;
let latestRequestAt = 0;
let busyTimer;

// The title and caption as text (never markup), and the details folded: the scene file's box, with the
// run's log moved in beside it, one click away.
function showPageOptions(options) {
  if (options.title) {
    document.title = options.title;
    $('title-text').textContent = options.title;
    $('version').hidden = true;
  }
  if (options.caption) {
    $('caption').textContent = options.caption;
    $('caption').hidden = false;
  }
  if (options.details === 'folded') {
    $('researcher').append($('run-info'));
    $('researcher').open = false;
  }
}

function showSceneText(text) {
  $('scene-text').value = text;
}

function onControl(path) {
  if (page.run) fitScene(page.scene, JSON.parse(page.run.text));
  const text = JSON.stringify(page.scene, null, 2);
  showSceneText(text);
  controls.refresh();
  start(text, 'scene.json', { control: path });
}

// Runs `text`; `origin` is where the user typed it ({control: path} or {box: true}), where a refusal shows.
async function start(text, sourceName, origin) {
  const id = ++request;
  const requestedAt = performance.now();
  latestRequestAt = requestedAt;
  pending = true;
  controls.clearErrors();
  $('scene-error').textContent = '';
  // One busy sign for the page, the newest run's: an older run's timer would show it after the newest
  // had ended, and its progress would move the newest run's bar.
  clearTimeout(busyTimer);
  busyTimer = setTimeout(() => { $('busy').hidden = false; }, 150);
  const progress = (rows, expected) => {
    if (id !== request) return;
    $('progress').value = expected > 0 ? rows / expected : 0;
    $('progress-text').textContent = `${rows} of ${expected} rows`;
  };
  progress(0, 0);
  try {
    const result = await runner.run(text, sourceName, progress, steadyRequestsOf(text));
    if (id !== request) return;
    const scene = JSON.parse(text);
    if (origin.box) page.scene = scene;
    page.trajectory = new Trajectory(result, scene);
    page.run = { text, sourceName, sampleDt: result.sampleDt };
    page.runRequest = id;
    timing.last = { requestedAt, resultAt: performance.now(), workerMs: result.ms };
    newRun(result);
    draw();  // now, not at the next animation frame: a frame can take 10 ms and more in software WebGL
  } catch (e) {
    if (e instanceof Cancelled || id !== request) return;
    const message = e.message;
    // A control's change refused: the control keeps the refused value and says why, and the page goes
    // on editing the scene on screen, so that the next change is not refused for this one.
    let shown = false;
    if (origin.control && page.run) {
      const refused = page.scene;
      page.scene = JSON.parse(page.run.text);
      shown = controls.refuse(origin.control, message, refused);
      controls.refresh();
    }
    if (!shown) $('scene-error').textContent = message;
    settle();
  } finally {
    if (id === request) {
      clearTimeout(busyTimer);
      $('busy').hidden = true;
    }
  }
}

function newRun(result) {
  const trajectory = page.trajectory;
  resize();
  const spec = renderSpec(trajectory.scene);
  view.setRun(trajectory, spec.trace);
  controls.refresh();
  const units = page.units(trajectory.scene);
  steadyPanel.show(trajectory.scene.initial, result.steady, units);
  steadyPanel.showWobble(trajectory, units);
  showKeys(units);
  page.t = 0;
  plots.show(trajectory, units);
  page.playing = true;
  page.holdUntil = 0;
  $('play').textContent = 'Pause';
  $('time').max = trajectory.endTime;
  const end = result.end.event === 'duration' ? `ran its ${result.end.time} s` : `stopped at t = ${result.end.time} s: ${result.end.description}`;
  $('run-info').textContent = `${result.rows} rows every ${+trajectory.sampleDt.toPrecision(6)} s, ${end}; ` +
                              `computed in ${result.ms.toFixed(0)} ms by coinroll's WebAssembly core\n${result.report.join('\n')}`;
  const file = `${trajectory.scene.name || 'coinroll'}.json`;
  $('command').textContent = `"Download scene" writes the scene of the run on screen; coinroll simulate ${file} --csv - ` +
                             `--sample-dt ${trajectory.sampleDt} prints its numbers.`;
  view.dirty = true;
}

function resize() {
  const box = $('view');
  const width = fixedSize ? fixedSize[0] : box.clientWidth, height = fixedSize ? fixedSize[1] : box.clientHeight;
  if (width === view.width && height === view.height) return;
  view.setSize(width, height, fixedSize ? 1 : window.devicePixelRatio);
  // render/overlay_text.cpp: the em from ascent to descent is a 45th of the height; DejaVu Sans
  // Mono's ascent to descent is 1.164 of its CSS font size.
  $('hud').style.fontSize = `${(Math.max(10, height / 45) / 1.164).toFixed(1)}px`;
  view.dirty = true;
}

// The scene's camera at t for the view on screen. It is `coinroll render`'s, which frames the scene's
// picture (render.width x render.height); the fov is vertical, so a view narrower than that picture (a
// phone held upright) widens the field until the picture's width fits, and a wider one shows more at
// the sides: tan(fov'/2) = tan(fov/2) max(1, (W/H)_scene / (w/h)_view).
function sceneCamera(t) {
  const trajectory = page.trajectory, spec = renderSpec(trajectory.scene).camera;
  const camera = trajectory.cameraAt(t);
  const narrowing = spec.aspect / (view.width / view.height);
  if (narrowing > 1) camera.fov = 2 * Math.atan(Math.tan(0.5 * camera.fov * Math.PI / 180) * narrowing) * 180 / Math.PI;
  camera.follows = spec.mode === 'follow';
  return camera;
}

// Draws the picture at the current time and shows its overlay.
function draw() {
  const trajectory = page.trajectory;
  const state = trajectory.stateAt(page.t);
  view.draw(state, sceneCamera(state.t), trajectory);
  const units = page.units(trajectory.scene), time = (t) => units.shown(t, 's').toFixed(3);
  $('hud').textContent = renderSpec(trajectory.scene).hud ? trajectory.overlayAt(state.t, units.seed) : '';
  $('time').value = page.t;
  plots.setTime(state.t);
  $('time-text').textContent = `${time(state.t)} / ${time(trajectory.endTime)} ${units.label('s')}`;
  if (timing.firstFrameAt === undefined) timing.firstFrameAt = performance.now();
  if (timing.last && timing.last.firstFrameAt === undefined) timing.last.firstFrameAt = performance.now();
  if (page.runRequest === request) settle();
  return state;
}

// Playback: simulated seconds advance at the scene's playback rate (render.time_scale, slowed by
// render.time_remap where the motion is fast, in the air and at each impact: the core's, per row) times
// the speed chosen; the end is held as a clip holds it, then the run plays again.
function frame(now) {
  requestAnimationFrame(frame);
  const elapsed = lastFrameTime === undefined ? 0 : Math.min((now - lastFrameTime) / 1000, 0.1);
  lastFrameTime = now;
  resize();
  const trajectory = page.trajectory;
  if (!trajectory || (pending && performance.now() - latestRequestAt < kHoldForRunMs)) return;
  if (page.playing) {
    if (page.t >= trajectory.endTime) {
      if (!page.holdUntil) page.holdUntil = now + 1000 * trajectory.visual.clock.holdSeconds;
      if (now >= page.holdUntil) { page.t = 0; page.holdUntil = 0; }
    } else {
      const rate = trajectory.playbackRate(page.t);
      page.t = Math.min(page.t + elapsed * rate * page.speed, trajectory.endTime);
    }
    view.dirty = true;
  }
  if (view.dirty) draw();
}

// The legend's grid against the coin on screen, and the key to the seed's units with their sizes.
function showKeys(units) {
  legend.show(page.trajectory.scene, units);
  const si = new Units('si');
  const size = (unit) => `${units.label(unit)} = ${formatG(units.scale(unit), 4)} ${si.label(unit)}`;
  $('units-key').textContent = units.seed ? `Lengths in ${size('m')}, times in ${size('s')}, ` +
    `rates in ${size('rad/s')}, velocities in ${size('m/s')}, energies in ${size('J')}, forces in ${size('N')}, ` +
    `moments of inertia in ${size('kg m^2')}: those of the run on screen. Angles stay in degrees; ` +
    'the coin\'s M and a and the gravity g, the units themselves, in SI.' : '';
}

function setPlaying(on) {
  page.playing = on;
  $('play').textContent = on ? 'Pause' : 'Play';
}

$('play').addEventListener('click', () => setPlaying(!page.playing));
for (const radio of document.querySelectorAll('input[name=units]')) {
  radio.addEventListener('change', () => {
    page.system = radio.value;
    controls.refresh();
    if (!page.trajectory) return;
    const units = page.units(page.trajectory.scene);
    steadyPanel.setUnits(units);
    plots.setUnits(units);
    showKeys(units);
    view.dirty = true;
  });
}
$('time').addEventListener('input', () => { page.t = Number($('time').value); page.holdUntil = 0; view.dirty = true; });
$('speed').addEventListener('change', () => { page.speed = Number($('speed').value); });
$('reset-view').addEventListener('click', () => { view.userCamera = false; view.dirty = true; });
$('run-text').addEventListener('click', () => start($('scene-text').value, 'scene.json', { box: true }));
for (const name of Object.keys(examples)) $('example').append(new Option(`examples/${name}.json`, name));
$('example').prepend(new Option('load an example…', ''));
$('example').value = '';
$('example').addEventListener('change', () => {
  const name = $('example').value;
  if (!name) return;
  showSceneText(examples[name]);
  start(examples[name], `examples/${name}.json`, { box: true });
});
$('file').addEventListener('change', async () => {
  const file = $('file').files[0];
  if (!file) return;
  const text = await file.text();
  showSceneText(text);
  start(text, file.name, { box: true });
});
$('download').addEventListener('click', () => {
  if (!page.run) return;
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([page.run.text], { type: 'application/json' }));
  link.download = `${page.trajectory.scene.name || 'coinroll'}.json`;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 0);
});

let defaultSceneText = '';
runner.ready.then(({ version, defaultScene, picture }) => {
  $('version').textContent = version;
  view.setPicture(picture);
  legend = new Legend($('legend'), picture);
  defaultSceneText = defaultScene;
  // A page written by `coinroll export` opens on its scene, as the scene file's JSON.
  const sceneText = exportedScene === null ? defaultScene : JSON.stringify(exportedScene, null, 2);
  page.scene = JSON.parse(sceneText);
  showSceneText(sceneText);
  controls.refresh();
  start(sceneText, exportedSourceName, { box: true });
}, (e) => { $('scene-error').textContent = e.message; });
requestAnimationFrame(frame);

// For tests and benchmarks (tests/web/page_test.mjs, bench/page_bench.mjs): what the page shows,
// read through the page itself.
window.coinrollPage = {
  settled: () => (pending ? new Promise((resolve) => waiters.push(resolve)) : Promise.resolve()),
  stateAt: (t) => page.trajectory.stateAt(t),
  // Stops playback at simulated time t and draws it; returns the overlay's text.
  seek(t) {
    setPlaying(false);
    page.t = t;
    page.holdUntil = 0;
    draw();
    return $('hud').textContent;
  },
  run: () => page.run && Object.assign({ rows: page.trajectory.rows, end: page.trajectory.end, names: page.trajectory.names }, page.run),
  camera: () => ({ eye: view.camera.position.toArray(), target: view.controls.target.toArray(), fov: view.camera.fov,
                   width: view.width, height: view.height, up: view.camera.up.toArray() }),
  setViewSize(width, height) {
    fixedSize = [width, height];
    Object.assign($('view').style, { width: `${width}px`, height: `${height}px` });
    $('view').classList.add('fixed-size');
    resize();
  },
  showTestMarks: (on) => view.showTestMarks(on),
  timing: () => Object.assign({}, timing, { last: timing.last && Object.assign({}, timing.last) }),
  playing: () => page.playing,
  defaultScene: () => defaultSceneText,
  // Milliseconds per frame drawn `frames` times in a row, each waited for (a pixel read back: in
  // Chromium gl.finish does not wait for the GPU process): as played with the camera still, with the
  // sky and floor drawn anew each frame (a moving camera), and without each other part in turn.
  profile(frames) {
    const context = view.renderer.getContext(), pixel = new Uint8Array(4);
    const perFrame = (moving) => {
      draw();
      context.readPixels(0, 0, 1, 1, context.RGBA, context.UNSIGNED_BYTE, pixel);
      const start = performance.now();
      for (let i = 0; i < frames; ++i) {
        page.t = (page.t + 0.01) % page.trajectory.endTime;
        if (moving) view.backgroundSeen = undefined;
        draw();
        context.readPixels(0, 0, 1, 1, context.RGBA, context.UNSIGNED_BYTE, pixel);
      }
      return (performance.now() - start) / frames;
    };
    const result = { 'camera still': perFrame(false), 'camera moving': perFrame(true) };
    const parts = { coin: [view.coin], shadow: [view.shadow], trace: [view.trace, view.traceTail, view.marker] };
    for (const [name, objects] of Object.entries(parts)) {
      const shown = objects.map((o) => o.visible);
      objects.forEach((o) => { o.visible = false; });
      result[`still, without ${name}`] = perFrame(false);
      objects.forEach((o, k) => { o.visible = shown[k]; });
    }
    const start = performance.now();
    for (let i = 0; i < frames; ++i) page.trajectory.stateAt((i * 0.01) % page.trajectory.endTime);
    result['stateAt alone'] = (performance.now() - start) / frames;
    return result;
  },
  // Each plot's numbers at its cursor (plots.js atCursor).
  plots: () => plots.atCursor(),
  playbackRate: (t) => page.trajectory.playbackRate(t),
  time: () => page.t,
};
