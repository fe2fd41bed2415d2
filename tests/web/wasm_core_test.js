#!/usr/bin/env node
// The WebAssembly core (build_wasm.sh's coinroll_core.js) against the program it was built from,
// run as users run it (docs/web.md "Equality with the program"):
//
//   node tests/web/wasm_core_test.js --module M.js --binary build/coinroll examples [--markdown FILE]
//       every example scene and the built-in default scene: the CSV of `coinroll simulate SCENE
//       --csv -` (the header, the rows, the time column and the sliding flag byte for byte, every
//       other column to the tolerance below), its end and its stderr report;
//   node tests/web/wasm_core_test.js --module M.js --binary build/coinroll bad-scenes CASES.json
//       every scene refusal of tests/cli/bad_inputs.py (its --export-scene-cases file): the
//       module's CoinrollError carries the program's message, byte for byte;
//   node tests/web/wasm_core_test.js --module M.js --binary build/coinroll visual
//       the visual track (core.visualRun) of a few scenes against `coinroll render SCENE --plan
//       --json`: the clip's clock at every frame, and the camera and overlay at every frame that
//       lies on a row of the track;
//   node tests/web/wasm_core_test.js --module M.js api
//       the JavaScript surface itself: default scene, options, progress and cancelling.
//
// Prints one line per case and "N passed, M failed"; exits 1 on any failure.

'use strict';

const childProcess = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const kRepo = path.resolve(__dirname, '..', '..');

// docs/web.md "Tolerance": a column's largest difference from the program, over the largest
// magnitude the program's column reaches (many columns cross zero, where a pointwise relative
// difference means nothing), plus an absolute 1e-12 in the column's SI unit for columns that are 0
// up to round-off. 1e-6 is below every example's own integration error (what a 100 times tighter
// rtol changes: up to 2e-6 of a column, in falling_flat). skid_and_spin's 117 stick-slip switches
// amplify any last-bit change as they would a change of its input; at its tolerances (rtol 1e-11,
// atol 1e-14) its CSV moves by up to 8.1e-8 of a column under one-ulp changes of initial.theta, v_x,
// omega_Y or omega_Z (8 runs). At the default tolerances one such input in 17 missed a slip's stop
// and moved it by 3e-3, which no tolerance here could tell from a wrong module.
const kTolerance = 1e-6;
const kAbsoluteFloor = 1e-12;
// The stderr report's step counts measure the adaptive step control's work, which follows the
// trajectory: the steps and the evaluations to this part of themselves, the rejected steps to this
// part of the steps (the work they waste is measured against the work done; a count of a few hundred
// rejections out of thousands of steps moves by tens with the last bit of the input). coin_toss, the
// most sensitive: under 16 one-ulp changes of initial.omega_X, v_y, theta or omega_Z the program's
// own counts span 8288-8313 steps (0.3 %), 199-239 rejected (0.5 % of the steps, 19 % of
// themselves) and 126924-127491 evaluations (0.45 %), while every column stays within 1e-6.
const kWorkCountTolerance = 0.01;
// Columns no library function computes: byte for byte.
const kExactColumns = ['t', 'sliding'];

function parseArguments(argv) {
  const options = { markdown: null };
  const rest = [];
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--module') options.module = path.resolve(argv[++i]);
    else if (argv[i] === '--binary') options.binary = path.resolve(argv[++i]);
    else if (argv[i] === '--markdown') options.markdown = path.resolve(argv[++i]);
    else rest.push(argv[i]);
  }
  [options.mode, options.cases] = rest;
  if (!options.module || !['examples', 'bad-scenes', 'visual', 'api'].includes(options.mode) ||
      (options.mode !== 'api' && !options.binary) || (options.mode === 'bad-scenes' && !options.cases)) {
    console.error('usage: wasm_core_test.js --module M.js [--binary coinroll] examples [--markdown FILE] | ' +
                  'bad-scenes CASES.json | visual | api');
    process.exit(2);
  }
  return options;
}

class Checks {
  constructor() {
    this.passed = 0;
    this.failed = 0;
  }
  // One case: `problems` empty passes it.
  record(name, problems, detail = '') {
    if (problems.length === 0) {
      ++this.passed;
      console.log(`ok   ${name}${detail ? ': ' + detail : ''}`);
    } else {
      ++this.failed;
      console.log(`FAIL ${name}: ${problems.join('; ')}`);
    }
  }
  finish() {
    console.log(`${this.passed} passed, ${this.failed} failed`);
    process.exit(this.failed === 0 ? 0 : 1);
  }
}

function runProgram(binary, args, cwd) {
  const r = childProcess.spawnSync(binary, args, { cwd, maxBuffer: 1 << 30 });
  if (r.error) throw r.error;
  return { status: r.status, stdout: r.stdout.toString('utf8'), stderr: r.stderr.toString('utf8') };
}

function errorMessageOf(stderr) {
  const prefix = 'coinroll: error: ';
  return stderr.startsWith(prefix) && stderr.endsWith('\n') && stderr.indexOf('\n') === stderr.length - 1
    ? stderr.slice(prefix.length, -1) : null;
}

// What the module throws for a call, or null when it returns.
function thrownBy(call) {
  try {
    call();
  } catch (e) {
    return e;
  }
  return null;
}

// ---------------------------------------------------------------------------------------------
// examples

// The numbers in a report line, and the line with each replaced by '#'.
function numbersOf(line) {
  const numbers = [];
  const masked = line.replace(/-?\d+(\.\d+)?(e[-+]?\d+)?/g, (text, fraction) => {
    numbers.push({ text, value: Number(text), decimals: fraction ? fraction.length - 1 : 0 });
    return '#';
  });
  return { masked, numbers };
}

// The module's report against the program's stderr: the same lines in the same words; printed
// times and fits to the tolerance (plus one unit of the last printed digit, where two roundings
// may part); counts exact, but the work counts of the last line to kWorkCountTolerance (of the
// steps, for the rejected steps).
function compareReports(program, wasm, tolerance) {
  const problems = [];
  if (program.length !== wasm.length) {
    return [`stderr has ${program.length} lines, the module's report ${wasm.length}: ${JSON.stringify(wasm)}`];
  }
  program.forEach((line, i) => {
    const p = numbersOf(line);
    const w = numbersOf(wasm[i]);
    if (p.masked !== w.masked || p.numbers.length !== w.numbers.length) {
      problems.push(`report line ${i + 1}: "${wasm[i]}" where the program says "${line}"`);
      return;
    }
    const workCounts = /^coinroll: # rows, # steps/.test(p.masked);
    p.numbers.forEach((a, k) => {
      const b = w.numbers[k];
      let allowed;
      if (workCounts && k === 2)
        allowed = kWorkCountTolerance * Math.abs(p.numbers[1].value);  // rejected, of the steps
      else if (workCounts && k > 0)
        allowed = kWorkCountTolerance * Math.abs(a.value);
      else if (a.decimals === 0 && !/e/.test(a.text)) allowed = 0;
      else allowed = tolerance * Math.max(1, Math.abs(a.value)) + 10 ** -a.decimals;
      if (!(Math.abs(a.value - b.value) <= allowed)) {
        problems.push(`report line ${i + 1}: ${b.text} where the program prints ${a.text} (allowed ${allowed.toExponential(1)})`);
      }
    });
  });
  return problems;
}

// The module's structured events, as the report prints them.
function eventLines(result) {
  return result.events.map((e) => {
    if (e.kind === 'switch') return `coinroll: ${e.name} at t = ${e.time.toFixed(9)} s`;
    if (e.kind === 'warning') return `coinroll: warning: the ideal contact fails here (on_invalid: warn, going on): ${e.description}`;
    return `coinroll: stopped early: ${e.description}`;
  });
}

function compareExample(core, binary, scene, checks, table) {
  const label = scene || 'built-in default scene';
  const program = runProgram(binary, ['simulate', ...(scene ? [scene] : []), '--csv', '-'], kRepo);
  const bytes = scene ? new Uint8Array(fs.readFileSync(path.join(kRepo, scene))) : null;
  const options = { sourceName: scene || '' };
  if (program.status !== 0) {
    // A scene the program refuses: the module must refuse it alike.
    const e = thrownBy(() => core.simulateCsv(bytes, [], options));
    const message = errorMessageOf(program.stderr);
    checks.record(label, e && e.message === message && e.exitCode === program.status ? []
      : [`the program refuses it (exit ${program.status}: ${program.stderr.trim()}); the module ${e ? `says "${e.message}"` : 'runs it'}`]);
    return;
  }
  const wasm = core.simulateCsv(bytes, [], options);
  const structured = core.simulate(bytes, [], options);
  const tolerance = kTolerance;
  const problems = [];

  const programLines = program.stdout.split('\n');
  const wasmLines = wasm.csv.split('\n');
  if (programLines[0] !== wasmLines[0]) problems.push(`header "${wasmLines[0]}" where the program writes "${programLines[0]}"`);
  if (programLines.length !== wasmLines.length || wasm.rows !== programLines.length - 2) {
    problems.push(`${wasm.rows} rows (${wasmLines.length - 2} lines) where the program writes ${programLines.length - 2}`);
  }
  const names = programLines[0].split(',');
  const rows = Math.min(programLines.length, wasmLines.length) - 2;
  const columns = names.map((name) => ({ name, maxAbs: 0, scale: 0, exactMismatch: null }));
  for (let r = 1; r <= rows; ++r) {
    const p = programLines[r].split(',');
    const w = wasmLines[r].split(',');
    columns.forEach((c, i) => {
      if (kExactColumns.includes(c.name)) {
        if (p[i] !== w[i] && c.exactMismatch === null) c.exactMismatch = `row ${r}: ${w[i]} where the program writes ${p[i]}`;
        return;
      }
      c.maxAbs = Math.max(c.maxAbs, Math.abs(Number(p[i]) - Number(w[i])));
      c.scale = Math.max(c.scale, Math.abs(Number(p[i])));
    });
  }
  for (const c of columns) {
    if (c.exactMismatch) problems.push(`${c.name} differs at ${c.exactMismatch}`);
    if (!(c.maxAbs <= tolerance * c.scale + kAbsoluteFloor)) {
      problems.push(`${c.name} differs by ${c.maxAbs.toExponential(2)}, more than ${tolerance} of its largest magnitude ` +
                    `${c.scale.toExponential(2)}`);
    }
  }

  // The structured form: the very doubles the CSV prints, under the CSV's names.
  if (structured.names.join(',') !== programLines[0]) problems.push(`simulate() names ${structured.names.join(',')}`);
  structured.names.forEach((name, i) => {
    const column = structured.columns[name];
    if (!(column instanceof Float64Array) || column.length !== wasm.rows) {
      problems.push(`simulate() column ${name} is no Float64Array of ${wasm.rows}`);
      return;
    }
    const k = column.findIndex((v, r) => !Object.is(v, Number(wasmLines[r + 1].split(',')[i])));
    if (k >= 0) problems.push(`simulate() column ${name} row ${k + 1} is ${column[k]}, the CSV says ${wasmLines[k + 1].split(',')[i]}`);
  });

  const report = program.stderr.trimEnd().split('\n');
  problems.push(...compareReports(report, wasm.report, tolerance));
  // The events as data say what the report says.
  const printedEvents = report.filter((l) => /^coinroll: (slides|rolls) at|^coinroll: warning: the ideal|^coinroll: stopped early/.test(l));
  problems.push(...compareReports(printedEvents, eventLines(structured), tolerance).map((p) => 'events: ' + p));
  const stop = report.find((l) => l.startsWith('coinroll: stopped early: '));
  const endEvent = stop ? stop.split(' ')[3] : 'duration';
  if (structured.end.event !== endEvent) problems.push(`ends by ${structured.end.event} where the program ends by ${endEvent}`);

  const worst = columns.filter((c) => !kExactColumns.includes(c.name) && tolerance * c.scale > kAbsoluteFloor)
    .reduce((a, c) => Math.max(a, c.maxAbs / c.scale), 0);
  checks.record(label, problems, `${wasm.rows} rows, ends by ${structured.end.event}; largest difference ${worst.toExponential(1)} ` +
                `of a column's magnitude (tolerance ${tolerance.toExponential(0)})`);
  table.push({ label, rows: wasm.rows, tolerance, columns });
}

// docs/web.md's table: each column's largest difference per scene, absolute and (in brackets)
// over the column's largest magnitude.
function markdownTable(table) {
  const short = (x) => x.toExponential(x === 0 ? 0 : 1);
  const scenes = table.map(({ label }) => label.replace('examples/', '').replace('.json', '').replace('built-in default scene', 'default'));
  const lines = [`| column | ${scenes.join(' | ')} |`, `|---|${scenes.map(() => '---|').join('')}`,
                 `| rows | ${table.map((t) => t.rows).join(' | ')} |`,
                 `| tolerance | ${table.map((t) => t.tolerance.toExponential(0)).join(' | ')} |`];
  const names = [...new Set(table.flatMap((t) => t.columns.map((c) => c.name)))];
  for (const name of names) {
    const cells = table.map(({ columns }) => {
      const c = columns.find((column) => column.name === name);
      if (!c) return '';
      if (kExactColumns.includes(name)) return 'identical';
      return c.maxAbs === 0 ? '0' : `${short(c.maxAbs)} (${short(c.maxAbs / c.scale)})`;
    });
    lines.push(`| ${name} | ${cells.join(' | ')} |`);
  }
  return lines.join('\n') + '\n';
}

function examples(core, options, checks) {
  const scenes = [null, ...fs.readdirSync(path.join(kRepo, 'examples')).filter((n) => n.endsWith('.json')).sort()
    .map((n) => `examples/${n}`)];
  const table = [];
  for (const scene of scenes) compareExample(core, options.binary, scene, checks, table);
  if (options.markdown) fs.writeFileSync(options.markdown, markdownTable(table));
}

// ---------------------------------------------------------------------------------------------
// bad scenes

function badScenes(core, options, checks) {
  const cases = JSON.parse(fs.readFileSync(options.cases, 'utf8'));
  // Not in the table, which names every file scene.json: the file's name in the message, with a
  // control character in it that the program shows escaped.
  cases.push({ id: 'control-character-in-file-name', file: 'sc\x1bene.json', scene_hex: Buffer.from('{').toString('hex'),
               overrides: [], message: 'sc\\x1bene.json: invalid JSON at line 1, column 2', or_message: '' });
  // Named by the process, as tests/support/scratch_dir.h names its directories: two builds' suites
  // may run at once.
  const directory = fs.mkdtempSync(path.join(os.tmpdir(), `coinroll_wasm_bad_scenes_${process.pid}_`));
  try {
    for (const c of cases) {
      const bytes = Buffer.from(c.scene_hex, 'hex');
      const file = c.file || 'scene.json';
      fs.writeFileSync(path.join(directory, file), bytes);
      const program = runProgram(options.binary,
                                 ['simulate', file, '--csv', 'o.csv', ...c.overrides.flatMap((o) => ['--set', o])], directory);
      const message = errorMessageOf(program.stderr);
      const problems = [];
      if (program.status !== 2 || message === null) {
        problems.push(`the program answers exit ${program.status}: ${JSON.stringify(program.stderr)}, not one error line and exit 2`);
      } else if (!message.includes(c.message) && !(c.or_message && message.includes(c.or_message))) {
        // The table's own test names the program's fault; here it would leave nothing to compare.
        problems.push(`the program's message "${message}" is not the table's "${c.message}"`);
      }
      fs.rmSync(path.join(directory, file));
      const e = thrownBy(() => core.simulateCsv(new Uint8Array(bytes), c.overrides, { sourceName: file }));
      if (!e) problems.push('the module runs it');
      else if (!(e instanceof core.CoinrollError)) problems.push(`the module throws ${e}`);
      else if (e.message !== message) problems.push(`the module says ${JSON.stringify(e.message)}, the program ${JSON.stringify(message)}`);
      else if (e.exitCode !== program.status || e.kind !== 'scene') problems.push(`kind ${e.kind}, exit code ${e.exitCode}`);
      checks.record(c.id, problems);
    }
  } finally {
    fs.rmSync(directory, { recursive: true, force: true });
  }
}

// ---------------------------------------------------------------------------------------------
// visual

// The scenes whose visual track is held against the program's plan: the default (fixed camera, no
// remap), a toss (follow camera, flight and impact slow-downs, landing's hold), the Euler's disk's
// first 20 s (the rate remap) and a skid to rolling (sliding). Under the Euler's disk's remap no
// frame but the first falls on a row, so it runs again with the remap's limit out of reach: its
// 20 s of overlay and camera are then compared at every frame.
const kVisualScenes = [
  { scene: null, overrides: [] },
  { scene: 'examples/coin_toss.json', overrides: [] },
  { scene: 'examples/euler_disk.json', overrides: ['duration=20'] },
  { scene: 'examples/euler_disk.json', overrides: ['duration=20', 'render.time_remap.precession_rate=1e6'] },
  { scene: 'examples/skid_and_spin.json', overrides: [] },
];
// The clock is the same code on the same doubles on both sides, but a frame time under a time remap
// is a sum of steps from libm's pow and the integrator's dense output, so it may part by round-off
// that the sum carries along: to this part of itself, or absolutely for a value that is 0.
const kClockTolerance = 1e-9;
const kClockFloor = 1e-12;
// The camera is single precision (render::CameraView): a few of float's ulps of a position of order
// 0.1-1 m, and of a field of view in degrees.
const kCameraTolerance = 1e-5;
// s: a frame "lies on" a row when their times agree to this (a frame time k time_scale / fps or a
// sum of steps, a row time k sampleDt: the same instant computed two ways).
const kOnRow = 1e-9;

// The overlay's first line, the time to the millisecond. A frame time summed step by step may lie
// a few ulps from its row's k sampleDt, and at a half millisecond the two then round apart (in
// coin_toss 5 of the 89 frames on rows: 0.11249999999999999 s prints 0.112, the row's 0.1125 s
// 0.113): the same instant computed two ways, not drift. Such a line passes when each side prints
// its own time and the two are a millisecond apart.
const kTimeLine = /^t +(\d+\.\d{3}) s$/;
function timeLinesRoundApart(programLine, trackLine, frameTime, rowTime) {
  const p = kTimeLine.exec(programLine);
  const w = kTimeLine.exec(trackLine || '');
  const half = 5e-4 * (1 + 1e-9);
  return frameTime !== rowTime && p !== null && w !== null && Math.abs(Number(p[1]) - frameTime) <= half &&
    Math.abs(Number(w[1]) - rowTime) <= half && Math.abs(Math.abs(Number(p[1]) - Number(w[1])) - 1e-3) < 1e-9;
}

const withinClock = (a, b) => Math.abs(a - b) <= Math.max(kClockTolerance * Math.abs(b), kClockFloor);

// The lines render's overlay adds after the track's own (pipeline::overlayExtraLines): the speed
// the frame plays at, or the landing's hold. How many there are follows the playback rate alone.
function extraOverlayLines(rate) {
  if (rate === 0) return { count: 1, prefix: 'landed, held ' };
  const slowdown = 1 / rate;
  if (slowdown > 1 + 1e-9) return { count: 1, prefix: 'slow motion ×' };
  if (slowdown < 1 - 1e-9) return { count: 1, prefix: 'fast forward ×' };
  return { count: 0, prefix: '' };
}

function compareVisual(core, binary, { scene, overrides }, checks) {
  const label = `${scene || 'built-in default scene'}${overrides.length ? ' ' + overrides.join(' ') : ''}`;
  const program = runProgram(binary, ['render', ...(scene ? [scene] : []), '--plan', '--json', '-q',
                                      ...overrides.flatMap((o) => ['--set', o])], kRepo);
  if (program.status !== 0) {
    checks.record(label, [`render --plan --json exits ${program.status}: ${program.stderr.trim()}`]);
    return;
  }
  const plan = JSON.parse(program.stdout);
  const sceneText = scene ? fs.readFileSync(path.join(kRepo, scene), 'utf8') : null;
  const result = core.visualRun(sceneText, overrides, {});
  const { clock } = result.visual;
  const problems = [];

  // (a) The clock: the frames before the landing's hold, then every frame's time and rate.
  const holdFrames = plan.landed ? Math.round(plan.hold_seconds * plan.fps) : 0;
  const planSimulated = plan.frames.length - holdFrames;
  if (planSimulated !== plan.simulated_frames) {
    problems.push(`the plan's ${plan.frames.length} frames less ${holdFrames} held are not its simulated_frames ` +
                  `${plan.simulated_frames}`);
  }
  if (clock.simulatedFrames !== planSimulated) {
    problems.push(`${clock.simulatedFrames} simulated frames where the program plans ${planSimulated}`);
  }
  if (clock.times.length !== plan.frames.length || clock.playbackRates.length !== plan.frames.length) {
    problems.push(`${clock.times.length} frames in all where the program plans ${plan.frames.length}`);
  }
  if (clock.fps !== plan.fps) problems.push(`fps ${clock.fps} where the program plans ${plan.fps}`);
  const frames = Math.min(clock.times.length, plan.frames.length);
  let maxTime = 0;
  let maxRate = 0;
  const relative = (a, b) => (a === b ? 0 : Math.abs(a - b) / Math.max(Math.abs(b), kClockFloor));
  for (let k = 0; k < frames; ++k) {
    const p = plan.frames[k];
    const t = clock.times[k];
    const rate = clock.playbackRates[k];
    maxTime = Math.max(maxTime, relative(t, p.sim_time_s));
    maxRate = Math.max(maxRate, relative(rate, p.playback_rate));
    if (!withinClock(t, p.sim_time_s)) problems.push(`frame ${k}: time ${t} where the program plans ${p.sim_time_s}`);
    if (!withinClock(rate, p.playback_rate)) {
      problems.push(`frame ${k}: playback rate ${rate} where the program plans ${p.playback_rate}`);
    }
    if (problems.length > 20) break;
  }

  // (b) At each frame before the hold whose time lies on a row of the track: the camera, and the SI
  // overlay without the lines render adds after it.
  const rowTimes = result.columns.t;
  const { cameras, overlay } = result.visual;
  const rows = overlay.si.length;
  if (cameras.fov.length !== rows || rowTimes.length !== rows) {
    problems.push(`the track has ${cameras.fov.length} cameras and ${rowTimes.length} rows for ${rows} overlays`);
  }
  let onRows = 0;
  let maxCamera = 0;
  let overlayMismatches = 0;
  let firstOverlayMismatch = null;
  let cameraMismatches = 0;
  let firstCameraMismatch = null;
  let timesRoundedApart = 0;
  for (let k = 0; k < Math.min(frames, planSimulated); ++k) {
    const p = plan.frames[k];
    const r = Math.round(p.sim_time_s / result.sampleDt);
    if (r >= rows || Math.abs(rowTimes[r] - p.sim_time_s) > kOnRow) continue;
    if (Math.abs(rowTimes[r] - r * result.sampleDt) > kOnRow) {
      problems.push(`row ${r} lies at ${rowTimes[r]} s, not ${r} sampleDt = ${r * result.sampleDt} s`);
      break;
    }
    ++onRows;
    const camera = p.camera;
    const differences = [
      ...['eye', 'target', 'up'].flatMap((name) => camera[name].map((v, i) => Math.abs(cameras[name][3 * r + i] - v))),
      Math.abs(cameras.fov[r] - camera.fov_y_degrees)];
    const worst = Math.max(...differences);
    maxCamera = Math.max(maxCamera, worst);
    if (!(worst <= kCameraTolerance)) {
      ++cameraMismatches;
      if (!firstCameraMismatch) {
        const at = (name) => cameras[name].slice(3 * r, 3 * r + 3).join(', ');
        firstCameraMismatch = `frame ${k} (row ${r}, t = ${p.sim_time_s} s) by ${worst.toExponential(2)}: eye ` +
          `${at('eye')}, target ${at('target')}, up ${at('up')}, fov ${cameras.fov[r]} where the program draws ` +
          JSON.stringify(camera);
      }
    }
    const extra = extraOverlayLines(p.playback_rate);
    const lines = p.overlay_lines;
    const own = lines.slice(0, lines.length - extra.count);
    if (extra.count && !(lines[lines.length - 1] || '').startsWith(extra.prefix)) {
      problems.push(`frame ${k}: the overlay's last line "${lines[lines.length - 1]}" is not ` +
                    `"${extra.prefix}..." at rate ${p.playback_rate}`);
    }
    const track = overlay.si[r].split('\n');
    if (own.length === track.length && own[0] !== track[0] &&
        timeLinesRoundApart(own[0], track[0], p.sim_time_s, rowTimes[r]) &&
        own.slice(1).join('\n') === track.slice(1).join('\n')) {
      ++timesRoundedApart;
    } else if (own.join('\n') !== overlay.si[r]) {
      ++overlayMismatches;
      if (!firstOverlayMismatch) {
        const i = own.findIndex((line, j) => line !== track[j]);
        const at = i < 0 ? own.length : i;
        firstOverlayMismatch = `frame ${k} (row ${r}, t = ${p.sim_time_s} s) overlay line ${at + 1}: ` +
          `"${track[at]}" where the program draws "${own[at]}"`;
      }
    }
  }
  if (firstCameraMismatch) problems.push(`${cameraMismatches} cameras differ, the first at ${firstCameraMismatch}`);
  if (firstOverlayMismatch) problems.push(`${overlayMismatches} overlays differ, the first at ${firstOverlayMismatch}`);
  if (onRows === 0) problems.push('no frame lies on a row of the track: nothing of the camera or overlay compared');
  checks.record(label, problems,
                `${plan.frames.length} frames (${planSimulated} before the hold), sampleDt ${result.sampleDt}; ` +
                `clock: max relative difference ${maxTime.toExponential(1)} in time, ${maxRate.toExponential(1)} in ` +
                `playback rate; ${onRows} frames on rows: camera max difference ${maxCamera.toExponential(1)}, ` +
                `${onRows - overlayMismatches - timesRoundedApart} of ${onRows} overlays identical` +
                (timesRoundedApart ? `, ${timesRoundedApart} but for the time rounded apart (frame and row ` +
                                     'times a few ulps apart at a half millisecond)' : ''));
}

function visual(core, options, checks) {
  for (const scene of kVisualScenes) compareVisual(core, options.binary, scene, checks);
}

// ---------------------------------------------------------------------------------------------
// api

function api(core, checks) {
  const expectThrow = (name, call, test) => {
    const e = thrownBy(call);
    checks.record(name, e && test(e) ? [] : [e ? `threw ${e.name}: ${e.message}` : 'did not throw']);
  };

  const document = JSON.parse(core.defaultSceneJson());
  const fromText = core.simulateCsv(core.defaultSceneJson(), ['duration=1']);
  const fromNull = core.simulateCsv(null, ['duration=1']);
  const fromObject = core.simulateCsv(document, ['duration=1']);
  checks.record('the default scene as JSON text, as an object and as null give one CSV',
                fromText.csv === fromNull.csv && fromObject.csv === fromNull.csv && fromNull.rows === 101 ? [] : ['they differ']);
  checks.record('defaultSceneJson() is the built-in scene', document.name === 'coinroll' && document.duration > 0 ? [] : [
    `got ${core.defaultSceneJson()}`]);

  const fine = core.simulateCsv(null, ['duration=1'], { sampleDt: 0.001 });
  checks.record('sampleDt sets the rows', fine.rows === 1001 && fine.csv.split('\n')[2].startsWith('0.001,') ? [] : [
    `${fine.rows} rows`]);

  const calls = [];
  const watched = core.simulateCsv(null, ['duration=2'], { onProgress: (done, expected) => { calls.push([done, expected]); } });
  const increasing = calls.every((c, i) => i === 0 || c[0] > calls[i - 1][0]);
  const last = calls[calls.length - 1];
  checks.record('onProgress counts the rows up to the last', calls.length >= 10 && increasing && last[0] === watched.rows &&
                last[1] === watched.rows ? [] : [`calls ${JSON.stringify(calls.slice(-3))} of ${calls.length}`]);

  let stoppedAt = 0;
  expectThrow('onProgress returning false cancels the run', () => core.simulateCsv(null, [], {
    onProgress: (done) => { stoppedAt = done; return done < 100; },
  }), (e) => e instanceof core.CoinrollError && e.kind === 'cancelled' && stoppedAt >= 100 && stoppedAt < 601);

  const mine = new Error('from the callback');
  expectThrow('an exception in onProgress stops the run and comes out of it', () => core.simulateCsv(null, [], {
    onProgress: () => { throw mine; },
  }), (e) => e === mine);
  checks.record('the module runs on after a callback threw', core.simulateCsv(null, ['duration=1']).rows === 101 ? [] : ['it does not']);

  expectThrow('a bad sampleDt is the program\'s refusal', () => core.simulateCsv(null, [], { sampleDt: 0 }),
              (e) => e.kind === 'request' && e.exitCode === 2 && e.message === 'sampleDt: must be a finite number > 0 s, got 0');
  expectThrow('a run past maxRows is refused before it starts', () => core.simulateCsv(null, [], { maxRows: 100 }),
              (e) => e.kind === 'request' && /gives 601 rows, more than the limit 100/.test(e.message));
  // The command's rule, not a copy of it: rows are whole, as the run writes them.
  checks.record('one row at sampleDt 1 on a 0.5 s run fits maxRows 1',
                core.simulateCsv(null, ['duration=0.5'], { sampleDt: 1, maxRows: 1 }).rows === 1 ? [] : ['refused']);
  expectThrow('sampleDt 0.3 on a 0.5 s run is 2 whole rows, past maxRows 1',
              () => core.simulateCsv(null, ['duration=0.5'], { sampleDt: 0.3, maxRows: 1 }),
              (e) => e.kind === 'request' && e.message === 'sampleDt 0.3: duration 0.5 s gives 2 rows, more than the '
                     + 'limit 1; raise sampleDt, or the limit with maxRows');
  expectThrow('an unknown option is named', () => core.simulateCsv(null, [], { sampleDT: 0.1 }),
              (e) => e instanceof TypeError && /unknown sampleDT/.test(e.message));
  expectThrow('overrides must be strings', () => core.simulateCsv(null, ['duration=1', 3]),
              (e) => e instanceof TypeError && /overrides/.test(e.message));
  expectThrow('a bad --set is the program\'s message', () => core.simulateCsv(null, ['initial.thta=3']),
              (e) => e.kind === 'scene' && e.message.startsWith('built-in default scene: initial.thta: unknown key'));
  expectThrow('sourceName names the scene in messages', () => core.simulateCsv('{', [], { sourceName: 'my.json' }),
              (e) => e.kind === 'scene' && e.message.startsWith('my.json: invalid JSON at line 1, column 2'));

  // steady(): `coinroll steady` as a call (the page's panel checks its numbers against the program's).
  const circle = core.steady(null, [], { kind: 'circle', theta: 20, omega_Z: 10 });
  checks.record('steady() solves the circle asked for, with its stability and eigenvalues', circle.initial.theta === 20 &&
                circle.initial.omega_Z === 10 && circle.initial.omega_X === 0 && ['stable', 'unstable'].includes(circle.stability.verdict) &&
                circle.eigenvalues.length === 2 && circle.eigenvalues[0].re === -circle.eigenvalues[1].re &&
                circle.eigenvalues[0].im === -circle.eigenvalues[1].im &&
                Math.hypot(circle.eigenvalues[0].re, circle.eigenvalues[0].im) === circle.stability.rate ? [] : [JSON.stringify(circle)]);
  // seed §5: the thin disk's critical spin is 1/sqrt(3) in units of sqrt(g/a).
  checks.record('steady() gives the thin disk\'s omega_c = 1/sqrt(3) sqrt(g/a)',
                Math.abs(circle.criticalSpinInNaturalUnits - 1 / Math.sqrt(3)) < 1e-15 && circle.rim === null ? [] : [
                  `${circle.criticalSpinInNaturalUnits}`]);
  const straight = core.steady(null, [], { kind: 'straight', omega_Z: 1 });
  checks.record('slow straight rolling is unstable, its eigenvalues real, its radii infinite', straight.stability.verdict === 'unstable' &&
                straight.eigenvalues[0].im === 0 && straight.radii.contact === Infinity ? [] : [JSON.stringify(straight)]);
  expectThrow('steady() refuses what the scene refuses, with the program\'s message',
              () => core.steady(null, [], { kind: 'straight', theta: 10, omega_Z: 5 }),
              (e) => e.kind === 'scene' && e.exitCode === 2 && /theta: only with steady: "circle" or "spin-in-place"/.test(e.message));
  expectThrow('steady() without kind needs a scene that names a steady state', () => core.steady(null, []),
              (e) => e.kind === 'request' && e.exitCode === 2 && /give kind straight\|circle\|spin-in-place/.test(e.message));
  expectThrow('steady()\'s theta without kind is refused', () => core.steady(null, [], { theta: 10 }),
              (e) => e.kind === 'request' && /give kind too/.test(e.message));
  expectThrow('steady()\'s theta must be finite', () => core.steady(null, [], { kind: 'spin-in-place', theta: NaN }),
              (e) => e.kind === 'request' && e.message === 'theta: must be a finite number, got nan');
  expectThrow('steady()\'s kind is one of the three', () => core.steady(null, [], { kind: 'wobble' }),
              (e) => e instanceof TypeError && /options.kind/.test(e.message));
  checks.record('version() is the project\'s', /^\d+\.\d+\.\d+$/.test(core.version()) ? [] : [`got ${core.version()}`]);
}

async function main() {
  const options = parseArguments(process.argv.slice(2));
  const core = await require(options.module)();
  const checks = new Checks();
  if (options.mode === 'examples') examples(core, options, checks);
  else if (options.mode === 'bad-scenes') badScenes(core, options, checks);
  else if (options.mode === 'visual') visual(core, options, checks);
  else api(core, checks);
  checks.finish();
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
