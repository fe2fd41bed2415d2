#!/usr/bin/python3
"""The cluster examples of docs/sweeps.md, run as written.

GNU parallel: the docs' command line, then its merged file against a single-process sweep of the
same grid. Slurm: a one-node cluster in a scratch directory (munged, slurmctld and slurmd with
their own socket, key, ports and state), the docs' job script and submission run as written, the
merged file against the same single-process sweep, and every daemon stopped again. The examples
are read from the docs (the blocks after a `<!-- slurm_test: NAME -->` comment), so the docs and
what is tested cannot drift apart. The examples call `coinroll` and read `scene.json` in their
working directory: the test puts the built binary first on PATH and the scene below there.

    /usr/bin/python3 tests/slurm/slurm_test.py --binary build/coinroll

Exit 77 (ctest's skip) where Slurm cannot start here: not root, or slurm-wlm and munge missing
(tools/setup.sh installs them). Standard library only.
"""

import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent
DOCS = REPO / "docs" / "sweeps.md"
SKIP = 77

# A point of this scene takes a few milliseconds: the test is about scheduling, not physics.
SCENE = """{"name": "toy", "coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
 "initial": {"theta": 10, "omega_Z": 12}, "duration": 1}
"""

# Seconds: the whole array and its merge take a few on this 2-core machine.
NODE_READY_TIMEOUT = 30
JOBS_TIMEOUT = 90


def docs_block(name):
    """The indented code block after `<!-- slurm_test: NAME -->` in docs/sweeps.md."""
    lines = DOCS.read_text(encoding="utf-8").splitlines()
    marker = f"<!-- slurm_test: {name} -->"
    if marker not in lines:
        sys.exit(f"{DOCS}: no {marker} before a code block")
    block = []
    for line in lines[lines.index(marker) + 1:]:
        if line.startswith("    "):
            block.append(line[4:])
        elif line.strip() or block:
            if line.strip():
                break
            block.append("")
    while block and not block[-1]:
        block.pop()
    return "\n".join(block) + "\n"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run(command, cwd, env, timeout=60):
    shell = isinstance(command, str)  # the docs' examples are bash
    result = subprocess.run(command, cwd=cwd, env=env, shell=shell, executable="/bin/bash" if shell else None,
                            capture_output=True, text=True, timeout=timeout)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {command}\n{result.stdout}{result.stderr}")
    return result.stdout


def single_process_sweep(script, directory, env):
    """The grid of the docs' command, swept in one process without shards: the reference bytes."""
    grid = re.findall(r"--grid (\S+)", script)
    if not grid:
        sys.exit(f"no --grid in the docs' command:\n{script}")
    directory.mkdir()
    (directory / "scene.json").write_text(SCENE)
    run(["coinroll", "sweep", "scene.json", *[a for g in grid for a in ("--grid", g)], "-q", "-o", "single.csv"],
        directory, env)
    return (directory / "single.csv").read_bytes()


def same_bytes(what, produced, reference):
    if produced != reference:
        sys.exit(f"{what}: differs from the single-process sweep\n--- merged\n{produced.decode()}\n"
                 f"--- single\n{reference.decode()}")
    rows = reference.decode().count("\n") - 1
    print(f"{what}: the merged file equals the single-process sweep byte for byte ({rows} points, "
          f"{len(reference)} bytes)")


def gnu_parallel(scratch, env):
    command = docs_block("parallel")
    if shutil.which("parallel") is None:
        sys.exit("GNU parallel is missing (tools/setup.sh installs it)")
    directory = scratch / "parallel"
    directory.mkdir()
    (directory / "scene.json").write_text(SCENE)
    print(f"GNU parallel, as docs/sweeps.md writes it:\n{command}")
    run(command, directory, env)
    same_bytes("GNU parallel", (directory / "map.csv").read_bytes(),
               single_process_sweep(command, scratch / "parallel_single", env))


def slurm_missing():
    if os.geteuid() != 0:
        return "not root: slurmd starts jobs as their user, which only root may do"
    missing = [p for p in ("munged", "slurmctld", "slurmd", "sbatch", "sinfo", "scontrol") if shutil.which(p) is None]
    if missing:
        return f"{', '.join(missing)} not installed (tools/setup.sh installs slurm-wlm and munge)"
    return None


class Cluster:
    """munged, slurmctld and slurmd for one node, everything they write under `root`."""

    def __init__(self, root, env):
        self.root, self.env, self.daemons = root, env, []
        (root / "state").mkdir(parents=True)
        (root / "spool").mkdir()
        (root / "munge").mkdir(mode=0o700)
        self.conf = root / "slurm.conf"
        env["SLURM_CONF"] = str(self.conf)

    def start(self):
        munge = self.root / "munge"
        key = munge / "munge.key"
        key.write_bytes(os.urandom(128))
        key.chmod(0o400)
        socket_path = munge / "munge.socket"
        self.spawn("munged", ["munged", "-F", "-f", f"--socket={socket_path}", f"--key-file={key}",
                              f"--pid-file={munge}/munged.pid", f"--log-file={munge}/munged.log",
                              f"--seed-file={munge}/munged.seed"])
        self.wait_for(lambda: socket_path.exists(), "munged's socket", 10)
        cpus = 2
        self.conf.write_text(f"""\
ClusterName=coinroll
SlurmctldHost=localhost
SlurmUser=root
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
AuthType=auth/munge
AuthInfo=socket={socket_path}
StateSaveLocation={self.root}/state
SlurmdSpoolDir={self.root}/spool
SlurmctldPidFile={self.root}/slurmctld.pid
SlurmdPidFile={self.root}/slurmd.pid
SlurmctldLogFile={self.root}/slurmctld.log
SlurmdLogFile={self.root}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MailProg=/bin/true
NodeName=localhost NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
""")
        self.spawn("slurmctld", ["slurmctld", "-D", "-i"])
        self.spawn("slurmd", ["slurmd", "-D", "-N", "localhost"])

        def idle():
            result = subprocess.run(["sinfo", "-h", "-o", "%t"], env=self.env, capture_output=True, text=True)
            return result.returncode == 0 and result.stdout.strip() == "idle"
        self.wait_for(idle, "the node to be idle (sinfo)", NODE_READY_TIMEOUT)

    def spawn(self, name, command):
        log = open(self.root / f"{name}.out", "w")
        process = subprocess.Popen(command, env=self.env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.daemons.append((name, process))

    def wait_for(self, ready, what, timeout):
        deadline = time.monotonic() + timeout
        while not ready():
            for name, process in self.daemons:
                if process.poll() is not None:
                    sys.exit(f"{name} exited ({process.returncode}) while waiting for {what}:\n{self.logs()}")
            if time.monotonic() > deadline:
                sys.exit(f"no {what} after {timeout} s:\n{self.logs()}")
            time.sleep(0.2)

    def logs(self):
        return "\n".join(f"--- {p.name}\n{p.read_text(errors='replace')[-3000:]}"
                         for p in sorted(self.root.glob("*.log")) + sorted(self.root.glob("munge/*.log"))
                         + sorted(self.root.glob("*.out")))

    def stop(self):
        """Stops every daemon started, the last first, and says which; jobs still running (a
        failed check) are cancelled first, so no job step outlives its slurmd."""
        if any(name == "slurmctld" and process.poll() is None for name, process in self.daemons):
            subprocess.run(["scancel", "--user", str(os.getuid())], env=self.env, capture_output=True, timeout=10)
            deadline = time.monotonic() + 10
            while time.monotonic() < deadline and any(
                    state in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING")
                    for state, _ in job_states(self.env).values()):
                time.sleep(0.2)
        for name, process in reversed(self.daemons):
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGTERM)
                try:
                    process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)
                    process.wait()
            print(f"stopped {name} (pid {process.pid}, exit {process.returncode})")
        self.daemons = []


def job_states(env):
    """{job id: (state, reason)} of every job slurmctld knows."""
    out = subprocess.run(["scontrol", "show", "job", "-o"], env=env, capture_output=True, text=True).stdout
    states = {}
    for line in out.splitlines():
        fields = dict(re.findall(r"(\w+)=(\S*)", line))
        if "JobId" in fields:
            # An array task by its array's id and task number, as sbatch and the log names show it.
            job = f"{fields['ArrayJobId']}_{fields['ArrayTaskId']}" if "ArrayTaskId" in fields else fields["JobId"]
            states[job] = (fields.get("JobState"), fields.get("Reason"))
    return states


def slurm(scratch, env):
    cluster = Cluster(scratch / "cluster", env)
    try:
        started = time.monotonic()
        cluster.start()
        print(f"started munged, slurmctld and slurmd in {time.monotonic() - started:.1f} s "
              f"(one node, 2 CPUs, state and sockets under the scratch directory)")
        script, submit = docs_block("sweep.sbatch"), docs_block("submit")
        work = scratch / "slurm"
        work.mkdir()
        (work / "scene.json").write_text(SCENE)
        (work / "sweep.sbatch").write_text(script)
        print(f"sweep.sbatch, as docs/sweeps.md writes it:\n{script}\nsubmitted as docs/sweeps.md writes it:\n{submit}")
        submitted = time.monotonic()
        print(run(submit, work, env), end="")
        deadline = time.monotonic() + JOBS_TIMEOUT
        while True:
            states = job_states(env)
            if any(reason == "DependencyNeverSatisfied" for _, reason in states.values()):
                break
            if states and all(state not in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING")
                              for state, _ in states.values()):
                break
            if time.monotonic() > deadline:
                sys.exit(f"jobs not finished after {JOBS_TIMEOUT} s: {states}\n{cluster.logs()}")
            time.sleep(0.5)
        print(f"jobs finished {time.monotonic() - submitted:.1f} s after submission: "
              + ", ".join(f"{job} {state}" for job, (state, _) in sorted(states.items())))
        for log in sorted((work / "logs").glob("*")):
            print(f"--- {log.relative_to(work)}\n{log.read_text()}", end="")
        if any(state != "COMPLETED" for state, _ in states.values()):
            sys.exit(f"a job did not complete: {states}\n{cluster.logs()}")
        same_bytes("Slurm", (work / "sweep.csv").read_bytes(), single_process_sweep(script, scratch / "slurm_single", env))
    finally:
        cluster.stop()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--binary", required=True, help="the coinroll binary to test")
    args = parser.parse_args()
    started = time.monotonic()
    env = dict(os.environ)
    # The examples call `coinroll`: this build's, whatever else is on PATH.
    bin_dir = Path(tempfile.mkdtemp(prefix="coinroll_bin_"))
    scratch = Path(tempfile.mkdtemp(prefix="coinroll_slurm_"))
    try:
        (bin_dir / "coinroll").symlink_to(Path(args.binary).resolve())
        env["PATH"] = f"{bin_dir}:{env['PATH']}"
        for name in [n for n in env if n.startswith("SLURM_")]:
            del env[name]  # a test run inside a Slurm job must not pass its own job's settings on
        gnu_parallel(scratch, env)
        reason = slurm_missing()
        if reason:
            print(f"SKIP the Slurm part: {reason}")
            return SKIP
        slurm(scratch, env)
        print(f"done in {time.monotonic() - started:.1f} s")
        return 0
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
        shutil.rmtree(bin_dir, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
