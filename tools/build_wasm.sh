#!/usr/bin/env bash
# Builds coinroll's core as one JavaScript module with its WebAssembly inlined (docs/web.md):
#     tools/build_wasm.sh [BUILD_DIR]        (default build-wasm)
# and prints the module's path, BUILD_DIR/coinroll_core.js. The compiler is Debian's emscripten
# (tools/setup.sh installs it); JOBS sets the parallel compile jobs (default: every core).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-wasm}
if ! command -v emcmake >/dev/null; then
  echo "build_wasm.sh: emcmake not found; install Debian's emscripten (tools/setup.sh)" >&2
  exit 1
fi
# Debian's emscripten runs its JavaScript optimizer under the system's node, which finds the acorn
# parser (Debian's node-acorn) only in Debian's module folder.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
emcmake cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
# Run from cmake --build's coinroll_page target this is a make's child that its jobserver does not
# reach (CMake 3.25's custom commands do not pass it on): its own make, with its own jobs.
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL cmake --build "$build" -j"${JOBS:-$(nproc)}" >&2
echo "$build/coinroll_core.js"
