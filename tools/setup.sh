#!/usr/bin/env bash
# Installs every Debian package coinroll needs to build, test, render and chart, and the page's npm
# packages (web/package-lock.json) into web/node_modules.
# Idempotent: skips apt entirely when everything is already installed (tools/apt_install.sh), and
# npm when web/node_modules was installed from the same lockfile.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

packages=(
  cmake g++ pkg-config make
  clang-format-14  # the lint tier's layout check (tests/lint/check_format.py); another version lays code out otherwise
  libeigen3-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libosmesa6-dev libglm-dev libstb-dev zlib1g-dev
  fonts-dejavu-core  # the overlay font, embedded in the binary at build time (DejaVuSansMono.ttf)
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri  # EGL back ends: glvnd's libEGL, Mesa's vendor and its llvmpipe
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  ffmpeg
  libboost-dev libsundials-dev
  python3 python3-matplotlib python3-numpy python3-scipy python3-sympy
  python3-dev pybind11-dev python3-pybind11 python3-pytest  # the Python module (python/) and its tests
  parallel
  emscripten node-acorn  # the WebAssembly core (tools/build_wasm.sh, docs/web.md); acorn for em++'s JavaScript optimizer
  chromium  # the page's browser test (tests/web/page_test.mjs), driven by puppeteer-core without a browser download
  slurm-wlm munge  # tests/slurm/slurm_test.py starts a one-node Slurm
)

"$here/apt_install.sh" "${packages[@]}"

# The page's build (esbuild, three.js) and browser test (puppeteer-core): exactly the lockfile's
# versions. The stamp is the lockfile they were installed from.
web=$here/../web
if [ -f "$web/package-lock.json" ] && ! cmp -s "$web/package-lock.json" "$web/node_modules/.coinroll-lock"; then
  if command -v npm >/dev/null; then
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
    cp "$web/package-lock.json" "$web/node_modules/.coinroll-lock"
  else
    echo "setup.sh: npm not found: the page (web/) cannot be built and its tests skip" >&2
  fi
fi
