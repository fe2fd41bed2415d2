#!/usr/bin/python3
"""Every C++ source (src/, include/, tests/, bench/, python/) is laid out as .clang-format says, by
Debian 12's clang-format-14: another version lays the same code out otherwise, so no other is taken.
Reformat a file with `clang-format-14 -i FILE`; a table kept as it reads sits between
`// clang-format off` and `// clang-format on`. Exits 77 (ctest's skip) without clang-format-14.

    check_format.py [SOURCE_DIR]
"""
import pathlib
import shutil
import subprocess
import sys

FORMATTER = "clang-format-14"


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2])
    formatter = shutil.which(FORMATTER)
    if formatter is None:
        print(f"SKIP: {FORMATTER} not found (tools/setup.sh installs it)")
        return 77
    files = [name for name in subprocess.run(["git", "-C", str(root), "ls-files", "src", "include", "tests", "bench",
                                               "python"], capture_output=True, text=True, check=True).stdout.split()
             if name.endswith((".cpp", ".h"))]
    unformatted = []
    for name in files:
        laid_out = subprocess.run([formatter, "--style=file", str(root / name)], capture_output=True, text=True,
                                  check=True, cwd=root).stdout
        if laid_out != (root / name).read_text(encoding="utf-8"):
            unformatted.append(name)
    for name in unformatted:
        print(f"{name}: not as {FORMATTER} lays it out; run `{FORMATTER} -i {name}`")
    print(f"check_format.py: {len(files)} files, {len(unformatted)} not formatted")
    return 1 if unformatted else 0


if __name__ == "__main__":
    sys.exit(main())
