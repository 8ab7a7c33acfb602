#!/usr/bin/python3
"""Opens a report generated from the test fixture in headless Chromium (Debian's `chromium`, which
`./scripts/setup --test` installs) and fails on any console error, a missing summary matrix, a
table that does not sort and filter, or missing pictures; saves a screenshot for a person to look at.

Exit 77 (ctest's SKIP_RETURN_CODE) when chromium is not installed.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

SKIP = 77
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-extensions", "--no-first-run",
                  "--disable-background-networking", "--disable-sync", "--disable-component-update",
                  "--disable-default-apps", "--mute-audio", "--hide-scrollbars"]
# Chromium logs every console message on stderr as "[...:INFO:CONSOLE:line] "text", source: ...",
# console.error and uncaught exceptions alike (Debian's chromium 156: all at INFO). The report
# writes nothing to the console, so any console line is a failure; console.error calls and
# uncaught errors are also counted by the page itself (report_html.ERROR_TRAP).
CONSOLE_ERROR = re.compile(r":CONSOLE[:(]|Uncaught ")


def chromium(binary, profile, args, timeout=180):
    argv = [binary, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", *args]
    return subprocess.run(argv, capture_output=True, text=True, timeout=timeout)


def check_page(binary, profile, url):
    """What is wrong with the page at `url` once Chromium has run its scripts (#selftest)."""
    problems = []
    dom = chromium(binary, profile, ["--virtual-time-budget=5000", "--dump-dom", url + "#selftest"])
    if dom.returncode != 0:
        problems.append(f"chromium --dump-dom exited {dom.returncode}: {dom.stderr.strip()[-400:]}")
    errors = [line for line in dom.stderr.splitlines() if CONSOLE_ERROR.search(line)]
    problems += [f"console: {line}" for line in errors]
    html = dom.stdout
    found = re.findall(r'<pre id="selftest">(.*?)</pre>', html, re.S)
    selftest = found[-1] if found else None  # the page appends it last
    if not selftest:
        problems.append("the page's self-test did not run (no <pre id=\"selftest\">)")
    else:
        if not selftest.startswith("selftest ok"):
            problems.append(selftest.splitlines()[0])
        if "console errors: 0" not in selftest:
            problems.append("errors recorded by the page: " + selftest.replace("\n", " | "))
    if not re.search(r'<table class="matrix" id="summary-matrix-[a-z-]+"', html):
        problems.append("no summary matrix")
    if not re.search(r'<table class="rows sortable filterable" id="all-rows"', html) or 'title="sort by scheme"' not in html:
        problems.append("no sortable table (or its script did not run)")
    if not (re.search(r'<img class="picture-shaded"[^>]*src="data:image/png;base64,', html)
            or 'class="pictures-unavailable"' in html):
        problems.append("neither pictures nor the sentence saying why there are none")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--subdivbench", required=True)
    ap.add_argument("--fixtures", required=True, help="reports/testdata")
    ap.add_argument("--out", required=True, help="build/chromium-report")
    args = ap.parse_args()
    binary = shutil.which("chromium")
    if not binary:
        print("chromium is not installed (./scripts/setup --test installs Debian's chromium): skipped")
        return SKIP
    out = os.path.abspath(args.out)
    report_dir = os.path.join(out, "report")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    subprocess.run([args.subdivbench, "report", "--in", os.path.join(args.fixtures, "sample", "results.json"),
                    "--paper", os.path.join(args.fixtures, "paper", "table.md"), "--out", report_dir], check=True)
    url = "file://" + os.path.join(report_dir, "report.html")
    problems = check_page(binary, os.path.join(out, "profile"), url)
    screenshot = os.path.join(out, "report-screenshot.png")
    shot = chromium(binary, os.path.join(out, "profile"), ["--window-size=1400,2600", f"--screenshot={screenshot}", url])
    problems += [f"console (screenshot): {line}" for line in shot.stderr.splitlines() if CONSOLE_ERROR.search(line)]
    if not os.path.isfile(screenshot) or open(screenshot, "rb").read(8) != b"\x89PNG\r\n\x1a\n":
        problems.append(f"no screenshot written (chromium exited {shot.returncode})")
    shutil.rmtree(os.path.join(out, "profile"), ignore_errors=True)

    for p in problems:
        print(f"chromium_test: {p}")
    if problems:
        return 1
    print(f"report.html opened in {binary} with no console error; summary matrix, sortable table and pictures "
          f"present; screenshot: {screenshot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
