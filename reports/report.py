#!/usr/bin/python3
"""Writes report.md and a self-contained report.html from one or more results.json files.

Plots are made with matplotlib (Debian's python3-matplotlib) and embedded in the HTML as
base64 PNG; the Markdown links the same PNGs from DIR/plots/.
"""
import argparse
import base64
import html
import io
import json
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMA = 1


def load(paths):
    machine, created, rows = None, None, []
    for p in paths:
        with open(p) as f:
            data = json.load(f)
        if data.get("schema") != SCHEMA:
            sys.exit(f"report: {p}: unknown results schema {data.get('schema')} (this report reads {SCHEMA})")
        machine = machine or data.get("machine", {})
        created = created or data.get("created", "")
        rows.extend(nan_for_null(r) for r in data.get("runs", []))
    return machine, created, rows


def nan_for_null(row):
    """JSON has no NaN: the harness writes it as null. Read back as NaN so arithmetic and plots
    treat it as a missing figure rather than failing."""
    def fix(v):
        if isinstance(v, dict):
            return {k: fix(x) for k, x in v.items()}
        if isinstance(v, list):
            return [fix(x) for x in v]
        return float("nan") if v is None else v
    keep_null = {"deviation", "gpu_time_ms", "peer_backend", "deviation_bound"}
    return {k: (v if v is None and k in keep_null else fix(v)) for k, v in row.items()}


def peer_rates(rows):
    """Triangle rate per (scheme, mesh, backend, tessellation) of the ok rows."""
    return {(r["scheme"], r["mesh"], r["backend"], r["tessellation"]): r["triangle_rate_mtris"]
            for r in rows if r["status"] == "ok"}


def peer_of(r, rates):
    """The row's peer (the scheme's SchemeInfo, recorded in the row) and its rate at the same mesh and
    tessellation on the row's peer backend; (name, None) when that row is not in the file."""
    peer, backend = r.get("peer") or "", r.get("peer_backend") or ""
    if not peer or not backend:
        return None, None
    return f"{peer} ({backend})", rates.get((peer, r["mesh"], backend, r["tessellation"]))


def time_of(r):
    t = r.get("gpu_time_ms") or r["time_ms"]
    return t["median"]


def fmt(x, digits=3):
    if x is None:
        return "–"
    if isinstance(x, (int,)) and not isinstance(x, bool):
        return f"{x:,}"
    return f"{x:.{digits}g}"


COLUMNS = ["scheme", "backend", "mesh", "level", "tess", "triangles", "median ms", "Mtri/s", "× peer", "peer",
           "bw %", "open edges", "cracks / rays", "dev max %", "dev p95 %", "normal max °", "Hausdorff", "status"]


def table_rows(rows, rates):
    out = []
    for r in rows:
        dev = r.get("deviation") or {}
        wt = r.get("watertight", {})
        peer, peer_rate = peer_of(r, rates)
        ratio = r["triangle_rate_mtris"] / peer_rate if peer_rate and r["status"] == "ok" else None
        cracks = f"{wt.get('ray_cracks')} / {wt.get('rays'):,}" if wt.get("ray_cracks", -1) >= 0 else "–"
        status = r["status"] + (f": {r['message']}" if r.get("message") else "")
        out.append([r.get("spec") or r["scheme"], r["backend"], r["mesh"], str(r["level"]), str(r["tessellation"]), fmt(r["triangles"]),
                    fmt(time_of(r)) if r["status"] != "unsupported" else "–", fmt(r["triangle_rate_mtris"]),
                    fmt(ratio), peer or "–", fmt(100 * r.get("bandwidth_fraction", 0)),
                    fmt(wt.get("open_edges")) if wt.get("open_edges", -1) >= 0 else "–", cracks,
                    fmt(dev.get("pos_max_pct")), fmt(dev.get("pos_p95_pct")), fmt(dev.get("normal_max_deg")),
                    fmt(dev.get("hausdorff_rel")) if dev.get("hausdorff_rel", -1) >= 0 else "–", status])
    return out


def rate_plots(rows, plot_dir):
    """One plot per mesh: triangle rate against tessellation (segments per edge), a line per scheme/backend."""
    by_mesh = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r["status"] == "ok" and r["triangle_rate_mtris"] > 0:
            by_mesh[r["mesh"]][(r["scheme"], r["backend"])].append((r["tessellation"], r["triangle_rate_mtris"]))
    plots = []
    for mesh, lines in sorted(by_mesh.items()):
        fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
        for (scheme, backend), pts in sorted(lines.items()):
            pts.sort()
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=f"{scheme} ({backend})")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("segments per base-face edge (depth k: 2^k, rate N: N-1)")
        ax.set_ylabel("triangle rate (M tri/s)")
        ax.set_title(f"{mesh}: triangle rate")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        name = "rate_" + mesh.replace("/", "_") + ".png"
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        plt.close(fig)
        with open(os.path.join(plot_dir, name), "wb") as f:
            f.write(buf.getvalue())
        plots.append((mesh, name, base64.b64encode(buf.getvalue()).decode()))
    return plots


def deviation_plot(rows, plot_dir):
    pts = [(f"{r['scheme']}/{r['backend']}/{r['mesh']}/{r['level']}", r["deviation"]["pos_max_pct"],
            r["deviation"]["pos_p95_pct"]) for r in rows if r.get("deviation") and r["deviation"].get("pos_max_pct") is not None]
    if not pts:
        return None
    pts = pts[:60]
    fig, ax = plt.subplots(figsize=(8, max(3, 0.18 * len(pts))), dpi=100)
    y = range(len(pts))
    ax.barh(list(y), [max(p[1], 1e-9) for p in pts], label="max", alpha=0.6)
    ax.barh(list(y), [max(p[2], 1e-9) for p in pts], label="95th percentile", alpha=0.8)
    ax.set_yticks(list(y))
    ax.set_yticklabels([p[0] for p in pts], fontsize=6)
    ax.set_xscale("log")
    ax.set_xlabel("distance to the limit at the same SurfaceCoord (% of local face size)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    plt.close(fig)
    with open(os.path.join(plot_dir, "deviation.png"), "wb") as f:
        f.write(buf.getvalue())
    return "deviation.png", base64.b64encode(buf.getvalue()).decode()


def machine_lines(machine, created):
    m = machine or {}
    return [f"Created {created}",
            f"CPU: {m.get('cpu_model', '?')}, {m.get('cores', '?')} cores, {m.get('memory_gib', 0):.0f} GiB",
            f"Write bandwidth: {m.get('write_bandwidth_gbs', 0):.1f} GB/s one thread, "
            f"{m.get('write_bandwidth_mt_gbs', 0):.1f} GB/s all threads",
            f"Vulkan: {m.get('vulkan_device') or 'none'} {m.get('vulkan_driver', '')} {m.get('vulkan_api', '')}".rstrip(),
            f"Build: {m.get('compiler', '?')}, {m.get('build_type', '?')}, commit {m.get('git_commit', '?')}"]


def write_markdown(path, machine, created, table, plots, dev):
    with open(path, "w") as f:
        f.write("# subdivbench report\n\n")
        for line in machine_lines(machine, created):
            f.write(f"- {line}\n")
        f.write("\nTimes are medians over repetitions; vulkan rows use GPU timestamp time. `× peer` is the "
                "triangle rate over the row's peer's (the scheme's declared peer, on the backend named) on the "
                "same mesh and tessellation in this run, measured once each, not paired; "
                "`bw %` is the output bytes per second over the machine's write bandwidth.\n\n")
        f.write("## Runs\n\n| " + " | ".join(COLUMNS) + " |\n|" + "---|" * len(COLUMNS) + "\n")
        for row in table:
            f.write("| " + " | ".join(c.replace("|", "/") for c in row) + " |\n")
        f.write("\n## Triangle rate\n\n")
        for mesh, name, _ in plots:
            f.write(f"![{mesh}](plots/{name})\n\n")
        if dev:
            f.write(f"## Deviation from the OpenSubdiv limit\n\n![deviation](plots/{dev[0]})\n")


def write_html(path, machine, created, table, plots, dev):
    e = html.escape
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>subdivbench report</title><style>",
             "body{font-family:sans-serif;margin:2em;} table{border-collapse:collapse;font-size:12px;}",
             "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right;} td:nth-child(-n+3){text-align:left;}",
             ".failed{background:#fdd;} img{max-width:100%;} .plots img{width:640px;}</style></head><body>",
             "<h1>subdivbench report</h1><ul>"]
    parts += [f"<li>{e(line)}</li>" for line in machine_lines(machine, created)]
    parts.append("</ul><h2>Triangle rate</h2><div class='plots'>")
    for mesh, _, b64 in plots:
        parts.append(f"<img alt='{e(mesh)}' src='data:image/png;base64,{b64}'>")
    parts.append("</div>")
    if dev:
        parts.append(f"<h2>Deviation from the OpenSubdiv limit</h2><img alt='deviation' src='data:image/png;base64,{dev[1]}'>")
    parts.append("<h2>Runs</h2><table><tr>" + "".join(f"<th>{e(c)}</th>" for c in COLUMNS) + "</tr>")
    for row in table:
        cls = " class='failed'" if row[-1].startswith("failed") else ""
        parts.append(f"<tr{cls}>" + "".join(f"<td>{e(c)}</td>" for c in row) + "</tr>")
    parts.append("</table></body></html>")
    with open(path, "w") as f:
        f.write("\n".join(parts))


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True)
    ap.add_argument("inputs", nargs="+")
    args = ap.parse_args()
    machine, created, rows = load(args.inputs)
    plot_dir = os.path.join(args.out, "plots")
    os.makedirs(plot_dir, exist_ok=True)
    table = table_rows(rows, peer_rates(rows))
    plots = rate_plots(rows, plot_dir)
    dev = deviation_plot(rows, plot_dir)
    write_markdown(os.path.join(args.out, "report.md"), machine, created, table, plots, dev)
    write_html(os.path.join(args.out, "report.html"), machine, created, table, plots, dev)


if __name__ == "__main__":
    try:
        main()
    except (OSError, KeyError, TypeError, ValueError) as err:
        # One line, not a traceback: the harness adds the folder and the exit status.
        sys.exit(f"report: {type(err).__name__}: {err}")
