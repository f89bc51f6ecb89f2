"""Helpers shared by the Table 1 report scripts (table1-report.py, table1-strong.py)."""
import json, math, os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def seconds(t):
    """A number of seconds from a table cell or a paper time; None when it is not one."""
    try:
        return float(t)
    except (TypeError, ValueError):
        return None


def fmt(v):
    """An objective as the tables show it."""
    if v is None:
        return "-"
    if abs(v) >= 1e5:
        return f"{v:.3g}"
    return f"{v:.4g}" if v != int(v) else f"{int(v)}"


def sgm(xs, shift):
    """Shifted geometric mean (None for no values)."""
    return math.exp(sum(math.log(x + shift) for x in xs) / len(xs)) - shift if xs else None


def design_of(run_dir, r):
    """A run's design as its result.json reports it: the design's own objective (recomputed by
    netspec, only when the design is valid), the start's objective and whether the start was the
    design returned, and the design's picture."""
    d = {"objective": None, "start": None, "start_returned": False, "picture": None}
    res = os.path.join(run_dir, "result.json")
    if r.get("killed") or not os.path.exists(res):
        return d
    try:
        j = json.load(open(res))
    except ValueError:
        return d
    if (j.get("validity") or {}).get("valid") and j.get("objective"):
        d["objective"] = j["objective"]["total"]
        png = os.path.join(run_dir, "network.png")
        d["picture"] = png if os.path.exists(png) else None
    st = j.get("start") or {}
    if st.get("accepted"):
        d["start"] = st.get("objective")
        d["start_returned"] = st.get("returned", False)
    return d


BACKENDS_OF_PAPER_RECIPE_RUN = ("highs", "cbc", "scip")


def paper_recipe_rows():
    """docs/table1-paper-recipe.md's per-row table (the paper recipe at min(paper time, 20 s)):
    row → {"limit": seconds, backend: {"status", "objective", "gap", "time"}} for HiGHS, CBC, SCIP."""
    out = {}
    doc = open(os.path.join(ROOT, "docs/table1-paper-recipe.md")).read()
    section = doc.split("## Per row", 1)[1].split("## Per backend", 1)[0]
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 6 or cells[0] in ("row", "---"):
            continue
        row = {"limit": seconds(cells[4])}
        for name, c in zip(BACKENDS_OF_PAPER_RECIPE_RUN, cells[5:8]):
            parts = [p.strip() for p in c.split("/")]
            if len(parts) == 4:
                status, obj, gap, t = parts
                row[name] = {"status": status, "objective": seconds(obj), "gap": gap, "time": seconds(t)}
        out[cells[0]] = row
    return out
