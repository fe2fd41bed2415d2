#!/usr/bin/env node
// How long the WebAssembly core (tools/build_wasm.sh) takes against the native code on the same runs
// (docs/web.md "Speed"), alternating one run of each so that both see the same machine state:
//   - wasm: the module's simulateCsv in this Node process (scene text in, CSV text out);
//   - native, in process: build/bench/csv_run_timer, the same calls of `coinroll simulate` timed
//     inside a native process (the like-for-like figure: neither side's start is counted);
//   - native, the program: `coinroll simulate SCENE --csv -` as a process, start included (its
//     rendering and video libraries take tens of milliseconds to load; the module loads once).
// Prints a table of medians and the medians of the paired ratios, of wall time and, for the two
// in-process runs, of CPU time, which a loaded machine disturbs less.
//
// Run (csv_run_timer needs -DCOINROLL_BENCHMARKS=ON):
//   node bench/wasm_vs_native.js [--runs 11] [--module build-wasm/coinroll_core.js] [--build build]

'use strict';

const childProcess = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const kRepo = path.resolve(__dirname, '..');

function options() {
  const result = { runs: 11, module: path.join(kRepo, 'build-wasm', 'coinroll_core.js'), build: path.join(kRepo, 'build') };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!(key in result) || argv[i + 1] === undefined) {
      console.error('usage: wasm_vs_native.js [--runs N] [--module M.js] [--build BUILD_DIR]');
      process.exit(2);
    }
    result[key] = key === 'runs' ? Number(argv[i + 1]) : path.resolve(argv[i + 1]);
  }
  return result;
}

function seconds(start) {
  return Number(process.hrtime.bigint() - start) / 1e9;
}

function run(binary, args) {
  const start = process.hrtime.bigint();
  const r = childProcess.spawnSync(binary, args, { cwd: kRepo, maxBuffer: 1 << 30 });
  const elapsed = seconds(start);
  if (r.status !== 0) throw new Error(`${binary} ${args.join(' ')}: exit ${r.status}: ${r.stderr}`);
  return { elapsed, stdout: r.stdout.toString() };
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

async function main() {
  const { runs, module, build } = options();
  const program = path.join(build, 'coinroll');
  const timer = path.join(build, 'bench', 'csv_run_timer');
  const loadStart = process.hrtime.bigint();
  const core = await require(module)();
  const load = seconds(loadStart);

  const rows = [];
  for (const file of [null, 'examples/euler_disk.json']) {
    const name = file || 'built-in default scene';
    const bytes = file ? new Uint8Array(fs.readFileSync(path.join(kRepo, file))) : null;
    const wasmRun = () => core.simulateCsv(bytes, [], { sourceName: name });
    // Untimed, and a check that all three do the same run. V8 runs the module in a baseline tier
    // first and optimises its hot functions as they run: a second of runs before timing them.
    const count = wasmRun().rows;
    for (const warm = process.hrtime.bigint(); seconds(warm) < 1;) wasmRun();
    const timerRows = run(timer, file ? [file] : []).stdout.trim().split(' ')[2];
    const programRows = run(program, ['simulate', ...(file ? [file] : []), '--csv', '-']).stdout.split('\n').length - 2;
    if (Number(timerRows) !== count || programRows !== count) throw new Error(`${name}: the runs disagree on the rows`);

    const wasm = [], wasmCpu = [], inProcess = [], inProcessCpu = [], whole = [];
    for (let i = 0; i < runs; ++i) {
      const start = process.hrtime.bigint();
      const cpu = process.cpuUsage();
      wasmRun();
      const used = process.cpuUsage(cpu);
      wasm.push(seconds(start));
      wasmCpu.push((used.user + used.system) / 1e6);
      const [wall, timerCpu] = run(timer, file ? [file] : []).stdout.split(' ').map(Number);
      inProcess.push(wall);
      inProcessCpu.push(timerCpu);
      whole.push(run(program, ['simulate', ...(file ? [file] : []), '--csv', '-']).elapsed);
    }
    rows.push({ name, count, wasm, wasmCpu, inProcess, inProcessCpu, whole });
  }

  console.log(`WebAssembly core vs native: medians of ${runs} alternating runs (ms), load ${os.loadavg()[0].toFixed(1)} ` +
              `on ${os.cpus().length} cores; the module loads once, in ${(load * 1e3).toFixed(0)} ms`);
  const header = ['scene', 'rows', 'wasm', 'native in process', 'wasm / native in process', 'the same in CPU time',
                  'native program', 'wasm / native program'];
  console.log(`| ${header.join(' | ')} |\n|${header.map(() => '---|').join('')}`);
  for (const r of rows) {
    const paired = (mine, other) => median(mine.map((w, i) => w / other[i])).toFixed(2);
    const ms = (xs) => (median(xs) * 1e3).toFixed(1);
    console.log(`| ${r.name} | ${r.count} | ${ms(r.wasm)} | ${ms(r.inProcess)} | ${paired(r.wasm, r.inProcess)} | ` +
                `${paired(r.wasmCpu, r.inProcessCpu)} | ${ms(r.whole)} | ${paired(r.wasm, r.whole)} |`);
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
