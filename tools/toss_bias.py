#!/usr/bin/env python3
"""What keeps a landed flip on the side it started on (docs/toss.md §3): natural flips onto a dead
table, read at the end of their bounces.

A flip launched heads up with its angular momentum L tilted towards the heads normal (psi < 90 deg)
spins about that normal with omega_Z > 0, and its vertical angular momentum about the centre,

    L_v = I_X omega_Y cos(theta) - I_Z omega_Z sin(theta)      (docs/seed.md's frame, eq. 9)

is positive: L_v omega_Z > 0. The script tallies, at the first row after the last impact, the sign
of L_v omega_Z against the face each flip is decided on. Run with the Python module built:

    PYTHONPATH=build/python python3 tools/toss_bias.py [RESTITUTION [FLIPS [--no-spin]]]

(--no-spin launches every flip with omega_Z = 0, the control: then no flip keeps a sense of spin.)
"""
import argparse
import math
import sys

import numpy as np

import coinroll

# docs/toss.md's US quarter; the thin cylinder's moments (the rim's fillet changes them by 0.3 %,
# nothing to a sign).
MASS, RADIUS, THICKNESS, EDGE_RADIUS = 5.67e-3, 12.13e-3, 1.75e-3, 0.3e-3
I_X = MASS * (RADIUS ** 2 / 4 + THICKNESS ** 2 / 12)
I_Z = MASS * RADIUS ** 2 / 2


def flip(psi, turns, up_speed, restitution, spin):
    """bench/toss_study.cpp's natural flip: heads up, 0.3 m above the table, L = I_X 2 pi turns."""
    momentum = I_X * turns * 2 * math.pi
    return {"coin": {"radius": RADIUS, "mass": MASS, "thickness": THICKNESS, "edge_radius": EDGE_RADIUS},
            "initial": {"theta": -89.999, "y": 0.3, "v_y": up_speed, "omega_X": momentum * math.sin(psi) / I_X,
                        "omega_Z": momentum * math.cos(psi) / I_Z if spin else 0.0},
            "friction": 0.3, "sliding": True, "flight": True, "restitution": restitution,
            "effects": [{"type": "rolling_resistance", "length": 2e-5}], "duration": 300,
            "stop_when_decided": True}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("restitution", type=float, nargs="?", default=0.2)
    parser.add_argument("flips", type=int, nargs="?", default=200)
    parser.add_argument("--no-spin", action="store_true", help="launch with omega_Z = 0 (the control)")
    args = parser.parse_args()
    random = np.random.default_rng(7)
    # (keeps the launch's sense, ends heads) -> flips; runs the module refused or the model ended off a face
    tally = {(keeps, heads): 0 for keeps in (True, False) for heads in (True, False)}
    other_ends = {}
    for _ in range(args.flips):
        psi = math.radians(90 - 15 * random.random())
        turns, up_speed = 30 + 15 * random.random(), 2 + random.random()
        run = coinroll.simulate(flip(psi, turns, up_speed, args.restitution, not args.no_spin), 0.001)
        if run.end_event != "decided":
            other_ends[run.end_event] = other_ends.get(run.end_event, 0) + 1
            continue
        impacts, theta = np.asarray(run["impacts"]), np.asarray(run["theta"])
        settled = int(np.argmax(impacts == impacts[-1]))  # the first row after the last impact
        omega_z = run["omega_Z"][settled]
        l_v = I_X * run["omega_Y"][settled] * math.cos(theta[settled]) - I_Z * omega_z * math.sin(theta[settled])
        tally[(l_v * omega_z > 0, bool(theta[-1] < 0))] += 1
    print(f"restitution {args.restitution}, {args.flips} flips{' without spin' if args.no_spin else ''}")
    print("| after the bounces | flips | heads (the starting side) |\n|---|---|---|")
    for keeps in (True, False):
        count = tally[(keeps, True)] + tally[(keeps, False)]
        share = f"{tally[(keeps, True)] / count:.3f}" if count else "-"
        print(f"| L_v omega_Z {'>' if keeps else '<='} 0 | {count} | {share} |")
    decided = sum(tally.values())
    print(f"| all decided | {decided} | {sum(v for (k, h), v in tally.items() if h) / max(decided, 1):.3f} |")
    if other_ends:
        print("other ends:", ", ".join(f"{count} {end}" for end, count in sorted(other_ends.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
