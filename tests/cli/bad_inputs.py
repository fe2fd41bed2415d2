#!/usr/bin/python3
"""Bad inputs and faults against the coinroll binary: one table, one runner.

Every case runs in its own fresh scratch directory (the binary's working directory) and checks
the exit code, a substring of stderr that names the field or flag, and that nothing but the
case's own inputs is left in the directory (for cases that must succeed: exactly the outputs they
name). docs/bad_inputs.md is generated from this table (--markdown).

    /usr/bin/python3 tests/cli/bad_inputs.py --binary build/coinroll [--only ID] [--markdown docs/bad_inputs.md]
    /usr/bin/python3 tests/cli/bad_inputs.py --binary build/coinroll --category signals   # one category
    /usr/bin/python3 tests/cli/bad_inputs.py --list-categories
    /usr/bin/python3 tests/cli/bad_inputs.py --export-scene-cases cases.json

ctest runs one entry per category (cli_bad_inputs.<slug>), so it can balance them against the
other tests. --export-scene-cases writes the cases that are a scene (and --set overrides) in and a
refusal out, for the in-process test tests/scene/bad_scene_test.cpp, which checks the same
messages without starting the program (in a second under AddressSanitizer).
    /usr/bin/python3 tests/cli/bad_inputs.py --binary OLD/coinroll --record-before tests/cli/bad_inputs_before.json

Standard library only: ctest runs it with the system's python3.
"""

import argparse
import concurrent.futures
import copy
import fnmatch
import gzip
import json
import os
import re
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent

# Non-ASCII file names and arguments must reach the binary as UTF-8 bytes whatever the locale
# ctest runs under; Python's UTF-8 mode makes every str <-> bytes conversion below UTF-8.
if sys.flags.utf8_mode == 0 and sys.getfilesystemencoding().lower().replace("-", "") != "utf8":
    os.execv(sys.executable, [sys.executable, "-X", "utf8", *sys.argv])

# ----------------------------------------------------------------------------------------------
# Inputs

BASE = {"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
        "initial": {"theta": 10, "omega_Z": 12}, "duration": 0.5}
DELETE = object()  # in scene(): remove this key from BASE


def merged(base, changes):
    out = copy.deepcopy(base)
    for key, value in changes.items():
        if value is DELETE:
            out.pop(key, None)
        elif isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merged(out[key], value)
        else:
            out[key] = value
    return out


def scene(**changes):
    """The valid 0.5 s scene with top-level keys changed (dicts merge, DELETE removes)."""
    return json.dumps(merged(BASE, changes))


VALID = scene()
SMALL = "--set render.width=64 --set render.height=48"  # renders in well under a second
HEADER = "point,initial.theta,end,t_end,theta_min,theta_max,energy_start,energy_end,theta_end,grid_points,sweep"
# The header of a shard written before theta_end existed.
HEADER_BEFORE_THETA_END = HEADER.replace(",theta_end", "")
SWEEP_ID = "40,0123456789abcdef"  # a 40-point grid's identity columns (written by the sweep itself)


def shard(points, identity=SWEEP_ID, before_theta_end=False):
    theta_end = "" if before_theta_end else ",0.15"
    rows = "".join(f"{p},{1 + p / 10},duration,0.5,0.1,0.2,0.3,0.3{theta_end},{identity}\n" for p in points)
    return (HEADER_BEFORE_THETA_END if before_theta_end else HEADER) + "\n" + rows


SHARDS = {"scene.json": VALID, "p1.csv": shard(range(0, 40, 2)), "p2.csv": shard(range(1, 40, 2))}
LONG = "a" * 251  # + ".csv" / ".png" / ".mp4": 255 bytes, the longest name Linux allows


class Dir:
    """An empty directory among a case's inputs."""


class Fifo:
    """A named pipe among a case's inputs."""


NOBODY = 65534  # user nobody: a case run as root runs as nobody where root would pass every permission check


def with_mode(content, mode, owner=None):
    """A file among a case's inputs with permission bits `mode` and, when run as root, owner `owner`."""
    def make(path):
        Path(path).write_bytes(content if isinstance(content, bytes) else content.encode())
        os.chmod(path, mode)
        if owner is not None and os.geteuid() == 0:
            os.chown(path, owner, owner)
    return make


def huge_zeros(path):
    with open(path, "wb") as out:
        out.truncate(17 << 20)  # sparse zero bytes: past the 16 MiB read limit without 17 MiB of writes


def deep_arrays(path):
    with open(path, "wb") as out:
        # Deeper than any recursive parser's stack survives; small enough that the sanitizer build
        # (several times slower) parses and frees it well within the timeout.
        out.write(b"[" * 2_000_000 + b"]" * 2_000_000)


def png(width, height, shade=128, bit_depth=8, damage_at=None, colour_type=6, idat=None):
    """A grey RGBA PNG written with the standard library, for compare's inputs: 8 or 16 bits per
    channel (16: every low byte `shade`, every high byte 0), and with the byte `damage_at` bytes
    from the end flipped, if given (inside the IDAT chunk's CRC). `colour_type` goes into the
    header only; `idat`, if given, replaces the compressed pixels (with a valid CRC)."""
    import struct
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    pixel = bytes([shade, shade, shade, 255]) if bit_depth == 8 else bytes([0, shade] * 3 + [255, 255])
    rows = b"".join(b"\0" + pixel * width for _ in range(height))
    header = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    data = bytearray(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", idat or zlib.compress(rows))
                     + chunk(b"IEND", b""))
    if damage_at is not None:
        data[-damage_at] ^= 0xFF
    return lambda path: Path(path).write_bytes(bytes(data))


# ----------------------------------------------------------------------------------------------
# The table


@dataclass
class Case:
    id: str
    cat: str
    what: str
    args: str                      # coinroll's arguments, shell-quoted; or a bash command (shell=True)
    rc: int
    msg: str | None                # stderr must contain this (today's wording)
    or_msg: str | None = None      # or this: the other designed outcome of a race the case cannot fix
    key: str | None = None         # what an older wording must still name (the field or flag); default msg
    files: dict = field(default_factory=lambda: {"scene.json": VALID})
    produces: tuple = ()           # glob patterns of outputs a succeeding case must leave
    alters: tuple = ()             # glob patterns of inputs the case may change or remove (an output over them)
    check: object = None           # check(directory) -> problem or None, run on the directory afterwards
    shell: bool = False            # args is a bash command; {bin} is the binary
    signal: int | None = None      # sent once the long work has started
    wait_for: str = "partial"      # "partial": a temporary in the directory; "stdout": data; "sleep"; "fifo": blocked opening a FIFO (every mode also waits until the signal has a handler)
    then: tuple = ()               # (signal, seconds after the one before) sent after `signal`
    settle: float | None = None    # seconds between the start seen and the signal (default 0.3; "sleep": 1)
    timeout: float = 20
    gtest: tuple = ()              # GoogleTest tests in tests/cli/*.cpp checking the same case
    unsanitized: str | None = None  # why the case cannot run against a sanitizer build (skipped there)
    na_before: str | None = None   # the feature did not exist at 32cc7d7


CASES: list[Case] = []


def unsanitized_reason(c: Case) -> str | None:
    """Why `c` cannot run against a build with AddressSanitizer, or None."""
    if "ulimit -v" in c.args:
        return "AddressSanitizer cannot start under an address-space limit (it reserves terabytes of shadow)"
    return c.unsanitized


def is_sanitized(binary: str) -> bool:
    return b"__asan_init" in Path(binary).read_bytes()


def case(*args, **kwargs):
    CASES.append(Case(*args, **kwargs))


G_SCENES = "CliTest.EveryBadSceneGetsExitTwoANamedKeyAndNoFile"
G_CMDLINE = "CliTest.BadCommandLinesGetExitTwo"
G_ABSURD = "CliTest.AbsurdRequestsAreRefusedUpFrontNamingWhatAndTheLimit"
G_TOL = "CliTest.ToleranceOutsideItsMeaningfulRangeIsRefused"
G_SAME = "CliTest.AnOutputThatIsTheInputIsRefusedAndTheInputKept"
G_EFFECTS = "EffectsCliTest.BadEffectsGetExitTwoNameTheKeyAndWriteNothing"
G_RENDER = "RenderCliTest.BadRequestsExitTwoAndLeaveNothing"
G_FULL = "RenderCliTest.AFullDiskFailsEveryWriterWithoutLeavingAFile"
G_SWEEP = "SweepCliTest.BadGridsAndShardsExitTwoWithoutAFile"
G_MERGE = "SweepCliTest.SameBytesForOneAndTwoThreadsAndForShardsRunByGnuParallel"
SIM = "simulate scene.json --csv o.csv"

# --- the scene file itself
C = "scene file"
case("file-missing", C, "scene file does not exist", "simulate missing.json --csv o.csv", 2,
     "missing.json: cannot open the scene file: No such file or directory", key="missing.json", gtest=(G_CMDLINE,))
case("file-directory", C, "a directory given as the scene", "simulate sub --csv o.csv", 2,
     "sub: is a directory; give a scene file (JSON)", key="sub", files={"sub": Dir}, gtest=(G_ABSURD,))
case("file-empty", C, "empty scene file (0 bytes)", SIM, 2,
     "scene.json: invalid JSON at line 1, column 1", key="scene.json", files={"scene.json": ""})
case("file-blank", C, "scene file of blanks only", SIM, 2,
     "invalid JSON at line 1, column 4", key="scene.json", files={"scene.json": "   "})
case("file-dev-null", C, "/dev/null as the scene", "simulate /dev/null --csv o.csv", 2,
     "/dev/null: invalid JSON at line 1, column 1", key="/dev/null", files={})
case("file-dev-zero", C, "/dev/zero as the scene (never ends)", "simulate /dev/zero --csv o.csv", 2,
     "/dev/zero: more than 16777216 bytes", key="/dev/zero", files={}, timeout=10, gtest=(G_ABSURD,))
case("file-huge", C, "17 MiB scene file", SIM, 2,
     "scene.json: more than 16777216 bytes; a scene file is a small JSON document", key="scene.json",
     files={"scene.json": huge_zeros}, timeout=10)
case("file-binary", C, "binary garbage (NUL, control bytes)", SIM, 2,
     "scene.json: invalid JSON at line 1, column 1", key="scene.json", files={"scene.json": b"\x00\x01\x02garbage"})
case("file-not-utf8", C, "Latin-1 byte in a string (not UTF-8)", SIM, 2,
     "UTF-8", key="UTF-8",
     files={"scene.json": VALID.encode()[:-1] + b', "name": "caf\xe9"}'})
case("file-bom", C, "UTF-8 byte-order mark before the JSON (must work)", SIM, 0, None,
     files={"scene.json": b"\xef\xbb\xbf" + VALID.encode()}, produces=("o.csv",))
PROBE3 = "accepted or unclear before"
case("file-nul-then-garbage", C, "a valid scene, then a NUL byte and garbage (the NUL ended the parse)", SIM, 2,
     "scene.json: invalid JSON at line 1, column", key="NUL", files={"scene.json": VALID.encode() + b"\0 xyz {"},
     na_before=PROBE3)
case("file-name-empty", C, "simulate '' (an empty scene name)", "simulate '' --csv o.csv", 2,
     "the scene file name is empty; give a scene file", key="scene file name", na_before=PROBE3)
case("file-deep-nesting", C, "2 000 000 nested arrays (4 MB)", SIM, 2,
     "(top level): must be an object, got an array", key="top level", files={"scene.json": deep_arrays}, timeout=30)
case("file-deep-in-field", C, "a million nested arrays as render.camera.eye", SIM, 2,
     "render.camera.eye: must be an array of three finite numbers", key="render.camera.eye",
     files={"scene.json": VALID[:-1] + ', "render": {"camera": {"eye": ' + "[" * 1_000_000 + "]" * 1_000_000 + "}}}"})

# `-` as the scene is standard input for every command that takes one (before: it was taken for
# a file named "-"); a file redirected in is an input no output may replace.
STDIN_BEFORE = "read a file named - before"
case("stdin-scene", C, "simulate - < scene.json (must work)", "exec {bin} simulate - --csv o.csv < scene.json", 0, None,
     shell=True, produces=("o.csv",), na_before=STDIN_BEFORE)
for command in ("simulate - --csv o.csv", "steady -", "render - -o o.mp4", "still - --time 0.1 -o o.png",
                "sweep - --grid initial.theta=1:2:2 -o o.csv", "export - -o o.html"):
    case(f"stdin-bad-{command.split()[0]}", C, f"{command} < a scene with coin.radius -1: its message names stdin",
         "exec {bin} " + command + " < bad.json", 2, "standard input: coin.radius: must be in [1e-06, 1000] m, got -1",
         key="standard input", shell=True, files={"bad.json": scene(coin={"radius": -1})}, na_before=STDIN_BEFORE)
case("stdin-closed", C, "simulate - with standard input closed", "exec {bin} simulate - --csv o.csv <&-", 2,
     "scene -: standard input is closed; give the scene on it (coinroll simulate - < scene.json), or name the scene "
     "file instead of -", key="standard input", shell=True, na_before=STDIN_BEFORE)
case("stdin-output-is-input", C, "simulate - --csv scene.json < scene.json: the CSV would replace the scene read",
     "exec {bin} simulate - --csv scene.json < scene.json", 2,
     "--csv scene.json: that is the input /dev/stdin; choose another output name", key="--csv", shell=True,
     na_before=STDIN_BEFORE)

# --- JSON syntax and values
C = "scene values"
case("json-trailing-comma", C, "trailing comma after the last member", SIM, 2,
     "scene.json: invalid JSON at line 1, column", key="line 1", files={"scene.json": VALID[:-1] + ",}"})
case("json-missing-comma", C, "missing comma, error on line 3", SIM, 2,
     "invalid JSON at line 3", key="line 3",
     files={"scene.json": '{\n  "coin": {"radius": 0.0375, "mass": 0.4}\n  "initial": {}, "duration": 1}'})
case("json-truncated", C, "file cut off before its closing brace", SIM, 2,
     "unexpected end of input; expected '}'", key="line 1", files={"scene.json": VALID[:-1]})
case("json-top-array", C, "top level is an array", SIM, 2, "(top level): must be an object, got an array",
     key="top level", files={"scene.json": "[]"})
case("json-top-number", C, "top level is a number", SIM, 2, "(top level): must be an object, got 42",
     key="top level", files={"scene.json": "42"})
case("json-nan", C, "NaN literal as duration", SIM, 2, "invalid literal", key="invalid literal",
     files={"scene.json": VALID.replace('"duration": 0.5', '"duration": NaN')})
case("json-overflow", C, "number beyond double range (1e400)", SIM, 2,
     "number overflow parsing '1e400' (numbers must be finite doubles)", key="1e400",
     files={"scene.json": scene(gravity=1.0).replace("1.0", "1e400")}, gtest=(G_SCENES,))
case("key-unknown", C, "unknown top-level key", SIM, 2,
     "colour: unknown key; allowed here: name, coin,", key="colour", files={"scene.json": scene(colour="red")},
     gtest=(G_SCENES,))
case("key-misspelt", C, "misspelt required key (duraton)", SIM, 2, "duraton: unknown key; allowed here:",
     key="duraton", files={"scene.json": scene(duration=DELETE, duraton=1)})
case("key-unknown-nested", C, "unknown key inside coin", SIM, 2,
     "coin.colour: unknown key; allowed here: shape, radius,", key="coin.colour",
     files={"scene.json": scene(coin={"colour": "gold"})})
case("type-duration-string", C, "duration is a string", SIM, 2, 'duration: must be a number, got string "long"',
     key="duration", files={"scene.json": scene(duration="long")}, gtest=(G_SCENES,))
case("type-duration-bool", C, "duration is true", SIM, 2, "duration: must be a number, got boolean true",
     key="duration", files={"scene.json": scene(duration=True)})
case("type-duration-null", C, "duration is null", SIM, 2, "duration: must be a number, got null",
     key="duration", files={"scene.json": scene(duration=None)})
case("type-coin-array", C, "coin is an array", SIM, 2, "coin: must be an object, got an array",
     key="coin", files={"scene.json": json.dumps({**BASE, "coin": []})})
case("type-name-number", C, "name is a number", SIM, 2, "name: must be a string, got 5",
     key="name", files={"scene.json": scene(name=5)})
case("required-mass", C, "coin.mass missing", SIM, 2, 'coin.mass: required (a number in kg); add it, e.g. "mass": 0.4', key="coin.mass",
     files={"scene.json": json.dumps({**BASE, "coin": {"radius": 0.0375}})})
case("required-duration", C, "duration missing", SIM, 2, 'duration: required (a number in s); add it, e.g. "duration": 1', key="duration",
     files={"scene.json": scene(duration=DELETE)})
case("required-initial", C, "initial missing", SIM, 2, "initial", files={"scene.json": scene(initial=DELETE)},
     gtest=(G_SCENES,))
case("range-radius", C, "coin.radius -1", SIM, 2, "coin.radius: must be in [1e-06, 1000] m, got -1", key="coin.radius",
     files={"scene.json": scene(coin={"radius": -1})}, gtest=(G_SCENES,))
case("range-mass", C, "coin.mass 0", SIM, 2, "coin.mass: must be in [1e-09, 1e+09] kg, got 0", key="coin.mass",
     files={"scene.json": scene(coin={"mass": 0})}, gtest=(G_SCENES,))
case("range-gravity", C, "gravity 0", SIM, 2, "gravity: must be in (0, 10000] m/s^2, got 0", key="gravity",
     files={"scene.json": scene(gravity=0)})
case("range-friction", C, "friction -0.1", SIM, 2, "friction: must be >= 0, got -0.1", key="friction",
     files={"scene.json": scene(friction=-0.1)})
case("range-theta", C, "initial.theta 95 degrees", SIM, 2, "initial.theta: must be in (-90, 90) degrees",
     key="theta", files={"scene.json": scene(initial={"theta": 95})}, gtest=(G_SCENES,))
case("range-duration", C, "duration -3", SIM, 2, "duration: must be > 0", key="duration",
     files={"scene.json": scene(duration=-3)}, gtest=(G_SCENES,))
case("shape-unknown", C, "coin.shape triangle", SIM, 2, "coin.shape", key="shape",
     files={"scene.json": scene(coin={"shape": "triangle"})}, gtest=(G_SCENES,))
case("ring-inner-too-big", C, "ring inner_radius > radius", SIM, 2,
     "coin.inner_radius: must be in [0, radius = 0.0375] m, got 0.05", key="coin.inner_radius",
     files={"scene.json": scene(coin={"shape": "ring", "inner_radius": 0.05})})
case("disk-with-inner", C, "inner_radius on a disk", SIM, 2, 'coin.inner_radius: only with shape: "ring" (only a ring has a hole); remove inner_radius or give shape: "ring"',
     key="coin.inner_radius", files={"scene.json": scene(coin={"inner_radius": 0.01})})
case("custom-no-inertia", C, "custom coin without I_X", SIM, 2, "coin.I_X", key="I_X",
     files={"scene.json": scene(coin={"shape": "custom"})}, gtest=(G_SCENES,))
case("custom-iz-too-big", C, "custom I_Z > 2 I_X", SIM, 2, "coin.I_Z", key="I_Z",
     files={"scene.json": scene(coin={"shape": "custom", "I_X": 1e-5, "I_Z": 3e-5})}, gtest=(G_SCENES,))
case("disk-with-inertia", C, "I_X given for a disk", SIM, 2, 'coin.I_X: only with shape: "custom" (the other shapes fix the inertia); remove I_X or give shape: "custom"',
     key="coin.I_X", files={"scene.json": scene(coin={"I_X": 0.01})})
case("steady-unknown", C, "initial.steady wobble", SIM, 2,
     'initial.steady: must be "straight", "circle" or "spin-in-place", got "wobble"', key="initial.steady",
     files={"scene.json": scene(initial={"steady": "wobble", "theta": DELETE, "omega_Z": DELETE})})
case("steady-no-spin", C, "steady straight without omega_Z", SIM, 2,
     'initial.omega_Z: required with steady: "straight" or "circle" (a coin spinning in place has omega_Z = 0); add it, e.g. "omega_Z": 10', key="omega_Z",
     files={"scene.json": scene(initial={"steady": "straight", "theta": DELETE, "omega_Z": DELETE})})
case("steady-with-rates", C, "steady circle with omega_X as well", SIM, 2,
     "initial.omega_X: unknown key; allowed here: steady, theta,", key="omega_X",
     files={"scene.json": scene(initial={"steady": "circle", "theta": 20, "omega_Z": 10, "omega_X": 3})})
case("huge-radius", C, "coin.radius 1e308 (finite, absurd)", SIM, 2, "coin.radius", key="coin.radius",
     files={"scene.json": scene(coin={"radius": 1e308})})
case("huge-spin", C, "initial.omega_Z 1e300 rad/s", SIM, 2, "initial.omega_Z", key="omega_Z",
     files={"scene.json": scene(initial={"omega_Z": 1e300})})

# --- the coin's rim: coin.thickness makes the coin a solid, coin.edge_radius rounds its rim (docs/contract.md §5)
# Meaning: what a scene says is what runs, or it is refused.
MEANING = "accepted before, with another meaning"
case("theta-beyond-flat-euler", C, "initial.theta 89.5 in the Euler-angle formulation, whose flat stop is 89 deg",
     SIM + " --set initial.theta=89.5 --set solver.formulation=euler-angles", 2,
     'initial.theta: 89.5 deg is at or beyond ±89 deg, where this run stops (coin-flat: the formulation\'s limit near '
     'flat); start inside (-89, 89) deg, or use solver.formulation "quaternion" (limit ±89.99 deg)', key="initial.theta",
     na_before=MEANING)
case("theta-at-flat-euler", C, "initial.theta exactly 89, the Euler-angle formulation's flat stop",
     SIM + " --set initial.theta=89 --set solver.formulation=euler-angles", 2,
     "initial.theta: 89 deg is at or beyond ±89 deg", key="initial.theta", na_before=MEANING)
case("theta-beyond-flat-negative", C, "initial.theta -89.995, beyond the quaternion formulation's -89.99",
     SIM + " --set initial.theta=-89.995 --set solver.formulation=quaternion", 2,
     "initial.theta: -89.995 deg is at or beyond ±89.99 deg", key="initial.theta", na_before=MEANING)
case("duplicate-key", C, "initial.theta given twice in one object", SIM, 2,
     "scene.json: initial.theta: given twice; give each key once", key="initial.theta",
     files={"scene.json": VALID.replace('"initial": {', '"initial": {"theta": 3, ')}, na_before=MEANING)
case("duplicate-key-top", C, "duration given twice at the top level", SIM, 2,
     "scene.json: duration: given twice", key="duration",
     files={"scene.json": VALID[:-1] + ', "duration": 2}'}, na_before=MEANING)
case("phi-huge", C, "initial.phi 1e20 deg (the heading froze)", SIM + " --set initial.phi=1e20", 2,
     "initial.phi: must be in [-1e+06, 1e+06] deg (an angle is the same modulo 360; reduce it), got 1e+20",
     key="initial.phi", na_before=MEANING)
# The projection needs 2^20 steps first: 2.5 s in a release build, over 30 s under the sanitizers.
case("duration-hopeless", C, "duration 1e6 s of a wobbling coin: 8.5e7 steps, more than a run may take",
     SIM + " --set duration=1e6 --sample-dt 1000", 1,
     "steps to reach t = 1000000 s at its pace so far", key="duration",
     timeout=150, na_before="failed after 5e7 steps (30 s) before")
case("steady-infinite-rate", C, "steady circle at 1e-200 deg without spin: omega_Y would be inf",
     "steady --kind circle --theta 1e-200 --omega-Z 0", 2,
     "initial.steady: this steady motion needs rates beyond any number (omega_X = 0, omega_Y = inf", key="initial.steady",
     na_before=MEANING)

C = "coin's rim"
NO_RIM = "no coin.edge_radius (thickness drawn only) before"
CORNERED = {"thickness": 0.013, "edge_radius": 0.001}  # rho < h/2: two corners meet at upright
G_THICK = "CliTest.SteadyOfAFullyRoundedThickCoinPrintsItsRimAndALowerCriticalSpin"
G_CORNERED = "CliTest.SteadyOfACorneredRimHasAVerdictButNoCriticalSpin"
case("rim-edge-without-thickness", C, "coin.edge_radius without coin.thickness", SIM, 2,
     "coin.edge_radius: only with thickness (a thin coin has no rim to round); remove edge_radius or give thickness, e.g. 0.003", key="coin.edge_radius",
     files={"scene.json": scene(coin={"edge_radius": 0.001})}, na_before=NO_RIM)
case("rim-edge-negative", C, "coin.edge_radius -0.001", SIM, 2,
     "coin.edge_radius: must be in [0, 0.0065] m (at most thickness / 2 = 0.0065 m), got -0.001", key="coin.edge_radius",
     files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": -0.001})}, na_before=NO_RIM)
case("rim-edge-past-half", C, "coin.edge_radius 0.007 > thickness / 2 = 0.0065", SIM, 2,
     "coin.edge_radius: must be in [0, 0.0065] m (at most thickness / 2 = 0.0065 m), got 0.007", key="coin.edge_radius",
     files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": 0.007})}, na_before=NO_RIM)
case("rim-edge-past-ring-width", C, "ring: coin.edge_radius 0.001 > radius - inner_radius = 0.0005", SIM, 2,
     "coin.edge_radius: must be in [0, 0.0005] m (at most thickness / 2 = 0.0065 m and radius - inner_radius = 0.0005 m, "
     "the ring's width), got 0.001", key="coin.edge_radius",
     files={"scene.json": scene(coin={"shape": "ring", "inner_radius": 0.037, "thickness": 0.013, "edge_radius": 0.001})},
     na_before=NO_RIM)
case("rim-thickness-zero", C, "coin.thickness 0", SIM, 2, "coin.thickness: must be in [6e-08, 1000] m, got 0",
     key="coin.thickness", files={"scene.json": scene(coin={"thickness": 0})})
case("rim-thickness-negative", C, "coin.thickness -0.013", SIM, 2, "coin.thickness: must be in [6e-08, 1000] m, got -0.013",
     key="coin.thickness", files={"scene.json": scene(coin={"thickness": -0.013})})
case("rim-thickness-string", C, 'coin.thickness "13mm" (a string)', SIM, 2,
     'coin.thickness: must be a number, got string "13mm"', key="coin.thickness",
     files={"scene.json": scene(coin={"thickness": "13mm"})})
case("rim-edge-nan", C, "--set coin.edge_radius=NaN", SIM + " --set coin.thickness=0.013 --set coin.edge_radius=NaN", 2,
     'coin.edge_radius: must be a number, got string "NaN"', key="coin.edge_radius", na_before=NO_RIM)
case("rim-edge-nan-literal", C, "NaN literal as coin.edge_radius in the file (not JSON)", SIM, 2,
     "scene.json: invalid JSON at line 1, column", key="scene.json",
     files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": 0.001}).replace("0.001", "NaN")})
case("rim-edge-string", C, 'coin.edge_radius "1mm" (a string)', SIM, 2,
     'coin.edge_radius: must be a number, got string "1mm"', key="coin.edge_radius",
     files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": "1mm"})}, na_before=NO_RIM)
case("rim-edge-null", C, "coin.edge_radius null", SIM, 2, "coin.edge_radius: must be a number, got null",
     key="coin.edge_radius", files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": None})}, na_before=NO_RIM)
case("rim-upright-corners", C, "initial.theta 0 with a cornered rim (h 0.013, rho 0.001): stands on two corners", SIM, 2,
     "initial.theta: a coin whose rim has corners (coin.edge_radius < thickness / 2) cannot start upright",
     key="initial.theta", files={"scene.json": scene(coin=CORNERED, initial={"theta": 0})}, na_before=NO_RIM)
case("rim-steady-straight-corners", C, "steady straight with a cornered rim", SIM, 2,
     "initial.steady: steady state straight: a rim with corners (edge radius 0.001000 m < thickness / 2 = 0.006500 m) "
     "cannot roll upright", key="initial.steady",
     files={"scene.json": scene(coin=CORNERED, initial={"steady": "straight", "theta": DELETE, "omega_Z": 12})},
     na_before=NO_RIM)
case("rim-steady-cmd-corners", C, "coinroll steady --kind straight with a cornered rim",
     "steady --kind straight --omega-Z 12 --set coin.thickness=0.013 --set coin.edge_radius=0.001", 2,
     "initial.steady: steady state straight: a rim with corners", key="initial.steady", files={}, gtest=(G_CORNERED,),
     na_before=NO_RIM)
case("rim-euler-angles-landing", C, 'solver.formulation "euler-angles" with thickness and effects', SIM, 2,
     'solver.formulation: "euler-angles" cannot carry a coin with thickness and effects to its landing',
     key="solver.formulation",
     files={"scene.json": scene(coin={"thickness": 0.013}, solver={"formulation": "euler-angles"},
                                effects=[{"type": "air_drag"}])},
     na_before="no thick-coin dynamics (thickness drawn only) before")
case("rim-thick-default-edge", C, "coin.thickness 0.013 with the default edge radius (fully rounded; must work)", SIM, 0,
     None, files={"scene.json": scene(coin={"thickness": 0.013})}, produces=("o.csv",))
case("rim-thick-upright", C, "fully rounded thick coin started upright (rolls through; must work)", SIM, 0, None,
     files={"scene.json": scene(coin={"thickness": 0.013}, initial={"theta": 0})}, produces=("o.csv",))
case("rim-sharp-tilted", C, "coin.edge_radius 0 (sharp corners), tilted start (must work)", SIM, 0, None,
     files={"scene.json": scene(coin={"thickness": 0.013, "edge_radius": 0})}, produces=("o.csv",), na_before=NO_RIM)
case("rim-ring-thick", C, "ring (inner_radius 0.03) with coin.thickness 0.004 (must work)", SIM, 0, None,
     files={"scene.json": scene(coin={"shape": "ring", "inner_radius": 0.03, "thickness": 0.004})}, produces=("o.csv",))
case("rim-steady-cmd-thick", C, "coinroll steady on a thick coin, straight (must work)",
     "steady --kind straight --omega-Z 12 --set coin.thickness=0.013", 0, None, files={}, gtest=(G_THICK,),
     na_before=NO_RIM)
case("rim-steady-cmd-cornered-circle", C, "coinroll steady, circle on a cornered rim: no critical spin (must work)",
     "steady --kind circle --theta 20 --omega-Z 10 --set coin.thickness=0.013 --set coin.edge_radius=0.0016", 0, None,
     files={}, gtest=(G_CORNERED,), na_before=NO_RIM)

# --- the render block
# --- rolling and sliding: "sliding", "friction_static", initial.v_x / v_z (docs/contract.md §6)
C = "rolling and sliding"
NO_SLIDING = "no sliding before"
case("sliding-without-friction", C, "sliding true without friction", SIM, 2,
     "sliding: true only with friction (the coefficient of Coulomb friction while the coin slides); remove sliding or give friction", key="sliding", files={"scene.json": scene(sliding=True)}, na_before=NO_SLIDING)
case("sliding-not-boolean", C, "sliding \"yes\"", SIM, 2, "sliding", key="sliding",
     files={"scene.json": scene(sliding="yes", friction=0.3)}, na_before=NO_SLIDING)
case("static-below-kinetic", C, "friction_static 0.2 < friction 0.3", SIM, 2,
     "friction_static: must be >= friction = 0.3", key="friction_static",
     files={"scene.json": scene(friction=0.3, friction_static=0.2)}, na_before=NO_SLIDING)
case("static-without-kinetic", C, "friction_static without friction", SIM, 2,
     "friction_static: only with friction (the kinetic coefficient, which it must be at least); remove friction_static or give friction", key="friction_static",
     files={"scene.json": scene(friction_static=0.5)}, na_before=NO_SLIDING)
case("velocity-without-sliding", C, "initial.v_x without sliding", SIM, 2,
     "initial.v_x: only with sliding: true (a rolling coin's velocity follows from its rates); remove v_x or give sliding: true", key="initial.v_x",
     files={"scene.json": scene(initial={"v_x": 1.0})}, na_before=NO_SLIDING)
case("velocity-absurd", C, "initial.v_z 1e9 m/s", SIM, 2, "initial.v_z", key="v_z",
     files={"scene.json": scene(sliding=True, friction=0.3, initial={"v_z": 1e9})}, na_before=NO_SLIDING)
case("sliding-in-euler-angles", C, "sliding with solver.formulation euler-angles", SIM, 2,
     "solver.formulation: \"euler-angles\" does not carry sliding", key="solver.formulation",
     files={"scene.json": scene(sliding=True, friction=0.3, solver={"formulation": "euler-angles"})}, na_before=NO_SLIDING)
case("sliding-painleve-start", C, "a disk at 24 deg sliding sideways away from under its centre, friction 2", SIM, 2,
     "initial: the coin starts sliding with no unique normal force (Painleve", key="initial",
     files={"scene.json": scene(sliding=True, friction=2, initial={"theta": 24, "omega_Z": 0, "v_z": -1})},
     na_before=NO_SLIDING)
case("sliding-skid-runs", C, "an upright skid (must work)", SIM, 0, "rolls at t = ", produces=("o.csv",),
     files={"scene.json": scene(sliding=True, friction=0.3, initial={"theta": 0, "v_x": 1.0})}, na_before=NO_SLIDING)

# --- flight and impact: "flight", "restitution", "impact_friction", initial.y / v_y (docs/flight.md)
C = "flight and impact"
NO_FLIGHT = "no flight before"
FLY = {"sliding": True, "friction": 0.3, "flight": True, "restitution": 0.5}
case("flight-without-sliding", C, "flight true without sliding", SIM, 2,
     "flight: true only with sliding: true (a coin that lands rolls or slides again); remove flight or give sliding: true", key="flight",
     files={"scene.json": scene(flight=True, friction=0.3, restitution=0.5)}, na_before=NO_FLIGHT)
case("flight-without-restitution", C, "flight true without restitution", SIM, 2,
     'restitution: required with flight: true (the impacts of a flight bounce by it); add it, e.g. "restitution": 0.5', key="restitution",
     files={"scene.json": scene(sliding=True, friction=0.3, flight=True)}, na_before=NO_FLIGHT)
case("restitution-above-one", C, "restitution 1.5", SIM, 2, "restitution: must be in [0, 1], got 1.5",
     key="restitution", files={"scene.json": scene(**{**FLY, "restitution": 1.5})}, na_before=NO_FLIGHT)
case("restitution-without-flight", C, "restitution without flight", SIM, 2,
     "restitution: only with flight: true (the impacts of a flight bounce by it); remove restitution or give flight: true", key="restitution",
     files={"scene.json": scene(sliding=True, friction=0.3, restitution=0.5)}, na_before=NO_FLIGHT)
case("impact-friction-negative", C, "impact_friction -0.1", SIM, 2, "impact_friction: must be", key="impact_friction",
     files={"scene.json": scene(**FLY, impact_friction=-0.1)}, na_before=NO_FLIGHT)
case("height-without-flight", C, "initial.y without flight", SIM, 2, "initial.y: only with flight: true (a rolling or sliding coin's height and vertical velocity follow from its attitude "
     "and rates); remove y or give flight: true",
     key="initial.y", files={"scene.json": scene(sliding=True, friction=0.3, initial={"y": 0.1})},
     na_before=NO_FLIGHT)
case("height-below-floor", C, "initial.y puts the rim below the floor", SIM, 2,
     "initial.y: 0.01 m puts the rim", key="initial.y",
     files={"scene.json": scene(**FLY, initial={"y": 0.01})}, na_before=NO_FLIGHT)
case("vertical-velocity-into-floor", C, "initial.v_y -1 m/s on the floor", SIM, 2,
     "initial.v_y: the coin's rim would move into the floor", key="initial.v_y",
     files={"scene.json": scene(**FLY, initial={"v_y": -1})}, na_before=NO_FLIGHT)
case("decided-without-flight", C, "stop_when_decided without flight", SIM, 2,
     "stop_when_decided: only with flight: true (it ends a toss once its face up is final); remove stop_when_decided or "
     "give flight: true", key="stop_when_decided",
     files={"scene.json": scene(sliding=True, friction=0.3, stop_when_decided=True)}, na_before=NO_FLIGHT)
case("decided-not-boolean", C, "stop_when_decided \"yes\"", SIM, 2, "stop_when_decided: must be", key="stop_when_decided",
     files={"scene.json": scene(**FLY, stop_when_decided="yes")}, na_before=NO_FLIGHT)
case("flight-drop-runs", C, "a coin dropped edge-down (must work)", SIM, 0, "impact at t = ", produces=("o.csv",),
     files={"scene.json": scene(**FLY, initial={"theta": 0, "y": 0.1})}, na_before=NO_FLIGHT)

C = "render block"
REN = "render scene.json -q -o o.mp4 --set "
case("fps-zero", C, "render.fps 0", REN + "render.fps=0", 2, "render.fps: must be in [1, 240], got 0", key="render.fps")
case("fps-high", C, "render.fps 241", REN + "render.fps=241", 2, "render.fps: must be in [1, 240], got 241",
     key="render.fps")
case("fps-fraction", C, "render.fps 29.97", REN + "render.fps=29.97", 2, "render.fps: must be an integer, got 29.97",
     key="render.fps")
case("width-negative", C, "render.width -5", REN + "render.width=-5", 2, "render.width: must be an even number",
     key="render.width", gtest=(G_RENDER,))
case("width-odd", C, "render.width 641 (odd)", REN + "render.width=641", 2,
     "render.width: must be an even number of pixels in [16, 7680] (H.264 yuv420p needs even sizes), got 641",
     key="render.width")
case("width-huge", C, "render.width 8000", REN + "render.width=8000", 2, "render.width: must be an even number",
     key="render.width")
case("height-tiny", C, "render.height 8", REN + "render.height=8", 2, "render.height: must be an even number",
     key="render.height")
case("msaa", C, "render.msaa 3", REN + "render.msaa=3", 2, "render.msaa: must be 1, 2, 4 or 8 samples, got 3",
     key="render.msaa", gtest=(G_RENDER,))
case("time-scale", C, "render.time_scale 0", REN + "render.time_scale=0", 2, "render.time_scale: must be > 0, got 0",
     key="render.time_scale")
case("crf", C, "render.video.crf 52", REN + "render.video.crf=52", 2, "render.video.crf: must be in [0, 51], got 52",
     key="render.video.crf")
case("x264-threads", C, "render.video.threads 0", REN + "render.video.threads=0", 2,
     "render.video.threads: must be in [1, 16], got 0", key="render.video.threads")
case("preset", C, "render.video.preset warp", REN + "render.video.preset=warp", 2,
     'render.video.preset: must be one of ultrafast,', key="preset", gtest=(G_RENDER,))
case("camera-mode", C, "render.camera.mode drone", REN + "render.camera.mode=drone", 2,
     'render.camera.mode: must be "fixed", "orbit" or "follow", got "drone"', key="render.camera.mode")
case("camera-fov", C, "render.camera.fov 180", REN + "render.camera.fov=180", 2,
     "render.camera.fov: must be in (1, 170) degrees, got 180", key="render.camera.fov")
case("camera-eye-2d", C, "render.camera.eye with two numbers", REN + "'render.camera.eye=[1,2]'", 2,
     "render.camera.eye: must be an array of three finite numbers", key="render.camera.eye")
case("camera-degenerate", C, "camera eye equal to its target (still)",
     "still scene.json --time 0.1 -o o.png --set 'render.camera={\"eye\": [0, 0.2, 0], \"target\": [0, 0.2, 0]}'", 2,
     "render.camera.target", gtest=("CliTest.ADegenerateCameraIsRefused",))
case("audio-volume", C, "render.audio.volume 2", REN + "render.audio.volume=2", 2,
     "render.audio.volume: must be in (0, 1], got 2", key="render.audio.volume")
case("audio-number", C, "render.audio 1", REN + "render.audio=1", 2,
     "render.audio: must be true, false or an object of options, got 1", key="render.audio")
case("remap-both", C, "time_remap with spin_rate and precession_rate",
     REN + "render.time_remap.spin_rate=1 --set render.time_remap.precession_rate=1", 2,
     "render.time_remap.precession_rate: not with spin_rate (one rate sets the slow-down); remove one of them", key="render.time_remap")
case("remap-growth-one", C, "time_remap growth 1 (would never slow down)",
     REN + "render.time_remap.precession_rate=10 --set render.time_remap.growth=1", 2,
     "render.time_remap.growth: must be in [0, 1)", key="render.time_remap.growth")
case("remap-empty", C, "time_remap with no rule at all",
     REN + "'render.time_remap={}'", 2,
     "render.time_remap: needs one of spin_rate, precession_rate, flight or impact (where the motion is fast, in the "
     "air or at each impact); add one or remove time_remap", key="render.time_remap")
case("remap-flight-no-slow", C, "time_remap.flight without its slow",
     REN + "render.time_remap.flight.window=0.1", 2,
     'render.time_remap.flight.slow: required (the playback rate in the air, times time_scale); add it, e.g. "slow": 0.25',
     key="render.time_remap.flight.slow")
case("remap-impact-slow-zero", C, "time_remap.impact.slow 0 (would never move on)",
     REN + "render.time_remap.impact.slow=0", 2,
     "render.time_remap.impact.slow: must be in (0, 1], got 0", key="render.time_remap.impact.slow")
case("remap-impact-window-zero", C, "time_remap.impact.window 0 (an instant no frame falls on)",
     REN + "render.time_remap.impact.slow=0.1 --set render.time_remap.impact.window=0", 2,
     "render.time_remap.impact.window: must be > 0 (the slow-down eases in and out over it", key="render.time_remap.impact.window")
case("remap-growth-alone", C, "time_remap growth with only a flight slow-down",
     REN + "render.time_remap.flight.slow=0.25 --set render.time_remap.growth=0.5", 2,
     "render.time_remap.growth: only with spin_rate or precession_rate (it shapes their slow-down); remove growth or give "
     "spin_rate or precession_rate",
     key="render.time_remap.growth")

# --- solver
C = "solver"
SOLV = SIM + " --set solver."
# The GoogleTest test tries one value below and one above each range (and atol = 0).
for value, tested in (("0", False), ("1e-15", True), ("0.1", True)):
    case(f"rtol-{value}", C, f"solver.rtol {value}", SOLV + "rtol=" + value, 2,
         f"solver.rtol: must be in [1e-14, 1e-2] (default 1e-10), got {value}", key="solver.rtol",
         gtest=(G_TOL,) if tested else ())
for value, tested in (("0", True), ("-1e-12", False), ("0.5", True)):
    case(f"atol-{value}", C, f"solver.atol {value}", SOLV + "atol=" + value, 2,
         f"solver.atol: must be in (0, 1e-2] (default 1e-12; 0 cannot weigh a state component that is 0), got {value}",
         key="solver.atol", gtest=(G_TOL,) if tested else ())
for value, shown, tested in (("0", "0", False), ("1e-8", "1e-08", True), ("2", "2", True)):
    case(f"dt-{value}", C, f"solver.dt {value} s (rk4)", SOLV + "method=rk4 --set solver.dt=" + value, 2,
         f"solver.dt: must be in [1e-7, 1] s (default 1e-3), got {shown}", key="solver.dt",
         gtest=(G_TOL,) if tested else ())
case("rtol-string", C, 'solver.rtol "1e-9" (a string)', SOLV + "rtol='\"1e-9\"'", 2,
     'solver.rtol: must be a number, got string "1e-9"', key="solver.rtol")
case("method-unknown", C, "solver.method RK4 (wrong case)", SOLV + "method=RK4", 2,
     'solver.method: unknown method "RK4"; available: euler, rk4, dopri5, dop853, gauss4', key="solver.method")
case("formulation-unknown", C, "solver.formulation matrix", SOLV + "formulation=matrix", 2, "solver.formulation",
     gtest=(G_SCENES,))

# --- effects
C = "effects"
EFF = SIM + " --set 'effects="
case("effects-object", C, "effects is an object, not a list", EFF + '{"type":"air_drag"}\'', 2,
     'effects: must be a list of effects, e.g. [{"type": "air_drag"}], got an object', key="effects",
     gtest=(G_EFFECTS,))
case("effects-string-entry", C, 'entry is the string "air_drag"', EFF + '["air_drag"]\'', 2,
     'effects[0]: must be an object with a "type"', key="effects[0]", gtest=(G_EFFECTS,))
case("effects-null-entry", C, "entry is null", EFF + "[null]'", 2,
     'effects[0]: must be an object with a "type": "air_drag", "rolling_resistance" or "spin_friction", got null',
     key="effects[0]")
case("effects-no-type", C, "entry without a type", EFF + '[{"model":"moffatt"}]\'', 2,
     'effects[0]: must be an object with a "type"', key="effects[0]")
case("effects-type-unknown", C, "type magnetism", EFF + '[{"type":"magnetism"}]\'', 2,
     'effects[0].type: must be "air_drag", "rolling_resistance" or "spin_friction", got "magnetism"',
     key="effects[0].type", gtest=(G_EFFECTS,))
case("effects-type-case", C, "type Air_Drag (wrong case)", EFF + '[{"type":"Air_Drag"}]\'', 2,
     'effects[0].type: must be "air_drag", "rolling_resistance" or "spin_friction", got "Air_Drag"',
     key="effects[0].type")
case("effects-model", C, "air_drag model turbulent", EFF + '[{"type":"air_drag","model":"turbulent"}]\'', 2,
     "effects[0].model", gtest=(G_EFFECTS,))
case("effects-viscosity", C, "air_drag viscosity -1", EFF + '[{"type":"air_drag","viscosity":-1}]\'', 2,
     "effects[0].viscosity: must be > 0, got -1", key="effects[0].viscosity", gtest=(G_EFFECTS,))
case("effects-unknown-param", C, "air_drag temperature 20", EFF + '[{"type":"air_drag","temperature":20}]\'', 2,
     "effects[0].temperature", gtest=(G_EFFECTS,))
case("effects-density-moffatt", C, "density given to Moffatt's model (boundary layer only)",
     EFF + '[{"type":"air_drag","model":"moffatt","density":1.2}]\'', 2, "effects[0].density")
case("effects-length-negative", C, "rolling_resistance length -2e-6",
     EFF + '[{"type":"rolling_resistance","length":-2e-6}]\'', 2, "effects[0].length", gtest=(G_EFFECTS,))
case("effects-load-exponent", C, "rolling_resistance load_exponent 2.5",
     EFF + '[{"type":"rolling_resistance","load_exponent":2.5}]\'', 2,
     "effects[0].load_exponent: must be in (0, 2]", key="effects[0].load_exponent")
case("effects-rate-exponent", C, "rolling_resistance rate_exponent 0.5",
     EFF + '[{"type":"rolling_resistance","rate_exponent":0.5}]\'', 2,
     "effects[0].rate_exponent: must be in [1, 3]", key="effects[0].rate_exponent")
case("effects-length-string", C, 'spin_friction length "5um"', EFF + '[{"type":"spin_friction","length":"5um"}]\'', 2,
     'effects[0].length: must be a number, got string "5um"', key="effects[0].length")
case("effects-length-huge", C, "spin_friction length 1e300 m", EFF + '[{"type":"spin_friction","length":1e300}]\'', 2,
     "effects[0].length")
case("effects-duplicate", C, "rolling_resistance twice",
     EFF + '[{"type":"rolling_resistance"},{"type":"rolling_resistance"}]\'', 2,
     'effects[1]: a second "rolling_resistance"; each law may appear once', key="effects[1]", gtest=(G_EFFECTS,))
case("on-invalid", C, "on_invalid ignore", SIM + " --set on_invalid=ignore", 2,
     'on_invalid: must be "stop" or "warn", got "ignore"', key="on_invalid", gtest=(G_EFFECTS,))

# --- --set
C = "--set"
case("set-not-utf8", C, "--set name=<byte 0xFF> on a sweep (a scene is UTF-8)",
     "exec {bin} sweep scene.json -q -o o.csv --grid initial.theta=5:10:2 --set $'name=\\xff'", 2,
     "--set name: the value is not UTF-8 text; scene values are UTF-8, as in a JSON file", key="--set name", shell=True,
     na_before="a library's message, exit 1, before")
case("set-negative", C, "--set coin.radius=-1", SIM + " --set coin.radius=-1", 2,
     "scene.json: coin.radius: must be in [1e-06, 1000] m, got -1", key="coin.radius")
case("set-unknown-key", C, "--set nosuch=1", SIM + " --set nosuch=1", 2, "nosuch: unknown key; allowed here:",
     key="nosuch")
case("set-unknown-nested", C, "--set coin.nosuch=1", SIM + " --set coin.nosuch=1", 2,
     "coin.nosuch: unknown key; allowed here: shape,", key="coin.nosuch")
NULL_KEY = "accepted in silence before"
case("set-unknown-key-null", C, "--set nosuch=null (null removes a key: there is no such key)",
     SIM + " --set nosuch=null", 2, "--set nosuch=null: nosuch: unknown key; allowed here: name,", key="nosuch",
     na_before=NULL_KEY)
case("set-unknown-nested-null", C, "--set coin.nosuch=null", SIM + " --set coin.nosuch=null", 2,
     "--set coin.nosuch=null: coin.nosuch: unknown key; allowed here: shape,", key="coin.nosuch", na_before=NULL_KEY)
case("set-unknown-parent-null", C, "--set nosuch.radius=null", SIM + " --set nosuch.radius=null", 2,
     "--set nosuch.radius=null: nosuch: unknown key; allowed here: name,", key="nosuch", na_before=NULL_KEY)
case("set-known-absent-null", C, "--set render.camera.eye=null on a scene without a render block (must work)",
     SIM + " --set render.camera.eye=null", 0, None, produces=("o.csv",), na_before=NULL_KEY)
case("set-empty-value", C, "--set coin.radius= (empty value)", SIM + " --set coin.radius=", 2,
     'coin.radius: must be a number, got string ""', key="coin.radius")
case("set-no-key", C, "--set =3", SIM + " --set =3", 2,
     "--set =3: expected KEY.PATH=VALUE, e.g. --set initial.theta=12", key="--set")
case("set-no-equals", C, "--set coin (no =)", SIM + " --set coin", 2,
     "--set coin: expected KEY.PATH=VALUE", key="--set")
case("set-leading-dot", C, "--set .coin.radius=1", SIM + " --set .coin.radius=1", 2,
     "--set .coin.radius=1: expected KEY.PATH=VALUE", key="--set")
case("set-through-number", C, "--set duration.x=1 (duration is a number)", SIM + " --set duration.x=1", 2,
     "--set duration.x=1: duration is 0.5, which has no field 'x'", key="duration")
case("set-nan", C, "--set duration=NaN", SIM + " --set duration=NaN", 2,
     'duration: must be a number, got string "NaN"', key="duration")
case("set-overflow", C, "--set duration=1e999", SIM + " --set duration=1e999", 2,
     'duration: must be a number, got string "1e999"', key="duration")
case("set-wrong-type", C, "--set initial=[1,2]", SIM + " --set 'initial=[1,2]'", 2,
     "initial: must be an object, got an array", key="initial")
case("set-range", C, "--set initial.theta=100", SIM + " --set initial.theta=100", 2, "initial.theta: must be in",
     key="theta", gtest=(G_CMDLINE,))
# Messages: each says what happened and what to do.
MESSAGES = "a misleading message before"
EFFECTS2 = scene(effects=[{"type": "air_drag"}, {"type": "rolling_resistance", "length": 1e-6}])
case("set-list-index", C, "--set effects.1.length=2e-6 changes the second effect (must work)",
     SIM + " --set effects.1.length=2e-6", 0, None, files={"scene.json": EFFECTS2}, produces=("o.csv",))
case("set-list-past-end", C, "--set effects.5.length=1 on a list of two effects", SIM + " --set effects.5.length=1", 2,
     "--set effects.5.length=1: effects is a list of 2 entries, numbered 0 to 1; '5' is none of them", key="effects",
     files={"scene.json": EFFECTS2}, na_before=MESSAGES)
case("set-list-missing", C, "--set effects.0.length=1 on a scene without effects", SIM + " --set effects.0.length=1", 2,
     "--set effects.0.length=1: the scene has no effects list; --set changes an entry of a list but cannot make one",
     key="effects", na_before=MESSAGES)
case("set-unsigned-64", C, "--set render.width=18446744073709551615 (read as -1 before)",
     SIM + " --set render.width=18446744073709551615", 2,
     "render.width: out of range [-1000000000, 1000000000], got 18446744073709551615", key="render.width",
     na_before=MESSAGES)
case("key-control-characters", C, "a scene key holding a NUL and a terminal escape: shown escaped, never raw", SIM, 2,
     'scene.json: "ab\\u0000c\\u001b[31m": unknown key', key="unknown key",
     files={"scene.json": VALID[:-1] + ', "ab\\u0000c\\u001b[31m": 1}'}, na_before=MESSAGES)
ESCAPED = "shown raw before"
case("name-escape-in-summary", C, "still -o with a terminal escape in the name: the summary shows it escaped",
     "exec {bin} still scene.json --time 0.1 " + SMALL + " -o $'\\e[31mred.png'", 0,
     "coinroll: wrote \\x1b[31mred.png (64x48", key="wrote", shell=True, produces=("\x1b[31mred.png",), na_before=ESCAPED)
case("name-newline-in-error", C, "a scene name with a line break: the error stays on one line",
     "exec {bin} simulate $'a\\nb.json' --csv o.csv", 2,
     "coinroll: error: a\\nb.json: cannot open the scene file", key="b.json", shell=True, na_before=ESCAPED)
case("camera-far-away", C, "render.camera.eye 1e300 m away (was called 'straight above')",
     "still scene.json -o s.png --time 0 --set 'render.camera.eye=[1e300,0.1,0]' --set 'render.camera.target=[0,0,0]'",
     2, "render.camera.eye: coordinates must be within [-1e+06, 1e+06] m, got [1e+300, 0.1, 0]", key="render.camera.eye",
     na_before=MESSAGES)
case("shader-dir-directory", C, "$COINROLL_SHADER_DIR holding a directory named coin.vert (was 'does not compile')",
     "COINROLL_SHADER_DIR=sd exec {bin} still scene.json -o s.png --time 0", 1,
     "shader: sd/coin.vert is a directory; $COINROLL_SHADER_DIR must hold the shader files", key="coin.vert", shell=True,
     files={"scene.json": VALID, "sd/coin.vert": Dir}, na_before=MESSAGES)

# --- the command line
C = "command line"
EMPTY = "read as 0 or as absent before"
for command, option in (("still scene.json -o s.png --time ''", "--time"),
                        ("compare a.png b.png --min-psnr ''", "--min-psnr"),
                        ("sweep scene.json -o o.csv --grid initial.theta=1:2:2 --threads ''", "--threads")):
    case(f"empty-number{option}", C, f"{option} '' (an empty number)", command, 2,
         f"{option}: the value is empty; give a number", key=option, na_before=EMPTY,
         files={"scene.json": VALID, "a.png": png(8, 8), "b.png": png(8, 8)})
case("cmd-none", C, "no command", "", 2, "A subcommand is required", key="subcommand")
case("cmd-unknown", C, "unknown command frobnicate", "frobnicate", 2,
     "unknown command 'frobnicate'; the commands are simulate, steady, render, still, sweep, sweep-merge",
     key="frobnicate", gtest=(G_CMDLINE,))
case("cmd-misspelt", C, "misspelt command simulat", "simulat scene.json", 2,
     "unknown command 'simulat'; the commands are simulate,", key="simulat", gtest=(G_ABSURD,))
case("cmd-case", C, "command in capitals (Simulate)", "Simulate scene.json --csv o.csv", 2,
     "unknown command 'Simulate'", key="Simulate")
CONVENTIONS = "no such behaviour before"
G_CONVENTIONS = "CliTest.HelpCommandIsTheCommandsHelpAndAMisspeltCommandGetsASuggestion"
case("cmd-suggestion", C, "misspelt command rendr: the command it is a slip of is suggested", "rendr scene.json", 2,
     "(coinroll --help); did you mean 'render'?", key="rendr", na_before=CONVENTIONS, gtest=(G_CONVENTIONS,))
case("cmd-help-command", C, "coinroll help render: render's help (must work)",
     "exec {bin} help render | grep -q -e --frame-times", 0, None, shell=True, na_before=CONVENTIONS,
     gtest=(G_CONVENTIONS,))
case("cmd-help-unknown", C, "coinroll help rendr", "help rendr", 2, "unknown command 'rendr'", key="rendr",
     na_before=CONVENTIONS, gtest=(G_CONVENTIONS,))
case("cmd-parse-error-style", C, "simulate without --csv: the parser's refusal in the program's style",
     "simulate scene.json", 2, "coinroll: error: --csv is required (coinroll simulate --help)", key="--csv",
     na_before=CONVENTIONS, gtest=("CliTest.ParseErrorsComeInTheProgramsOwnStyle",))
case("still-size", C, "still --size 480p, as render takes it (must work: an 854x480 PNG)",
     "still scene.json --time 0.1 -o s.png --size 480p", 0, None, produces=("s.png",), na_before=CONVENTIONS,
     check=lambda d: None if (d / "s.png").read_bytes()[16:24] == (854).to_bytes(4, "big") + (480).to_bytes(4, "big")
     else "s.png is not 854x480")
case("still-size-unknown", C, "still --size 9p", "still scene.json --time 0.1 -o s.png --size 9p", 2,
     "--size 9p: unknown size; give 480p, 720p, 1080p, 1440p or 2160p", key="--size", na_before=CONVENTIONS)
case("flag-unknown", C, "unknown flag --bogus", SIM + " --bogus", 2,
     "The following argument was not expected: --bogus", key="--bogus")
case("flag-fps", C, "render --fps 30 (fps is render.fps in the scene)", "render scene.json -o o.mp4 --fps 30", 2,
     "The following arguments were not expected: 30 --fps", key="--fps")
case("flag-size", C, "render --size 64x48 (--size takes a name; any other size is render.width/height)",
     "render scene.json -o o.mp4 --size 64x48", 2,
     "--size 64x48: unknown size; give 480p, 720p, 1080p, 1440p or 2160p (or set render.width and render.height "
     "with --set)", key="--size")
case("csv-missing", C, "simulate without --csv", "simulate scene.json", 2, "--csv is required", gtest=(G_CMDLINE,))
case("extra-positional", C, "two scene files", "simulate scene.json scene.json --csv o.csv", 2,
     "The following argument was not expected: scene.json", key="scene.json")
for value, shown in (("0", "0"), ("-1", "-1"), ("nan", "nan"), ("inf", "inf")):
    case(f"sample-dt-{value}", C, f"--sample-dt {value}", SIM + " --sample-dt " + value, 2,
         f"--sample-dt: must be a finite number > 0 s, got {shown}", key="--sample-dt",
         gtest=(G_CMDLINE,) if value == "0" else ())
case("sample-dt-text", C, "--sample-dt abc", SIM + " --sample-dt abc", 2, "Could not convert: --sample-dt = abc",
     key="--sample-dt")
case("max-rows-negative", C, "--max-rows -5", SIM + " --max-rows -5", 2, "--max-rows",
     na_before="no --max-rows before")
case("max-rows-small", C, "--max-rows 10 for a 51-row run", SIM + " --max-rows 10", 2,
     "gives 51 rows (about 15.3 kB of CSV), more than the limit 10; raise --sample-dt, or the limit with --max-rows",
     key="--max-rows",
     na_before="no --max-rows before")
case("max-frames-small", C, "--max-frames 10 for a 16-frame clip", REN.replace("--set ", "") + "--max-frames 10", 2,
     "gives 16 frames, more than the limit 10;", key="--max-frames", gtest=(G_ABSURD,),
     na_before="no --max-frames before")
case("max-frames-negative", C, "--max-frames -1", REN.replace("--set ", "") + "--max-frames -1 " + SMALL, 2,
     "--max-frames", na_before="no --max-frames before")
case("max-frames-text", C, "--max-frames abc", REN.replace("--set ", "") + "--max-frames abc", 2,
     "--max-frames: must be a whole number >= 1, got abc", key="--max-frames", na_before="no --max-frames before")
case("render-avi", C, "render -o o.avi", "render scene.json -o o.avi", 2,
     "o.avi: unknown output kind: expected a video ending in .mp4, .gif, .webm or .mov", key=".mp4", gtest=(G_RENDER,))
FORMATS = "no such option or scene field before"
RW = "render scene.json -q -o o.mp4 "
case("size-unknown", C, "render --size 4k", RW + "--size 4k", 2,
     "--size 4k: unknown size; give 480p, 720p, 1080p, 1440p or 2160p", key="--size", gtest=(G_RENDER,),
     na_before=FORMATS)
case("from-after-to", C, "render --from 0.4 --to 0.1", RW + "--from 0.4 --to 0.1", 2,
     "--from 0.4 --to 0.1: the window ends before it starts; give --from <= --to", key="--from", gtest=(G_RENDER,),
     na_before=FORMATS)
case("from-beyond-end", C, "render --from 2 past a 0.5 s run", RW + "--from 2", 2,
     "--from 2: beyond the run's end at 0.5 s; give a time in [0, 0.5]", key="--from",
     gtest=(G_RENDER,), na_before=FORMATS)
case("from-negative", C, "render --from -1", RW + "--from -1", 2, "--from -1: must be a simulated time >= 0 s",
     key="--from", gtest=(G_RENDER,), na_before=FORMATS)
case("to-nan", C, "render --to nan", RW + "--to nan", 2,
     "--to nan: must be a finite number of seconds (simulated time >= 0 s); leave --to out for the clip's end", key="--to",
     na_before=FORMATS)
case("from-empty", C, "render --from ''", RW + "--from ''", 2, "--from: the value is empty; give a number",
     key="--from", na_before=FORMATS)
case("window-without-frames", C, "render --from 0.21 --to 0.22: no frame at 30 fps in between",
     RW + "--from 0.21 --to 0.22", 2, "--from 0.21 --to 0.22: no frame's simulated time lies in this window",
     key="--from", gtest=(G_RENDER,), na_before=FORMATS)
# Windows by video time and the dry run: one clock at a time, each refusal naming both options.
VIDEO_TIME = "no video-time windows and no --plan before"
case("from-and-from-video", C, "render --from 1 --from-video 2: two clocks", RW + "--from 1 --from-video 2", 2,
     "--from and --from-video cannot be combined: --from counts simulated seconds, --from-video seconds of video",
     key="--from-video", na_before=VIDEO_TIME)
case("to-and-last", C, "render --to 0.4 --last 0.2: two clocks", RW + "--to 0.4 --last 0.2", 2,
     "--to and --last cannot be combined", key="--last", na_before=VIDEO_TIME)
case("last-and-from-video", C, "render --last 0.2 --from-video 0.1: two ways to start", RW + "--last 0.2 --from-video 0.1",
     2, "--last and --from-video cannot be combined: --last L is the window from L s of video before the clip's end",
     key="--last", na_before=VIDEO_TIME)
case("from-video-after-to-video", C, "render --from-video 0.4 --to-video 0.1", RW + "--from-video 0.4 --to-video 0.1", 2,
     "--from-video 0.4 --to-video 0.1: the window ends before it starts; give --from-video <= --to-video",
     key="--from-video", na_before=VIDEO_TIME)
case("from-video-beyond-end", C, "render --from-video 5 past a 0.5 s clip", RW + "--from-video 5", 2,
     "--from-video 5: beyond the clip's last frame at 0.5 s of video", key="--from-video", na_before=VIDEO_TIME)
case("last-zero", C, "render --last 0", RW + "--last 0", 2, "--last 0: give the seconds of video to keep, > 0",
     key="--last", na_before=VIDEO_TIME)
case("last-shorter-than-a-frame", C, "render --last 0.01: less than a frame at 30 fps", RW + "--last 0.01", 2,
     "--last 0.01: no frame plays in the last 0.01 s", key="--last", na_before=VIDEO_TIME)
case("last-longer-than-clip", C, "render --last 5 of a 0.53 s clip", RW + "--last 5", 2,
     "--last 5: longer than the clip, which lasts 0.533333333 s of video", key="--last", na_before=VIDEO_TIME)
case("to-video-negative", C, "render --to-video -1", RW + "--to-video -1", 2,
     "--to-video -1: must be a video time >= 0 s", key="--to-video", na_before=VIDEO_TIME)
case("plan-and-frame-times", C, "render --plan --frame-times f.csv: a plan writes nothing",
     RW + "--plan --frame-times f.csv", 2, "--plan and --frame-times cannot be combined", key="--plan",
     na_before=VIDEO_TIME)
# The plan as JSON (render --plan --json, read by the WebAssembly core's drift test).
PLAN_JSON = "no --plan --json before"
case("json-without-plan", C, "render --json without --plan: no plan to print", RW + "--json", 2,
     "--json: prints the --plan as one JSON document, and there is no plan; give --plan too", key="--json",
     gtest=("FrameTimesCliTest.ThePlanAsJsonHoldsTheRendersFramesAndTheirOverlay",), na_before=PLAN_JSON)
for ext in ("mp4", "GIF"):
    case(f"transparent-{ext.lower()}", C, f"render.background transparent with .{ext}",
         f"render scene.json -q -o o.{ext} --set 'render.background=\"transparent\"'", 2,
         f'render.background: "transparent" needs an output with alpha, and .{ext.lower()} has none; write a .webm, '
         'a .mov or a PNG sequence', key="render.background", gtest=(G_RENDER,), na_before=FORMATS)
case("background-bad", C, "render.background \"clear\"", "render scene.json -q -o o.mov --set 'render.background=\"clear\"'",
     2, 'render.background: expected "opaque" or "transparent", got "clear"', key="render.background",
     gtest=(G_RENDER,), na_before=FORMATS)
case("theme-bad", C, "render.theme \"dark\"", "render scene.json -q -o o.mov --set 'render.theme=\"dark\"'", 2,
     'render.theme: must be "classic" or "paper", got "dark"', key="render.theme", na_before=FORMATS)
case("scale-bar-negative", C, "render.scale_bar -0.01", "render scene.json -q -o o.mov --set render.scale_bar=-0.01", 2,
     "render.scale_bar: must be true, false or a length in (0, 10] m, got -0.01", key="render.scale_bar",
     na_before=FORMATS)
case("scale-bar-string", C, "render.scale_bar \"1 cm\"", "render scene.json -q -o o.mov --set 'render.scale_bar=\"1 cm\"'",
     2, 'render.scale_bar: must be true, false or a length in (0, 10] m, got string "1 cm"', key="render.scale_bar",
     na_before=FORMATS)
case("provenance-bad", C, "render.provenance \"yes\"", "render scene.json -q -o o.mov --set 'render.provenance=\"yes\"'",
     2, 'render.provenance: must be true or false, got string "yes"', key="render.provenance", na_before=FORMATS)
case("audio-webm", C, "render.audio with .webm", "render scene.json -q -o o.webm --set render.audio=true", 2,
     "render.audio: a .webm gets no sound track; write a .mp4 or a .mov, or leave the sound out with --set render.audio=null", key="render.audio",
     na_before=FORMATS)
case("gif-fps-60", C, "render.fps 60 with .gif (browsers would play its 1-hundredth delays as 10)",
     "render scene.json -q -o o.gif --set render.fps=60", 2,
     "render.fps: a .gif plays at most 50 fps (its frame delays are whole hundredths of a second, and browsers play a "
     "delay under 2 as 10), got 60; set render.fps to 50 or less, or write a .mp4, a .webm or a .mov", key="render.fps",
     gtest=(G_RENDER,), na_before=FORMATS)
case("render-two-patterns", C, "PNG pattern with two %d", "render scene.json -o o_%d_%d.png", 2,
     "o_%d_%d.png: bad PNG sequence pattern: more than one % conversion", key="%")
case("render-pattern-s", C, "PNG pattern with %s", "render scene.json -o o_%s.png", 2,
     "o_%s.png: bad PNG sequence pattern: only %d and %0Nd are supported", key="%")
case("still-time-late", C, "still --time 7 past a 0.5 s run", "still scene.json --time 7 -o o.png", 2,
     "--time: must be within the scene's duration, 0 to 0.5 s, got 7", key="--time", gtest=(G_RENDER,))
case("still-time-negative", C, "still --time -1", "still scene.json --time -1 -o o.png", 2,
     "--time: must be within the scene's duration", key="--time")
case("still-time-nan", C, "still --time nan", "still scene.json --time nan -o o.png", 2,
     "--time: must be within the scene's duration, 0 to 0.5 s, got nan", key="--time")
case("still-no-time", C, "still without --time", "still scene.json -o o.png", 2, "--time is required")
case("still-jpg", C, "still -o o.jpg", "still scene.json --time 0.1 -o o.jpg", 2,
     'a still is written as PNG; give a name ending in .png, got "o.jpg"', key=".png")
# One rule for every output name: an extension in any case, as render takes clip.GIF.
case("still-upper-png", C, "still -o UP.PNG (.png in any case)", f"still scene.json --time 0.1 {SMALL} -o UP.PNG", 0, None,
     produces=("UP.PNG",))
case("render-seq-upper-png", C, "render -o F_%03d.PNG (.png in any case)",
     f"render scene.json -q {SMALL} --set duration=0.1 -o F_%03d.PNG", 0, None, produces=("F_00[0-3].PNG",))
case("panels-without-strobe", C, "still --panels without --strobe", "still scene.json --time 0.1 -o o.png --panels", 2,
     "--panels: lays out the --strobe copies side by side, and there are none; give --strobe N too", key="--panels",
     na_before="no --panels before")
case("strobe-negative", C, "still --strobe -3", "still scene.json --time 0.1 -o o.png --strobe -3", 2,
     "--strobe: must be 0 to 500 copies, got -3", key="--strobe")
case("strobe-from-late", C, "--strobe-from after --time",
     "still scene.json --time 0.3 -o o.png --strobe 4 --strobe-from 0.4", 2,
     "--strobe-from: must be at least 0 and before --time (0.3 s), got 0.4", key="--strobe-from")
for strobe in ("", "--strobe 0 "):
    case(f"strobe-from-alone{'-zero' if strobe else ''}", C, f"still {strobe}--strobe-from 0.05 (no copies to place)",
         f"still scene.json --time 0.1 -o o.png {strobe}--strobe-from 0.05", 2,
         "--strobe-from: places the first of the --strobe copies, and there are none; give --strobe N too",
         key="--strobe-from", na_before=PROBE3)
case("steady-kind", C, "steady --kind wobble", "steady --kind wobble", 2,
     "--kind: wobble not in {straight,circle,spin-in-place}", key="--kind")
case("steady-no-kind", C, "steady --theta without --kind", "steady --theta 20", 2,
     "--theta, --omega-Z and --branch describe a steady state: give --kind too", key="--kind",
     gtest=("CliTest.SteadyReportsKAndAVerdict",))
case("steady-theta", C, "steady --theta 95", "steady --kind circle --theta 95 --omega-Z 10", 2,
     "initial.theta: must be in (-90, 90) degrees", key="theta")
case("steady-branch", C, "steady --branch x", "steady --kind circle --theta 20 --omega-Z 10 --branch x", 2,
     "--branch: x not in {+,-}", key="--branch")
for option, value in (("--theta", "nan"), ("--omega-Z", "-inf")):
    case(f"steady-{option[2:].lower()}-{value.strip('-')}", C, f"steady {option} {value}",
         f"steady --kind circle {'--omega-Z 10' if option == '--theta' else '--theta 20'} {option} {value}", 2,
         f"{option}: must be a finite number, got {value}", key=option, na_before="said 'got null' before")
case("steady-kind-with-set", C, "steady --kind circle with --set initial.phi=45: the --set lands on the kind's block",
     "exec {bin} steady --kind circle --omega-Z 10 --set initial.theta=20 --set initial.phi=45 > out.txt", 0, None,
     shell=True, produces=("out.txt",),
     check=lambda d: None if '"theta": 20, "phi": 45,' in (d / "out.txt").read_text() else "the --set values were dropped",
     na_before="--set initial.* was dropped before")

# Before, "inf" was refused as if it were a negative time.
case("to-video-inf", C, "render --to-video inf (meant: to the end)", RW + "--to-video inf", 2,
     "--to-video inf: must be a finite number of seconds (video time >= 0 s); leave --to-video out for the clip's end",
     key="--to-video", na_before=VIDEO_TIME)

# Before, --version was refused under a COINROLL_GL that only drawing needs.
case("version-bad-gl", C, "COINROLL_GL=bogus coinroll --version: the version all the same, the value named",
     "COINROLL_GL=bogus exec {bin} --version 1>&2", 0,
     "; COINROLL_GL=bogus: not an OpenGL back end; accepted values: ", key="COINROLL_GL", shell=True)
case("still-bad-gl", C, "COINROLL_GL=bogus coinroll still: drawing refuses it",
     "COINROLL_GL=bogus exec {bin} still scene.json --time 0.1 -o o.png", 2,
     "COINROLL_GL=bogus: not an OpenGL back end; accepted values: ", key="COINROLL_GL", shell=True)

# --- sweep and sweep-merge
C = "sweep"
SW = "sweep scene.json -q -o o.csv "
case("grid-missing", C, "sweep without --grid", "sweep scene.json -o o.csv", 2, "--grid is required")
case("grid-no-count", C, "--grid initial.theta=5:40", SW + "--grid initial.theta=5:40", 2,
     "--grid initial.theta=5:40: expected KEY.PATH=START:STOP:COUNT", key="--grid", gtest=(G_SWEEP,))
case("grid-count-zero", C, "COUNT 0", SW + "--grid initial.theta=5:40:0", 2,
     '--grid initial.theta=5:40:0: COUNT must be a whole number >= 1, got "0"', key="--grid", gtest=(G_SWEEP,))
case("grid-count-fraction", C, "COUNT 2.5", SW + "--grid initial.theta=5:40:2.5", 2,
     'COUNT must be a whole number >= 1, got "2.5"', key="--grid")
case("grid-no-key", C, "--grid =5:40:3", SW + "--grid =5:40:3", 2, "--grid =5:40:3: expected KEY.PATH=START:STOP:COUNT",
     key="--grid", gtest=(G_SWEEP,))
case("grid-start-text", C, "START a", SW + "--grid initial.theta=a:40:3", 2,
     '--grid initial.theta=a:40:3: START must be a finite number, got "a"', key="--grid", gtest=(G_SWEEP,))
case("grid-start-nan", C, "START nan", SW + "--grid initial.theta=nan:40:3", 2,
     'START must be a finite number, got "nan"', key="--grid")
case("grid-repeated-key", C, "the same key on two --grid axes",
     SW + "--grid initial.theta=1:2:2 --grid initial.theta=3:4:2", 2, "initial.theta")
case("grid-unknown-key", C, "--grid over a key the scene does not have", SW + "--grid nosuch.key=1:2:3", 2,
     "nosuch")
PROBE = "exit 0 with an error on every row before"
for key, holds, message in (("coin", "an object", "coin: must be an object, got 1"),
                            ("name", "text", "name: must be a string, got 1"),
                            ("sliding", "true or false", "sliding: must be true or false, got 1"),
                            ("render.camera.eye", "a point", "render.camera.eye: must be an array of three"),
                            ("initial.steady", "a steady kind's name",
                             'initial.steady: must be "straight", "circle" or "spin-in-place", got 1')):
    case(f"grid-not-number-{key.replace('.', '-')}", C, f"--grid over {key}, which holds {holds}",
         SW + f"--grid {key}=1:2:2", 2, f"--grid {key}: not a number field, so a grid cannot vary it: scene.json: {message}",
         key="--grid", na_before=PROBE)
case("grid-too-many", C, "10^12 points", SW + "--grid initial.theta=1:2:1000000 --grid initial.omega_Z=1:2:1000000", 2,
     "--grid: the grid has more than 10000000 points (--max-points); raise it if you mean it", key="--max-points",
     timeout=10)
case("max-points-small", C, "--max-points 2 for 3 points", SW + "--grid initial.theta=1:2:3 --max-points 2", 2,
     "the grid has more than 2 points (--max-points)", key="--max-points", gtest=(G_SWEEP,))
case("max-points-zero", C, "--max-points 0", SW + "--grid initial.theta=1:2:3 --max-points 0", 2, "--max-points")
case("max-points-negative", C, "--max-points -1", SW + "--grid initial.theta=1:2:3 --max-points -1", 2,
     "--max-points: must be a whole number >= 1, got -1", key="--max-points")
for value, gt in (("4/3", True), ("0/3", True), ("1/0", False), ("x", False)):
    case(f"shard-{value.replace('/', 'of')}", C, f"--shard {value}",
         SW + "--grid initial.theta=1:2:3 --shard " + value, 2,
         f"--shard {value}: expected K/N with 1 <= K <= N, e.g. --shard 2/8", key="--shard",
         gtest=(G_SWEEP,) if gt else ())
# Listed and geometric axes, --shard auto/N.
AXES_BEFORE = "no listed or geometric axes, no --shard auto/N before"
case("grid-list-repeated", C, "a value listed twice", SW + "--grid initial.theta=5,10,5", 2,
     "--grid initial.theta=5,10,5: 5 is listed twice; list each value once", key="--grid", gtest=(G_SWEEP,),
     na_before=AXES_BEFORE)
case("grid-list-empty-value", C, "an empty value in a list", SW + "--grid initial.theta=5,,10", 2,
     '--grid initial.theta=5,,10: value 2 must be a finite number, got ""', key="--grid", na_before=AXES_BEFORE)
case("grid-list-text", C, "a value that is no number in a list", SW + "--grid initial.theta=5,ten", 2,
     '--grid initial.theta=5,ten: value 2 must be a finite number, got "ten"', key="--grid", na_before=AXES_BEFORE)
case("grid-list-and-range", C, "a list mixed into a range", SW + "--grid initial.theta=1:10:3,4", 2,
     "--grid initial.theta=1:10:3,4: expected KEY.PATH=START:STOP:COUNT, KEY.PATH=START:STOP:COUNT:log or "
     "KEY.PATH=V1,V2,...", key="--grid")
case("grid-log-zero", C, "a log axis from 0", SW + "--grid coin.mass=0:1:3:log", 2,
     "--grid coin.mass=0:1:3:log: a log axis needs START > 0 and STOP > 0", key="--grid", na_before=AXES_BEFORE)
case("grid-log-negative", C, "a log axis to a negative STOP", SW + "--grid initial.theta=1:-10:3:log", 2,
     "a log axis needs START > 0 and STOP > 0", key="--grid", na_before=AXES_BEFORE)
case("grid-not-log", C, "a fourth field other than log", SW + "--grid initial.theta=1:10:3:lin", 2,
     '--grid initial.theta=1:10:3:lin: the field after COUNT must be log (geometric spacing), got "lin"', key="--grid",
     gtest=(G_SWEEP,))
case("shard-auto-no-task", C, "--shard auto/4 outside a Slurm array task",
     "exec env -u SLURM_ARRAY_TASK_ID {bin} " + SW + "--grid initial.theta=1:2:3 --shard auto/4", 2,
     "--shard auto/4: auto takes K from $SLURM_ARRAY_TASK_ID, which is not set: this is not a task of a Slurm job "
     "array; submit it with sbatch --array=1-4, or give K, e.g. --shard 1/4", key="--shard", shell=True,
     gtest=("SweepCliTest.ShardAutoTakesKFromTheSlurmArrayTask",), na_before=AXES_BEFORE)
for task in ("0", "5", "x"):
    case(f"shard-auto-task-{task}", C, f"--shard auto/4 in array task {task}",
         f"SLURM_ARRAY_TASK_ID={task} exec {{bin}} " + SW + "--grid initial.theta=1:2:3 --shard auto/4", 2,
         f'--shard auto/4: $SLURM_ARRAY_TASK_ID is "{task}", not a shard number 1 to 4; submit the array as '
         "--array=1-4 (task K computes shard K/4)", key="--shard", shell=True,
         gtest=("SweepCliTest.ShardAutoTakesKFromTheSlurmArrayTask",) if task == "5" else (), na_before=AXES_BEFORE)
case("shard-auto-zero", C, "--shard auto/0", SW + "--grid initial.theta=1:2:3 --shard auto/0", 2,
     "--shard auto/0: expected K/N with 1 <= K <= N, e.g. --shard 2/8, or auto/N in a Slurm array task", key="--shard",
     na_before=AXES_BEFORE)
case("threads-negative", C, "--threads -1", SW + "--grid initial.theta=1:2:3 --threads -1", 2,
     "--threads: must be 1 to 1024 (0: every hardware thread), got -1", key="--threads", gtest=(G_SWEEP,))
case("threads-huge", C, "--threads 100000", SW + "--grid initial.theta=1:2:3 --threads 100000", 2,
     "--threads: must be 1 to 1024", key="--threads")
MERGE = "sweep-merge -o m.csv "
case("merge-missing-point", C, "sweep-merge of one shard of two", MERGE + "p1.csv", 1,
     "sweep-merge: points missing (of 40 in the grid): 1, 3, 5", key="missing", files=SHARDS, gtest=(G_MERGE,))
case("merge-repeated", C, "sweep-merge with a shard given twice", MERGE + "p1.csv p2.csv p2.csv", 1,
     "sweep-merge: points repeated: 1, 3, 5", key="repeated", files=SHARDS, gtest=(G_MERGE,))
case("merge-stdin-closed", C, "sweep-merge - with standard input closed (it read as an empty shard)",
     "exec {bin} " + MERGE + "p1.csv - <&-", 1,
     "standard input: closed, so there is no shard to read from it", key="standard input", shell=True, files=SHARDS,
     na_before="called an empty shard before")
case("merge-empty-name", C, "sweep-merge with an empty shard name", MERGE + "p1.csv ''", 2,
     "a shard name is empty; give the shard files", key="shard name", files=SHARDS, na_before=PROBE3)
case("merge-no-file", C, "sweep-merge of a shard that does not exist", MERGE + "p1.csv p3.csv", 1,
     "p3.csv: cannot open the shard", key="p3.csv", files=SHARDS)
case("merge-other-sweep", C, "shards of different sweeps (headers differ)", MERGE + "p1.csv q2.csv", 1,
     "q2.csv: its header differs from p1.csv's: shards of sweeps over different axes", key="q2.csv",
     files={**SHARDS, "q2.csv": shard(range(1, 40, 2)).replace("initial.theta", "initial.omega_Z")})
case("merge-empty", C, "an empty shard file", MERGE + "e.csv", 2, "e.csv: empty, not a sweep shard", key="e.csv",
     files={"e.csv": ""})
case("merge-directory", C, "a directory as a shard", MERGE + "sub", 2, "sub: is a directory", key="sub",
     files={"sub": Dir})
case("merge-scene", C, "a scene JSON given as a shard", MERGE + "scene.json", 2, "scene.json: not a sweep shard")
case("merge-truncated", C, "a shard cut off mid-row", MERGE + "p1.csv p2.csv", 1,
     "p2.csv:21: cut short inside a row (no line break at its end)", key="p2.csv",
     files={**SHARDS, "p2.csv": shard(range(1, 40, 2))[:-20]})
case("merge-no-point", C, "a row without its point number", MERGE + "bad.csv", 1,
     "bad.csv:2: a row must start with its point number", key="bad.csv",
     files={"bad.csv": HEADER + "\nx,1,duration,0.5,0.1,0.2,0.3,0.3,0.15,40,0123456789abcdef\n"})
# Shards that know their sweep: the identity columns grid_points and sweep.
case("merge-cut-at-line-break", C, "the last shard cut after a whole row (an interrupted `sweep -o - > part.csv`)",
     MERGE + "p1.csv p2.csv", 1, "sweep-merge: points missing (of 40 in the grid): 39", key="missing",
     files={**SHARDS, "p2.csv": shard(range(1, 39, 2))})
case("merge-other-scene", C, "shards of sweeps over the same axes of different scenes or --set",
     MERGE + "p1.csv p2.csv", 1,
     "p2.csv:2: from another sweep than p1.csv:2 (grid_points,sweep: 40,fedcba9876543210 here, "
     "40,0123456789abcdef there): the scene, its --set values or the grid differ", key="p2.csv",
     files={**SHARDS, "p2.csv": shard(range(1, 40, 2), "40,fedcba9876543210")})
case("merge-other-count", C, "shards of sweeps over grids of different sizes", MERGE + "p1.csv p2.csv", 1,
     "p2.csv:2: from another sweep than p1.csv:2 (grid_points,sweep: 80,0123456789abcdef here", key="p2.csv",
     files={**SHARDS, "p2.csv": shard(range(1, 40, 2), "80,0123456789abcdef")})
case("merge-header-only-missing", C, "a shard holding only its header where points belong",
     MERGE + "p1.csv h.csv", 1, "sweep-merge: points missing (of 40 in the grid): 1, 3, 5", key="missing",
     files={**SHARDS, "h.csv": shard([])})
case("merge-empty-shard-ok", C, "a legitimately empty shard (N larger than the grid) merges as nothing (must work)",
     MERGE + "p1.csv h.csv p2.csv", 0, None, files={**SHARDS, "h.csv": shard([])}, produces=("m.csv",))
case("merge-only-headers", C, "every shard holds only its header", MERGE + "h.csv", 1,
     "sweep-merge: no shard holds a point, but shard 1 of every sweep holds point 0", key="no shard",
     files={"h.csv": shard([])})
case("merge-no-identity", C, "a shard without the identity columns (an older coinroll's)", MERGE + "old.csv", 2,
     "old.csv: its header has no grid_points and sweep columns", key="old.csv",
     files={"old.csv": "point,initial.theta,end,t_end,theta_min,theta_max,energy_start,energy_end\n"
                       "0,1,duration,0.5,0.1,0.2,0.3,0.3\n"})
# Shards that say each toss's face (theta_end): a shard of an older coinroll, alone or with this one's
# in either order, is named, not merged into a file this coinroll does not write or taken for another sweep.
NO_THETA_END = "no theta_end column before"
OLD_SHARDS = {**SHARDS, "old2.csv": shard(range(1, 40, 2), before_theta_end=True)}
case("merge-before-theta-end", C, "a shard without theta_end (an older coinroll's) after this one's",
     MERGE + "p1.csv old2.csv", 2,
     "old2.csv: its header has no theta_end column (\"...,energy_end,grid_points,sweep\" where this coinroll "
     "writes \"...,energy_end,theta_end,grid_points,sweep\"): written by an older coinroll; run that shard again",
     key="old2.csv", files=OLD_SHARDS, na_before=NO_THETA_END)
case("merge-before-theta-end-first", C, "a shard without theta_end (an older coinroll's) given first",
     MERGE + "old2.csv p1.csv", 2, "old2.csv: its header has no theta_end column", key="old2.csv", files=OLD_SHARDS,
     na_before=NO_THETA_END)
case("merge-other-columns", C, "a shard whose summary columns are not this coinroll's", MERGE + "p1.csv x2.csv", 2,
     "x2.csv: its header's columns after the grid keys are \"end,t_end,theta_min,theta_max,energy_start,theta_end\" "
     "where this coinroll writes \"end,t_end,theta_min,theta_max,energy_start,energy_end,theta_end\"",
     key="x2.csv", files={**SHARDS, "x2.csv": shard(range(1, 40, 2)).replace("energy_end,", "")})
case("merge-point-beyond-grid", C, "a row numbered beyond its grid's size", MERGE + "p1.csv p2.csv far.csv", 1,
     "far.csv:2: point 40 is outside the grid of 40 points", key="far.csv",
     files={**SHARDS, "far.csv": shard([40])})
case("merge-from-pipes", C, "shards read from a pipe, a process substitution and standard input (must work)",
     "cat p2.csv | exec {bin} sweep-merge -o m.csv <(cat p1.csv) - ", 0, None, shell=True, files=SHARDS,
     produces=("m.csv",))
case("merge-stdin-twice", C, "- (standard input) given twice", MERGE + "- -", 2,
     "sweep-merge: - (standard input) is given more than once", key="standard input", files=SHARDS)

# Every cell of a row is of its column's type (before: a theta_end edited to "abc" merged, exit 0).
DAMAGED = "merged as it was before"


def damaged_shard(row, column, value):
    """p2.csv with the cell `column` of its `row`-th row (1: the first after the header) set to `value`."""
    lines = shard(range(1, 40, 2)).splitlines()
    cells = lines[row].split(",")
    cells[HEADER.split(",").index(column)] = value
    lines[row] = ",".join(cells)
    return "\n".join(lines) + "\n"


case("merge-cell-not-number", C, "a shard with a theta_end edited to abc", MERGE + "p1.csv p2.csv", 1,
     'p2.csv:3: theta_end: "abc" is not a number; a damaged or edited shard, run it again', key="p2.csv:3",
     files={**SHARDS, "p2.csv": damaged_shard(2, "theta_end", "abc")}, na_before=DAMAGED)
case("merge-grid-cell-not-number", C, "a shard with a grid value edited to 1.2x", MERGE + "p1.csv p2.csv", 1,
     'p2.csv:2: initial.theta: "1.2x" is not a number', key="p2.csv:2",
     files={**SHARDS, "p2.csv": damaged_shard(1, "initial.theta", "1.2x")}, na_before=DAMAGED)
case("merge-cell-empty", C, "a shard with an empty energy_end where the point did not fail", MERGE + "p1.csv p2.csv",
     1, 'p2.csv:4: energy_end: "" is not a number', key="p2.csv:4",
     files={**SHARDS, "p2.csv": damaged_shard(3, "energy_end", "")}, na_before=DAMAGED)
case("merge-end-empty", C, "a shard with an empty end", MERGE + "p1.csv p2.csv", 1,
     "p2.csv:2: end: empty; it holds how the run ended", key="p2.csv:2",
     files={**SHARDS, "p2.csv": damaged_shard(1, "end", "")}, na_before=DAMAGED)
case("merge-digest-damaged", C, "a shard whose first row's sweep digest is not 16 hex digits", MERGE + "p1.csv",
     1, 'p1.csv:2: sweep: "0123456789abcdeg" is not 16 hexadecimal digits', key="p1.csv:2",
     files={**SHARDS, "p1.csv": shard(range(0, 40, 2), "40,0123456789abcdeg")}, na_before=DAMAGED)
case("merge-failed-point-ok", C, "a shard with a failed point (end quoted, its six numbers empty) merges (must work)",
     MERGE + "p1.csv p2.csv", 0, None, produces=("m.csv",),
     files={**SHARDS, "p2.csv": shard(range(3, 40, 2)).replace("\n", '\n1,1.1,"error: integration stalled, at t = 0.2 s",'
                                                                   ',,,,,,40,0123456789abcdef\n', 1)},
     na_before=DAMAGED)
case("merge-summary", C, "sweep-merge says what it wrote (must work)", MERGE + "p1.csv p2.csv", 0,
     "coinroll: wrote m.csv (40 points from 2 shards)", key="wrote", files=SHARDS, produces=("m.csv",),
     na_before="no summary before")
case("merge-quiet", C, "sweep-merge -q, like the other commands: nothing on stderr (must work)",
     "set -o pipefail; {bin} sweep-merge -q -o m.csv p1.csv p2.csv 2>&1 | (! grep .)", 0, None, shell=True,
     files=SHARDS, produces=("m.csv",), na_before="no -q before")

# The range's twin of a value listed twice (before: three identical points before).
case("grid-range-equal-ends", C, "--grid initial.theta=5:5:3: three points of one value",
     SW + "--grid initial.theta=5:5:3", 2,
     "--grid initial.theta=5:5:3: START and STOP are equal, so its 3 points would all be 5; give COUNT 1 for that one "
     "value, or a STOP other than START", key="--grid", na_before="three identical points before")
case("grid-log-equal-ends", C, "--grid coin.mass=0.4:0.4:2:log", SW + "--grid coin.mass=0.4:0.4:2:log", 2,
     "--grid coin.mass=0.4:0.4:2:log: START and STOP are equal, so its 2 points would all be 0.4", key="--grid",
     na_before="two identical points before")

# --- output paths
C = "output paths"
# A default output name (no -o) is never taken over from another scene's output: the scene
# digest its provenance carries tells; a file that names no scene is not replaced either.
DEFAULT_NAMES = "replaced silently before"


def png_of_scene(digest):
    """A PNG header and the tEXt chunk a coinroll still carries, naming the scene digest `digest`."""
    import struct
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0))
            + chunk(b"tEXt", b"coinroll-scene-digest\0" + digest.encode()) + chunk(b"IEND", b""))


case("default-name-other-scene", C, "still without -o where scene.png came from another scene",
     f"still scene.json --time 0.1 {SMALL} -q", 2,
     "scene.png: exists, made from another scene (its digest fnv1a64:0123456789abcdef, this scene's fnv1a64:",
     key="--force", files={"scene.json": VALID, "scene.png": png_of_scene("fnv1a64:0123456789abcdef")},
     na_before=DEFAULT_NAMES)
case("default-name-foreign", C, "render without -o where scene.mp4 names no scene", f"render scene.json -q {SMALL}", 2,
     "scene.mp4: exists, does not say which scene made it (no coinroll provenance), and is only this scene's default "
     "output name; give -o NAME to write elsewhere, or --force to replace it", key="--force",
     files={"scene.json": VALID, "scene.mp4": "the user's own notes"}, na_before=DEFAULT_NAMES)
case("out-no-dir-csv", C, "--csv into a directory that does not exist", "simulate scene.json --csv nodir/o.csv", 1,
     "nodir/o.csv: cannot write: directory 'nodir' does not exist", key="nodir",
     gtest=("CliTest.UnwritableOutputFailsWithoutLeavingFiles",))
case("out-no-dir-png", C, "still -o into a missing directory", "still scene.json --time 0.1 -o nodir/o.png " + SMALL, 1,
     "nodir/o.png: cannot write: directory 'nodir' does not exist", key="nodir")
case("out-no-dir-mp4", C, "render -o into a missing directory", "render scene.json -q -o nodir/o.mp4 " + SMALL, 1,
     "nodir/o.mp4: cannot write: directory 'nodir' does not exist", key="nodir", gtest=(G_RENDER,))
case("out-no-dir-seq", C, "PNG sequence into a missing directory",
     "render scene.json -q -o nodir/f_%03d.png " + SMALL, 1,
     "nodir/f_%03d.png: cannot write: directory 'nodir' does not exist", key="nodir")
case("out-no-dir-sweep", C, "sweep -o into a missing directory", SW.replace("o.csv", "nodir/o.csv") +
     "--grid initial.theta=1:2:2", 1, "nodir/o.csv: cannot write: directory 'nodir' does not exist", key="nodir")
case("out-is-input", C, "--csv the scene itself", "simulate scene.json --csv scene.json", 2,
     "--csv scene.json: that is the input scene.json; choose another output name", key="input", gtest=(G_SAME,))
case("provenance-is-input", C, "simulate --provenance the scene itself",
     "simulate scene.json --csv o.csv --provenance scene.json", 2,
     "--provenance scene.json: that is the input scene.json; choose another output name", key="--provenance")
case("provenance-is-csv", C, "simulate --provenance the CSV's own name",
     "simulate scene.json --csv o.csv --provenance o.csv", 2,
     "--provenance o.csv: give a file of its own beside the CSV, e.g. o.csv.json", key="--provenance")
case("frame-times-is-input", C, "render --frame-times the scene itself",
     "render scene.json -q -o o.mov --frame-times scene.json", 2,
     "--frame-times scene.json: that is the input scene.json; choose another output name", key="--frame-times")
case("frame-times-is-video", C, "render --frame-times the video's own name",
     "render scene.json -q -o o.mov --frame-times o.mov", 2,
     "--frame-times o.mov: that is the video's own name; give a file of its own beside it, e.g. o_frames.csv",
     key="--frame-times")
case("out-is-input-dot", C, "--csv ./scene.json", "simulate scene.json --csv ./scene.json", 2,
     "that is the input scene.json", key="input", gtest=(G_SAME,))
case("out-is-input-link", C, "--csv a symlink to the scene", "simulate scene.json --csv link.json", 2,
     "--csv link.json: that is the input scene.json", key="input",
     files={"scene.json": VALID, "link.json": ("symlink", "scene.json")})
case("out-is-input-render", C, "render -o the scene", "render scene.json -o scene.json", 2,
     "-o scene.json: that is the input scene.json", key="scene.json")
case("out-is-input-mp4", C, "render -o its scene, named scene.mp4", "render scene.mp4 -q -o scene.mp4", 2,
     "-o scene.mp4: that is the input scene.mp4; choose another output name", key="input",
     files={"scene.mp4": VALID})
case("out-is-input-still", C, "still -o its scene, named scene.png",
     f"still scene.png --time 0.1 {SMALL} -o scene.png", 2,
     "-o scene.png: that is the input scene.png; choose another output name", key="input",
     files={"scene.png": VALID}, gtest=(G_SAME,))
case("out-is-input-seq", C, "PNG sequence whose frame 0 is the scene (f_000.png)",
     f"render f_000.png -q {SMALL} --set duration=0.1 -o f_%03d.png", 2, "one of its frames would be the input f_000.png", key="input",
     files={"f_000.png": VALID})
case("out-is-input-sweep", C, "sweep -o the scene", "sweep scene.json --grid initial.theta=1:2:2 -o scene.json", 2,
     "that is the input scene.json", key="input", gtest=(G_SAME,))
case("out-is-input-merge", C, "sweep-merge -o one of its shards", "sweep-merge -o p1.csv p1.csv p2.csv", 2,
     "-o p1.csv: that is the input p1.csv; choose another output name", key="input", files=SHARDS)
for command, name in (("simulate scene.json --csv", "o.csv"), ("still scene.json --time 0.1 " + SMALL + " -o", "o.png"),
                      ("render scene.json -q " + SMALL + " -o", "o.mp4"),
                      ("sweep scene.json --grid initial.theta=1:2:2 -q -o", "s.csv")):
    case(f"out-is-dir-{name.split('.')[1]}{'-sweep' if command.startswith('sweep') else ''}", C,
         f"{command.split()[0]} output {name} is an existing directory", f"{command} {name}", 1,
         f"{name}: cannot write: is a directory; give a file name", key=name, files={"scene.json": VALID, name: Dir})
UNI = "out dir/"
SPACED = {"scene.json": VALID, "out dir": Dir, "out dir/scène 1.json": VALID}
case("unicode-csv", C, "scene and CSV with spaces and non-ASCII names",
     f"simulate '{UNI}scène 1.json' --csv '{UNI}résultat ü.csv'", 0, None, files=SPACED,
     produces=("out dir/résultat ü.csv",))
case("unicode-png", C, "still named 'Bild ü.png' in 'out dir'",
     f"still '{UNI}scène 1.json' --time 0.1 {SMALL} -o '{UNI}Bild ü.png'", 0, None, files=SPACED,
     produces=("out dir/Bild ü.png",))
case("unicode-mp4", C, "MP4 named 'vidéo 1.mp4'",
     f"render '{UNI}scène 1.json' -q {SMALL} -o '{UNI}vidéo 1.mp4'", 0, None,
     files=SPACED, produces=("out dir/vidéo 1.mp4",))
case("unicode-seq", C, "PNG sequence 'фрейм %03d.png'",
     f"render '{UNI}scène 1.json' -q {SMALL} --set duration=0.1 -o '{UNI}фрейм %03d.png'", 0, None,
     files=SPACED, produces=("out dir/фрейм 00[0-3].png",))
case("unicode-sweep", C, "sweep to 'süß 1.csv'",
     f"sweep '{UNI}scène 1.json' -q --grid initial.theta=1:2:2 -o '{UNI}süß 1.csv'",
     0, None, files=SPACED, produces=("out dir/süß 1.csv",))
case("unicode-merge", C, "sweep-merge to 'zusammen ü.csv'", "sweep-merge -o 'zusammen ü.csv' p1.csv p2.csv", 0, None,
     files=SHARDS, produces=("zusammen ü.csv",))
case("unicode-default-name", C, "render without -o, scene named 'mön coin'",
     f"render scene.json -q {SMALL} --set duration=0.1 --set 'name=\"mön coin\"'", 0, None, produces=("*.mp4",))
case("name-255-csv", C, "255-byte CSV name", f"simulate scene.json --csv {LONG}.csv", 0, None,
     produces=(LONG + ".csv",), gtest=("CliTest.ALegalLongFileNameIsWritten",))
case("name-255-png", C, "255-byte PNG name", f"still scene.json --time 0.1 {SMALL} -o {LONG}.png", 0, None,
     produces=(LONG + ".png",))
case("name-255-mp4", C, "255-byte MP4 name", f"render scene.json -q {SMALL} -o {LONG}.mp4", 0, None,
     produces=(LONG + ".mp4",))
case("name-255-seq", C, "PNG sequence whose names are 255 bytes",
     f"render scene.json -q {SMALL} --set duration=0.1 -o {'a' * 245}_%05d.png", 0, None,
     produces=("a" * 245 + "_0000[0-3].png",))
case("name-255-utf8", C, "255-byte name of two-byte characters",
     f"simulate scene.json --csv {'é' * 125}a.csv", 0, None, produces=("é" * 125 + "a.csv",))
case("name-256", C, "256-byte CSV name (one past the limit), refused before the run", f"simulate scene.json --csv a{LONG}.csv", 1,
     "cannot write: File name too long (256 bytes; this file system allows 255)", key="File name too long (256 bytes")

# --- outputs that behave like Unix files (docs/outputs.md): links are written through,
# devices, FIFOs and descriptors are streamed to, a replaced file keeps its mode, names are checked first
C = "outputs as Unix files"
CSV_HEAD = b"t,theta,phi,psi,"
PNG_HEAD = b"\x89PNG\r\n\x1a\n"


def starts(path, head):
    path = Path(path)
    return path.is_file() and path.read_bytes().startswith(head)


def is_csv(path):
    return starts(path, CSV_HEAD)


def is_png(path):
    return starts(path, PNG_HEAD)


def is_mp4(path):
    data = Path(path).read_bytes() if Path(path).is_file() else b""
    return data[4:8] == b"ftyp" and 0 < data.find(b"moov") < data.find(b"mdat")  # faststart: the index first


def check_link(link, target, holds):
    """The link is still a link to `target`, which now holds the new output (holds(path) says)."""
    def check(d):
        if not (d / link).is_symlink():
            return f"{link} is no longer a link"
        if os.readlink(d / link) != target:
            return f"{link} now points to {os.readlink(d / link)}"
        return None if holds(d / link) else f"{target} does not hold the new output"
    return check


def check_files(pattern, test, count=None, why="not the new output"):
    def check(d):
        found = sorted(p for p in d.glob(pattern) if not p.name.startswith("."))
        if count is not None and len(found) != count:
            return f"{len(found)} files {pattern}, expected {count}: {', '.join(p.name for p in found)}"
        bad = [p.name for p in found if not test(p)]
        return f"{', '.join(bad)}: {why}" if bad else None
    return check


def check_mode(name, mode, owner):
    def check(d):
        info = (d / name).stat()
        want_owner = owner if os.geteuid() == 0 else os.geteuid()
        if stat.S_IMODE(info.st_mode) != mode or info.st_uid != want_owner:
            return f"{name} is {stat.S_IMODE(info.st_mode):o} owned by {info.st_uid}, was {mode:o} owned by {want_owner}"
        return None if is_csv(d / name) else f"{name} does not hold the CSV"
    return check


def as_nobody_when_root(arguments):
    """Root passes every permission check; the case runs as nobody then, in a directory nobody may write."""
    return (f"if [ \"$(id -u)\" = 0 ]; then chmod 777 . && exec setpriv --reuid={NOBODY} --regid={NOBODY} "
            f"--clear-groups {{bin}} {arguments}; else exec {{bin}} {arguments}; fi")


PNGS_FOR_DIFF = {"a.png": png(64, 48), "b.png": png(64, 48, 130)}
FRAMES = {"scene.json": VALID, **{f"f_{i:03d}.png": f"frame {i} of an earlier, longer run" for i in range(10)},
          "f_0010.png": "not a name f_%03d.png gives", "g_005.png": "another sequence's"}
SEQ = f"render scene.json -q {SMALL} --set duration=0.1 -o "  # 4 frames
case("link-csv", C, "--csv a link into another directory (written through; the link stays)",
     "simulate scene.json --csv link.csv", 0, None,
     files={"scene.json": VALID, "data/target.csv": "old\n", "link.csv": ("symlink", "data/target.csv")},
     alters=("data/target.csv",), check=check_link("link.csv", "data/target.csv", is_csv))
case("link-dangling", C, "--csv a link to a name that does not exist yet (creates it, as `>` does)",
     "simulate scene.json --csv link.csv", 0, None, files={"scene.json": VALID, "link.csv": ("symlink", "new.csv")},
     produces=("new.csv",), check=check_link("link.csv", "new.csv", is_csv))
case("link-png", C, "still -o a link", f"still scene.json --time 0.1 {SMALL} -o link.png", 0, None,
     files={"scene.json": VALID, "pics/old.png": "old", "link.png": ("symlink", "pics/old.png")},
     alters=("pics/old.png",), check=check_link("link.png", "pics/old.png", is_png))
case("link-mp4", C, "render -o a link", SEQ + "link.mp4", 0, None,
     files={"scene.json": VALID, "clips/old.mp4": "old", "link.mp4": ("symlink", "clips/old.mp4")},
     alters=("clips/old.mp4",), check=check_link("link.mp4", "clips/old.mp4", is_mp4))
case("link-loop", C, "--csv a link loop (a.csv -> b.csv -> a.csv)", "simulate scene.json --csv a.csv", 1,
     "a.csv: cannot write: Too many levels of symbolic links", key="a.csv",
     files={"scene.json": VALID, "a.csv": ("symlink", "b.csv"), "b.csv": ("symlink", "a.csv")})
case("dev-stdout-csv", C, "--csv /dev/stdout > out.csv (a descriptor: never the /dev/stdout link itself)",
     "{bin} simulate scene.json --csv /dev/stdout > out.csv", 0, None, shell=True, produces=("out.csv",),
     check=lambda d: None if is_csv(d / "out.csv") and os.path.islink("/dev/stdout")
     else "out.csv lacks the CSV, or /dev/stdout is no longer a link")
case("dev-null-csv", C, "--csv /dev/null", "simulate scene.json --csv /dev/null", 0, None,
     check=lambda d: None if stat.S_ISCHR(os.stat("/dev/null").st_mode) else "/dev/null is no longer a device")
case("dev-null-sweep", C, "sweep -o /dev/null", "sweep scene.json -q --grid initial.theta=1:2:2 -o /dev/null", 0, None)
case("dev-null-mp4", C, "render -o /dev/null (MP4 made in $TMPDIR, then copied; nothing left there)",
     "mkdir tmp && TMPDIR=$PWD/tmp exec {bin} " + SEQ + "/dev/null", 0, None, shell=True, produces=("tmp",),
     check=lambda d: None if not any((d / "tmp").iterdir()) else "left a file in $TMPDIR")
case("tmpdir-empty", C, "render -o /dev/null with TMPDIR='' (POSIX: as if unset, so /tmp)",
     "TMPDIR= exec {bin} " + SEQ + "/dev/null", 0, None, shell=True,
     na_before="refused as 'no temporary directory' before")
case("mp4-name-with-percent", C, "render -o '100%.mp4': an MP4 named with a literal %", "exec {bin} " + SEQ + "'100%.mp4'", 0, None,
     shell=True, produces=("100%.mp4",), check=lambda d: None if is_mp4(d / "100%.mp4") else "100%.mp4 is not an MP4",
     na_before="called a bad PNG sequence pattern before")
case("procsub-csv", C, "--csv >(gzip > t.csv.gz) (a pipe under /dev/fd)",
     "{bin} simulate scene.json --csv >(gzip > t.csv.gz); rc=$?; wait $!; exit $rc", 0, None, shell=True,
     produces=("t.csv.gz",), check=lambda d: None if gzip.decompress((d / "t.csv.gz").read_bytes()).startswith(CSV_HEAD)
     else "t.csv.gz does not hold the CSV")
# The reader gives up after 15 s, so a binary that never opens the FIFO cannot leave it blocked for ever.
case("fifo-csv", C, "--csv a FIFO a reader empties", "timeout 15 cat fifo > got.csv & {bin} simulate scene.json --csv fifo; "
     "rc=$?; wait; exit $rc", 0, None, shell=True, files={"scene.json": VALID, "fifo": Fifo}, produces=("got.csv",),
     check=lambda d: None if is_csv(d / "got.csv") else "got.csv does not hold the CSV")
case("stdout-mp4", C, "render -o /dev/stdout > o.mp4 (faststart MP4 through a descriptor)",
     "exec {bin} " + SEQ + "/dev/stdout > o.mp4", 0, None, shell=True, produces=("o.mp4",),
     check=lambda d: None if is_mp4(d / "o.mp4") else "o.mp4 is not a faststart MP4")
case("stdout-png", C, "still -o /dev/stdout > o.png (no .png in the name: it is a descriptor)",
     f"exec {{bin}} still scene.json --time 0.1 {SMALL} -o /dev/stdout > o.png", 0, None, shell=True,
     produces=("o.png",), check=lambda d: None if is_png(d / "o.png") else "o.png is not a PNG")
case("stdout-broken-pipe", C, "--csv /dev/stdout into a reader that quits (SIGPIPE ignored)",
     "trap '' PIPE; {bin} simulate scene.json --csv /dev/stdout --set duration=50 | head -c 10 >/dev/null; "
     "exit ${PIPESTATUS[0]}", 1, "/dev/stdout: writing the CSV failed: Broken pipe", key="/dev/stdout", shell=True)
case("dev-stdin", C, "--csv /dev/stdin, open for reading", "exec {bin} simulate scene.json --csv /dev/stdin < /dev/null",
     1, "/dev/stdin: cannot write: descriptor 0 is open for reading only", key="/dev/stdin", shell=True)
case("mode-kept", C, "--csv over a 0600 file (of user nobody, when run as root): mode and owner kept",
     SIM, 0, None, files={"scene.json": VALID, "o.csv": with_mode("old\n", 0o600, NOBODY)}, alters=("o.csv",),
     check=check_mode("o.csv", 0o600, NOBODY))
case("read-only-refused", C, "--csv over a read-only file (as nobody when run as root), refused before the run",
     as_nobody_when_root("simulate scene.json --csv ro.csv --sample-dt 0.001 --set duration=1e4"), 1,
     "ro.csv: cannot write: Permission denied: the file is not writable for you; make it writable (chmod u+w)",
     key="ro.csv", shell=True, timeout=10, files={"scene.json": VALID, "ro.csv": with_mode("keep\n", 0o444)})
LONG_WORK = " --sample-dt 0.001 --set duration=1e4"  # minutes of work if the check came after it
for id_, command, option, example in (
        ("csv", SIM.replace("o.csv", "''") + LONG_WORK, "--csv", "--csv out.csv (or - for standard output)"),
        ("sweep", "sweep scene.json -q --grid initial.theta=1:20:100000 -o ''", "-o", "-o sweep.csv"),
        ("merge", "sweep-merge -o '' p1.csv p2.csv", "-o", "-o merged.csv"),
        ("render", "render scene.json -q -o '' --set duration=60", "-o", "-o clip.mp4"),
        ("still", "still scene.json --time 0.1 -o ''", "-o", "-o still.png"),
        ("diff", "compare a.png b.png --diff ''", "--diff", "--diff diff.png")):
    case(f"empty-name-{id_}", C, f"{command.split()[0]} {option} '' (an empty output name), refused before any work",
         command, 2, f"{option}: the output name is empty; give a file name, e.g. {example}", key=option, timeout=5,
         files=SHARDS if id_ == "merge" else PNGS_FOR_DIFF if id_ == "diff" else {"scene.json": VALID})
case("name-trailing-slash", C, "--csv out/ (names a directory)", "simulate scene.json --csv out/", 1,
     "out/: cannot write: 'out/' names a directory; give a file name", key="out/")
case("seq-stale-frames", C, "4 frames over 10 of an earlier run: f_004..f_009 removed, other names kept",
     SEQ + "f_%03d.png", 0, None, files=FRAMES, alters=("f_00?.png",),
     check=check_files("f_*.png", lambda p: p.name == "f_0010.png" or is_png(p), count=5))
case("seq-frame-is-dir", C, "a PNG sequence one of whose names is a directory: nothing changes",
     SEQ + "f_%03d.png", 1, "f_002.png: cannot write: is a directory; give a file name", key="f_002.png",
     files={"scene.json": VALID, "f_000.png": "earlier", "f_001.png": "earlier", "f_002.png": Dir})
case("seq-frame-link", C, "a frame name that is a link: its target gets the frame, the link stays",
     SEQ + "f_%03d.png", 0, None, produces=("f_00[1-3].png",),
     files={"scene.json": VALID, "keep/zero.png": "old", "f_000.png": ("symlink", "keep/zero.png")},
     alters=("keep/zero.png",), check=check_link("f_000.png", "keep/zero.png", is_png))
PROBE2 = "lost data before"
case("seq-stale-name-is-dir", C, "a directory named like a stale frame (f_005.png/ over 4 frames): left as it is",
     SEQ + "f_%03d.png", 0, None, produces=("f_00[0-3].png",), files={"scene.json": VALID, "f_005.png/keep.txt": "precious"},
     check=lambda d: None if (d / "f_005.png/keep.txt").read_text() == "precious" and
     not any(p.name.startswith(".") for p in d.iterdir()) else "the directory f_005.png was moved or a hidden name left",
     na_before="hidden under .f_005.png.previous-* before")
case("seq-frame-link-to-scene", C, "a frame name that is a link to the scene: refused before rendering, the scene kept",
     SEQ + "f_%03d.png", 2, "f_001.png: cannot write: it leads to scene.json, an input of this command",
     key="f_001.png", files={"scene.json": VALID, "f_001.png": ("symlink", "scene.json")}, na_before=PROBE2)
case("seq-stale-link-to-scene", C, "a stale frame name (f_007.png of 4 frames) linked to the scene: refused too",
     SEQ + "f_%03d.png", 2, "f_007.png: cannot write: it leads to scene.json, an input of this command", key="f_007.png",
     files={"scene.json": VALID, "f_007.png": ("symlink", "scene.json")}, na_before=PROBE2)
case("seq-two-frames-one-file", C, "two frame names linked to one file: refused, not one frame silently lost",
     SEQ + "f_%03d.png", 1, "f_002.png: cannot write: it leads to the same file as f_001.png", key="f_002.png",
     files={"scene.json": VALID, "target.png": "old", "f_001.png": ("symlink", "target.png"),
            "f_002.png": ("symlink", "target.png")}, na_before=PROBE2)
case("still-over-asset", C, "still -o onto the coin-face texture $COINROLL_ASSET_DIR reads: refused",
     "COINROLL_ASSET_DIR=ad exec {bin} still scene.json --time 0.1 -o ad/coin_face.png", 2,
     "-o ad/coin_face.png: that is the input ad/coin_face.png", key="coin_face.png", shell=True,
     files={"scene.json": VALID, "ad/coin_face.png": png(8, 8)}, na_before=PROBE2)
case("default-name-cyrillic", C, "render without -o, scenes named 'имя' and 'дом': two files, not one",
     f"{{bin}} render scene.json -q {SMALL} --set duration=0.1 --set 'name=\"имя\"' && "
     f"exec {{bin}} render scene.json -q {SMALL} --set duration=0.1 --set 'name=\"дом\"'", 0, None, shell=True,
     produces=("______+*.mp4",), check=check_files("*.mp4", is_mp4, count=2))
case("default-name-unsafe", C, "scenes named 'a/b' and 'a_b': two files",
     f"{{bin}} render scene.json -q {SMALL} --set duration=0.1 --set 'name=\"a/b\"' && "
     f"exec {{bin}} render scene.json -q {SMALL} --set duration=0.1 --set 'name=\"a_b\"'", 0, None, shell=True,
     produces=("a_b.mp4", "a_b+*.mp4"), check=check_files("*.mp4", is_mp4, count=2))
case("default-name-scene-file", C, "render without -o, two scenes without a name: named after their files, not both coinroll.mp4",
     f"{{bin}} render a.json -q {SMALL} --set duration=0.1 && exec {{bin}} render b.json -q {SMALL} --set duration=0.1",
     0, None, shell=True, files={"a.json": VALID, "b.json": VALID}, produces=("a.mp4", "b.mp4"),
     check=check_files("*.mp4", is_mp4, count=2), na_before="no such behaviour before",
     gtest=("CliTest.RenderWithoutANameOrOutputNamesTheVideoAfterTheSceneFile",))
case("default-name-dot", C, "render without -o, scene named '.hidden': no hidden file",
     SEQ.replace("-o ", "") + "--set 'name=\".hidden\"'", 0, None, produces=("_hidden+*.mp4",),
     check=lambda d: None if not any(p.name.startswith(".") for p in d.iterdir()) else "left a hidden file")

# --- full disk: /dev/full, and a 512-byte file-size limit with SIGXFSZ ignored (writes fail with EFBIG)
C = "full disk"
FULL = "ulimit -f 1; trap '' XFSZ; exec {bin} "
case("dev-full-csv", C, "--csv /dev/full (written to as a device, which is full)", "simulate scene.json --csv /dev/full", 1,
     "/dev/full: writing the CSV failed: No space left on device", key="/dev/full")
case("dev-full-stdout", C, "--csv - with stdout on /dev/full", "exec {bin} simulate scene.json --csv - >/dev/full", 1,
     "writing the CSV to stdout failed: No space left on device", key="No space left on device", shell=True,
     gtest=("CliTest.AFailedWriteToStdoutIsAnError",))
case("dev-full-sweep-stdout", C, "sweep -o - with stdout on /dev/full",
     "exec {bin} sweep scene.json -q --grid initial.theta=1:20:4 -o - >/dev/full", 1,
     "writing the sweep to stdout failed: No space left on device", key="No space left on device", shell=True,
     na_before="no -o - for sweep before")
case("dev-full-merge-stdout", C, "sweep-merge -o - with stdout on /dev/full",
     "exec {bin} sweep-merge -o - p1.csv p2.csv >/dev/full", 1,
     "writing the merged sweep to stdout failed: No space left on device", key="No space left on device", shell=True,
     files=SHARDS, na_before="no -o - for sweep-merge before")
case("dev-full-steady", C, "steady with stdout on /dev/full",
     "exec {bin} steady --kind straight --omega-Z 5 >/dev/full", 1,
     "No space left on device", shell=True)
case("ulimit-csv", C, "CSV past a 512-byte file-size limit", FULL + "simulate scene.json --csv o.csv", 1,
     "coinroll: error: o.csv: writing the CSV failed: File too large", key="o.csv", shell=True, gtest=(G_FULL,))
case("ulimit-png", C, "PNG still past the limit", FULL + f"still scene.json --time 0.1 {SMALL} -o o.png", 1,
     "coinroll: error: o.png: writing the PNG failed: File too large", key="o.png", shell=True, gtest=(G_FULL,))
case("ulimit-mp4", C, "MP4 past the limit", FULL + f"render scene.json -q {SMALL} -o o.mp4", 1,
     "coinroll: error: o.mp4: writing the MP4", key="o.mp4", shell=True, gtest=(G_FULL,))
case("ulimit-seq", C, "PNG sequence past the limit", FULL + f"render scene.json -q {SMALL} -o f_%03d.png", 1,
     "coinroll: error: f_000.png: writing the PNG failed: File too large", key="f_000.png", shell=True, gtest=(G_FULL,))
case("ulimit-sweep", C, "sweep past the limit", FULL + "sweep scene.json -q --grid initial.theta=1:20:40 -o o.csv", 1,
     "coinroll: error: o.csv: writing the sweep failed: File too large", key="o.csv", shell=True, gtest=(G_FULL,))
case("ulimit-merge", C, "sweep-merge past the limit", FULL + "sweep-merge -o m.csv p1.csv p2.csv", 1,
     "m.csv", shell=True, files=SHARDS)

# The same limit as a user's shell sets it, SIGXFSZ not ignored: it used to kill coinroll and leave
# the temporary; now the write fails with EFBIG and says which limit it reached.
LIMIT = "ulimit -f 1; exec {bin} "
TOO_LARGE = "File too large (the file-size limit, ulimit -f, is 1024 bytes)"
G_LIMIT = "RenderCliTest.AFileSizeLimitIsAWriteErrorEvenWithSigxfszAtItsDefault"
case("ulimit-default-csv", C, "CSV past a 1024-byte file-size limit, SIGXFSZ at its default",
     LIMIT + "simulate scene.json --csv o.csv", 1, "o.csv: writing the CSV failed: " + TOO_LARGE, key="o.csv",
     shell=True, gtest=(G_LIMIT,))
case("ulimit-default-png", C, "PNG still past the limit, SIGXFSZ at its default",
     LIMIT + f"still scene.json --time 0.1 {SMALL} -o o.png", 1, "o.png: writing the PNG failed: " + TOO_LARGE,
     key="o.png", shell=True, gtest=(G_LIMIT,))
case("ulimit-default-mp4", C, "MP4 past the limit, SIGXFSZ at its default",
     LIMIT + f"render scene.json -q {SMALL} -o o.mp4", 1, TOO_LARGE, key="o.mp4", shell=True, gtest=(G_LIMIT,))
case("ulimit-default-seq", C, "PNG sequence past the limit, SIGXFSZ at its default",
     LIMIT + f"render scene.json -q {SMALL} -o f_%03d.png", 1, "f_000.png: writing the PNG failed: " + TOO_LARGE,
     key="f_000.png", shell=True, gtest=(G_LIMIT,))
case("ulimit-default-sweep", C, "sweep past the limit, SIGXFSZ at its default",
     LIMIT + "sweep scene.json -q --grid initial.theta=1:20:40 -o o.csv", 1,
     "o.csv: writing the sweep failed: " + TOO_LARGE, key="o.csv", shell=True)

# --- pipes
C = "pipes"
case("stdout-closed", C, "--csv - with stdout closed", "exec {bin} simulate scene.json --csv - >&-", 1,
     "writing the CSV to stdout failed: Bad file descriptor", key="stdout", shell=True)
case("stdout-reader-gone", C, "--csv - into a reader that quits (SIGPIPE ignored)",
     "trap '' PIPE; {bin} simulate scene.json --csv - --set duration=50 | head -c 10 >/dev/null; exit ${PIPESTATUS[0]}",
     1, "writing the CSV to stdout failed: Broken pipe", key="stdout", shell=True)
case("steady-stdout-closed", C, "steady with stdout closed", "exec {bin} steady --kind straight --omega-Z 5 >&-", 1,
     "Bad file descriptor", shell=True)

# --- signals: sent once the run is writing its temporary (or producing data), so the work is under way
C = "signals"
LONG_SIM = "simulate scene.json --csv o.csv --sample-dt 0.001 --set duration=1e4"
LONG_RENDER = f"render scene.json {SMALL} --set duration=60 -o "
INT, TERM = signal.SIGINT, signal.SIGTERM


def interrupted(sig, output):
    return f"interrupted by {sig.name}; nothing was written to {output}"


G_INT_SIM = "CliTest.InterruptedSimulateExitsOneAndLeavesNothing"
for id_, command in (("version-full", "--version > /dev/full"), ("help-full", "--help > /dev/full"),
                     ("help-closed", "simulate --help >&-")):
    case(id_, "pipes", f"coinroll {command}: the failed write is an error", "exec {bin} " + command, 1,
         "writing to standard output failed: " + ("Bad file descriptor" if "&-" in command else "No space left on device"),
         key="standard output", shell=True, na_before=PROBE3)
case("sigint-simulate", C, "SIGINT during a long simulate", LONG_SIM, 1, interrupted(INT, "o.csv"), key="interrupted",
     signal=INT, gtest=(G_INT_SIM,))
case("sigterm-simulate", C, "SIGTERM during a long simulate", LONG_SIM, 1, interrupted(TERM, "o.csv"),
     key="interrupted", signal=TERM, gtest=(G_INT_SIM,))
case("sigint-simulate-stdout", C, "SIGINT during a long simulate to stdout", LONG_SIM.replace("o.csv", "-"), 1,
     "interrupted by SIGINT; standard output keeps what it was given before", key="interrupted", signal=INT,
     wait_for="stdout")
case("sigint-render", C, "SIGINT during an MP4 render", LONG_RENDER + "o.mp4", 1, interrupted(INT, "o.mp4"),
     key="interrupted", signal=INT, gtest=("RenderCliTest.InterruptLeavesNoFileAndExitsOne",))
case("sigterm-render", C, "SIGTERM during an MP4 render", LONG_RENDER + "o.mp4", 1, interrupted(TERM, "o.mp4"),
     key="interrupted", signal=TERM)
case("sigint-sequence", C, "SIGINT during a PNG sequence over earlier frames of the same names",
     LONG_RENDER + "f_%03d.png", 1, interrupted(INT, "f_%03d.png"), key="interrupted", signal=INT,
     files={"scene.json": VALID, "f_000.png": "earlier frame, must survive"})
case("sigterm-still", C, "SIGTERM while a still frames a long run",
     f"still scene.json --time 0.1 -o o.png {SMALL} --set duration=400 --set solver.method=rk4 --set solver.dt=1e-5", 1,
     interrupted(TERM, "o.png"), key="interrupted", signal=TERM, wait_for="sleep")
case("sigint-sweep", C, "SIGINT during a sweep", "sweep scene.json --grid initial.theta=1:20:100000 -o o.csv", 1,
     interrupted(INT, "o.csv"), key="interrupted", signal=INT)
case("sigterm-sweep", C, "SIGTERM during a sweep", "sweep scene.json --grid initial.theta=1:20:100000 -o o.csv", 1,
     interrupted(TERM, "o.csv"), key="interrupted", signal=TERM)

# Every signal whose default is to end the process is a request to stop, like SIGINT (
# section 2: SIGHUP left 1491 hidden frames after 3 s); a second one, or the first left unanswered
# for 3 s, ends the run at once, and neither leaves a file (docs/outputs.md, "Signals").
SIGNALS_BEFORE = "no such behaviour before"
EARLIER = {"scene.json": VALID, "f_000.png": "earlier frame, must survive"}
for sig in (signal.SIGHUP, signal.SIGQUIT, signal.SIGTERM, signal.SIGUSR1, signal.SIGXCPU):
    case(f"{sig.name.lower()}-sequence", C, f"{sig.name} during a PNG sequence over earlier frames",
         LONG_RENDER + "f_%03d.png", 1, f"interrupted by {sig.name}", key="interrupted", signal=sig, files=EARLIER,
         gtest=("SignalsCliTest.EveryRequestToStopLeavesNoFile",))
for sig in (signal.SIGHUP, signal.SIGQUIT):
    case(f"{sig.name.lower()}-render", C, f"{sig.name} during an MP4 render", LONG_RENDER + "o.mp4", 1,
         interrupted(sig, "o.mp4"), key="interrupted", signal=sig, gtest=("SignalsCliTest.EveryRequestToStopLeavesNoFile",))
case("sighup-sweep", C, "SIGHUP during a sweep (a closed terminal)",
     "sweep scene.json --grid initial.theta=1:20:100000 -o o.csv", 1, interrupted(signal.SIGHUP, "o.csv"),
     key="interrupted", signal=signal.SIGHUP)
# Either the first signal's unwinding or the second's immediate end wins the race; neither leaves a
# staged frame (two runs left 706 and 848 before). The second path alone: SignalsCliTest.ASecondSignal...
case("sigint-twice-sequence", C, "a second SIGINT 2 ms after the first, during a PNG sequence",
     LONG_RENDER + "f_%03d.png", 1, "interrupted by SIGINT", key="interrupted", signal=INT, then=((INT, 0.002),),
     files=EARLIER, settle=1.0, gtest=("SignalsCliTest.ASecondSignalWhileFramesAreStagedEndsAtOnceAndLeavesNothing",))
case("sigint-twice-render", C, "a second SIGINT 2 ms after the first, during an MP4 render",
     LONG_RENDER + "o.mp4", 1, "interrupted by SIGINT", key="interrupted", signal=INT, then=((INT, 0.002),))
# Opening a FIFO waits for a reader and cannot poll: only the second signal, or the grace, ends it.
FIFO_SIM = "simulate scene.json --csv fifo"
case("sigint-twice-fifo", C, "a second SIGINT while opening a FIFO nobody reads", FIFO_SIM, 1,
     "interrupted by SIGINT twice: stopped at once; no unfinished file is left", key="interrupted",
     files={"scene.json": VALID, "fifo": Fifo}, signal=INT, then=((INT, 0.5),), wait_for="fifo", settle=0.1,
     na_before=SIGNALS_BEFORE)
case("sigterm-grace-fifo", C, "one SIGTERM while opening a FIFO nobody reads: ends after the 3 s grace", FIFO_SIM, 1,
     "interrupted by SIGTERM and not stopped within 3 s", key="interrupted", files={"scene.json": VALID, "fifo": Fifo},
     signal=TERM, wait_for="fifo", settle=0.1, timeout=10, na_before=SIGNALS_BEFORE,
     gtest=("SignalsCliTest.ARequestToStopNotAnsweredInTimeEndsTheRunAtOnce",))
# Standard error a pipe whose reader is gone: the forced end's line raised SIGPIPE inside
# the handler that had just locked the list of unfinished files to remove them, and the SIGPIPE
# handler waited for that lock, spinning at 100 % CPU until SIGKILL. No message can arrive; the exit
# code, the time and the directory say it. A stop the loop answers writes its line from the program,
# not a handler: SIGPIPE ends it silently, as a reader gone always does, after the removal.
DEAD_STDERR = " 2> >(exit 0)"
SPUN_BEFORE = "spun for ever before"
case("sigterm-grace-fifo-stderr-gone", C, "one SIGTERM while opening a FIFO nobody reads, stderr a pipe nobody reads",
     "exec {bin} " + FIFO_SIM + DEAD_STDERR, 1, None, shell=True, files={"scene.json": VALID, "fifo": Fifo},
     signal=TERM, wait_for="fifo", settle=0.1, timeout=10, na_before=SPUN_BEFORE)
case("sigint-twice-fifo-stderr-gone", C, "a second SIGINT while opening a FIFO nobody reads, stderr a pipe nobody reads",
     "exec {bin} " + FIFO_SIM + DEAD_STDERR, 1, None, shell=True, files={"scene.json": VALID, "fifo": Fifo},
     signal=INT, then=((INT, 0.5),), wait_for="fifo", settle=0.1, timeout=10, na_before=SPUN_BEFORE)
case("sigint-sequence-stderr-gone", C, "SIGINT during a PNG sequence, stderr a pipe nobody reads: no frame left",
     "exec {bin} " + LONG_RENDER + "f_%03d.png -q" + DEAD_STDERR, -signal.SIGPIPE, None, shell=True, files=EARLIER,
     signal=INT, na_before=SPUN_BEFORE)
# A signal ignored when coinroll starts stays ignored: nohup's SIGHUP.
case("nohup-sighup", C, "SIGHUP under nohup (ignored from the start): the run goes on to its end",
     "trap '' HUP; exec {bin} simulate scene.json --csv o.csv --sample-dt 0.0005 --set duration=150", 0, None,
     shell=True, signal=signal.SIGHUP, produces=("o.csv",), timeout=60)
# A reader gone (SIGPIPE) or a crash still ends the process as before, after removing what it staged.
case("sigpipe-sequence", C, "SIGPIPE during a PNG sequence: ends silently as before, leaves no frame",
     LONG_RENDER + "f_%03d.png", -signal.SIGPIPE, None, files=EARLIER, signal=signal.SIGPIPE)
for sig in (signal.SIGSEGV, signal.SIGABRT):
    case(f"{sig.name.lower()}-sequence", C, f"{sig.name} (a crash) during a PNG sequence: crashes, leaves no frame",
         "ulimit -c 0; exec {bin} " + LONG_RENDER + "f_%03d.png", -sig, None, shell=True, files=EARLIER, signal=sig,
         unsanitized="AddressSanitizer handles SIGSEGV itself: it reports, then aborts"
         if sig == signal.SIGSEGV else None)

# A strobe's copies are drawn in one call that cannot poll (before: exit 0 and the PNG): the
# request is answered after the draw, before the file; panels are drawn one by one, each polled.
# A draw on a loaded machine may outlast the 3 s grace: its forced end leaves no file either.
STROBE_BEFORE = "exit 0 and the PNG before"
case("sigint-still-strobe", C, "SIGINT while a still draws 500 strobe copies",
     "still scene.json --time 0.4 --strobe 500 -o o.png", 1, interrupted(INT, "o.png"),
     or_msg="interrupted by SIGINT and not stopped within 3 s", key="interrupted", signal=INT, wait_for="sleep",
     na_before=STROBE_BEFORE)
case("sigterm-still-panels", C, "SIGTERM while a still draws 501 panels",
     "still scene.json --time 0.4 --strobe 500 --panels -o o.png --set render.width=320 --set render.height=180", 1,
     interrupted(TERM, "o.png"), key="interrupted", signal=TERM, wait_for="sleep", na_before=STROBE_BEFORE)

# --- sidecars: render --frame-times and simulate --provenance are outputs of their run like
# the video or the CSV: one group, compared by the file a name leads to (not its spelling), published
# with the rest or not at all, earlier files kept on a failure and on a signal (docs/outputs.md).
C = "sidecars"
NO_SIDECARS = "no --frame-times or --provenance before"
G_SIDECAR = "FrameTimesCliTest.TheSidecarIsRefusedAsAFrameOrTheVideoUnderAnySpelling"
G_SIDECAR_FAIL = "FrameTimesCliTest.AFailedRunKeepsBothEarlierFiles"
G_SIDECAR_SIGNAL = "SignalsCliTest.ARequestToStopLeavesTheEarlierOutputsAndTheirSidecars"
SHORT_RENDER = f"render scene.json -q {SMALL} --set duration=0.1 "  # 4 frames
case("frame-times-is-frame", C, "--frame-times f_002.png with -o f_%03d.png (the frame would replace it)",
     SHORT_RENDER + "-o f_%03d.png --frame-times f_002.png", 2,
     "--frame-times f_002.png: that is named like a frame of -o f_%03d.png, which would replace it or remove it; "
     "give a name the pattern cannot make, e.g. f_frames.csv", key="--frame-times", na_before=NO_SIDECARS,
     gtest=(G_SIDECAR,))
case("frame-times-is-stale-frame", C, "--frame-times f_007.png, a frame of an earlier, longer sequence (its cleanup would remove it)",
     SHORT_RENDER + "-o f_%03d.png --frame-times f_007.png", 2, "--frame-times f_007.png: that is named like a frame of",
     key="--frame-times", files=FRAMES, na_before=NO_SIDECARS)
case("frame-times-is-video-dot", C, "-o v.mp4 --frame-times ./v.mp4", SHORT_RENDER + "-o v.mp4 --frame-times ./v.mp4", 2,
     "--frame-times ./v.mp4: that is the video's own name; give a file of its own beside it, e.g. v_frames.csv",
     key="--frame-times", na_before=NO_SIDECARS, gtest=(G_SIDECAR,))
case("frame-times-is-video-link", C, "--frame-times a symlink to the (earlier) video",
     SHORT_RENDER + "-o v.mp4 --frame-times link.csv", 2, "--frame-times link.csv: that is the video's own name",
     key="--frame-times", files={"scene.json": VALID, "v.mp4": "an earlier video", "link.csv": ("symlink", "v.mp4")},
     na_before=NO_SIDECARS)
case("frame-times-empty", C, "--frame-times ''", SHORT_RENDER + "-o v.mp4 --frame-times ''", 2,
     "--frame-times: the output name is empty; give a file name, e.g. --frame-times v_frames.csv", key="--frame-times",
     na_before=NO_SIDECARS)
case("provenance-is-csv-dot", C, "--csv o.csv --provenance ./o.csv", SIM + " --provenance ./o.csv", 2,
     "--provenance ./o.csv: give a file of its own beside the CSV, e.g. o.csv.json", key="--provenance",
     na_before=NO_SIDECARS, gtest=(G_SIDECAR,))
case("provenance-is-csv-absolute", C, "--csv o.csv --provenance $PWD/o.csv",
     'exec {bin} simulate scene.json --csv o.csv --provenance "$PWD/o.csv"', 2,
     "o.csv: give a file of its own beside the CSV, e.g. o.csv.json", key="--provenance", shell=True,
     na_before=NO_SIDECARS)
case("provenance-is-csv-link", C, "--provenance a symlink to the (earlier) CSV", SIM + " --provenance link.json", 2,
     "--provenance link.json: give a file of its own beside the CSV", key="--provenance",
     files={"scene.json": VALID, "o.csv": "an earlier CSV\n", "link.json": ("symlink", "o.csv")}, na_before=NO_SIDECARS)
case("provenance-both-stdout", C, "--csv - --provenance -", "simulate scene.json --csv - --provenance -", 2,
     "--provenance -: give a file of its own beside the CSV, e.g. run.json", key="--provenance", na_before=NO_SIDECARS)
case("provenance-stdout-dev", C, "--csv - --provenance /dev/stdout", "simulate scene.json --csv - --provenance /dev/stdout", 2,
     "--provenance /dev/stdout: give a file of its own beside the CSV, e.g. run.json", key="--provenance",
     na_before=NO_SIDECARS)
case("provenance-empty", C, "--provenance ''", SIM + " --provenance ''", 2,
     "--provenance: the output name is empty; give a file name, e.g. --provenance o.csv.json", key="--provenance",
     na_before=NO_SIDECARS)
case("provenance-non-utf8-csv", C, "--provenance for a CSV whose name is not UTF-8 (the JSON names it with U+FFFD)",
     "exec {bin} simulate scene.json --csv $'o\\xff.csv' --provenance p.json", 0, None, shell=True,
     produces=("o*.csv", "p.json"), na_before=NO_SIDECARS)
case("frame-times-sequence", C, "--frame-times beside a PNG sequence (must work)",
     SHORT_RENDER + "-o f_%03d.png --frame-times times.csv", 0, None, produces=("f_00[0-3].png", "times.csv"),
     na_before=NO_SIDECARS)
case("frame-times-video-fails", C, "-o /dev/full --frame-times t.csv over an earlier t.csv: the video fails, t.csv stays",
     SHORT_RENDER + "-o /dev/full --frame-times t.csv", 1, "/dev/full: writing the MP4 failed: No space left on device",
     key="/dev/full", files={"scene.json": VALID, "t.csv": "an earlier sidecar\n"}, na_before=NO_SIDECARS,
     gtest=(G_SIDECAR_FAIL,))
case("provenance-csv-fails", C, "--csv /dev/full --provenance p.json over an earlier p.json: the CSV fails, p.json stays",
     "simulate scene.json --csv /dev/full --provenance p.json", 1, "/dev/full: writing the CSV failed: No space left on device",
     key="/dev/full", files={"scene.json": VALID, "p.json": "an earlier provenance\n"}, na_before=NO_SIDECARS,
     gtest=(G_SIDECAR_FAIL,))
case("sigint-render-frame-times", C, "SIGINT during a render with --frame-times over earlier files (hung before)",
     LONG_RENDER + "o.mp4 --frame-times t.csv", 1, interrupted(INT, "o.mp4"), key="interrupted", signal=INT,
     files={"scene.json": VALID, "o.mp4": "an earlier video", "t.csv": "an earlier sidecar\n"}, na_before=NO_SIDECARS,
     gtest=(G_SIDECAR_SIGNAL,))
case("sigint-simulate-provenance", C, "SIGINT during simulate --provenance over earlier files (exit 0 before)",
     LONG_SIM + " --provenance p.json", 1, interrupted(INT, "o.csv"), key="interrupted", signal=INT,
     files={"scene.json": VALID, "o.csv": "an earlier CSV\n", "p.json": "an earlier provenance\n"},
     na_before=NO_SIDECARS, gtest=(G_SIDECAR_SIGNAL,))

# --- export: the page template is an input like the scene, read within a bound; the page
# goes only under an HTML name, and its embedded scene cannot end or swallow the page's script.
C = "export"
PAGE_SLOT = '<script type="application/json" id="coinroll-scene">'
OPTIONS_SLOT = '<script type="application/json" id="coinroll-page-options">'
# The page's list of its controls in their groups (web/src/page.html), of which this page has three.
PAGE_CONTROLS = ('<script type="application/json" id="coinroll-controls">[{"group": "initial", "title": "Start", '
                 '"keys": ["initial.theta", "initial.omega_Z"]}, {"group": "floor", "title": "Floor contact", '
                 '"keys": ["friction"]}]</script>')
PAGE_TAIL = f"{PAGE_CONTROLS}<script>start()</script></html>"
PAGE = f"<html>{PAGE_SLOT}null</script>{OPTIONS_SLOT}null</script>{PAGE_TAIL}"
EXPORT = "COINROLL_PAGE=page.html exec {bin} export scene.json -q "
WITH_PAGE = {"scene.json": VALID, "page.html": PAGE}
EATEN = "no such check before"


def check_embedded_scene(name, scene_name):
    """The page `name` holds the scene named `scene_name` in its slot as JSON with no '<' in it (so no
    '</script', '<!--' or '<script' can change where the element ends), and the page's script after it."""
    def check(d):
        html = (d / name).read_text()
        start = html.find(PAGE_SLOT)
        if start < 0:
            return f"{name} has no scene element"
        body = html[start + len(PAGE_SLOT):]
        end = body.find("</script>")
        embedded = body[:end]
        if "<" in embedded:
            return f"{name}: the embedded scene holds a raw '<': {embedded[:80]!r}"
        if json.loads(embedded).get("name") != scene_name:
            return f"{name}: the embedded scene's name is not {scene_name!r}"
        if not body[end:].startswith(f"</script>{OPTIONS_SLOT}") or not body.endswith(f"</script>{PAGE_TAIL}"):
            return f"{name}: the page after the scene changed"
        return None
    return check


case("export-over-template", C, "export -o the page template it reads (COINROLL_PAGE=page.html -o page.html)",
     EXPORT + "-o page.html", 2, "-o page.html: that is the input page.html; choose another output name", key="page.html",
     shell=True, files=WITH_PAGE, na_before=EATEN)
case("export-over-template-link", C, "export -o a link to the page template",
     EXPORT + "-o link.html", 2, "-o link.html: that is the input page.html; choose another output name",
     key="link.html", shell=True, files={**WITH_PAGE, "link.html": ("symlink", "page.html")}, na_before=EATEN)
case("export-page-dev-zero", C, "COINROLL_PAGE=/dev/zero (never ends)",
     "COINROLL_PAGE=/dev/zero exec {bin} export scene.json -q -o o.html", 1,
     "COINROLL_PAGE=/dev/zero: more than 67108864 bytes, far more than a built page", key="COINROLL_PAGE",
     shell=True, timeout=10, na_before=EATEN)
case("export-page-directory", C, "COINROLL_PAGE a directory",
     "COINROLL_PAGE=sub exec {bin} export scene.json -q -o o.html", 1,
     "COINROLL_PAGE=sub: is a directory; name the built page", key="COINROLL_PAGE", shell=True,
     files={"scene.json": VALID, "sub": Dir}, na_before=EATEN)
case("export-page-missing", C, "COINROLL_PAGE a file that does not exist",
     "COINROLL_PAGE=nope.html exec {bin} export scene.json -q -o o.html", 1,
     "COINROLL_PAGE=nope.html: cannot read the built page: No such file or directory", key="COINROLL_PAGE",
     shell=True, na_before=EATEN)
case("export-page-unreadable", C, "COINROLL_PAGE a file nobody may read (as nobody when run as root)",
     "export COINROLL_PAGE=page.html; " + as_nobody_when_root("export scene.json -q -o o.html"), 1,
     "COINROLL_PAGE=page.html: cannot read the built page: Permission denied", key="COINROLL_PAGE", shell=True,
     files={"scene.json": VALID, "page.html": with_mode(PAGE, 0o000)}, na_before=EATEN)
case("export-as-mp4", C, "export -o page.mp4 (an HTML page under a video's name)", EXPORT + "-o page.mp4", 2,
     "-o page.mp4: export writes an HTML page; name it .html, e.g. -o page.html", key="-o page.mp4", shell=True,
     files=WITH_PAGE, na_before=EATEN)
HOSTILE_NAME = "a <!-- b <script> c </script> d"
case("export-name-comment-script", C, "a scene name holding '<!--' then '<script': the page's script stays alive",
     EXPORT + "-o o.html", 0, None, shell=True, produces=("o.html",),
     files={"scene.json": scene(name=HOSTILE_NAME), "page.html": PAGE},
     check=check_embedded_scene("o.html", HOSTILE_NAME), na_before=EATEN)

# --- export's options for a course page: each refused, naming the option and the fix,
# before anything is written; the title and caption go into the page as JSON with no '<' in it.
NO_PAGE_OPTIONS = "no page options before"
CONTROLS_VALID = ("give control keys as the page's tooltips name them (initial.theta, initial.omega_Z, friction) "
                  "or a group (all, initial, floor), separated by commas")
case("export-controls-unknown", C, "--controls naming a key the page has no control for",
     EXPORT + "-o o.html --controls initial.theta,initial.thet", 2,
     "--controls initial.thet: no such control on the page; did you mean initial.theta? " + CONTROLS_VALID,
     key="--controls", shell=True,
     files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-controls-group-slip", C, "--controls naming a group with a letter dropped (floo)",
     EXPORT + "-o o.html --controls floo", 2, "--controls floo: no such control on the page; did you mean floor? ",
     key="--controls", shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-controls-render-key", C, "--controls naming a scene key that has no control (render.fps)",
     EXPORT + "-o o.html --controls render.fps", 2, "--controls render.fps: no such control on the page; give",
     key="--controls", shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-controls-empty-item", C, "--controls with an empty name between commas",
     EXPORT + "-o o.html --controls initial.theta,,friction", 2,
     "--controls initial.theta,,friction: an empty name between commas", key="--controls", shell=True,
     files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-controls-empty", C, "--controls ''", EXPORT + "-o o.html --controls ''", 2,
     "--controls: empty; give control keys", key="--controls", shell=True, files=WITH_PAGE,
     na_before=NO_PAGE_OPTIONS)
case("export-controls-unknown-preset", C, "--controls naming a group the page does not have",
     EXPORT + "-o o.html --controls students", 2, "--controls students: no such control on the page",
     key="--controls", shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-title-empty", C, "--title ''", EXPORT + "-o o.html --title ''", 2,
     "--title: empty; give the page's heading as one line of text, or leave --title out for the scene's name",
     key="--title", shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-title-newline", C, "--title of two lines", EXPORT + "-o o.html --title $'a\\nb'", 2,
     "--title a\\nb: holds a control character; give the page's heading as one line of text", key="--title",
     shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-title-not-utf8", C, "--title with a Latin-1 byte (not UTF-8)", EXPORT + "-o o.html --title $'caf\\xe9'", 2,
     "--title: not UTF-8 text", key="--title", shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-caption-too-long", C, "--caption of 1001 characters", EXPORT + "-o o.html --caption " + "é" * 1001, 2,
     "--caption: 1001 characters, more than 1000; give a short paragraph under the heading", key="--caption",
     shell=True, files=WITH_PAGE, na_before=NO_PAGE_OPTIONS)
case("export-details-unknown", C, "--details open (neither folded nor shown)", EXPORT + "-o o.html --details open", 2,
     "--details open: must be folded (one click away) or shown", key="--details", shell=True, files=WITH_PAGE,
     na_before=NO_PAGE_OPTIONS)
case("export-page-without-options-slot", C, "a page built before the page options (no placeholder for them)",
     EXPORT + "-o o.html", 1, "page.html: not a coinroll page of this version (it has no page-options placeholder); "
     "rebuild it with tools/build_page.sh", key="page.html", shell=True,
     files={"scene.json": VALID, "page.html": f"<html>{PAGE_SLOT}null</script><script>start()</script></html>"},
     na_before=NO_PAGE_OPTIONS)


def check_page_options(name, expected):
    """The page `name` holds `expected` as its options' JSON, with no '<' in it."""
    def check(d):
        html = (d / name).read_text()
        start = html.find(OPTIONS_SLOT)
        if start < 0:
            return f"{name} has no page-options element"
        body = html[start + len(OPTIONS_SLOT):]
        embedded = body[:body.find("</script>")]
        if "<" in embedded:
            return f"{name}: the page options hold a raw '<': {embedded[:80]!r}"
        found = json.loads(embedded)
        return None if found == expected else f"{name}: page options {found}, not {expected}"
    return check


HOSTILE_CAPTION = "a <b>caption</b> </script><!-- <script> c"
case("export-options-reach-page", C, "title, caption with '</script>', two controls and a group (must work)",
     EXPORT + "-o o.html --title 'A <i>title</i>' --caption '" + HOSTILE_CAPTION + "' --controls friction,initial "
     "--details shown", 0, None, shell=True, produces=("o.html",), files=WITH_PAGE,
     check=check_page_options("o.html", {"title": "A <i>title</i>", "caption": HOSTILE_CAPTION,
                                         "controls": ["initial.theta", "initial.omega_Z", "friction"], "details": "shown"}),
     na_before=NO_PAGE_OPTIONS)
case("export-options-defaults", C, "no options: the scene's name as title, all controls, details folded (must work)",
     EXPORT + "-o o.html", 0, None, shell=True, produces=("o.html",), files={**WITH_PAGE, "scene.json": scene(name="tilt")},
     check=check_page_options("o.html", {"title": "tilt", "caption": None, "controls": None, "details": "folded"}),
     na_before=NO_PAGE_OPTIONS)

# --- compare: a golden check in someone else's CI; 2 means "could not compare", never "same"
C = "compare"
NO_COMPARE = "no compare command before"
PNGS = {"a.png": png(64, 48), "b.png": png(64, 48, 130), "small.png": png(64, 32), "n.png": "not a picture\n"}
case("compare-missing", C, "a picture that does not exist", "compare a.png missing.png", 2,
     "missing.png: no such file; give the path of a PNG to compare", key="missing.png", files=PNGS, na_before=NO_COMPARE)
case("compare-not-png", C, "a text file named .png", "compare a.png n.png", 2, "n.png: not a PNG file", key="n.png",
     files=PNGS, na_before=NO_COMPARE)
case("compare-sizes", C, "pictures of different sizes", "compare a.png small.png", 2,
     "a.png is 64x48 but small.png is 64x32: compare pictures of the same size", key="64x32", files=PNGS, na_before=NO_COMPARE)
case("compare-diff-is-input", C, "--diff naming an input", "compare a.png b.png --diff a.png", 2,
     "--diff a.png: that is the input a.png; choose another output name", key="--diff", files=PNGS, na_before=NO_COMPARE)
case("compare-diff-not-png", C, "--diff without .png", "compare a.png b.png --diff d.txt", 2,
     "--diff: the diff image is a PNG; give a name ending in .png", key="--diff", files=PNGS, na_before=NO_COMPARE)
case("compare-diff-upper-png", C, "--diff D.PNG (.png in any case)", "compare a.png b.png --diff D.PNG", 1, "", key=None,
     files=PNGS, produces=("D.PNG",), na_before=NO_COMPARE)
case("compare-tolerance-range", C, "--channel-tolerance 300", "compare a.png b.png --channel-tolerance 300", 2,
     "--channel-tolerance: must be a whole number 0..255, got 300", key="--channel-tolerance", files=PNGS, na_before=NO_COMPARE)
case("compare-different", C, "every pixel differs by 2 levels", "compare a.png b.png", 1,
     "", key=None, files=PNGS, na_before=NO_COMPARE)
case("compare-within-tolerance", C, "the same pictures within --channel-tolerance 2",
     "compare a.png b.png --channel-tolerance 2", 0, "", key=None, files=PNGS, na_before=NO_COMPARE)
ACCEPTED_BEFORE = "accepted before"
case("compare-16-bit", C, "two 16-bit PNGs that differ in every low byte (read as 8 bits they were equal)",
     "compare a16.png b16.png", 2, "a16.png: 16 bits per channel; compare reads 8-bit PNGs", key="16 bits",
     files={"a16.png": png(8, 8, 10, bit_depth=16), "b16.png": png(8, 8, 20, bit_depth=16)}, na_before=ACCEPTED_BEFORE)
case("compare-bad-crc", C, "a PNG whose IDAT chunk fails its CRC (the decoder ignores CRCs)",
     "compare a.png bad.png", 2, "bad.png: chunk IDAT fails its CRC check at byte 33: a damaged or truncated PNG",
     key="CRC", files={"a.png": png(64, 48), "bad.png": png(64, 48, damage_at=14)}, na_before=ACCEPTED_BEFORE)
UNCLEAR_BEFORE = "a library's message before"
case("compare-empty-name", C, "compare '' a.png", "compare '' a.png", 2, "a PNG name is empty", key="PNG name",
     files={"a.png": png(8, 8)}, na_before=PROBE3)
case("compare-bad-zlib", C, "a PNG whose IDAT is not zlib data (its CRC right)", "compare a.png bad.png", 2,
     "bad.png: cannot read PNG: its compressed pixel data does not inflate", key="bad.png",
     files={"a.png": png(8, 8), "bad.png": png(8, 8, idat=b"\x78\x9cnot deflate data")}, na_before=UNCLEAR_BEFORE)
case("compare-bad-depth", C, "a PNG header with 4 bits per channel of RGB (PNG allows 8 or 16)", "compare bad.png a.png", 2,
     "bad.png: cannot read the PNG header: bit depth 4 with colour type 2 is not allowed in PNG", key="bit depth",
     files={"a.png": png(8, 8), "bad.png": png(8, 8, bit_depth=4, colour_type=2)}, na_before=UNCLEAR_BEFORE)
for id_, files, message in (
        ("missing", {}, "ad/coin_face.png: cannot read PNG: No such file or directory ($COINROLL_ASSET_DIR names"),
        ("bad-zlib", {"ad/coin_face.png": png(8, 8, idat=b"\x78\x9cnot deflate data")},
         "ad/coin_face.png: cannot read PNG: its compressed pixel data does not inflate ($COINROLL_ASSET_DIR names")):
    case(f"asset-dir-{id_}", C, f"$COINROLL_ASSET_DIR without a readable coin_face.png ({id_})",
         "COINROLL_ASSET_DIR=ad exec {bin} still scene.json --time 0.1 -o o.png", 1, message,
         key="$COINROLL_ASSET_DIR", shell=True, files={"scene.json": VALID, **files}, na_before=UNCLEAR_BEFORE)



def png_header_only(width, height):
    """A PNG whose header declares width x height and whose pixel data is missing: what a
    comparison must judge by its header, never by decoding."""
    import struct
    import zlib
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    ihdr = struct.pack(">I", len(header)) + b"IHDR" + header + struct.pack(">I", zlib.crc32(b"IHDR" + header))
    return lambda path: Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + ihdr)


def big_png(width, height, shade=128):
    """png(), streamed row by row: a 7680x7680 picture without 225 MiB in the test's memory."""
    import struct
    import zlib

    def make(path):
        compressor, row = zlib.compressobj(1), b"\0" + bytes([shade, shade, shade, 255]) * width
        data = b"".join(compressor.compress(row) for _ in range(height)) + compressor.flush()
        header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
        chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
        Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b""))
    return make


# A PNG of one colour is tiny on disk for any size it declares (before: 389 KB for 20000x20000,
# 1.5 GiB decoded); sizes are judged from the headers, and what will not fit is refused, before
# anything is decoded. The address-space limit (1 GB, above what the binary maps to start) makes
# any decoding of these fail loudly.
UNCHECKED_BEFORE = "no such check before"
HUGE = {"huge.png": png_header_only(20000, 20000), "a.png": png(64, 48), "max.png": png_header_only(7680, 7680),
        "max2.png": png_header_only(7680, 7680)}
case("compare-header-size-first", C, "a PNG declaring 20000x20000 against a 64x48 one: refused by the headers",
     "ulimit -v 1000000; exec {bin} compare huge.png a.png", 2, "huge.png is 20000x20000 but a.png is 64x48",
     key="20000x20000", shell=True, files=HUGE, timeout=5, na_before=NO_COMPARE)
case("compare-too-large", C, "two PNGs declaring 20000x20000: more than compare decodes",
     "ulimit -v 1000000; exec {bin} compare huge.png huge.png", 2,
     "are 20000x20000, more than the 58982400 pixels compare decodes (7680x7680, the largest picture coinroll draws)",
     key="20000x20000", shell=True, files=HUGE, timeout=5, na_before=UNCHECKED_BEFORE)
case("compare-memory", C, "two 7680x7680 PNGs under a 650 MB address-space limit: refused before decoding",
     "ulimit -v 650000; exec {bin} compare max.png max2.png", 2,
     "not enough memory for comparing two 7680x7680 pictures: it needs about 675 MiB", key="memory", shell=True,
     files=HUGE, timeout=5, na_before=UNCHECKED_BEFORE)
# A decode cannot stop half-way; on a loaded machine one can outlast the 3 s grace, and then the
# grace's own ending (exit 2, nothing left, no verdict) is the designed outcome, not a failure.
case("compare-sigint", C, "SIGINT while decoding two 7680x7680 pictures: stops, exit 2 (never a verdict)",
     "compare a.png b.png", 2, "interrupted by SIGINT; nothing was compared", key="interrupted", signal=INT,
     or_msg="interrupted by SIGINT and not stopped within 3 s (inside a call that cannot stop half-way)",
     wait_for="sleep", settle=0.3, files={"a.png": big_png(7680, 7680), "b.png": big_png(7680, 7680, 130)},
     na_before=NO_COMPARE)

# --- absurd sizes: refused up front, not after hours of work (a short timeout is the check)
C = "absurd sizes"
case("rows-absurd", C, "--sample-dt 1e-10: 5e9 rows", SIM + " --sample-dt 1e-10", 2,
     "more than the limit 100000000; raise --sample-dt, or the limit with --max-rows", key="rows", timeout=5,
     gtest=(G_ABSURD,))
case("frames-absurd", C, "render 1e7 s at 240 fps: 2.4e9 frames",
     "render scene.json -o o.mp4 --set duration=1e7 --set render.fps=240", 2,
     "2.4e+09 frames, more than the limit 1000000", key="frames", timeout=5, gtest=(G_ABSURD,))
case("steps-absurd", C, "rk4 at dt 1e-7 for 1000 s: 1e10 fixed steps",
     SIM + " --sample-dt 1 --set solver.method=rk4 --set solver.dt=1e-7 --set duration=1000", 2, "solver.dt", timeout=5)
case("points-absurd", C, "one grid axis of 10^9 points", SW + "--grid initial.theta=1:2:1000000000", 2,
     "the grid has more than 10000000 points (--max-points)", key="--max-points", timeout=5)
case("strobe-absurd", C, "still --strobe 100000000", f"still scene.json --time 0.1 -o o.png --strobe 100000000", 2,
     "--strobe: must be 0 to 500 copies, got 100000000", key="--strobe", timeout=5)

# Before, 5e8 rows ran without a word (150 GB of CSV); the count was a fraction ("1.5 rows").
ROWS_BEFORE = "ran, or counted rows as a fraction, before"
case("rows-sample-dt-1e-9", C, "--sample-dt 1e-9 on a 0.5 s run: 5e8 rows", SIM + " --sample-dt 1e-9", 2,
     "--sample-dt 1e-09: duration 0.5 s gives 500000001 rows (about 150 GB of CSV), more than the limit 100000000; "
     "raise --sample-dt, or the limit with --max-rows", key="rows", timeout=5, na_before=ROWS_BEFORE)
case("rows-whole-count", C, "--sample-dt 1 --max-rows 1 on a 0.5 s run: one row, t = 0 (must work)",
     SIM + " --sample-dt 1 --max-rows 1", 0, None, produces=("o.csv",), na_before=ROWS_BEFORE)
case("rows-whole-count-refused", C, "--sample-dt 0.3 --max-rows 1 on a 0.5 s run: 2 rows, not 2.667",
     SIM + " --sample-dt 0.3 --max-rows 1", 2, "--sample-dt 0.3: duration 0.5 s gives 2 rows (about 0.6 kB of CSV), "
     "more than the limit 1", key="rows", na_before=ROWS_BEFORE)

# Before, the hopeless-pace refusal took 31-42 s; the toss at 1e6 s ran on past 60 s (now more
# rows than the limit at the default --sample-dt).
EXAMPLES = REPO / "examples"
case("pace-hopeless-ring", C, "the ring at omega_Z 1e6 rad/s for 1000 s: 2.7e8 steps, refused within seconds",
     "simulate ring.json --set initial.omega_Z=1e6 --set duration=1000 --csv /dev/null", 1,
     "integration would need about 2.7e+08 steps to reach t = 1000 s at its pace so far", key="steps",
     files={"ring.json": (EXAMPLES / "ring.json").read_text()}, timeout=15, na_before="refused after 31-42 s before",
     unsanitized="the check is the time, and the sanitizers run the integration several times slower")
case("toss-no-effects-1e6", C, "the toss without effects for 1e6 s at the default 0.01 s: 1e8 rows, refused up front",
     "simulate coin_toss.json --set effects=[] --set duration=1e6 --csv o.csv", 2,
     "--sample-dt 0.01: duration 1000000 s gives 100000001 rows", key="rows",
     files={"coin_toss.json": (EXAMPLES / "coin_toss.json").read_text()}, timeout=5,
     na_before="ran on past 60 s before")
case("toss-no-effects-1e6-coarse", C, "the same toss sampled every 1000 s: 2.6e8 steps over thousands of segments",
     "simulate coin_toss.json --set effects=[] --set duration=1e6 --sample-dt 1000 --csv o.csv", 1,
     "steps to reach t = 1000000 s at its pace so far", key="steps",
     files={"coin_toss.json": (EXAMPLES / "coin_toss.json").read_text()}, timeout=20,
     na_before="ran on past 5 minutes before: each segment's pace was judged alone",
     unsanitized="the check is the time, and the sanitizers run the integration several times slower")

# --- resources: what a command needs is checked before it starts, and what
# runs out is named. OpenGL on llvmpipe does not check its allocations (it segfaulted or hung);
# the pictures here need about 2 GiB, more than a 1.5 GB address-space limit leaves after the
# binary's own 0.35 GB.
C = "resources"
BIG = "--set render.width=7680 --set render.height=4320"
AS_LIMIT = "ulimit -v 1500000; exec {bin} "
G_AS = "RenderCliTest.UnderAnAddressSpaceLimitTooSmallRenderingIsRefusedNamingIt"
case("still-address-space", C, "a 7680x4320 still under a 1.5 GB address-space limit",
     AS_LIMIT + f"still scene.json --time 0.1 -o o.png {BIG}", 1,
     "not enough memory for drawing 7680x4320 pictures with 4 samples per pixel", key="memory", shell=True,
     timeout=10, gtest=(G_AS,))
case("render-address-space", C, "a 7680x4320 MP4 under a 1.5 GB address-space limit",
     AS_LIMIT + f"render scene.json -q -o o.mp4 {BIG}", 1,
     "not enough memory for drawing and encoding 7680x4320 pictures", key="memory", shell=True, timeout=10,
     gtest=(G_AS,))
case("sequence-address-space", C, "a 7680x4320 PNG sequence under a 1.5 GB address-space limit",
     AS_LIMIT + f"render scene.json -q -o f_%03d.png {BIG}", 1,
     "not enough memory for drawing and encoding 7680x4320 pictures", key="memory", shell=True, timeout=10)
# Threads whose 1 GB stacks (ulimit -s) cannot all fit: it used to say only "Resource temporarily
# unavailable", or end in std::terminate.
case("sweep-thread-stacks", C, "sweep --threads 4 with 1 GB thread stacks under a 1.5 GB limit",
     "ulimit -v 1500000; ulimit -s 1000000; exec {bin} sweep scene.json -q --threads 4 "
     "--grid initial.theta=1:20:40 -o o.csv", 1, "of 4: Resource temporarily unavailable: a thread needs memory for "
     "its stack, within the address-space limit of 1465 MiB (ulimit -v 1500000)",
     key="thread", shell=True, timeout=10)
# A bare std::bad_alloc before. A legal 8 MiB scene (padded with spaces) cannot be read and parsed
# under 16 MB.
case("out-of-memory-named", C, "an 8 MiB scene under a 16 MB address-space limit: out of memory, named",
     "ulimit -v 16000; exec {bin} simulate big.json --csv o.csv", 1,
     "out of memory: the address-space limit of 16 MiB (ulimit -v 16000) is used up", key="memory", shell=True,
     files={"big.json": VALID[:-1] + " " * (8 << 20) + "}"}, timeout=10)
# Before, the scene reader took 16 MiB for any scene, so a 400-byte one could not run under 16 MB.
case("small-scene-small-limit", C, "a small scene under a 12 MB address-space limit runs (reads in chunks)",
     "ulimit -v 12000; exec {bin} simulate scene.json --csv o.csv", 0, None, produces=("o.csv",), shell=True,
     timeout=10, na_before="out of memory under 16 MB before")
# A 16 MiB array is eight million JSON values: parsed, it took 128 MB, and as much again to free,
# which under a 250 MB limit ended the program in std::terminate as the scene's error unwound.
case("scene-too-many-values", C, "a 16 MB scene array of zeros under a 250 MB address-space limit",
     "ulimit -v 250000; exec {bin} simulate big.json --csv o.csv", 2,
     "big.json: (top level): more than 65536 values in one array or object", key="(top level)", shell=True,
     files={"big.json": "[" + "0," * ((8 << 20) - 4) + "0]"}, timeout=10)
# A damaged row numbered 9e18 made sweep-merge count (and list) every point up to it.
case("merge-point-9e18", C, "sweep-merge with a row numbered 9e18 under a 1 GB address-space limit",
     "ulimit -v 1000000; exec {bin} sweep-merge -o m.csv p1.csv p2.csv far.csv", 1,
     "far.csv:2: point 9000000000000000000 is outside the grid of 40 points", key="far.csv", shell=True, timeout=5,
     files={**SHARDS, "far.csv": shard([9000000000000000000])})


# ----------------------------------------------------------------------------------------------
# The runner


@dataclass
class Result:
    case: Case
    ok: bool
    why: str
    rc: int | None
    stderr: str
    seconds: float


def populate(directory: Path, files: dict):
    for name, content in files.items():
        path = directory / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if content is Dir:
            path.mkdir(exist_ok=True)
        elif content is Fifo:
            os.mkfifo(path)
        elif callable(content):
            content(path)
        elif isinstance(content, tuple) and content[0] == "symlink":
            path.symlink_to(content[1])
        else:
            path.write_bytes(content if isinstance(content, bytes) else content.encode())


def snapshot(directory: Path) -> dict:
    """Every entry under the directory, with a file's size and modification time (contents may be 17 MiB)."""
    state = {}
    for root, dirs, names in os.walk(directory):
        for name in dirs + names:
            path = Path(root) / name
            rel = str(path.relative_to(directory))
            if path.is_symlink():
                state[rel] = ("link", os.readlink(path))
            elif path.is_dir():
                state[rel] = ("dir",)
            elif not stat.S_ISREG(path.stat().st_mode):
                state[rel] = ("special", stat.S_IFMT(path.stat().st_mode))  # never opened: a FIFO would block
            else:
                info = path.stat()
                small = path.read_bytes() if info.st_size < 1 << 20 else None
                state[rel] = ("file", info.st_size, info.st_mtime_ns, small, stat.S_IMODE(info.st_mode), info.st_uid)
    return state


def short(name: str) -> str:
    return name if len(name) <= 40 else name[:16] + "…" + name[-16:]


def check_directory(c: Case, before: dict, after: dict) -> str | None:
    problems = []
    new = sorted(set(after) - set(before))
    problems += [f"did not write {short(pattern)}" for pattern in c.produces
                 if not any(fnmatch.fnmatchcase(name, pattern) for name in new)]
    left = [name for name in new if not any(fnmatch.fnmatchcase(name, p) for p in c.produces)]
    if left:
        problems.append("left " + ", ".join(map(short, left[:3])) + (" ..." if len(left) > 3 else ""))
    altered = lambda name: any(fnmatch.fnmatchcase(name, p) for p in c.alters)
    problems += [f"removed its input {short(name)}" for name in sorted(set(before) - set(after)) if not altered(name)]
    problems += [f"changed its input {short(name)}" for name in before
                 if name in after and before[name] != after[name] and not altered(name)]
    return "; ".join(problems) or None


class Drain(threading.Thread):
    """Reads a pipe to its end: a child blocked on a full pipe would never see its signal."""

    def __init__(self, pipe):
        super().__init__(daemon=True)
        self.pipe, self.data = pipe, bytearray()

    def run(self):
        for chunk in iter(lambda: self.pipe.read1(65536), b""):
            self.data += chunk


def command_of(c: Case, binary: str) -> list[str]:
    if c.shell:
        return ["bash", "-c", c.args.replace("{bin}", shlex.quote(binary))]
    return [binary, *shlex.split(c.args)]


def catches(pid: int, sig: int) -> bool:
    """Whether the process handles or ignores `sig` (its SigCgt and SigIgn masks in /proc)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    masks = [int(line.split()[1], 16) for line in status.splitlines() if line.startswith(("SigCgt:", "SigIgn:"))]
    return any(mask >> (int(sig) - 1) & 1 for mask in masks)


def writing_temporary(pid: int, directory: Path) -> bool:
    """True while the process writes a temporary in `directory`: a hidden `.NAME.partial-PID-N`, or an
    unnamed file (O_TMPFILE, src/io/temporary.h) among its descriptors, whose link reads "DIR/#INODE (deleted)"."""
    if any(".partial" in p.name for p in directory.iterdir()):
        return True
    unnamed = str(directory.resolve()) + "/#"
    try:
        descriptors = os.listdir(f"/proc/{pid}/fd")
    except OSError:
        return False
    for descriptor in descriptors:
        try:
            if os.readlink(f"/proc/{pid}/fd/{descriptor}").startswith(unnamed):
                return True
        except OSError:
            pass
    return False


def kernel_wait(pid: int) -> str:
    """The kernel function the process sleeps in ("wait_for_partner": opening a FIFO nobody reads)."""
    try:
        return Path(f"/proc/{pid}/wchan").read_text().strip()
    except OSError:
        return ""


def run_process(c: Case, binary: str, directory: Path):
    """Returns (exit code or None on timeout, stderr text, problem found while running or None)."""
    process = subprocess.Popen(command_of(c, binary), cwd=directory, stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = Drain(process.stdout), Drain(process.stderr)
    out.start()
    err.start()
    problem = None
    if c.signal is not None:
        deadline = time.monotonic() + 10
        started = lambda: (writing_temporary(process.pid, directory) if c.wait_for == "partial"
                           else len(out.data) > 0 if c.wait_for == "stdout"
                           else kernel_wait(process.pid) == "wait_for_partner" if c.wait_for == "fifo" else False)
        while c.wait_for != "sleep" and process.poll() is None and not started() and time.monotonic() < deadline:
            time.sleep(0.01)
        # A fixed sleep alone is too short on a loaded machine: the signal would land before the
        # handlers exist and kill the process outright. So wait until it catches the signal.
        while process.poll() is None and not catches(process.pid, c.signal) and time.monotonic() < deadline:
            time.sleep(0.01)
        time.sleep(c.settle if c.settle is not None else 0.3 if c.wait_for != "sleep" else 1.0)  # past any setup
        if process.poll() is not None:
            problem = "finished before the signal (make the run longer)"
        else:
            process.send_signal(c.signal)
            for later, seconds in c.then:
                time.sleep(seconds)
                if process.poll() is None:
                    process.send_signal(later)
    try:
        rc = process.wait(timeout=c.timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
        rc, problem = None, problem or f"still running after {c.timeout:g} s (killed)"
    out.join()
    err.join()
    return rc, err.data.decode("utf-8", "replace"), problem


def exit_text(rc: int | None) -> str:
    """An exit code, or the signal a negative one (Popen's way) says the process died of."""
    return f"killed by {signal.Signals(-rc).name}" if rc is not None and rc < 0 else f"exit {rc}"


def run_case(c: Case, binary: str, lenient: bool = False) -> Result:
    """lenient: an older wording passes if it names c.key (for the 'before' column)."""
    directory = Path(tempfile.mkdtemp(prefix=f"coinroll_bad_{c.id}_"))
    start = time.monotonic()
    try:
        populate(directory, c.files)
        before = snapshot(directory)
        rc, stderr, problem = run_process(c, binary, directory)
        seconds = time.monotonic() - start
        after = snapshot(directory)
        why = problem
        if why is None and rc is not None and rc < 0 and rc != c.rc:
            why = f"killed by {signal.Signals(-rc).name}"
        if why is None and rc != c.rc:
            why = f"{exit_text(rc)}, expected {exit_text(c.rc)}"
        wanted = (c.key or c.msg) if lenient else c.msg
        if why is None and wanted is not None and wanted not in stderr and not (c.or_msg and c.or_msg in stderr):
            why = f"stderr lacks {wanted!r}: {first_line(stderr) or '(nothing)'}"
        # After our own SIGKILL a temporary is expected: the timeout is the finding, not the leftover.
        directory_problem = check_directory(c, before, after) if rc is not None else None
        if directory_problem is None and rc is not None and c.check is not None:
            directory_problem = c.check(directory)
        if directory_problem:
            why = directory_problem if why is None else f"{why}; {directory_problem}"
        return Result(c, why is None, why or "", rc, stderr, seconds)
    finally:
        shutil.rmtree(directory, ignore_errors=True)


def first_line(stderr: str, containing: str | None = None) -> str:
    lines = [line.strip() for line in re.split(r"[\r\n]+", stderr) if line.strip()]
    for line in lines:
        if containing and containing in line:
            return line
    return lines[0] if lines else ""


# ----------------------------------------------------------------------------------------------
# The document


def gtest_names() -> set[str]:
    names = set()
    for source in (HERE).glob("*.cpp"):
        for suite, test in re.findall(r"TEST(?:_F)?\(\s*(\w+)\s*,\s*(\w+)\s*\)", source.read_text(errors="replace")):
            names.add(f"{suite}.{test}")
    return names


def cell(text: str, limit: int = 110) -> str:
    text = text.replace("|", "\\|").replace("\n", " ").strip()
    text = text if len(text) <= limit else text[: limit - 1] + "…"
    return text


def write_markdown(path: Path, results: list[Result], before: dict, seconds: float):
    # Cases added after the recording: a feature that did not exist then is n/a, not unknown.
    before = {**{r.case.id: "n/a" for r in results if r.case.na_before}, **before}
    known = gtest_names()
    wrong_before = sum(1 for r in results if before.get(r.case.id, "").startswith("wrong"))
    na_before = sum(1 for r in results if before.get(r.case.id) == "n/a")
    failing = [r for r in results if not r.ok]
    categories = list(dict.fromkeys(r.case.cat for r in results))
    lines = [
        "# Bad inputs and faults",
        "",
        "<!-- Generated by tests/cli/bad_inputs.py --markdown docs/bad_inputs.md; edit the table there. -->",
        "",
        "What coinroll does with bad scenes, bad command lines, unwritable or full outputs, broken pipes and "
        "signals: one row per case of `tests/cli/bad_inputs.py`, which runs each against the binary in its own "
        "scratch directory and checks the exit code (0 ok, 1 runtime failure, 2 bad input), that stderr names the "
        "field or flag, and that nothing is left in the directory (a case that must succeed leaves exactly its "
        "output). Run it with",
        "",
        "    /usr/bin/python3 tests/cli/bad_inputs.py --binary build/coinroll            # --only ID for one case",
        "",
        "ctest runs it as `cli_bad_inputs.CATEGORY`, one entry per category (`--category`); the cases that are a "
        "scene in and a refusal out run in process too (`bad_scene_test`). This page is its `--markdown "
        "docs/bad_inputs.md` output.",
        "",
        f"**{len(results)} cases** in {len(categories)} categories; against today's binary {len(results) - len(failing)} "
        f"pass and {len(failing)} fail (column *now*), in {seconds:.0f} s. Against the build of commit 32cc7d7, the "
        f"last before the reliability work, **{wrong_before} were wrong** and {na_before} n/a (the feature did not exist "
        "then); column *before*. There the message only had to name the field or flag, not match today's wording. "
        "That column comes from `tests/cli/bad_inputs_before.json`, recorded with",
        "",
        "    git worktree add /tmp/coinroll_before 32cc7d7",
        "    cmake -S /tmp/coinroll_before -B /tmp/coinroll_before/build -DCOINROLL_BENCHMARKS=OFF",
        "    cmake --build /tmp/coinroll_before/build -j2 --target coinroll",
        "    /usr/bin/python3 tests/cli/bad_inputs.py --binary /tmp/coinroll_before/build/coinroll \\",
        "        --record-before tests/cli/bad_inputs_before.json",
        "",
        "| category | cases | fail now | wrong before | n/a before |",
        "|---|---|---|---|---|",
        *[f"| {cat} | {sum(r.case.cat == cat for r in results)} | "
          f"{sum(r.case.cat == cat and not r.ok for r in results)} | "
          f"{sum(r.case.cat == cat and before.get(r.case.id, '').startswith('wrong') for r in results)} | "
          f"{sum(r.case.cat == cat and before.get(r.case.id) == 'n/a' for r in results)} |" for cat in categories],
        "",
        "*Exit* is the expected exit code; *message* the first line of stderr that holds what the case checks, "
        "as today's binary prints it; *now* whether today's binary passes; *tests* the GoogleTest tests in "
        "`tests/cli/*.cpp` that check the same case, besides bad_inputs.py.",
        "",
    ]
    for category in categories:
        rows = [r for r in results if r.case.cat == category]
        lines += [f"## {category} ({len(rows)})", "",
                  "| case | input / fault | exit | message | now | tests | before |",
                  "|---|---|---|---|---|---|---|"]
        for r in rows:
            c = r.case
            tests = ["bad_inputs.py"] + [g for g in c.gtest if g in known]
            message = first_line(r.stderr, c.msg) if c.msg or r.stderr.strip() else ""
            lines.append(f"| `{c.id}` | {cell(c.what)} | {c.rc if c.rc >= 0 else exit_text(c.rc)} | {cell(message) if message else '(none)'} | "
                         f"{'ok' if r.ok else 'FAILS: ' + cell(r.why, 90)} | {', '.join(tests)} | "
                         f"{cell(before.get(c.id, '?'), 80)} |")
        lines.append("")
    path.write_text("\n".join(lines))


# ----------------------------------------------------------------------------------------------


def slug(category: str) -> str:
    """A category as a ctest name part: "coin's rim" -> coins_rim, "--set" -> set."""
    return re.sub(r"[^a-z0-9]+", "_", category.lower().replace("'", "")).strip("_")


def scene_case_overrides(c: Case) -> list[str] | None:
    """The --set assignments of a case that is only a scene refused on loading, or None: a plain
    `simulate scene.json --csv o.csv [--set K=V]...` over one scene file, exit 2 with a message, no
    signal, no directory check. Such a case's refusal comes from reading, parsing or building the
    simulation, before the program writes or runs anything."""
    if c.shell or c.signal or c.check is not None or c.rc != 2 or not c.msg or set(c.files) != {"scene.json"}:
        return None
    if not isinstance(c.files["scene.json"], (str, bytes)):
        return None
    words = shlex.split(c.args)
    if words[:4] != ["simulate", "scene.json", "--csv", "o.csv"] or len(words) % 2:
        return None
    pairs = list(zip(words[4::2], words[5::2]))
    if any(flag != "--set" for flag, _ in pairs):
        return None
    return [value for _, value in pairs]


def export_scene_cases(path: Path):
    cases = []
    for c in CASES:
        overrides = scene_case_overrides(c)
        if overrides is None:
            continue
        content = c.files["scene.json"]
        raw = content if isinstance(content, bytes) else content.encode()
        # In hex: some scenes are not UTF-8 (that is what they test), and a JSON string holds text.
        cases.append({"id": c.id, "scene_hex": raw.hex(), "overrides": overrides, "message": c.msg,
                      "or_message": c.or_msg or ""})
    path.write_text(json.dumps(cases, indent=1, ensure_ascii=True) + "\n")


def main() -> int:
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the listing quietly; children get SIG_DFL anyway
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--binary", default=str(REPO / "build" / "coinroll"),
                        help="the coinroll binary (default: ../../build/coinroll beside this script)")
    parser.add_argument("--only", help="run this case id only")
    parser.add_argument("--markdown", help="write the table as Markdown to this file")
    parser.add_argument("--before-results", default=str(HERE / "bad_inputs_before.json"),
                        help="the --record-before file the Markdown's 'before' column reads")
    parser.add_argument("--record-before", metavar="FILE",
                        help="run against an older binary and record per case ok / wrong: why / n/a")
    parser.add_argument("--jobs", type=int, default=2, help="cases run at once (default 2; each has its own directory)")
    parser.add_argument("--category", action="append", metavar="SLUG",
                        help="run this category only (its --list-categories slug); may be repeated")
    parser.add_argument("--list-categories", action="store_true", help="print each category's slug and case count")
    parser.add_argument("--export-scene-cases", metavar="FILE",
                        help="write the scene-only refusals as JSON for the in-process test, and exit")
    options = parser.parse_args()

    categories = list(dict.fromkeys(c.cat for c in CASES))
    if options.list_categories:
        for category in categories:
            print(f"{slug(category)} {sum(c.cat == category for c in CASES)}")
        return 0
    if options.export_scene_cases:
        export_scene_cases(Path(options.export_scene_cases))
        return 0
    unknown = set(options.category or ()) - {slug(category) for category in categories}
    if unknown:
        print(f"bad_inputs.py: no category {', '.join(sorted(unknown))}; --list-categories lists them", file=sys.stderr)
        return 2

    binary = str(Path(options.binary).resolve())
    if not os.access(binary, os.X_OK):
        print(f"bad_inputs.py: {binary}: not an executable (build it, or give --binary)", file=sys.stderr)
        return 2
    ids = [c.id for c in CASES]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    cases = [c for c in CASES if options.only in (None, c.id) and (not options.category or slug(c.cat) in options.category)]
    if not cases:
        print(f"bad_inputs.py: no case {options.only!r}", file=sys.stderr)
        return 2
    if is_sanitized(binary):
        for c in cases:
            if unsanitized_reason(c):
                print(f"SKIP {c.id}: {unsanitized_reason(c)}")
        cases = [c for c in cases if not unsanitized_reason(c)]

    start = time.monotonic()
    pool = concurrent.futures.ThreadPoolExecutor(max(1, options.jobs))
    if options.record_before:
        verdicts = {}
        runnable = [c for c in cases if not c.na_before]
        for r in pool.map(lambda c: run_case(c, binary, lenient=True), runnable):
            verdicts[r.case.id] = "ok" if r.ok else "wrong: " + r.why
        verdicts = {c.id: verdicts.get(c.id, "n/a") for c in cases}
        for case_id, verdict in verdicts.items():
            print(f"{case_id}: {verdict}")
        Path(options.record_before).write_text(json.dumps(verdicts, indent=1, ensure_ascii=False) + "\n")
        return 0

    results = []
    for r in pool.map(lambda c: run_case(c, binary), cases):  # in table order, as they finish
        results.append(r)
        print(f"{'PASS' if r.ok else 'FAIL'} {r.case.id} ({r.case.cat}; {r.seconds:.1f} s)"
              f"{': ' + r.why if not r.ok else ''}", flush=True)
    seconds = time.monotonic() - start
    failed = [r for r in results if not r.ok]
    print(f"{len(results)} cases, {len(results) - len(failed)} passed, {len(failed)} failed, {seconds:.1f} s")

    if options.markdown:
        path = Path(options.before_results)
        before = json.loads(path.read_text()) if path.exists() else {}
        write_markdown(Path(options.markdown), results, before, seconds)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
