#!/usr/bin/env node
// The page's speed in headless Chromium (docs/web.md "The page"), as a table (not a test):
//     node bench/page_bench.mjs [--page build/web/coinroll.html] [--chromium /usr/bin/chromium] [--runs 15]
// - page load (file://) to the first frame drawn of the default scene;
// - a slider move on the default 6 s scene: from the input event to the new run's first frame;
// - a burst of key presses on a slider: from the last press to its run's first frame;
// - the Euler's disk (examples/euler_disk.json) run to its landing in the worker;
// - playback at 1280x720 in software WebGL (SwiftShader): frames per second while playing, and
//   where a frame's time goes (each part of the picture left out in turn, every frame waited for).
// Needs `node web/build.mjs` (or ctest's web_page_build) and tools/setup.sh's npm ci in web/.
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { loadavg } from 'node:os';

const repo = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const options = { page: join(repo, 'build/web/coinroll.html'), chromium: '/usr/bin/chromium', runs: 15 };
for (let i = 2; i < process.argv.length; i += 2) {
  const key = process.argv[i].replace(/^--/, '');
  options[key] = key === 'runs' ? Number(process.argv[i + 1]) : resolve(process.argv[i + 1]);
}
const puppeteer = (await import(pathToFileURL(createRequire(join(repo, 'web/package.json')).resolve('puppeteer-core')))).default;
const browser = await puppeteer.launch({ executablePath: options.chromium, headless: true,
                                         args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
const url = pathToFileURL(options.page).href;
const median = (xs) => xs.slice().sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const p90 = (xs) => xs.slice().sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(0.9 * xs.length))];
const rows = [];
const row = (what, goal, measured, note = '') => rows.push([what, goal, measured, note]);

async function open(width, height) {
  const page = await browser.newPage();
  await page.setViewport({ width, height });
  await page.goto(url);
  await page.waitForFunction(() => window.coinrollPage && window.coinrollPage.run(), { timeout: 60000 });
  await page.evaluate(() => window.coinrollPage.settled());
  return page;
}

try {
  // Load to first frame: performance.now() counts from the navigation's start.
  const loads = [], ready = [];
  for (let i = 0; i < 5; ++i) {
    const page = await open(1700, 900);
    const timing = await page.evaluate(() => window.coinrollPage.timing());
    loads.push(timing.firstFrameAt);
    ready.push(timing.last.requestedAt);
    await page.close();
  }
  row('page load to first frame (file://)', '≤ 1000 ms', `${median(loads).toFixed(0)} ms`,
      `median of 5; the worker's core ready (the run requested) at ${median(ready).toFixed(0)} ms`);

  const page = await open(1700, 900);
  const moves = [], workerMs = [], resultMs = [];
  for (let i = 0; i < options.runs; ++i) {
    const timing = await page.evaluate(async (k) => {
      const slider = document.querySelector('.control[data-path="initial.theta"] input[type=range]');
      slider.value = String(Number(slider.value) + (k % 2 ? -5 : 5));
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      await window.coinrollPage.settled();
      return window.coinrollPage.timing().last;
    }, i);
    if (i < 2) continue;  // the first runs of a worker run in V8's baseline tier
    moves.push(timing.firstFrameAt - timing.requestedAt);
    workerMs.push(timing.workerMs);
    resultMs.push(timing.resultAt - timing.requestedAt);
  }
  row('slider move on the default 6 s scene to its first frame', '≤ 30 ms', `${median(moves).toFixed(1)} ms (p90 ${p90(moves).toFixed(1)})`,
      `median of ${moves.length}: the run in the worker ${median(workerMs).toFixed(1)} ms, its result back ${median(resultMs).toFixed(1)} ms, ` +
      'then drawn at once');

  // A burst of key presses, as a student holding an arrow key: 10 presses 30 ms apart on the tilt
  // slider; from the last press to the frame of its run (the page draws nothing older after it).
  await page.focus('.control[data-path="initial.theta"] input[type=range]');
  await page.evaluate(() => {
    window.benchKeys = [];
    document.addEventListener('keydown', () => window.benchKeys.push(performance.now()), true);
  });
  const bursts = [], burstRuns = [], spacings = [];
  for (let i = 0; i < options.runs; ++i) {
    await page.evaluate(async () => {
      await window.coinrollPage.settled();
      window.benchKeys = [];
    });
    // Not awaited one by one: a press's round trip to the browser takes longer than 30 ms.
    const presses = [];
    for (let k = 0; k < 10; ++k) {
      presses.push(page.keyboard.press(i % 2 ? 'ArrowLeft' : 'ArrowRight'));
      if (k < 9) await new Promise((r) => setTimeout(r, 30));
    }
    await Promise.all(presses);
    const { timing, keys } = await page.evaluate(async () => {
      await window.coinrollPage.settled();
      return { timing: window.coinrollPage.timing().last, keys: window.benchKeys };
    });
    bursts.push(timing.firstFrameAt - keys[keys.length - 1]);
    burstRuns.push(timing.workerMs);
    spacings.push((keys[keys.length - 1] - keys[0]) / (keys.length - 1));
  }
  row('a burst of 10 key presses 30 ms apart: the last press to its run drawn', '≤ 60 ms',
      `${median(bursts).toFixed(1)} ms (max ${Math.max(...bursts).toFixed(1)})`,
      `median of ${bursts.length} bursts, the presses ${median(spacings).toFixed(0)} ms apart in the page; ` +
      `the last run in the worker ${median(burstRuns).toFixed(1)} ms`);

  const euler = [], eulerTotal = [];
  for (let i = 0; i < 3; ++i) {
    const timing = await page.evaluate(async (k) => {
      const menu = document.getElementById('example');
      menu.value = k % 2 ? 'steady_circle' : 'euler_disk';
      menu.dispatchEvent(new Event('change'));
      await window.coinrollPage.settled();
      menu.value = 'euler_disk';
      menu.dispatchEvent(new Event('change'));
      await window.coinrollPage.settled();
      return window.coinrollPage.timing().last;
    }, i);
    euler.push(timing.workerMs);
    eulerTotal.push(timing.firstFrameAt - timing.requestedAt);
  }
  row("Euler's disk to its landing (117 s, 11 719 rows) in the worker", '≤ 500 ms', `${median(euler).toFixed(0)} ms`,
      `median of 3; to its first frame ${median(eulerTotal).toFixed(0)} ms`);

  // Playback of the default scene at 1280x720.
  await page.evaluate(() => {
    const menu = document.getElementById('example');
    document.getElementById('scene-text').value = window.coinrollPage.defaultScene();
    document.getElementById('run-text').click();
    menu.value = '';
  });
  await page.evaluate(() => window.coinrollPage.settled());
  await page.evaluate(() => window.coinrollPage.setViewSize(1280, 720));
  const fps = await page.evaluate(async () => {
    document.getElementById('play').click();
    if (!window.coinrollPage.playing()) document.getElementById('play').click();
    let frames = 0;
    const count = () => { ++frames; requestAnimationFrame(count); };
    requestAnimationFrame(count);
    await new Promise((r) => setTimeout(r, 1000));
    const start = performance.now(), f0 = frames;
    await new Promise((r) => setTimeout(r, 5000));
    return (frames - f0) / ((performance.now() - start) / 1000);
  });
  const profile = await page.evaluate(() => window.coinrollPage.profile(30));
  row('playback at 1280x720, software WebGL (SwiftShader)', '60 fps', `${fps.toFixed(1)} fps`,
      'a frame drawn and waited for: ' + Object.entries(profile).map(([k, v]) => `${k} ${v.toFixed(1)} ms`).join(', '));
} finally {
  await browser.close();
}
console.log(`load average ${loadavg().map((l) => l.toFixed(1)).join(' ')}, ${new Date().toISOString()}\n`);
console.log('| what | goal | measured | how |\n|---|---|---|---|');
for (const r of rows) console.log(`| ${r.join(' | ')} |`);
