#!/usr/bin/env python3
"""The module graph as a test: every #include against cmake/module_graph.txt.

  check_module_graph.py --root SRC [--graph FILE] [--scheme-dir DIR]... [--plant FILE:HEADER]...
                        [--allow MODULE:MODULE]...

Reads every .h/.cpp under app/, harness/, schemes/, datasets/, reports/ and tests/ of SRC, and of each
out-of-tree scheme folder (a module schemes/<folder name>), and prints one line per include the
graph does not allow; exit 1 when there is one (or when the graph has a cycle or names a module
no file belongs to), 0 otherwise with a count of what was checked. --plant adds an include line
to a file as if it were written there, --allow an edge to the graph (the tests that the check
catches an upward include and a cycle).
"""
import argparse
import os
import re
import sys

SCANNED = ("app", "harness", "schemes", "datasets", "reports", "tests")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


class Graph:
    def __init__(self, path):
        self.allowed = {}   # module pattern -> [allowed pattern]
        self.external = {}  # <name> -> [include prefix]
        self.tests = []
        for number, raw in enumerate(open(path, encoding="utf-8"), 1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            if ":" not in line:
                sys.exit(f"{path}:{number}: expected 'module : modules', got {raw.strip()!r}")
            head, tail = (s.strip() for s in line.split(":", 1))
            items = tail.split()
            if head.startswith("[external]"):
                self.external[head[len("[external]"):].strip()] = items
            elif head == "[tests]":
                self.tests = items
            elif head in self.allowed:
                self.allowed[head] += items
            else:
                self.allowed[head] = items

    def module_of(self, path):
        """The longest module pattern holding `path`, and its '*' binding."""
        best = None
        for pattern in self.allowed:
            parts = pattern.split("/")
            folders = path.split("/")[:-1]
            if len(folders) < len(parts):
                continue
            if all(p == "*" or p == f for p, f in zip(parts, folders)):
                star = next((f for p, f in zip(parts, folders) if p == "*"), None)
                if best is None or len(parts) > len(best[0].split("/")):
                    best = (pattern, star)
        return best

    def external_of(self, header):
        for name, prefixes in self.external.items():
            if any(header.startswith(p) for p in prefixes):
                return name
        return None

    def cycle(self):
        """A cycle among the declared modules (wildcards as one node), or None."""
        edges = {m: [a for a in allowed if a in self.allowed and a != m] for m, allowed in self.allowed.items()}
        state = {}

        def visit(m, trail):
            state[m] = "open"
            for n in edges[m]:
                if state.get(n) == "open":
                    return trail + [m, n]
                if n not in state:
                    found = visit(n, trail + [m])
                    if found:
                        return found
            state[m] = "done"
            return None

        for m in edges:
            if m not in state:
                found = visit(m, [])
                if found:
                    return found
        return None


def is_test_code(rel):
    """Tests, and a module's GoogleTest support for them (testing.h: sdb_gpu_testing)."""
    name = os.path.basename(rel)
    return (rel.startswith("tests/") or "/tests/" in rel or name.endswith("_test.cpp")
            or name in ("testing.h", "testing.cpp"))


def target_module(graph, header):
    """The module a project header belongs to, with its binding; None for an unknown path."""
    if header.split("/")[0] not in SCANNED:
        return None
    return graph.module_of(header)


def permits(graph, source, test_code, target):
    """Whether code of `source` (module pattern, '*' binding) may include `target`'s headers. A
    wildcard pattern allowed to a bound module means its own binding (a scheme's paper tables
    reach their own scheme); to an unbound one, any."""
    module, star = source
    tmodule, tstar = target
    if module == tmodule and star == tstar:
        return True
    allowed = graph.allowed.get(module, []) + (graph.tests if test_code else [])
    for pattern in allowed:
        if pattern == tmodule and ("*" not in pattern or star is None or tstar == star):
            return True
    return False


def sources(root, scheme_dirs):
    """(path as the graph sees it, path on disk) of every C++ file checked."""
    for top in SCANNED:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if name.endswith((".h", ".cpp")):
                    disk = os.path.join(folder, name)
                    yield os.path.relpath(disk, root).replace(os.sep, "/"), disk
    for outside in scheme_dirs:
        outside = os.path.abspath(outside)
        family = os.path.basename(outside.rstrip("/"))
        for folder, _, files in os.walk(outside):
            for name in sorted(files):
                if name.endswith((".h", ".cpp")):
                    disk = os.path.join(folder, name)
                    yield "schemes/" + family + "/" + os.path.relpath(disk, outside).replace(os.sep, "/"), disk


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", required=True)
    parser.add_argument("--graph")
    parser.add_argument("--scheme-dir", action="append", default=[])
    parser.add_argument("--plant", action="append", default=[], help="FILE:HEADER, FILE relative to the root")
    parser.add_argument("--allow", action="append", default=[], help="MODULE:MODULE, an edge added to the graph")
    args = parser.parse_args()
    graph_path = args.graph or os.path.join(args.root, "cmake", "module_graph.txt")
    graph = Graph(graph_path)
    for edge in args.allow:
        module, target = edge.split(":", 1)
        graph.allowed.setdefault(module, []).append(target)

    cycle = graph.cycle()
    if cycle:
        print(f"{graph_path}: the declared graph has a cycle: {' -> '.join(cycle)}")
        return 1

    planted = {}
    for plant in args.plant:
        file, header = plant.split(":", 1)
        planted.setdefault(file, []).append(f'#include "{header}"')

    files = list(sources(args.root, args.scheme_dir))
    known = {rel for rel, _ in files}
    for rel in planted:
        if rel not in known:
            print(f"--plant {rel}: no such file under {args.root}")
            return 1
    # Bare names ("cpu.h") resolve beside the including file; elsewhere they would reach another
    # module through an include path: such a name is judged as the one header that has it.
    by_name = {}
    for rel, _ in files:
        by_name.setdefault(os.path.basename(rel), []).append(rel)

    bad, includes, seen_modules = [], 0, set()
    for rel, disk in files:
        source = graph.module_of(rel)
        if source is None:
            bad.append(f"{rel}: belongs to no module of {graph_path}")
            continue
        seen_modules.add(source[0])
        test_code = is_test_code(rel)
        lines = open(disk, encoding="utf-8", errors="replace").read().splitlines() + planted.get(rel, [])
        for number, line in enumerate(lines, 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            header = m.group(2)
            includes += 1
            external = graph.external_of(header) if m.group(1) == "<" or "/" in header else None
            if external:
                target = (external, None)
            elif "/" not in header:
                beside = os.path.join(os.path.dirname(rel), header)
                targets = [graph.module_of(c) for c in by_name.get(header, [])]
                targets = [t for t in targets if t]
                if beside in known or not targets or any(permits(graph, source, test_code, t) for t in targets):
                    continue
                target = targets[0]
            else:
                target = target_module(graph, header)
            if target is None:
                continue
            if not permits(graph, source, test_code, target):
                where = source[0].replace("*", source[1]) if source[1] else source[0]
                what = target[0].replace("*", target[1]) if target[1] else target[0]
                bad.append(f'{rel}:{number}: #include "{header}": {where} may not depend on {what} '
                           f"({graph_path})")

    unused = [m for m in graph.allowed if m not in seen_modules]
    for m in unused:
        bad.append(f"{graph_path}: module {m} holds no file")
    for line in bad:
        print(line)
    if bad:
        return 1
    print(f"module graph: {len(files)} files, {includes} includes, {len(seen_modules)} modules, none against {graph_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
