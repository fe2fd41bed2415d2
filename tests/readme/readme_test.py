#!/usr/bin/python3
"""The README is tested (the docs tier, docs/quality.md "Tests and CI"): every command it shows
runs, or is exempted below by name with a reason; the synopsis names only options the
program's --help knows; the Python session is run as a doctest; and the numbers listed in CLAIMS
are computed from the program's own output and must be the ones the README quotes.

    tests/readme/readme_test.py --binary build/coinroll [--python-dir build/python] [--list]

A command is a line of a ```sh block, an indented line that starts like a command
(`build/coinroll`, `/usr/bin/python3`, `tools/`, `cmake`, ...), or an inline code span that does
(`coinroll steady --kind circle ...`; a span of a bare command name, `coinroll simulate`, only
names it). `a && b` lines are split. Each runs with bash in a scratch directory holding links to
the build, the examples and tools, with `coinroll` on PATH; it must exit 0 within its timeout.
"""

import argparse
import doctest
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
COMMAND_START = re.compile(
    r"^(\$ )?(build/coinroll|coinroll |tools/|/usr/bin/python3 |python3 |cmake|ctest|c\+\+ |podman |PYTHONPATH=|COINROLL_\w+=)")
TIMEOUT_SECONDS = 600

# Commands not run here, each with the reason; matched as regular expressions from the start.
EXEMPT = [
    (r"tools/setup\.sh", "installs Debian packages as root; CI's .ci/run runs it on a fresh machine"),
    (r"tools/test\.sh", "runs the whole suite, this test included"),
    (r"cmake -B build|cmake --build build", "the build this test runs in"),
    (r"cmake --install", "tests/install/install_test.sh (ctest install_and_consume) installs into a temporary prefix"),
    (r"c\+\+ -o app", "install_and_consume builds a consumer with CMake and with pkg-config"),
    (r"podman build", "needs podman and a network; tools/container_steps.sh is the same steps"),
    (r"build/coinroll render examples/euler_disk\.json",
     "about 30 minutes of CPU (8298 frames); rim_cli_test renders its landing and hold, the strobe command below its last second"),
    (r"(/usr/bin/)?python3 tools/(make_gallery|plot_\w+)\.py|tools/plot_\w+\.py",
     "draws a figure in docs/: tools/make_figures.sh runs them all, checked by ctest figures_reproducible"),
    (r"tools/(check_\w+)\.py", "ctest sympy_* runs each derivation check"),
    (r"tools/make_coin_face\.py", "writes assets/coin_face.png; render_test's embedded-asset test checks the binary's copy against the file"),
    (r"tools/(mutation_check\.py|sanitize\.sh|fuzz\.sh)", "CI stages of their own (sanitizers, fuzzing) or 50 minutes (mutants)"),
    (r"(COINROLL_\w+=\S+ )*ctest", "ctest inside ctest; these are the suite's own runs"),
    (r"COINROLL_UPDATE_GOLDEN=1", "rewrites the goldens"),
    (r"PYTHONPATH=build/python python3 examples/notebook\.py", "ctest python_notebook runs it"),
    (r"PYTHONPATH=build/python python3$", "starts the interactive session below, which runs as a doctest"),
    (r"COINROLL_GL=egl-device", "needs a GPU"),
    (r"tools/build_page\.sh", "builds the WebAssembly core and the page: ctest's wasm_core_build and web_page_build make the same files"),
    (r"build/coinroll export ", "needs the built page; web_page_browser exports a scene and opens the page in Chromium"),
    (r"build/coinroll compare golden\.png new\.png", "needs two pictures of the user's; compare_cli_test compares stills the program draws"),
]

# The README is the front page; its chapters moved to these pages and are held to the same rule.
PAGES = ["README.md", "docs/usage.md", "docs/physics.md", "docs/quality.md"]


@dataclass
class Command:
    line: int
    text: str


SUBCOMMANDS = {"render", "still", "simulate", "steady", "sweep", "sweep-merge", "compare", "schema", "export"}


def shown_commands(readme: str) -> list[Command]:
    commands: list[Command] = []
    prose: list[str] = []  # the README with blocks blanked, where inline spans are looked for
    fence = None
    pending = ""
    for number, raw in enumerate(readme.split("\n"), 1):
        prose.append("")
        if raw.startswith("```"):
            fence = None if fence is not None else raw[3:].strip()
            continue
        if fence is not None and fence != "sh":
            continue
        text = raw.strip()
        if fence == "sh" or (raw.startswith("    ") and (pending or COMMAND_START.match(text))):
            text = pending + re.sub(r"\s+#.*$", "", text).removeprefix("$ ")
            if text.endswith("\\"):
                pending = text[:-1].rstrip() + " "
                continue
            pending = ""
            if text:
                commands += [Command(number, part.strip()) for part in text.split("&&")]
            continue
        prose[-1] = raw
    joined = "\n".join(prose)
    for match in re.finditer(r"`([^`]+)`", joined):
        span = " ".join(match.group(1).split())
        words = span.split()
        if not COMMAND_START.match(span) or span.startswith("coinroll:") or len(words) < 3:
            continue  # names a command, a file or an output line, or quotes what the program prints
        if words[0] == "coinroll" and words[1] not in SUBCOMMANDS | {"--version", "--help"}:
            continue  # "coinroll 0.1.0 (git ...)": what --version prints
        commands.append(Command(joined.count("\n", 0, match.start()) + 1, span))
    return commands


def is_synopsis(command: str) -> bool:
    """A usage line or a fragment naming options: metasyntax ([optional], a|b, CAPITAL
    placeholders), a flag without its value, or `compare` without its two pictures."""
    if not command.startswith("coinroll "):
        return False
    return bool(re.search(r"\[|\]|\.\.\.|\b[A-Z][A-Z0-9_]*\.(json|csv|png|mp4)\b|, coinroll| -o$", command)) or (
        command.startswith("coinroll compare") and command.count(".png") < 2)


def exemption(command: str) -> str | None:
    for pattern, reason in EXEMPT:
        if re.match(pattern, command):
            return reason
    return None


def scratch_directory(binary: Path) -> Path:
    work = Path(tempfile.mkdtemp(prefix="coinroll_readme_"))
    (work / "build").symlink_to(binary.resolve().parent)
    for name in ("examples", "tools", "tests"):
        (work / name).symlink_to(SOURCE / name)
    bin_dir = work / ".bin"
    bin_dir.mkdir()
    (bin_dir / "coinroll").symlink_to(binary.resolve())
    return work


def run_shell(command: str, work: Path, timeout: float = TIMEOUT_SECONDS) -> subprocess.CompletedProcess:
    env = dict(os.environ, PATH=f"{work / '.bin'}:{os.environ['PATH']}")
    return subprocess.run(["bash", "-c", command], cwd=work, env=env, capture_output=True, text=True, timeout=timeout)


def check_synopsis(command: str, work: Path) -> list[str]:
    """Every --option of a usage line is in its command's --help."""
    words = command.split()
    sub = words[1] if len(words) > 1 and not words[1].startswith("-") else None
    help_text = run_shell(f"coinroll {sub} --help" if sub else "coinroll --help", work).stdout
    missing = [o for o in re.findall(r"(--[a-zA-Z][\w-]*)", command) if o not in help_text]
    return [f"{o} is not in `coinroll {sub or ''} --help`" for o in missing]


# Numbers the README quotes, each computed from the program: (what, function of the scratch
# directory returning the exact text the README must contain).
def steady_circle_lines(work: Path) -> str:
    out = run_shell("coinroll steady --kind circle --theta 20 --omega-Z 10", work).stdout
    return "\n".join(out.rstrip("\n").split("\n")[-2:])


def critical_spin(thickness: str):
    def claim(work: Path) -> str:
        extra = f" --set coin.thickness={thickness}" if thickness else ""
        out = run_shell(f"coinroll steady --kind straight --omega-Z 12{extra}", work).stdout
        rate = re.search(r"omega_c = (\S+) rad/s", out)
        if rate is None:
            raise AssertionError(f"no critical spin in `coinroll steady` output:\n{out}")
        return f"critical spin {float(rate.group(1)):.3g} rad/s"
    return claim


def csv_rows(path: Path) -> tuple[list[str], list[list[float]]]:
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    return header, [[float(v) for v in line.split(",")] for line in lines[1:]]


def falling_flat_energy(work: Path) -> str:
    run_shell("coinroll simulate examples/falling_flat.json --csv ff.csv", work)
    header, rows = csv_rows(work / "ff.csv")
    e = [row[header.index("energy")] for row in rows]
    drift = max(abs(x - e[0]) for x in e) / abs(e[0])
    return f"energy held to {drift:.1e}".replace(".0e", "e")


def skid_rows(work: Path) -> str:
    run_shell("coinroll simulate examples/skid_and_spin.json --csv skid.csv", work)
    header, rows = csv_rows(work / "skid.csv")
    sliding = sum(1 for row in rows if row[header.index("sliding")] > 0.5)
    return f"{sliding} of its {len(rows)} rows sliding"


def euler_disk_end(work: Path) -> str:
    out = run_shell("coinroll simulate examples/euler_disk.json --csv ed.csv", work).stderr
    end = float(re.search(r"face-down at t = (\S+) s", out).group(1))
    slides = re.findall(r"slides at t = (\S+) s", out)
    return f"slips {len(slides)} times from {float(slides[0]):.1f} s and spins down for {end:.1f} s until it lies on its face"


def euler_disk_top_rate(work: Path) -> str:
    """The contact rate the README gives as the toy's fastest before its landing."""
    if not (work / "ed.csv").exists():
        euler_disk_end(work)
    header, rows = csv_rows(work / "ed.csv")
    # phi is continuous in the CSV, so its differences over a row give the contact point's rate.
    phi = [row[header.index("phi")] for row in rows]
    t = [row[0] for row in rows]
    rates = [abs(phi[k + 1] - phi[k]) / (t[k + 1] - t[k]) / (2 * math.pi) for k in range(len(t) - 1)]
    return f"from {rates[0]:.1f} to {max(rates):.0f} Hz"


def test_count(work: Path) -> str:
    listing = subprocess.run(["ctest", "-N", "--test-dir", str((work / "build").resolve())], capture_output=True, text=True).stdout
    total = int(re.search(r"Total Tests: (\d+)", listing).group(1))
    # Rounded down to a multiple of 50: still true when a change adds a test, without an edit of the
    # README for each one.
    return f"(over {total // 50 * 50} tests,"


def bad_input_count(work: Path) -> str:
    sys.path.insert(0, str(SOURCE / "tests" / "cli"))
    import bad_inputs
    return f"lists {len(bad_inputs.CASES)} cases"


def evaluations(command: str, work: Path) -> int:
    out = run_shell(command, work).stderr
    return int(re.search(r"(\d+) right-hand-side evaluations", out).group(1))


def spaced(n: int) -> str:
    return f"{n:,}".replace(",", " ")


def default_scene_evaluations(work: Path) -> str:
    dop853 = evaluations("coinroll simulate --set duration=2 --csv a.csv", work)
    dopri5 = evaluations("coinroll simulate --set duration=2 --set solver.method=dopri5 --csv b.csv", work)
    return f"with {spaced(dop853)} right-hand-side evaluations instead of {spaced(dopri5)}"


def rolling_spin_down_evaluations(work: Path) -> str:
    n = evaluations("coinroll simulate examples/euler_disk.json --set sliding=false --csv rolling.csv", work)
    return f"({spaced(round(n, -3))} right-hand-side evaluations)"


CLAIMS = [
    ("DOP853 against DOPRI5 on the default scene", default_scene_evaluations),
    ("the rolling spin-down's evaluations", rolling_spin_down_evaluations),
    ("the test count", test_count),
    ("the bad-input case count", bad_input_count),
    ("steady's example, its last two lines", steady_circle_lines),
    ("the thin disk's critical spin", critical_spin("")),
    ("the toy's critical spin", critical_spin("0.013")),
    ("falling_flat's energy", falling_flat_energy),
    ("skid_and_spin's sliding rows", skid_rows),
    ("the Euler's disk's spin-down time", euler_disk_end),
    ("the Euler's disk's contact rate", euler_disk_top_rate),
]


def run_doctest(readme: str, work: Path, python_dir: Path) -> list[str]:
    """The ```pycon session, run as a doctest in the scratch directory."""
    blocks = re.findall(r"```pycon\n(.*?)```", readme, re.S)
    if not blocks:
        return ["no ```pycon session found"]
    sys.path.insert(0, str(python_dir))
    failures: list[str] = []
    cwd = os.getcwd()
    os.chdir(work)
    try:
        for block in blocks:
            parser = doctest.DocTestParser()
            test = parser.get_doctest(block, {}, "README pycon", "README.md", 0)
            runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
            output: list[str] = []
            runner.run(test, out=output.append)
            if runner.failures:
                failures.append("".join(output))
    finally:
        os.chdir(cwd)
    return failures


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", type=Path, required=True)
    parser.add_argument("--python-dir", type=Path, help="where `import coinroll` is built (skip the doctest without it)")
    parser.add_argument("--list", action="store_true", help="list each command and what is done with it, run nothing")
    args = parser.parse_args()
    texts = [(SOURCE / page).read_text() for page in PAGES]
    readme = "\n".join(texts)
    starts = []  # (first line in `readme`, page)
    line = 1
    for page, text in zip(PAGES, texts):
        starts.append((line, page))
        line += text.count("\n") + 1

    def where(number: int) -> str:
        first, page = max(start for start in starts if start[0] <= number)
        return f"{page}:{number - first + 1}"

    commands = shown_commands(readme)
    work = scratch_directory(args.binary)
    failures: list[str] = []
    counts = {"run": 0, "synopsis": 0, "exempt": 0}
    started = time.monotonic()
    try:
        for command in commands:
            if is_synopsis(command.text):
                counts["synopsis"] += 1
                if args.list:
                    print(f"{where(command.line)}: synopsis  {command.text}")
                    continue
                failures += [f"{where(command.line)}: {f}" for f in check_synopsis(command.text, work)]
                continue
            reason = exemption(command.text)
            if reason:
                counts["exempt"] += 1
                print(f"{where(command.line)}: exempt    {command.text}\n    ({reason})")
                continue
            counts["run"] += 1
            if args.list:
                print(f"{where(command.line)}: run       {command.text}")
                continue
            begun = time.monotonic()
            try:
                result = run_shell(command.text, work)
            except subprocess.TimeoutExpired:
                failures.append(f"{where(command.line)}: `{command.text}` took more than {TIMEOUT_SECONDS} s")
                continue
            print(f"{where(command.line)}: ran in {time.monotonic() - begun:5.1f} s: {command.text}", flush=True)
            if result.returncode != 0:
                failures.append(f"{where(command.line)}: `{command.text}` exited {result.returncode}:\n{result.stderr[-2000:]}")
        if args.list:
            return 0
        for what, claim in CLAIMS:
            expected = claim(work)
            flowing = " ".join(readme.split())  # a quote may wrap onto the next line
            missing = [line for line in expected.split("\n") if " ".join(line.split()) not in flowing]
            if missing:
                failures.append(f"{what}: the program gives `{expected}`, which the README does not say")
            else:
                print(f"claim ok: {what}: {expected!r}")
        if args.python_dir:
            failures += run_doctest(readme, work, args.python_dir)
    finally:
        shutil.rmtree(work)
    print(f"{len(commands)} commands shown: {counts['run']} run, {counts['synopsis']} synopsis lines checked against --help, "
          f"{counts['exempt']} exempt; {len(CLAIMS)} quoted numbers recomputed; {time.monotonic() - started:.0f} s")
    for failure in failures:
        print("FAIL:", failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
