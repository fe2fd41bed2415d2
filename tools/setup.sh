#!/usr/bin/env bash
# Installs every Debian package coinroll needs to build, test, render and chart.
# Idempotent: skips apt entirely when everything is already installed (tools/apt_install.sh).
set -euo pipefail

packages=(
  cmake g++ pkg-config make
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
  slurm-wlm munge  # tests/slurm/slurm_test.py starts a one-node Slurm
)

exec "$(dirname "$0")/apt_install.sh" "${packages[@]}"
