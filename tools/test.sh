#!/usr/bin/env bash
# Sets up, builds and runs every test (the README's second Quick start command), fastest tier first
# so a broken library fails in seconds: the in-process unit tests, then the program run from
# outside (cli, slow, SymPy derivations, layering), then what the README and docs promise.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
cmake -B build
cmake --build build -j"$(nproc)"
tier() {
  local name=$1
  shift
  local start=$SECONDS
  ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
  echo "test.sh: $name tier took $((SECONDS - start)) s" >&2
}
tier unit -L '^unit$'
tier "cli, slow, derivations and lint" -LE '^(unit|docs)$'
tier docs -L '^docs$'
