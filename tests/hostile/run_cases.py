#!/usr/bin/env python3
"""The hostile-input suite: every case in cases.txt runs subdivbench once, as a user would, and
asserts its exit code, that no signal ended it, that it finished within its time bound, and, for
bad input (exit 2), that stderr is one line matching the case's pattern (naming the file and line).
Usage: run_cases.py SUBDIVBENCH CASES WORKDIR [SHARED_DATASETS]"""
import os
import re
import resource
import shlex
import subprocess
import sys
import time

import make_inputs

ADDRESS_LIMIT = 6 << 30
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def limit_child():
    # An ASan build (scripts/sanitize --all) maps terabytes of shadow memory at start: no address limit.
    if "ASAN_OPTIONS" not in os.environ:
        resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_LIMIT, ADDRESS_LIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def parse_cases(path):
    """One case a line: EXIT SECONDS PATTERN ARGS...  (PATTERN a Python regex in single quotes,
    matched against stderr for exit 2, stdout otherwise; '' matches anything; ARGS may start with
    NAME=VALUE settings, split_settings)."""
    cases = []
    with open(path) as f:
        for no, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            tok = shlex.split(line)
            if len(tok) < 4:
                sys.exit(f"{path}:{no}: a case needs EXIT SECONDS PATTERN ARGS")
            cases.append((no, int(tok[0]), float(tok[1]), tok[2], tok[3:]))
    return cases


def split_settings(args):
    """Leading NAME=VALUE arguments set the environment (STDOUT=PATH: standard output goes to PATH,
    /dev/full say); the rest is the argument vector."""
    env, stdout = dict(os.environ), subprocess.PIPE
    while args and re.match(r"^[A-Z_]+=", args[0]):
        name, value = args[0].split("=", 1)
        if name == "STDOUT":
            stdout = open(value, "wb")
        else:
            env[name] = value
        args = args[1:]
    return env, stdout, args


def check(case, exe, subst, workdir):
    no, want, seconds, pattern, args = case
    env, stdout, args = split_settings([a.format(**subst) for a in args])
    argv = [exe] + args
    start = time.monotonic()
    try:
        p = subprocess.run(argv, cwd=workdir, stdout=stdout, stderr=subprocess.PIPE, timeout=seconds,
                           preexec_fn=limit_child, stdin=subprocess.DEVNULL, env=env)
    except subprocess.TimeoutExpired:
        return f"hang: over {seconds:g} s"
    took = time.monotonic() - start
    out, err = (p.stdout or b"").decode(errors="replace"), p.stderr.decode(errors="replace")
    if p.returncode < 0:
        return f"signal {-p.returncode}; stderr: {err[-300:]!r}"
    problems = []
    if p.returncode != want:
        problems.append(f"exit {p.returncode}, expected {want}")
    if len(err) > 2000:
        problems.append(f"stderr of {len(err)} characters")
    if want == 2:
        lines = err.rstrip("\n").split("\n")
        if len(lines) != 1 or not lines[0]:
            problems.append(f"stderr has {len(lines)} lines, expected one")
        if not re.search(pattern, err):
            problems.append(f"stderr does not match {pattern!r}")
    elif pattern and not re.search(pattern, out, re.M):
        problems.append(f"stdout does not match {pattern!r}")
    if problems:
        return "; ".join(problems) + f"\n      stderr: {err[:300]!r}\n      stdout: {out[-300:]!r}"
    return None


def main():
    exe, cases_path, workdir = os.path.abspath(sys.argv[1]), sys.argv[2], os.path.abspath(sys.argv[3])
    shared = os.path.abspath(sys.argv[4]) if len(sys.argv) > 4 and os.path.isdir(sys.argv[4]) else ""
    inputs = os.path.join(workdir, "in")
    make_inputs.write_all(inputs)
    cases = parse_cases(cases_path)
    only = os.environ.get("HOSTILE_ONLY")
    failures = 0
    for case in cases:
        if only and not re.search(only, " ".join(case[4])):
            continue
        if "{S}" in " ".join(case[4]) and not shared:
            print(f"skip  line {case[0]}: needs the shared corpus")
            continue
        problem = check(case, exe, {"D": inputs, "S": shared, "W": workdir, "R": REPO, "NL": "\n", "ESC": "\x1b"}, workdir)
        print(f"{'FAIL' if problem else 'ok  '}  line {case[0]}: {' '.join(case[4])}" + (f"\n      {problem}" if problem else ""))
        failures += bool(problem)
    if os.path.exists(os.path.join(workdir, "SHELL_RAN")):
        print("FAIL  a workload name ran a shell command (SHELL_RAN exists)")
        failures += 1
    print(f"hostile inputs: {len(cases)} cases, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
