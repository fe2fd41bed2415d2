#!/usr/bin/env python3
"""`coinroll simulate` against tests/oracles/sliding_reference.py, an independent Newton-Euler integration in
world vectors (docs/sliding.md), in two cases (angles in rad, rates in units of sqrt(g/a), positions in
units of a, energy relative; the switch time to 1e-9 s):
- a tilted spinning coin that skids, then rolls (a free slide that ends), within 1e-8;
- a wobbling coin that rolls, then slides from the instant its rolling reaction reaches mu N, with mu_k =
  mu_s (the creeping onset of docs/sliding.md §4.6, whose friction direction is a first-order reduction,
  against the reference's seeded onset (4.8)), within 1e-7.

Usage: sliding_reference_test.py --binary build/coinroll
"""
import argparse
import csv
import io
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# A small coin on a steady circle, its centre launched off its rolling velocity: it skids and rolls again.
SKID = {"mass": 0.00567, "radius": 0.01213, "mu": 0.3, "theta": 0.3, "omega_Y": -5.263469899354806, "omega_Z": -30.0,
        "v_x": 0.3, "v_z": 0.05, "duration": 0.05, "sample_dt": 0.001}
# The same coin rolling with a wobble: it needs mu N at t = 0.0232 s and slides from there (docs/sliding.md §4.4).
ONSET = {"mass": 0.00567, "radius": 0.01213, "mu": 0.3, "theta": 0.3, "omega_X": 3.0, "omega_Y": 2.0, "omega_Z": -30.0,
         "duration": 0.1, "sample_dt": 0.001}
CASES = [("skid, then roll", SKID, "rolls at t = ", 1e-8), ("roll, then slide", ONSET, "slides at t = ", 1e-7)]


def scene_of(case):
    initial = {"theta": math.degrees(case["theta"])}
    initial.update({k: case[k] for k in ("omega_X", "omega_Y", "omega_Z", "v_x", "v_z") if k in case})
    return {"coin": {"radius": case["radius"], "mass": case["mass"]}, "friction": case["mu"], "sliding": True,
            "initial": initial, "duration": case["duration"], "solver": {"rtol": 1e-12, "atol": 1e-14}}


def compare(binary, name, case, switch_line, bound):
    reference = subprocess.run([sys.executable, str(ROOT / "tests" / "oracles" / "sliding_reference.py"), json.dumps(case)],
                               capture_output=True, text=True, check=True)
    with tempfile.TemporaryDirectory() as scratch:
        scene = Path(scratch) / "scene.json"
        scene.write_text(json.dumps(scene_of(case)))
        ours = subprocess.run([binary, "simulate", str(scene), "--csv", "-", "--sample-dt", str(case["sample_dt"])],
                              capture_output=True, text=True, check=True)
    a = list(csv.DictReader(io.StringIO(reference.stdout)))
    b = list(csv.DictReader(io.StringIO(ours.stdout)))
    if len(a) != len(b):
        print(f"{name}: row counts differ: reference {len(a)}, coinroll {len(b)}")
        return False
    rate, length = math.sqrt(9.81 / case["radius"]), case["radius"]
    scale = {"theta": 1, "omega_X": rate, "omega_Y": rate, "omega_Z": rate, "x": length, "z": length,
             "slip_speed": rate * length, "energy": float(a[0]["energy"])}
    worst = {k: max(abs(float(p[k]) - float(q[k])) / s for p, q in zip(a, b)) for k, s in scale.items()}
    modes = all(p["sliding"] == q["sliding"] for p, q in zip(a, b))
    ref_switch = float(reference.stderr.split(switch_line)[1].split()[0].rstrip(";"))
    our_switch = float(ours.stderr.split(switch_line)[1].split()[0])
    print(f"{name}: largest difference per column (scaled): " + ", ".join(f"{k} {v:.2e}" for k, v in worst.items()))
    print(f"{name}: switch: reference {ref_switch:.12f} s, coinroll {our_switch:.9f} s; modes agree: {modes}")
    return max(worst.values()) < bound and modes and abs(ref_switch - our_switch) < 1e-9


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binary", required=True)
    binary = parser.parse_args().binary
    results = [compare(binary, *case) for case in CASES]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
