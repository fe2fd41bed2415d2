#!/usr/bin/env bash
# ctest's way into the page's tests (tests/web/CMakeLists.txt, docs/web.md "The page"), skipped
# (exit 77), saying why, only where what they need is not installed:
#     run_page_test.sh build ARGS...      builds the page: node web/build.mjs ARGS...
#     run_page_test.sh browser ARGS...    checks it in Chromium: node tests/web/page_test.mjs ARGS...
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
web=$here/../../web
if ! command -v emcc >/dev/null; then
  echo "SKIP: emcc not found, so the WebAssembly core the page holds cannot be built (tools/setup.sh installs Debian's emscripten)"
  exit 77
fi
if [ ! -d "$web/node_modules/esbuild" ] || [ ! -d "$web/node_modules/puppeteer-core" ]; then
  echo "SKIP: web/node_modules lacks esbuild or puppeteer-core (tools/setup.sh runs npm ci in web/)"
  exit 77
fi
case ${1:-} in
  build) shift; exec node "$web/build.mjs" "$@" ;;
  browser) shift; exec node "$here/page_test.mjs" "$@" ;;
  *) echo "usage: run_page_test.sh build ARGS... | browser ARGS..." >&2; exit 2 ;;
esac
