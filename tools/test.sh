#!/usr/bin/env bash
# Sets up, builds and runs every test (the README's second Quick start command).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
cmake -B build
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
