#!/usr/bin/python3
"""Source lines stay readable: no line of the C++ sources (src/, include/, tests/, bench/, python/)
is longer than .clang-format's ColumnLimit, counted in characters. `clang-format -i --lines=N:N
FILE` rewraps one in the code's own style.

    check_line_length.py [SOURCE_DIR]
"""
import pathlib
import re
import subprocess
import sys


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2])
    limit = int(re.search(r"^ColumnLimit:\s*(\d+)", (root / ".clang-format").read_text(), re.M).group(1))
    files = subprocess.run(["git", "-C", str(root), "ls-files", "src", "include", "tests", "bench", "python"],
                           capture_output=True, text=True, check=True).stdout.split()
    long_lines = []
    for name in files:
        if not name.endswith((".cpp", ".h")):
            continue
        for number, line in enumerate((root / name).read_text(encoding="utf-8").split("\n"), 1):
            if len(line) > limit:
                long_lines.append(f"{name}:{number}: {len(line)} characters")
    for entry in long_lines:
        print(entry)
    checked = sum(name.endswith((".cpp", ".h")) for name in files)
    print(f"check_line_length.py: {checked} files, {len(long_lines)} lines over {limit} characters")
    return 1 if long_lines else 0


if __name__ == "__main__":
    sys.exit(main())
