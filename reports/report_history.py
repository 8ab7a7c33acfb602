"""The gate's view over commits: each gated benchmark's time, normalised as harness/bench/gate.cpp
normalises it, in each of several results files (one per commit, in the order given)."""
import json
import re

from report_data import CALIBRATION, Schemes, finite, median, spec_of, timing

try:
    from scipy.stats import mannwhitneyu
except ImportError:  # python3-scipy is in scripts/setup; without it the table judges by threshold alone
    mannwhitneyu = None


class Span:
    def __init__(self, samples):
        self.samples = samples
        self.median, self.low, self.high = median(samples), min(samples), max(samples)


def run_name(r):
    return f"{spec_of(r)}/{r['backend']}/{r['mesh']}/{r['level']}"


def find_unit(row, data):
    """gate.cpp find_unit: the row's peer at the same mesh and tessellation on its peer backend,
    else the calibration probe of the row's backend."""
    if row.get("peer") and row.get("peer_backend"):
        for p in data["runs"]:
            if (p["scheme"] == row["peer"] and p["status"] == "ok" and p["mesh"] == row["mesh"]
                    and p["tessellation"] == row["tessellation"] and p["backend"] == row["peer_backend"]
                    and timing(p).get("samples")):
                return p
    for p in data["runs"]:
        if p["scheme"] == CALIBRATION and p["backend"] == row["backend"] and timing(p).get("samples"):
            return p
    return None


def normalise(row, data):
    """(samples, normaliser) as gate.cpp normalise(): sample r over the unit's sample r of the same
    round when the file went in rounds, else over the unit's fastest sample; rows without a unit
    are multiplied by the bandwidth probe's figure."""
    t = [s for s in timing(row).get("samples", [])]
    paired = data.get("rounds", 0) > 0
    unit = find_unit(row, data)
    if unit:
        u = timing(unit)["samples"]
        by = "write probe" if unit["scheme"] == CALIBRATION else unit["scheme"]
        if paired and len(u) == len(t):
            return [a / b for a, b in zip(t, u)], by + ", paired"
        return [a / min(u) for a in t], by
    m = data.get("machine", {})
    bw = {"cpu-mt": m.get("write_bandwidth_mt_gbs", 0), "vulkan": m.get("gpu_write_bandwidth_gbs", 0),
          "opengl": m.get("gpu_write_bandwidth_gbs", 0)}.get(row["backend"], m.get("write_bandwidth_gbs", 0))
    if not finite(bw) or bw <= 0:
        return None, None
    return [s * bw for s in t], "bandwidth probe"


class History:
    def __init__(self, files, registry_order, gate_config):
        """files: [(name, data)] in commit order."""
        self.labels = commit_labels([d for _, d in files])
        self.names = [n for n, _ in files]
        self.files = [d for _, d in files]
        rows = [r for d in self.files for r in d["runs"]]
        self.schemes = Schemes(registry_order, rows)
        self.config = gate_config or {}
        self._series, self._by, self._row = {}, {}, {}
        for i, data in enumerate(self.files):
            for r in data["runs"]:
                if r["scheme"] == CALIBRATION or r["status"] != "ok":
                    continue
                samples, by = normalise(r, data)
                if not samples or not all(finite(s) and s > 0 for s in samples):
                    continue
                name = run_name(r)
                self._series.setdefault(name, [None] * len(self.files))[i] = Span(samples)
                self._by.setdefault(name, by)
                self._row.setdefault(name, r)

    def benchmarks(self):
        """Those the gate would call slower somewhere first (the CI user's question), then the rest,
        each group in the registry's order."""
        return sorted(self._series, key=lambda n: (not self.moved(n, "slower"), self.schemes.key(spec_of(self._row[n])), n))

    def moved(self, name, verdict):
        """The indices of the files where the benchmark moved so (from the file before)."""
        return [i for i in range(1, len(self.files)) if (self.change(name, i) or (0, ""))[1] == verdict]

    def series(self, name):
        return self._series[name]

    def normaliser(self, name):
        return self._by[name]

    def colour_of(self, name):
        return self.schemes.colour_of(spec_of(self._row[name]))

    def threshold(self, name):
        for t in self.config.get("thresholds", []):
            if re.search(t["match"], name):
                return t["threshold"]
        return self.config.get("default_threshold", 0.25)

    def change(self, name, i):
        """(relative change of the median from file i-1 to file i, 'slower' | 'faster' | 'same' as the
        gate would judge it, p-value or None)."""
        s = self._series[name]
        if i == 0 or not s[i] or not s[i - 1]:
            return None
        change = s[i].median / s[i - 1].median - 1
        p = None
        if mannwhitneyu and len(s[i].samples) > 1 and len(s[i - 1].samples) > 1:
            p = float(mannwhitneyu(s[i - 1].samples, s[i].samples, alternative="two-sided").pvalue)
        significant = p is None or p < self.config.get("alpha", 0.05)
        limit = self.threshold(name)
        verdict = "slower" if significant and change > limit else "faster" if significant and change < -limit else "same"
        return change, verdict, p


def commit_labels(files):
    labels = []
    for d in files:
        m = d.get("machine", {})
        label = (m.get("git_commit") or "?")[:12]
        if label in labels:
            label += f" #{len(labels) + 1}"
        labels.append(label)
    return labels


def read_gate_config(path):
    if not path:
        return {}
    with open(path) as f:
        return json.load(f)


def verdict_lines(history):
    """Per commit after the first, what the gate would call slower or faster than the one before."""
    lines = []
    for i in range(1, len(history.labels)):
        moved = {"slower": [], "faster": []}
        for name in history.benchmarks():
            ch = history.change(name, i)
            if ch and ch[1] in moved:
                p = p_words(ch[2])
                moved[ch[1]].append(f"{name} {ch[0]:+.0%}{p}")
        said = [f"{k}: " + "; ".join(v) for k, v in moved.items() if v]
        lines.append((history.labels[i], ("; ".join(said) if said else "no change beyond the gate's thresholds")
                      + f" (against {history.labels[i - 1]})."))
    return lines


def p_words(p):
    if p is None:
        return ""
    return ", p < 0.001" if p < 0.001 else f", p {p:.3f}"
