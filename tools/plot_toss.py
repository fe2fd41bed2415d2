#!/usr/bin/python3
"""Charts the toss study (bench/toss_study.cpp): caught flips against Diaconis, Holmes and
Montgomery's formula, and the natural flips caught and landed on a table.

    build/bench/toss_study OUT_DIR [LANDED_TOSSES] && tools/plot_toss.py OUT_DIR docs/toss.png
"""

import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def diaconis(psi_deg):
    cot2 = 1 / math.tan(math.radians(psi_deg)) ** 2
    return 1.0 if cot2 >= 1 else 0.5 + math.asin(cot2) / math.pi


def main():
    folder, out = Path(sys.argv[1]), Path(sys.argv[2])
    caught, landed = rows(folder / "toss_caught.csv"), rows(folder / "toss_landed.csv")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    grid = [30 + 0.25 * k for k in range(241)]
    left.plot(grid, [diaconis(p) for p in grid], color="0.3", label="Diaconis et al. (2007)")
    left.plot([r["psi_deg"] for r in caught], [r["same_side"] for r in caught], "o", color="tab:orange",
              label="coinroll, caught")
    left.set_xlabel("angle between normal and angular momentum ψ (deg)")
    left.set_ylabel("same side up")
    left.set_title("Caught in the hand")
    left.legend()
    e = [r["restitution"] for r in landed]
    right.plot(e, [r["caught_same_side"] for r in landed], "s-", color="tab:orange", label="caught")
    right.plot(e, [r["same_side"] for r in landed], "o-", color="tab:blue", label="landed on the table")
    right.axhline(0.508, color="0.5", linestyle=":", label="Bartoš et al. (2023), 0.508")
    right.set_xlabel("restitution e")
    right.set_title(f"Natural flips, {int(landed[0]['tosses'])} per point")
    right.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
