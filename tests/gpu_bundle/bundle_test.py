#!/usr/bin/python3
"""scripts/gpu-bundle end to end (issue 44): the bundle is written and is at most 60 MiB; ldd finds
every library the binary links beyond glibc, libstdc++ and libgcc inside it; a copy of it elsewhere
(the original deleted) runs `run --quick --allow-cpu-device --out DIR` on this machine's Vulkan
device (lavapipe) in a clean environment (env -i with PATH and HOME only) in which the source tree,
the build tree and the mesh corpus are hidden (a private mount namespace with empty folders mounted
over them), killed once its journal holds a measured stage and resumed; LD_DEBUG=libs shows every
library of the bundle loaded from the bundle; every Vulkan scheme of the registry has a row; the
summary and the last lines call lavapipe a CPU implementation of Vulkan and rank nothing; HOME and
the bundle are left as they were. Then the bundle's report without matplotlib.

    bundle_test.py --source SRC --build BUILD
"""
import argparse
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

LIMIT = 60 * 1024 * 1024
# glibc's libraries, libstdc++ and libgcc: the machine's, as the issue allows.
SYSTEM = re.compile(r"^(linux-vdso|ld-linux-x86-64|libc|libm|libdl|libpthread|librt|libresolv|libutil|libstdc\+\+|libgcc_s)\.so")


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files)


def listing(path):
    return sorted((os.path.relpath(os.path.join(d, f), path), os.path.getsize(os.path.join(d, f)))
                  for d, _, files in os.walk(path) for f in files)


def make_bundle(source, build, made):
    env = dict(os.environ, SUBDIVBENCH_BUILD_DIR=build)
    p = subprocess.run([os.path.join(source, "scripts", "gpu-bundle"), "--out", made], env=env, text=True,
                       capture_output=True, timeout=900)
    print(p.stdout + p.stderr)
    check(p.returncode == 0, f"scripts/gpu-bundle exited {p.returncode}")
    size = folder_bytes(made)
    print(f"bundle: {size / 1048576:.1f} MiB of {LIMIT / 1048576:.0f}")
    check(size <= LIMIT, f"the bundle is {size} bytes, over 60 MiB")
    for part in ("run", "bin/subdivbench", "lib/libvulkan.so.1", "meshes/stein/sword_quad_dominant.obj",
                 "meshes/README.md", "reports/report.py", "COMMIT", "REQUIRES"):
        check(os.path.exists(os.path.join(made, part)), f"the bundle lacks {part}")


def check_ldd(bundle):
    lib = os.path.join(bundle, "lib")
    out = subprocess.run(["ldd", os.path.join(bundle, "bin", "subdivbench")], env={"LD_LIBRARY_PATH": lib, "PATH": "/usr/bin:/bin"},
                         text=True, capture_output=True, check=True).stdout
    inside = 0
    for line in out.splitlines():
        parts = line.split()
        if "=>" not in parts:
            continue
        name, path = parts[0], parts[2]
        check(path != "not", f"ldd: {name} not found")
        if os.path.realpath(path).startswith(os.path.realpath(lib) + os.sep):
            inside += 1
        else:
            check(SYSTEM.match(name), f"ldd: {name} resolves outside the bundle, to {path}")
    print(f"ldd: {inside} libraries from the bundle, the rest glibc, libstdc++ and libgcc")
    check(inside >= 6, "ldd: fewer than 6 libraries from the bundle (Embree, OpenSubdiv x2, TBB, OpenMesh, Google Benchmark)")


def hidden_run(args, hide, bundle, home, debug_prefix, new_session=True):
    """`bundle/run args` in env -i (PATH, HOME) and a mount namespace with `hide` covered by empty tmpfs."""
    mounts = " && ".join(f'mount -t tmpfs -o ro none "${i + 1}"' for i in range(len(hide)))
    script = f'{mounts} && exec env -i PATH=/usr/bin:/bin HOME="$0" LD_DEBUG=libs LD_DEBUG_OUTPUT="${len(hide) + 1}" ' \
             f'"${len(hide) + 2}/run" "${{@:{len(hide) + 3}}}"'
    cmd = ["unshare", "--map-root-user", "--mount", "bash", "-c", script, home, *hide, debug_prefix, bundle, *args]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=new_session)


def journal_stages(out):
    try:
        with open(os.path.join(out, "gpu-check.jsonl")) as f:
            return [json.loads(line) for line in f.read().splitlines()[1:]]
    except (OSError, ValueError):
        return []


def run_killed_then_resumed(hide, bundle, home, debug_prefix, out):
    # Killed (the whole process group, SIGKILL) once a stage after the device facts is journalled.
    p = hidden_run(["--quick", "--allow-cpu-device", "--out", out], hide, bundle, home, debug_prefix)
    deadline = time.time() + 600
    while time.time() < deadline and p.poll() is None and len([s for s in journal_stages(out) if s["stage"] != "device"]) < 1:
        time.sleep(0.2)
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    first = p.communicate()[0]
    check(p.returncode == -signal.SIGKILL, f"the first run ended (exit {p.returncode}) before it could be killed:\n{first}")
    kept = [s for s in journal_stages(out)]
    check(kept and kept[0]["stage"] == "device", "the killed run journalled no device stage:\n" + first)
    measured = [s for s in kept if s["stage"] != "device" and s["status"] == "ok"]
    check(measured, "the killed run journalled no measured stage:\n" + first)
    stage_file = os.path.join(out, "stages", measured[0]["stage"].replace("size ", "").replace(": ", "-"), "results.json")
    check(os.path.exists(stage_file), f"{stage_file} missing after the kill")
    check(os.path.exists(os.path.join(out, "results.json")) and os.path.exists(os.path.join(out, "summary.txt")),
          "the killed run left no results.json or summary.txt from its finished stages")
    before = os.stat(stage_file).st_mtime_ns
    print(f"killed after {len(kept)} journalled stages")

    p = hidden_run(["--quick", "--allow-cpu-device", "--out", out, "--resume"], hide, bundle, home, debug_prefix)
    output = p.communicate(timeout=900)[0]
    print(output)
    check(p.returncode == 0, f"run --resume exited {p.returncode}")
    check(f"resuming {out}: {len(kept)} of" in output, "the resumed run did not read the journal")
    check(f"{measured[0]['stage']} (" in output and ": journalled (ok)" in output, "a journalled stage was not skipped")
    check(os.stat(stage_file).st_mtime_ns == before, f"{measured[0]['stage']} was measured again on --resume")
    return output


def check_results(bundle, out, output):
    for name in ("results.json", "summary.txt", "report.html", "report.md", "paper/ni2008-table4.md"):
        check(os.path.exists(os.path.join(out, name)), f"{name} was not written")
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)
    check(results["machine"].get("vulkan_device_type") == "cpu", "results.json does not say the device is a CPU one")
    env = {"LD_LIBRARY_PATH": os.path.join(bundle, "lib"), "PATH": "/usr/bin:/bin"}
    listed = subprocess.run([os.path.join(bundle, "bin", "subdivbench"), "list", "schemes"], env=env, text=True,
                            capture_output=True, check=True).stdout.splitlines()[1:]
    vulkan_schemes = [cols[0] for cols in (line.split() for line in listed)
                      if len(cols) > 2 and cols[1] != "test" and "vulkan" in cols[2].split(",")]
    check(len(vulkan_schemes) >= 10, f"only {len(vulkan_schemes)} Vulkan schemes listed")
    ok = {(r["scheme"], r["backend"]) for r in results["runs"] if r["status"] == "ok"}
    missing = [s for s in vulkan_schemes if (s, "vulkan") not in ok]
    check(not missing, f"no ok vulkan row for {missing}")
    cpu_rows = [r for r in results["runs"] if r["backend"] == "cpu-mt" and r["status"] == "ok"]
    check(len(cpu_rows) >= len(vulkan_schemes), "fewer cpu-mt rows than Vulkan schemes")
    backend_cells = [p for p in results.get("paired", []) if p["peer"]["scheme"] == p["scheme"]]
    check(backend_cells, "no GPU row paired with its own cpu-mt row")
    with open(os.path.join(out, "summary.txt")) as f:
        summary = f.read().splitlines()
    check(len(summary) <= 40 and max(len(line) for line in summary) <= 100, "summary.txt is more than a screen")
    check(any("a CPU implementation of Vulkan (lavapipe), NOT a GPU" in line for line in summary), "summary.txt does not label lavapipe")
    check(not any("fastest" in line or "GPU target" in line for line in summary), "summary.txt ranks lavapipe as a GPU")
    last = output.strip().splitlines()[-len(summary) - 3:]
    check(any("a CPU implementation of Vulkan" in line for line in last), "run's last lines do not label lavapipe")
    with open(os.path.join(out, "report.md")) as f:
        check("a CPU implementation of Vulkan" in f.read(), "report.md does not label lavapipe")
    print(f"results: {len(results['runs'])} rows, {len(vulkan_schemes)} Vulkan schemes each with an ok row, "
          f"{len(backend_cells)} GPU rows paired with their cpu-mt rows; summary {len(summary)} lines")


def check_libraries(bundle, debug_prefix):
    """Every process of the bundle's subdivbench: what it loaded before main is the bundle's or the
    system's glibc, libstdc++ and libgcc; every library the bundle ships that it loaded at all
    (libvulkan.so.1 with dlopen) came from the bundle."""
    program = os.path.join(bundle, "bin", "subdivbench")
    shipped = {os.path.basename(p) for p in glob.glob(os.path.join(bundle, "lib", "*.so*"))}
    processes = loaded_vulkan = 0
    for path in glob.glob(debug_prefix + ".*"):
        with open(path, errors="replace") as f:
            text = f.read()
        if f"transferring control: {program}" not in text:
            continue  # bash, python3, getconf: not ours
        processes += 1
        before_main = text.split("transferring control:")[0]
        for lib in re.findall(r"calling init: (\S+)", before_main):
            if not lib.startswith(bundle + os.sep):
                check(SYSTEM.match(os.path.basename(lib)), f"{os.path.basename(path)}: {lib} loaded before main from outside the bundle")
        for lib in re.findall(r"calling init: (\S+)", text):
            if os.path.basename(lib) in shipped:
                check(lib.startswith(bundle + os.sep), f"{os.path.basename(path)}: {lib} loaded from outside the bundle")
                loaded_vulkan += os.path.basename(lib) == "libvulkan.so.1"
    check(processes >= 3, f"LD_DEBUG saw {processes} subdivbench processes")
    check(loaded_vulkan >= 1, "no subdivbench process loaded libvulkan.so.1")
    print(f"LD_DEBUG: {processes} subdivbench processes, every bundled library from the bundle "
          f"(libvulkan.so.1 in {loaded_vulkan})")


def check_report_without_matplotlib(bundle, out, work):
    fake = os.path.join(work, "no-matplotlib", "matplotlib")
    os.makedirs(fake)
    with open(os.path.join(fake, "__init__.py"), "w") as f:
        f.write("raise ImportError('No module named matplotlib (hidden by the test)')\n")
    report = os.path.join(work, "report-without-plots")
    env = {"LD_LIBRARY_PATH": os.path.join(bundle, "lib"), "PATH": "/usr/bin:/bin", "HOME": work,
           "SUBDIVBENCH_HOME": bundle, "PYTHONPATH": os.path.dirname(fake), "PYTHONDONTWRITEBYTECODE": "1"}
    p = subprocess.run([os.path.join(bundle, "bin", "subdivbench"), "report", "--in", os.path.join(out, "results.json"),
                        "--out", report], env=env, text=True, capture_output=True)
    check(p.returncode == 0, f"report without matplotlib exited {p.returncode}: {p.stderr}")
    with open(os.path.join(report, "report.md")) as f:
        check("No plots: No module named matplotlib" in f.read(), "report.md does not say why it has no plots")
    print("report without matplotlib: written, no plots, saying why")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    args = ap.parse_args()
    source, build = os.path.realpath(args.source), os.path.realpath(args.build)
    corpus = os.path.realpath(os.environ.get("SUBDIVBENCH_DATASETS") or os.path.join(source, "..", "shared", "datasets"))
    work = tempfile.mkdtemp(prefix="sdb-bundle-test-")
    try:
        made = os.path.join(build, "gpu-bundle-test")
        make_bundle(source, build, made)
        check_ldd(made)
        bundle = os.path.join(work, "elsewhere", "gpu-bundle")
        shutil.copytree(made, bundle, symlinks=True)
        shutil.rmtree(made)
        home, out, debug = os.path.join(work, "home"), os.path.join(work, "out"), os.path.join(work, "ld", "libs")
        os.makedirs(home)
        os.makedirs(os.path.dirname(debug))
        hide = []
        for d in sorted(p for p in (corpus, source, build) if os.path.isdir(p)):
            if not any(d == h or d.startswith(h + os.sep) for h in hide):
                hide.append(d)  # a folder inside one already hidden is hidden with it
        check(not any(work.startswith(h + os.sep) for h in hide), f"the test's folder {work} lies in a folder it hides")
        probe = subprocess.run(["unshare", "--map-root-user", "--mount", "true"], capture_output=True, text=True)
        check(probe.returncode == 0, "cannot hide the corpus and the source tree: unshare --map-root-user --mount "
                                     f"refused ({probe.stderr.strip()}); this test needs user and mount namespaces")
        files_before = listing(bundle)
        output = run_killed_then_resumed(hide, bundle, home, debug, out)
        check_results(bundle, out, output)
        check_libraries(bundle, debug)
        check(os.listdir(home) == [], f"the run wrote into HOME: {os.listdir(home)}")
        check(listing(bundle) == files_before, "the run changed the bundle")
        print(f"HOME and the bundle unchanged ({len(files_before)} files); hidden: {', '.join(hide)}")
        check_report_without_matplotlib(bundle, out, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("PASS")


if __name__ == "__main__":
    main()
