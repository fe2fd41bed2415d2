#!/usr/bin/python3
# Independent on purpose: a benchmark peer (scipy's DOP853 on its own NumPy right-hand side); it never calls coinroll.
"""scipy's DOP853 (solve_ivp) as one more peer of the work-precision benchmark.

Reads the cases and reference end states that build/bench/work_precision wrote
(docs/data/work_precision_cases.csv), integrates each case at rtol = atol = 10^-3 .. 10^-12 and
writes docs/data/work_precision_scipy.csv in the benchmark's columns, then prints our DOP853's time
over scipy's at equal error (our points from docs/data/work_precision.csv).

Not the same right-hand-side object as the C++ peers: a NumPy port of physics::rhs
(src/physics/dynamics.cpp, seed eqs. 14-19), so the ratio includes Python's per-call overhead;
it says what a user of scipy would see, not how the two DOP853 codes compare.

Usage: /usr/bin/python3 tools/scipy_peer.py [DATA_DIR]
"""

import csv
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp


def make_rhs(M, a, g, I_X, I_Z):
    Ma2, Mga = M * a * a, M * g * a

    def rhs(_t, y):
        theta, phi, _psi, omega_X, omega_Y, omega_Z = y[:6]
        sin_theta, cos_theta = math.sin(theta), math.cos(theta)
        sin_phi, cos_phi = math.sin(phi), math.cos(phi)
        tan_theta = sin_theta / cos_theta
        return [
            omega_X,                                                         # (17)
            omega_Y / cos_theta,                                             # (18)
            omega_Z + tan_theta * omega_Y,                                   # (19)
            (-(I_Z + Ma2) * omega_Y * omega_Z - I_X * omega_Y * omega_Y * tan_theta
             + Mga * sin_theta) / (I_X + Ma2),                               # (14)
            omega_X * omega_Y * tan_theta + (I_Z / I_X) * omega_Z * omega_X,  # (15)
            Ma2 * omega_X * omega_Y / (I_Z + Ma2),                           # (16)
            a * (-omega_Z * cos_phi + omega_X * cos_theta * sin_phi),        # v_x
            a * (omega_Z * sin_phi + omega_X * cos_theta * cos_phi),         # v_z
        ]

    def energy(y):
        theta, _phi, _psi, omega_X, omega_Y, omega_Z = y[:6]
        return (0.5 * Ma2 * (omega_X**2 + omega_Z**2)
                + 0.5 * (I_X * (omega_X**2 + omega_Y**2) + I_Z * omega_Z**2) + Mga * np.cos(theta))

    return rhs, energy


def seconds_at_error(points, target):
    """Log-time interpolated in log-error between the bracketing points (coarse to fine)."""
    for (e0, s0), (e1, s1) in zip(points, points[1:]):
        if e0 >= target >= e1 and e0 > e1:
            f = math.log(e0 / target) / math.log(e0 / e1)
            return math.exp(math.log(s0) + f * math.log(s1 / s0))
    return None


def main():
    data = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "docs" / "data"
    with open(data / "work_precision_cases.csv", newline="") as f:
        cases = list(csv.DictReader(f))
    rows = []
    for case in cases:
        rhs, energy = make_rhs(*(float(case[k]) for k in ("M", "a", "g", "I_X", "I_Z")))
        y0 = np.array([float(case[f"y0_{i}"]) for i in range(8)])
        reference = np.array([float(case[f"yref_{i}"]) for i in range(8)])
        t_end, E0 = float(case["t_end"]), energy(y0)
        for k in range(3, 13):
            tol = 10.0**-k
            best = math.inf
            for _ in range(2):  # best of two: runs take 0.01..2 s, noise is small against that
                start = time.perf_counter()
                solution = solve_ivp(rhs, (0, t_end), y0, method="DOP853", rtol=tol, atol=tol)
                best = min(best, time.perf_counter() - start)
            error = np.linalg.norm(solution.y[:, -1] - reference) / np.linalg.norm(reference)
            energy_error = max(abs(energy(solution.y[:, j]) - E0) / abs(E0) for j in range(solution.y.shape[1]))
            rows.append([case["case"], "scipy_dop853", 1, f"{tol:.6g}", f"{error:.6g}", f"{energy_error:.6g}",
                         solution.nfev, solution.t.size - 1, -1, f"{best:.6g}"])
            print(f"{case['case']:>10} scipy_dop853 {tol:9.1e} {error:10.3e} {energy_error:10.3e} "
                  f"{solution.nfev:9d} {best:10.3e}", flush=True)
    with open(data / "work_precision_scipy.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["case", "method", "is_peer", "parameter", "rel_error", "max_energy_error",
                         "rhs_evaluations", "steps", "rejected_steps", "seconds"])
        writer.writerows(rows)
    with open(data / "work_precision.csv", newline="") as f:
        ours = [r for r in csv.DictReader(f) if r["method"] == "dop853" and float(r["seconds"]) > 0]
    print("\nOur DOP853 time / scipy DOP853 time at equal relative state error")
    for case in cases:
        name = case["case"]
        our_line = [(float(r["rel_error"]), float(r["seconds"])) for r in ours if r["case"] == name]
        their_line = [(float(r[4]), float(r[9])) for r in rows if r[0] == name]
        ratios = []
        for target in (1e-6, 1e-8, 1e-10, 1e-12):
            mine, theirs = seconds_at_error(our_line, target), seconds_at_error(their_line, target)
            ratios.append(f"{mine / theirs:.4f}" if mine and theirs else "n/a")
        print(f"{name:>10} " + " ".join(f"{target:>8.0e}: {r:>7}" for target, r in zip((1e-6, 1e-8, 1e-10, 1e-12), ratios)))


if __name__ == "__main__":
    main()
