#!/usr/bin/env node
// The page (docs/web.md "The page") in a real browser: Debian's Chromium, driven by puppeteer-core
// (web/package-lock.json), opens the built page from file:// and is checked against the program:
//     node tests/web/page_test.mjs --page build/web/coinroll.html --binary build/coinroll
//
// - no console error and no request beyond the page's own file, its Blob worker and data URIs;
// - the numbers the page holds and its overlay shows at given times are `coinroll simulate`'s CSV for
//   the same scene and sample step;
// - a slider moved by the page's own keyboard events runs the changed scene, which "download scene"
//   writes, and which `coinroll simulate` reproduces;
// - the coin's centre and contact point in a screenshot are where a pinhole camera puts the CSV's,
//   and the coin where `coinroll still` draws it, within 2 px;
// - a bad scene in the box, or a bad value in a control, shows the program's message beside it;
// - a run in progress shows its progress and gives way to a newer one; playback follows
//   render.time_remap as `coinroll render --frame-times` reports it, in the air and at each impact too.
// Exits 77 (ctest's skip), saying why, where Chromium or web/node_modules is missing.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { readPng } from './png.mjs';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const options = { page: join(repo, 'build/web/coinroll.html'), binary: join(repo, 'build/coinroll'), chromium: '/usr/bin/chromium' };
for (let i = 2; i < process.argv.length; i += 2) options[process.argv[i].replace(/^--/, '')] = resolve(process.argv[i + 1]);

function skip(reason) {
  console.log(`SKIP: ${reason}`);
  process.exit(77);
}
if (!existsSync(options.chromium)) skip(`${options.chromium} not found (tools/setup.sh installs Debian's chromium)`);
let puppeteer;
try {
  puppeteer = (await import(pathToFileURL(createRequire(join(repo, 'web/package.json')).resolve('puppeteer-core')))).default;
} catch (e) {
  skip(`puppeteer-core is not installed in web/node_modules (tools/setup.sh runs npm ci there): ${e.message.split('\n')[0]}`);
}
if (!existsSync(options.page)) throw new Error(`${options.page} not found: build it with node web/build.mjs (the web_page_build test)`);

let passed = 0, failed = 0;
function check(name, ok, detail = '') {
  if (ok) ++passed;
  else ++failed;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail ? `: ${detail}` : ''}`);
}

const scratch = mkdtempSync(join(tmpdir(), `coinroll-page-test-${process.pid}-`));
function coinroll(args, sceneText) {
  if (sceneText !== undefined) writeFileSync(join(scratch, 'scene.json'), sceneText);
  return spawnSync(options.binary, args, { cwd: scratch, encoding: 'utf8', maxBuffer: 1 << 30 });
}
function csvOf(text) {
  const lines = text.trim().split('\n');
  const names = lines[0].split(',');
  const columns = Object.fromEntries(names.map((n) => [n, []]));
  for (const line of lines.slice(1)) line.split(',').forEach((v, c) => columns[names[c]].push(Number(v)));
  return { names, columns, rows: lines.length - 1 };
}
function simulate(sceneText, sampleDt) {
  const args = ['simulate', ...(sceneText === undefined ? [] : ['scene.json']), '--csv', '-', '--sample-dt', String(sampleDt)];
  const result = coinroll(args, sceneText);
  if (result.status !== 0) throw new Error(`coinroll ${args.join(' ')} failed: ${result.stderr}`);
  return csvOf(result.stdout);
}
// What `coinroll simulate` prints after "coinroll: error: " for this scene text, named scene.json as the page names it.
function refusal(sceneText) {
  const result = coinroll(['simulate', 'scene.json', '--csv', '/dev/null'], sceneText);
  const match = /^coinroll: error: (.*)$/m.exec(result.stderr);
  return match ? match[1] : `(no refusal: exit ${result.status}, ${result.stderr.trim()})`;
}

const browser = await puppeteer.launch({
  executablePath: options.chromium, headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-gpu-sandbox'],
});
const problems = [];
const pageUrl = pathToFileURL(options.page).href;
const pagesOpened = new Set([pageUrl]);  // the built page, and the page coinroll export writes
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1800, height: 1000 });
  page.on('console', (m) => {
    if (m.type() === 'error' || (m.type() === 'warn' && /WebGL|THREE/.test(m.text()))) problems.push(`console ${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('request', (r) => {
    const url = r.url();
    if (!pagesOpened.has(url) && !url.startsWith('blob:') && !url.startsWith('data:')) problems.push(`request ${url}`);
  });
  page.on('workercreated', (worker) => worker.on('console', (m) => { if (m.type() === 'error') problems.push(`worker console error: ${m.text()}`); }));
  const client = await page.createCDPSession();
  await client.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: scratch });

  const hook = (name, ...args) => page.evaluate((n, a) => window.coinrollPage[n](...a), name, args);
  const settled = () => page.evaluate(() => window.coinrollPage.settled());
  await page.goto(pageUrl);
  await page.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
  await settled();

  // The numbers at given rows: the page's state to the core's tolerance against the program
  // (docs/web.md "Tolerance"), and its overlay to the last digit it prints.
  async function compareWithCsv(label, csv, rowsToCheck) {
    const info = await hook('run');
    check(`${label}: the page's run has the CSV's rows`, info.rows === csv.rows, `page ${info.rows}, coinroll simulate ${csv.rows}`);
    let worst = { excess: 0 };
    const hudErrors = [];
    for (const row of rowsToCheck) {
      const t = csv.columns.t[row];
      const state = await hook('stateAt', t);
      for (const name of csv.names) {
        const column = csv.columns[name];
        const tolerance = 1e-6 * Math.max(...column.map(Math.abs)) + 1e-12;
        const excess = Math.abs(state[name] - column[row]) / tolerance;
        if (!(excess <= worst.excess)) worst = { excess, detail: `${name} at t = ${t}: page ${state[name]}, CSV ${column[row]}` };
      }
      const shown = (await hook('seek', t)).split('\n');
      const c = csv.columns, degrees = 180 / Math.PI;
      // The contact's rate from the CSV's own heading, by central differences (the page's comes from
      // the rates), to within the differences' own error, which the forward and backward ones bracket.
      const i0 = Math.max(row - 1, 0), i1 = Math.min(row + 1, csv.rows - 1);
      const phiDot = (c.phi[i1] - c.phi[i0]) / (c.t[i1] - c.t[i0]);
      const sides = Math.abs((c.phi[i1] - c.phi[row]) / (c.t[i1] - c.t[row]) - (c.phi[row] - c.phi[i0]) / (c.t[row] - c.t[i0]));
      const expected = [
        [0, c.t[row], 3], [1, c.theta[row] * degrees, 2], [1, 90 - Math.abs(c.theta[row]) * degrees, 2, 1],
        [2, Math.abs(phiDot) / (2 * Math.PI), 2, 0, (sides + 1e-4 * Math.abs(phiDot)) / (2 * Math.PI)], [3, c.omega_Z[row] / (2 * Math.PI), 2], [4, c.energy[row], 5],
      ];
      // At the first and last rows there is no central difference: the contact rate is checked inside.
      if (row === 0 || row === csv.rows - 1) expected.splice(3, 1);
      for (const [line, value, digits, which = 0, slack = 0] of expected) {
        const numbers = (shown[line] || '').match(/-?\d+\.\d+/g) || [];
        const number = Number(numbers[which]);
        if (!(Math.abs(number - value) <= 0.5 * 10 ** -digits + 1e-9 + slack)) hudErrors.push(`t = ${t}, line "${shown[line]}": expected ${value.toFixed(digits + 2)}`);
      }
    }
    check(`${label}: every column at ${rowsToCheck.length} times within the core's tolerance of coinroll simulate's`, worst.excess <= 1,
          worst.detail ? `worst ${worst.excess.toFixed(3)} of the tolerance, ${worst.detail}` : '');
    check(`${label}: the overlay shows the CSV's t, tilt, contact rate, face spin and energy`, hudErrors.length === 0, hudErrors.join('; '));
  }

  const first = await hook('run');
  check('the built-in default scene runs on load', first.sourceName === 'built-in default scene', first.sourceName);
  const defaultCsv = simulate(undefined, first.sampleDt);
  await compareWithCsv('default scene', defaultCsv, [0, 1, 240, 777, defaultCsv.rows - 1]);
  // Playback at the scene's pace, time_scale 0.5, or slower where frames take long (a frame's step is
  // capped at 0.1 s, so that a stalled page does not jump).
  await hook('seek', 0);
  await page.click('#play');
  const pace = await page.evaluate(async () => {
    const t0 = window.coinrollPage.time(), start = performance.now();
    await new Promise((r) => setTimeout(r, 2000));
    return { simulated: window.coinrollPage.time() - t0, real: (performance.now() - start) / 1000 };
  });
  check('play advances the simulated time, at most at the scene\'s pace', pace.simulated > 0 && pace.simulated <= 0.5 * pace.real + 0.05,
        `${pace.simulated.toFixed(3)} s simulated in ${pace.real.toFixed(3)} s at time_scale 0.5`);

  // A slider moved by the keyboard, as a user would: each step an input event, a run.
  const hudBefore = await hook('seek', 1);
  await page.focus('.control[data-path="initial.theta"] input[type=range]');
  for (let i = 0; i < 8; ++i) await page.keyboard.press('ArrowRight');
  await new Promise((r) => setTimeout(r, 50));
  await settled();
  const moved = await hook('run');
  const movedTheta = JSON.parse(moved.text).initial.theta;
  check('the theta slider changed the scene that ran', movedTheta > 15, `initial.theta ${movedTheta}`);
  const boxText = await page.$eval('.control[data-path="initial.theta"] input[type=number]', (e) => e.value);
  check('the theta box shows the slider\'s value', Number(boxText) === movedTheta, boxText);
  const hudAfter = await hook('seek', 1);
  check('the overlay changed with the run', hudAfter !== hudBefore, hudAfter.split('\n')[1]);
  await page.click('#download');
  const downloaded = join(scratch, `${JSON.parse(moved.text).name || 'coinroll'}.json`);
  for (let i = 0; i < 50 && !existsSync(downloaded); ++i) await new Promise((r) => setTimeout(r, 100));
  check('"download scene" writes the scene that ran', existsSync(downloaded) && readFileSync(downloaded, 'utf8') === moved.text, downloaded);
  const movedCsv = simulate(existsSync(downloaded) ? readFileSync(downloaded, 'utf8') : moved.text, moved.sampleDt);
  await compareWithCsv('after the slider, against the downloaded scene', movedCsv, [0, 240, movedCsv.rows - 1]);

  // A slider dragged with the mouse, as a student's first try is: many small moves while the runs
  // they start come back. The value follows the pointer monotonically over the span the drag began
  // on (a span re-centred on each value compounded: 15 px took omega_Z from 16 to 44,400 rad/s).
  {
    const slider = '.control[data-path="initial.omega_Z"] input[type=range]';
    const box = '.control[data-path="initial.omega_Z"] input[type=number]';
    const span = await page.$eval(slider, (e) => {
      const r = e.getBoundingClientRect();
      return { left: r.left, width: r.width, y: r.top + r.height / 2, position: Number(e.value), from: Number(e.dataset.from), to: Number(e.dataset.to) };
    });
    const before = Number(await page.$eval(box, (e) => e.value));
    // The thumb's centre, for Chromium's 16 px thumb inside the track.
    const thumb = span.left + 8 + (span.width - 16) * span.position / 1000;
    await page.mouse.move(thumb, span.y);
    await page.mouse.down();
    const values = [];
    for (let px = 1; px <= 15; ++px) {
      await page.mouse.move(thumb + px, span.y);
      await new Promise((r) => setTimeout(r, 40));
      values.push(Number(await page.$eval(box, (e) => e.value)));
    }
    await page.mouse.up();
    await new Promise((r) => setTimeout(r, 50));
    await settled();
    const after = JSON.parse((await hook('run')).text).initial.omega_Z;
    const monotonic = values.every((v, i) => i === 0 || v >= values[i - 1]);
    check('a mouse drag moves the value monotonically with the pointer', monotonic && after > before, `${before} -> ${values.join(', ')}`);
    // 15 px of a track (span.width - 16) px wide is that fraction of the span the drag started on.
    const expected = before + (span.to - span.from) * 15 / (span.width - 16);
    check('a 15 px drag moves the value 15 px of the span it started on', after >= span.from && after <= span.to &&
          Math.abs(after - expected) <= 0.2 * Math.abs(expected - before), `span [${span.from}, ${span.to}], ${before} -> ${after}, expected ${expected.toPrecision(4)}`);
    const recentred = await page.$eval(slider, (e) => ({ from: Number(e.dataset.from), to: Number(e.dataset.to) }));
    check('the released slider re-centres its span on the new value', recentred.from < after && recentred.to > after, JSON.stringify(recentred));
  }

  // A value out of range typed into a control: the program's message, at that control.
  const lastRun = (await hook('run')).text;
  await page.click('.control[data-path="coin.radius"] input[type=number]', { clickCount: 3 });
  await page.keyboard.type('-1');
  await page.keyboard.press('Tab');
  await settled();
  const radiusError = await page.$eval('.control[data-path="coin.radius"] .error', (e) => e.textContent);
  const radiusRefusal = refusal(await page.$eval('#scene-text', (e) => e.value));
  check('a bad radius shows the program\'s message at the radius', radiusError === radiusRefusal, `page "${radiusError}", coinroll "${radiusRefusal}"`);
  check('the refused run leaves the last run playing', (await hook('run')).text === lastRun);

  // Bad scenes in the box, typed there.
  const badScenes = [
    '{"coin": {"radius": 0.03, "mass": 0.01}, "initial": {"theta": 10}, "duration": 2,}',
    '{"coin": {"radius": 0.03, "mass": 0.01, "colour": "red"}, "initial": {"theta": 10}, "duration": 2}',
    '{"coin": {"radius": 0.03, "mass": 0.01}, "initial": {"theta": 95}, "duration": 2}',
  ];
  for (const text of badScenes) {
    await page.click('#scene-text');
    await page.keyboard.down('Control');
    await page.keyboard.press('KeyA');
    await page.keyboard.up('Control');
    await page.keyboard.press('Backspace');
    await page.keyboard.type(text);
    await page.click('#run-text');
    await settled();
    const shown = await page.$eval('#scene-error', (e) => e.textContent);
    const expected = refusal(text);
    check(`the box shows the program's message for ${text.slice(0, 48)}...`, shown === expected, `page "${shown}", coinroll "${expected}"`);
  }

  // Where the coin is drawn: the default scene's camera (render.camera eye, target, fov) at the
  // still's size, its overlay and trace off so that only the coin is brass-coloured.
  const geometryScene = JSON.parse(await hook('defaultScene'));
  Object.assign(geometryScene.render, { hud: false, trace: false });
  const geometryText = JSON.stringify(geometryScene, null, 2);
  await page.$eval('#scene-text', (e, text) => { e.value = text; }, geometryText);
  await page.click('#run-text');
  await settled();
  await hook('setViewSize', 1280, 720);
  const time = 1;
  await hook('seek', time);
  const canvas = await page.$('#canvas');
  const pageShot = readPng(Buffer.from(await canvas.screenshot({ type: 'png' })));
  await hook('showTestMarks', true);
  await hook('seek', time);
  const markShot = readPng(Buffer.from(await canvas.screenshot({ type: 'png' })));
  await hook('showTestMarks', false);
  const still = coinroll(['still', 'scene.json', '--time', String(time), '-o', 'still.png'], geometryText);
  if (still.status !== 0) throw new Error(`coinroll still failed: ${still.stderr}`);
  const stillShot = readPng(readFileSync(join(scratch, 'still.png')));
  check('the page draws at the still\'s size', pageShot.width === stillShot.width && pageShot.height === stillShot.height,
        `${pageShot.width}x${pageShot.height} and ${stillShot.width}x${stillShot.height}`);
  const camera = await hook('camera');
  const row = Math.round(time / (await hook('run')).sampleDt);
  const geometryCsv = simulate(geometryText, (await hook('run')).sampleDt);
  const c = geometryCsv.columns;
  const project = pinhole(geometryScene.render.camera, stillShot.width, stillShot.height);
  const marks = [['centre', [255, 0, 255], project([c.x[row], c.y[row], c.z[row]])], ['contact point', [0, 255, 255], project([c.contact_x[row], 0, c.contact_z[row]])]];
  for (const [name, colour, expected] of marks) {
    const found = centroid(markShot, (r, g, b) => Math.abs(r - colour[0]) < 60 && Math.abs(g - colour[1]) < 60 && Math.abs(b - colour[2]) < 60);
    const distance = found ? Math.hypot(found.x - expected[0], found.y - expected[1]) : Infinity;
    check(`the coin's ${name} is drawn within 2 px of the CSV's, projected by the scene's camera`, distance <= 2,
          found ? `page (${found.x.toFixed(2)}, ${found.y.toFixed(2)}), projected (${expected[0].toFixed(2)}, ${expected[1].toFixed(2)}): ${distance.toFixed(2)} px` : 'no mark found');
  }
  check('the page\'s camera is the scene\'s', [0, 1, 2].every((k) => Math.abs(camera.eye[k] - geometryScene.render.camera.eye[k]) < 1e-6 &&
        Math.abs(camera.target[k] - geometryScene.render.camera.target[k]) < 1e-6) && camera.fov === 35, JSON.stringify(camera));
  const brass = (r, g, b) => r - b > 40 && r >= g;
  const inPage = centroid(pageShot, brass), inStill = centroid(stillShot, brass);
  if (!inPage || !inStill) {
    check('the coin is found in the page and in the still', false, `page ${JSON.stringify(inPage)}, still ${JSON.stringify(inStill)}`);
  } else {
    const moves = ['x', 'y', 'left', 'right', 'top', 'bottom'].map((k) => Math.abs(inPage[k] - inStill[k]));
    check('the coin lies where coinroll still draws it: centroid and every edge within 2 px', Math.max(...moves) <= 2,
          `page ${describe(inPage)}; still ${describe(inStill)}`);
    check('the coin covers the still\'s area within 3 %', Math.abs(inPage.count / inStill.count - 1) < 0.03, `${inPage.count} and ${inStill.count} px`);
  }

  // The Euler's disk: progress while it runs, a newer run taking over, and its playback's slow motion.
  await page.select('#example', 'euler_disk');
  const busy = await page.waitForFunction(() => {
    const shown = !document.getElementById('busy').hidden, value = document.getElementById('progress').value;
    return shown && value > 0 && { value, running: window.coinrollPage.run().sourceName !== 'examples/euler_disk.json' };
  }, { timeout: 60000 }).then((h) => h.jsonValue(), (e) => ({ error: e.message }));
  check('a long run shows its progress', busy.running && busy.value < 1, JSON.stringify(busy));
  await page.select('#example', 'steady_circle');
  await settled();
  const taken = await hook('run');
  check('a newer run takes over from one in progress', taken.sourceName === 'examples/steady_circle.json' &&
        (await page.$eval('#scene-error', (e) => e.textContent)) === '', taken.sourceName);
  await page.select('#example', 'euler_disk');
  await settled();
  const euler = await hook('run');
  const eulerText = readFileSync(join(repo, 'examples/euler_disk.json'), 'utf8');
  check('the Euler\'s disk runs to its landing', euler.end.event === 'face-down', JSON.stringify(euler.end));
  await compareWithCsv('Euler\'s disk', simulate(eulerText, euler.sampleDt), [0, 5000, 10000, 11000, 11700]);
  // Between its rows (10 ms apart here) the page interpolates the rates; in the landing's last tenth
  // of a second phi-dot wobbles within a row (300, 293, then 369 rad/s at 117.1, 117.116 and 117.15 s),
  // and the page's playback rate may be 1.2 % off there: 2.5 % is allowed in that window, 1 % before.
  let worstRate = { error: 0 };
  for (const [from, to, tolerance] of [[50, 50.02, 0.01], [110, 110.02, 0.01], [117.1, 117.12, 0.025]]) {
    const result = coinroll(['render', 'scene.json', '--from', String(from), '--to', String(to), '--frame-times', 'frames.csv', '-o', 'f_%05d.png',
                             '--set', 'render.width=64', '--set', 'render.height=64'], eulerText);
    if (result.status !== 0) throw new Error(`coinroll render failed: ${result.stderr}`);
    const frames = csvOf(readFileSync(join(scratch, 'frames.csv'), 'utf8')).columns;
    for (let k = 0; k < frames.sim_time_s.length; ++k) {
      const rate = await hook('playbackRate', frames.sim_time_s[k]), expected = frames.playback_rate[k];
      const error = Math.abs(rate / expected - 1) / tolerance;
      if (!(error <= worstRate.error)) worstRate = { error, detail: `t = ${frames.sim_time_s[k]} s: page ${rate}, coinroll render ${expected}` };
    }
  }
  check('playback slows down as coinroll render\'s time remap does', worstRate.error <= 1, `worst ${worstRate.error.toFixed(2)} of the tolerance, ${worstRate.detail}`);

  // The coin toss: slower in the air and eased to 20x slow at each impact (render.time_remap.flight and
  // .impact), from the impacts the core reports: each frame's rate as coinroll render chose it, to 1e-4.
  await page.select('#example', 'coin_toss');
  await settled();
  const tossText = readFileSync(join(repo, 'examples/coin_toss.json'), 'utf8');
  const tossRender = coinroll(['render', 'scene.json', '--to', '0.8', '--frame-times', 'frames.csv', '-o', 'f_%05d.png',
                               '--set', 'render.width=64', '--set', 'render.height=64'], tossText);
  if (tossRender.status !== 0) throw new Error(`coinroll render failed: ${tossRender.stderr}`);
  const tossFrames = csvOf(readFileSync(join(scratch, 'frames.csv'), 'utf8')).columns;
  let worstToss = { error: 0 };
  for (let k = 0; k < tossFrames.sim_time_s.length; ++k) {
    const rate = await hook('playbackRate', tossFrames.sim_time_s[k]), expected = tossFrames.playback_rate[k];
    const error = Math.abs(rate / expected - 1) / 1e-4;
    if (!(error <= worstToss.error)) worstToss = { error, detail: `t = ${tossFrames.sim_time_s[k]} s: page ${rate}, coinroll render ${expected}` };
  }
  check('playback slows down in the air and at each impact as coinroll render does', worstToss.error <= 1 &&
        tossFrames.playback_rate.some((r) => Math.abs(r - 0.05) < 1e-3), `worst ${worstToss.error.toFixed(2)} of the tolerance, ${worstToss.detail}`);

  // coinroll export: the built page with a scene in it opens on that scene and runs it as the program does.
  const exported = join(scratch, 'ring.html');
  const ringText = readFileSync(join(repo, 'examples/ring.json'), 'utf8');
  const written = spawnSync(options.binary, ['export', join(repo, 'examples/ring.json'), '-o', exported],
                            { encoding: 'utf8', env: { ...process.env, COINROLL_PAGE: options.page } });
  check('coinroll export writes the page', written.status === 0 && existsSync(exported), written.stderr.trim());
  check('the exported page is at most 2 MB', statSync(exported).size <= 2e6, `${statSync(exported).size} bytes`);
  pagesOpened.add(pathToFileURL(exported).href);
  await page.goto(pathToFileURL(exported).href);
  await page.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
  await settled();
  const ring = await hook('run');
  check('the exported page opens on its scene', ring.sourceName === 'exported scene' && JSON.parse(ring.text).name === JSON.parse(ringText).name,
        ring.sourceName);
  const ringCsv = simulate(ringText, ring.sampleDt);
  await compareWithCsv('the exported ring', ringCsv, [0, Math.floor(ringCsv.rows / 2), ringCsv.rows - 1]);
  check('no console error, no network request', problems.length === 0, problems.slice(0, 5).join('; '));
} finally {
  await browser.close();
  rmSync(scratch, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);

// Pixel coordinates (x right, y down, from the top-left corner) of a world point seen by a pinhole
// camera at eye looking at target, y up, with vertical field of view fov degrees: render/camera.cpp's rule.
function pinhole({ eye, target, fov = 35 }, width, height) {
  const sub = (a, b) => a.map((v, i) => v - b[i]), dot = (a, b) => a.reduce((s, v, i) => s + v * b[i], 0);
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => a.map((v) => v / Math.hypot(...a));
  const forward = unit(sub(target, eye)), right = unit(cross(forward, [0, 1, 0])), up = cross(right, forward);
  const tanHalf = Math.tan(fov * Math.PI / 360);
  return (p) => {
    const d = sub(p, eye), depth = dot(d, forward);
    const x = dot(d, right) / depth / (tanHalf * width / height), y = dot(d, up) / depth / tanHalf;
    return [(x + 1) / 2 * width, (1 - y) / 2 * height];
  };
}

// The centroid (pixel centres) and bounding box of the pixels `inside` picks, or null.
function centroid({ width, height, rgba }, inside) {
  let count = 0, sx = 0, sy = 0, left = Infinity, right = -Infinity, top = Infinity, bottom = -Infinity;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      const p = 4 * (y * width + x);
      if (!inside(rgba[p], rgba[p + 1], rgba[p + 2])) continue;
      ++count; sx += x + 0.5; sy += y + 0.5;
      left = Math.min(left, x); right = Math.max(right, x); top = Math.min(top, y); bottom = Math.max(bottom, y);
    }
  }
  return count ? { x: sx / count, y: sy / count, left, right, top, bottom, count } : null;
}

function describe(box) {
  return `centroid (${box.x.toFixed(2)}, ${box.y.toFixed(2)}), x ${box.left}..${box.right}, y ${box.top}..${box.bottom}`;
}
