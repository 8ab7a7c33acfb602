#!/usr/bin/env python3
"""Writes the fuzz targets' seeds made at run time into OUT/<target>/: the hostile suite's files
(tests/hostile/make_inputs.py) by kind, the shared corpus's meshes (small ones whole; every OBJ's
tag lines for the tag target) and the project's own gate configuration and baseline. Nothing here
is kept in the repository: the shared corpus stays in ../shared, the hostile files are made from
code. Hand-made seeds live in tests/fuzz/seeds/<target> and are passed to libFuzzer as they are.
Usage: seed_corpus.py OUT [SHARED_DATASETS]"""
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "tests", "hostile"))
import make_inputs  # noqa: E402

MAX_SEED_BYTES = 64 * 1024  # larger files would only be cut to the targets' max_len


def by_kind(name):
    ext = os.path.splitext(name)[1].lower()
    if ext in (".obj", ".off", ".ply"):
        return [ext[1:]]
    if ext == ".json":
        return ["gate_config"] if name.startswith("gate_") else ["results"]
    return []


def tag_lines(text):
    return "".join(line[2:] + "\n" for line in text.splitlines() if line.startswith("t "))


def put(out, target, name, data):
    folder = os.path.join(out, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode("utf-8"))


def hostile_seeds(out):
    for name, content in make_inputs.files().items():
        data = content if isinstance(content, bytes) else content.encode("utf-8")
        if len(data) > MAX_SEED_BYTES:
            continue
        for target in by_kind(name):
            put(out, target, name, data)
        if name.endswith(".obj") and tag_lines(data.decode("utf-8", "replace")):
            put(out, "obj_tag", name, tag_lines(data.decode("utf-8", "replace")))


def shared_seeds(out, shared):
    for root, _, files in os.walk(shared):
        for name in sorted(files):
            path = os.path.join(root, name)
            kind = by_kind(name)
            if not kind or kind[0] not in ("obj", "off", "ply"):
                continue
            seed = os.path.relpath(path, shared).replace(os.sep, "_")
            with open(path, "rb") as f:
                data = f.read()
            if len(data) <= MAX_SEED_BYTES:
                put(out, kind[0], seed, data)
            if kind[0] == "obj" and tag_lines(data.decode("utf-8", "replace")):
                put(out, "obj_tag", seed, tag_lines(data.decode("utf-8", "replace")))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    shutil.rmtree(out, ignore_errors=True)
    hostile_seeds(out)
    shared = sys.argv[2] if len(sys.argv) > 2 else ""
    if shared and os.path.isdir(shared):
        shared_seeds(out, shared)
    else:
        print(f"seed_corpus: no shared datasets at '{shared}'; seeds from the hostile suite only", file=sys.stderr)
    for target, name in (("gate_config", "gate.json"), ("results", "baseline.json")):
        with open(os.path.join(REPO, "ci", name), "rb") as f:
            put(out, target, name, f.read())
    for target in sorted(os.listdir(out)):
        print(f"seed_corpus: {target}: {len(os.listdir(os.path.join(out, target)))} seeds")


if __name__ == "__main__":
    main()
