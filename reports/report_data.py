"""What the report reads from results files, and the figures it derives from them.

Inputs were read and validated by `subdivbench report` (reports/report.cpp) and written again
whole, so every field is present; JSON's null where a number belongs means "not measured".
"""
import json
import math
from collections import defaultdict

SCHEMA = 1
# The summary's common output size: each cell is the row whose output is nearest this.
CALIBRATION = "calibration"  # harness/results/results.h kCalibrationScheme
BACKEND_ORDER = ["cpu", "cpu-mt", "vulkan", "opengl"]

# One colour per scheme, the same in every plot and every report: the registry's methods (the
# papers' schemes, what a reader looks for) take the strongest colours in the registry's order,
# then its peers, then anything else; saturated colours only, no two alike.
PALETTE = ["#d62728", "#ff7f0e", "#8c564b", "#2ca02c", "#17becf", "#9467bd", "#e377c2", "#bcbd22",
           "#1f77b4", "#000075", "#7f7f7f", "#3b3b3b", "#808000", "#469990", "#4363d8", "#f032e6",
           "#9a6324", "#b8860b", "#800000", "#00a86b", "#6a3d9a", "#ff1493", "#556b2f", "#008b8b"]
BACKEND_STYLE = {"cpu": ("o", "-"), "cpu-mt": ("s", "--"), "vulkan": ("^", ":"), "opengl": ("D", "-.")}


def load_results(path):
    with open(path) as f:
        data = json.load(f)
    if data.get("schema") != SCHEMA:
        raise ValueError(f"{path}: unknown results schema {data.get('schema')} (this report reads {SCHEMA})")
    data["runs"] = [nan_for_null(r) for r in data.get("runs", [])]
    return data


def nan_for_null(row):
    """JSON has no NaN: the harness writes it as null. Read back as NaN so arithmetic and plots
    treat it as a missing figure rather than failing."""
    def fix(v):
        if isinstance(v, dict):
            return {k: fix(x) for k, x in v.items()}
        if isinstance(v, list):
            return [fix(x) for x in v]
        return float("nan") if v is None else v
    keep_null = {"deviation", "gpu_time_ms", "peer_backend", "deviation_bound", "own_deviation_bound"}
    return {k: (v if v is None and k in keep_null else fix(v)) for k, v in row.items()}


def finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def spec_of(r):
    return r.get("spec") or r["scheme"]


def timing(r):
    """Vulkan rows are timed by GPU timestamps, the others by the wall clock (as the gate does)."""
    return r.get("gpu_time_ms") or r["time_ms"]


def cpu_implementation(machine, backend):
    """The words for a GPU backend whose rows ran on a CPU implementation of its API (the machine
    block's device type, harness/results/results.h: lavapipe, llvmpipe), else ""."""
    m = machine or {}
    device = {"vulkan": ("vulkan_device", "vulkan_device_type", "Vulkan"),
              "opengl": ("opengl_renderer", "opengl_device_type", "OpenGL")}.get(backend)
    if not device or m.get(device[1]) != "cpu":
        return ""
    return f"{m.get(device[0], '?')}, a CPU implementation of {device[2]}, not a GPU: its rates are not GPU figures"


def backend_key(b):
    return (BACKEND_ORDER.index(b) if b in BACKEND_ORDER else len(BACKEND_ORDER), b)


class Schemes:
    """The registry's order (peers, then methods, then test schemes) and a colour per scheme.

    registry: [(name, role)] as `subdivbench report` passes it (--schemes name=role,...)."""

    def __init__(self, registry, rows):
        self.order = [name for name, _ in registry]
        self.role = dict(registry)
        for r in rows:
            self.role.setdefault(r["scheme"], r.get("role", ""))
        for name in sorted({r["scheme"] for r in rows} - set(self.order)):
            self.order.append(name)
        ranked = ([n for n in self.order if self.role.get(n) == "method"] + [n for n in self.order if self.role.get(n) == "peer"]
                  + [n for n in self.order if self.role.get(n) not in ("method", "peer")])
        self.colour = {name: PALETTE[i % len(PALETTE)] for i, name in enumerate(ranked)}

    def key(self, spec):
        base = spec.split(":")[0]
        return (self.order.index(base) if base in self.order else len(self.order), spec)

    def colour_of(self, spec):
        return self.colour.get(spec.split(":")[0], "#333333")

    def is_paper_scheme(self, spec):
        return self.role.get(spec.split(":")[0]) == "method"


class Results:
    """One (merged) results file: its rows indexed the ways the report looks them up."""

    def __init__(self, data, registry_order, overview):
        """overview: reports/overview.cpp's figures for this file (its summary cells)."""
        self._cells = {(c["scheme"], c["mesh"], c["backend"]): c for c in overview["cells"]}
        self.machine = data.get("machine", {})
        self.created = data.get("created", "")
        self.rounds = data.get("rounds", 0)
        self.shard = data.get("shard")
        self.rows = [r for r in data["runs"] if r["scheme"] != CALIBRATION]
        self.paired = data.get("paired") or []
        self.schemes = Schemes(registry_order, self.rows)
        self.limits = overview["limits"]
        self._by_cell = defaultdict(list)  # (spec, mesh, backend): rows; a sweep has thousands of meshes
        self._specs = {}
        for r in self.rows:
            self._by_cell[(spec_of(r), r["mesh"], r["backend"])].append(r)
        # Backend cells pair a GPU row with its own scheme's cpu-mt row (harness/bench/paired.h);
        # the summary cells are the peer ones.
        self.backend_pairs = [p for p in self.paired if is_backend_pair(p)]
        self._paired = {(p["scheme"], p["mesh"], p["backend"]): p for p in self.paired if not is_backend_pair(p)}

    def meshes(self):
        return sorted({r["mesh"] for r in self.rows})

    def backends(self):
        return sorted({r["backend"] for r in self.rows}, key=backend_key)

    def specs(self, backend=None):
        """Asked once per mesh by the summary: computed once per backend (a sweep has 30,000 rows)."""
        if backend not in self._specs:
            self._specs[backend] = sorted({spec for (spec, _, b) in self._by_cell if backend is None or b == backend},
                                          key=self.schemes.key)
        return self._specs[backend]

    def paired_cell(self, spec, mesh, backend):
        return self._paired.get((spec, mesh, backend))

    def summary_cell(self, spec, mesh, backend):
        """The row the summary shows for (scheme, mesh, backend), as reports/overview.cpp chose it
        (the paired level where the run paired the cell, else the ok row nearest 1 M triangles, else
        the nearest row, to show its status), with its paired figures; None where it has no row."""
        c = self._cells.get((spec, mesh, backend))
        if not c:
            return None
        row = next(r for r in self._by_cell[(spec, mesh, backend)] if r["level"] == c["level"])
        return Cell(row, self.paired_cell(spec, mesh, backend) if c["paired"] else None, c)


def is_backend_pair(p):
    """A paired cell of a scheme's row against the same scheme on another backend (paired.h)."""
    return p["peer"]["scheme"] == p["scheme"] and p["peer"]["backend"] != p["backend"]


class Cell:
    """A summary cell: a row, and its ratio to its peer, paired or single pass (reports/overview.cpp)."""

    def __init__(self, row, paired, figures):
        """figures: the overview's cell (reports/overview.cpp): its rate, ratio and fastest flag."""
        self.row = row
        self.paired = paired
        self.fastest = figures["fastest"]  # the fastest on its mesh and backend
        self._rate = figures["rate_mtris"]
        self.peer = None
        self.ratio = None
        if paired:
            self.ratio = figures["ratio"]
            self.peer = f"{paired['peer']['scheme']} ({paired['peer']['backend']})"
        elif row["status"] == "ok":
            self.ratio = figures["ratio"]
            if row.get("peer"):
                self.peer = f"{row['peer']} ({row.get('peer_backend') or '?'})"

    @property
    def ok(self):
        return self.row["status"] == "ok"

    @property
    def rate(self):
        """M triangles/s: from the paired rounds' median time where the run paired the cell (the
        single pass can read 40% off), else the row's (reports/overview.cpp)."""
        return self._rate if self.ok else None

    def ratio_range(self):
        if not self.paired:
            return None
        rr = self.paired["rate_ratio"]
        return rr.get("min"), rr.get("max"), self.paired.get("rounds", len(rr.get("per_round", [])))

    def verdict(self):
        """'win', 'lose' or 'even' against the peer; None without a ratio. A paired cell wins only
        when every round did (its range lies above 1), a single pass when its one ratio is above 1."""
        if not finite(self.ratio):
            return None
        if self.paired:
            lo, hi, _ = self.ratio_range()
            if finite(lo) and lo > 1:
                return "win"
            if finite(hi) and hi < 1:
                return "lose"
            return "even"
        return "win" if self.ratio > 1 else "lose"

    def ratio_words(self):
        """The ratio as the summary states it: '1.92x osd-bfr (cpu), median of 9 paired rounds, 1.71-2.04x'."""
        if not finite(self.ratio):
            return "no peer row to compare with" if self.peer else "no peer: it is the anchor"
        if self.paired:
            lo, hi, n = self.ratio_range()
            return f"{self.ratio:.2f}x {self.peer}, median of {n} paired rounds, range {lo:.2f}-{hi:.2f}x"
        return f"{self.ratio:.2f}x {self.peer}, single pass"


def watertight_state(r):
    """('closed' | 'open' | 'leaky' | 'unchecked', words)."""
    wt = r.get("watertight", {})
    open_edges, cracks, rays = wt.get("open_edges", -1), wt.get("ray_cracks", -1), wt.get("rays", 0)
    if r["status"] == "unsupported":
        return "unchecked", "not run"
    if cracks is None or not finite(cracks) or cracks < 0:
        if finite(open_edges) and open_edges >= 0:
            return "open", f"open input ({int(open_edges)} boundary edges; no ray test)"
        return "unchecked", "not checked"
    if cracks > 0 or (finite(open_edges) and open_edges > 0):
        return "leaky", f"{int(max(open_edges, 0))} open edges, {int(cracks)} cracks in {int(rays):,} rays"
    return "closed", f"closed: 0 open edges, 0 cracks in {int(rays):,} rays"


def bound_state(r):
    """('kept' | 'past' | 'none' | 'unmeasured', words): the row's deviation against the bounds it
    declares, as harness/results/bound_judgement.cpp judged it (attach_bounds put it in the row)."""
    return tuple(r["bound_state"])


def attach_bounds(data, overview):
    """Each row's bound judgement and single-pass ratio to its peer's row from the overview
    (reports/overview.cpp), by the file's row order."""
    judged, ratios = overview["row_bounds"], overview["row_peer_ratios"]
    if len(judged) != len(data["runs"]) or len(ratios) != len(data["runs"]):
        raise ValueError(f"the overview judges {len(judged)} rows, the results file has {len(data['runs'])}")
    for r, j, ratio in zip(data["runs"], judged, ratios):
        r["bound_state"] = j
        r["peer_ratio"] = ratio


def percent_of_diagonal(x):
    return f"{100 * x:.2g}%" if finite(x) else "–"


def limit_words(cell):
    """What a scheme's rows on one mesh say of the input's limit surface, from the overview's limit
    cell (reports/overview.cpp): 'reproduces' where every measured row does, else 'approximates:
    max M, p95 P' (the largest of the approximating rows' figures, % of the diagonal), naming the
    levels when only some approximate."""
    if cell["limit"] != "approximates":
        return "reproduces"
    text = (f"approximates: max {percent_of_diagonal(cell['worst_max_rel_diag'])}, "
            f"p95 {percent_of_diagonal(cell['worst_p95_rel_diag'])}")
    if cell["some_reproduce"]:
        levels = cell["approximating_levels"]
        text += f" (at level{'s' if len(levels) > 1 else ''} {', '.join(map(str, levels))}; reproduces at the others)"
    if cell["nearest_point"]:
        text += ", by nearest points"
    return text


def validation_state(r):
    """The validation matrix's colour: 'good', 'bad', 'grey' (not checked or not run)."""
    if r["status"] == "unsupported":
        return "na"
    wt, _ = watertight_state(r)
    bd, _ = bound_state(r)
    if r["status"] == "failed" or wt == "leaky" or bd == "past":
        return "bad"
    if wt in ("closed", "open") and bd in ("kept", "none", "unmeasured"):
        return "good"
    return "grey"


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, int) and not isinstance(x, bool):
        return f"{x:,}"
    return f"{x:.{digits}g}"


def median(values):
    v = sorted(values)
    n = len(v)
    if n == 0:
        return float("nan")
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def group(rows, key):
    out = defaultdict(list)
    for r in rows:
        out[key(r)].append(r)
    return out
