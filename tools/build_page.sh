#!/usr/bin/env bash
# Builds the web page (docs/web.md "The page") beside the program, where `coinroll export` finds it:
#     tools/build_page.sh [BUILD_DIR]      (default build; the program must be built there)
# the WebAssembly core into BUILD_DIR/wasm, then the page into BUILD_DIR/web/coinroll.html, the
# same files ctest's web_page_build makes. Needs Debian's emscripten and web/node_modules
# (tools/setup.sh installs both).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
if [ ! -x "$build/coinroll" ]; then
  echo "build_page.sh: $build/coinroll not found; build the program first (cmake -B $build && cmake --build $build)" >&2
  exit 1
fi
core=$(tools/build_wasm.sh "$build/wasm")
node web/build.mjs --core "$core" --coinroll "$build/coinroll" --out "$build/web/coinroll.html"
