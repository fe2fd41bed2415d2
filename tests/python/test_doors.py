"""The Python door keeps the command's rules and speaks Python (docs/usage.md "Python"): an output
never replaces the scene it was read from, a run's size is refused before any work, messages name
the keywords a Python user types, scene dicts take numpy's scalars and refuse NaN naming the key,
the tables are read-only, and an interpreter without numpy is told what the package was built for.
"""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import coinroll
from conftest import TOY

# The S: the toy run with small pictures.
S = {"name": "s", **TOY, "render": {"width": 160, "height": 90}}


def refusal(call, *args, **kwargs):
    with pytest.raises(ValueError) as raised:
        call(*args, **kwargs)
    return str(raised.value)


def test_render_never_writes_over_its_scene_file(tmp_path):
    scene = tmp_path / "scene.mp4"
    scene.write_text(json.dumps(S))
    assert refusal(coinroll.render, scene, scene) == (
        f"path {scene}: that is the input {scene}; choose another output name")
    assert json.loads(scene.read_text()) == S


def test_render_never_writes_a_png_sequence_over_its_scene_file(tmp_path):
    scene = tmp_path / "frame_00001.png"
    scene.write_text(json.dumps(S))
    assert f"one of its frames would be the input {scene}" in refusal(coinroll.render, scene,
                                                                       tmp_path / "frame_%05d.png")
    assert json.loads(scene.read_text()) == S
    assert os.listdir(tmp_path) == ["frame_00001.png"]


def test_simulate_refuses_more_rows_than_the_commands_limit_at_once():
    # In a child with 4 GB of address space: a run that is not refused fails there with MemoryError
    # instead of filling the machine's memory.
    check = f"""
import resource, time, coinroll
resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
start = time.monotonic()
try:
    coinroll.simulate({S!r}, 1e-10)
except ValueError as error:
    print(error)
print(time.monotonic() - start < 5)
"""
    result = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, timeout=120)
    assert result.stdout.splitlines() == [
        "sample_dt 1e-10: duration 0.5 s gives 5000000006 rows, more than the limit 100000000; raise sample_dt",
        "True"], result.stderr


def test_messages_name_the_python_keywords_and_no_command_line_flag(tmp_path):
    assert refusal(coinroll.simulate, S, -1) == "sample_dt: must be a finite number > 0 s, got -1"
    assert refusal(coinroll.still, S, 7) == "t: must be within the scene's duration, 0 to 0.5 s, got 7"
    assert refusal(coinroll.render, S, "") == (
        'path: the file name is empty; give the file to write, e.g. "clip.mp4" (or "frame_%05d.png" for a '
        "PNG sequence)")
    transparent = refusal(coinroll.render, S, tmp_path / "clip.mp4", overrides=['render.background="transparent"'])
    assert transparent.startswith('render.background: "transparent" needs an output with alpha'), transparent
    frames = refusal(coinroll.render, S, tmp_path / "clip.mp4", overrides=["duration=1e9"])
    assert frames.endswith("shorten the duration, raise time_scale or lower fps"), frames
    for message in (transparent, frames):
        assert "--" not in message and "VideoOptions" not in message, message
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("nan", [float("nan"), np.float32("nan"), float("inf"), np.float16("-inf")])
def test_a_nan_in_a_scene_dict_is_refused_naming_its_key(nan):
    scene = json.loads(json.dumps(S))
    scene["initial"]["y"] = nan
    assert refusal(coinroll.simulate, scene) == f"scene JSON: initial.y: must be a finite number, got {float(nan)}"
    scene = {**S, "coin": {**S["coin"], "restitution": [0.5, nan]}}
    assert refusal(coinroll.simulate, scene).startswith("scene JSON: coin.restitution[1]: must be a finite number")


@pytest.mark.parametrize("kind", [np.float32, np.int64, np.float16, np.uint8])
def test_steady_takes_numpys_scalars_as_simulate_does(kind):
    assert coinroll.steady(kind="circle", theta=kind(20), omega_Z=kind(10)) == \
        coinroll.steady(kind="circle", theta=20, omega_Z=10)


def test_steady_reads_a_numpy_bool_as_the_bool_it_is():
    assert refusal(coinroll.steady, kind="circle", theta=np.bool_(True), omega_Z=10) == \
        refusal(coinroll.steady, kind="circle", theta=True, omega_Z=10)


def test_the_tables_arrays_are_read_only():
    run = coinroll.simulate(S)
    sweep = coinroll.sweep(S, {"initial.theta": [5, 10]})
    for array in [*run.values(), *sweep.values()]:
        assert not array.flags.writeable
    with pytest.raises(ValueError):
        run["t"][0] = 1


def test_an_interpreter_without_numpy_is_told_what_the_package_was_built_for():
    # -S leaves out site-packages, where this interpreter's numpy is: as a python3 without numpy.
    result = subprocess.run([sys.executable, "-S", "-c", "import coinroll"], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode != 0
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith(f"ImportError: coinroll cannot be imported by {sys.executable} (Python "), last
    assert "No module named 'numpy'; coinroll was built for /" in last and "-m pip install numpy" in last, last


# A multiprocessing "fork" pool, as a researcher's sweep would use one. Each case runs in a fresh
# interpreter, because what a child may do depends on what its parent drew before the fork.
FORK_POOL = """
import multiprocessing, sys
import coinroll
S = %r
def draw(_):
    try:
        return int(coinroll.still(S, 0.2).sum())
    except RuntimeError as error:
        return str(error)
if sys.argv[1] == 'after':
    coinroll.still(S, 0.2)
with multiprocessing.get_context('fork').Pool(2) as pool:
    print(repr(pool.map_async(draw, range(2)).get(timeout=60)))
"""


def fork_pool(when, **environment):
    result = subprocess.run([sys.executable, "-c", FORK_POOL % S, when], capture_output=True, text=True,
                            timeout=120, env={**os.environ, **environment})
    assert result.returncode == 0, result.stderr
    return eval(result.stdout)


def test_a_child_forked_after_a_draw_is_refused_naming_the_fix_not_left_waiting():
    # Before, the pool's children waited for ever on the parent's llvmpipe threads: a TimeoutError.
    for answer in fork_pool("after"):
        assert "forked from process" in answer and "multiprocessing.get_context('spawn')" in answer, answer


def test_a_child_forked_before_any_draw_draws_what_the_parent_draws():
    expected = int(coinroll.still(S, 0.2).sum())
    assert fork_pool("before") == [expected, expected]


def test_a_child_forked_after_a_draw_on_one_thread_draws_too():
    expected = int(coinroll.still(S, 0.2).sum())
    assert fork_pool("after", LP_NUM_THREADS="0") == [expected, expected]
