#!/usr/bin/python3
"""What calling coinroll.simulate from Python costs over the C++ call it wraps.

A 10 s run of the README's toy coin (radius 3.75 cm, 0.4 kg, tilted 10 deg, spinning at 12
rad/s; 1001 rows at the default 0.01 s), timed RUNS times each way, alternating one call of each
in this process so both see the same load and caches: coinroll::simulate through
build/bench/libapi_simulate_timer.so (ctypes; the scene is loaded outside its timing), and
coinroll.simulate (the whole call: the scene dict to JSON, the worker thread, the numpy arrays).
Prints a table of both, the ratio of the medians and the median of the paired ratios.

Run: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--runs 201] [--build build]
"""

import argparse
import ctypes
import json
import statistics
import tempfile
import time
from pathlib import Path

import coinroll

TOY_10S = {"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4}, "initial": {"theta": 10, "omega_Z": 12},
           "duration": 10}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=201)
    parser.add_argument("--build", default=str(Path(__file__).resolve().parent.parent / "build"))
    args = parser.parse_args()
    timer = ctypes.CDLL(str(Path(args.build) / "bench" / "libapi_simulate_timer.so"))
    timer.coinroll_simulate_seconds.restype = ctypes.c_double
    timer.coinroll_simulate_seconds.argtypes = [ctypes.c_char_p, ctypes.c_double]

    with tempfile.TemporaryDirectory() as scratch:
        scene = Path(scratch) / "toy_10s.json"
        scene.write_text(json.dumps(TOY_10S))
        # Untimed: the first calls pay for page faults and lazy binding.
        rows = coinroll.simulate(TOY_10S).rows
        timer.coinroll_simulate_seconds(bytes(scene), 0.01)
        cpp, python = [], []
        for _ in range(args.runs):
            seconds = timer.coinroll_simulate_seconds(bytes(scene), 0.01)
            assert seconds > 0, "coinroll::simulate threw"
            cpp.append(seconds)
            start = time.perf_counter()
            coinroll.simulate(TOY_10S)
            python.append(time.perf_counter() - start)

    print(f"coinroll.simulate from Python vs coinroll::simulate in C++: 10 s toy run, {rows} rows, "
          f"{args.runs} runs each, alternating")
    print(f"{'':<26}{'median ms':>10}{'min ms':>10}{'max ms':>10}")
    for name, times in (("C++ coinroll::simulate", cpp), ("Python coinroll.simulate", python)):
        print(f"{name:<26}{statistics.median(times) * 1e3:>10.3f}{min(times) * 1e3:>10.3f}{max(times) * 1e3:>10.3f}")
    ratio = statistics.median(python) / statistics.median(cpp)
    paired = statistics.median(p / c for p, c in zip(python, cpp))
    print(f"ratio of medians (Python / C++): {ratio:.4f} ({(ratio - 1) * 100:+.2f} %); "
          f"median of paired ratios: {paired:.4f}")


if __name__ == "__main__":
    main()
