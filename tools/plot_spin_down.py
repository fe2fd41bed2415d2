#!/usr/bin/python3
"""Charts of Euler's disk settling flat (Debian's matplotlib and numpy; run with /usr/bin/python3).

Runs build/coinroll on scenes written to a temporary folder and on examples/euler_disk.json, and
writes
  docs/spin_down.png     tilt alpha and contact-point rate Omega / 2 pi against t0 - t, log-log, for
                         each dissipation law of docs/euler_disk.md alone ((3.5)-(3.7): simulation,
                         least-squares slope, quasi-steady exponent) and for rolling resistance plus
                         Moffatt air drag (the two-law curve (3.12) and its crossover (3.13))
  docs/energy_budget.png energy E, dissipated work D and E + D for examples/euler_disk.json, and the
                         relative residual |E + D - E0| / E0 with the dissipated power P

and prints the fitted slopes and the crossover times.

t0 is read from coinroll's "singular time t0 = ... s" line (docs/euler_disk.md §4: a line through
E/P over the last stretch of the run, i.e. one power law E ~ (t0 - t)^gamma). In the two-law scene
gamma still drifts at the stop (air drag takes over from rolling resistance), so there t0 is
refitted the same way (E/P linear in t) over the last t0 - t_stop before the stop only; both
values are printed.

The quasi-steady laws and the crossover (3.5)-(3.13) are formulas of docs/euler_disk.md that the
program does not compute: independent analytic oracles for its runs, in Python on purpose.

Usage: tools/plot_spin_down.py [COINROLL] [--out-dir DIR] [--energy-scene SCENE]
  COINROLL        the program (default: build/coinroll beside this script's folder)
  --out-dir       where the two PNGs go (default: docs/)
  --energy-scene  the scene whose energy budget is drawn (default: examples/euler_disk.json)
"""

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

# The toy coin of docs/euler_disk.md (3.14); the scenes state the air's viscosity the closed forms use.
A, M, G, MU = 0.0375, 0.4, 9.81, 1.8e-5
COIN = {"shape": "disk", "radius": A, "mass": M}
MOFFATT = {"type": "air_drag", "model": "moffatt", "viscosity": MU}
BOUNDARY_LAYER = {"type": "air_drag", "model": "boundary_layer", "viscosity": MU}
DELTA_CROSS = 1e-6  # rolling-resistance length of the two-law scene [m]

# (key, title, alpha0 [deg], effects, quasi-steady exponents of alpha and Omega, as text)
SINGLE_LAWS = [
    ("moffatt", "(a) Moffatt air drag, α₀ = 4°", 4, [MOFFATT], (1 / 3, -1 / 6), ("1/3", "−1/6")),
    ("boundary_layer", "(b) boundary-layer air drag, α₀ = 6°", 6, [BOUNDARY_LAYER],
     (4 / 9, -2 / 9), ("4/9", "−2/9")),
    ("rolling", "(c) rolling resistance δ = 3.75 µm, α₀ = 6°", 6,
     [{"type": "rolling_resistance", "length": 3.75e-6}], (2 / 3, -1 / 3), ("2/3", "−1/3")),
]
CROSS = ("crossover", "(d) rolling δ = 1 µm + Moffatt, α₀ = 12°", 12,
         [{"type": "rolling_resistance", "length": DELTA_CROSS}, MOFFATT])

SAMPLE_DT = 1e-3  # s; resolves the last two decades of t0 - t (t0 - t_stop is 0.06 s or more)
T0_LINE = re.compile(r"singular time t0 = ([0-9.eE+-]+) s")
SLIP_LINE = re.compile(r"slip at t = ([0-9.eE+-]+) s")
COLUMNS = ("t,theta,phi,psi,omega_X,omega_Y,omega_Z,x,y,z,contact_x,contact_z,energy,normal_force,"
           "friction_force,power,dissipated").split(",")


def simulate(coinroll, scene_path, csv_path, sample_dt, overrides=()):
    """Run coinroll simulate; return ({column: array}, stderr)."""
    sets = [arg for o in overrides for arg in ("--set", o)]
    run = subprocess.run([str(coinroll), "simulate", str(scene_path), "--csv", str(csv_path),
                          "--sample-dt", repr(sample_dt), *sets], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{coinroll} simulate {scene_path} failed ({run.returncode}):\n{run.stderr}")
    with open(csv_path) as f:
        header = f.readline().strip().split(",")
    if header != COLUMNS:
        sys.exit(f"unexpected CSV header in {csv_path}: {header}")
    table = np.loadtxt(csv_path, delimiter=",", skiprows=1, ndmin=2)
    return {name: table[:, i] for i, name in enumerate(header)}, run.stderr


def parse_t0(stderr):
    match = T0_LINE.search(stderr)
    if not match:
        sys.exit("coinroll printed no 'singular time t0 = ... s' line:\n" + stderr)
    return float(match.group(1))


def run_spin_down(coinroll, folder, key, alpha0, effects):
    scene = {"name": key, "coin": COIN, "initial": {"steady": "spin-in-place", "theta": 90 - alpha0},
             "duration": 20000, "effects": effects}
    scene_path = folder / f"{key}.json"
    scene_path.write_text(json.dumps(scene))
    data, stderr = simulate(coinroll, scene_path, folder / f"{key}.csv", SAMPLE_DT)
    data["alpha"] = np.pi / 2 - np.abs(data["theta"])
    data["Omega"] = np.abs(data["omega_Y"] / np.cos(data["theta"]))
    return data, parse_t0(stderr)


def refit_t0(data, t0, iterations=20):
    """docs/euler_disk.md §4: the root of a line through u = E/P, over the last t0 - t_stop only."""
    t, u = data["t"], data["energy"] / data["power"]
    for _ in range(iterations):
        window = t >= t[-1] - (t0 - t[-1])
        slope, intercept = np.polyfit(t[window], u[window], 1)
        t0_new = -intercept / slope
        if abs(t0_new - t0) < 1e-9:
            break
        t0 = t0_new
    return t0


def log_even(tau, count, lo=None, hi=None):
    """Indices of rows whose t0 - t (decreasing down the file) lie closest to `count` targets evenly
    spaced in log(t0 - t) between lo and hi (default: the whole run)."""
    lo = tau[-1] if lo is None else lo
    hi = tau[0] if hi is None else hi
    targets = np.logspace(math.log10(lo), math.log10(hi), count)
    order = -tau  # increasing
    idx = np.clip(np.searchsorted(order, -targets), 1, len(tau) - 1)
    nearer_left = np.abs(tau[idx - 1] - targets) < np.abs(tau[idx] - targets)
    idx = np.unique(np.where(nearer_left, idx - 1, idx))
    return idx[(tau[idx] > 0) & (tau[idx] >= lo * 0.999) & (tau[idx] <= hi * 1.001)]


def fit_window(tau):
    """The last two decades of t0 - t above ten times t0 - t_stop (as much of them as the run has)."""
    lo = 10 * tau[-1]
    return lo, min(100 * lo, tau[0])


def style_log_axes(ax):
    """Plain numbers at 1-2-5 (or 1-3 over more than two decades) instead of powers of ten."""
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        subs = (1.0, 3.0) if hi / lo > 100 else (1.0, 2.0, 5.0)
        axis.set_major_locator(LogLocator(base=10, subs=subs))
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="major", alpha=0.3)


def plot_single_law(axes, data, t0, title, exponents, exponent_text):
    tau = t0 - data["t"]
    lo, hi = fit_window(tau)
    shown = log_even(tau, 70)
    fitted = log_even(tau, 200, lo, hi)
    middle = math.sqrt(lo * hi)
    slopes = []
    series = [np.degrees(data["alpha"]), data["Omega"] / (2 * np.pi)]  # alpha [deg], Omega / 2 pi [Hz]
    for ax, y, p, p_text in zip(axes, series, exponents, exponent_text):
        slope, intercept = np.polyfit(np.log(tau[fitted]), np.log(y[fitted]), 1)
        slopes.append(slope)
        ax.axvspan(lo, hi, color="tab:orange", alpha=0.07, lw=0)
        ax.loglog(tau[shown], y[shown], "o", ms=3, color="tab:blue", label="simulation")
        span = np.array([lo, hi])
        ax.loglog(span, np.exp(intercept) * span ** slope, "-", color="tab:orange", lw=2.5,
                  label=f"fit {slope:.3f}".replace("-", "−"))
        anchor = math.exp(np.interp(math.log(middle), np.log(tau[::-1]), np.log(y[::-1])))
        full = np.array([tau[-1], tau[0]])
        ax.loglog(full, anchor * (full / middle) ** p, "--", color="k", lw=1,
                  label=f"theory {p_text}")
        ax.legend(fontsize=9, loc="upper left" if p > 0 else "upper right", framealpha=0.9)
        style_log_axes(ax)
    axes[0].set_title(title, fontsize=10.5)
    return (lo, hi), slopes


def two_law_theory(alpha):
    """docs/euler_disk.md (3.12): t0 - t at tilt alpha [rad] for rolling (delta) + Moffatt."""
    scale = math.pi * MU * A ** 4 / (4 * DELTA_CROSS ** 2 * M * G)
    alpha_x = (math.pi * MU * A ** 2.5 / (2 * DELTA_CROSS * M * math.sqrt(G))) ** (2 / 3)
    x = (alpha / alpha_x) ** 1.5
    return scale * (x - np.log1p(x)), scale, alpha_x


def simulated_crossover(data, t0):
    """Time and tilt where the rolling power delta N |psi'| equals the air drag's P - delta N |psi'|
    (the last change of sign of their difference: from rolling-dominated to air-dominated)."""
    psi_dot = data["omega_Z"] + np.tan(data["theta"]) * data["omega_Y"]
    rolling = DELTA_CROSS * data["normal_force"] * np.abs(psi_dot)
    excess = rolling - (data["power"] - rolling)
    changes = np.nonzero(np.diff(np.sign(excess)))[0]
    if len(changes) == 0:
        sys.exit("no crossover of the rolling and air powers in the two-law run")
    i = changes[-1]
    w = excess[i] / (excess[i] - excess[i + 1])
    t_x = data["t"][i] + w * (data["t"][i + 1] - data["t"][i])
    alpha_x = data["alpha"][i] + w * (data["alpha"][i + 1] - data["alpha"][i])
    return t0 - t_x, alpha_x


def plot_crossover(axes, data, t0, title):
    tau = t0 - data["t"]
    shown = log_even(tau, 90)
    alpha = np.radians(np.geomspace(0.4, 13, 400))
    tau_theory, scale, alpha_x = two_law_theory(alpha)
    tau_x_predicted = scale * (1 - math.log(2))
    tau_x_simulated, alpha_x_simulated = simulated_crossover(data, t0)
    rate = lambda a: np.sqrt(4 * G / (A * a)) / (2 * np.pi)  # noqa: E731  Omega / 2 pi, (3.1)
    keep = (tau_theory >= tau[-1] * 0.8) & (tau_theory <= tau[0] * 1.2)
    series = [(np.degrees(data["alpha"]), np.degrees), (data["Omega"] / (2 * np.pi), rate)]
    for ax, (y, convert) in zip(axes, series):
        ax.loglog(tau[shown], y[shown], "o", ms=3, color="tab:blue", label="simulation")
        ax.loglog(tau_theory[keep], convert(alpha[keep]), "--", color="k", lw=1.2,
                  label="two-law theory (3.12)")
        ax.axvline(tau_x_predicted, color="tab:red", ls="--", lw=1.2,
                   label=f"predicted crossover {tau_x_predicted:.3f} s")
        ax.axvline(tau_x_simulated, color="tab:green", ls=":", lw=2,
                   label=f"simulated crossover {tau_x_simulated:.3f} s")
        ax.plot([tau_x_predicted], [convert(alpha_x)], "o", mfc="none", mec="tab:red", ms=9, mew=1.5)
        ax.plot([tau_x_simulated], [convert(alpha_x_simulated)], "x", color="tab:green", ms=8, mew=2)
        style_log_axes(ax)
    axes[0].legend(fontsize=8.5, loc="upper left", framealpha=0.9)
    axes[1].text(tau_x_predicted, 0.04, "air drag dominates ←     → rolling dominates", ha="center",
                 fontsize=8, color="0.3", transform=axes[1].get_xaxis_transform())
    axes[0].set_title(title, fontsize=10.5)
    return tau_x_predicted, tau_x_simulated, math.degrees(alpha_x), math.degrees(alpha_x_simulated)


def plot_spin_down(coinroll, docs):
    figure, axes = plt.subplots(2, 4, figsize=(14, 6.5), sharex="col")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for column, (key, title, alpha0, effects, exponents, texts) in enumerate(SINGLE_LAWS):
            data, t0 = run_spin_down(coinroll, folder, key, alpha0, effects)
            window, slopes = plot_single_law(axes[:, column], data, t0, title, exponents, texts)
            rows.append((key, t0, t0 - data["t"][-1], window, slopes, exponents, texts))
        key, title, alpha0, effects = CROSS
        data, t0_coinroll = run_spin_down(coinroll, folder, key, alpha0, effects)
        t0 = refit_t0(data, t0_coinroll)
        crossover = plot_crossover(axes[:, 3], data, t0, title)
        tau_x_with_coinroll_t0 = crossover[1] + (t0_coinroll - t0)
    for ax in axes[0]:
        ax.set_ylabel("tilt above the floor α [deg]" if ax is axes[0, 0] else "α [deg]")
    for ax in axes[1]:
        ax.set_ylabel("contact-point rate Ω/2π [Hz]" if ax is axes[1, 0] else "Ω/2π [Hz]")
        ax.set_xlabel("t0 − t [s]")
    figure.suptitle("Euler's disk settling flat (a = 37.5 mm, M = 0.4 kg): coinroll against the "
                    "quasi-steady laws of docs/euler_disk.md §3 (shaded: slope-fit window)", fontsize=11)
    figure.tight_layout()
    figure.savefig(docs / "spin_down.png", dpi=110)
    plt.close(figure)

    print("Fitted slopes over the last two decades of t0 - t above 10 (t0 - t_stop):")
    print(f"{'law':<15} {'t0 [s]':>10} {'t0-t_stop':>10} {'fit window t0-t [s]':>21} "
          f"{'alpha fit':>9} {'theory':>13} {'Omega fit':>10} {'theory':>14}")
    for key, law_t0, tau_stop, (lo, hi), slopes, exponents, texts in rows:
        decades = math.log10(hi / lo)
        print(f"{key:<15} {law_t0:10.4f} {tau_stop:10.4f} {lo:9.3g} .. {hi:<7.3g} ({decades:.2f} dec)"
              f" {slopes[0]:9.4f} {exponents[0]:7.4f} ({texts[0]:>3}) {slopes[1]:10.4f}"
              f" {exponents[1]:7.4f} ({texts[1].replace('−', '-'):>4})")
    tau_x_pred, tau_x_sim, alpha_x_pred, alpha_x_sim = crossover
    print("Crossover, rolling resistance delta = 1e-6 m + Moffatt air drag, alpha0 = 12 deg:")
    print(f"  t0 from coinroll (one power law over its window)   {t0_coinroll:10.4f} s")
    print(f"  t0 refitted from E/P over the last t0 - t_stop     {t0:10.4f} s   (used in the chart)")
    print(f"  t0 - t_x predicted, S (1 - ln 2) (3.13)            {tau_x_pred:10.4f} s   "
          f"alpha_x = {alpha_x_pred:.3f} deg (3.11)")
    print(f"  t0 - t_x simulated, delta N |psi'| = P_air         {tau_x_sim:10.4f} s   "
          f"alpha = {alpha_x_sim:.3f} deg   ({tau_x_with_coinroll_t0:.4f} s with coinroll's t0)")


def plot_energy_budget(coinroll, docs, scene):
    with tempfile.TemporaryDirectory() as tmp:
        # Held to rolling, as the README's figure is: the example itself slides near the end.
        data, stderr = simulate(coinroll, scene, Path(tmp) / "energy.csv", 0.01, ["sliding=false"])
    t, E, D, P = data["t"], data["energy"], data["dissipated"], data["power"]
    E0 = E[0]
    residual = np.abs(E + D - E0) / E0
    slip = SLIP_LINE.search(stderr)
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    top.plot(t, E, color="tab:blue", label="energy E")
    top.plot(t, D, color="tab:red", label="dissipated D = ∫P dt")
    top.plot(t, E + D, color="k", lw=1.5, ls="--", label="E + D")
    top.set_ylabel("energy [J]")
    default = scene.resolve() == (ROOT / "examples" / "euler_disk.json").resolve()
    top.set_title("examples/euler_disk.json (the 13 mm toy from 30°, boundary-layer air + rolling resistance "
                  "δ = 3.75 µm, to its landing): energy budget" if default else f"{scene.name}: energy budget",
                  fontsize=10)
    top.grid(True, alpha=0.3)
    nonzero = residual > 0
    bottom.semilogy(t[nonzero], residual[nonzero], ".", ms=1.5, color="tab:purple", rasterized=True,
                    label=f"|E + D − E₀| / E₀  ({np.count_nonzero(~nonzero)} exact zeros not shown)")
    # A decade of headroom above the largest residual, whatever the formulation and tolerance.
    bottom.set_ylim(1e-17, 10 ** np.ceil(np.log10(max(residual.max(), 1e-16)) + 1))
    bottom.set_ylabel("relative residual |E + D − E₀| / E₀")
    bottom.set_xlabel("t [s]")
    bottom.grid(True, which="major", alpha=0.3)
    power = bottom.twinx()
    power.semilogy(t, P * 1e3, color="tab:orange", lw=1.2, label="dissipated power P (right axis)")
    power.set_ylabel("P [mW]")
    power.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    power.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    power.yaxis.set_minor_formatter(NullFormatter())
    lines = bottom.get_legend_handles_labels()
    more = power.get_legend_handles_labels()
    if slip:
        t_slip = float(slip.group(1))
        for ax in (top, bottom):
            ax.axvline(t_slip, color="0.4", ls=":", lw=1.2,
                       label=f"slip warning (friction reaches μ_s N, μ_s = friction_static) at t = {t_slip:.1f} s" if ax is top else None)
    top.legend(fontsize=8, loc="center left")
    bottom.legend(lines[0] + more[0], lines[1] + more[1], fontsize=8, loc="upper left", markerscale=6)
    figure.tight_layout()
    figure.savefig(docs / "energy_budget.png", dpi=100)
    plt.close(figure)
    print(f"Energy budget of {scene}: E0 = {E0:.6g} J, E(end) = {E[-1]:.4g} J, "
          f"D(end) = {D[-1]:.4g} J, max |E + D - E0| / E0 = {residual.max():.2e}")


def main():
    parser = argparse.ArgumentParser(description="Charts of Euler's disk settling flat.")
    parser.add_argument("coinroll", nargs="?", type=Path, default=ROOT / "build" / "coinroll")
    parser.add_argument("--out-dir", type=Path, default=ROOT / "docs")
    parser.add_argument("--energy-scene", type=Path, default=ROOT / "examples" / "euler_disk.json")
    args = parser.parse_args()
    if not args.coinroll.exists():
        sys.exit(f"no coinroll binary at {args.coinroll} (build it, or pass its path)")
    args.out_dir.mkdir(parents=True, exist_ok=True)
    plot_spin_down(args.coinroll, args.out_dir)
    plot_energy_budget(args.coinroll, args.out_dir, args.energy_scene)


if __name__ == "__main__":
    main()
