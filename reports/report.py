#!/usr/bin/python3
"""Writes report.md and a self-contained report.html from results files, for a reader with a minute:
the summary first (per mesh the fastest scheme per backend and its ratio to its peer, paired where
the run paired it), then validation at a glance, plots, pictures, the papers' tables and every row.
With --history, the files are one per commit and the report is the gate's view across them.

Run by `subdivbench report` (reports/report.cpp), which has read and validated every input and
writes into a temporary folder it moves into place only when this script succeeded.
"""
import argparse
import json
import os
import re
import sys

import report_html as H
from report_data import Results, attach_bounds, cpu_implementation, load_results, fmt, spec_of
from report_history import History, verdict_lines
from report_overview import load_overview, scheme_table_html, scheme_table_md, tradeoff_figures
try:
    from report_plots import cost_growth, deviation_distributions, history_plot, label_backends, rate_grid
    NO_PLOTS = ""
except ImportError as missing:  # a GPU machine's python3 may lack matplotlib: the report without plots
    NO_PLOTS = (f"No plots: {missing} (python3-matplotlib is not installed here); `subdivbench report --in "
                "results.json` on a machine with it draws them.")
from report_summary import (fastest, fastest_lines, gpu_lines, limit_table, matrix, scheme_lines, validation_grid,
                            validation_sentence)

READING = ("Each cell is the run at the level nearest 1 M output triangles (the paired level where the run paired "
           "it): triangle rate in M triangles/s; its ratio to the scheme's peer (above 1: faster than the peer), "
           "the median of paired rounds with their range and count where the run paired it, else marked single "
           "pass (each row measured once with other work around it: read it as a hint, not a figure); "
           "the rate is the paired rounds' median where the run paired the cell; &#10003; closed = no open edge and no ray crack; p95 = the 95th percentile of the distance from the "
           "input's limit surface in % of the local face size. The fastest per mesh and backend is outlined.")


def comparison(args, plot_dir):
    data = load_results(args.inputs[0])
    overview = load_overview(args.overview)
    attach_bounds(data, overview)
    results = Results(data, args.scheme_order, overview)
    m = matrix(results)
    fast = fastest_lines(results, m)
    verdicts = scheme_lines(results, m)
    invalid, validity = validation_sentence(results)
    grid = validation_grid(results)
    if not NO_PLOTS:
        label_backends(results.machine)
    plots = [] if NO_PLOTS else [p for p in (rate_grid(results, plot_dir), cost_growth(results, plot_dir),
                                             deviation_distributions(results, plot_dir)) if p]
    first = [] if NO_PLOTS else tradeoff_figures(overview, results.schemes, plot_dir)
    manifest = None
    if args.pictures:
        with open(args.pictures) as f:
            manifest = json.load(f)
    papers = []
    for path in args.paper:
        with open(path, encoding="utf-8") as f:  # checked UTF-8 by reports/report_inputs.cpp
            papers.append((path, f.read()))
    write_comparison_html(os.path.join(args.out, "report.html"), results, m, fast, verdicts, (invalid, validity), grid,
                          plots, manifest, args.pictures, (papers, args.papers_note), args.merged_from,
                          (overview, first))
    write_comparison_md(os.path.join(args.out, "report.md"), results, m, fast, verdicts, validity, plots, manifest,
                        (papers, args.papers_note),
                        (overview, first))


def write_comparison_html(path, results, m, fast, verdicts, validation, grid, plots, manifest, manifest_path, papers,
                          merged_from, first_screen):
    invalid, validity = validation
    overview, first = first_screen
    papers, papers_note = papers
    body = [
        "<section id='overview'><div class='figures-row'>" + "".join(H.figure(p) for p in first) + "</div>",
        (f"<p>{H.e(NO_PLOTS)}</p>" if NO_PLOTS else ""),
        "<h3>Per scheme</h3>", scheme_table_html(overview, results.schemes), "</section>",
        "<section id='summary'><h2>Summary</h2>",
        f"<p class='lede{' bad' if invalid else ''}'>{H.e(validity)}</p>",
        (f"<p class='lede bad'>Part of a sweep only: {H.e(merged_from)}.</p>" if "MISSING" in merged_from else ""),
        f"<h3>Matrix: meshes &times; schemes, per backend</h3><p class='reading'>{READING}</p>",
        f"<div id='summary-matrix'>{H.summary_matrix(results, m, fastest)}</div>",
        "<h3>Fastest per mesh</h3>", H.sentences(fast),
        "<h3>Where each scheme wins and loses against its peer</h3>", H.sentences(verdicts, results.schemes),
        *gpu_section_html(results), "</section>",
        "<section id='validation'><h2>Validation</h2>",
        "<p>One chip per level: <span class='chip good'>ok</span> closed (or open input) with no crack and within the "
        "scheme's deviation bound on every backend; <span class='chip bad'>bad</span> an open edge, a crack, the bound "
        "exceeded or a failure on some backend; <span class='chip grey'>?</span> not checked; "
        "<span class='chip na'>n/a</span> not run (unsupported). Hover a chip for the figures.</p>",
        H.validation_matrix(grid, results.meshes(), results.schemes),
        "<h3>Against the input's limit surface</h3>", H.limit_matrix(limit_table(results), results.meshes(), results.schemes),
        "</section>",
        "<section id='plots'><h2>Plots</h2>", *[H.figure(p) for p in plots],
        (f"<p>{H.e(NO_PLOTS)}</p>" if NO_PLOTS else ""), "</section>",
        "<section id='pictures'><h2>Pictures</h2>", H.pictures_section(manifest, manifest_path), "</section>",
        "<section id='papers'><h2>Paper tables</h2>", H.paper_section(papers, results.machine, papers_note), "</section>",
        "<section id='paired'><h2>Paired cells</h2>", cpu_implementation_note(results), H.paired_table(results),
        "</section>",
        "<section id='rows'><h2>Every row</h2>",
        "<p>Ratios here are single pass (each row once); sort by a header, filter by scheme, backend and mesh.</p>",
        cpu_implementation_note(results),
        H.rows_table(results), "</section>"]
    nav = [("overview", "Overview"), ("summary", "Summary"), ("validation", "Validation"), ("plots", "Plots"), ("pictures", "Pictures"),
           ("papers", "Paper tables"), ("paired", "Paired cells"), ("rows", "Every row")]
    with open(path, "w") as f:
        f.write(H.page("subdivbench report", H.machine_words(results.machine, results.created, H.e(merged_from)),
                       nav, "\n".join(body)))


GPU_READING = ("Each scheme's GPU row against its own cpu-mt row on the same mesh and level, timed in the same "
               "paired rounds: the triangle rate's ratio (GPU time: the kernel's timestamps; below 1: the device path "
               "is slower than the CPU path on this machine).")


def gpu_section_html(results):
    lines = gpu_lines(results)
    if not lines:
        return []
    return ["<h3>GPU against the same scheme's CPU</h3>", f"<p class='reading'>{H.e(gpu_reading(results))}</p>",
            H.sentences(lines, results.schemes)]


def cpu_implementation_note(results):
    """One line above a table whose rows name a backend that ran on a CPU implementation of its API."""
    labels = [f"{b} rows ran on {cpu_implementation(results.machine, b)}" for b in results.backends()
              if cpu_implementation(results.machine, b)]
    return f"<p class='reading'>{H.e('; '.join(labels))}.</p>" if labels else ""


MD_SPECIAL = re.compile(r"([\\`*_\[\]|~])")


def md(text):
    """Text from data (a mesh's file name, a scheme's message) as Markdown that shows it as it is:
    HTML's three characters as entities (a renderer would take <img ...> as markup), the
    punctuation Markdown reads inside a line escaped (a | would end a table cell, * and _ start
    emphasis, [ a link), line breaks as spaces."""
    text = H.html.escape(str(text), quote=False).replace("\r", " ").replace("\n", " ")
    return MD_SPECIAL.sub(r"\\\1", text)


def gpu_reading(results):
    """GPU_READING, and what the device is where it is a CPU implementation (lavapipe, llvmpipe)."""
    labels = [f"{b}: {cpu_implementation(results.machine, b)}." for b in ("vulkan", "opengl")
              if cpu_implementation(results.machine, b)]
    return " ".join([GPU_READING] + labels)


def md_cell(cell):
    if not cell.ok:
        return md(cell.row["status"])
    ratio = "anchor" if not cell.peer else "no peer row"
    if cell.ratio is not None:
        if cell.paired:
            lo, hi, n = cell.ratio_range()
            ratio = f"{cell.ratio:.2f}x ({lo:.2f}-{hi:.2f}, {n} rounds)"
        else:
            ratio = f"{cell.ratio:.2f}x single pass"
    return f"{fmt(cell.rate)} Mtri/s, {ratio}"


def write_comparison_md(path, results, m, fast, verdicts, validity, plots, manifest, papers, first_screen):
    overview, first = first_screen
    papers, papers_note = papers
    out = ["# subdivbench report", "", H.machine_words(results.machine, results.created).replace("<code>", "`")
           .replace("</code>", "`"), ""]
    out += [f"![{md(p.alt)}](plots/{p.name})\n\n{md(p.caption)}\n" for p in first]
    out += ["### Per scheme", ""] + scheme_table_md(overview, results.schemes, md)
    out += ["", "## Summary", "", validity, "", "### Fastest per mesh", ""]
    for mesh, parts in fast:
        out += [f"- **{md(mesh)}**"] + [f"  - {md(p)}" for p in parts]
    out += ["", "### Where each scheme wins and loses against its peer", ""]
    out += [f"- **{md(spec)}**: {md(text)}" for spec, text in verdicts]
    gpu = gpu_lines(results)
    if gpu:
        out += ["", "### GPU against the same scheme's CPU", "", gpu_reading(results), ""]
        out += [f"- **{md(spec)}**: {md(text)}" for spec, text in gpu]
    for backend, per_mesh in m.items():
        specs = [s for s in results.specs(backend) if any(s in c for c in per_mesh.values())]
        label = cpu_implementation(results.machine, backend)
        out += ["", f"### {md(backend)}" + (f" (on {md(label)})" if label else ""), "",
                "| mesh | " + " | ".join(md(s) for s in specs) + " |", "|---" * (len(specs) + 1) + "|"]
        for mesh, cells in per_mesh.items():
            best = fastest(cells)
            out.append(f"| {md(mesh)} | " + " | ".join(
                (f"**{md_cell(cells[s])}**" if s == best else md_cell(cells[s])) if s in cells else "" for s in specs) + " |")
    out += ["", "## Against the input's limit surface", "", H.LIMIT_READING, ""]
    limits = limit_table(results)
    meshes = sorted({m for per_mesh in limits.values() for m in per_mesh})
    out += ["| scheme | " + " | ".join(md(m) for m in meshes) + " |", "|---" * (len(meshes) + 1) + "|"]
    out += [f"| {md(spec)} | " + " | ".join(md(per_mesh.get(m, "")) for m in meshes) + " |" for spec, per_mesh in limits.items()]
    out += ["", "## Plots", ""] + [f"![{md(p.title)}](plots/{p.name})\n\n{md(p.caption)}\n" for p in plots]
    out += [NO_PLOTS, ""] if NO_PLOTS else []
    out += ["## Pictures", ""]
    if manifest and manifest.get("available"):
        out.append(f"{len(manifest.get('pictures', []))} pictures in pictures/ (see report.html).")
    else:
        out.append("No pictures: " + md((manifest or {}).get("reason") or "the run wrote no pictures/pictures.json") + ".")
    out += ["", "## Paper tables", ""] + ([md(papers_note), ""] if papers_note else [])
    if not papers and not papers_note:
        out += ["No paper table in this report: `subdivbench report --paper results/paper/ID.md` includes them.", ""]
    for p, text in papers:
        out += [text.replace("\n#", "\n###"), ""]
    out += ["## Every row", "", "| " + " | ".join(c[0] for c in H.ROW_COLUMNS) + " |", "|---" * len(H.ROW_COLUMNS) + "|"]
    for r in sorted(results.rows, key=lambda r: (results.schemes.key(spec_of(r)), r["backend"], r["mesh"], r["level"])):
        out.append("| " + " | ".join(md_row_cells(r, results)) + " |")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def md_row_cells(r, results):
    """The Every-row table's cells as the HTML has them, for the Markdown."""
    cells = re.findall(r"<td[^>]*>(.*?)</td>", H.row_html(r, results))
    return [md(H.html.unescape(c)) for c in cells]


def history(args, plot_dir):
    files = [(name, load_results(path)) for name, path in zip(args.names or args.inputs, args.inputs)]
    h = History(args.history, [n for n, _ in files], args.scheme_order, [r for _, d in files for r in d["runs"]])
    plot = None if NO_PLOTS else history_plot(h, plot_dir)
    first = files[-1][1]
    body = ["<section id='history'><h2>Gated benchmarks per commit</h2>",
            f"<p class='lede'>{len(files)} results files, oldest first: {H.e(', '.join(h.labels))}. Each benchmark's "
            "time is divided by its normaliser's in the same round (its peer's, as the gate does; the write probe's for "
            "the anchors), so a busy machine cancels out; a cell is marked where the change from the previous commit "
            "is beyond the gate's threshold and its U test calls it significant.</p>",
            H.sentences(verdict_lines(h)), H.figure(plot), H.history_table(h), "</section>"]
    with open(os.path.join(args.out, "report.html"), "w") as f:
        f.write(H.page("subdivbench history", H.machine_words(first.get("machine"), first.get("created", "")),
                       [("history", "History")], "\n".join(body)))
    lines = ["# subdivbench history", "", f"Commits, oldest first: {md(', '.join(h.labels))}", ""]
    lines += [f"- **{md(label)}**: {md(text)}" for label, text in verdict_lines(h)] + [""]
    if plot:
        lines += [f"![{md(plot.title)}](plots/{plot.name})", ""]
    lines += ["| benchmark | normalised by | " + " | ".join(md(x) for x in h.labels) + " |", "|---" * (len(h.labels) + 2) + "|"]
    for name in h.benchmarks():
        cells = []
        for i, s in enumerate(h.series(name)):
            ch = h.change(name, i)
            cells.append("–" if not s else f"{s.median:.3g}" + (f" ({ch[0]:+.0%}, {ch[1]})" if ch else ""))
        lines.append(f"| {md(name)} | {md(h.normaliser(name))} | " + " | ".join(cells) + " |")
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, help="folder for report.md, report.html and plots/")
    ap.add_argument("--history", default="", help="history.json (reports/history.cpp): the inputs are one results file per commit, oldest first")
    ap.add_argument("--schemes", default="", help="the registry's schemes in its order, as name=role,... (the colours)")
    ap.add_argument("--pictures", default="", help="pictures/pictures.json")
    ap.add_argument("--paper", action="append", default=[], help="a paper table's Markdown (repeatable)")
    ap.add_argument("--names", nargs="*", help="the inputs' names as the user gave them (history)")
    ap.add_argument("--merged-from", default="", help="which files (shards) the one input was merged from")
    ap.add_argument("--papers-note", default="", help="why the report has no (or not every) paper table, one line")
    ap.add_argument("--overview", default="", help="the first screen's figures (reports/overview.cpp)")
    ap.add_argument("inputs", nargs="+")
    args = ap.parse_args()
    args.scheme_order = [tuple(s.split("=", 1)) if "=" in s else (s, "") for s in args.schemes.split(",") if s]
    plot_dir = os.path.join(args.out, "plots")
    os.makedirs(plot_dir, exist_ok=True)
    (history if args.history else comparison)(args, plot_dir)


if __name__ == "__main__":
    try:
        main()
    except (OSError, KeyError, TypeError, ValueError) as err:
        # One line, not a traceback: the harness adds the folder and the exit status.
        sys.exit(f"report: {type(err).__name__}: {err}")
