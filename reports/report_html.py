"""report.html: one self-contained file (plots and pictures inlined as data URIs, the table script
inline), nothing fetched when it opens."""
import base64
import html
import os
import re

from report_data import bound_state, cpu_implementation, finite, fmt, spec_of, timing, watertight_state
from report_history import p_words

e = html.escape
SCRIPT_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "report_tables.js")

CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:1.5em 2em;color:#222}
p,ul.sentences,figcaption{max-width:1150px}
h1{margin-bottom:.2em} h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.6em}
.machine{color:#555;font-size:13px;margin:.2em 0 1em} nav a{margin-right:1em}
.lede{background:#f6f8fa;border-left:4px solid #4363d8;padding:.6em 1em;font-size:14px}
.lede.bad{border-left-color:#d32f2f;background:#fdf0f0}
ul.sentences li{margin:.3em 0;font-size:14px}
.swatch{display:inline-block;width:.8em;height:.8em;border-radius:2px;margin-right:.3em;vertical-align:-1px}
.scroll{overflow-x:auto;margin-bottom:1em}
table{border-collapse:collapse;font-size:12px}
td,th{border:1px solid #ccc;padding:3px 6px;vertical-align:top}
th{background:#f3f3f3;position:sticky;top:0}
table.matrix td{min-width:78px;max-width:95px;text-align:right;white-space:nowrap;line-height:1.25}
table.matrix th{font-weight:600;font-size:11px;vertical-align:bottom;max-width:95px;overflow-wrap:anywhere}
table.matrix th.mesh{max-width:160px}
table.schemes td,table.schemes th{font-size:13px} table.schemes td.leaky{color:#c0392b} table.matrix th.mesh{text-align:left;vertical-align:top}
table.matrix .rate{font-size:15px;font-weight:700} table.matrix .ratio{font-size:13px}
.range,.tris{color:#666;font-size:10px} p.reading{font-size:12px;color:#444}
.single{color:#a35a00;font-size:10px;font-weight:600;text-transform:uppercase;letter-spacing:.03em}
td.best{background:#e3f4e1;outline:2px solid #2e8b57;outline-offset:-2px}
td.na{color:#999;background:#fafafa;text-align:center}
.closed{color:#1d7a33;font-weight:700} .leaky{color:#c0392b;font-weight:700} .open,.unchecked{color:#777}
table.validation td{padding:2px 4px} .chip{display:inline-block;min-width:1.6em;text-align:center;margin:1px;
 border-radius:3px;padding:1px 3px;font-size:11px;cursor:default}
.chip.good{background:#4caf50;color:#fff} .chip.bad{background:#d32f2f;color:#fff} .chip.grey{background:#bbb;color:#fff}
.chip.na{background:#eee;color:#999}
.figures-row{display:flex;flex-wrap:wrap;gap:8px 16px} .figures-row figure{flex:0 1 650px;margin-bottom:.6em}
figure{margin:0 0 1.5em} figcaption{font-size:12px;color:#555;max-width:900px} img.plot{max-width:100%}
.pictures-row{display:flex;flex-wrap:wrap;gap:14px;margin-bottom:1em}
.picture{border:1px solid #ddd;padding:6px;background:#fff;flex:0 0 auto} .picture .pair{display:flex;gap:4px}
.picture figcaption{max-width:446px}
.picture img{width:220px;height:auto;background:#000}
.picture-error{width:220px;font-size:12px;color:#c0392b;padding:4px;white-space:normal}
.colour-bar img{max-width:420px}
.pictures-unavailable{background:#fff4e5;border-left:4px solid #f58231;padding:.6em 1em}
.paper table td,.paper table th{text-align:right} .paper table td:first-child{text-align:left}
.filters{margin:.5em 0;font-size:13px} .filters select,.filters input{margin-right:.8em}
table.sortable th{cursor:pointer;user-select:none} table.sortable th:after{content:" \\2195";color:#aaa}
table.sortable th.asc:after{content:" \\25B2";color:#333} table.sortable th.desc:after{content:" \\25BC";color:#333}
table.rows td{white-space:nowrap} table.rows td:last-child{white-space:normal;min-width:14em}
table.rows td.num{text-align:right} tr.paper-row td{background:#eef3fb} tr.ours-row td{background:#fff} tr.failed td{background:#fde3e3} tr.unsupported td{color:#999}
td.slower{background:#fde3e3;font-weight:600} td.faster{background:#e3f4e1}
"""

# Installed first, before any other script: errors and console.error calls are kept, so a test
# (or a reader with #selftest) can read them from the page.
ERROR_TRAP = """<script>window.reportErrors=[];
window.addEventListener('error',function(ev){window.reportErrors.push(String(ev.message||ev));});
window.addEventListener('unhandledrejection',function(ev){window.reportErrors.push(String(ev.reason));});
(function(){var ce=console.error;console.error=function(){window.reportErrors.push(Array.prototype.join.call(arguments,' '));
return ce.apply(console,arguments);};})();</script>"""


def page(title, machine_line, nav, body):
    with open(SCRIPT_FILE) as f:
        script = f.read()
    return "\n".join([
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        f"<title>{e(title)}</title>",
        "<meta name='viewport' content='width=device-width, initial-scale=1'>",
        ERROR_TRAP, f"<style>{CSS}</style></head><body>",
        f"<h1>{e(title)}</h1>", f"<p class='machine'>{machine_line}</p>",
        "<nav>" + " ".join(f"<a href='#{a}'>{e(t)}</a>" for a, t in nav) + "</nav>",
        body, f"<script>{script}</script></body></html>"])


def machine_words(machine, created, extra=""):
    m = machine or {}
    parts = [f"{e(m.get('cpu_model', '?'))}, {m.get('cores', '?')} cores",
             f"write bandwidth {m.get('write_bandwidth_gbs', 0):.1f} GB/s one thread, "
             f"{m.get('write_bandwidth_mt_gbs', 0):.1f} GB/s all",
             f"Vulkan: {e(m.get('vulkan_device') or 'none')}"
             f"{' (a CPU implementation of Vulkan, not a GPU)' if cpu_implementation(m, 'vulkan') else ''}{vulkan_bandwidths(m)}",
             f"{e(m.get('compiler', '?'))} {e(m.get('build_type', ''))}, commit <code>{e(m.get('git_commit', '?'))}</code>",
             f"created {e(created)}"]
    return " · ".join(parts) + (f" · {extra}" if extra else "")


def vulkan_bandwidths(m):
    """The device's buffer fill (what bandwidth fractions divide by) and what a compute shader
    that only stores reaches (harness/bench/machine.h): on a CPU-emulated device far apart."""
    fill, shader = m.get("gpu_write_bandwidth_gbs", 0), m.get("gpu_shader_write_bandwidth_gbs", 0)
    if not fill:
        return ""
    words = f", buffer fill {fill:.1f} GB/s"
    return words + (f", a store-only shader {shader:.1f} GB/s" if shader else "")


def swatch(colour):
    return f"<span class='swatch' style='background:{colour}'></span>"


def sentences(items, schemes=None):
    """A list of (head, sentence) or (head, [sentences]) items."""
    out = ["<ul class='sentences'>"]
    for head, text in items:
        sw = swatch(schemes.colour_of(head)) if schemes else ""
        if isinstance(text, list):
            text_html = "<ul>" + "".join(f"<li>{e(t)}</li>" for t in text) + "</ul>"
            out.append(f"<li>{sw}<b>{e(head)}</b>{text_html}</li>")
        else:
            out.append(f"<li>{sw}<b>{e(head)}</b>: {e(text)}</li>")
    out.append("</ul>")
    return "\n".join(out)


def matrix_cell(cell, best):
    r = cell.row
    title = e(f"{spec_of(r)} {r['backend']} {r['mesh']} level {r['level']}: {r['triangles']:,} triangles; "
              f"{cell.ratio_words()}; {watertight_state(r)[1]}; {bound_state(r)[1]}")
    if not cell.ok:
        return f"<td class='na' title='{title}'>{e(r['status'])}</td>"
    wt, _ = watertight_state(r)
    mark = {"closed": "<span class='closed'>&#10003;</span>", "leaky": "<span class='leaky'>&#10007; leaks</span>",
            "open": "<span class='open'>open</span>"}.get(wt, "<span class='unchecked'>?</span>")
    if finite(cell.ratio):
        if cell.paired:
            lo, hi, n = cell.ratio_range()
            ratio = (f"<div class='ratio'>{cell.ratio:.2f}&times;</div>"
                     f"<div class='range'>{lo:.2f}&ndash;{hi:.2f}, {n} rounds</div>")
        else:
            ratio = f"<div class='ratio'>{cell.ratio:.2f}&times;</div><div class='single'>single pass</div>"
    else:  # the anchor has no peer; a scheme whose peer did not run here has no ratio either
        ratio = f"<div class='ratio range'>{'no peer row' if cell.peer else 'anchor'}</div><div class='range'>&nbsp;</div>"
    dev = (r.get("deviation") or {}).get("pos_p95_pct")
    dev_text = f"p95 {fmt(dev, 2)}%" if finite(dev) else "p95 &ndash;"
    cls = " class='best'" if best else ""
    return (f"<td{cls} title='{title}'><div class='rate'>{fmt(cell.rate)}</div>{ratio}"
            f"<div class='marks'>{mark} <span class='range'>{dev_text}</span></div>"
            f"<div class='tris'>{r['triangles']:,} tri, L{r['level']}</div></td>")


# Scheme columns per matrix table: each about 95 px wide and the mesh column 160, so that a
# 1400-pixel window shows a whole table without scrolling sideways; more schemes wrap into a
# second table of the same meshes.
MATRIX_COLUMNS = 11


def summary_matrix(results, m, fastest):
    out = []
    for backend, per_mesh in m.items():
        specs = [s for s in results.specs(backend) if any(s in cells for cells in per_mesh.values())]
        if not specs:
            continue
        label = cpu_implementation(results.machine, backend)
        out.append(f"<h3>{e(backend)}{' (on ' + e(label) + ')' if label else ''}</h3>")
        for part in range(0, len(specs), MATRIX_COLUMNS):
            out.append(matrix_table(results, backend, per_mesh, specs[part:part + MATRIX_COLUMNS], fastest,
                                    "" if part == 0 else f"-{part // MATRIX_COLUMNS + 1}"))
    return "\n".join(out)


def matrix_table(results, backend, per_mesh, specs, fastest, suffix):
    """One table of the backend's matrix: its meshes against `specs`; the fastest is outlined among
    all the backend's schemes on the mesh, not only these."""
    out = [f"<div class='scroll'><table class='matrix' id='summary-matrix-{e(backend)}{suffix}' "
           f"data-backend='{e(backend)}'><thead><tr><th>mesh</th>"]
    for s in specs:
        peers = sorted({c.peer.split(" (")[0] for cells in per_mesh.values() for x, c in cells.items() if x == s and c.peer})
        vs = f"<div class='range'>vs {e(' / '.join(peers))}</div>" if peers else "<div class='range'>anchor</div>"
        out.append(f"<th>{swatch(results.schemes.colour_of(s))}{e(s)}{vs}</th>")
    out.append("</tr></thead><tbody>")
    for mesh, cells in per_mesh.items():
        best = fastest(cells)
        out.append(f"<tr><th class='mesh'>{e(mesh)}</th>")
        for s in specs:
            out.append(matrix_cell(cells[s], s == best) if s in cells else "<td class='na'></td>")
        out.append("</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


def validation_matrix(grid, meshes, schemes):
    out = ["<div class='scroll'><table class='validation' id='validation-matrix'><thead><tr><th>scheme</th>"]
    out += [f"<th>{e(m)}</th>" for m in meshes]
    out.append("</tr></thead><tbody>")
    for spec, per_mesh in grid.items():
        out.append(f"<tr><th style='text-align:left'>{swatch(schemes.colour_of(spec))}{e(spec)}</th>")
        for mesh in meshes:
            chips = "".join(f"<span class='chip {state}' title='{e(title)}'>{level}</span>"
                            for level, state, title in per_mesh.get(mesh, []))
            out.append(f"<td>{chips}</td>")
        out.append("</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


LIMIT_READING = ("Every deviation is measured against the limit surface of the mesh the run was given (Catmull-Clark "
                 "for quad schemes, Loop for triangle ones, Catmull-Clark for mipgh-quadtri): at each vertex's surface coordinate, or, for a scheme whose "
                 "vertices have none on the input (a geometry image fitted to it, a refined control mesh), from each "
                 "vertex to the nearest point of that surface. A scheme reproduces the surface, or approximates it by "
                 "the largest distance and 95th percentile over its rows, in % of the bounding-box diagonal.")


def limit_matrix(table, meshes, schemes):
    """Scheme x mesh: 'reproduces' or 'approximates: max, p95' against the input's limit surface."""
    out = [f"<p class='reading'>{e(LIMIT_READING)}</p>",
           "<div class='scroll'><table class='validation' id='limit-matrix'><thead><tr><th>scheme</th>"]
    out += [f"<th>{e(m)}</th>" for m in meshes]
    out.append("</tr></thead><tbody>")
    for spec, per_mesh in table.items():
        out.append(f"<tr><th style='text-align:left'>{swatch(schemes.colour_of(spec))}{e(spec)}</th>")
        out += [f"<td>{e(per_mesh.get(m, ''))}</td>" for m in meshes]
        out.append("</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


def figure(plot):
    if plot is None:
        return ""
    return (f"<figure><img class='plot' alt='{e(getattr(plot, 'alt', plot.title))}' src='{plot.data_uri()}'>"
            f"<figcaption><b>{e(plot.title)}.</b> {e(plot.caption)}</figcaption></figure>")


PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def is_png_inside(path, folder):
    """A regular file (not a link) inside `folder` that starts as a PNG: what may be inlined. A
    paper table is data; its image links must not publish /etc/passwd as a picture."""
    real, base = os.path.realpath(path), os.path.realpath(folder)
    if os.path.islink(path) or not os.path.isfile(path) or os.path.commonpath([real, base]) != base:
        return False
    with open(path, "rb") as f:
        return f.read(8) == PNG_SIGNATURE


def png_uri(path):
    with open(path, "rb") as f:
        data = f.read()
    if not data.startswith(PNG_SIGNATURE):  # reports/report_inputs.cpp checked it; never inline anything else
        raise ValueError(f"{path}: not a PNG file")
    return "data:image/png;base64," + base64.b64encode(data).decode()


def pictures_section(manifest, manifest_path):
    """Shaded and deviation pictures side by side, per mesh; or the reason there are none."""
    if manifest is None:
        return ("<p class='pictures-unavailable'>No pictures in this report: the run wrote no "
                "<code>pictures/pictures.json</code> (<code>subdivbench pictures --out DIR</code> renders them "
                "where a Vulkan device exists).</p>")
    if not manifest.get("available"):
        return (f"<p class='pictures-unavailable'>No pictures: {e(manifest.get('reason') or 'no reason given')}. "
                "Surfaces are rendered with the Vulkan renderer, which needs a Vulkan device.</p>")
    folder = os.path.dirname(manifest_path)
    pics = manifest.get("pictures", [])
    groups = {}
    for p in pics:
        groups.setdefault(p["mesh"], {}).setdefault((p["scheme"], p["backend"], p["level"]), {})[p["kind"]] = p
    out = [f"<p>Rendered offscreen on {e(manifest.get('device') or 'the Vulkan device')}: each scheme's surface shaded, "
           "and coloured by its distance from the OpenSubdiv limit (in units of the bounding-box diagonal; the range "
           "of each picture in its caption).</p>"]
    if manifest.get("colour_bar"):
        out.append(f"<div class='colour-bar'><img alt='colour bar' src='{png_uri(os.path.join(folder, manifest['colour_bar']))}'>"
                   "<div class='range'>deviation: low (left) to high (right) of each picture's range</div></div>")
    for mesh, by_run in groups.items():
        out.append(f"<h3>{e(mesh)}</h3><div class='pictures-row'>")
        for (scheme, backend, level), kinds in by_run.items():
            imgs = "".join(picture_img(kinds[kind], folder) for kind in ("shaded", "deviation") if kind in kinds)
            any_pic = next(iter(kinds.values()))
            rng = kinds.get("deviation", {}).get("deviation_range")
            rng_text = f", deviation {rng[0]:.2g}&ndash;{rng[1]:.2g}" if rng and len(rng) == 2 else ""
            out.append(f"<figure class='picture'><div class='pair'>{imgs}</div><figcaption><b>{e(scheme)}</b> "
                       f"{e(backend)}, level {level}, {any_pic.get('triangles', 0):,} triangles{rng_text}</figcaption></figure>")
        out.append("</div>")
    return "\n".join(out)


def picture_img(p, folder):
    if not p.get("file"):
        return f"<div class='picture-error'>{e(p['kind'])} picture not made: {e(p.get('error', 'no file'))}</div>"
    return (f"<img class='picture-{e(p['kind'])}' alt='{e(p['scheme'])} {e(p['kind'])}' "
            f"src='{png_uri(os.path.join(folder, p['file']))}'>")


def markdown_to_html(text, folder):
    """The paper verb's Markdown: headings, paragraphs, bullet lists, pipe tables, inline code,
    bold and images (inlined from beside the file). Not a general Markdown reader."""
    out, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        line = lines[i].rstrip()
        if not line.strip():
            i += 1
        elif line.startswith("#"):
            level = min(len(line) - len(line.lstrip("#")) + 2, 6)
            out.append(f"<h{level}>{inline(line.lstrip('#').strip(), folder)}</h{level}>")
            i += 1
        elif line.lstrip().startswith("|"):
            block = []
            while i < len(lines) and lines[i].lstrip().startswith("|"):
                block.append(lines[i].strip())
                i += 1
            out.append(md_table(block, folder))
        elif re.match(r"^\s*[-*] ", line):
            out.append("<ul>")
            while i < len(lines) and re.match(r"^\s*[-*] ", lines[i]):
                item = re.sub(r"^\s*[-*] ", "", lines[i])
                out.append(f"<li>{inline(item, folder)}</li>")
                i += 1
            out.append("</ul>")
        else:
            para = []
            while i < len(lines) and lines[i].strip() and not lines[i].lstrip().startswith(("|", "#")):
                para.append(lines[i].strip())
                i += 1
            out.append(f"<p>{inline(' '.join(para), folder)}</p>")
    return "\n".join(out)


def md_table(block, folder):
    cells = [[c.strip() for c in row.strip("|").split("|")] for row in block]
    head, body = cells[0], [r for r in cells[1:] if not all(re.fullmatch(r":?-{2,}:?", c) for c in r if c)]
    out = ["<div class='scroll'><table><thead><tr>" + "".join(f"<th>{inline(c, folder)}</th>" for c in head) + "</tr></thead><tbody>"]
    for r in body:
        kind = "paper-row" if r and r[0].lower().startswith("paper") else "ours-row" if r and r[0].lower().startswith("ours") else ""
        out.append(f"<tr class='{kind}'>" + "".join(f"<td>{inline(c, folder)}</td>" for c in r) + "</tr>")
    out.append("</tbody></table></div>")
    return "".join(out)


def inline(text, folder):
    def image(m):
        path = os.path.join(folder, m.group(2))
        if m.group(2).endswith(".png") and is_png_inside(path, folder or "."):
            return f"<img alt='{e(m.group(1))}' style='max-width:420px' src='{png_uri(path)}'>"
        return f"[{e(m.group(1))}]"
    parts = re.split(r"(!\[[^\]]*\]\([^)]*\))", text)
    out = []
    for p in parts:
        m = re.fullmatch(r"!\[([^\]]*)\]\(([^)]*)\)", p)
        if m:
            out.append(image(m))
            continue
        s = e(p)
        s = re.sub(r"`([^`]+)`", r"<code>\1</code>", s)
        s = re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", s)
        s = re.sub(r"\[([^\]]+)\]\(([^)]+)\)", r"\1", s)
        out.append(s)
    return "".join(out)


def paper_section(papers, machine, note=""):
    """The papers' tables as `subdivbench paper ID` wrote them (each headed by its ID, the paper's
    figures beside ours), and `note`: one line saying why there are none, or which are missing."""
    said = f"<p class='papers-note'>{e(note)}</p>" if note else ""
    if not papers:
        return said or ("<p class='papers-note'>No paper table in this report: <code>subdivbench report --paper "
                        "results/paper/ID.md</code> includes the Markdown <code>subdivbench paper ID</code> writes.</p>")
    m = machine or {}
    out = [said, f"<p>Paper rows shaded blue, ours white. Ours measured on {e(m.get('cpu_model', '?'))} "
           f"({m.get('cores', '?')} cores); Vulkan device: {e(m.get('vulkan_device') or 'none')} "
           f"{e(m.get('vulkan_driver', ''))}. Each table says which device its own rows ran on.</p>"]
    for path, text in papers:
        out.append(f"<div class='paper' data-file='{e(os.path.basename(path))}'>{markdown_to_html(text, os.path.dirname(path))}</div>")
    return "\n".join(out)


ROW_COLUMNS = [("scheme", "scheme", False), ("backend", "backend", False), ("mesh", "mesh", False), ("level", "", True),
               ("triangles", "", True), ("median ms", "", True), ("M tri/s", "", True), ("x peer (single pass)", "", True),
               ("peer", "", False), ("bw %", "", True), ("open edges", "", True), ("cracks / rays", "", True),
               ("limit", "", False), ("dev max / diag", "", True), ("dev p95 / diag", "", True),
               ("dev max %", "", True), ("dev p95 %", "", True), ("normal max deg", "", True),
               ("Hausdorff", "", True), ("own mesh max / diag", "", True), ("status", "", False)]


def rows_table(results):
    """Every row, sortable by any column and filtered by scheme, backend and mesh."""
    out = ["<div class='filters' data-for='all-rows'></div>",
           "<div class='scroll'><table class='rows sortable filterable' id='all-rows'><thead><tr>"]
    for label, col, _ in ROW_COLUMNS:
        out.append(f"<th data-col='{col}'>{e(label)}</th>" if col else f"<th>{e(label)}</th>")
    out.append("</tr></thead><tbody>")
    for r in sorted(results.rows, key=lambda r: (results.schemes.key(spec_of(r)), r["backend"], r["mesh"], r["level"])):
        out.append(row_html(r, results))
    out.append("</tbody></table></div>")
    return "\n".join(out)


def row_html(r, results):
    dev = r.get("deviation") or {}
    own = dev.get("own_reference") or {}
    wt = r.get("watertight", {})
    ok = r["status"] == "ok"
    ratio = r["peer_ratio"]  # reports/overview.cpp: the row's rate over its peer's row's, same pass
    t = timing(r)["median"] if r["status"] != "unsupported" else None
    cracks = wt.get("ray_cracks", -1)
    values = [
        (spec_of(r), None), (r["backend"], None), (r["mesh"], None), (str(r["level"]), r["level"]),
        (fmt(r["triangles"]), r["triangles"]), (fmt(t), t), (fmt(r["triangle_rate_mtris"]) if ok else "–", r["triangle_rate_mtris"] if ok else None),
        (fmt(ratio), ratio), (r.get("peer") or "–", None),
        (fmt(100 * r.get("bandwidth_fraction", 0)), 100 * r.get("bandwidth_fraction", 0)),
        (fmt(wt.get("open_edges")) if finite(wt.get("open_edges")) and wt["open_edges"] >= 0 else "–", wt.get("open_edges")),
        (f"{int(cracks)} / {int(wt.get('rays', 0)):,}" if finite(cracks) and cracks >= 0 else "–", cracks),
        ((r.get("limit") or "–") + (" (nearest points)" if dev.get("measured_by") == "nearest-point" else ""), None),
        (fmt(dev.get("pos_max_rel_diag")), dev.get("pos_max_rel_diag")),
        (fmt(dev.get("pos_p95_rel_diag")), dev.get("pos_p95_rel_diag")),
        (fmt(dev.get("pos_max_pct")), dev.get("pos_max_pct")), (fmt(dev.get("pos_p95_pct")), dev.get("pos_p95_pct")),
        (fmt(dev.get("normal_max_deg")), dev.get("normal_max_deg")),
        (fmt(dev.get("hausdorff_rel")) if finite(dev.get("hausdorff_rel")) and dev["hausdorff_rel"] >= 0 else "–", None),
        (fmt(own.get("pos_max_rel_diag")), own.get("pos_max_rel_diag")),
        (r["status"] + (f": {r['message']}" if r.get("message") else ""), None)]
    cells = []
    for text, v in values:
        if v is not None and finite(v):
            cells.append(f"<td class='num' data-v='{v!r}'>{e(str(text))}</td>")
        else:
            cells.append(f"<td>{e(str(text))}</td>")
    return f"<tr class='{e(r['status'])}'>" + "".join(cells) + "</tr>"


def paired_table(results):
    if not results.paired:
        return ("<p>This run paired no cell: every ratio in it is a <span class='single'>single pass</span> figure, each "
                "row measured once with other rows' work around it, which can read 0.7&times; where rounds say 1.8&times;.</p>")
    out = ["<div class='filters' data-for='paired-cells'></div>",
           "<div class='scroll'><table class='rows sortable filterable' id='paired-cells'><thead><tr>",
           "<th data-col='scheme'>scheme</th><th data-col='backend'>backend</th><th data-col='mesh'>mesh</th><th>level</th>"
           "<th>triangles</th><th>peer</th><th>rounds</th><th>ratio median</th><th>min</th><th>max</th>"
           "<th>ms</th><th>peer ms</th></tr></thead><tbody>"]
    for p in sorted(results.paired, key=lambda p: (results.schemes.key(p["scheme"]), p["backend"], p["mesh"])):
        rr, peer = p["rate_ratio"], p["peer"]
        nums = [p["level"], p["triangles"]]
        out.append(f"<tr><td>{e(p['scheme'])}</td><td>{e(p['backend'])}</td><td>{e(p['mesh'])}</td>"
                   + "".join(f"<td class='num' data-v='{v}'>{fmt(v)}</td>" for v in nums)
                   + f"<td>{e(peer['scheme'])} ({e(peer['backend'])}, L{peer['level']})</td>"
                   + "".join(f"<td class='num' data-v='{v!r}'>{fmt(v)}</td>" for v in
                             (p.get("rounds"), rr.get("median"), rr.get("min"), rr.get("max"),
                              p.get("time_ms", {}).get("median"), p.get("peer_time_ms", {}).get("median")) if finite(v))
                   + "</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


def history_table(history):
    out = ["<div class='filters' data-for='history-table'></div>",
           "<div class='scroll'><table class='rows sortable filterable' id='history-table'><thead><tr>"
           "<th>benchmark</th><th data-col='scheme'>scheme</th><th data-col='backend'>backend</th><th data-col='mesh'>mesh</th>"
           "<th>normalised by</th>"]
    out += [f"<th title='{e(n)}'>{e(label)}</th>" for label, n in zip(history.labels, history.names)]
    out.append("</tr></thead><tbody>")
    for name in history.benchmarks():
        spec, backend, mesh = name.split("/")[0], name.split("/")[1], "/".join(name.split("/")[2:-1])
        out.append(f"<tr><td>{e(name)}</td><td>{e(spec)}</td><td>{e(backend)}</td><td>{e(mesh)}</td>"
                   f"<td>{e(history.normaliser(name))}</td>")
        for i, span in enumerate(history.series(name)):
            if not span:
                out.append("<td>–</td>")
                continue
            ch = history.change(name, i)
            if ch:
                change, verdict, p = ch
                p_text = p_words(p)
                out.append(f"<td class='num {verdict}' data-v='{span.median!r}' title='{verdict}{p_text}'>"
                           f"{span.median:.3g} <span class='range'>{change:+.0%}</span></td>")
            else:
                out.append(f"<td class='num' data-v='{span.median!r}'>{span.median:.3g}</td>")
        out.append("</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)
