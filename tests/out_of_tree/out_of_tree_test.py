#!/usr/bin/env python3
"""A scheme from outside the tree, built in by SUBDIVBENCH_SCHEME_DIRS, used like any other.

  out_of_tree_test.py --source SRC --work DIR [--cmake-arg ARG]...

Copies the test-only bilinear scheme (tests/schemes/bilinear) to a folder outside the checkout, as
a researcher's scheme (not test-only: it joins subdivbench), configures a second build of SRC in
DIR with -DSUBDIVBENCH_SCHEME_DIRS=<that folder> (and only the peers of schemes/, to keep the
build short), builds subdivbench and the scheme's tests, and checks that
  - the conformance suite passes on it (its own tests/, SDB_CONFORMANCE_SUITE),
  - its includes keep to the module graph (cmake/module_graph.txt) as a scheme folder's must,
  - `subdivbench list schemes` lists it, and `run`, `bench --rounds`, `gate` and `report` take it
    like any other scheme (its rows in results.json, the gate's lines and the report).
Exit 0 when all hold; 1 with the failing step's output otherwise.
"""
import argparse
import filecmp
import hashlib
import json
import os
import shutil
import subprocess
import sys

FAMILY = "bilinear"
SCHEME = "bilinear-limit"


def step(title, command, env=None, expect=0):
    print(f"== {title}: {' '.join(command)}", flush=True)
    r = subprocess.run(command, capture_output=True, text=True, env=env)
    if r.returncode != expect:
        print(r.stdout[-6000:], r.stderr[-6000:], sep="\n")
        sys.exit(f"out-of-tree: {title} exited {r.returncode}, expected {expect}")
    return r.stdout + r.stderr


def check(condition, what, output=""):
    if not condition:
        print(output[-6000:])
        sys.exit(f"out-of-tree: {what}")
    print(f"ok: {what}", flush=True)


def scheme_outside(source, work):
    """The scheme folder copied outside the checkout, files unchanged since the last run keeping
    their times (the second build stays incremental); TEST_ONLY dropped: a researcher's scheme."""
    key = hashlib.sha1(os.path.abspath(work).encode()).hexdigest()[:12]
    outside = os.path.join("/tmp", f"sdb-out-of-tree-{key}", FAMILY)
    checkout = os.path.abspath(source)
    if os.path.commonpath([checkout, outside]) == checkout:
        sys.exit(f"out-of-tree: {outside} is inside the checkout {checkout}")
    original = os.path.join(source, "tests", "schemes", FAMILY)
    for folder, _, files in os.walk(original):
        target = os.path.join(outside, os.path.relpath(folder, original))
        os.makedirs(target, exist_ok=True)
        for name in files:
            src, dst = os.path.join(folder, name), os.path.join(target, name)
            if name == "CMakeLists.txt":
                text = open(src, encoding="utf-8").read().replace(" TEST_ONLY", "")
                if not os.path.exists(dst) or open(dst, encoding="utf-8").read() != text:
                    open(dst, "w", encoding="utf-8").write(text)
            elif not os.path.exists(dst) or not filecmp.cmp(src, dst, shallow=False):
                shutil.copy2(src, dst)
    return outside


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--cmake-arg", action="append", default=[])
    parser.add_argument("--jobs", default="2")
    args = parser.parse_args()
    source, work = os.path.abspath(args.source), os.path.abspath(args.work)
    build = work  # the runs' outputs go into its subfolders run/, bench/, report/
    outside = scheme_outside(source, work)

    step("configure", ["cmake", "-S", source, "-B", build, f"-DSUBDIVBENCH_SCHEME_DIRS={outside}",
                       "-DSUBDIVBENCH_IN_TREE_SCHEMES=peers"] + args.cmake_arg)
    # With ccache as the launcher (scripts/build makes it so), as scripts/build hashes: paths
    # relative to a folder holding the source and both builds, and depend mode.
    ccache_env = dict(os.environ)
    ccache_env.setdefault("CCACHE_BASEDIR", os.path.commonpath([source, work]))
    ccache_env.setdefault("CCACHE_DEPEND", "1")
    step("build", ["cmake", "--build", build, "-j", args.jobs, "--target", "subdivbench", f"{FAMILY}_test"],
         env=ccache_env)

    out = step("conformance suite", ["ctest", "--test-dir", build, "-R", f"^{FAMILY}_test", "--output-on-failure"])
    check("100% tests passed" in out and "No tests were found" not in out,
          f"the conformance suite passes on {outside}", out)
    out = step("module graph", [sys.executable, os.path.join(source, "tests", "layering", "check_module_graph.py"),
                                "--root", source, "--scheme-dir", outside])
    check(out.startswith("module graph:"), "its includes keep to the module graph", out)

    subdivbench = os.path.join(build, "subdivbench")
    out = step("list schemes", [subdivbench, "list", "schemes"])
    check(any(line.split()[:1] == [SCHEME] for line in out.splitlines()), f"`list schemes` lists {SCHEME}", out)

    runs = os.path.join(work, "run")
    step("run", [subdivbench, "run", "--scheme", SCHEME, "--mesh", "torus-8x8", "--level", "5", "--backend", "cpu",
                 "--out", runs])
    rows = json.load(open(os.path.join(runs, "results.json"), encoding="utf-8"))["runs"]
    mine = [r for r in rows if r["scheme"] == SCHEME]
    check(len(mine) == 1 and mine[0]["status"] == "ok", f"`run` measures and validates {SCHEME}: one ok row",
          json.dumps(rows, indent=1))

    bench = os.path.join(work, "bench")
    step("bench", [subdivbench, "bench", "--run", "osd-bfr/cpu/torus-8x8/5", "--run", f"{SCHEME}/cpu/torus-8x8/5",
                   "--out", bench, "--rounds", "9", "--benchmark_min_time=0.01"])
    results = os.path.join(bench, "results.json")
    out = step("gate", [subdivbench, "gate", "--baseline", results, "--current", results])
    check(f"{SCHEME}/cpu/torus-8x8/5" in out, f"the gate judges {SCHEME}'s row (against its peer osd-bfr)", out)

    report = os.path.join(work, "report")
    step("report", [subdivbench, "report", "--in", results, "--out", report])
    text = open(os.path.join(report, "report.md"), encoding="utf-8").read()
    check(SCHEME in text, f"the report shows {SCHEME}", text)
    print(f"out-of-tree: {outside} built in, conformant, listed, run, gated and reported")
    return 0


if __name__ == "__main__":
    sys.exit(main())
