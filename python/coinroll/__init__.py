"""coinroll from Python: a coin rolling on a table, simulated and rendered headless.

The same library as the ``coinroll`` command, with its scenes, numbers and pixels:

    >>> import coinroll
    >>> run = coinroll.simulate("examples/steady_circle.json", sample_dt=0.01)
    >>> run["energy"]            # a float64 numpy array per CSV column, the CSV's names
    >>> run.end_event, run.end_time
    ('duration', 4.0)

A ``scene`` is a dict in the scene file's JSON format, a path (str or os.PathLike) to a scene
file, or None for the built-in default scene; ``overrides`` are the command line's --set
("initial.theta=12", the value read as JSON). A bad scene or request raises ValueError with the
command's message, which names the field, or the call's keyword where the command names its
option (sample_dt, t, path); a NaN in a scene dict is refused naming its key. Simulating, drawing and sweeping release the GIL, so
Python threads run meanwhile; Ctrl-C stops a still, a render or a sweep cleanly (no partial file
is left) with KeyboardInterrupt, and comes after a simulate returns.
"""

import json
import math
import os
import platform
import sys
import warnings
from collections.abc import Mapping

from ._built_for import PYTHON as _BUILT_FOR, PYTHON_VERSION as _BUILT_FOR_VERSION


def _cannot_import(error, fix):
    """An ImportError saying which interpreter the package was built for, and what this one lacks."""
    this = f"{sys.executable} (Python {platform.python_version()})"
    return ImportError(f"coinroll cannot be imported by {this}: {error}; coinroll was built for {_BUILT_FOR} "
                       f"(Python {_BUILT_FOR_VERSION}), which has numpy: run it with that interpreter, or {fix}")


try:
    import numpy as np
except ImportError as error:
    raise _cannot_import(error, f"install numpy for this one ({sys.executable} -m pip install numpy)") from error
try:
    from . import _coinroll
except ImportError as error:
    raise _cannot_import(error, f"build coinroll for this one (cmake -DPython3_EXECUTABLE={sys.executable})") from error

__all__ = ["simulate", "still", "render", "steady", "sweep", "Table", "Trajectory", "SweepTable"]
__version__ = _coinroll.version()


class Table(Mapping):
    """Columns by name, in the CSV's order: ``table["energy"]`` is a numpy array.

    A read-only mapping of read-only arrays: ``dict(table)``, ``pandas.DataFrame(dict(table))``,
    ``table["t"].copy()`` for one to edit.
    """

    def __init__(self, names, arrays):
        self._columns = dict(zip(names, arrays))

    @property
    def columns(self):
        """The column names, in the CSV's order."""
        return list(self._columns)

    @property
    def rows(self):
        return len(next(iter(self._columns.values()), ()))

    def __getitem__(self, name):
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r} (this table's columns: {', '.join(self._columns)})") from None

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return len(self._columns)

    def __repr__(self):
        return f"<{type(self).__name__}: {self.rows} rows of {', '.join(self._columns)}>"


class Trajectory(Table):
    """``coinroll simulate``'s CSV as columns, and how the run ended.

    end_event: "duration" when the run reached the scene's duration, else the validity event that
    stopped it early ("coin-flat", "face-down", "lift-off", "slip", ...), as the sweep's end column
    names it; end_time: s; end_description: what ``coinroll simulate`` prints after "stopped
    early: " ("" for "duration").
    """

    def __init__(self, names, arrays, end_event, end_time, end_description):
        super().__init__(names, arrays)
        self.end_event = end_event
        self.end_time = end_time
        self.end_description = end_description

    def __repr__(self):
        return f"<Trajectory: {self.rows} rows of {', '.join(self._columns)}; ended by {self.end_event} at t = {self.end_time} s>"


class SweepTable(Table):
    """``coinroll sweep``'s table: a row per grid point, in point order.

    Columns "point", one per grid key (its values), "end" (a str array: "duration", the event
    that ended the point's run, or "error: <why>"), then "t_end", "theta_min", "theta_max"
    (rad), "energy_start", "energy_end" (J), "theta_end" (rad, at the run's end: a toss's face,
    heads where < 0), NaN where the point failed. grid_points: the points in the grid; digest: the
    sweep's identity, as its CSV's "sweep" column.
    """

    def __init__(self, names, arrays, end, grid_points, digest):
        columns = dict(zip(names, arrays))
        after_keys = list(columns).index("t_end")
        ordered = list(columns.items())
        end = np.array(end, dtype=str)
        end.flags.writeable = False  # read-only, as the number columns are
        ordered.insert(after_keys, ("end", end))
        super().__init__([name for name, _ in ordered], [array for _, array in ordered])
        self.grid_points = grid_points
        self.digest = digest


def _json_value(value):
    """What json.dumps cannot write, refused naming its type."""
    raise TypeError(f"scene: {type(value).__name__} is not a JSON value")


def _json_ready(value, key):
    """`value` with numpy's scalars and arrays as JSON's numbers and lists, and a NaN or an
    infinity refused naming its key: json.dumps would write a bare NaN, which the scene reader
    can only call a JSON syntax error."""
    if isinstance(value, (np.generic, np.ndarray)):
        value = value.tolist()
    if isinstance(value, Mapping):
        return {name: _json_ready(item, f"{key}.{name}" if key else str(name)) for name, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(item, f"{key}[{i}]") for i, item in enumerate(value)]
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"scene JSON: {key}: must be a finite number, got {value}")
    return value


def _scene(scene, overrides=()):
    overrides = [overrides] if isinstance(overrides, str) else list(overrides)
    if scene is None:
        return _coinroll.Scene.built_in_default(overrides)
    if isinstance(scene, Mapping):
        return _coinroll.Scene.from_json(json.dumps(_json_ready(scene, ""), default=_json_value), overrides)
    if isinstance(scene, (str, os.PathLike)):
        return _coinroll.Scene.from_file(os.fspath(scene), overrides)
    raise TypeError(f"scene: give a dict in the scene file's format, a path to a scene file or None, "
                    f"got {type(scene).__name__}")


def simulate(scene, sample_dt=0.01, overrides=()):
    """Integrates the scene and samples it every ``sample_dt`` s: ``coinroll simulate``'s CSV.

    Returns a Trajectory: ``r["theta"]`` a float64 array per CSV column (the same doubles as the
    CSV, whose %.17g reads back exactly), ``r.columns`` the names, ``r.end_event`` and
    ``r.end_time`` how the run ended. More rows than the command's limit (duration / sample_dt + 1 >
    10^9) is refused before any work.
    """
    return Trajectory(*_coinroll.simulate(_scene(scene, overrides), sample_dt))


def still(scene, t, overrides=()):
    """The picture ``coinroll still --time t`` draws, as an (H, W, 4) uint8 RGBA array, top row first.

    A run that a validity event stopped before t shows its end.
    """
    return _coinroll.still(_scene(scene, overrides), t)


def render(scene, path, overrides=()):
    """Writes the clip ``coinroll render -o path`` writes and returns ``path``.

    The kind follows the name: .mp4, or a %d pattern of .png names for a PNG sequence. The file
    appears only once it is complete; an error or Ctrl-C leaves none. As the command's -o, ``path``
    is refused when it is (or a frame of its sequence would be) the scene's file.
    """
    _coinroll.render(_scene(scene, overrides), os.fspath(path))
    return path


def steady(scene=None, *, kind=None, theta=None, omega_Z=None, branch=None, overrides=()):
    """A steady motion and its linear stability, as ``coinroll steady`` prints them.

    Either the scene's ``initial`` names the steady state, or ``kind`` ("straight", "circle",
    "spin-in-place") with ``theta`` (degrees), ``omega_Z`` (rad/s) and ``branch`` ("+" or "-")
    replaces it, as the command's --kind, --theta, --omega-Z and --branch do (``overrides``
    apply after, so "initial.phi=45" lands on it). The scene defaults to the built-in one.

    Returns a dict: the coin ("mass", "radius", "gravity", "inertia_X", "inertia_Z",
    "thickness", "edge_radius"), "natural_rate" sqrt(g/a) and "critical_spin" (rad/s; None for a
    rim with corners); "initial", the state in scene units, ready to paste into a scene;
    "precession_rate" and "spin_rate" (rad/s), "centre_of_mass_radius" and "contact_radius" (m,
    inf rolling straight), "normal_force" and "friction_force" (N); "K" (1/s^2: small tilt
    perturbations obey d(theta)'' = -K d(theta)) and "stability": "stable" (a wobble at sqrt(K)
    rad/s), "unstable" (growing like exp(sqrt(-K) t)) or "marginal". These are the ideal model's:
    with effects the state is only where a slowing motion starts.
    """
    overrides = [overrides] if isinstance(overrides, str) else list(overrides)
    if kind is not None:
        initial = {"steady": kind}
        for name, value in (("theta", theta), ("omega_Z", omega_Z)):
            if value is not None:
                if not math.isfinite(value):
                    raise ValueError(f"{name}: must be a finite number, got {value}")
                initial[name] = value
        if branch is not None:
            initial["branch"] = branch
        overrides.insert(0, "initial=" + json.dumps(_json_ready(initial, "initial"), default=_json_value))
    elif theta is not None or omega_Z is not None or branch is not None:
        raise ValueError("theta, omega_Z and branch describe a steady state: give kind too")
    return _coinroll.steady(_scene(scene, overrides))


def _axis(key, values):
    if isinstance(values, str):
        return f"{key}={values}"
    return f"{key}={','.join(repr(float(v)) for v in values)}"


def sweep(scene, grid, threads=0, overrides=()):
    """``coinroll sweep``: the scene at every point of a grid, summarised in a SweepTable.

    ``grid`` maps each scene field to its axis in the command's --grid syntax,
    ``{"initial.theta": "5:40:8"}`` (8 values from 5 to 40), ``"0.01:1:5:log"`` (geometric), or
    to the values themselves, ``{"initial.omega_Z": [8, 12, 16]}``; the last axis runs fastest.
    A list of the command's "KEY=START:STOP:COUNT" strings works too. ``threads``: 0 uses
    every hardware thread. A key that is no scene field, or no number, is refused before any work.
    """
    if isinstance(grid, Mapping):
        axes = [_axis(key, values) for key, values in grid.items()]
    elif isinstance(grid, str):
        axes = [grid]
    else:
        axes = list(grid)
    table = SweepTable(*_coinroll.sweep(_scene(scene, overrides), axes, threads))
    # A failed point is a row like the others; the command's summary counts them, so a script that
    # only reads the numbers is told here instead of averaging over NaNs unawares.
    failed = [str(end) for end in table["end"] if str(end).startswith("error:")]
    if failed:
        warnings.warn(f"sweep: {len(failed)} of {len(table['end'])} points failed (first: {failed[0]}); "
                      "their rows have end 'error: ...' and NaN numbers", RuntimeWarning, stacklevel=2)
    return table
