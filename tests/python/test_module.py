"""The module's calls against the command's outputs and messages, its errors and its manners:
Ctrl-C stops a long call cleanly, and Python threads run while it works."""

import csv
import json
import math
import multiprocessing
import os
import re
import signal
import threading
import time

import numpy as np
import pytest

import coinroll
from conftest import EXAMPLES, TOY


def test_a_bad_scene_raises_value_error_with_the_commands_message(tmp_path, run_cli):
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps({**TOY, "coin": {**TOY["coin"], "radius": -1}}))
    cli = run_cli("simulate", scene, "--csv", tmp_path / "out.csv")
    assert cli.returncode == 2
    with pytest.raises(ValueError) as raised:
        coinroll.simulate(scene)
    assert "coin.radius" in str(raised.value)
    assert cli.stderr.strip() == f"coinroll: error: {raised.value}"
    with pytest.raises(ValueError, match=r"^scene JSON: coin\.radius: "):
        coinroll.simulate({**TOY, "coin": {**TOY["coin"], "radius": -1}})
    with pytest.raises(ValueError, match=r"initial\.theta"):
        coinroll.simulate(TOY, overrides=["initial.theta=\"steep\""])


def test_simulate_takes_a_dict_a_path_or_the_default(tmp_path):
    scene = tmp_path / "toy.json"
    scene.write_text(json.dumps(TOY))
    from_dict, from_path = coinroll.simulate(TOY), coinroll.simulate(scene)
    assert from_dict.rows == 51 and from_dict["t"][-1] == 0.5
    assert all(np.array_equal(from_dict[name], from_path[name]) for name in from_dict)
    assert coinroll.simulate(str(scene), sample_dt=0.1).rows == 6
    assert coinroll.simulate(None, overrides=["duration=0.2"]).rows == 21
    with pytest.raises(KeyError, match="energy"):
        from_dict["energie"]


def test_a_run_that_stops_early_says_how():
    run = coinroll.simulate(EXAMPLES / "skid_and_spin.json")
    assert run.end_event == "face-down"
    assert 6 < run.end_time < 6.5 and run["t"][-1] <= run.end_time
    assert run.end_description.startswith(f"face-down at t = {run.end_time:.9f} s")


def test_still_is_an_rgba_array():
    picture = coinroll.still(TOY, 0.25)
    assert picture.shape == (120, 160, 4) and picture.dtype == np.uint8
    assert (picture[..., 3] == 255).all()
    assert len(np.unique(picture.reshape(-1, 4), axis=0)) > 100  # a coin and its shading, not a blank
    with pytest.raises(ValueError, match="^t: must be within the scene's duration"):
        coinroll.still(TOY, 3)


def test_render_writes_the_clip_and_returns_its_path(tmp_path):
    clip = tmp_path / "toy.mp4"
    assert coinroll.render({**TOY, "duration": 0.2}, clip) == clip
    assert clip.stat().st_size > 1000
    frames = coinroll.render({**TOY, "duration": 0.1}, str(tmp_path / "f_%03d.png"))
    assert frames == str(tmp_path / "f_%03d.png")
    assert (tmp_path / "f_000.png").exists()


def test_steady_is_what_the_command_prints(run_cli):
    printed = run_cli("steady", "--kind", "circle", "--theta", 20, "--omega-Z", 10)
    assert printed.returncode == 0, printed.stderr
    state = coinroll.steady(kind="circle", theta=20, omega_Z=10)
    K = float(re.search(r"K = (\S+) 1/s\^2", printed.stdout)[1])
    assert math.isclose(state["K"], K, rel_tol=1e-8)
    assert state["stability"] == "stable" and "STABLE" in printed.stdout
    omega_c = float(re.search(r"omega_c = (\S+) rad/s", printed.stdout)[1])
    assert math.isclose(state["critical_spin"], omega_c, rel_tol=1e-5)
    initial = json.loads("{" + re.search(r'"initial": \{(.*)\}', printed.stdout)[1] + "}")
    assert all(math.isclose(state["initial"][key], value, rel_tol=1e-11, abs_tol=1e-12) for key, value in initial.items())

    assert coinroll.steady(EXAMPLES / "steady_circle.json") == state  # the same state from the scene's initial
    straight = coinroll.steady(kind="straight", omega_Z=6)
    assert straight["stability"] == "unstable" and straight["K"] < 0 and math.isinf(straight["contact_radius"])
    cornered = coinroll.steady(kind="spin-in-place", theta=60, overrides=["coin.thickness=0.013", "coin.edge_radius=0.0016"])
    assert cornered["critical_spin"] is None
    with pytest.raises(ValueError, match="initial"):
        coinroll.steady(TOY)
    with pytest.raises(ValueError, match="give kind"):
        coinroll.steady(theta=20)


def test_sweep_gives_the_commands_table(tmp_path, run_cli):
    grid = {"initial.theta": "10:40:4", "initial.omega_Z": [8, 12]}
    table = coinroll.sweep(TOY, grid, threads=2)
    scene = tmp_path / "toy.json"
    scene.write_text(json.dumps(TOY))
    out = tmp_path / "sweep.csv"
    cli = run_cli("sweep", scene, "--grid", "initial.theta=10:40:4", "--grid", "initial.omega_Z=8,12", "-o", out, "--quiet")
    assert cli.returncode == 0, cli.stderr
    rows = list(csv.DictReader(out.open()))
    assert table.columns == ["point", "initial.theta", "initial.omega_Z", "end", "t_end", "theta_min", "theta_max",
                             "energy_start", "energy_end", "theta_end"]
    assert table.rows == len(rows) == table.grid_points == 8
    assert list(table["end"]) == [row["end"] for row in rows]
    for name in table.columns:
        if name != "end":
            assert table[name].dtype == np.float64
            assert np.array_equal(table[name], [float(row[name]) for row in rows]), name
    assert table.digest == rows[0]["sweep"]
    assert coinroll.sweep(TOY, ["initial.theta=10:40:4", "initial.omega_Z=8,12"]).digest == table.digest


def test_sweep_refuses_a_misnamed_key_and_marks_failed_points():
    with pytest.raises(ValueError, match="initial.thta: not a scene field"):
        coinroll.sweep(TOY, {"initial.thta": "10:40:4"})
    # The command's summary counts failed points; the module warns, naming how many and the first.
    with pytest.warns(RuntimeWarning, match=r"sweep: 1 of 2 points failed \(first: error: .*coin.radius"):
        failing = coinroll.sweep(TOY, {"coin.radius": [0.03, -1]})
    assert failing["end"][0] in ("duration", "coin-flat") and failing["end"][1].startswith("error: ")
    assert "coin.radius" in failing["end"][1] and np.isnan(failing["t_end"][1])


def interrupt_after(seconds):
    """Sends this process SIGINT, as Ctrl-C does, from a thread; returns the time it did."""
    sent = {}

    def send():
        time.sleep(seconds)
        sent["at"] = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)
    threading.Thread(target=send, daemon=True).start()
    return sent


def test_ctrl_c_stops_a_long_render_and_leaves_no_file(tmp_path):
    long_clip = {**TOY, "duration": 600, "render": {"width": 320, "height": 240}}
    sent = interrupt_after(1.0)
    with pytest.raises(KeyboardInterrupt):
        coinroll.render(long_clip, tmp_path / "long.mp4")
    assert time.monotonic() - sent["at"] < 2.0  # a frame or two and the encoder's teardown, on a loaded machine
    assert os.listdir(tmp_path) == []


def test_ctrl_c_stops_a_long_sweep(tmp_path):
    sent = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        coinroll.sweep({**TOY, "duration": 60}, {"initial.theta": "5:40:1000"}, threads=1)
    assert time.monotonic() - sent["at"] < 2.0
    assert coinroll.simulate(TOY).rows == 51  # the module works on after an interruption


def test_ctrl_c_during_simulate_comes_when_it_returns():
    interrupt_after(0.1)
    with pytest.raises(KeyboardInterrupt):
        rows_of_toy_run(2000)
        time.sleep(10)  # Python's own check for signals, which the run did not cut short


def test_python_threads_run_while_simulating():
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)
    counter = threading.Thread(target=count)
    counter.start()
    try:
        started = time.monotonic()
        run = coinroll.simulate({**TOY, "duration": 2000})
        finished = time.monotonic()
    finally:
        stop.set()
        counter.join()
    assert run.rows == 200001
    during = [t for t in ticks if started < t < finished]
    # With the GIL held for the whole call the counter could not tick at all in between; a loaded
    # machine slows it, so a few ticks are proof enough.
    assert finished - started > 0.2 and len(during) >= 10


def rows_of_toy_run(duration):
    return coinroll.simulate({**TOY, "duration": duration}).rows


def test_calls_from_threads_at_once_and_from_forked_processes():
    rows = {}
    callers = [threading.Thread(target=lambda i=i: rows.update({i: rows_of_toy_run(100 + i)})) for i in range(3)]
    for caller in callers:
        caller.start()
    for caller in callers:
        caller.join()
    assert rows == {0: 10001, 1: 10101, 2: 10201}
    # multiprocessing's fork copies the module but none of its threads.
    with multiprocessing.get_context("fork").Pool(2) as children:
        assert children.map(rows_of_toy_run, [0.5, 1.0, 1.5]) == [51, 101, 151]
