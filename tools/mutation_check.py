#!/usr/bin/python3
"""Mutation check (docs/mutation_report.md): do the tests notice small, realistic bugs?

Applies each mutation of the MUTATIONS table below, one at a time, to a separate git worktree of
HEAD (never to the live tree), rebuilds, runs ctest, and reports which mutants the tests kill,
which survive and which did not build. A mutant is one exact snippet replaced once in one file;
the snippet must occur exactly once, so the table fails loudly when the source drifts.

    tools/mutation_check.py --list                      # the table, with a check of every snippet
    tools/mutation_check.py --sync-from /work/main      # all mutants, against the live tests
    tools/mutation_check.py --only 3,17-20 --report r.md --keep-worktree

Score = killed / built. Progress goes to stderr (and --log FILE), the markdown table to stdout
(and --report FILE). The worktree (default /tmp/coinroll_mutants) is removed at the end unless
--keep-worktree; a kept one is reused by the next run, so only the mutated files rebuild.
"""

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


@dataclass
class Mutation:
    file: str         # path from the repository root
    original: str     # exact snippet; must occur exactly once in the file
    replacement: str
    kind: str         # sign-flip, swap-args, wrong-variable, drop-term, off-by-one, skip-check, wrong-comparison
    description: str
    # A test binary that tests the mutated unit directly. A header mutant rebuilds nearly the whole
    # project (8 minutes on 2 cores); this one is built and run alone first, and a confirmed failure
    # there is a kill. Only when it passes does the full build and suite run.
    first: str = ""


M = Mutation
MUTATIONS = [
    # ---------------------------------------------------------------- src/physics (14)
    M("src/physics/dynamics.cpp",
      "- m.I_X * omega_Y * omega_Y * tanTheta", "+ m.I_X * omega_Y * omega_Y * tanTheta",
      "sign-flip", "eq. (14): sign of the I_X omega_Y^2 tan(theta) term"),
    M("src/physics/dynamics.cpp",
      "(m.I_Z / m.I_X) * omega_Z * omega_X", "(m.I_X / m.I_Z) * omega_Z * omega_X",
      "swap-args", "eq. (15): moment ratio I_Z / I_X inverted"),
    M("src/physics/dynamics.cpp",
      "y[kOmega_Z] + (sinTheta / cosTheta) * y[kOmega_Y];", "y[kOmega_Z] - (sinTheta / cosTheta) * y[kOmega_Y];",
      "sign-flip", "eq. (19): psi-dot = omega_Z - tan(theta) omega_Y"),
    M("src/physics/dynamics.cpp",
      "a * (-omega_Z * cosPhi + omega_X * cosTheta * sinPhi)", "a * (-omega_Z * sinPhi + omega_X * cosTheta * cosPhi)",
      "wrong-variable", "centre-of-mass v_x: sin(phi) and cos(phi) exchanged"),
    M("src/physics/dynamics.cpp",
      "ideal.y() += torqueXYZ.y() / m.I_X;", "ideal.y() += torqueXYZ.y() / (m.I_X + Ma2);",
      "wrong-variable", "couple: e_Y entry of the mass matrix given the M a^2 shift"),
    M("src/physics/dynamics.cpp",
      "for (int pass = 0; pass < 2; ++pass)", "for (int pass = 0; pass < 1; ++pass)",
      "off-by-one", "effects: one pass for the N-dependent couples instead of two"),
    M("src/physics/observables.cpp",
      "0.5 * (m.I_X * (wX2 + wY2) + m.I_Z * wZ2)", "0.5 * (m.I_X * (wX2 + wY2))",
      "drop-term", "energy: the spin's I_Z omega_Z^2 / 2 dropped"),
    M("src/physics/observables.cpp",
      "ct * sp, -st, ct * cp;", "ct * sp, st, ct * cp;",
      "sign-flip", "R(theta, phi): sign of e_Z's vertical component"),
    M("src/physics/steady.cpp",
      "const double plusSqrtRoot = (B >= 0) ? rootFromC : rootFromQ;",
      "const double plusSqrtRoot = (B > 0) ? rootFromC : rootFromQ;",
      "wrong-comparison", "steady circle: B = 0 (omega_Z = 0) picks the wrong root for f+"),
    M("src/physics/steady.cpp",
      "if (!(std::abs(theta) < std::numbers::pi / 2))", "if (!(std::abs(theta) <= std::numbers::pi / 2))",
      "wrong-comparison", "steady states: theta = 90 deg accepted"),
    M("src/physics/validity.cpp",
      "(mu * f.reaction.N - f.reaction.F)", "(mu * f.reaction.N + f.reaction.F)",
      "sign-flip", "slip margin mu N + F"),
    M("src/physics/quaternion_dynamics.cpp",
      "naturalRate(model) * (1 - normSquared)", "naturalRate(model) * (normSquared - 1)",
      "sign-flip", "quaternion: the unit-norm restoring term pushes away"),
    M("src/physics/rolling_resistance.cpp",
      "if (!(k.N > 0)) return {};", "(void)0;",
      "skip-check", "rolling resistance: no-load check skipped"),
    M("src/physics/rolling_resistance.cpp",
      "couple / cosTheta", "couple * cosTheta",
      "wrong-variable", "rolling resistance: couple times cos(theta) instead of over it"),
    # ---------------------------------------------------------------- src/integrate (11)
    M("src/integrate/steppers.h",
      "const Vec<N> k4 = f(t + h, Vec<N>(y + h * k3));", "const Vec<N> k4 = f(t + h, Vec<N>(y + h * k2));",
      "wrong-variable", "RK4: fourth stage from k2 instead of k3"),
    M("src/integrate/steppers.h",
      "d.r4 = d.r2 - h * f1 - d.r3;", "d.r4 = d.r2 - h * f0 - d.r3;",
      "wrong-variable", "Hermite dense output: start slope used for the end"),
    M("src/integrate/steppers.h",
      "+ e6 * r.k6 + e7 * r.f1);", "+ e6 * r.k6);",
      "drop-term", "DOPRI5 error estimate: FSAL stage e7 k7 dropped"),
    M("src/integrate/dop853.h",
      "r.error3 = increment - bhh1 * k1 - bhh2 * r.k9 - bhh3 * r.k12;",
      "r.error3 = increment - bhh1 * k1 - bhh2 * r.k9;",
      "drop-term", "DOP853 3rd-order estimate: bhh3 k12 dropped"),
    M("src/integrate/trajectory.h",
      "return std::sqrt((error.cwiseQuotient(scale)).squaredNorm() / N);",
      "return std::sqrt((error.cwiseQuotient(scale)).squaredNorm());",
      "drop-term", "DOPRI5 error norm: RMS without the 1/N"),
    M("src/integrate/trajectory.h",
      "std::clamp(factor, 1 / c.maxFactor, 1 / c.minFactor)", "std::clamp(factor, 1 / c.minFactor, 1 / c.maxFactor)",
      "swap-args", "step control: clamp bounds swapped"),
    M("src/integrate/event_location.h",
      "if ((gc < 0) == (gb < 0)) {", "if ((gc < 0) != (gb < 0)) {",
      "wrong-comparison", "event root: keeps the wrong half of the bracket"),
    M("src/integrate/event_location.h",
      "if (side == -1) ga *= 0.5;", "",
      "drop-term", "event root: Illinois halving of the stale end dropped (plain regula falsi)"),
    M("src/integrate/trajectory.h",
      "(e.direction >= 0 && rising)", "(e.direction > 0 && rising)",
      "wrong-comparison", "events: direction 0 ignores rising crossings"),
    M("src/integrate/trajectory.h",
      "tRoot < earliestTerminal->t", "tRoot > earliestTerminal->t",
      "wrong-comparison", "events: the latest terminal root in a step wins"),
    M("src/integrate/trajectory.h",
      'if (!y_.allFinite()) throw std::invalid_argument("initial state has a non-finite component");', "",
      "skip-check", "non-finite initial state accepted"),
    # ---------------------------------------------------------------- src/video (10)
    M("src/video/encoder_sink.cpp",
      "if (&target == &video) packet->duration = 1;", "",
      "drop-term", "MP4: video packets without a duration (last frame lost from the length)"),
    M("src/video/encoder_sink.cpp",
      "if (x264.threads < 1 || x264.threads > kMaxX264Threads) {", "if (x264.threads < 1) {",
      "skip-check", "MP4 options: threads above the maximum accepted"),
    M("src/video/encoder_sink.cpp",
      "frame.width != options_.width || frame.height != options_.height ||", "frame.width != options_.width ||",
      "skip-check", "MP4 push: frame height not checked"),
    M("src/video/encoder_sink.cpp",
      "if (!encoder.pending.empty()) encoder.encodeAudioBlock(static_cast<int>(encoder.pending.size()));", "",
      "skip-check", "MP4 finish: the last, short audio block is never encoded"),
    M("src/video/encoder_sink.cpp",
      "picture.pts = framesPushed_;", "picture.pts = framesPushed_ + 1;",
      "off-by-one", "MP4: frame timestamps start at 1"),
    M("src/video/rgba_to_yuv.cpp",
      "setScalerColorDetails(*scaler, bt709, true, bt709, false,", "setScalerColorDetails(*scaler, bt709, false, bt709, false,",
      "swap-args", "RGBA to YUV: source taken as limited range"),
    M("src/video/png_sequence_sink.cpp",
      "if (parsed.minimumDigits < 1 || parsed.minimumDigits > kMaxDigits) {", "if (parsed.minimumDigits > kMaxDigits) {",
      "skip-check", "PNG pattern: width 0 (%00d) accepted"),
    M("src/video/png_sequence_sink.cpp",
      "      ++i;\n      continue;\n    }\n    return true;", "      continue;\n    }\n    return true;",
      "off-by-one", "sequence detection: '%%' escape not skipped"),
    M("src/video/async_sink.cpp",
      "queue_.size() < capacity_", "queue_.size() <= capacity_",
      "off-by-one", "async sink: queue holds capacity + 1 frames"),
    M("src/video/async_sink.cpp",
      "  {\n    std::lock_guard lock(mutex_);\n    rethrowWorkerError();\n  }\n  inner_->finish();",
      "  inner_->finish();",
      "skip-check", "async sink finish: the worker's error is not rethrown"),
    # ---------------------------------------------------------------- src/pipeline (11)
    M("src/pipeline/playback_clock.cpp",
      "std::floor(simulatedSeconds / timeScale * fps * (1 + 1e-12) + 1e-9)", "std::floor(simulatedSeconds / timeScale * fps)",
      "drop-term", "frame count: no rounding nudge"),
    M("src/pipeline/playback_clock.cpp",
      "fps * (1 + 1e-12) + 1e-9)", "fps + 1e-9)",
      "drop-term", "frame count: only the absolute nudge (fails for long clips)"),
    M("src/pipeline/playback_clock.cpp",
      "return k < frameCount(end, scene_.render.timeScale", "return k <= frameCount(end, scene_.render.timeScale",
      "off-by-one", "frame times: one frame too many after an early stop"),
    M("src/pipeline/playback_clock.cpp",
      "return std::min(render.timeScale, visible / rate);", "return std::max(render.timeScale, visible / rate);",
      "wrong-comparison", "time remap: speeds up instead of slowing down"),
    M("src/pipeline/sound_track.h",
      "static_cast<std::int64_t>(k) * video::kAudioSampleRate / fps_",
      "static_cast<std::int64_t>(k) * (video::kAudioSampleRate / fps_)",
      "wrong-grouping", "audio: samples per frame rounded before multiplying"),
    M("src/pipeline/sound_track.h",
      "if (k == 1) synth_.fadeIn(block_);", "if (k == 0) synth_.fadeIn(block_);",
      "off-by-one", "audio: the fade-in never applied"),
    M("src/pipeline/trajectory_samples.cpp",
      "std::floor(duration / sampleDt * (1 + 1e-9))", "std::floor(duration / sampleDt)",
      "drop-term", "CSV row count: no rounding nudge"),
    M("src/pipeline/singular_time.cpp",
      ".gamma = law.exponent,", ".gamma = -law.exponent,",
      "sign-flip", "singular time: exponent of the tilt with the wrong sign"),
    M("src/pipeline/trajectory_motion.h",
      "if (!hit || hit->t > duration_) return std::nullopt;", "if (!hit) return std::nullopt;",
      "skip-check", "events past the run's duration reported"),
    M("src/pipeline/coin_run.cpp",
      "constexpr double kUnwrapTurn = std::numbers::pi / 4;", "constexpr double kUnwrapTurn = std::numbers::pi * 4;",
      "wrong-constant", "quaternion run: phi/psi unwrapped every 2 turns instead of every 1/8"),
    M("src/pipeline/run_record.cpp",
      "if (++gridIndex_ > lastGrid_) gridDone_ = true;", "if (++gridIndex_ > lastGrid_ - 2) gridDone_ = true;",
      "off-by-one", "motion survey stops two samples early"),
]


def folder(m: Mutation) -> str:
    return "/".join(m.file.split("/")[:2])

for m in MUTATIONS:
    if m.file.startswith("src/integrate/"):
        m.first = "integrate_test"

# --------------------------------------------------------------------------- helpers

LOG = None


def log(message: str) -> None:
    line = time.strftime("%H:%M:%S ") + message
    print(line, file=sys.stderr, flush=True)
    if LOG:
        with open(LOG, "a") as f:
            f.write(line + "\n")


def run(cmd, cwd=None, timeout=None):
    """Runs cmd niced in its own process group; returns (returncode, combined output). Interrupted, it
    ends the whole group (make's and ctest's children included) before passing the interrupt on."""
    proc = subprocess.Popen(["nice", "-n", "10", *cmd], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, errors="replace", start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=timeout)
    except BaseException:
        try:
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait(timeout=10)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            os.killpg(proc.pid, signal.SIGKILL)
        raise
    return proc.returncode, out


def git(*args, cwd=REPO):
    return subprocess.run(["git", *args], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def parse_only(text: str, count: int):
    ids = set()
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        if "-" in part:
            a, b = part.split("-", 1)
            ids.update(range(int(a), int(b) + 1))
        else:
            ids.add(int(part))
    bad = [i for i in ids if not 1 <= i <= count]
    if bad:
        sys.exit(f"--only: no mutation {bad} (there are {count})")
    return sorted(ids)


SYNC_DIRS = ["src", "tests", "cmake", "tools", "shaders", "assets", "examples"]
SYNC_FILES = ["CMakeLists.txt"]


def mirror(source: Path, target: Path) -> int:
    """rsync -a --delete, by content: copies changed files (new mtime, so they rebuild), removes extra ones."""
    changed = 0
    if source.is_file():
        if not target.is_file() or target.read_bytes() != source.read_bytes():
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, target)
            changed += 1
        return changed
    if not source.is_dir():
        return 0
    target.mkdir(parents=True, exist_ok=True)
    wanted = set()
    for root, dirs, files in os.walk(source):
        dirs[:] = [d for d in dirs if d not in ("__pycache__",)]
        rel = Path(root).relative_to(source)
        (target / rel).mkdir(parents=True, exist_ok=True)
        for name in files:
            wanted.add(rel / name)
            changed += mirror(Path(root) / name, target / rel / name)
    for root, dirs, files in os.walk(target, topdown=False):
        rel = Path(root).relative_to(target)
        for name in files:
            if rel / name not in wanted and "__pycache__" not in (rel / name).parts:
                (target / rel / name).unlink()
                changed += 1
        if rel != Path(".") and not (source / rel).exists():
            shutil.rmtree(target / rel, ignore_errors=True)
    return changed


# --------------------------------------------------------------------------- the run

class Runner:
    def __init__(self, args):
        self.args = args
        self.work = Path(args.workdir).resolve()
        self.build = self.work / "_mutation_build"
        self.marker = self.work / ".mutation_in_progress"
        self.created = False

    def prepare_worktree(self):
        if (self.work / ".git").exists() and git("rev-parse", "--is-inside-work-tree", cwd=self.work).returncode == 0:
            log(f"reusing worktree {self.work}")
        else:
            if self.work.exists():
                sys.exit(f"{self.work} exists and is not a git worktree; choose another --workdir")
            result = git("worktree", "add", "--detach", str(self.work), "HEAD")
            if result.returncode != 0:
                sys.exit("git worktree add failed:\n" + result.stdout)
            self.created = True
            log(f"created worktree {self.work} at {git('rev-parse', '--short', 'HEAD').stdout.strip()}")
        self.recover()
        if self.args.sync_from:
            live = Path(self.args.sync_from).resolve()
            changed = sum(mirror(live / d, self.work / d) for d in SYNC_DIRS + SYNC_FILES)
            log(f"synced {', '.join(SYNC_DIRS + SYNC_FILES)} from {live}: {changed} file(s) changed")

    def recover(self):
        """A run killed hard (SIGKILL) leaves a marker: put the mutated file back."""
        if self.marker.exists():
            lines = self.marker.read_text().split("\n", 1)
            path, content = self.work / lines[0], lines[1]
            path.write_text(content)
            self.marker.unlink()
            log(f"restored {lines[0]} left mutated by an interrupted run")

    def configure_and_build(self):
        if not (self.build / "CMakeCache.txt").exists():
            rc, out = run(["cmake", "-S", str(self.work), "-B", str(self.build), "-DCOINROLL_BENCHMARKS=OFF",
                           "-DCMAKE_BUILD_TYPE=Release"])
            if rc != 0:
                sys.exit("configure failed:\n" + out[-4000:])
        t = time.time()
        rc, out = run(["cmake", "--build", str(self.build), "-j", str(self.args.jobs)])
        if rc != 0:
            sys.exit("baseline build failed:\n" + out[-6000:])
        log(f"baseline build {time.time() - t:.0f} s")

    def ctest(self, only=None, exclude=()):
        """Runs ctest (all tests but --exclude and `exclude`, or just the names in `only`);
        returns (passed, failed test names, seconds, output). The whole suite runs by tiers: the
        unit label first, the rest only once it passes (with --stop-on-failure), so a mutant the
        unit tests kill in seconds never waits for the README and figure tests, which ctest's
        COST properties would otherwise start first."""
        if only:
            return self.ctest_run(["-R", "^(" + "|".join(re.escape(name) for name in only) + ")$"])
        patterns = ([self.args.exclude] if self.args.exclude else []) + ["^" + re.escape(name) + "$" for name in exclude]
        selection = ["-E", "|".join(patterns)] if patterns else []
        if self.args.stop_on_failure:
            selection.append("--stop-on-failure")
        t = time.time()
        outputs, failed = [], []
        for tier in (["-L", "^unit$"], ["-LE", "^unit$"]):
            tier_passed, tier_failed, _, out = self.ctest_run(tier + selection)
            outputs.append(out)
            failed += tier_failed
            if not tier_passed and self.args.stop_on_failure:
                break
        return not failed, failed, time.time() - t, "\n".join(outputs)

    def ctest_run(self, selection):
        failed_log = self.build / "Testing" / "Temporary" / "LastTestsFailed.log"
        if failed_log.exists():
            failed_log.unlink()
        t = time.time()
        cmd = ["ctest", "--test-dir", str(self.build), "-j", str(self.args.jobs), "--timeout", str(self.args.timeout),
               "--output-on-failure", *selection]
        rc, out = run(cmd)
        failed = []
        if failed_log.exists():
            failed = [line.split(":", 1)[1] for line in failed_log.read_text().splitlines() if ":" in line]
        if rc != 0 and not failed:
            failed = ["(ctest exit %d)" % rc]
        return rc == 0, failed, time.time() - t, out

    def confirmed_failures(self, index):
        """ctest until a failure repeats: a test that fails with the mutant and then passes when run
        again on the same mutant is flaky (say soak_short's memory growth under load), not a kill;
        it is set aside and the rest of the suite runs. Returns (confirmed failures, flaky ones)."""
        flaky = []
        while True:
            passed, failed, _, out = self.ctest(exclude=flaky)
            self.save_output(index, out)
            if passed:
                return [], flaky
            if failed[0].startswith("(ctest exit"):
                return failed, flaky
            again, still, _, out2 = self.ctest(only=failed)
            self.save_output(index, out2)
            if not again:
                return still, flaky
            log(f"    {', '.join(failed)} failed, then passed when run again on the same mutant: flaky, set aside")
            flaky += failed

    def first_test_kills(self, index, target):
        """Builds `target` alone and runs it twice; the tests that fail both times, or none."""
        rc, out = run(["cmake", "--build", str(self.build), "-j", str(self.args.jobs), "--target", target])
        if rc != 0:
            return []  # the full build says why
        failures = []
        for _ in range(2):
            try:
                rc, out = run([str(self.build / "tests" / target)], timeout=self.args.timeout)
            except subprocess.TimeoutExpired:
                rc, out = -1, f"{target}: no end within {self.args.timeout} s"
            self.save_output(index, out)
            names = re.findall(r"^\[  FAILED  \] (\w+[./]\S+)", out, re.MULTILINE)
            if rc == 0:
                return []
            failures.append(list(dict.fromkeys(names)) or [f"({target} exit {rc})"])
        return [name for name in failures[0] if name in failures[1]] or failures[1]

    def save_output(self, index, out):
        if self.args.logs:
            Path(self.args.logs).mkdir(parents=True, exist_ok=True)
            with open(Path(self.args.logs) / f"mutant_{index:02d}.log", "a") as f:
                f.write(out + "\n")

    def baseline(self):
        passed, failed, seconds, out = self.ctest()
        if not passed and not failed[0].startswith("(ctest exit"):
            passed, _, _, _ = self.ctest(only=failed)
            if passed:
                log(f"baseline: {', '.join(failed)} failed once and passed when run again (flaky)")
        if not passed:
            sys.exit("baseline ctest is not green (%s); fix that first:\n%s" % (", ".join(failed), out[-4000:]))
        count = re.search(r"tests failed out of (\d+)", out)
        log(f"baseline ctest green ({count.group(1) if count else '?'} tests) in {seconds:.0f} s")

    def mutate(self, index: int, m: Mutation):
        path = self.work / m.file
        original = path.read_text()
        occurrences = original.count(m.original)
        if occurrences != 1:
            return {"result": "snippet-error", "detail": f"snippet found {occurrences} times", "seconds": 0}
        self.marker.write_text(m.file + "\n" + original)
        t = time.time()
        try:
            path.write_text(original.replace(m.original, m.replacement, 1))
            if m.first:
                killers = self.first_test_kills(index, m.first)
                if killers:
                    return {"result": "killed", "detail": ", ".join(killers[:3]) + f" ({m.first} built alone)",
                            "seconds": time.time() - t}
            rc, out = run(["cmake", "--build", str(self.build), "-j", str(self.args.jobs)])
            if rc != 0:
                error = next((line.strip() for line in out.splitlines() if "error:" in line), "build failed")
                return {"result": "not built", "detail": error[:160], "seconds": time.time() - t}
            failed, flaky = self.confirmed_failures(index)
            note = f" (flaky, set aside: {', '.join(flaky)})" if flaky else ""
            if not failed:
                return {"result": "SURVIVED", "detail": note.strip(), "seconds": time.time() - t}
            return {"result": "killed", "detail": ", ".join(failed[:3]) + (" ..." if len(failed) > 3 else "") + note,
                    "seconds": time.time() - t}
        finally:
            path.write_text(original)
            os.utime(path, None)  # newer than its object files: the next build picks the original up
            self.marker.unlink()

    def cleanup(self):
        if self.args.keep_worktree:
            log(f"kept worktree {self.work} (remove with: git worktree remove --force {self.work})")
            return
        result = git("worktree", "remove", "--force", str(self.work))
        log(f"removed worktree {self.work}" if result.returncode == 0 else "worktree remove failed: " + result.stdout)


def report(rows, selected) -> str:
    lines = ["| # | folder | file | kind | mutation | result | killed by | s |",
             "|---|---|---|---|---|---|---|---|"]
    for index, m, r in rows:
        lines.append(f"| {index} | {folder(m)} | {Path(m.file).name} | {m.kind} | {m.description} | {r['result']} | "
                     f"{r['detail']} | {r['seconds']:.0f} |")
    built = [r for _, _, r in rows if r["result"] in ("killed", "SURVIVED")]
    killed = [r for r in built if r["result"] == "killed"]
    lines.append("")
    if built:
        lines.append(f"**Score: {len(killed)}/{len(built)} built mutants killed = {100 * len(killed) / len(built):.1f} %** "
                     f"({len(rows)} run of {len(selected)} selected; "
                     f"{sum(r['result'] == 'not built' for _, _, r in rows)} not built, "
                     f"{sum(r['result'] == 'snippet-error' for _, _, r in rows)} snippet errors)")
    survivors = [(i, m) for i, m, r in rows if r["result"] == "SURVIVED"]
    if survivors:
        lines.append("")
        lines.append("Survivors: " + "; ".join(f"#{i} {m.file}: {m.description}" for i, m in survivors))
    per_folder = {}
    for _, m, r in rows:
        f = per_folder.setdefault(folder(m), [0, 0])
        f[0] += r["result"] == "killed"
        f[1] += r["result"] in ("killed", "SURVIVED")
    lines.append("")
    lines.append("Per folder: " + ", ".join(f"{k} {v[0]}/{v[1]}" for k, v in per_folder.items()))
    return "\n".join(lines) + "\n"


def list_table(root: Path):
    print("| # | file | kind | mutation | snippet found |")
    print("|---|---|---|---|---|")
    ok = True
    for i, m in enumerate(MUTATIONS, 1):
        text = (root / m.file).read_text() if (root / m.file).exists() else ""
        n = text.count(m.original)
        ok &= n == 1
        print(f"| {i} | {m.file} | {m.kind} | {m.description} | {'once' if n == 1 else f'{n} times (BAD)'} |")
    counts = {}
    for m in MUTATIONS:
        counts[folder(m)] = counts.get(folder(m), 0) + 1
    print("\n" + ", ".join(f"{k}: {v}" for k, v in counts.items()) + f"; total {len(MUTATIONS)}")
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--list", action="store_true", help="print the mutation table, check each snippet, exit")
    parser.add_argument("--only", help="run only these mutations: N, N,M or N-M (1-based, as --list numbers them)")
    parser.add_argument("--workdir", default="/tmp/coinroll_mutants", help="scratch git worktree (default %(default)s)")
    parser.add_argument("--sync-from", metavar="TREE",
                        help="copy src/ tests/ CMakeLists.txt cmake/ tools/ shaders/ assets/ examples/ from this live "
                             "tree into the worktree before the baseline (uncommitted work counts)")
    parser.add_argument("--report", metavar="FILE", help="also write the markdown table here")
    parser.add_argument("--log", metavar="FILE", help="also append progress lines here")
    parser.add_argument("--jobs", type=int, default=2, help="build and ctest parallelism (default %(default)s)")
    parser.add_argument("--timeout", type=int, default=120, help="ctest per-test timeout, s (default %(default)s)")
    parser.add_argument("--exclude", metavar="REGEX", help="ctest -E: tests left out of every mutant's run")
    parser.add_argument("--logs", metavar="DIR", help="keep each mutant's ctest output here (mutant_NN.log)")
    parser.add_argument("--no-stop-on-failure", dest="stop_on_failure", action="store_false",
                        help="run every test of a mutant instead of stopping at the first failure")
    parser.add_argument("--keep-worktree", action="store_true", help="leave the worktree (and its build) for reuse")
    args = parser.parse_args()

    if args.list:
        root = Path(args.sync_from).resolve() if args.sync_from else REPO
        sys.exit(0 if list_table(root) else 1)

    global LOG
    LOG = args.log
    selected = parse_only(args.only, len(MUTATIONS)) if args.only else list(range(1, len(MUTATIONS) + 1))

    # SIGTERM / SIGHUP unwind like Ctrl-C, so the finally blocks restore the mutated file.
    def interrupted(signum, _frame):
        raise KeyboardInterrupt(f"signal {signum}")
    signal.signal(signal.SIGTERM, interrupted)
    signal.signal(signal.SIGHUP, interrupted)

    runner = Runner(args)
    rows = []
    try:
        runner.prepare_worktree()
        runner.configure_and_build()
        runner.baseline()
        for n, index in enumerate(selected, 1):
            m = MUTATIONS[index - 1]
            log(f"[{n}/{len(selected)}] #{index} {m.file}: {m.description}")
            result = runner.mutate(index, m)
            log(f"    -> {result['result']} {result['detail']} ({result['seconds']:.0f} s)")
            rows.append((index, m, result))
    except KeyboardInterrupt as e:
        log(f"interrupted ({e}); the mutated file has been restored")
    finally:
        text = report(rows, selected)
        print(text)
        if args.report:
            Path(args.report).write_text(text)
        runner.cleanup()


if __name__ == "__main__":
    main()
