"""Shared by the Python module's tests: the command they compare with, and small scenes.

ctest runs them with PYTHONPATH=build/python and COINROLL_BINARY=build/coinroll; by hand:
    PYTHONPATH=build/python COINROLL_BINARY=build/coinroll python3 -m pytest tests/python
"""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent.parent
EXAMPLES = REPO / "examples"

# The README's toy coin, small enough that a still or a short clip takes a fraction of a second.
TOY = {"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4}, "initial": {"theta": 10, "omega_Z": 12},
       "duration": 0.5, "render": {"width": 160, "height": 120}}


@pytest.fixture(scope="session")
def binary():
    return os.environ.get("COINROLL_BINARY", str(REPO / "build" / "coinroll"))


@pytest.fixture
def run_cli(binary):
    """Runs `coinroll ARGS...`; returns the CompletedProcess (text), whatever its exit code."""
    def run(*args):
        return subprocess.run([binary, *map(str, args)], capture_output=True, text=True, timeout=600)
    return run
