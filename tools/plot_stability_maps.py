#!/usr/bin/python3
"""Stability and spin-down maps from `coinroll sweep` (Debian's matplotlib and numpy; run with /usr/bin/python3).

Runs coinroll's sweeps on scenes written to a temporary folder and writes, into OUT_DIR (default docs/),
  docs/map_straight.png   straight rolling kicked by a small tilt: largest tilt reached against spin
                          and kick, for the disk, the thin hoop and a custom inertia, with the critical
                          spin omega_c of docs/derivations.md (3.7)
  docs/map_circles.png    steady circles (f+ and f- roots of (3.1)) kicked by +0.5 deg of tilt: largest
                          tilt deviation / kick against theta0 and omega_Z0, with the stability boundary
                          K = 0 of (3.6)
  docs/map_spin_down.png  spin-down time (run to the coin-flat stop, 0.5 deg above the floor) against
                          mass and radius for Moffatt's and Bildsten's air drag and rolling resistance,
                          with the quasi-steady closed forms (3.5)-(3.7) of docs/euler_disk.md, and
                          t_end against mass at a = 37.5 mm (air drag: t ~ M; rolling: independent of M)

and prints, per stability panel, where the simulated and the analytic boundaries lie (per grid row, in
grid steps), the fitted spin-down exponents, a summary table and the run times.

A kicked steady state is classed unstable when its tilt leaves theta0 by more than R = 5 kicks within
the run. Besides K = 0 each stability panel draws where linear theory puts that threshold. A kick k of
the tilt with the rates kept gives (docs/derivations.md (3.2)-(3.5))

    d(theta)(t) = k (1 - Q g(t)),   Q = (I_X w_Y0^2 / cos^2 theta0 - Mga cos theta0) / (I_X + Ma^2),
    g = 2 sin^2(sqrt(K) t / 2) / K  (K > 0),   2 sinh^2(sqrt(-K) t / 2) / (-K)  (K < 0)

a wobble between the kick and 1 - 2Q/K kicks (a neighbouring steady state that moves off without bound
as K -> 0+; for straight rolling (r^2 + 1) / (r^2 - 1), r = omega_Z0 / omega_c), or growth like
exp(sqrt(-K) t). Its largest value over the run's samples (every 0.01 s) equal to R is the dashed curve:
it lies on the stable side of K = 0 (straight rolling: 1.225 omega_c for every coin), where the wobble
period is well below the run's length, so it moves by less than 0.01 grid steps for a 60 s run or
0.001 s sampling. The simulated boundary (dots) follows the dashed curve for small kicks; what is left
is the kick's finite size (at the 20 deg circle the ratio is 4.12 for a vanishing kick, 3.89 for 0.5 deg;
checked below).

Where the curves come from: the steady states, the critical spin omega_c and K are the program's
(the Python module's coinroll.steady, the code of src/physics/steady.cpp), so they cannot drift from
it. The kick's linear response (Q, g above) and the spin-down closed forms (3.5)-(3.7) are formulas of
the docs that the program does not compute: independent analytic oracles, in Python on purpose.

The steady circles cannot be gridded by one sweep: their omega_Y depends on (theta0, omega_Z0) and a
steady "initial" (which solves it) takes no kick; so every point is its own one-point sweep (two at a
time), which costs about 50 ms of program start-up per point.

Usage: tools/plot_stability_maps.py [COINROLL] [--module-dir DIR] [--out-dir DIR] [--data-dir DIR]
                                     [--only map_straight,map_circles,map_spin_down]
  COINROLL      the program (default build/coinroll beside this script's folder)
  --module-dir  where the coinroll Python module is built (default build/python)
  --out-dir     where the PNGs go (default docs/)
  --data-dir    keeps every sweep's rows there as a CSV, one per panel (map_straight_disk.csv, ...),
                and reads a CSV found there instead of running its sweep: redraw from kept data, or
                from your own `coinroll sweep` output with the same grid and columns
"""

import argparse
import csv
import importlib
import json
import math
import os
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

plt.rcParams.update({"font.size": 11})
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm, TwoSlopeNorm  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"  # where the PNGs go: --out-dir
coinroll = None  # the Python module, imported in main() from --module-dir

# The toy coin (docs/euler_disk.md (3.14)) and coinroll's default air and rolling constants.
A, M, G = 0.0375, 0.4, 9.81
MU, RHO, DELTA = 1.8e-5, 1.2, 3.75e-6
MA2, MGA = M * A * A, M * G * A
SAMPLE_DT = 0.01  # s: the sweep's theta_min / theta_max come from samples this far apart (and the end)
R_UNSTABLE = 5.0  # a kicked steady state is "unstable" if its tilt leaves theta0 by more than R kicks

# (key, title, coin block of the scene)
COINS = [
    ("disk", "disk (I_X = Ma²/4, I_Z = Ma²/2)", {"shape": "disk"}),
    ("hoop", "thin hoop (ring, I_X = Ma²/2, I_Z = Ma²)", {"shape": "ring"}),
    ("custom", "custom (I_X = 0.3 Ma², I_Z = 0.45 Ma²)", {"shape": "custom", "I_X": 0.3 * MA2, "I_Z": 0.45 * MA2}),
]

STRAIGHT_DURATION = 4.5  # s
STRAIGHT_SPIN = (0.3, 2.5, 60)  # omega_Z0 / omega_c: start, stop, count
STRAIGHT_KICK = (0.5, 10.0, 30)  # deg

CIRCLE_DURATION = 5.0  # s
CIRCLE_KICK = 0.5  # deg, added to theta0 with the steady rates kept
CIRCLE_THETA = (2.0, 27.0, 26)  # deg; K > 0 for every theta0 above 18.6 deg (checked below)
CIRCLE_SPIN = (-3.0, 12.0, 31)  # rad/s, f+ (K < 0 for 0.1..9.3 rad/s); f- gets the mirrored range

ALPHA0_DEG, ALPHA_STOP_DEG = 10.0, 0.5  # spin-in-place at theta = 80 deg; coin-flat with effects at 0.5 deg
SPIN_DOWN_MASS = (0.05, 1.0, 12)  # kg
SPIN_DOWN_RADIUS = (0.015, 0.06, 10)  # m
LINE_RADIUS, LINE_MASS = 0.0375, (0.05, 1.0, 12)
# t_end agrees with the default tolerances (1e-10, 1e-12) to 3e-9 relative at the grid's corners, 2.9x faster
SPIN_DOWN_SOLVER = {"rtol": 1e-6, "atol": 1e-8}


# ----------------------------------------------------------------------------------------------
# Analytic side. Steady states, omega_c and K: the program's (coinroll.steady). Q and the linear
# response: docs/derivations.md (3.2)-(3.5), not in the program (an independent oracle).


def steady(coin, kind, omega_z, theta_deg=None, branch=None):
    """coinroll.steady of the coin (scene block) at a steady state named as `coinroll steady --kind` does."""
    theta = None if theta_deg is None else float(theta_deg)
    return coinroll.steady({"coin": coin_block(coin), "duration": 1.0}, kind=kind, theta=theta, omega_Z=float(omega_z),
                           branch=branch)


def critical_spin(coin):
    """omega_c of straight rolling, (3.7), as the program computes it."""
    return steady(coin, "straight", 1.0)["critical_spin"]


def kick_response(state):
    """Q of a steady state from the program: Q = (I_X w_Y0^2 / cos^2 theta0 - Mga cos theta0) / (I_X + Ma^2),
    the part of K that does not involve the slaved rate perturbations (docs/derivations.md (3.5)). A tilt kick
    k with the rates kept gives d(theta) = k (1 - Q g(t))."""
    i_x, m, a, g = state["inertia_X"], state["mass"], state["radius"], state["gravity"]
    theta, omega_y = math.radians(state["initial"]["theta"]), state["initial"]["omega_Y"]
    return (i_x * omega_y ** 2 / math.cos(theta) ** 2 - m * g * a * math.cos(theta)) / (i_x + m * a * a)


def straight_wobble(coin, omega_z):
    """(K, Q) of straight rolling upright at each spin of the array omega_z, from the program."""
    states = [steady(coin, "straight", w) for w in np.ravel(omega_z)]
    shape = np.shape(omega_z)
    return (np.reshape([st["K"] for st in states], shape), np.reshape([kick_response(st) for st in states], shape))


def circle_wobble(coin, theta, omega_z, branch):
    """(omega_Y, K, Q) of the steady circles, root f+ (branch +1) or f- (-1) of (3.1), at every point of the
    broadcast arrays theta (rad) and omega_z (rad/s), from the program."""
    theta, omega_z = np.broadcast_arrays(np.asarray(theta, float), np.asarray(omega_z, float))
    omega_y, k, q = (np.empty(theta.shape) for _ in range(3))
    for index in np.ndindex(theta.shape):
        state = steady(coin, "circle", omega_z[index], math.degrees(theta[index]), "+" if branch > 0 else "-")
        omega_y[index], k[index], q[index] = state["initial"]["omega_Y"], state["K"], kick_response(state)
    return omega_y, k, q


def linear_ratio(k, q, duration):
    """Largest |d(theta)| / kick over the samples t = 0, 0.01, ..., duration of the linearised motion
    d(theta)/kick = 1 - Q g(t), g = (1 - cos(sqrt(K) t)) / K (cosh for K < 0); arrays K, Q of any shape."""
    t = np.append(np.arange(0.0, duration, SAMPLE_DT), duration)
    k = np.asarray(k, float)[..., None]
    q = np.asarray(q, float)[..., None]
    root = np.sqrt(np.abs(k))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        g = np.where(k > 0, 2 * np.sin(root * t / 2) ** 2 / k, 2 * np.sinh(root * t / 2) ** 2 / np.abs(k))
        g = np.where(np.abs(k) * t * t < 1e-8, t * t / 2, g)
        ratio = np.abs(1 - q * g)
    return np.nanmax(np.where(np.isfinite(ratio), ratio, np.inf), axis=-1)


def spin_down_prediction(law, mass, radius):
    """Quasi-steady time from alpha0 = 10 deg down to the 0.5 deg stop, docs/euler_disk.md (3.5)-(3.7)."""
    a0, a1 = math.radians(ALPHA0_DEG), math.radians(ALPHA_STOP_DEG)
    if law == "moffatt":
        return (a0 ** 3 - a1 ** 3) * mass / (2 * math.pi * MU * radius)
    if law == "boundary_layer":
        rate = (3 * math.pi / math.sqrt(2)) * math.sqrt(MU * RHO) * G ** 0.25 * radius ** 1.75 / mass
        return (a0 ** 2.25 - a1 ** 2.25) / rate
    rate = 2 * DELTA * math.sqrt(G) / radius ** 1.5  # no mass: the couple, like the inertia, scales with M
    return (a0 ** 1.5 - a1 ** 1.5) / rate


# ----------------------------------------------------------------------------------------------
# Running coinroll


class Runner:
    def __init__(self, coinroll_binary, folder, data_dir=None):
        self.coinroll, self.folder, self.count = str(coinroll_binary), Path(folder), 0
        self.data_dir = None if data_dir is None else Path(data_dir)

    def scene(self, scene):
        self.count += 1
        path = self.folder / f"scene_{self.count}.json"
        path.write_text(json.dumps(scene))
        return path

    def kept(self, name, compute):
        """The rows of `name`: read from DATA_DIR/name.csv when it is there, else compute() (a list of dicts
        with the same keys), written there when a data folder was given."""
        if self.data_dir is not None and (self.data_dir / f"{name}.csv").exists():
            with open(self.data_dir / f"{name}.csv", newline="") as f:
                rows = list(csv.DictReader(f))
            print(f"  {name}: {len(rows)} rows read from {self.data_dir / (name + '.csv')}")
            return rows
        rows = compute()
        if self.data_dir is not None:
            self.data_dir.mkdir(parents=True, exist_ok=True)
            with open(self.data_dir / f"{name}.csv", "w", newline="") as f:
                writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
                writer.writeheader()
                writer.writerows(rows)
        return rows

    def sweep(self, scene, grids, sets=(), threads=0, name=None):
        """One `coinroll sweep`; grids [(key, start, stop, count)], sets [(key, value)]; returns its rows.
        A `name` keeps the rows in the data folder (see kept)."""
        if name is not None:
            return self.kept(name, lambda: self.sweep(scene, grids, sets, threads))
        path = self.scene(scene) if isinstance(scene, dict) else scene
        out = path.with_name(f"{path.stem}_{threading.get_ident()}_{len(grids)}.csv")
        command = [self.coinroll, "sweep", str(path), "-o", str(out), "-q", "--threads", str(threads)]
        for key, start, stop, count in grids:
            command += ["--grid", f"{key}={float(start)!r}:{float(stop)!r}:{int(count)}"]
        for key, value in sets:
            command += ["--set", f"{key}={json.dumps(value)}"]
        run = subprocess.run(command, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"coinroll sweep failed ({run.returncode}): {' '.join(command)}\n{run.stderr}")
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
        out.unlink()
        return rows


def coin_block(coin):
    return dict({"radius": A, "mass": M}, **coin)


def grid_values(start, stop, count):
    return np.linspace(start, stop, count)


# ----------------------------------------------------------------------------------------------
# Boundaries: per grid row, where a quantity crosses a level, in fractional column indices


def crossings(values, level):
    """Fractional indices where the sequence crosses `level` (linear interpolation between neighbours)."""
    s = np.asarray(values, float) - level
    found = []
    for i in range(len(s) - 1):
        if s[i] == 0:
            found.append(float(i))
        elif s[i] * s[i + 1] < 0:
            found.append(i + s[i] / (s[i] - s[i + 1]))
    return found


def compare_rows(simulated, analytic):
    """simulated, analytic: per row, lists of crossing positions (grid steps). Each analytic crossing is
    matched with the nearest simulated one of its row. Returns (distances, rows with an analytic
    crossing, missed analytic crossings (none simulated in their row), simulated crossings left unmatched)."""
    distances, where, missed, extra, rows = [], [], 0, 0, 0
    for r, (sim, ana) in enumerate(zip(simulated, analytic)):
        rows += bool(ana)
        matched = set()
        for x in ana:
            if sim:
                nearest = min(range(len(sim)), key=lambda n: abs(x - sim[n]))
                distances.append(abs(x - sim[nearest]))
                where.append(r)
                matched.add(nearest)
            else:
                missed += 1
        extra += len(sim) - len(matched)
    worst_row = where[int(np.argmax(distances))] if distances else None
    return np.array(distances), rows, missed, extra, worst_row


def describe(distances):
    if len(distances) == 0:
        return float("nan"), float("nan")
    return float(distances.max()), float(distances.mean())


def signed(value, digits=3):
    """A number with a real minus sign and no negative zero."""
    text = f"{round(value, digits) + 0.0:.{digits}f}"
    return text.replace("-", "−")


def plain_log_colourbar(bar, ticks):
    bar.set_ticks(ticks)
    bar.set_ticklabels([f"{t:g}" for t in ticks])
    bar.ax.minorticks_off()


# ----------------------------------------------------------------------------------------------
# Map 1: straight rolling


def map_straight(runner, summary):
    spins_rel = grid_values(*STRAIGHT_SPIN)
    kicks = grid_values(*STRAIGHT_KICK)
    figure, axes = plt.subplots(1, 3, figsize=(12.5, 4.9), sharey=True)
    norm = LogNorm(vmin=0.5, vmax=90)
    panels = []
    for ax, (key, title, coin) in zip(axes, COINS):
        omega_c = critical_spin(coin)
        start, stop, count = STRAIGHT_SPIN[0] * omega_c, STRAIGHT_SPIN[1] * omega_c, STRAIGHT_SPIN[2]
        scene = {"name": f"straight_{key}", "coin": coin_block(coin), "initial": {"theta": 1.0, "omega_Z": omega_c},
                 "duration": STRAIGHT_DURATION}
        began = time.monotonic()
        rows = runner.sweep(scene, [("initial.theta", *STRAIGHT_KICK), ("initial.omega_Z", start, stop, count)],
                            name=f"map_straight_{key}")
        seconds = time.monotonic() - began
        shape = (STRAIGHT_KICK[2], count)
        spins = np.array([float(r["initial.omega_Z"]) for r in rows]).reshape(shape)[0]
        kick_col = np.array([float(r["initial.theta"]) for r in rows]).reshape(shape)[:, 0]
        tilt = np.degrees(np.maximum(np.abs([float(r["theta_min"]) for r in rows]),
                                     np.abs([float(r["theta_max"]) for r in rows]))).reshape(shape)
        ends = np.array([r["end"] for r in rows]).reshape(shape)
        tilt = np.where(ends == "coin-flat", 90.0, tilt)  # fell: the run stops at 89 deg
        assert np.allclose(kick_col, kicks) and np.allclose(spins, spins_rel * omega_c)
        step = spins[1] - spins[0]

        # Boundaries per kick row, in grid steps from the first column.
        ratio = tilt / kick_col[:, None]
        simulated = [crossings(np.log(row), math.log(R_UNSTABLE)) for row in ratio]
        analytic = [[(omega_c - spins[0]) / step]] * len(kicks)
        fine = np.linspace(spins[0], spins[-1], 20 * (count - 1) + 1)
        k_fine, q_fine = straight_wobble(coin, fine)
        linear = linear_ratio(k_fine, q_fine, STRAIGHT_DURATION)
        lin_x = [fine[0] + c * (fine[1] - fine[0]) for c in crossings(np.log(linear), math.log(R_UNSTABLE))]
        threshold = [[(x - spins[0]) / step for x in lin_x]] * len(kicks)

        mesh = ax.pcolormesh(spins, kicks, tilt, norm=norm, cmap="magma", shading="nearest", rasterized=True)
        ax.axvline(omega_c, color="#00e5ff", lw=2.2)
        for x in lin_x:
            ax.axvline(x, color="#00e5ff", lw=1.4, ls="--")
        sx = [spins[0] + c * step for row, k in zip(simulated, kicks) for c in row]
        sy = [k for row, k in zip(simulated, kicks) for _ in row]
        ax.plot(sx, sy, "o", ms=4, mfc="white", mec="black", mew=0.6)
        ax.set_title(f"{title}\nω_c = {omega_c:.2f} rad/s", fontsize=11)
        ax.set_xlabel("spin ω_Z0 [rad/s]")
        ax.set_xlim(spins[0] - step / 2, spins[-1] + step / 2)
        ax.set_ylim(kicks[0] - 0.17, kicks[-1] + 0.17)
        panels.append(dict(name=f"straight {key}", grid=f"{STRAIGHT_KICK[2]} kicks x {count} spins",
                           step=f"{step:.3f} rad/s", rows=len(kicks), simulated=simulated, analytic=analytic,
                           threshold=threshold, seconds=seconds, points=len(rows),
                           row_label=lambda r, kicks=kicks: f"kick {kicks[r]:.1f}",
                           events=dict(zip(*np.unique(ends, return_counts=True)))))
        first, last = (spins[0] + simulated[0][0] * step) / omega_c, (spins[0] + simulated[-1][0] * step) / omega_c
        print(f"  {key}: simulated boundary at {first:.3f} omega_c (kick {kicks[0]:g} deg), {last:.3f} omega_c "
              f"(kick {kicks[-1]:g} deg); linear theory's {R_UNSTABLE:g}-kick threshold at "
              f"{lin_x[0] / omega_c:.3f} omega_c")
        print(f"  {key}: omega_c = {omega_c:.4f} rad/s; {len(rows)} points in {seconds:.1f} s; ends "
              f"{dict(zip(*np.unique(ends, return_counts=True)))}; largest tilt below 0.5 omega_c "
              f"{tilt[:, spins < 0.5 * omega_c].min():.1f}..{tilt[:, spins < 0.5 * omega_c].max():.1f} deg")
    axes[0].set_ylabel("tilt kick θ(0) [deg]  (rates of straight rolling)")
    figure.subplots_adjust(left=0.055, right=0.91, bottom=0.2, top=0.82, wspace=0.07)
    bar = figure.colorbar(mesh, cax=figure.add_axes([0.925, 0.2, 0.013, 0.62]))
    bar.set_label(f"largest tilt in {STRAIGHT_DURATION:g} s [deg]  (90 = fell)")
    plain_log_colourbar(bar, [0.5, 1, 2, 5, 10, 20, 50, 90])
    handles = [Line2D([], [], color="#00e5ff", lw=2.2, label="critical spin ω_c, eq. (3.7): K = 0"),
               Line2D([], [], color="#00e5ff", lw=1.4, ls="--",
                      label=f"linear theory: tilt reaches {R_UNSTABLE:g} × kick in {STRAIGHT_DURATION:g} s"),
               Line2D([], [], ls="", marker="o", ms=5, mfc="white", mec="black",
                      label=f"simulated: largest tilt = {R_UNSTABLE:g} × kick (per row)")]
    figure.legend(handles=handles, loc="lower center", ncol=3, fontsize=9.5, frameon=False)
    figure.suptitle("Straight rolling kicked by a small tilt: below the critical spin ω_c the tilt runs away",
                    fontsize=12.5, y=0.985)
    figure.savefig(DOCS / "map_straight.png", dpi=90)
    plt.close(figure)
    summary.extend(panels)


# ----------------------------------------------------------------------------------------------
# Map 2: steady circles


def map_circles(runner, summary, workers=2):
    key, title, coin = COINS[0]
    thetas = grid_values(*CIRCLE_THETA)
    plus_spins = grid_values(*CIRCLE_SPIN)
    spins = {1: plus_spins, -1: -plus_spins[::-1]}  # f-(omega_Z) mirrors f+(-omega_Z): the same range mirrored
    base = runner.scene({"name": "circle_kick", "coin": coin_block(coin),
                         "initial": {"theta": 10.0, "omega_Y": 0.0, "omega_Z": 0.0}, "duration": CIRCLE_DURATION})

    # The linearised wobble (what the dashed curves use) against the simulation, small kicks on a stable circle.
    th0, wz0 = math.radians(20.0), 10.0
    wy0, k0, q0 = (float(v) for v in circle_wobble(coin, th0, wz0, 1))
    predicted = float(linear_ratio(k0, q0, CIRCLE_DURATION))
    measured = []
    for kick_deg in (2.0, CIRCLE_KICK, 0.1, 0.02):
        row = runner.sweep(base, [("initial.theta", 20.0 + kick_deg, 20.0 + kick_deg, 1)],
                           [("initial.omega_Y", wy0), ("initial.omega_Z", wz0)], threads=1,
                           name=f"map_circles_kick_{kick_deg:g}")[0]
        dev = max(float(row["theta_max"]) - th0, th0 - float(row["theta_min"]))
        measured.append(f"{kick_deg:g} deg: {dev / math.radians(kick_deg):.4f}")
    print(f"  f+ circle theta0 = 20 deg, omega_Z0 = 10 rad/s: largest |theta - theta0| / kick, linear theory "
          f"{predicted:.4f}; simulated, kick " + ", ".join(measured))

    # Where K < 0 at all (so that the plotted ranges hold every unstable circle).
    th_all = np.radians(np.linspace(0.5, 88.5, 177))[:, None]  # the program refuses 89 deg and above
    wz_all = np.linspace(-150, 150, 301)[None, :]
    for branch in (1, -1):
        k_all = circle_wobble(coin, th_all, wz_all, branch)[1]
        rows, cols = np.nonzero(k_all < 0)
        print(f"  {'f+' if branch > 0 else 'f-'}: K < 0 only for theta0 <= {np.degrees(th_all[rows.max(), 0]):.2f} deg "
              f"and omega_Z0 in [{wz_all[0, cols.min()]:.1f}, {wz_all[0, cols.max()]:.1f}] rad/s "
              f"(scanned theta0 0.5..88.5 deg in 0.5 deg, |omega_Z0| <= 150 rad/s in 1 rad/s)")

    jobs = []
    for branch in (1, -1):
        for i, th in enumerate(thetas):
            wy = circle_wobble(coin, math.radians(th), spins[branch], branch)[0]
            for j, wz in enumerate(spins[branch]):
                jobs.append((branch, i, j, th, float(wy[j]), float(wz)))

    def one(job):
        branch, i, j, th, wy, wz = job
        theta_kicked = th + CIRCLE_KICK
        row = runner.sweep(base, [("initial.theta", theta_kicked, theta_kicked, 1)],
                           [("initial.omega_Y", wy), ("initial.omega_Z", wz)], threads=1)[0]
        return dict(row, branch=branch, theta0=th, omega_Y0=wy, omega_Z0=wz)

    def run_all():
        with ThreadPoolExecutor(max_workers=workers) as pool:
            return list(pool.map(one, jobs))

    began = time.monotonic()
    points = runner.kept("map_circles_points", run_all)  # one row per job, in the jobs' order
    results = [(job, row) for job, row in zip(jobs, points)]
    seconds = time.monotonic() - began
    print(f"  {len(jobs)} one-point sweeps in {seconds:.1f} s ({len(jobs) / seconds:.0f} points/s, "
          f"{workers} at a time)")

    kick = math.radians(CIRCLE_KICK)
    shape = (len(thetas), len(plus_spins))
    ratio = {1: np.zeros(shape), -1: np.zeros(shape)}
    ends = {1: np.empty(shape, dtype=object), -1: np.empty(shape, dtype=object)}
    for (branch, i, j, th, wy, wz), row in results:
        th0 = math.radians(th)
        deviation = max(float(row["theta_max"]) - th0, th0 - float(row["theta_min"]))
        if row["end"] == "coin-flat":
            deviation = max(deviation, math.radians(90) - th0)  # fell: unstable
        elif row["end"] != "duration":
            deviation = math.nan  # lift-off or slip: left the model, no verdict
        ratio[branch][i, j] = deviation / kick
        ends[branch][i, j] = row["end"]
    same = np.isfinite(ratio[1]) & np.isfinite(ratio[-1][:, ::-1])
    mirror = np.max(np.abs(np.log(ratio[1][same]) - np.log(ratio[-1][:, ::-1][same])))
    print(f"  mirror check: f-(omega_Z) = -f+(-omega_Z) and (omega_Y, omega_Z) -> (-omega_Y, -omega_Z) is a symmetry "
          f"of (14)-(16); the simulated ratios of the two panels differ by at most {mirror:.1e} (log)")

    figure, axes = plt.subplots(1, 2, figsize=(12, 5.2), sharey=True)
    vmax = math.log10(90 / CIRCLE_KICK)
    norm = TwoSlopeNorm(vmin=0.0, vcenter=math.log10(R_UNSTABLE), vmax=vmax)
    fine_th = np.radians(np.linspace(thetas[0], thetas[-1], 8 * (len(thetas) - 1) + 1))
    for ax, branch in zip(axes, (1, -1)):
        name = "f+" if branch > 0 else "f−"
        wz = spins[branch]
        step_wz = wz[1] - wz[0]
        fine_wz = np.linspace(wz[0], wz[-1], 10 * (len(wz) - 1) + 1)
        mesh = ax.pcolormesh(wz, thetas, np.log10(ratio[branch]), norm=norm, cmap="RdBu_r", shading="nearest",
                             rasterized=True)
        gone = ~np.isfinite(ratio[branch])
        if gone.any():
            gi, gj = np.nonzero(gone)
            ax.plot(wz[gj], thetas[gi], "x", color="black", ms=6)
        # Analytic K = 0 and the linear-theory threshold, on a finer grid.
        _, k_f, q_f = circle_wobble(coin, fine_th[:, None], fine_wz[None, :], branch)
        lin_f = np.vstack([linear_ratio(k_f[r], q_f[r], CIRCLE_DURATION) for r in range(len(fine_th))])
        ax.contour(fine_wz, np.degrees(fine_th), k_f, levels=[0], colors="black", linewidths=2.2)
        ax.contour(fine_wz, np.degrees(fine_th), np.log(lin_f), levels=[math.log(R_UNSTABLE)], colors="black",
                   linewidths=1.3, linestyles="--")
        # Per theta0 row: simulated, analytic (K = 0) and linear-threshold crossings, in grid steps.
        simulated, analytic, threshold = [], [], []
        _, k_rows, q_rows = circle_wobble(coin, np.radians(thetas)[:, None], fine_wz[None, :], branch)
        to_steps = (fine_wz[1] - fine_wz[0]) / step_wz
        for r in range(len(thetas)):
            simulated.append(crossings(np.log(ratio[branch][r]), math.log(R_UNSTABLE)))
            analytic.append([c * to_steps for c in crossings(k_rows[r], 0.0)])
            lin_r = linear_ratio(k_rows[r], q_rows[r], CIRCLE_DURATION)
            threshold.append([c * to_steps for c in crossings(np.log(lin_r), math.log(R_UNSTABLE))])
        sx = [wz[0] + c * step_wz for row in simulated for c in row]
        sy = [th for row, th in zip(simulated, thetas) for _ in row]
        ax.plot(sx, sy, "o", ms=4.5, mfc="white", mec="black", mew=0.7)
        root = "larger" if branch > 0 else "smaller"
        ax.set_title(f"{name} circles: ω_Y0 = {name}(θ0, ω_Z0), the {root} root of (3.1)", fontsize=11)
        ax.set_xlabel("spin ω_Z0 [rad/s]")
        ax.set_xlim(wz[0] - step_wz / 2, wz[-1] + step_wz / 2)
        ax.set_ylim(thetas[0] - 0.5, thetas[-1] + 0.5)
        counts = {e: int((ends[branch] == e).sum()) for e in sorted(set(ends[branch].flat))}
        summary.append(dict(name=f"circles {name}", grid=f"{len(thetas)} tilts x {len(wz)} spins",
                            step=f"{step_wz:.3f} rad/s", rows=len(thetas), simulated=simulated, analytic=analytic,
                            threshold=threshold, seconds=seconds / 2, points=len(thetas) * len(wz), events=counts,
                            row_label=lambda r: f"θ0 {thetas[r]:.0f}"))
    axes[1].text(0.97, 0.97, "the mirror image of f+:\n(ω_Y, ω_Z) → (−ω_Y, −ω_Z)\n"
                 "is a symmetry of (14)-(16);\nsimulated values identical",
                 transform=axes[1].transAxes, ha="right", va="top", fontsize=9.5, color="white")
    axes[0].set_ylabel(f"steady tilt θ0 [deg]  (started at θ0 + {CIRCLE_KICK:g}°)")
    figure.subplots_adjust(left=0.065, right=0.895, bottom=0.2, top=0.87, wspace=0.06)
    bar = figure.colorbar(mesh, cax=figure.add_axes([0.91, 0.2, 0.014, 0.67]))
    ticks = [1, 2, 5, 10, 20, 50, 100, 180]
    bar.set_ticks([math.log10(t) for t in ticks])
    bar.set_ticklabels([f"{t:g}" for t in ticks])
    bar.set_label(f"largest |θ − θ0| in {CIRCLE_DURATION:g} s / kick")
    handles = [Line2D([], [], color="black", lw=2.2, label="K = 0, eq. (3.6) (unstable inside)"),
               Line2D([], [], color="black", lw=1.3, ls="--",
                      label=f"linear theory: |θ − θ0| reaches {R_UNSTABLE:g} × kick in {CIRCLE_DURATION:g} s"),
               Line2D([], [], ls="", marker="o", ms=5, mfc="white", mec="black",
                      label=f"simulated: |θ − θ0| = {R_UNSTABLE:g} × kick")]
    if any((~np.isfinite(ratio[b])).any() for b in ratio):
        handles.append(Line2D([], [], ls="", marker="x", color="black", label="lift-off (N < 0)"))
    figure.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=9.5, frameon=False)
    figure.suptitle(f"Steady circles of the disk kicked by +{CIRCLE_KICK:g}° of tilt (rates kept): "
                    "blue stays, red runs away", fontsize=12.5)
    figure.savefig(DOCS / "map_circles.png", dpi=90)
    plt.close(figure)


# ----------------------------------------------------------------------------------------------
# Map 3: spin-down time


# (key, title, effect, closed-form exponents of M and a as text, contour levels [s])
LAWS = [
    ("moffatt", "Moffatt air drag", {"type": "air_drag", "model": "moffatt", "viscosity": MU}, ("1", "−1"),
     [50, 100, 200, 500, 1000, 2000]),
    ("boundary_layer", "boundary-layer air drag", {"type": "air_drag", "model": "boundary_layer", "viscosity": MU, "density": RHO},
     ("1", "−7/4"),
     [5, 10, 20, 50, 100, 200, 500]),
    ("rolling", "rolling resistance δ = 3.75 µm", {"type": "rolling_resistance", "length": DELTA}, ("0", "3/2"),
     [7, 10, 15, 20, 30, 40]),
]


def spin_down_scene(effect):
    return {"name": "spin_down", "coin": {"shape": "disk", "radius": A, "mass": M},
            "initial": {"steady": "spin-in-place", "theta": 90 - ALPHA0_DEG}, "duration": 100000,
            "effects": [effect], "solver": SPIN_DOWN_SOLVER}


def map_spin_down(runner, fits):
    masses = grid_values(*SPIN_DOWN_MASS)
    radii = grid_values(*SPIN_DOWN_RADIUS)
    figure, axes = plt.subplots(2, 2, figsize=(12, 9.4))
    norm = LogNorm(vmin=2, vmax=5000)
    line_ax = axes[1, 1]
    colours = {"moffatt": "tab:blue", "boundary_layer": "tab:orange", "rolling": "tab:green"}
    for ax, (key, title, effect, exponents, levels) in zip([axes[0, 0], axes[0, 1], axes[1, 0]], LAWS):
        scene = runner.scene(spin_down_scene(effect))
        began = time.monotonic()
        rows = runner.sweep(scene, [("coin.mass", *SPIN_DOWN_MASS), ("coin.radius", *SPIN_DOWN_RADIUS)],
                            name=f"map_spin_down_{key}")
        line = runner.sweep(scene, [("coin.mass", *LINE_MASS)], [("coin.radius", LINE_RADIUS)],
                            name=f"map_spin_down_{key}_line")
        seconds = time.monotonic() - began
        for r in rows + line:
            if r["end"] != "coin-flat":
                sys.exit(f"spin-down {key} ended with {r['end']!r} at {r}")
        t_end = np.array([float(r["t_end"]) for r in rows]).reshape(len(masses), len(radii)).T  # [radius, mass]
        got_m = np.array([float(r["coin.mass"]) for r in rows]).reshape(len(masses), len(radii))[:, 0]
        got_a = np.array([float(r["coin.radius"]) for r in rows]).reshape(len(masses), len(radii))[0]
        assert np.allclose(got_m, masses) and np.allclose(got_a, radii)
        predicted = np.array([[spin_down_prediction(key, m, a) for m in masses] for a in radii])
        mesh = ax.pcolormesh(masses, radii * 1000, t_end, norm=norm, cmap="viridis", shading="nearest",
                             rasterized=True)
        sim_c = ax.contour(masses, radii * 1000, t_end, levels=levels, colors="white", linewidths=1.3)
        ax.clabel(sim_c, fmt=lambda v: f"{v:g} s", fontsize=8)
        ax.contour(masses, radii * 1000, predicted, levels=levels, colors="black", linewidths=1.1,
                   linestyles="--")
        ax.set_xlabel("mass M [kg]")
        ax.set_ylabel("radius a [mm]")

        # Exponents: t_end ~ M^p a^q over the whole grid, and ~ M^p along a = 37.5 mm.
        design = np.column_stack([np.ones(t_end.size), np.log(np.tile(masses, len(radii))),
                                  np.log(np.repeat(radii, len(masses)))])
        coef = np.linalg.lstsq(design, np.log(t_end.ravel()), rcond=None)[0]
        lm = np.array([float(r["coin.mass"]) for r in line])
        lt = np.array([float(r["t_end"]) for r in line])
        p_line = np.polyfit(np.log(lm), np.log(lt), 1)[0]
        lp = np.array([spin_down_prediction(key, m, LINE_RADIUS) for m in lm])
        ratio = t_end / predicted
        ax.set_title(f"{title}: t ∝ M^p a^q, closed form p = {exponents[0]}, q = {exponents[1]}\n"
                     f"fit p = {signed(coef[1])}, q = {signed(coef[2])};  simulated / closed form "
                     f"{ratio.min():.3f}–{ratio.max():.3f}", fontsize=10.5)
        fits.append(dict(law=key, p_line=p_line, p_grid=coef[1], q_grid=coef[2], ratio_min=ratio.min(),
                         ratio_max=ratio.max(), line_ratio=(lt / lp), seconds=seconds, points=len(rows) + len(line),
                         t_range=(t_end.min(), t_end.max())))
        line_ax.loglog(lm, lp, "-", color=colours[key], lw=1.3)
        line_ax.loglog(lm, lt, "o", color=colours[key], ms=5.5, label=f"{title}: slope {signed(p_line)}")
    figure.subplots_adjust(left=0.07, right=0.9, bottom=0.065, top=0.885, wspace=0.25, hspace=0.36)
    bar = figure.colorbar(mesh, cax=figure.add_axes([0.915, 0.565, 0.014, 0.32]))
    bar.set_label("time to the coin-flat stop [s]")
    plain_log_colourbar(bar, [2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000])
    axes[1, 0].legend(handles=[Line2D([], [], color="white", lw=1.3, label="simulated (labelled)"),
                               Line2D([], [], color="black", lw=1.1, ls="--",
                                      label="closed form, euler_disk.md (3.5)-(3.7)")],
                      loc="center left", bbox_to_anchor=(0.01, 0.555), fontsize=8.5, facecolor="#888888",
                      framealpha=0.85)
    line_ax.set_title(f"against mass at a = {LINE_RADIUS * 1000:g} mm:\n"
                      "air drag t ∝ M, rolling resistance independent of M", fontsize=11)
    line_ax.set_xlabel("mass M [kg]")
    line_ax.set_ylabel("time to the coin-flat stop [s]")
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    for axis in (line_ax.xaxis, line_ax.yaxis):
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(NullFormatter())
    line_ax.grid(True, which="major", alpha=0.3)
    line_ax.legend(title="dots simulated, lines closed form", title_fontsize=9, fontsize=9, loc="upper left")
    figure.suptitle(f"Spin-down of a disk let go spinning in place at α0 = {ALPHA0_DEG:g}° above the floor, "
                    f"one law at a time (run to the stop at {ALPHA_STOP_DEG:g}°)", fontsize=12.5, y=0.985)
    figure.savefig(DOCS / "map_spin_down.png", dpi=80)
    plt.close(figure)


# ----------------------------------------------------------------------------------------------


def main():
    global DOCS, coinroll
    parser = argparse.ArgumentParser(description="Stability and spin-down maps from coinroll sweeps.")
    parser.add_argument("coinroll_binary", nargs="?", type=Path, default=ROOT / "build" / "coinroll",
                        help="the coinroll program (default: build/coinroll)")
    parser.add_argument("--module-dir", type=Path, default=ROOT / "build" / "python",
                        help="folder holding the built coinroll Python module (default: build/python)")
    parser.add_argument("--out-dir", type=Path, default=DOCS, help="where the PNGs go (default: docs/)")
    parser.add_argument("--data-dir", type=Path,
                        help="keep each panel's sweep rows there as CSV, and read any CSV already there instead of "
                             "running its sweep")
    parser.add_argument("--only", help="comma-separated maps to draw: map_straight,map_circles,map_spin_down")
    args = parser.parse_args()
    only = None if args.only is None else set(args.only.split(","))
    if not os.access(args.coinroll_binary, os.X_OK):
        sys.exit(f"{args.coinroll_binary}: not an executable (build it first)")
    sys.path.insert(0, str(args.module_dir))
    try:
        coinroll = importlib.import_module("coinroll")
    except ImportError as error:
        sys.exit(f"the coinroll Python module is not in {args.module_dir} (build it first): {error}")
    DOCS = args.out_dir
    DOCS.mkdir(parents=True, exist_ok=True)
    summary, fits, timings = [], [], {}
    total = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="coinroll_maps_") as folder:
        runner = Runner(args.coinroll_binary, folder, args.data_dir)
        for name, job in (("map_straight", lambda: map_straight(runner, summary)),
                          ("map_circles", lambda: map_circles(runner, summary)),
                          ("map_spin_down", lambda: map_spin_down(runner, fits))):
            if only is not None and name not in only:
                continue
            print(f"{name}:")
            began = time.monotonic()
            job()
            timings[name] = time.monotonic() - began

    print(f"\nStability boundaries (unstable: |theta - theta0| > {R_UNSTABLE:g} x kick), distances per grid row "
          "in grid steps,\nsimulated against K = 0 and against linear theory's R-threshold curve:")
    head = f"{'rows':>4} {'max':>5} {'(row)':<9} {'mean':>5} {'miss':>4} {'extra':>5}"
    print(f"  {'':<50} | {'vs K = 0':^37} | {'vs linear-theory threshold':^37} |")
    print(f"  {'panel':<16} {'grid':<21} {'step':<11} | {head} | {head} | ends")
    for p in summary:
        cells = []
        for target in ("analytic", "threshold"):
            d, rows, missed, extra, worst_row = compare_rows(p["simulated"], p[target])
            worst, mean = describe(d)
            at = "" if worst_row is None else p["row_label"](worst_row)
            cells.append(f"{rows:>4} {worst:>5.2f} {at:<9} {mean:>5.2f} {missed:>4} {extra:>5}")
        print(f"  {p['name']:<16} {p['grid']:<21} {p['step']:<11} | {cells[0]} | {cells[1]} | {p['events']}")
    print("  rows: rows with an analytic crossing; miss: analytic crossings in rows with no simulated one;"
          "\n  extra: simulated crossings that are no analytic crossing's nearest")

    print("\nSpin-down time t_end ~ M^p a^q (fits of log t_end; closed forms: Moffatt p = 1, q = -1; boundary layer "
          "p = 1, q = -7/4; rolling p = 0, q = 3/2):")
    print(f"  {'law':<15} {'p (a = 37.5 mm)':>15} {'p (grid)':>9} {'q (grid)':>9} | {'t_end range [s]':>17} | "
          f"{'simulated / closed form':>23}")
    for f in fits:
        p_line, p_grid, q_grid = (round(f[k], 4) + 0.0 for k in ("p_line", "p_grid", "q_grid"))  # no "-0.0000"
        print(f"  {f['law']:<15} {p_line:>15.4f} {p_grid:>9.4f} {q_grid:>9.4f} | "
              f"{f['t_range'][0]:>7.1f} .. {f['t_range'][1]:>6.1f} | {f['ratio_min']:>10.4f} .. {f['ratio_max']:.4f}")

    print("\nRun times and files:")
    for name, seconds in timings.items():
        size = (DOCS / f"{name}.png").stat().st_size
        print(f"  {name:<14} {seconds:6.1f} s   {DOCS / (name + '.png')} {size / 1024:6.1f} KiB")
    print(f"  total          {time.monotonic() - total:6.1f} s")


if __name__ == "__main__":
    main()
