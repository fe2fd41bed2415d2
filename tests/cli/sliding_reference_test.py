#!/usr/bin/env python3
"""A tilted spinning coin that skids, then rolls: `coinroll simulate` against tools/sliding_reference.py,
an independent Newton-Euler integration in world vectors (docs/sliding.md), within 1e-8 (angles in rad,
rates in units of sqrt(g/a), positions in units of a, energy relative), and the switch time to 1e-9 s.

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
CASE = {"mass": 0.00567, "radius": 0.01213, "mu": 0.3, "theta": 0.3, "omega_Y": -5.263469899354806, "omega_Z": -30.0,
        "v_x": 0.3, "v_z": 0.05, "duration": 0.05, "sample_dt": 0.001}
SCENE = {"coin": {"radius": CASE["radius"], "mass": CASE["mass"]}, "friction": CASE["mu"], "sliding": True,
         "initial": {"theta": math.degrees(CASE["theta"]), "omega_Y": CASE["omega_Y"], "omega_Z": CASE["omega_Z"],
                     "v_x": CASE["v_x"], "v_z": CASE["v_z"]},
         "duration": CASE["duration"], "solver": {"rtol": 1e-12, "atol": 1e-14}}
BOUND = 1e-8


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binary", required=True)
    binary = parser.parse_args().binary
    reference = subprocess.run([sys.executable, str(ROOT / "tools" / "sliding_reference.py"), json.dumps(CASE)],
                               capture_output=True, text=True, check=True)
    with tempfile.TemporaryDirectory() as scratch:
        scene = Path(scratch) / "scene.json"
        scene.write_text(json.dumps(SCENE))
        ours = subprocess.run([binary, "simulate", str(scene), "--csv", "-", "--sample-dt", str(CASE["sample_dt"])],
                              capture_output=True, text=True, check=True)
    a = list(csv.DictReader(io.StringIO(reference.stdout)))
    b = list(csv.DictReader(io.StringIO(ours.stdout)))
    if len(a) != len(b):
        print(f"row counts differ: reference {len(a)}, coinroll {len(b)}")
        return 1
    rate, length = math.sqrt(9.81 / CASE["radius"]), CASE["radius"]
    scale = {"theta": 1, "omega_X": rate, "omega_Y": rate, "omega_Z": rate, "x": length, "z": length,
             "slip_speed": rate * length, "energy": float(a[0]["energy"])}
    worst = {k: max(abs(float(p[k]) - float(q[k])) / s for p, q in zip(a, b)) for k, s in scale.items()}
    modes = all(p["sliding"] == q["sliding"] for p, q in zip(a, b))
    ref_switch = float(reference.stderr.split("rolls at t = ")[1].split()[0].rstrip(";"))
    our_switch = float(ours.stderr.split("rolls at t = ")[1].split()[0])
    print("largest difference per column (scaled): " + ", ".join(f"{k} {v:.2e}" for k, v in worst.items()))
    print(f"switch to rolling: reference {ref_switch:.12f} s, coinroll {our_switch:.9f} s; modes agree: {modes}")
    ok = max(worst.values()) < BOUND and modes and abs(ref_switch - our_switch) < 1e-9
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
