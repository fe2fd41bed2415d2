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
# Under make (cmake --build's coinroll_page target) the jobs are its jobserver's: a -j here would
# start as many again beside it.
if [[ "${MAKEFLAGS:-}" == *jobserver* ]]; then
  cmake --build "$build" >&2
else
  cmake --build "$build" -j"${JOBS:-$(nproc)}" >&2
fi
echo "$build/coinroll_core.js"
