#!/usr/bin/env bash
# ctest's way into the WebAssembly core's tests (tests/web/CMakeLists.txt), skipped (exit 77),
# saying why, only where Emscripten is not installed:
#     run_wasm_test.sh build BUILD_DIR     builds the module into BUILD_DIR (tools/build_wasm.sh)
#     run_wasm_test.sh node ARGS...        runs tests/web/wasm_core_test.js ARGS...
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if ! command -v emcc >/dev/null; then
  echo "SKIP: emcc not found, so the WebAssembly core cannot be built (tools/setup.sh installs Debian's emscripten)"
  exit 77
fi
case ${1:-} in
  build) JOBS=${JOBS:-2} exec "$here/../../tools/build_wasm.sh" "$2" ;;
  node) shift; exec node "$here/wasm_core_test.js" "$@" ;;
  *) echo "usage: run_wasm_test.sh build BUILD_DIR | node ARGS..." >&2; exit 2 ;;
esac
