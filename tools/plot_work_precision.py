#!/usr/bin/python3
"""Charts of the integrator benchmarks (Debian's matplotlib; run with /usr/bin/python3).

Reads the CSV files in docs/data/ written by build/bench/work_precision, build/bench/stability and
(if run) tools/scipy_peer.py, and writes
  docs/work_precision.png  relative state error at t_end against wall time, log-log, one panel
                           per case, one line per method; peers dashed
  docs/stability.png       RK4's and explicit Euler's largest stable step against spin, and the
                           energy error against time over 10^4 wobble periods

Usage: tools/plot_work_precision.py [OUT_DIR]   (default: docs/ beside this script's folder)
"""

import csv
import math
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

CASE_TITLES = {
    "straight": "straight roll, 1.5 x critical spin, 100 natural times",
    "circle50": "steady circle (kicked 0.01 rad), 50 periods",
    "flat_spin": "near flat: rolling on the rim at 80 deg, 50 periods",
    "wobble1000": "wobbling coin, t = 0..1000 natural units",
}


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def plot_work_precision(data, docs):
    rows = read_rows(data / "work_precision.csv")
    scipy_rows = data / "work_precision_scipy.csv"  # written by tools/scipy_peer.py, if run
    if scipy_rows.exists():
        rows += read_rows(scipy_rows)
    lines = defaultdict(list)  # (case, method) -> [(seconds, error)]
    peers = set()
    for row in rows:
        error, seconds = float(row["rel_error"]), float(row["seconds"])
        if not (math.isfinite(error) and error > 0 and seconds > 0):
            continue  # a blown-up or failed run has no place on a log-log chart
        lines[(row["case"], row["method"])].append((seconds, error))
        if row["is_peer"] == "1":
            peers.add(row["method"])
    cases = [c for c in CASE_TITLES if any(key[0] == c for key in lines)]
    methods = sorted({key[1] for key in lines}, key=lambda m: (m in peers, m))
    colours = {m: plt.cm.tab10(i % 10) for i, m in enumerate(methods)}
    figure, axes = plt.subplots(2, 2, figsize=(13, 10), sharex=False, sharey=True)
    for ax, case in zip(axes.flat, cases):
        for method in methods:
            points = sorted(lines.get((case, method), []))
            if not points:
                continue
            ax.loglog([p[0] for p in points], [p[1] for p in points], marker="o", markersize=3,
                      linestyle="--" if method in peers else "-", color=colours[method], label=method)
        ax.set_title(CASE_TITLES[case], fontsize=10)
        ax.set_xlabel("wall time per run [s]")
        ax.set_ylabel("relative state error at t_end")
        ax.set_ylim(1e-14, 1)
        ax.grid(True, which="major", alpha=0.3)
    axes.flat[0].legend(fontsize=8, loc="lower left")
    figure.suptitle("Work-precision on the rolling coin (ours solid, peers dashed; the C++ peers on the same RHS "
                    "in the same run, scipy from Python)")
    figure.tight_layout()
    figure.savefig(docs / "work_precision.png", dpi=90)


def plot_stability(data, docs):
    steps = read_rows(data / "stability_steps.csv")
    energy = read_rows(data / "stability_energy.csv")
    figure, (left, right) = plt.subplots(1, 2, figsize=(13, 5))
    by_method = defaultdict(list)
    limit = {}
    for row in steps:
        spin = float(row["spin_natural"])
        by_method[row["method"]].append((spin, float(row["largest_stable_dt"])))
        limit[spin] = float(row["rk4_linear_limit"])
    for method, points in sorted(by_method.items()):
        points.sort()
        left.loglog([p[0] for p in points], [p[1] for p in points], marker="o", label=f"{method} (measured)")
    spins = sorted(limit)
    left.loglog(spins, [limit[s] for s in spins], "k--", label="RK4 linear limit 2√2 / √K")
    left.set_xlabel("spin ω_Z of the 20° steady circle [√(g/a)]")
    left.set_ylabel("largest step with |ΔE/E| < 1e-2 over 100 wobbles [s]")
    left.set_title("Largest stable step against spin")
    left.grid(True, which="major", alpha=0.3)
    left.legend(fontsize=9)
    histories = defaultdict(list)
    for row in energy:
        histories[row["method"]].append((float(row["periods"]), float(row["energy_error"])))
    for label, points in histories.items():
        points = [p for p in points if p[1] > 0 and math.isfinite(p[1])]
        right.loglog([p[0] for p in points], [p[1] for p in points], label=label)
    right.set_xlabel("simulated time [wobble periods]")
    right.set_ylabel("relative energy error |ΔE/E|")
    right.set_title("Energy error over 10⁴ wobble periods (spin 1.5 √(g/a))")
    right.grid(True, which="major", alpha=0.3)
    right.legend(fontsize=9)
    figure.tight_layout()
    figure.savefig(docs / "stability.png", dpi=90)


def main():
    data = Path(__file__).resolve().parent.parent / "docs" / "data"
    docs = Path(sys.argv[1]) if len(sys.argv) > 1 else data.parent
    plot_work_precision(data, docs)
    plot_stability(data, docs)


if __name__ == "__main__":
    main()
