#!/usr/bin/env node
// Builds the page (docs/web.md "The page") into ONE self-contained HTML file that opens from
// file:// with no network: the WebAssembly core, the page's script, the worker's script, the
// tree-shaken parts of three.js, uPlot and its stylesheet, the scene schema, the examples, the
// renderer's fragment shaders and the coin's face texture, all inlined.
//
//     node web/build.mjs [--core build-wasm/coinroll_core.js] [--coinroll build/coinroll]
//                        [--out build-web/coinroll.html]
//
// The schema is `coinroll schema`'s JSON, read at build time from the native program, so that the
// controls' ranges, defaults, units and tooltips are the loader's own, not a copy.
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import * as esbuild from 'esbuild';

const web = dirname(fileURLToPath(import.meta.url));
const repo = resolve(web, '..');

function parseArgs(argv) {
  const options = {
    core: join(repo, 'build-wasm/coinroll_core.js'),
    coinroll: join(repo, 'build/coinroll'),
    out: join(repo, 'build-web/coinroll.html'),
  };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!(key in options) || argv[i + 1] === undefined) {
      throw new Error(`build.mjs: unknown or incomplete option ${argv[i]}; the options are --core FILE, --coinroll FILE, --out FILE`);
    }
    options[key] = resolve(argv[i + 1]);
  }
  return options;
}

function readInput(path, what, how) {
  try {
    return readFileSync(path);
  } catch (e) {
    throw new Error(`build.mjs: cannot read ${what} ${path} (${e.code}); ${how}`);
  }
}

const options = parseArgs(process.argv.slice(2));
const coreFile = readInput(options.core, 'the WebAssembly core', 'build it with tools/build_wasm.sh, or name it with --core').toString();
// The module inlines its WebAssembly as base64 (-sSINGLE_FILE): 1.4 MB, which with three.js would
// pass the page's 2 MB. The page carries it gzipped instead (a third of the size) and the worker
// hands it to the module as wasmBinary; the module's own data URI is left empty, so it is still a
// data URI (nothing is fetched) and never decoded.
const payload = /(data:application\/octet-stream;base64,)([A-Za-z0-9+/=]{1000,})/g;
const payloads = [...coreFile.matchAll(payload)];
if (payloads.length !== 1) {
  throw new Error(`build.mjs: expected the core ${options.core} to inline its WebAssembly as one base64 data URI ` +
                  `(-sSINGLE_FILE), found ${payloads.length}; was it built by tools/build_wasm.sh?`);
}
const wasmGzipBase64 = gzipSync(Buffer.from(payloads[0][2], 'base64'), { level: 9 }).toString('base64');
const coreSource = coreFile.replace(payload, '$1');
let schemaText;
try {
  schemaText = execFileSync(options.coinroll, ['schema'], { encoding: 'utf8' });
} catch (e) {
  throw new Error(`build.mjs: \`${options.coinroll} schema\` failed (${e.message.split('\n')[0]}); build the program ` +
                  '(cmake --build build), or name it with --coinroll');
}
const examples = Object.fromEntries(readdirSync(join(repo, 'examples')).filter((f) => f.endsWith('.json')).sort()
  .map((f) => [f.replace(/\.json$/, ''), readFileSync(join(repo, 'examples', f), 'utf8')]));
// The renderer's fragment shaders (shaders/*.frag), which the page compiles as they are: GLSL 3.30's
// fragment stage and GLSL ES 3.00's agree on what they use, once the version line, which WebGL 2 sets
// itself, is dropped. The vertex stages differ (three.js names the attributes and matrices its own way).
const fragmentShaders = Object.fromEntries(['coin', 'floor', 'trace', 'flat'].map((name) => {
  const text = readInput(join(repo, `shaders/${name}.frag`), 'a shader', 'it is in the repository').toString();
  if (!text.startsWith('#version 330 core\n')) throw new Error(`build.mjs: shaders/${name}.frag does not start with #version 330 core`);
  return [name, text.slice('#version 330 core\n'.length)];
}));
const facePng = readInput(join(repo, 'assets/coin_face.png'), 'the coin face', 'it is in the repository').toString('base64');

// The page's own modules ask for these by name; esbuild resolves them here.
const inlined = {
  'inline:schema': `export default ${schemaText.trim()};`,
  'inline:examples': `export default ${JSON.stringify(examples)};`,
  'inline:shaders': `export default ${JSON.stringify(fragmentShaders)};`,
  'inline:face': `export default ${JSON.stringify(`data:image/png;base64,${facePng}`)};`,
  'inline:wasm': `export default ${JSON.stringify(wasmGzipBase64)};`,
};
const inlinePlugin = (extra) => ({
  name: 'inline',
  setup(build) {
    const all = Object.assign({}, inlined, extra);
    build.onResolve({ filter: /^inline:/ }, (args) => ({ path: args.path, namespace: 'inline' }));
    build.onLoad({ filter: /.*/, namespace: 'inline' }, (args) => {
      if (!(args.path in all)) throw new Error(`build.mjs: nothing inlined as ${args.path}`);
      return { contents: all[args.path], loader: 'js' };
    });
  },
});

const common = { bundle: true, minify: true, write: false, format: 'iife', target: 'es2020', legalComments: 'none', logLevel: 'warning' };
// The worker's script runs after the core's in one Blob (src/worker.js), so the core is never parsed
// twice nor held twice in the file.
const worker = await esbuild.build(Object.assign({}, common, { entryPoints: [join(web, 'src/worker.js')], plugins: [inlinePlugin({})] }));
const workerSource = worker.outputFiles[0].text;
const page = await esbuild.build(Object.assign({}, common, {
  entryPoints: [join(web, 'src/main.js')],
  plugins: [inlinePlugin({
    'inline:worker': `export const coreSource = ${JSON.stringify(coreSource)};\nexport const workerSource = ${JSON.stringify(workerSource)};`,
  })],
}));
// Inside a <script> element only "</script" ends it early; a JSON string may hold it.
const script = page.outputFiles[0].text.replace(/<\/(script)/gi, '<\\/$1');
// uPlot's own stylesheet first, so that the page's rules for the plots come after it.
const plotStyle = readFileSync(createRequire(join(web, 'package.json')).resolve('uplot/dist/uPlot.min.css'), 'utf8');
const style = `${plotStyle}\n${readFileSync(join(web, 'src/page.css'), 'utf8')}`;
const html = readFileSync(join(web, 'src/page.html'), 'utf8')
  .replace('/*STYLE*/', () => style)
  .replace('/*SCRIPT*/', () => script);
mkdirSync(dirname(options.out), { recursive: true });
writeFileSync(options.out, html);
const mb = (n) => (n / 1e6).toFixed(3);
console.log(`${options.out}: ${mb(html.length)} MB (the core's script ${mb(coreSource.length)} MB and its WebAssembly gzipped ` +
            `${mb(wasmGzipBase64.length)} MB in base64, the page's script, three.js, uPlot and fflate ` +
            `${mb(script.length - JSON.stringify(workerSource).length - JSON.stringify(coreSource).length -
                  wasmGzipBase64.length)} MB)`);
