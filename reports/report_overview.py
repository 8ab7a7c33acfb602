"""The report's first screen: per backend, triangle rate against deviation from the input's limit
surface with the Pareto front, and one row per scheme. Every figure here was computed by
`subdivbench report` (reports/overview.cpp) and arrives as overview.json; this module lays it out.
"""
import html
import json

MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "h", "*", "p"]


def e(text):
    return html.escape(str(text), quote=True)


def load_overview(path):
    if not path:
        return None
    with open(path) as f:
        return json.load(f)


def backend_title(b):
    """'vulkan on llvmpipe (LLVM 15.0.6, 256 bits), a CPU implementation of Vulkan, not a GPU' where
    the device is one (results.h cpu_implementation_words)."""
    label = b.get("cpu_implementation")
    return f"{b['backend']} on {label}" if label else b["backend"]


def percent(x):
    return f"{100 * x:.2g}%"


def alt_text(b, floor):
    points = b["points"]
    exact = sum(1 for p in points if p["exact"])
    front = [p for p in sorted(points, key=lambda p: -p["rate_mtris"]) if p["pareto"]]
    words = (f"Triangle rate against deviation from the input's limit surface on {backend_title(b)}: "
             f"{len(points)} marks, one per scheme and mesh ({exact} exact, drawn at the precision floor "
             f"{floor:g} of the diagonal). Pareto front: ")
    words += "; ".join(f"{p['scheme']} on {p['mesh']} {p['rate_mtris']:.3g} M triangles/s at "
                       f"{'the floor (exact)' if p['exact'] else 'p95 ' + percent(p['p95_rel_diag']) + ' of the diagonal'}"
                       for p in front) + "."
    return words


def tradeoff_figures(overview, schemes, plot_dir):
    """One figure per backend: x the triangle rate (log), y the p95 deviation from the input's limit
    over the diagonal (log); exact rows on the floor line; the Pareto front as a step line."""
    if not overview:
        return []
    from report_plots import Line2D, plot_text, plt, save  # matplotlib: absent on some GPU machines
    floor = overview["precision_floor_rel_diag"]
    meshes = sorted({p["mesh"] for b in overview["backends"] for p in b["points"]})
    marker = {m: MARKERS[i % len(MARKERS)] for i, m in enumerate(meshes)}
    plots = []
    for b in overview["backends"]:
        points = b["points"]
        if not points:
            continue
        fig, ax = plt.subplots(figsize=(7.2, 4.2))
        ax.axhline(floor, color="#999999", lw=1, ls=":")
        for p in points:
            colour = schemes.colour_of(p["scheme"])
            ax.scatter([p["rate_mtris"]], [p["plotted_p95"]], marker=marker[p["mesh"]], s=46 if p["pareto"] else 30,
                       facecolors=colour if p["exact"] else "white", edgecolors=colour, linewidths=1.6, zorder=3)
        front = sorted((p for p in points if p["pareto"]), key=lambda p: p["rate_mtris"])
        if front:
            ax.step([p["rate_mtris"] for p in front], [p["plotted_p95"] for p in front], where="post", color="#222222",
                    lw=1.2, zorder=2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(bottom=floor / 2)
        ax.set_xlabel("triangle rate (M triangles/s, log)")
        ax.set_ylabel("deviation from the input's limit\n(p95, fraction of the diagonal, log)", fontsize=9)
        ax.set_title(plot_text(backend_title(b)), fontsize=10, wrap=True)
        ax.text(ax.get_xlim()[0], floor, " exact: on the limit (drawn at the float precision floor)", fontsize=7,
                color="#555555", va="bottom")
        ax.grid(True, which="major", alpha=0.3)
        specs = sorted({p["scheme"] for p in points}, key=schemes.key)
        handles = [Line2D([], [], color=schemes.colour_of(s), marker="o", ls="", label=plot_text(s)) for s in specs]
        handles += [Line2D([], [], color="#555555", marker=marker[m], ls="", mfc="white", label=plot_text(m))
                    for m in meshes if any(p["mesh"] == m for p in points)]
        handles += [Line2D([], [], color="#222222", lw=1.2, label="Pareto front"),
                    Line2D([], [], color="#555555", marker="o", ls="", label="filled: exact; hollow: approximates")]
        fig.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 0.98), fontsize=7, frameon=False,
                   title="scheme / mesh", title_fontsize=8)
        fig.tight_layout()
        name = f"tradeoff-{b['backend']}.png"
        unplotted = (" Not drawn (no deviation measured): " + "; ".join(b["unplotted"]) + ".") if b["unplotted"] else ""
        plot = save(fig, plot_dir, name, f"Triangle rate against deviation from the limit, {backend_title(b)}",
                    "One mark per scheme and mesh at its summary cell (the level nearest "
                    f"{overview['summary_triangles']:,} output triangles; the paired rounds' rate where the run "
                    "paired it). Up and left is nearer the surface, right is faster; the line joins the cells no "
                    "other cell beats on both." + unplotted)
        plot.alt = alt_text(b, floor)
        plots.append(plot)
    return plots


def ratio_words(s):
    if not s["peer"]:
        return "anchor: the others' peer"
    if not s["paired_cells"]:
        return f"not paired against {e(s['peer'])} in this run"
    return (f"{s['ratio_median']:.2f}&times; {e(s['peer'])} ({s['ratio_min']:.2f}&ndash;{s['ratio_max']:.2f}, "
            f"{s['paired_cells']} cell{'s' if s['paired_cells'] > 1 else ''})")


def limit_words(s):
    if s["limit"] == "exact":
        return "exact"
    if s["limit"] == "approximates":
        return f"approximates (p95 {percent(s['worst_p95_rel_diag'])} of the diagonal)"
    return "not recorded"


def watertight_words(s):
    if not s["closed_inputs"]:
        return "no closed input"
    n, k = s["closed_inputs"], s["watertight_inputs"]
    return f"{'yes' if k == n else 'NO'}: {k} of {n} closed input{'s' if n > 1 else ''}"


def best_words(s, escape=e):
    where = f"{s['best_backend']}, {s['best_mesh']}"
    if s["best_on_cpu_implementation"]:
        where += ", on a CPU implementation: not a GPU figure"
    if not s.get("best_in_band", True):
        where += ", below the summary's size: its levels do not reach it"
    return f"{s['best_rate_mtris']:.3g} M tri/s ({escape(where)})"


TABLE_READING = ("One row per scheme over its summary cells: the fastest (a CPU implementation of a GPU API is not "
                 "ranked); the median of its paired ratios to its peer (above 1: faster), with the slowest and "
                 "fastest round; exact where every cell reproduces the input's limit surface, else the largest p95 "
                 "distance from it; watertight: closed inputs on which no row left an open edge or a ray crack.")


def scheme_table_html(overview, schemes):
    if not overview or not overview["schemes"]:
        return "<p>No ok row: no per-scheme table.</p>"
    rows = sorted(overview["schemes"], key=lambda s: schemes.key(s["scheme"]))
    out = [f"<p class='reading'>{e(TABLE_READING)}</p>",
           "<table class='schemes' id='scheme-table'><thead><tr><th>scheme</th><th>best rate</th>"
           "<th>paired ratio to its peer</th><th>limit surface</th><th>watertight</th></tr></thead><tbody>"]
    for s in rows:
        bad = " class='leaky'" if s["watertight_inputs"] < s["closed_inputs"] else ""
        out.append(f"<tr><th class='mesh'>{e(s['scheme'])}</th><td>{best_words(s)}</td><td>{ratio_words(s)}</td>"
                   f"<td>{e(limit_words(s))}</td><td{bad}>{e(watertight_words(s))}</td></tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def scheme_table_md(overview, schemes, md):
    if not overview or not overview["schemes"]:
        return ["No ok row: no per-scheme table."]
    out = [TABLE_READING, "", "| scheme | best rate | paired ratio to its peer | limit surface | watertight |",
           "|---|---|---|---|---|"]
    for s in sorted(overview["schemes"], key=lambda s: schemes.key(s["scheme"])):
        ratio = html.unescape(ratio_words(s)).replace("–", "-")
        out.append(f"| {md(s['scheme'])} | {md(best_words(s, str))} | {md(ratio)} | {md(limit_words(s))} | "
                   f"{md(watertight_words(s))} |")
    return out
