#!/usr/bin/python3
"""The figures in docs/ are the program's (docs/usage.md "Examples"): tools/make_figures.sh --quick
draws them into a scratch folder and each must equal the one in docs/, by `coinroll compare`'s
golden rule (exact; with COINROLL_GOLDEN_TOLERANT=1, for another CPU, the tolerance of
docs/snapshot_testing.md).

    tests/readme/figures_test.py --binary build/coinroll
"""

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", type=Path, required=True)
    args = parser.parse_args()
    binary = str(args.binary.resolve())
    tolerance = (["--max-differing-fraction", "0.001", "--min-psnr", "60"]
                 if os.environ.get("COINROLL_GOLDEN_TOLERANT") == "1" else [])
    with tempfile.TemporaryDirectory(prefix="coinroll_figures_") as scratch:
        made = subprocess.run([str(SOURCE / "tools" / "make_figures.sh"), "--quick", "--coinroll", binary, scratch],
                              capture_output=True, text=True)
        if made.returncode != 0:
            print(f"tools/make_figures.sh failed ({made.returncode}):\n{made.stderr}", file=sys.stderr)
            return 1
        figures = sorted(Path(scratch).glob("*.png"))
        if not figures:
            print("tools/make_figures.sh made no PNG", file=sys.stderr)
            return 1
        failures = 0
        for figure in figures:
            committed = SOURCE / "docs" / figure.name
            verdict = subprocess.run([binary, "compare", str(committed), str(figure), *tolerance],
                                     capture_output=True, text=True)
            print(f"{figure.name}: {(verdict.stdout or verdict.stderr).strip()}")
            if verdict.returncode != 0:
                failures += 1
        print(f"{len(figures)} figures remade, {failures} differ from docs/ "
              "(remake them with tools/make_figures.sh and look at them before committing)")
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
