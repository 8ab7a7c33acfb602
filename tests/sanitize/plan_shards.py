#!/usr/bin/env python3
"""Deals the sanitizer's tests to the CPUs by their measured cost (scripts/sanitize).

gtest's own sharding deals tests round-robin by position: peers_test's second shard held 83% of its
CPU (its corpus sweeps sit together), so one CPU idled while the other ran on. Here every test the
filters select goes, most expensive first, to the CPU with the least cost so far (longest
processing time first), using the seconds measured under ASan in tests/sanitize/costs.txt; a test
that file does not know costs the median of those it knows. Each CPU then runs, executable by
executable, one process with the tests it was dealt: every selected test runs once, in one process.

    plan_shards.py COSTS CPUS LISTING...      LISTING: EXE:FILE, FILE holding EXE --gtest_list_tests

Prints one line per process: CPU, executable, its estimated seconds and its --gtest_filter value
(tab-separated), the most loaded CPU first; and on stderr each CPU's estimated seconds.
"""
import statistics
import sys


def read_costs(path):
    costs = {}
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            fields = line.split()
            if len(fields) != 3:
                sys.exit(f"{path}:{number}: expected 'EXECUTABLE TEST SECONDS'")
            costs[(fields[0], fields[1])] = float(fields[2])
    return costs


def listed_tests(path):
    """Full test names from gtest's --gtest_list_tests ("Suite." then "  Name  # GetParam() = ...")."""
    tests, suite = [], None
    with open(path) as f:
        for line in f:
            if not line.strip() or line.startswith("Running main()"):
                continue
            if not line.startswith(" "):
                suite = line.split("#", 1)[0].strip()
            else:
                tests.append(suite + line.split("#", 1)[0].strip())
    return tests


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    costs = read_costs(sys.argv[1])
    cpus = int(sys.argv[2])
    known = sorted(costs.values())
    default = statistics.median(known) if known else 1.0
    jobs = []  # (cost, exe, test)
    for listing in sys.argv[3:]:
        exe, path = listing.split(":", 1)
        jobs += [(costs.get((exe, t), default), exe, t) for t in listed_tests(path)]
    load = [0.0] * cpus
    dealt = [dict() for _ in range(cpus)]  # per CPU: exe -> [tests]
    for cost, exe, test in sorted(jobs, key=lambda j: (-j[0], j[1], j[2])):
        cpu = min(range(cpus), key=lambda c: load[c])
        load[cpu] += cost
        dealt[cpu].setdefault(exe, []).append((test, cost))
    for cpu in sorted(range(cpus), key=lambda c: -load[c]):
        for exe, tests in dealt[cpu].items():
            print(f"{cpu}\t{exe}\t{sum(c for _, c in tests):.1f}\t{':'.join(t for t, _ in tests)}")
    print("estimated seconds per CPU: " + ", ".join(f"{load[c]:.0f}" for c in range(cpus)), file=sys.stderr)


if __name__ == "__main__":
    main()
