"""The summary a reader with a minute gets: per mesh the fastest scheme per backend with its ratio to
its peer, per scheme where it wins and loses, and the validation in one sentence."""
from report_data import cpu_implementation, fmt, group, limit_words, spec_of, validation_state, watertight_state, bound_state


def matrix(results):
    """{backend: {mesh: {spec: Cell}}} over every (scheme, mesh, backend) the run has rows for."""
    out = {}
    for backend in results.backends():
        per_mesh = {}
        for mesh in results.meshes():
            cells = {}
            for spec in results.specs(backend):
                cell = results.summary_cell(spec, mesh, backend)
                if cell:
                    cells[spec] = cell
            if cells:
                per_mesh[mesh] = cells
        out[backend] = per_mesh
    return out


def fastest(cells):
    """The spec of the cell reports/overview.cpp marked fastest on this mesh and backend, or None."""
    return next((spec for spec, c in cells.items() if c.fastest), None)


def fastest_lines(results, m):
    """Per mesh, one sentence: on each backend the fastest scheme, its rate and its ratio to its peer."""
    lines = []
    for mesh in results.meshes():
        parts = []
        for backend, per_mesh in m.items():
            cells = per_mesh.get(mesh)
            if not cells:
                continue
            best = fastest(cells)
            if best is None:
                parts.append(f"on {backend} nothing ran")
                continue
            c = cells[best]
            if cpu_implementation(results.machine, backend):
                parts.append(f"on {backend} (a CPU implementation of the API, not ranked as a GPU) {best} has the "
                             f"highest rate ({fmt(c.rate)} M triangles/s at {c.row['triangles']:,} triangles)")
                continue
            parts.append(f"on {backend} {best} is fastest ({fmt(c.rate)} M triangles/s at {c.row['triangles']:,} "
                         f"triangles; {c.ratio_words()})")
        if parts:
            lines.append((mesh, [p + "." for p in parts]))
    return lines


def scheme_lines(results, m):
    """Per scheme with a peer: where it is faster than its peer (wins), slower (loses), or within
    the paired rounds' range (even), grouped by mesh."""
    by_spec = {}
    for backend, per_mesh in m.items():
        for mesh, cells in per_mesh.items():
            for spec, c in cells.items():
                by_spec.setdefault(spec, []).append((mesh, backend, c))
    lines = []
    for spec in sorted(by_spec, key=results.schemes.key):
        entries = by_spec[spec]
        peers = sorted({c.peer.split(" (")[0] for _, _, c in entries if c.peer})
        verdicts = {"win": {}, "lose": {}, "even": {}}
        for mesh, backend, c in entries:
            v = c.verdict()
            if v:
                tag = f" paired ({c.ratio_range()[2]} rounds)" if c.paired else ""
                verdicts[v].setdefault(mesh, []).append(f"{backend} {c.ratio:.2f}x{tag}")
        judged = sum(len(x) for v in verdicts.values() for x in v.values())
        if not judged:
            why = "no peer row in this run to compare with" if peers else "no peer: the others are measured against it"
            lines.append((spec, why + "."))
            continue
        said = []
        for key, words in (("win", "faster"), ("lose", "slower"), ("even", "even (the paired range spans 1x)")):
            n = sum(len(x) for x in verdicts[key].values())
            if n:
                where = ", ".join(f"{mesh} ({'; '.join(v)})" for mesh, v in sorted(verdicts[key].items()))
                said.append(f"{words} in {n} of {judged}: {where}")
        lines.append((spec, f"against {' / '.join(peers)}: " + "; ".join(said) + "."))
    return lines


def validation_sentence(results):
    """(whether a row failed its checks, the sentence saying so)."""
    bad = [r for r in results.rows if validation_state(r) == "bad"]
    return bool(bad), validation_words(results, bad)


def validation_words(results, bad):
    checked = [r for r in results.rows if r["status"] != "unsupported"]
    if not checked:
        return "No row ran."
    states = [watertight_state(r)[0] for r in checked]
    if not bad:
        unchecked = states.count("unchecked")
        return (f"No row failed its checks: {states.count('closed')} of the {len(checked)} rows that ran are closed with "
                f"no open edge and no ray crack, {states.count('open')} on open inputs"
                + (f", {unchecked} not checked (timed only)" if unchecked else "")
                + "; none is past its scheme's deviation bound.")
    names = [f"{spec_of(r)}/{r['backend']}/{r['mesh']}/{r['level']} ({why(r)})" for r in bad[:8]]
    more = f" and {len(bad) - 8} more" if len(bad) > 8 else ""
    return f"Not valid: {len(bad)} of the {len(checked)} rows that ran: " + "; ".join(names) + more + "."


def why(r):
    if r["status"] == "failed" and r.get("message"):
        return r["message"]
    wt, words = watertight_state(r)
    if wt == "leaky":
        return words
    return bound_state(r)[1]


def validation_grid(results):
    """{spec: {mesh: [(level, state, title)]}} in the registry's order, levels ascending; the title
    says, per backend, what was checked."""
    grid = {}
    for (spec, mesh, level), rows in sorted(group(results.rows, lambda r: (spec_of(r), r["mesh"], r["level"])).items()):
        states = [validation_state(r) for r in rows]
        state = "bad" if "bad" in states else "good" if "good" in states else "grey" if "grey" in states else "na"
        title = "\n".join(f"{r['backend']}: {r['status']}; {watertight_state(r)[1]}; {bound_state(r)[1]}"
                          + dev_words(r) for r in sorted(rows, key=lambda r: r["backend"]))
        grid.setdefault(spec, {}).setdefault(mesh, []).append((level, state, f"{spec} {mesh} level {level}\n{title}"))
    return {spec: grid[spec] for spec in sorted(grid, key=results.schemes.key)}


def limit_table(results):
    """{spec: {mesh: words}}: whether each scheme reproduces its input's limit surface on each mesh
    or approximates it, and how closely (the overview's limit cells, limit_words), in the registry's order."""
    table = {}
    for cell in results.limits:
        table.setdefault(cell["scheme"], {})[cell["mesh"]] = limit_words(cell)
    return {spec: table[spec] for spec in sorted(table, key=results.schemes.key)}


def dev_words(r):
    dev = r.get("deviation") or {}
    if dev.get("pos_p95_pct") is None:
        return ""
    return (f"; deviation from the input's limit p95 {fmt(dev.get('pos_p95_pct'))}%, max {fmt(dev.get('pos_max_pct'))}% "
            "of the local face size")


def gpu_lines(results):
    """Per scheme, its GPU rows against its own cpu-mt rows in the same paired rounds: [(spec, text)]."""
    by_spec = {}
    for p in results.backend_pairs:
        rr = p["rate_ratio"]
        by_spec.setdefault(p["scheme"], []).append(
            f"{p['mesh']} {p['backend']} {rr['median']:.3f}x of {p['peer']['backend']} (range {rr['min']:.3f}-{rr['max']:.3f}, "
            f"{p['rounds']} rounds; {fmt(p['time_ms']['median'])} against {fmt(p['peer_time_ms']['median'])} ms)")
    return [(spec, "; ".join(parts) + ".") for spec, parts in sorted(by_spec.items(), key=lambda kv: results.schemes.key(kv[0]))]
