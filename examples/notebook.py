# %% [markdown]
# # coinroll from Python
#
# Straight rolling is stable only above a critical spin. This notebook asks the steady-state
# analysis where that spin is and how fast a slower coin falls over, checks both against
# simulations, sweeps the spin across the threshold, and draws and films the coin.
#
# Cells for Jupyter or VS Code (`# %%`), or run it whole, headless, from the repository:
#
#     PYTHONPATH=build/python python3 examples/notebook.py
#
# which writes notebook.png (the figure) and notebook.mp4 (the clip) in the current directory.

# %%
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt  # without a display, matplotlib falls back to Agg: files only
import numpy as np

import coinroll

EXAMPLES = Path(__file__).resolve().parent if "__file__" in globals() else Path("examples")

# %% [markdown]
# The steady state: upright rolling of the 3.75 cm, 0.4 kg toy at 6 rad/s. K < 0 means a small
# tilt grows like exp(sqrt(-K) t).

# %%
straight = coinroll.steady(kind="straight", omega_Z=6, overrides=["coin.radius=0.0375", "coin.mass=0.4"])
growth_rate = np.sqrt(-straight["K"]) if straight["stability"] == "unstable" else 0.0
print(f"critical spin {straight['critical_spin']:.3f} rad/s; at 6 rad/s: {straight['stability']}, "
      f"tilt grows at {growth_rate:.3f} 1/s")

# %% [markdown]
# Simulate both example scenes, 3 degrees off upright: at 6 rad/s (below the critical spin) and
# at 14 rad/s (above). Each result is a table of numpy arrays named as the CSV's columns.

# %%
unstable = coinroll.simulate(EXAMPLES / "straight_unstable.json")
stable = coinroll.simulate(EXAMPLES / "straight_stable.json")
print(unstable)
print(f"energy drift over the run: {np.ptp(unstable['energy']) / unstable['energy'][0]:.1e} of the energy")

# %% [markdown]
# Sweep the spin across the threshold, from 0.1 degrees off upright so that the linear analysis
# holds: each point is a 4 s run, theta_max its largest tilt (rad).

# %%
sweep = coinroll.sweep(EXAMPLES / "straight_stable.json", {"initial.omega_Z": "3:12:37"},
                       overrides=["initial.theta=0.1"])
print(sweep)

# %%
figure, (tilt, spins, picture) = plt.subplots(1, 3, figsize=(15, 4.2))

for run, label in ((unstable, "6 rad/s"), (stable, "14 rad/s")):
    tilt.plot(run["t"], np.degrees(np.abs(run["theta"])), label=f"simulated, omega_Z = {label}")
# Released at rest 3 degrees off, a small tilt grows as cosh: while it stays small.
early = unstable["t"] < 0.25
tilt.plot(unstable["t"][early], 3 * np.cosh(growth_rate * unstable["t"][early]), "k--",
          label=f"steady analysis: 3 deg x cosh({growth_rate:.2f} t)")
tilt.set(yscale="log", xlabel="t (s)", ylabel="|tilt| (deg)", title="Tilt from upright")
tilt.legend(fontsize=8)

spins.plot(sweep["initial.omega_Z"], np.degrees(sweep["theta_max"]), "o-", markersize=3)
spins.axvline(straight["critical_spin"], color="k", linestyle="--",
              label=f"critical spin {straight['critical_spin']:.2f} rad/s")
spins.set(xlabel="initial omega_Z (rad/s)", ylabel="largest tilt in 4 s (deg)", yscale="log",
          title="Sweep: 0.1 deg off upright")
spins.legend(fontsize=8)

picture.imshow(coinroll.still(EXAMPLES / "straight_unstable.json", 2.0,
                              overrides=["render.width=480", "render.height=320"]))
picture.set(title="still at t = 2 s, 6 rad/s")
picture.axis("off")

figure.tight_layout()
figure.savefig("notebook.png", dpi=100)
if matplotlib.get_backend().lower() != "agg":
    plt.show()  # Agg cannot show, and says so

# %% [markdown]
# And a short clip of the falling coin (the kind follows the name: .mp4, or f_%03d.png frames).

# %%
clip = coinroll.render(EXAMPLES / "straight_unstable.json", "notebook.mp4",
                       overrides=["duration=2", "render.width=320", "render.height=240"])
print(f"wrote {clip}")
