#!/usr/bin/env bash
# Makes every figure in docs/ from the built program, so the README's pictures are the program's
# (docs/usage.md "Examples"). ctest figures_reproducible runs the quick set into a scratch folder
# and compares each picture with the one in docs/.
#
#   tools/make_figures.sh [--quick] [--coinroll BIN] [OUT_DIR]     (defaults: all, build/coinroll, docs/)
#
# --quick leaves out the two slow sets: the stability maps (thousands of runs, minutes) and the
# spectrograms (the 138 s Euler's-disk clip is rendered whole for its sound). The work-precision
# charts and the anti-aliasing chart are drawn from the benchmark tables in docs/data/ (timings:
# build/bench/work_precision, build/bench/stability and build/bench/antialias_quality measure them anew).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
quick=0
coinroll=$root/build/coinroll
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --coinroll) coinroll=$(realpath "$2"); shift 2 ;;
    -h|--help) sed -n 2,11p "$0"; exit 0 ;;
    -*) echo "make_figures.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) break ;;
  esac
done
out=$(realpath -m "${1:-$root/docs}")
mkdir -p "$out"
python=/usr/bin/python3
cd "$root"

step() { echo "make_figures: $*" >&2; }

step "gallery.png"
$python tools/make_gallery.py --coinroll "$coinroll" --output "$out/gallery.png"

step "euler_disk_last_second.png (docs/physics.md's strobe command: six panels)"
"$coinroll" still examples/euler_disk.json --time 117.18 --strobe 5 --strobe-from 116.18 --panels \
  --set 'render.camera.eye=[0.16,0.003,0]' --set render.camera.fov=18 \
  --set render.width=480 --set render.height=270 -o "$out/euler_disk_last_second.png"

step "toss_arc.png (docs/toss.md: the toss's arc, 21 copies 25 ms apart, seen from the side)"
"$coinroll" still examples/coin_toss.json --time 0.5 --strobe 20 --strobe-from 0 --set render.hud=false \
  --set render.camera.mode=fixed --set 'render.camera.eye=[0.03,0.17,0.75]' --set 'render.camera.target=[0.03,0.17,0]' \
  --set render.camera.fov=40 --set render.width=720 --set render.height=720 -o "$out/toss_arc.png"

step "spin_down.png, energy_budget.png"
$python tools/plot_spin_down.py "$coinroll" --out-dir "$out" >/dev/null

step "work_precision.png, stability.png (from the benchmark tables)"
$python tools/plot_work_precision.py "$out" >/dev/null

step "antialias_quality.png (from build/bench/antialias_quality's table)"
$python tools/plot_antialias_quality.py "$out"

if [[ $quick == 0 ]]; then
  step "map_straight.png, map_circles.png, map_spin_down.png (minutes)"
  $python tools/plot_stability_maps.py "$coinroll" --out-dir "$out"
  step "spectrogram.png (renders the Euler's-disk clip whole: minutes)"
  $python tools/plot_spectrograms.py "$coinroll" --output "$out/spectrogram.png"
fi
step "done: $out"
