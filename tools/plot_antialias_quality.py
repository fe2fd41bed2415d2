#!/usr/bin/python3
"""Chart of the anti-aliasing benchmark (Debian's matplotlib; run with /usr/bin/python3).

Reads docs/data/antialias_quality.csv, written by build/bench/antialias_quality, and writes
  docs/antialias_quality.png  edge error against cost per frame (ratio to 4x MSAA in the same run),
                              one panel per picture, one marker per method, filled for the mean
                              error on edge pixels and hollow for their 99th percentile; osmesa
                              circles, egl squares

Usage: tools/plot_antialias_quality.py [OUT_DIR]   (default: docs/ beside this script's folder)
"""

import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

BACKEND_MARKERS = {"osmesa": "o", "egl": "s"}


def main():
    data = Path(__file__).resolve().parent.parent / "docs" / "data"
    docs = Path(sys.argv[1]) if len(sys.argv) > 1 else data.parent
    with open(data / "antialias_quality.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f) if int(r["samples"]) > 0]  # methods this OpenGL refused
    pictures = list(dict.fromkeys(r["picture"] for r in rows))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    colours = {m: plt.cm.tab10(i % 10) for i, m in enumerate(methods)}
    columns = 2
    figure, axes = plt.subplots((len(pictures) + columns - 1) // columns, columns, figsize=(10, 7), sharey=True,
                                squeeze=False)
    for ax, picture in zip(axes.flat, pictures):
        for r in rows:
            if r["picture"] != picture:
                continue
            cost, marker, colour = float(r["cost_vs_msaa4"]), BACKEND_MARKERS.get(r["backend"], "^"), colours[
                r["method"]]
            ax.semilogy(cost, float(r["edge_mean"]), marker=marker, color=colour, linestyle="none", markersize=7)
            ax.semilogy(cost, float(r["edge_p99"]), marker=marker, markerfacecolor="none", color=colour,
                        linestyle="none", markersize=7)
        ax.set_title(picture, fontsize=10)
        ax.set_xlabel("cost per frame / 4x MSAA's (same run)")
        ax.set_ylabel("error on edge pixels [8-bit levels]")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes.flat[len(pictures):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], marker="o", color=colours[m], linestyle="none", label=m) for m in methods]
    handles += [plt.Line2D([], [], marker=BACKEND_MARKERS[b], color="grey", linestyle="none", label=b)
                for b in BACKEND_MARKERS if any(r["backend"] == b for r in rows)]
    handles += [plt.Line2D([], [], marker="o", color="grey", linestyle="none", label="mean"),
                plt.Line2D([], [], marker="o", color="grey", markerfacecolor="none", linestyle="none",
                           label="99th percentile")]
    axes.flat[0].legend(handles=handles, fontsize=7, loc="upper right")
    figure.suptitle("Anti-aliasing: error against a 64-sample reference vs cost (1280x720, llvmpipe)")
    figure.tight_layout()
    figure.savefig(docs / "antialias_quality.png", dpi=72)


if __name__ == "__main__":
    main()
