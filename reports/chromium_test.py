#!/usr/bin/python3
"""Opens reports generated from the test fixtures in headless Chromium (Debian's `chromium`, which
`./scripts/setup --test` installs), 1400 pixels wide, and fails on any console error, a page or
matrix wider than the window, a missing summary matrix, a table that does not sort and filter, or
missing pictures; on a real quick run's results (testdata/quick), also on a first screen that is
not the rate-against-deviation figure and the per-scheme table, or paper tables missing. Saves a
screenshot of each for a person to look at.

Exit 77 (ctest's SKIP_RETURN_CODE) when chromium is not installed.
"""
import argparse
import glob
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
WIDTH = 1400  # the window the matrices must fit without scrolling sideways (issue 42)


def chromium(binary, profile, args, timeout=180):
    argv = [binary, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", *args]
    return subprocess.run(argv, capture_output=True, text=True, timeout=timeout)


def check_page(binary, profile, url, papers=0):
    """What is wrong with the page at `url` once Chromium has run its scripts (#selftest); with
    `papers`, also its first screen and that many paper tables (first_screen_problems)."""
    problems = []
    dom = chromium(binary, profile, ["--virtual-time-budget=5000", f"--window-size={WIDTH},2600", "--dump-dom",
                                     url + "#selftest"])
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
    if f"window width: {WIDTH} px" not in (selftest or ""):
        problems.append(f"the page was not laid out {WIDTH} pixels wide, so its width was not checked")
    if papers:
        problems += first_screen_problems(html, papers)
    if not re.search(r'<table class="matrix" id="summary-matrix-[a-z-]+"', html):
        problems.append("no summary matrix")
    if not re.search(r'<table class="rows sortable filterable" id="all-rows"', html) or 'title="sort by scheme"' not in html:
        problems.append("no sortable table (or its script did not run)")
    if not (re.search(r'<img class="picture-shaded"[^>]*src="data:image/png;base64,', html)
            or 'class="pictures-unavailable"' in html):
        problems.append("neither pictures nor the sentence saying why there are none")
    return problems


def first_screen_problems(html, expected_papers):
    """Issue 42's first screen: under the title the speed-accuracy figure (its alt text saying what it
    shows), then the per-scheme table; the papers' tables each headed by its ID."""
    problems = []
    figure = re.search(r'<section id="overview">\s*<div class="figures-row"><figure><img class="plot" alt="([^"]*)" '
                       r'src="data:image/png;base64,', html)
    if not figure:
        problems.append("the report does not open with a figure")
    elif not figure.group(1).startswith("Triangle rate against deviation from the input's limit surface"):
        problems.append(f"the first figure's alt text does not say it is rate against deviation: {figure.group(1)[:120]}")
    summary = html.find('id="summary"')
    table = html.find('<table class="schemes" id="scheme-table">')
    if table < 0 or (summary >= 0 and table > summary):
        problems.append("no per-scheme table before the summary")
    elif not re.search(r'<table class="schemes" id="scheme-table">.*?<tbody>\s*<tr><th class="mesh">[^<]+</th><td>[0-9.]+ M tri/s',
                       html, re.S):
        problems.append("the per-scheme table has no row with a best rate")
    papers = re.findall(r'<div class="paper" data-file="[^"]+"><h3>([a-z0-9]+-[a-z0-9-]+)', html)
    if len(papers) != expected_papers:
        problems.append(f"{len(papers)} paper tables headed by their ID ({', '.join(papers)}), not {expected_papers}")
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
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    problems = []
    # The sample (pictures, a paired and a failed cell), then a real quick run with the eight quick
    # paper tables: its first screen, read by a person in the screenshot.
    quick_papers = sorted(glob.glob(os.path.join(args.fixtures, "quick", "paper", "*.md")))
    for name, inputs, papers, check_papers in (
            ("sample", [os.path.join(args.fixtures, "sample", "results.json")],
             [os.path.join(args.fixtures, "paper", "table.md")], 0),
            ("quick", [os.path.join(args.fixtures, "quick", "results.json")], quick_papers, len(quick_papers))):
        report_dir = os.path.join(out, name)
        argv = [args.subdivbench, "report", "--out", report_dir]
        for i in inputs:
            argv += ["--in", i]
        for p in papers:
            argv += ["--paper", p]
        subprocess.run(argv, check=True)
        url = "file://" + os.path.join(report_dir, "report.html")
        problems += [f"{name}: {p}" for p in check_page(binary, os.path.join(out, "profile"), url, check_papers)]
        screenshot = os.path.join(out, f"report-{name}-screenshot.png")
        shot = chromium(binary, os.path.join(out, "profile"), [f"--window-size={WIDTH},2600", f"--screenshot={screenshot}", url])
        problems += [f"{name}: console (screenshot): {line}" for line in shot.stderr.splitlines() if CONSOLE_ERROR.search(line)]
        if not os.path.isfile(screenshot) or open(screenshot, "rb").read(8) != b"\x89PNG\r\n\x1a\n":
            problems.append(f"{name}: no screenshot written (chromium exited {shot.returncode})")
    if len(quick_papers) != 8:
        problems.append(f"the quick fixture holds {len(quick_papers)} paper tables, not the eight registered")
    shutil.rmtree(os.path.join(out, "profile"), ignore_errors=True)

    for p in problems:
        print(f"chromium_test: {p}")
    if problems:
        return 1
    print(f"report.html opened in {binary} with no console error, {WIDTH} pixels wide without sideways scrolling; "
          f"summary matrix, sortable table and pictures present; the quick run's report opens with the rate against "
          f"deviation figure and the per-scheme table and holds its {len(quick_papers)} paper tables; screenshots in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
