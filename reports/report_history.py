"""The gate's view over commits, as reports/history.cpp computed it with the gate's own code (each
gated benchmark's normalised time per results file, and the gate's verdict from each file to the
next): read and laid out here, never normalised or judged again."""
import json

from report_data import Schemes


class Span:
    def __init__(self, d):
        self.median, self.low, self.high = d["median"], d["low"], d["high"]


class History:
    def __init__(self, model_path, names, registry_order, rows):
        """model_path: history.json; names: the results files as the user gave them, oldest first;
        rows: every row of those files (the schemes' colours)."""
        with open(model_path) as f:
            model = json.load(f)
        self.labels = model["labels"]
        self.names = names
        self.schemes = Schemes(registry_order, rows)
        self._order = [b["name"] for b in model["benchmarks"]]
        self._b = {b["name"]: b for b in model["benchmarks"]}

    def benchmarks(self):
        """Those the gate calls slower (or fails on) somewhere first, then the registry's order."""
        return self._order

    def moved(self, name, verdict):
        """The indices of the files where the gate judged the benchmark so (from the file before)."""
        return [i for i, s in enumerate(self._b[name]["steps"]) if s and s["verdict"] == verdict]

    def series(self, name):
        return [Span(s) if s else None for s in self._b[name]["spans"]]

    def normaliser(self, name):
        return self._b[name]["normaliser"]

    def colour_of(self, name):
        return self.schemes.colour_of(self._b[name]["scheme"])

    def change(self, name, i):
        """(relative change of the median from file i-1 to file i, the gate's verdict, its p-value),
        or None where the gate judged nothing there."""
        s = self._b[name]["steps"][i]
        if not s or s["verdict"] not in ("slower", "faster", "same"):
            return None
        return s["change"], s["verdict"], s["p_value"]

    def unjudged(self, name, i):
        """(verdict, why) where the gate named the benchmark at file i without judging its time."""
        s = self._b[name]["steps"][i]
        return (s["verdict"], s["why"]) if s and s["verdict"] not in ("slower", "faster", "same") else None


def verdict_lines(history):
    """Per commit after the first, what the gate calls slower, faster or fails on, against the one before."""
    lines = []
    for i in range(1, len(history.labels)):
        moved = {"slower": [], "faster": [], "failed (gone or not ok)": []}
        for name in history.benchmarks():
            ch = history.change(name, i)
            if ch and ch[1] in moved:
                moved[ch[1]].append(f"{name} {ch[0]:+.0%}{p_words(ch[2])}")
            gap = history.unjudged(name, i)
            if gap and gap[0] == "gap":
                moved["failed (gone or not ok)"].append(f"{name} ({gap[1]})")
        said = [f"{k}: " + "; ".join(v) for k, v in moved.items() if v]
        lines.append((history.labels[i], ("; ".join(said) if said else "no change beyond the gate's thresholds")
                      + f" (against {history.labels[i - 1]})."))
    return lines


def p_words(p):
    if p is None:
        return ""
    return ", p < 0.001" if p < 0.001 else f", p {p:.3f}"
