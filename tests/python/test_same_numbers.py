"""coinroll.simulate gives the doubles of `coinroll simulate`'s CSV, for every example scene.

The CSV prints every double with %.17g (pipeline/trajectory_csv.cpp), which reads back to the
same double, so the comparison is exact: float(text) == value, bit for bit, every cell.
"""

import json
import re

import numpy as np
import pytest

import coinroll
from conftest import EXAMPLES

@pytest.mark.parametrize("scene", sorted(EXAMPLES.glob("*.json")), ids=lambda path: path.stem)
def test_simulate_equals_the_commands_csv(scene, tmp_path, run_cli):
    csv = tmp_path / "run.csv"
    cli = run_cli("simulate", scene, "--csv", csv)
    assert cli.returncode == 0, cli.stderr

    run = coinroll.simulate(scene, sample_dt=0.01)

    header, *rows = csv.read_text().splitlines()
    assert run.columns == header.split(",")
    printed = np.array([[float(field) for field in row.split(",")] for row in rows])
    for i, name in enumerate(run.columns):
        assert run[name].dtype == np.float64
        assert np.array_equal(run[name], printed[:, i]), name
    stopped = re.search(r"stopped early: (\S+) at t = ([0-9.]+) s", cli.stderr)
    if stopped:
        assert run.end_event == stopped[1]
        assert f"{run.end_time:.9f}" == stopped[2]
        assert cli.stderr.count(run.end_description) == 1
    else:
        duration = json.loads(scene.read_text())["duration"]
        assert (run.end_event, run.end_time, run.end_description) == ("duration", duration, "")
