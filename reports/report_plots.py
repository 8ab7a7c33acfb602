"""The report's plots (matplotlib, Agg). One colour per scheme and one marker and line style per
backend in every plot (report_data.PALETTE, BACKEND_STYLE); legends sit outside the axes."""
import base64
import io
import math
import os
import random

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from report_data import BACKEND_STYLE, cpu_implementation, finite, group, median, spec_of, timing  # noqa: E402

# The machine whose backends the legends and panel titles name (a CPU implementation of a GPU API
# is labelled in every plot): set by each plot from its results.
LABELLED = {}


def backend_label(b):
    return f"{b} (on a CPU implementation)" if LABELLED.get(b) else b


def label_backends(machine):
    LABELLED.clear()
    LABELLED.update({b: bool(cpu_implementation(machine, b)) for b in ("vulkan", "opengl")})

DPI = 90


class Plot:
    """A saved figure: its file under plots/ (for the Markdown) and its bytes (for the HTML)."""

    def __init__(self, name, title, caption, png):
        self.name, self.title, self.caption, self.png = name, title, caption, png
        self.alt = title  # what the figure shows, for a reader who cannot see it

    def data_uri(self):
        return "data:image/png;base64," + base64.b64encode(self.png).decode()


def save(fig, plot_dir, name, title, caption):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    with open(os.path.join(plot_dir, name), "wb") as f:
        f.write(buf.getvalue())
    return Plot(name, title, caption, buf.getvalue())


def style(backend):
    return BACKEND_STYLE.get(backend, ("x", "-"))


def legend_handles(schemes, specs, backends):
    handles = [Line2D([], [], color=schemes.colour_of(s), lw=2.5, label=s) for s in specs]
    handles += [Line2D([], [], color="#555555", marker=style(b)[0], linestyle=style(b)[1], label=backend_label(b))
                for b in backends]
    return handles


def outside_legend(fig, handles, title="scheme / backend"):
    fig.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 0.98), fontsize=8, title=title,
               title_fontsize=8, frameon=False)


def ok_rows(results):
    return [r for r in results.rows if r["status"] == "ok" and r["triangles"] > 0 and finite(r["triangle_rate_mtris"])
            and r["triangle_rate_mtris"] > 0]


# A row of panels per mesh is readable, and drawn in seconds, for a handful of meshes; a sweep of
# the corpus has thousands (2,500 meshes did not finish in 180 s). Beyond this many the plot shows
# the meshes with the most schemes run on them, and says so; every row stays in the tables.
RATE_GRID_MESHES = 8


def plot_text(text):
    """Text from data in a plot: matplotlib reads $...$ as mathematics (a mesh named a$b$c.obj
    would fail the report), so every $ is escaped."""
    return str(text).replace("$", r"\$")


def rate_grid_meshes(rows):
    by_mesh = group(rows, lambda r: r["mesh"])
    ranked = sorted(by_mesh, key=lambda m: (-len({spec_of(r) for r in by_mesh[m]}), -len(by_mesh[m]), m))
    return sorted(ranked[:RATE_GRID_MESHES]), len(by_mesh)


def rate_grid(results, plot_dir):
    """Triangle rate against output size: a row of panels per mesh, one panel per backend."""
    rows = ok_rows(results)
    if not rows:
        return None
    meshes, all_meshes = rate_grid_meshes(rows)
    rows = [r for r in rows if r["mesh"] in set(meshes)]
    backends = [b for b in results.backends() if any(r["backend"] == b for r in rows)]
    fig, axes = plt.subplots(len(meshes), len(backends), figsize=(3.3 * len(backends), 2.5 * len(meshes)),
                             sharex=True, sharey=True, squeeze=False)
    by_cell = group(rows, lambda r: (r["mesh"], r["backend"]))
    specs = set()
    for i, mesh in enumerate(meshes):
        for j, backend in enumerate(backends):
            ax = axes[i][j]
            for spec, pts in sorted(group(by_cell.get((mesh, backend), []), spec_of).items(),
                                    key=lambda kv: results.schemes.key(kv[0])):
                specs.add(spec)
                pts.sort(key=lambda r: r["triangles"])
                marker, line = style(backend)
                ax.plot([r["triangles"] for r in pts], [r["triangle_rate_mtris"] for r in pts], marker=marker,
                        linestyle=line, color=results.schemes.colour_of(spec), ms=4, lw=1.3)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="major", alpha=0.3)
            if i == 0:
                ax.set_title(backend_label(backend), fontsize=10)
            if j == 0:
                ax.set_ylabel(f"{plot_text(mesh)}\nM triangles/s", fontsize=8)
            if i == len(meshes) - 1:
                ax.set_xlabel("output triangles", fontsize=8)
            ax.tick_params(labelsize=7)
    outside_legend(fig, legend_handles(results.schemes, sorted(specs, key=results.schemes.key), backends))
    fig.tight_layout()
    shown = (f" {len(meshes)} of the {all_meshes:,} meshes: those with the most schemes run on them (every row is in "
             "the tables)." if len(meshes) < all_meshes else "")
    return save(fig, plot_dir, "rate.png", "Triangle rate against output size",
                "One row of panels per mesh, one panel per backend; single-pass figures (each row measured once)." + shown)


def cost_mesh(results):
    """The mesh with the most schemes run on it: the cost-growth plot's."""
    counts = group(ok_rows(results), lambda r: r["mesh"])
    if not counts:
        return None
    return max(sorted(counts), key=lambda m: (len({spec_of(r) for r in counts[m]}), len(counts[m])))


def cost_growth(results, plot_dir):
    """Time against output triangles on one mesh, log-log, every scheme and backend, with the
    time the machine needs just to write the output (the write-bandwidth bound) as a line."""
    mesh = cost_mesh(results)
    if mesh is None:
        return None
    rows = [r for r in ok_rows(results) if r["mesh"] == mesh]
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    specs, backends = set(), set()
    for (spec, backend), pts in sorted(group(rows, lambda r: (spec_of(r), r["backend"])).items(),
                                       key=lambda kv: results.schemes.key(kv[0][0])):
        specs.add(spec)
        backends.add(backend)
        pts.sort(key=lambda r: r["triangles"])
        marker, line = style(backend)
        ax.plot([r["triangles"] for r in pts], [timing(r)["median"] for r in pts], marker=marker, linestyle=line,
                color=results.schemes.colour_of(spec), ms=4, lw=1.3)
    handles = legend_handles(results.schemes, sorted(specs, key=results.schemes.key),
                             sorted(backends, key=lambda b: list(BACKEND_STYLE).index(b) if b in BACKEND_STYLE else 9))
    handles += bandwidth_bounds(ax, rows, results.machine)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("output triangles")
    ax.set_ylabel("median time (ms)")
    ax.set_title(f"Cost growth on {plot_text(mesh)}", fontsize=11)
    ax.grid(True, which="major", alpha=0.3)
    outside_legend(fig, handles, "scheme / backend / bound")
    fig.tight_layout()
    return save(fig, plot_dir, "cost_growth.png", f"Cost growth on {mesh}",
                "Time against output triangles, log-log; the black lines are the time to write the output at the "
                "machine's measured write bandwidth (bytes per triangle: the median of these rows'), "
                "a floor no scheme can beat on that many threads.")


def bandwidth_bounds(ax, rows, machine):
    per_tri = [r["bytes_out"] / r["triangles"] for r in rows if r.get("bytes_out", 0) > 0]
    if not per_tri:
        return []
    bpt = median(per_tri)
    lo = min(r["triangles"] for r in rows)
    hi = max(r["triangles"] for r in rows)
    xs = [lo, hi]
    handles = []
    for key, words, line in (("write_bandwidth_gbs", "one thread", "-"), ("write_bandwidth_mt_gbs", "all threads", "--")):
        gbs = machine.get(key, 0)
        if finite(gbs) and gbs > 0:
            ys = [x * bpt / (gbs * 1e9) * 1e3 for x in xs]
            ax.plot(xs, ys, color="black", linestyle=line, lw=1.6)
            handles.append(Line2D([], [], color="black", linestyle=line, lw=1.6,
                                  label=f"write bound, {words}: {gbs:.1f} GB/s x {bpt:.0f} B/triangle"))
    return handles


def deviation_distributions(results, plot_dir):
    """Per paper scheme (peers left out: they are the reference's own library), the distribution
    over its rows of the deviation from the input's limit surface: max and 95th percentile."""
    rows = [r for r in results.rows if r["status"] in ("ok", "failed") and results.schemes.is_paper_scheme(spec_of(r))
            and r.get("deviation") and finite(r["deviation"].get("pos_max_pct"))]
    if not rows:
        return None
    by_spec = group(rows, spec_of)
    specs = sorted(by_spec, key=results.schemes.key)
    fig, axes = plt.subplots(1, 2, figsize=(10, 0.45 * len(specs) + 1.6), sharey=True, squeeze=False)
    rng = random.Random(1)  # a fixed jitter: the same input draws the same picture
    backends = set()
    for ax, key, label in ((axes[0][0], "pos_max_pct", "max"), (axes[0][1], "pos_p95_pct", "95th percentile")):
        data = [[max(r["deviation"][key], 1e-12) for r in by_spec[s] if finite(r["deviation"].get(key))] for s in specs]
        box = ax.boxplot(data, vert=False, widths=0.6, patch_artist=True, showfliers=False,
                         medianprops={"color": "black"})
        for patch, s in zip(box["boxes"], specs):
            patch.set_facecolor(results.schemes.colour_of(s))
            patch.set_alpha(0.35)
        for i, s in enumerate(specs):
            # One line of dots per scheme and backend: one per row would be thousands of artists.
            for backend, pts in sorted(group([r for r in by_spec[s] if finite(r["deviation"].get(key))],
                                             lambda r: r["backend"]).items()):
                backends.add(backend)
                ax.plot([max(r["deviation"][key], 1e-12) for r in pts], [i + 1 + rng.uniform(-0.2, 0.2) for _ in pts],
                        marker=style(backend)[0], color=results.schemes.colour_of(s), ms=4, alpha=0.8, linestyle="none")
        ax.set_xscale("log")
        ax.set_title(f"deviation, {label}", fontsize=10)
        ax.set_xlabel("% of the local face size", fontsize=8)
        ax.grid(True, axis="x", which="major", alpha=0.3)
    axes[0][0].set_yticks(range(1, len(specs) + 1))
    axes[0][0].set_yticklabels([plot_text(s) for s in specs], fontsize=8)
    handles = [Line2D([], [], color="#555555", marker=style(b)[0], linestyle="none", label=backend_label(b))
               for b in sorted(backends, key=lambda b: list(BACKEND_STYLE).index(b) if b in BACKEND_STYLE else 9)]
    outside_legend(fig, handles, "backend")
    fig.tight_layout()
    return save(fig, plot_dir, "deviation.png", "Deviation from the input's limit surface (paper schemes)",
                "Per scheme, over all its rows (meshes, levels, backends): the distance from each output vertex to the "
                "limit surface of the input at the same surface coordinate, or at the nearest point for a scheme whose "
                "vertices have no coordinate on the input (geometry-image); boxes span the middle half, dots are rows.")


def history_plot(history, plot_dir):
    """Each gated benchmark's normalised time per commit: median and the rounds' range."""
    names = history.benchmarks()
    if not names:
        return None
    cols = min(3, len(names))
    nrows = math.ceil(len(names) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 2.6 * nrows), squeeze=False, sharex=True)
    xs = list(range(len(history.labels)))
    for k, name in enumerate(names):
        ax = axes[k // cols][k % cols]
        series = history.series(name)
        colour = history.colour_of(name)
        pts = [(x, s) for x, s in zip(xs, series) if s]
        if pts:
            ax.errorbar([x for x, _ in pts], [s.median for _, s in pts],
                        yerr=[[s.median - s.low for _, s in pts], [s.high - s.median for _, s in pts]],
                        color=colour, marker="o", ms=4, capsize=3, lw=1.3)
        slower, faster = history.moved(name, "slower"), history.moved(name, "faster")
        for i, colour_mark in [(i, "#d32f2f") for i in slower] + [(i, "#2e8b57") for i in faster]:
            ax.plot([xs[i]], [series[i].median], marker="o", ms=11, mfc="none", mec=colour_mark, mew=2)
        flag = " - SLOWER" if slower else " - faster" if faster else ""
        ax.set_title(plot_text(name) + flag, fontsize=8, color="#d32f2f" if slower else "#2e8b57" if faster else "black",
                     fontweight="bold" if flag else "normal")
        ax.set_ylabel(f"time / {history.normaliser(name)}", fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.tick_params(labelsize=7)
    for k in range(len(names), nrows * cols):
        axes[k // cols][k % cols].set_visible(False)
    for row in axes:
        for ax in row:
            ax.set_xticks(xs)
            ax.set_xticklabels(history.labels, rotation=30, ha="right", fontsize=7)
            ax.tick_params(labelbottom=True)
    fig.tight_layout()
    return save(fig, plot_dir, "history.png", "Normalised time per commit",
                "Each gated benchmark's time over its normaliser's in the same round (the gate's figure), "
                "median over rounds with the range as bars; up is slower.")
