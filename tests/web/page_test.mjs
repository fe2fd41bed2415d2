#!/usr/bin/env node
// The page (docs/web.md "The page") in a real browser: Debian's Chromium, driven by puppeteer-core
// (web/package-lock.json), opens the built page from file:// and is checked against the program:
//     node tests/web/page_test.mjs --page build/web/coinroll.html --binary build/coinroll
//
// - no console error and no request beyond the page's own file, its Blob worker and data URIs;
// - opened with #probe=T1,T2,..., its DOM dump holds the CSV's numbers at those times;
// - the numbers the page holds and its overlay shows at given times are `coinroll simulate`'s CSV for
//   the same scene and sample step;
// - a slider moved by the page's own keyboard events runs the changed scene, which "download scene"
//   writes, and which `coinroll simulate` reproduces;
// - the coin's centre and contact point in a screenshot are where a pinhole camera puts the CSV's,
//   and the coin where `coinroll still` draws it, within 2 px;
// - a bad scene in the box, or a bad value in a control, shows the program's message beside it; a
//   refused control is marked invalid, says the run on screen is the last one, goes back to it on
//   Escape or its button, and does not make the next change refused too;
// - no slider offers a value outside its key's range (the tilt's also inside the flat stop), on every
//   example and a scene holding every key the page shows;
// - the custom shape's moments and the flight keys have controls, shown by the schema's presence rules,
//   that fill what the choice needs (a disk made custom runs as the disk did; flight, its restitution);
// - a run in progress shows its progress and gives way to a newer one; playback follows
//   render.time_remap as `coinroll render --frame-times` reports it, in the air and at each impact too;
// - a steady circle nudged by a degree wobbles at the period the panel predicts, as measured on the
//   page and on the CSV;
// - the steady-motion panel shows, for the run's coin and tilt, every number `coinroll steady` prints
//   for each motion it lists, follows a change of tilt or coin, and its buttons start those motions;
// - in the seed's units (M = a = g = 1) the panel, the controls and the overlay show the program's
//   numbers over their units' sizes (ω_c = 1/√3 for the thin disk), and a value typed or slid there
//   reaches the core in SI;
// - a legend says what the picture draws; every control has a readable name and a tooltip naming its key;
// - `coinroll export --title --caption --controls` puts its title and caption on the page as text, shows
//   only the controls chosen, and folds the researcher's details one click away, within an 800x600 iframe;
// - at 360 px, in an 800x600 iframe and at 1600 px nothing lies past the window's sides, the view takes
//   the phone's width (the coin in it) and at least half the wider windows'.
// Exits 77 (ctest's skip), saying why, where Chromium or web/node_modules is missing.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
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

// `coinroll steady`'s numbers for a request ({kind, theta, omega_Z, branch}) on a scene: each as
// printed, by the names the page's steady panel gives them (data-quantity); or its refusal.
function steadyReport(sceneText, { kind, theta, omega_Z: omegaZ, branch }) {
  const args = ['steady', 'scene.json', '--kind', kind];
  if (theta !== undefined) args.push('--theta', String(theta));
  if (omegaZ !== undefined) args.push('--omega-Z', String(omegaZ));
  if (branch !== undefined) args.push('--branch', branch);
  const result = coinroll(args, sceneText);
  if (result.status !== 0) return { error: (/^coinroll: error: (.*)$/m.exec(result.stderr) || [, result.stderr.trim()])[1] };
  const out = result.stdout, numbers = {};
  const n = '(-?(?:inf|[\\d.]+(?:e[-+]?\\d+)?))';
  const grab = (pattern, names) => {
    const match = new RegExp(pattern).exec(out);
    if (match) names.forEach((name, i) => { numbers[name] = match[i + 1]; });
  };
  grab(`coin: M = ${n} kg, a = ${n} m, g = ${n} m/s\\^2, I_X = ${n} kg m\\^2, I_Z = ${n} kg m\\^2`, ['M', 'a', 'g', 'I_X', 'I_Z']);
  grab(`natural rate sqrt\\(g/a\\) = ${n} rad/s`, ['naturalRate']);
  grab(`omega_c = ${n} rad/s \\(${n} sqrt\\(g/a\\)`, ['criticalSpin', 'criticalSpinInNaturalUnits']);
  for (const key of ['theta', 'omega_Y', 'omega_Z']) grab(`"${key}": ${n}`, [key]);
  grab(`phi-dot = ${n} rad/s, psi-dot = ${n} rad/s`, ['precessionRate', 'spinRate']);
  grab(`R_G = ${n} m, contact point R_C = ${n} m`, ['radiusCentreOfMass', 'radiusContact']);
  grab(`N = ${n} N, F = ${n} N \\(needs mu >= ${n}\\)`, ['N', 'F', 'frictionNeeded']);
  grab(`K = ${n} 1/s\\^2`, ['K']);
  grab(`(?:wobbles at ${n} rad/s \\(period|grows like exp\\(${n} t / s\\) \\(e-folding time) ${n} s`, ['rate', 'rate2', 'time']);
  if (numbers.rate === undefined) numbers.rate = numbers.rate2;
  delete numbers.rate2;
  numbers.verdict = (/^verdict: (\w+)/m.exec(out) || [])[1];
  return { numbers };
}
// A number the page shows against the program's printed one, to the digits the page shows: equal,
// or one unit of the last shown digit apart where the module's libm and the program's round apart
// (docs/web.md "Tolerance").
function agreesToShownDigits(shown, printed) {
  const value = (text) => (text === '∞' || text === 'inf' ? Infinity : text === '-inf' ? -Infinity : Number(text));
  const a = value(shown), b = value(printed);
  if (a === b) return true;
  const [mantissa, exponent = '0'] = shown.split('e');
  const decimals = mantissa.includes('.') ? mantissa.split('.')[1].length : 0;
  return Number.isFinite(a) && Math.abs(a - b) <= Math.pow(10, Number(exponent) - decimals) * (1 + 1e-9);
}

// #probe (docs/contract.md "Web page"), read as an outside script would: Chromium's DOM dump, no
// driver. The numbers are the CSV's at those times to the core's tolerance (docs/web.md
// "Tolerance"); a time past the run's end is null; a refused scene gives the program's message.
function probed(pageFile, fragment) {
  const dumped = spawnSync(options.chromium, ['--headless', '--no-sandbox', '--disable-gpu', '--dump-dom',
                                              `${pathToFileURL(pageFile).href}#probe=${fragment}`],
                           { encoding: 'utf8', maxBuffer: 1 << 30, timeout: 120000 });
  const found = /<pre id="coinroll-probe"[^>]*>([^<]*)<\/pre>/.exec(dumped.stdout || '');
  if (!found) return { missing: `no <pre id="coinroll-probe"> in the DOM dump (status ${dumped.status}): ${(dumped.stderr || '').slice(-300)}` };
  return JSON.parse(found[1].replace(/&amp;/g, '&').replace(/&lt;/g, '<').replace(/&gt;/g, '>').replace(/&quot;/g, '"'));
}
function exportPage(sceneText, name) {
  const file = join(scratch, `${name}.html`);
  writeFileSync(join(scratch, `${name}.json`), sceneText);
  const written = spawnSync(options.binary, ['export', join(scratch, `${name}.json`), '-o', file, '-q'],
                            { encoding: 'utf8', env: { ...process.env, COINROLL_PAGE: options.page } });
  if (written.status !== 0) throw new Error(`coinroll export failed: ${written.stderr}`);
  return file;
}
{
  const times = [0, 0.5, 1, 2, 1e6];
  const probes = [['the built-in default scene', options.page, undefined],
                  ['the coin toss, exported', exportPage(readFileSync(join(repo, 'examples/coin_toss.json'), 'utf8'), 'toss'),
                   readFileSync(join(repo, 'examples/coin_toss.json'), 'utf8')]];
  for (const [label, file, sceneText] of probes) {
    const shown = probed(file, times.join(','));
    let worst = { excess: 0 };
    for (const [k, t] of times.entries()) {
      const csv = t > 0 ? simulate(sceneText, t) : simulate(sceneText, 1);
      const row = t > 0 ? 1 : 0;
      for (const name of ['theta', 'x', 'y', 'z', 'energy']) {
        const expected = row < csv.rows ? csv.columns[name][row] : null;
        const value = shown[name] ? shown[name][k] : undefined;
        const tolerance = expected === null ? 0 : 1e-6 * Math.max(...csv.columns[name].map(Math.abs)) + 1e-12;
        const excess = expected === null ? (value === null ? 0 : Infinity) : Math.abs(value - expected) / tolerance;
        if (!(excess <= worst.excess)) worst = { excess, detail: `${name} at t = ${t}: page ${value}, CSV ${expected}` };
      }
    }
    check(`#probe on ${label}: the DOM dump holds t and the CSV's theta, x, y, z, energy at ${times.join(', ')} s (null past the end)`,
          !shown.missing && JSON.stringify(shown.t) === JSON.stringify(times) && worst.excess <= 1,
          shown.missing || (worst.detail ? `worst ${worst.excess.toFixed(3)} of the tolerance, ${worst.detail}` : ''));
  }
  // export refuses such a scene; a page holding one anyway (the placeholder filled by hand) says why.
  const badScene = '{"coin": {"radius": -1}}';
  const refusedPage = join(scratch, 'refused.html');
  writeFileSync(refusedPage, readFileSync(options.page, 'utf8').replace(
    '<script type="application/json" id="coinroll-scene">null</script>',
    `<script type="application/json" id="coinroll-scene">${badScene}</script>`));
  const refused = probed(refusedPage, '1');
  const expectedRefusal = refusal(badScene).replace(/^scene\.json: /, 'exported scene: ');
  check('#probe on a scene the program refuses gives the program\'s message', refused.error === expectedRefusal,
        `page ${JSON.stringify(refused)}, coinroll "${expectedRefusal}"`);
  const malformed = probed(options.page, '1,soon');
  check('a #probe that is not a list of times says so', /#probe=1,soon: expected simulated times/.test(malformed.error || ''),
        JSON.stringify(malformed));
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
  const ranScene = async () => JSON.parse((await hook('run')).text);
  // What the control of `path` shows: shown or hidden, its inputs' values and marks, its messages.
  const control = (path) => page.$eval(`.control[data-path="${path}"]`, (row) => {
    const box = row.querySelector('input[type=number]'), slider = row.querySelector('input[type=range]');
    const check = row.querySelector('input[type=checkbox]'), note = row.querySelector('.refusal-note');
    return {
      hidden: row.hidden, box: box && box.value, checked: check && check.checked, from: slider && Number(slider.dataset.from),
      to: slider && Number(slider.dataset.to), invalid: [box, slider].filter(Boolean).map((e) => e.getAttribute('aria-invalid')),
      error: row.querySelector('.error').textContent, note: note && !note.hidden ? note.textContent : '',
    };
  }).catch(() => null);
  const shownErrors = () => page.$$eval('.error', (all) => all.map((e) => e.textContent).filter(Boolean));
  async function runSceneText(text) {
    await page.$eval('#scene-text', (e, t) => { e.value = t; }, text);
    await page.click('#run-text');
    await settled();
  }
  // A part that drives a control a page may lack fails as a check, not the whole test.
  async function part(name, body) {
    try {
      await body();
    } catch (e) {
      check(`${name}: the part runs through`, false, e.message.split('\n')[0]);
    }
  }
  async function keyOn(selector, key) {
    await page.focus(selector);
    await page.keyboard.press(key);
    await new Promise((r) => setTimeout(r, 50));
    await settled();
  }
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

  // The plots under the view (web/src/plots.js): the run's own columns, the cursor on the playback
  // time, a press seeking the motion, the seed's units rescaling them.
  await part('plots', async () => {
    const kExpected = { tilt: ['theta'], spins: ['omega_X', 'omega_Y', 'omega_Z'], energy: ['energy'],
                        contact: ['normal_force', 'friction_force'] };
    const row = 777, t = defaultCsv.columns.t[row];
    await hook('seek', t);
    const plots = await hook('plots');
    const drawn = await page.$$eval('.plot', (all) =>
      all.map((p) => p.dataset.plot + (p.querySelector('canvas') ? '' : '?')));
    const shape = Object.fromEntries(Object.entries(plots).map(([id, p]) => [id, Object.keys(p.values)]));
    check('the default scene has the tilt, spins, energy and floor-reaction plots, with their series',
          JSON.stringify(shape) === JSON.stringify(kExpected) && drawn.join(' ') === Object.keys(kExpected).join(' '),
          `${JSON.stringify(shape)}; ${drawn.join(', ')}`);
    // At the cursor: the page's own column (θ in degrees), exactly, and coinroll simulate's CSV within 1e-9 of
    // the column's largest magnitude (the module differs from the program by 9.2e-15 of it here, docs/web.md).
    const state = await hook('stateAt', t), misses = [];
    for (const [id, plot] of Object.entries(plots)) {
      if (plot.idx !== row || plot.x !== t) misses.push(`${id}: cursor at row ${plot.idx}, t = ${plot.x}`);
      for (const [name, value] of Object.entries(plot.values)) {
        const factor = name === 'theta' ? 180 / Math.PI : 1, column = defaultCsv.columns[name];
        const tolerance = 1e-9 * Math.max(...column.map(Math.abs)) * factor + 1e-12;
        if (value !== state[name] * factor || !(Math.abs(value - column[row] * factor) <= tolerance)) {
          misses.push(`${id} ${name}: plotted ${value}, page ${state[name] * factor}, CSV ${column[row] * factor}`);
        }
      }
    }
    check(`every plot's cursor at t = ${t} s is on row ${row}, its values the CSV's there`,
          misses.length === 0 && Object.keys(plots).length > 0, misses.slice(0, 4).join('; '));

    // The legends' values change as the cursor moves, and wrap anew; the picture's size must not follow
    // (each change resizes the WebGL canvas, which in software takes a frame's time and more).
    const viewSizes = new Set();
    for (let k = 0; k <= 24; ++k) {
      await hook('seek', 0.25 * k);
      viewSizes.add(await page.$eval('#view', (e) => `${e.clientWidth}x${e.clientHeight}`));
    }
    check('the picture keeps its size while the plots\' cursor and legends move through the run', viewSizes.size === 1,
          [...viewSizes].join(', '));

    // A press in the middle of the tilt plot, playing, pauses at the middle of the run; a drag seeks on.
    const over = await page.$eval('.plot[data-plot="tilt"] .u-over', (e) => {
      e.scrollIntoView({ block: 'center' });
      const r = e.getBoundingClientRect();
      return { left: r.left, width: r.width, y: r.top + r.height / 2 };
    });
    const { sampleDt } = await hook('run'), end = defaultCsv.columns.t[defaultCsv.rows - 1];
    await page.click('#play');
    await page.mouse.click(over.left + over.width / 2, over.y);
    await new Promise((r) => setTimeout(r, 100));
    const clicked = await hook('time'), stopped = !(await hook('playing'));
    check('a click in the middle of the tilt plot pauses the motion at the middle of the run (within a sample)',
          stopped && Math.abs(clicked - end / 2) <= sampleDt, `t = ${clicked}, expected ${end / 2}, paused ${stopped}`);
    await page.mouse.move(over.left + over.width / 4, over.y);
    await page.mouse.down();
    for (let k = 1; k <= 10; ++k) await page.mouse.move(over.left + over.width * (0.25 + 0.05 * k), over.y);
    await page.mouse.up();
    await new Promise((r) => setTimeout(r, 100));
    const dragged = await hook('time'), cursor = (await hook('plots')).tilt;
    check('a drag along the tilt plot seeks to where it ends, the cursor following',
          Math.abs(dragged - 0.75 * end) <= sampleDt && Math.abs(cursor.x - dragged) <= sampleDt / 2 + 1e-12,
          `t = ${dragged}, expected ${0.75 * end}, cursor at ${cursor.x}`);

    // The seed's units: energies over M g a, times over sqrt(a/g), and the axes say so.
    await hook('seek', t);
    const scene = JSON.parse((await hook('run')).text);
    const schemaGravity = () => JSON.parse(coinroll(['schema']).stdout).keys.find((k) => k.path === 'gravity').default;
    const g = scene.gravity !== undefined ? scene.gravity : schemaGravity();
    const Mga = scene.coin.mass * g * scene.coin.radius;
    await page.click('input[name=units][value=seed]');
    const seed = (await hook('plots')).energy, si = plots.energy;
    await page.click('input[name=units][value=si]');
    const back = (await hook('plots')).energy;
    check('in the seed\'s units the energy plot shows E / (M g a) against t / √(a/g), labelled so; SI again after',
          Math.abs(seed.values.energy * Mga / si.values.energy - 1) <= 1e-12 &&
          Math.abs(seed.x * Math.sqrt(scene.coin.radius / g) / t - 1) <= 1e-12 &&
          seed.axes.join(' | ') === 't (√(a/g)) | E (Mga)' &&
          back.values.energy === si.values.energy && back.axes.join(' | ') === 't (s) | E (J)',
          `E ${si.values.energy} J at row ${si.idx}, ${seed.values.energy} Mga (M g a ${Mga} J) at row ${seed.idx}; ` +
          `axes ${seed.axes.join(', ')}; back ${back.values.energy} J at row ${back.idx}, ` +
          `axes ${back.axes.join(', ')}`);
  });
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
  // A burst whose presses come while earlier runs are still out (not awaited one by one): once the
  // last is drawn and every press's busy delay has passed, no older run's sign may come up.
  // Three bursts: the page before this check left the sign up after 3 of 5.
  let busyShown = 0;
  for (let trial = 0; trial < 3; ++trial) {
    const burst = [];
    for (let i = 0; i < 6; ++i) {
      burst.push(page.keyboard.press(i % 2 ? 'ArrowLeft' : 'ArrowRight'));
      await new Promise((r) => setTimeout(r, 15));
    }
    await Promise.all(burst);
    await settled();
    await new Promise((r) => setTimeout(r, 400));
    if (await page.$eval('#busy', (e) => !e.hidden)) ++busyShown;
  }
  check('after a burst of presses the busy sign is down', busyShown === 0, `left up after ${busyShown} of 3 bursts`);
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
    // In view first, as a student scrolls to it: the panel may have scrolled down to the scene box.
    await page.$eval(slider, (e) => e.scrollIntoView({ block: 'center' }));
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
  const radiusShown = await control('coin.radius');
  const runningRadius = JSON.parse(lastRun).coin.radius;
  check('the refused radius stays in its box, marked invalid, saying the run on screen is the last one', radiusShown.box === '-1' &&
        radiusShown.invalid.every((v) => v === 'true') && radiusShown.note.includes(`still the last run's, with coin.radius = ${runningRadius} m`),
        JSON.stringify(radiusShown));
  await part('the radius\'s "Back to" button', async () => {
    await page.click('.control[data-path="coin.radius"] .refusal-note button');
    const radiusBack = await control('coin.radius');
    check('its "Back to" button shows the running radius again, unmarked, and the scene box the running scene', radiusBack.box === String(runningRadius) &&
          radiusBack.invalid.every((v) => v === null) && radiusBack.note === '' && radiusBack.error === '' &&
          (await page.$eval('#scene-text', (e) => e.value)) === lastRun, JSON.stringify(radiusBack));
  });

  // A refused tilt typed into its box: the next change of another control runs the scene on screen
  // with that change (the refused value no longer in it), and Escape goes back to the running value.
  await part('a refused tilt', async () => {
    const theta = '.control[data-path="initial.theta"] input[type=number]';
    const runningTheta = (await ranScene()).initial.theta;
    await page.click(theta, { clickCount: 3 });
    await page.keyboard.type('95');
    await page.keyboard.press('Enter');
    await settled();
    const refused = await control('initial.theta');
    check('a refused tilt is marked invalid (aria-invalid) on its box and slider, with the program\'s message and the running value',
          refused.box === '95' && refused.invalid.length === 2 && refused.invalid.every((v) => v === 'true') &&
          refused.error.includes('initial.theta: must be in (-90, 90) degrees') && refused.note.includes(`initial.theta = ${runningTheta} degrees`),
          JSON.stringify(refused));
    await keyOn('.control[data-path="initial.omega_Z"] input[type=range]', 'ArrowRight');
    const next = await ranScene(), errors = await shownErrors();
    check('after a refusal, the next change of another control runs, on the scene on screen', errors.length === 0 &&
          next.initial.theta === runningTheta && (await control('initial.theta')).invalid.every((v) => v === null),
          `theta ${next.initial.theta}, errors ${JSON.stringify(errors)}`);
    await page.click(theta, { clickCount: 3 });
    await page.keyboard.type('95');
    await page.keyboard.press('Enter');
    await settled();
    await page.keyboard.press('Escape');
    const back = await control('initial.theta');
    check('Escape in a refused box puts the running value back, unmarked', back.box === String(runningTheta) && back.invalid.every((v) => v === null) &&
          back.note === '' && back.error === '' && (await page.$eval('#scene-text', (e) => e.value)) === (await hook('run')).text, JSON.stringify(back));
  });

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

  // Every slider's ends are values its key's range takes: strictly inside an excluded bound, and for a
  // tilt inside +-89 degrees, where a start is refused for lying near flat (physics/validity.h
  // kFlatTilt). On every example and a scene with every key the page shows, whatever its value.
  await part('slider ends', async () => {
    const schemaKeys = new Map(JSON.parse(coinroll(['schema']).stdout).keys.map((k) => [k.path, k]));
    const everyKey = JSON.stringify({
      coin: { shape: 'custom', radius: 0.02, mass: 0.01, I_X: 1e-6, I_Z: 2e-6, thickness: 0.002, edge_radius: 0.0005 },
      initial: { theta: -30, omega_Z: 5, y: 0.1, v_y: 0.5, v_x: 0.1, v_z: -0.1 },
      friction: 0.3, friction_static: 0.4, sliding: true, flight: true, restitution: 0.5, impact_friction: 0.2, duration: 1,
      effects: [{ type: 'air_drag', model: 'boundary_layer' }, { type: 'rolling_resistance' }, { type: 'spin_friction' }],
    });
    const outside = [];
    let sliders = 0;
    const scenes = [...readdirSync(join(repo, 'examples')).filter((f) => f.endsWith('.json')).map((f) => readFileSync(join(repo, 'examples', f), 'utf8')), everyKey];
    for (const text of scenes) {
      await runSceneText(text);
      const name = JSON.parse(text).name || 'every key';
      if ((await hook('run')).text !== text) outside.push(`${name}: not run: ${await page.$eval('#scene-error', (e) => e.textContent)}`);
      const ends = await page.$$eval('.control:not([hidden])', (rows) => rows.filter((r) => r.querySelector('input[type=range]'))
        .map((r) => ({ path: r.dataset.path, from: Number(r.querySelector('input[type=range]').dataset.from), to: Number(r.querySelector('input[type=range]').dataset.to) })));
      for (const { path, from, to } of ends) {
        ++sliders;
        const key = schemaKeys.get(path);
        const tilt = /theta$/.test(path) ? 89 : Infinity;
        const above = (v, b) => (b ? (b.inclusive ? v >= b.value : v > b.value) : true);
        const below = (v, b) => (b ? (b.inclusive ? v <= b.value : v < b.value) : true);
        for (const v of [from, to]) {
          if (!(Number.isFinite(v) && above(v, key.minimum) && below(v, key.maximum) && Math.abs(v) < tilt)) outside.push(`${name}: ${path} end ${v}`);
        }
      }
    }
    check('every slider\'s ends lie in its key\'s range (inside excluded bounds, a tilt inside +-89 deg)', outside.length === 0 && sliders > 100,
          `${sliders} sliders; ${outside.slice(0, 6).join('; ')}`);
    await runSceneText(await hook('defaultScene'));
    const tiltEnds = [];
    for (const key of ['End', 'Home']) {
      await keyOn('.control[data-path="initial.theta"] input[type=range]', key);
      tiltEnds.push(`${(await ranScene()).initial.theta}: ${(await shownErrors()).join(' ') || 'ran'}`);
    }
    check('the tilt slider\'s two ends run', tiltEnds.every((t) => t.endsWith(': ran')) && (await shownErrors()).length === 0, tiltEnds.join('; '));
  });

  // The custom shape: its moments get controls, a disk made custom starts with its own moments and
  // moves as it did, the moments' bound is the program's, and back to a disk they leave the scene.
  await part('the custom shape', async () => {
    await runSceneText(await hook('defaultScene'));
    const disk = await ranScene();
    const diskState = await hook('stateAt', 2);
    await page.select('.control[data-path="coin.shape"] select', 'custom');
    await settled();
    const custom = await ranScene();
    const [I_X, I_Z] = [await control('coin.I_X'), await control('coin.I_Z')];
    check('shape custom shows I_X and I_Z, filled with the disk\'s moments, and runs', I_X && I_Z && !I_X.hidden && !I_Z.hidden &&
          custom.coin.I_X === disk.coin.mass * disk.coin.radius ** 2 / 4 && custom.coin.I_Z === disk.coin.mass * disk.coin.radius ** 2 / 2 &&
          Number(I_X.box) === custom.coin.I_X && Number(I_Z.box) === custom.coin.I_Z && (await shownErrors()).length === 0,
          JSON.stringify({ coin: custom.coin, I_X, I_Z }));
    const customState = await hook('stateAt', 2);
    check('the disk made custom moves exactly as the disk did', ['theta', 'phi', 'psi', 'x', 'z', 'omega_Z'].every((k) => customState[k] === diskState[k]),
          `theta ${customState.theta} and ${diskState.theta}`);
    await page.click('.control[data-path="coin.I_Z"] input[type=number]', { clickCount: 3 });
    await page.keyboard.type(String(3 * custom.coin.I_X));
    await page.keyboard.press('Enter');
    await settled();
    const tooLarge = await control('coin.I_Z');
    const expected = refusal(await page.$eval('#scene-text', (e) => e.value));
    check('an I_Z above 2 I_X is refused at I_Z with the program\'s message', tooLarge.error === expected && tooLarge.invalid.every((v) => v === 'true'),
          `page "${tooLarge.error}", coinroll "${expected}"`);
    await page.keyboard.press('Escape');
    await keyOn('.control[data-path="coin.I_X"] input[type=range]', 'ArrowRight');
    const heavier = await ranScene();
    check('the I_X slider runs a custom coin', heavier.coin.I_X > custom.coin.I_X && heavier.coin.I_Z === custom.coin.I_Z && (await shownErrors()).length === 0,
          JSON.stringify(heavier.coin));
    await page.select('.control[data-path="coin.shape"] select', 'disk');
    await settled();
    const back = await ranScene();
    check('back to a disk, I_X and I_Z leave the scene and their controls hide', back.coin.I_X === undefined && back.coin.I_Z === undefined &&
          (await control('coin.I_X')).hidden && (await shownErrors()).length === 0, JSON.stringify(back.coin));
  });

  // Flight: its group says what brings it; friction and sliding bring the flight box, which brings
  // restitution (filled: flight needs it), impact friction, the height and the vertical velocity; a
  // toss from a height runs; the coin toss example shows its values there; sliding off takes them out.
  await part('flight', async () => {
    await runSceneText(await hook('defaultScene'));
    const flightKeys = ['flight', 'restitution', 'impact_friction', 'initial.y', 'initial.v_y'];
    const hint = await page.$$eval('fieldset', (sets) => sets.filter((f) => f.querySelector('legend').textContent === 'Flight')
      .map((f) => [...f.querySelectorAll('.hint')].filter((h) => !h.hidden).map((h) => h.textContent).join('')));
    check('a Flight group, which without sliding says what shows it', hint.length === 1 && /friction.*sliding/.test(hint[0]) &&
          (await control('flight')) !== null && (await control('flight')).hidden, JSON.stringify(hint));
    await page.click('.control[data-path="friction"] input[type=checkbox]');
    await settled();
    await page.click('.control[data-path="sliding"] input[type=checkbox]');
    await settled();
    check('with friction and sliding the flight box shows, its settings not yet', !(await control('flight')).hidden &&
          (await Promise.all(flightKeys.slice(1).map(control))).every((c) => c.hidden));
    await page.click('.control[data-path="flight"] input[type=checkbox]');
    await settled();
    const flying = await ranScene();
    const shown = await Promise.all(flightKeys.map(control));
    check('ticking flight runs, with restitution filled, and shows the flight keys', flying.flight === true && flying.restitution === 0.5 &&
          shown.every((c) => !c.hidden) && (await shownErrors()).length === 0 && (await page.$eval('#scene-error', (e) => e.textContent)) === '',
          JSON.stringify({ flight: flying.flight, restitution: flying.restitution, errors: await shownErrors() }));
    await page.click('.control[data-path="initial.y"] input[type=checkbox]');
    await settled();
    const tossed = await ranScene(), start = await hook('stateAt', 0);
    check('a height ticked starts the coin in the air', tossed.initial.y > 0 && Math.abs(start.y - tossed.initial.y) < 1e-12 &&
          (await shownErrors()).length === 0, `initial.y ${tossed.initial.y}, the page's y at 0: ${start.y}`);
    await page.click('.control[data-path="sliding"] input[type=checkbox]');
    await settled();
    const grounded = await ranScene();
    check('sliding off takes flight and its keys out of the scene, and runs', flightKeys.every((k) => (k.startsWith('initial.') ? grounded.initial[k.slice(8)] : grounded[k]) === undefined) &&
          (await shownErrors()).length === 0 && (await page.$eval('#scene-error', (e) => e.textContent)) === '', JSON.stringify(grounded));
    await page.select('#example', 'coin_toss');
    await settled();
    const toss = await Promise.all(flightKeys.map(control));
    check('the coin toss shows its flight keys: flight on, restitution 0.4, y 0.3, v_y 1.2', toss[0].checked && toss[1].box === '0.4' &&
          toss[3].box === '0.3' && toss[4].box === '1.2' && toss.every((c) => !c.hidden), JSON.stringify(toss.map((c) => [c.checked, c.box])));
  });

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
  // The page plays by the clip's own clock (the core's visual track plans it as `render --plan` does):
  // each frame's rate is coinroll render's to the WebAssembly's round-off: 1e-11 of the rate (the rates
  // follow the motion, which the module computes to libm's last bits), 1e-10 in the landing's last tenth
  // of a second, whose singularity amplifies it (1.6e-11 seen; a port of the rule was 1.2 % off there).
  let worstRate = { error: 0 };
  for (const [from, to, tolerance] of [[50, 50.02, 1e-11], [110, 110.02, 1e-11], [117.1, 117.12, 1e-10]]) {
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
  // .impact): each frame's rate as coinroll render chose it, to round-off.
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
    const error = Math.abs(rate / expected - 1) / 1e-12;
    if (!(error <= worstToss.error)) worstToss = { error, detail: `t = ${tossFrames.sim_time_s[k]} s: page ${rate}, coinroll render ${expected}` };
  }
  check('playback slows down in the air and at each impact as coinroll render does', worstToss.error <= 1 &&
        tossFrames.playback_rate.some((r) => Math.abs(r - 0.05) < 1e-3), `worst ${worstToss.error.toFixed(2)} of the tolerance, ${worstToss.detail}`);

  // The steady-motion panel: for the run on screen, every number it shows is `coinroll steady`'s for
  // the same scene and request, and a motion's button starts that motion.
  const steadyPanel = () => page.evaluate(() => ({
    coin: Object.fromEntries([...document.querySelectorAll('.steady-coin [data-quantity]')].map((e) => [e.dataset.quantity, e.textContent])),
    coinUnits: Object.fromEntries([...document.querySelectorAll('.steady-coin [data-quantity]')]
      .map((e) => [e.dataset.quantity, e.dataset.unit])),
    cards: [...document.querySelectorAll('.steady-motion')].map((card) => ({
      request: JSON.parse(card.dataset.request || 'null'), branch: card.dataset.branch,
      verdict: card.querySelector('.verdict').textContent,
      error: card.querySelector('.steady-refusal').textContent.replace(/^No such motion here: /, ''),
      disabled: card.querySelector('button').disabled,
      numbers: Object.fromEntries([...card.querySelectorAll('dl [data-quantity]')].map((e) => [e.dataset.quantity, e.textContent])),
      units: Object.fromEntries([...card.querySelectorAll('dl [data-quantity]')]
        .map((e) => [e.dataset.quantity, e.dataset.unit])),
    })),
  }));
  const kCardQuantities = ['theta', 'omega_Z', 'omega_Y', 'K', 'precessionRate', 'spinRate', 'radiusCentreOfMass', 'radiusContact',
                           'N', 'F', 'frictionNeeded', 'rate', 'time'];
  async function compareSteadyPanel(label) {
    const ran = await hook('run'), panel = await steadyPanel();
    const mismatches = [];
    let compared = 0, identical = 0;
    for (const card of panel.cards) {
      const name = `${card.request.kind}${card.branch}`;
      const program = steadyReport(ran.text, card.request);
      if (program.error || card.error) {
        if (program.error !== card.error || !card.disabled) mismatches.push(`${name}: page refuses "${card.error}", coinroll "${program.error}"`);
        continue;
      }
      if (card.verdict !== program.numbers.verdict) mismatches.push(`${name}: verdict ${card.verdict}, coinroll ${program.numbers.verdict}`);
      const missing = kCardQuantities.filter((q) => card.numbers[q] === undefined);
      if (missing.length) mismatches.push(`${name}: the panel shows no ${missing.join(', ')}`);
      for (const [quantity, shown] of Object.entries(Object.assign({}, panel.coin, card.numbers))) {
        ++compared;
        if (program.numbers[quantity] === undefined) mismatches.push(`${name}: ${quantity} ${shown}, not in coinroll steady's output`);
        else if (!agreesToShownDigits(shown, program.numbers[quantity])) mismatches.push(`${name}: ${quantity} ${shown}, coinroll ${program.numbers[quantity]}`);
        else if (shown.replace('∞', 'inf') === program.numbers[quantity] || Number(shown) === Number(program.numbers[quantity])) ++identical;
      }
    }
    check(`${label}: the steady panel shows coinroll steady's numbers, every one to its digits (${compared} compared, ${identical} identical)`,
          mismatches.length === 0 && compared > 40, mismatches.slice(0, 6).join('; '));
    return panel;
  }
  await part('steady motions', async () => {
    await runSceneText(await hook('defaultScene'));
    const before = await compareSteadyPanel('the default scene');
    const ranTheta = JSON.parse((await hook('run')).text).initial.theta;
    check('the steady panel takes the run\'s tilt', before.cards.filter((c) => c.request.theta !== undefined).every((c) => c.request.theta === ranTheta),
          JSON.stringify(before.cards.map((c) => c.request)));
    await keyOn('.control[data-path="initial.theta"] input[type=range]', 'ArrowRight');
    const tilted = await compareSteadyPanel('after the theta slider');
    const newTheta = JSON.parse((await hook('run')).text).initial.theta;
    check('the steady panel follows a tilt change', newTheta !== ranTheta && tilted.cards[1].request.theta === newTheta,
          `${ranTheta} -> ${newTheta}, panel ${tilted.cards[1].request.theta}`);
    await page.click('.control[data-path="coin.thickness"] input[type=checkbox]');
    await settled();
    const thick = await compareSteadyPanel('a coin with thickness');
    check('the steady panel follows a coin change', thick.coin.I_X !== tilted.coin.I_X, `I_X ${tilted.coin.I_X} -> ${thick.coin.I_X}`);

    // With friction 0.5 the f- circle, which needs mu >= 20 or so, does not exist: the panel says so
    // in the program's words, and offers no button for it.
    await page.click('.control[data-path="friction"] input[type=checkbox]');
    await settled();
    const rough = await compareSteadyPanel('with friction');
    const refused = rough.cards.filter((c) => c.error);
    check('with friction 0.5 the f- circle is refused as coinroll steady refuses it, its button disabled',
          refused.length === 1 && refused[0].branch === '-' && refused[0].disabled && /needs friction/.test(refused[0].error) &&
          (await shownErrors()).length === 0, JSON.stringify(refused));
    await page.click('.control[data-path="friction"] input[type=checkbox]');
    await settled();

    // circle on the f- root: the button starts it, as the start menu would with the branch set.
    const card = thick.cards.find((c) => c.request.kind === 'circle' && c.branch === '-');
    await page.click('.steady-motion[data-kind="circle"][data-branch="-"] button');
    await settled();
    const started = await hook('run');
    const initial = JSON.parse(started.text).initial;
    check('circle f-\'s button runs that steady start', JSON.stringify(initial) === JSON.stringify(Object.assign({ steady: 'circle' }, card.request, { kind: undefined })) &&
          (await page.$eval('.control[data-path="initial[steady].steady"] select', (e) => e.value)) === 'circle' && (await shownErrors()).length === 0,
          JSON.stringify(initial));
    const start = await hook('stateAt', 0);
    check('the started run begins in the panel\'s steady state (omega_Y, omega_Z)', agreesToShownDigits(card.numbers.omega_Y, String(start.omega_Y)) &&
          agreesToShownDigits(card.numbers.omega_Z, String(start.omega_Z)), `panel ${card.numbers.omega_Y}, ${card.numbers.omega_Z}; run ${start.omega_Y}, ${start.omega_Z}`);
    const startedCsv = simulate(started.text, started.sampleDt);
    await compareWithCsv('the started steady circle', startedCsv, [0, Math.floor(startedCsv.rows / 2), startedCsv.rows - 1]);
    await compareSteadyPanel('the started steady circle');
  });

  // The wobble a student can watch: a steady circle tapped (tilt rate sqrt K times 1 degree) wobbles
  // at the period the panel predicts (2 pi / sqrt K) to second order in the tap, and the page's
  // measured period is the one the tilt's maxima in `coinroll simulate`'s CSV of the same start give.
  await part('the nudged wobble', async () => {
    await page.select('#example', 'steady_circle');
    await settled();
    const card = (await steadyPanel()).cards.find((c) => c.request.kind === 'circle' && c.branch === '+');
    await page.click('.steady-motion[data-kind="circle"][data-branch="+"] button.nudge');
    await new Promise((r) => setTimeout(r, 50));
    await settled();
    const nudged = await hook('run');
    const initial = JSON.parse(nudged.text).initial;
    const wobble = await page.$eval('.wobble', (e) => ({
      hidden: e.hidden, text: e.textContent,
      numbers: Object.fromEntries([...e.querySelectorAll('[data-quantity]')].map((n) => [n.dataset.quantity, Number(n.textContent)])),
    }));
    const tap = Math.sqrt(Number(card.numbers.K)) * Math.PI / 180;
    check('the nudge starts the motion with its tilt rate sqrt(K) x 1 degree', !wobble.hidden &&
          agreesToShownDigits(card.numbers.theta, String(initial.theta)) && Math.abs(initial.omega_X / tap - 1) < 1e-6 &&
          agreesToShownDigits(card.numbers.omega_Y, String(initial.omega_Y)) && agreesToShownDigits(card.numbers.omega_Z, String(initial.omega_Z)),
          `${JSON.stringify(initial)} against the panel's ${JSON.stringify(card.numbers)}`);
    const predicted = Number(card.numbers.time);
    const { measuredPeriod: measured, predictedPeriod } = wobble.numbers;
    check('the tapped circle wobbles at the predicted period to 0.3 % (1 degree each way)', predictedPeriod === predicted &&
          Math.abs(measured / predicted - 1) < 3e-3, wobble.text);
    const fine = simulate(nudged.text, 1e-3);
    const { t, theta } = fine.columns, maxima = [];
    for (let i = 1; i + 1 < fine.rows; ++i) {
      if (!(theta[i] > theta[i - 1] && theta[i] >= theta[i + 1])) continue;
      const curvature = theta[i - 1] - 2 * theta[i] + theta[i + 1];
      maxima.push(t[i] + 0.5 * (theta[i - 1] - theta[i + 1]) / curvature * (t[i + 1] - t[i]));
    }
    const fromCsv = (maxima[maxima.length - 1] - maxima[0]) / (maxima.length - 1);
    check('the page\'s measured period is the CSV\'s (tilt maxima at 1 ms rows) to 1e-3', Math.abs(measured / fromCsv - 1) < 1e-3,
          `page ${measured} s, CSV ${fromCsv} s over ${maxima.length - 1} wobbles`);
  });

  // The seed's units (M = a = g = 1, docs/web.md "Units"): the switch shows the steady panel, the
  // controls and the overlay in them, each number the program's SI one over its unit's size, runs
  // nothing, and a number typed or slid in them reaches the core in SI.
  await part('the seed\'s units', async () => {
    await runSceneText(await hook('defaultScene'));
    const ran = await hook('run'), scene = JSON.parse(ran.text);
    const gravity = JSON.parse(coinroll(['schema']).stdout).keys.find((k) => k.path === 'gravity').default;
    const M = scene.coin.mass, a = scene.coin.radius, g = scene.gravity !== undefined ? scene.gravity : gravity;
    const rate = Math.sqrt(g / a);
    // Each unit's size in SI, written out here rather than read from the page; SI's own are 1.
    const sizes = { 'M': M, 'a': a, '√(a/g)': 1 / rate, '√(g/a)': rate, 'g/a': g / a, 'Ma²': M * a * a, 'Mg': M * g,
                    'kg': 1, 'm': 1, 'm/s²': 1, 'rad/s': 1, '°': 1, '': 1 };
    const criticalSpin = () => page.$eval('.steady-coin [data-quantity="criticalSpin"]',
                                          (e) => ({ text: e.textContent, unit: e.dataset.unit }));
    const unitOf = (path) => page.$eval(`.control[data-path="${path}"] .unit`, (e) => e.textContent);
    const si = await criticalSpin();
    check('in SI the steady panel shows the thin disk\'s ω_c = √(g/a)/√3 in rad/s', si.unit === 'rad/s' &&
          agreesToShownDigits(si.text, String(rate / Math.sqrt(3))), `${si.text} ${si.unit}`);
    await page.click('input[name=units][value=seed]');
    const seed = await criticalSpin();
    check('in the seed\'s units the steady panel shows the thin disk\'s ω_c = 1/√3 = 0.577 √(g/a)',
          seed.unit === '√(g/a)' && Number(seed.text).toFixed(3) === '0.577' &&
          agreesToShownDigits(seed.text, String(1 / Math.sqrt(3))), `${seed.text} ${seed.unit}`);
    check('the switch runs nothing: the scene stays as it ran, in SI', (await hook('run')).text === ran.text &&
          (await page.$eval('#scene-text', (e) => e.value)) === ran.text);

    // Every number of the panel, times its unit's size, is coinroll steady's (one unit of the last
    // digit of each apart at most), and the motions' own are in the seed's units.
    const panel = await steadyPanel(), mismatches = [];
    const lastDigit = (text) => {
      const [mantissa, exponent = '0'] = text.split('e');
      return Math.pow(10, Number(exponent) - (mantissa.includes('.') ? mantissa.split('.')[1].length : 0));
    };
    const agrees = (text, size, printed) => (text === '∞' ? printed === 'inf'
      : Math.abs(Number(text) * size - Number(printed)) <= (lastDigit(text) * size + lastDigit(printed)) * (1 + 1e-9));
    const kSeedUnits = {
      I_X: 'Ma²', I_Z: 'Ma²', criticalSpin: '√(g/a)', omega_Z: '√(g/a)', omega_Y: '√(g/a)', K: 'g/a',
      precessionRate: '√(g/a)', spinRate: '√(g/a)', radiusCentreOfMass: 'a', radiusContact: 'a', N: 'Mg', F: 'Mg',
      rate: '√(g/a)', time: '√(a/g)',
    };
    let compared = 0;
    for (const card of panel.cards) {
      const program = steadyReport(ran.text, card.request);
      if (program.error) continue;
      const shown = Object.assign({}, panel.coin, card.numbers), units = Object.assign({}, panel.coinUnits, card.units);
      for (const [quantity, text] of Object.entries(shown)) {
        const unit = units[quantity], size = sizes[unit];
        const printed = program.numbers[quantity === 'criticalSpinSI' ? 'criticalSpin' : quantity];
        ++compared;
        const name = `${card.request.kind}${card.branch} ${quantity}`;
        if (kSeedUnits[quantity] !== undefined && unit !== kSeedUnits[quantity]) mismatches.push(`${name} in ${unit}`);
        else if (printed === undefined || size === undefined || !agrees(text, size, printed)) {
          mismatches.push(`${name}: ${text} ${unit} (${Number(text) * size} in SI), coinroll ${printed}`);
        }
      }
    }
    check(`in the seed's units every steady-panel number is coinroll steady's over its unit (${compared} compared)`,
          mismatches.length === 0 && compared > 40, mismatches.slice(0, 6).join('; '));

    const omegaZ = await control('initial.omega_Z');
    const unitPaths = ['initial.omega_Z', 'initial.x', 'duration', 'coin.radius', 'coin.mass', 'gravity'];
    const shownUnits = await Promise.all(unitPaths.map(unitOf));
    check('the controls show rates in √(g/a), lengths in a, times in √(a/g), M, a and g in SI, and ω_Z as ω_Z / √(g/a)',
          shownUnits.join(' ') === '√(g/a) a √(a/g) m kg m/s²' &&
          agreesToShownDigits(omegaZ.box, String(scene.initial.omega_Z / rate)),
          `units ${shownUnits.join(', ')}; ω_Z box ${omegaZ.box}`);
    const hud = (await hook('seek', 1)).split('\n'), state = await hook('stateAt', 1);
    const numberIn = (line) => Number(((line || '').match(/-?\d+\.\d+/) || [])[0]);
    const timeText = await page.$eval('#time-text', (e) => e.textContent);
    check('the overlay and the time readout show t in √(a/g), ω_Z in √(g/a) and E in Mga',
          hud[0].endsWith(' √(a/g)') && Math.abs(numberIn(hud[0]) - rate) <= 5e-4 + 1e-9 &&
          hud[3].includes(' √(g/a) ') && Math.abs(numberIn(hud[3]) - state.omega_Z / rate) <= 5e-4 + 1e-9 &&
          hud[4].endsWith(' Mga') && Math.abs(numberIn(hud[4]) - state.energy / (M * g * a)) <= 5e-6 + 1e-9 &&
          timeText.endsWith(' √(a/g)') && Math.abs(numberIn(timeText) - rate) <= 5e-4 + 1e-9,
          `${hud.join(' | ')}; ${timeText}`);

    await page.click('.control[data-path="initial.omega_Z"] input[type=number]', { clickCount: 3 });
    await page.keyboard.type('2');
    await page.keyboard.press('Enter');
    await settled();
    const typed = await ranScene();
    check('ω_Z = 2 typed in the seed\'s units runs the scene with ω_Z = 2 √(g/a) rad/s',
          Math.abs(typed.initial.omega_Z / (2 * rate) - 1) <= 1e-12 && (await control('initial.omega_Z')).box === '2' &&
          (await shownErrors()).length === 0, `initial.omega_Z ${typed.initial.omega_Z}, 2 √(g/a) = ${2 * rate}`);
    await keyOn('.control[data-path="initial.omega_Z"] input[type=range]', 'ArrowRight');
    const slid = await ranScene(), slidBox = Number((await control('initial.omega_Z')).box);
    check('the ω_Z slider in the seed\'s units writes three digits of √(g/a), run as that many rad/s',
          slidBox > 2 && Number(slidBox.toPrecision(3)) === slidBox &&
          Math.abs(slid.initial.omega_Z / (slidBox * rate) - 1) <= 1e-12 &&
          (await shownErrors()).length === 0, `box ${slidBox}, initial.omega_Z ${slid.initial.omega_Z}`);

    await page.click('input[name=units][value=si]');
    const back = await control('initial.omega_Z');
    check('back in SI the panel, the controls and the overlay show SI', (await criticalSpin()).unit === 'rad/s' &&
          (await unitOf('initial.omega_Z')) === 'rad/s' && back.box === String(slid.initial.omega_Z) &&
          (await hook('seek', 1)).split('\n')[0].endsWith(' s'), `ω_Z box ${back.box}`);
  });

  // The legend says what the picture draws, and every control has a readable name and names its key.
  await part('the legend and the controls\' names', async () => {
    const legend = await page.$eval('#legend', (e) => ({ summary: e.querySelector('summary').textContent,
                                                         text: e.textContent })).catch(() => null);
    const kLegendWords = ['Trace', 'path of the contact point', 'orange-red', 'blue', 'slid', 'Marker', 'every 1 cm',
                          'every 10 cm', 'heads'];
    check('a legend names the trace (the contact point\'s path), its colours, the marker, the grid and the faces',
          legend !== null && legend.summary === 'Legend' && kLegendWords.every((words) => legend.text.includes(words)),
          legend && legend.text);
    const schemaUnits = new Map(JSON.parse(coinroll(['schema']).stdout).keys.map((k) => [k.path, k.unit]));
    const rows = await page.$$eval('.control', (all) => all.map((row) => ({
      path: row.dataset.path, title: row.title, name: row.querySelector('.name').textContent.trim(),
      unit: row.querySelector('.unit') && row.querySelector('.unit').textContent,
    })));
    const unnamed = rows.filter((r) => !r.title.startsWith(r.path) || r.name === '' || r.name.includes('_') ||
                                       (r.unit !== null && Boolean(schemaUnits.get(r.path)) !== Boolean(r.unit)));
    const names = Object.fromEntries(rows.map((r) => [r.path, r.name]));
    check(`every control (${rows.length}) has a name without the key's underscores, its unit, a tooltip naming the key`,
          rows.length > 30 && unnamed.length === 0 && names['initial.theta'] === 'tilt θ' &&
          names['initial.omega_Z'] === 'spin ωZ' && names['coin.radius'] === 'radius a',
          JSON.stringify(unnamed.slice(0, 4)));
  });

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

  // coinroll export for a course page: a title and a caption shown as text (markup and a "</script>" in
  // the caption shown literally, the page still alive), only the three controls chosen, the researcher's
  // details folded and one click away, and the page within an 800x600 iframe.
  const coursePage = join(scratch, 'course.html');
  const courseTitle = 'Rolling <i>straight</i> & steady';
  const courseCaption = 'Change the tilt, the spin and the friction: <b>bold</b> stays text, </script><!-- <script> too.';
  const courseControls = ['initial.theta', 'initial.omega_Z', 'friction'];
  await part('a page for a course', async () => {
    const wrote = spawnSync(options.binary, ['export', join(repo, 'examples/straight_stable.json'), '-o', coursePage, '-q',
                                             '--title', courseTitle, '--caption', courseCaption, '--controls', courseControls.join(',')],
                            { encoding: 'utf8', env: { ...process.env, COINROLL_PAGE: options.page } });
    check('coinroll export --title --caption --controls writes the page', wrote.status === 0 && existsSync(coursePage), wrote.stderr.trim());
    pagesOpened.add(pathToFileURL(coursePage).href);
    await page.setViewport({ width: 1280, height: 800 });
    await page.goto(pathToFileURL(coursePage).href);
    await page.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
    await settled();
    const shown = await page.evaluate(() => {
      // Drawn: a closed <details>'s content keeps its boxes, hidden by content-visibility.
      const visible = (e) => e.checkVisibility({ contentVisibilityAuto: true, visibilityProperty: true });
      return {
        title: document.title, heading: document.querySelector('h1').innerText.trim(),
        caption: document.getElementById('caption').textContent, captionTags: document.getElementById('caption').children.length,
        controls: [...document.querySelectorAll('.control')].filter(visible).map((row) => row.dataset.path),
        open: document.getElementById('researcher').open,
        boxVisible: visible(document.getElementById('scene-text')), logVisible: visible(document.getElementById('run-info')),
      };
    });
    const ran = await hook('run');
    check('the course page shows its title and caption as text, markup and "</script>" literally, and runs its scene',
          shown.title === courseTitle && shown.heading === courseTitle && shown.caption === courseCaption &&
          shown.captionTags === 0 && JSON.parse(ran.text).name === 'straight_stable', JSON.stringify(shown));
    check('the course page shows exactly the three controls chosen', JSON.stringify(shown.controls) === JSON.stringify(courseControls),
          shown.controls.join(', '));
    check('the researcher\'s details start folded, the scene box and the log hidden', !shown.open && !shown.boxVisible && !shown.logVisible,
          JSON.stringify(shown));
    await page.click('#researcher > summary');
    const opened = await page.evaluate(() => ({
      open: document.getElementById('researcher').open, box: document.getElementById('scene-text').checkVisibility(),
      log: document.getElementById('run-info').checkVisibility(),
      text: document.getElementById('scene-text').value,
    }));
    check('one click opens them: the scene file\'s box with the scene that runs, and the log', opened.open && opened.box &&
          opened.log && opened.text === ran.text, JSON.stringify({ ...opened, text: opened.text.slice(0, 40) }));
    const frameUrl = pathToFileURL(join(scratch, 'course_embedded.html')).href;
    writeFileSync(join(scratch, 'course_embedded.html'), '<!DOCTYPE html><title>course</title><body style="margin:0">' +
                  `<iframe src="${pathToFileURL(coursePage).href}" width="800" height="600" style="border:0"></iframe></body>`);
    pagesOpened.add(frameUrl);
    await page.setViewport({ width: 1000, height: 800 });
    await page.goto(frameUrl);
    const frame = page.frames().find((f) => f !== page.mainFrame());
    await frame.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
    await frame.evaluate(() => window.coinrollPage.settled());
    const inFrame = await frame.evaluate(() => {
      const outside = [...document.querySelectorAll('body *')].filter((e) => {
        const r = e.getBoundingClientRect();
        return r.width > 0 && r.height > 0 && (r.left < -0.5 || r.right > innerWidth + 0.5 || r.bottom > innerHeight + 0.5) &&
          e.checkVisibility() && !e.closest('#panel, #heading');  // those two scroll inside themselves
      }).map((e) => `${e.tagName.toLowerCase()}#${e.id} at ${JSON.stringify(e.getBoundingClientRect())}`);
      const { scrollWidth, scrollHeight } = document.documentElement;
      const heading = document.getElementById('heading').getBoundingClientRect();
      const view = document.getElementById('view').getBoundingClientRect();
      return { innerWidth, innerHeight, scrollWidth, scrollHeight, outside: outside.slice(0, 4),
               heading: [heading.bottom, heading.right], view: [view.width, view.height] };
    });
    check('the course page in an 800x600 iframe: nothing outside it, its heading in view, the view at least half its width',
          inFrame.innerWidth === 800 && inFrame.scrollWidth <= 800 && inFrame.scrollHeight <= 600 && inFrame.outside.length === 0 &&
          inFrame.heading[0] <= 600 && inFrame.heading[1] <= 800 && inFrame.view[0] >= 400, JSON.stringify(inFrame));
  });

  // The layout from a phone to a wide screen: nothing past the window's sides, the view as wide as a
  // phone (with the coin in it) and at least half of an 800 px iframe and of a 1600 px window, whose
  // pages fit their height (the panel scrolls).
  await part('layout', async () => {
    const measure = (frame) => frame.evaluate(() => {
      const outside = [...document.querySelectorAll('body *')].filter((e) => {
        const r = e.getBoundingClientRect();
        return r.width > 0 && r.height > 0 && (r.left < -0.5 || r.right > innerWidth + 0.5);
      }).map((e) => `${e.tagName.toLowerCase()}#${e.id}.${e.className} ends at ${e.getBoundingClientRect().right}`);
      const view = document.getElementById('view').getBoundingClientRect();
      const { scrollWidth, scrollHeight } = document.documentElement;
      const charts = [...document.querySelectorAll('.plot .uplot')].map((e) => e.getBoundingClientRect())
        .map((r) => [r.left, r.top, r.width].map(Math.round));
      return { innerWidth, innerHeight, scrollWidth, scrollHeight, outside: outside.slice(0, 4),
               view: [view.width, view.height], plots: { open: document.getElementById('plots').open, charts } };
    });
    const fits = (m) => m.scrollWidth <= m.innerWidth && m.outside.length === 0;
    const open = async (frame) => {
      await frame.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
      await frame.evaluate(() => window.coinrollPage.settled());
    };
    await page.setViewport({ width: 360, height: 740 });
    await page.goto(pageUrl);
    await open(page);
    const phone = await measure(page);
    check('at 360 px nothing lies past the window\'s sides, and the view is as wide as the window', fits(phone) &&
          phone.view[0] >= phone.innerWidth - 1 && phone.view[1] >= 200, JSON.stringify(phone));
    check('at 360 px the four plots are open, one above another, each at least 300 px wide', phone.plots.open &&
          phone.plots.charts.length === 4 && phone.plots.charts.every(([, top, width], k, all) => width >= 300 &&
          (k === 0 || top > all[k - 1][1])), JSON.stringify(phone.plots));
    // The default scene's camera frames its whole circle in the program's 16:9 picture, which the
    // phone's narrower view must not cut: the coin's centre mark is in the picture all round.
    await hook('showTestMarks', true);
    const times = Array.from({ length: 13 }, (_, k) => 0.5 * k), missed = [];
    for (const t of times) {
      await hook('seek', t);
      const shot = readPng(Buffer.from(await (await page.$('#canvas')).screenshot({ type: 'png' })));
      if (!centroid(shot, (r, g, b) => r > 200 && g < 60 && b > 200)) missed.push(t);
    }
    check('at 360 px the scene\'s camera keeps the coin in the picture all round its circle', missed.length === 0,
          missed.length ? `no coin at t = ${missed.join(', ')} s` : `in all ${times.length} pictures, 0 to 6 s`);
    await hook('showTestMarks', false);

    const frameUrl = pathToFileURL(join(scratch, 'embedded.html')).href;
    writeFileSync(join(scratch, 'embedded.html'), '<!DOCTYPE html><title>embedded</title><body style="margin:0">' +
                  `<iframe src="${pageUrl}" width="800" height="600" style="border:0"></iframe></body>`);
    pagesOpened.add(frameUrl);
    await page.setViewport({ width: 1000, height: 800 });
    await page.goto(frameUrl);
    const frame = page.frames().find((f) => f !== page.mainFrame());
    await open(frame);
    const embedded = await measure(frame);
    check('in an 800x600 iframe nothing lies past its sides or below it, and the view takes at least half its width',
          embedded.innerWidth === 800 && fits(embedded) && embedded.scrollHeight <= embedded.innerHeight &&
          embedded.view[0] >= 400,
          JSON.stringify(embedded));
    // The plots, closed there to leave the picture its height, opened: they scroll inside their section.
    await frame.evaluate(() => { document.getElementById('plots').open = true; });
    await new Promise((r) => setTimeout(r, 200));
    const opened = await measure(frame);
    check('in the 800x600 iframe the plots start closed, and opened they fit its width and height',
          !embedded.plots.open && opened.plots.charts.length === 4 && fits(opened) &&
          opened.scrollHeight <= opened.innerHeight && opened.view[1] >= 150, JSON.stringify(opened));

    await page.setViewport({ width: 1600, height: 900 });
    await page.goto(pageUrl);
    await open(page);
    const wide = await measure(page);
    check('at 1600 px nothing lies past the window, and the view takes at least half its width', fits(wide) &&
          wide.scrollHeight <= wide.innerHeight && wide.view[0] >= 800, JSON.stringify(wide));
    check('at 1600 px the four plots are open side by side under the view, the view keeping 60 % of the height',
          wide.plots.open && wide.plots.charts.length === 4 &&
          wide.plots.charts.every(([, top]) => top === wide.plots.charts[0][1]) &&
          wide.view[1] >= 0.6 * wide.innerHeight, JSON.stringify(wide.plots));
  });
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
