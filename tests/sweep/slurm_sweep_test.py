#!/usr/bin/python3
"""The sharded sweep (ci/sweep/) on a real Slurm cluster of one node, and the GitHub workflow's
steps run locally.

Starts munged, slurmctld and slurmd (Debian's Slurm 22.05, installed by `scripts/setup --test`)
on this machine, with the munge key, slurm.conf, state and logs in a temporary folder and ports
that are free; runs ci/sweep/slurm-submit.sh on a small selection in three shards, waits for the
merge job, and checks that the merged rows equal an unsharded run's (all but the timings) and
that the report says all three shards are there; then submits again, cancels one shard, and
checks that the merge names the missing shard and fails. Then ci/sweep/run-workflow-locally
runs github-sweep.yml's jobs on the same selection in three shards. Every process started here
is ended by its PID, and the test checks none is left.

  slurm_sweep_test.py --subdivbench BUILD/subdivbench --work DIR

Exit 77 (ctest's SKIP_RETURN_CODE) where Slurm or munge is not installed.
"""
import argparse
import glob
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

SKIP = 77
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DAEMONS = ["munged", "mungekey", "slurmctld", "slurmd", "sbatch", "squeue", "scancel", "scontrol", "sinfo"]
# Two fast peers on two built-in meshes at two levels: 8 rows, 3 + 3 + 2 in three shards.
SELECTION = ["--scheme", "osd-bfr", "--scheme", "osd-uniform", "--mesh", "cube", "--mesh", "torus-8x8",
             "--level", "2", "--level", "3", "--backend", "cpu", "--reps", "2", "--rays", "2000"]
TIMINGS = ("time_ms", "gpu_time_ms", "upload_ms", "readback_ms", "gpu_passes", "triangle_rate_mtris", "bandwidth_fraction")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(what, ready, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if ready():
            return
        time.sleep(0.5)
    raise AssertionError(f"timed out after {seconds} s waiting for {what}")


def children_of(pids):
    """Processes whose parent is one of `pids` (slurmstepd and the jobs it runs, under slurmd)."""
    found = []
    for stat in glob.glob("/proc/[0-9]*/stat"):
        try:
            with open(stat) as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) in pids:
            found.append(int(stat.split("/")[2]))
    return found


class Cluster:
    """munged, slurmctld and slurmd on localhost, everything they write inside `folder`."""

    def __init__(self, folder):
        self.folder = folder
        self.node = socket.gethostname().split(".")[0]
        self.processes = []
        self.env = dict(os.environ, SLURM_CONF=os.path.join(folder, "slurm.conf"))

    def path(self, name):
        return os.path.join(self.folder, name)

    def spawn(self, argv, log):
        out = open(self.path(log), "w")
        p = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, env=self.env, cwd=self.folder,
                             start_new_session=True)
        out.close()
        self.processes.append(p)
        return p

    def write_config(self):
        socket_path = self.path("munge.socket")
        conf = f"""ClusterName=subdivbench-test
SlurmctldHost={self.node}(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={socket_path}
SlurmUser=root
SlurmdUser=root
StateSaveLocation={self.path("state")}
SlurmdSpoolDir={self.path("spool")}
SlurmctldPidFile={self.path("slurmctld.pid")}
SlurmdPidFile={self.path("slurmd.pid")}
SlurmctldLogFile={self.path("slurmctld.log")}
SlurmdLogFile={self.path("slurmd.log")}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
SlurmdParameters=config_overrides
NodeName={self.node} NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
"""
        with open(self.path("slurm.conf"), "w") as f:
            f.write(conf)

    def start(self):
        os.makedirs(self.folder, mode=0o700)
        for d in ("state", "spool"):
            os.makedirs(self.path(d))
        subprocess.run(["mungekey", "--create", f"--keyfile={self.path('munge.key')}"], check=True)
        self.spawn(["munged", "--foreground", "--force", f"--socket={self.path('munge.socket')}",
                    f"--key-file={self.path('munge.key')}", f"--pid-file={self.path('munged.pid')}",
                    f"--seed-file={self.path('munged.seed')}", f"--log-file={self.path('munged.log')}"], "munged.out")
        wait_for("munged's socket", lambda: os.path.exists(self.path("munge.socket")), 30)
        self.write_config()
        self.spawn(["slurmctld", "-D", "-i"], "slurmctld.out")
        self.spawn(["slurmd", "-D"], "slurmd.out")

        def idle():
            r = subprocess.run(["sinfo", "-h", "-o", "%T"], env=self.env, capture_output=True, text=True)
            return r.returncode == 0 and r.stdout.strip() == "idle"

        wait_for("the node to be idle", idle, 90)

    def command(self, argv, **kwargs):
        return subprocess.run(argv, env=self.env, capture_output=True, text=True, **kwargs)

    def wait_job(self, job, seconds):
        def gone():
            r = self.command(["squeue", "-h", "-j", str(job)])
            return r.returncode == 0 and not r.stdout.strip()
        wait_for(f"job {job} to end", gone, seconds)

    def job_state(self, job):
        out = self.command(["scontrol", "show", "job", str(job)]).stdout
        m = re.search(r"JobState=(\S+)", out)
        return m.group(1) if m else "?"

    def stop(self):
        """Cancels every job, waits for them, then ends each daemon started here by its PID."""
        if any(p.poll() is None for p in self.processes[1:]):
            self.command(["scancel", "--full", "--user", "root"])
            try:
                wait_for("the queue to empty", lambda: not self.command(["squeue", "-h"]).stdout.strip(), 60)
            except AssertionError as e:
                print(f"stop: {e}")
        slurmd = [p.pid for p in self.processes[2:] if p.poll() is None]
        wait_for("slurmstepd to end", lambda: not children_of(set(slurmd)), 60)
        for p in reversed(self.processes):
            if p.poll() is None:
                os.kill(p.pid, signal.SIGTERM)
                try:
                    p.wait(30)
                except subprocess.TimeoutExpired:
                    os.kill(p.pid, signal.SIGKILL)
                    p.wait(10)
        left = [p.pid for p in self.processes if p.poll() is None]
        assert not left, f"processes left running: {left}"


def without_timings(row):
    return {k: v for k, v in row.items() if k not in TIMINGS}


def rows_of(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            rows += json.load(f)["runs"]
    return {f"{r['spec']}/{r['backend']}/{r['mesh']}/{r['level']}": without_timings(r) for r in rows}, len(rows)


def run_name_count(md):
    """Rows in report.md's "Every row" table."""
    table = md.split("## Every row", 1)[1]
    return sum(1 for line in table.splitlines() if line.startswith("| ") and not line.startswith("| scheme"))


def submit(cluster, sweep, build_dir):
    env = dict(cluster.env, SWEEP_CPUS_PER_TASK="1", SUBDIVBENCH_BUILD_DIR=build_dir, SWEEP_BUILD="0")
    r = subprocess.run([os.path.join(REPO, "ci", "sweep", "slurm-submit.sh"), "3", sweep, "--", *SELECTION],
                       env=env, capture_output=True, text=True, cwd=REPO)
    assert r.returncode == 0, f"slurm-submit.sh: exit {r.returncode}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}"
    m = re.search(r"queued shards as job (\d+) and the merge as job (\d+)", r.stdout)
    assert m, f"slurm-submit.sh said no job ids: {r.stdout[-500:]}"
    return int(m.group(1)), int(m.group(2))


def merge_log(sweep, merge):
    with open(os.path.join(sweep, f"slurm-subdivbench-merge-{merge}.out")) as f:
        return f.read()


def check_whole_sweep(cluster, work, build_dir, whole_rows):
    sweep = os.path.join(work, "sweep")
    start = time.monotonic()
    array, merge = submit(cluster, sweep, build_dir)
    cluster.wait_job(merge, 900)
    took = time.monotonic() - start
    log = merge_log(sweep, merge)
    assert "merge: all 3 shards" in log, f"the merge did not find all three shards:\n{log[-2000:]}"
    assert cluster.job_state(merge) == "COMPLETED", f"merge job {merge}: {cluster.job_state(merge)}"
    merged, count = rows_of(sorted(glob.glob(os.path.join(sweep, "shard-*", "results.json"))))
    assert count == len(whole_rows), f"the shards hold {count} rows, the unsharded run {len(whole_rows)}"
    assert merged == whole_rows, "the merged rows differ from the unsharded run's: " + ", ".join(
        n for n in sorted(set(merged) | set(whole_rows)) if merged.get(n) != whole_rows.get(n))
    with open(os.path.join(sweep, "merged", "report.html")) as f:
        assert "merged from 3 files (shards of 3, all present)" in f.read(), "the report does not say all shards came"
    with open(os.path.join(sweep, "merged", "report.md")) as f:
        assert run_name_count(f.read()) == len(whole_rows), "the merged report's every-row table lacks rows"
    print(f"three-shard sweep on the one-node cluster ({len(whole_rows)} rows): {took:.0f} s from submit to the merged report")


def check_cancelled_shard(cluster, work, build_dir):
    sweep = os.path.join(work, "sweep-cancelled")
    array, merge = submit(cluster, sweep, build_dir)
    r = cluster.command(["scancel", f"{array}_1"])
    assert r.returncode == 0, f"scancel {array}_1: {r.stderr}"
    cluster.wait_job(merge, 900)
    log = merge_log(sweep, merge)
    assert "MISSING shard 1 of 3" in log, f"the merge did not name the cancelled shard:\n{log[-2000:]}"
    assert cluster.job_state(merge) == "FAILED", f"merge job {merge} after a cancelled shard: {cluster.job_state(merge)}"
    with open(os.path.join(sweep, "merged", "report.html")) as f:
        assert "MISSING: 1" in f.read(), "the report of the other shards does not name the missing one"
    print("a cancelled shard: the merge named it (MISSING shard 1 of 3) and failed")


def check_workflow(work, build_dir, whole_rows):
    folder = os.path.join(work, "workflow")
    selection = os.path.join(work, "selection.txt")
    with open(selection, "w") as f:
        f.write("\n".join(SELECTION) + "\n")
    env = dict(os.environ, SUBDIVBENCH_SWEEP_SELECTION_FILE=selection, SUBDIVBENCH_BUILD_DIR=build_dir)
    start = time.monotonic()
    r = subprocess.run([os.path.join(REPO, "ci", "sweep", "run-workflow-locally"), "--shards", "3", "--work", folder],
                       env=env, capture_output=True, text=True, cwd=REPO)
    assert r.returncode == 0, f"run-workflow-locally: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-2000:]}"
    steps = re.findall(r"^\[(\S+)\] (ok  |FAIL|skip) ", r.stdout, re.M)
    assert [s for s in steps if s[1] == "FAIL"] == [], r.stdout
    assert [job for job, _ in steps][:1] == ["shard-0"] and steps[-1][0] == "merge", f"jobs out of order: {steps}"
    merged, count = rows_of(sorted(glob.glob(os.path.join(folder, "artifacts", "shard-*", "results.json"))))
    assert count == len(whole_rows) and merged == whole_rows, "the workflow's shards differ from the unsharded run"
    with open(os.path.join(folder, "artifacts", "sweep-report", "report.html")) as f:
        assert "merged from 3 files (shards of 3, all present)" in f.read()
    print(f"github-sweep.yml run locally in three shards: {len(steps)} steps in order, {time.monotonic() - start:.0f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--subdivbench", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    sys.stdout.reconfigure(line_buffering=True)  # a killed test still shows how far it came
    missing = [d for d in DAEMONS if not shutil.which(d) and not os.path.exists(f"/usr/sbin/{d}")]
    if missing:
        print(f"skipped: {' '.join(missing)} not installed (./scripts/setup --test installs Slurm and munge)")
        return SKIP
    os.environ["PATH"] = os.environ.get("PATH", "") + ":/usr/sbin:/sbin"
    build_dir = os.path.dirname(os.path.abspath(args.subdivbench))
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    whole = os.path.join(work, "whole")
    r = subprocess.run([args.subdivbench, "run", *SELECTION, "--out", whole, "--no-report"], capture_output=True, text=True)
    assert r.returncode == 0, f"the unsharded run: exit {r.returncode}\n{r.stderr[-2000:]}"
    whole_rows, _ = rows_of([os.path.join(whole, "results.json")])
    cluster = Cluster(os.path.join(work, "cluster"))
    try:
        cluster.start()
        check_whole_sweep(cluster, work, build_dir, whole_rows)
        check_cancelled_shard(cluster, work, build_dir)
    finally:
        cluster.stop()
    print("cluster stopped: munged, slurmctld and slurmd ended by their PIDs, no job step left")
    check_workflow(work, build_dir, whole_rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
