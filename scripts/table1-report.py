#!/usr/bin/env python3
"""Writes docs/table1.md (Table 1 at the paper's times) from docs/table1/results.json and
models/table1.toml, and with a netspec binary the charts docs/img/table1/{profile,bars}.svg.

Usage (from anywhere; paths are the repository's):
  scripts/table1-report.py [--netspec BIN]
      Write docs/table1.md; with BIN also the charts, by
      `BIN compare --merge docs/table1 --manifest models/table1.toml --out TMP` (run from the
      repository's root; profile.svg and bars.svg are copied from TMP).
  scripts/table1-report.py --check [--netspec BIN]
      Regenerate into a temporary directory and compare byte for byte with the committed
      files; exit 1 naming each file that differs (with the first lines of the difference).
      Without BIN only the page is checked. Also warns (without failing) where a record's spec
      digest no longer matches its spec file: that row's results are for an older spec.
  scripts/table1-report.py --import DIR[,DIR...] [--shared-machine]
      Put the runs of `netspec compare --out DIR` outputs (DIR/runs/*/run.json and each run's
      result.json) into docs/table1/results.json: a run goes to the column of its backend and
      formulation (a column's `solver` and `formulation`), a record with the same row and
      column replaces the old one, a new column is added after the others (its command taken
      from DIR/results.json). --shared-machine marks the imported runs as having shared the
      machine with another run. Then rerun this script to write the page and the charts.

docs/table1/results.json is what `netspec compare --merge` reads (`settings` with `manifest`
and `time_limit`, `records` of src/compare.rs RunRecord, `summary`), one record per line; each
record is a run's run.json plus five fields from its result.json and the protocol:
design_objective (the design's own objective, recomputed by netspec from the network, when the
design is valid), start_objective and start_returned (the heuristic's checked MIP start, and
whether it was the design returned), solver_hints (the recipe's backend settings) and
shared_machine (the run ran while another run shared the machine's two cores).

Standard library only (Python 3.11+, for tomllib).
"""
import difflib, glob, json, math, os, shutil, subprocess, sys, tempfile, textwrap, tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = "docs/table1/results.json"
MANIFEST = "models/table1.toml"
PAGE = "docs/table1.md"
CHARTS = ["docs/img/table1/profile.svg", "docs/img/table1/bars.svg"]

PROVEN_GAP = 1e-4  # src/compare.rs PROVEN_GAP (Gurobi's default MIPGap)
TOL = 1e-6  # objectives and bounds closer than this (relative, at least 1) count as equal
RECORD_KEYS = ["instance", "solver", "seed", "edges", "vars", "rows", "nonzeros", "status", "objective",
               "dual_bound", "gap", "nodes", "solver_time", "wall_time", "valid", "killed", "solver_version",
               "exit_code", "time_limit", "settings"]
EXTRA_KEYS = ["design_objective", "start_objective", "start_returned", "solver_hints", "shared_machine"]


# ---------------------------------------------------------------------------------------------
# Numbers


def seconds(t):
    """A number of seconds from a paper time; None when it is not one (`-`, `379/366/49`)."""
    try:
        return float(t)
    except (TypeError, ValueError):
        return None


def fmt(v):
    """An objective or bound as the tables show it."""
    if v is None:
        return "-"
    if abs(v) >= 1e5:
        return f"{v:.3g}"
    return f"{v:.4g}" if v != int(v) else f"{int(v)}"


def sgm(xs, shift):
    """Shifted geometric mean `exp(mean(ln(x + shift))) - shift` (None for no values)."""
    return math.exp(sum(math.log(x + shift) for x in xs) / len(xs)) - shift if xs else None


def within_gap(r):
    """A valid design whose solver went on but whose gap is at most PROVEN_GAP."""
    return r["status"] != "optimal" and r["valid"] and r.get("gap") is not None and r["gap"] <= PROVEN_GAP


def proven(r):
    """src/compare.rs solved(): infeasible, or a valid design optimal or within PROVEN_GAP."""
    return r["status"] == "infeasible" or (r["valid"] and (r["status"] == "optimal" or within_gap(r)))


# ---------------------------------------------------------------------------------------------
# The results file


def load_manifest():
    """models/table1.toml's rows as netspec's Manifest::load serializes them (spec paths
    relative to the repository's root)."""
    with open(os.path.join(ROOT, MANIFEST), "rb") as f:
        rows = tomllib.load(f)["row"]
    out = []
    for r in rows:
        p = r.get("paper") or {}
        out.append({
            "name": r["name"],
            "spec": os.path.normpath(os.path.join(os.path.dirname(MANIFEST), r["spec"])) if r.get("spec") else None,
            "missing": r.get("missing"),
            "paper": {"edges": p.get("edges"), "variables": p.get("variables"), "time": p.get("time")},
        })
    return out


def summarize(records, columns):
    """src/compare.rs summarize(): per column the shifted geometric mean of time (shift 10 s;
    runs not proven charged their limit), runs proven, runs, and rows where it proved fastest."""
    instances = list(dict.fromkeys(r["instance"] for r in records))
    out = []
    for c in columns:
        mine = [r for r in records if r["solver"] == c]
        times = [min(r["wall_time"], r["time_limit"]) if proven(r) else r["time_limit"] for r in mine]
        wins = 0
        for i in instances:
            done = [r for r in records if r["instance"] == i and proven(r)]
            if done and min(done, key=lambda r: r["wall_time"])["solver"] == c:
                wins += 1
        out.append({"solver": c, "sgm_time": sgm(times, 10.0) or 0.0, "solved": sum(1 for r in mine if proven(r)),
                    "runs": len(mine), "wins": wins})
    return out


def dump(res):
    """The results file's text: compact, one column, manifest row or record per line."""
    j = lambda v: json.dumps(v, ensure_ascii=False, separators=(", ", ": "))
    listed = lambda items: [j(x) + ("," if i < len(items) - 1 else "") for i, x in enumerate(items)]
    s = res["settings"]
    rows = [r["name"] for r in s["manifest"]["row"]]
    cols = [c["label"] for c in s["columns"]]
    records = sorted(res["records"], key=lambda r: (rows.index(r["instance"]), cols.index(r["solver"])))
    lines = ["{", f'"netspec_version": {j(res["netspec_version"])},', '"settings": {']
    for k in ("time_limit", "grace", "paper_limits"):
        lines.append(f"{j(k)}: {j(s[k])},")
    lines += ['"columns": ['] + listed(s["columns"]) + ["],"]
    lines += ['"manifest": {"row": ['] + listed(s["manifest"]["row"]) + ["]}"]
    lines += ["},", '"records": ['] + listed(records) + ["],"]
    lines += ['"summary": ['] + listed(summarize(records, cols)) + ["]", "}"]
    return "\n".join(lines) + "\n"


def run_record(run_json, shared):
    """A run's record for the results file: its run.json and the extra fields."""
    r = json.load(open(run_json))
    missing = [k for k in RECORD_KEYS if k not in r]
    if missing:
        sys.exit(f"{run_json}: not a compare run record (no {', '.join(missing)})")
    rec = {k: r[k] for k in RECORD_KEYS}
    extra = {"design_objective": None, "start_objective": None, "start_returned": False, "solver_hints": None}
    res = os.path.join(os.path.dirname(run_json), "result.json")
    if not r.get("killed") and os.path.exists(res):
        try:
            j = json.load(open(res))
        except ValueError:
            j = {}
        if (j.get("validity") or {}).get("valid") and j.get("objective"):
            extra["design_objective"] = j["objective"]["total"]
        extra["solver_hints"] = j.get("solver_hints")
        st = j.get("start") or {}
        if st.get("accepted"):
            extra["start_objective"] = st.get("objective")
            extra["start_returned"] = st.get("returned", False)
    rec.update(extra)
    rec["shared_machine"] = shared
    return rec


def import_runs(dirs, shared):
    path = os.path.join(ROOT, RESULTS)
    res = json.load(open(path))
    s = res["settings"]
    s["manifest"]["row"] = load_manifest()
    names = [r["name"] for r in s["manifest"]["row"]]
    by = {(r["instance"], r["solver"]): r for r in res["records"]}
    # A run belongs to the column of the backend and formulation it ran: the strong columns run
    # `strong:lns=off`, which compare labels `…/strong:lns=off`.
    column_of = {f'{c["solver"]}/{c["formulation"]}': c["label"] for c in s["columns"]}
    for d in dirs:
        runs = sorted(glob.glob(os.path.join(d, "runs", "*", "run.json")))
        if not runs:
            sys.exit(f"{d}: no runs/*/run.json (a `netspec compare --out {d}` output?)")
        try:
            cmd = json.load(open(os.path.join(d, "results.json"))).get("command") or []
        except (OSError, ValueError):
            cmd = []
        for p in runs:
            rec = run_record(p, shared)
            if rec["instance"] not in names:
                sys.exit(f"{p}: row {rec['instance']!r} is not in {MANIFEST}")
            if rec["status"] == "interrupted":
                sys.exit(f"{p}: an interrupted run (resume the comparison first)")
            label = rec["solver"] = column_of.get(rec["solver"], rec["solver"])
            if label not in [c["label"] for c in s["columns"]]:
                st = rec["settings"] or {}
                s["columns"].append({"label": label, "solver": label.split("/")[0],
                                     "formulation": st.get("formulation"), "threads": st.get("threads"),
                                     "command": " ".join(["netspec"] + cmd[1:]) if cmd else None})
            by[(rec["instance"], label)] = rec
        print(f"{d}: {len(runs)} runs")
    res["records"] = list(by.values())
    open(path, "w").write(dump(res))
    print(f"wrote {RESULTS}: {len(res['records'])} records")


# ---------------------------------------------------------------------------------------------
# The page


def cell(r):
    """One column's cell of a row: status, the design's own objective, time or gap and bound."""
    if r is None:
        return "not run"
    t, o = r["wall_time"], r["design_objective"]
    if r.get("killed"):
        text = f"killed at {t:.0f} s"
    elif r["status"] == "optimal" and r["valid"]:
        text = f"**optimal** {fmt(o)} in {t:.1f} s"
    elif r["status"] == "infeasible":
        text = f"**infeasible** (proven) in {t:.1f} s"
    elif within_gap(r):
        text = f"**optimal** {fmt(o)} in {t:.1f} s ({r['status']} at gap {r['gap']:.1e} ≤ 1e-4)"
    else:
        gap = f", gap {100 * r['gap']:.1f} %" if r.get("gap") is not None and o is not None else ""
        bound = f", bound {fmt(r['dual_bound'])}" if r.get("dual_bound") is not None and o is not None else ""
        text = f"{r['status']}: {fmt(o) if o is not None else 'no design'}{gap}{bound}"
    return text + (" †" if r.get("shared_machine") else "")


def words(n, one, many=None):
    return f"{n} {one if n == 1 else (many or one + 's')}"


def listing(xs):
    xs = list(xs)
    return ", ".join(xs[:-1]) + " and " + xs[-1] if len(xs) > 1 else "".join(xs)


def wrap(text, first="", rest=""):
    """A paragraph or list item wrapped at 100 columns (never inside a row name)."""
    return textwrap.fill(text, 100, initial_indent=first, subsequent_indent=rest, break_on_hyphens=False,
                         break_long_words=False)


def render(res, manifest):
    rows = manifest
    ran = [r for r in rows if r["spec"]]
    cols = [c["label"] for c in res["settings"]["columns"]]
    colinfo = {c["label"]: c for c in res["settings"]["columns"]}
    by = {(r["instance"], r["solver"]): r for r in res["records"]}
    recs = res["records"]
    grace = res["settings"]["grace"]
    cap = res["settings"]["time_limit"]
    versions = {}
    for r in recs:
        if r.get("solver_version"):
            versions.setdefault(r["solver"].split("/")[0], set()).add(r["solver_version"])
    netspec_versions = sorted({(r["settings"] or {}).get("netspec_version") for r in recs} - {None})

    def design(n, c):
        r = by.get((n, c))
        return r["design_objective"] if r else None

    # Per row: the best design, the best bound, whether and how fast some column proved it.
    best, bound, fastest = {}, {}, {}
    for row in ran:
        n = row["name"]
        objs = [(design(n, c), c) for c in cols if design(n, c) is not None]
        # Ties go to the earlier column.
        best[n] = min(objs, key=lambda oc: (oc[0], cols.index(oc[1]))) if objs else None
        bs = [(by[(n, c)]["dual_bound"], c) for c in cols if (n, c) in by and by[(n, c)].get("dual_bound") is not None]
        bound[n] = max(bs, key=lambda bc: (bc[0], -cols.index(bc[1]))) if bs else None
        done = [(by[(n, c)]["wall_time"], c) for c in cols if (n, c) in by and proven(by[(n, c)])]
        fastest[n] = min(done) if done else None
    proven_rows = [r["name"] for r in ran if fastest[r["name"]]]
    open_rows = [r["name"] for r in ran if not fastest[r["name"]]]
    no_design = [r["name"] for r in ran if best[r["name"]] is None]
    paper_s = {r["name"]: seconds(r["paper"]["time"]) for r in rows}
    shared = sum(1 for r in recs if r.get("shared_machine"))
    killed = sum(1 for r in recs if r.get("killed"))

    lines = []
    w = lines.append
    w("# Table 1 at the paper's times")
    w("")
    w("<!-- Generated by scripts/table1-report.py from docs/table1/results.json and models/table1.toml;")
    w("     edit the script, not this page. scripts/table1-check.sh checks that the two agree. -->")
    w("")
    w(wrap("Peng et al. (SIGGRAPH 2016) list in their Table 1 every network of the paper with its mesh's "
           "edges, its MILP's variables and the time Gurobi took to solve it. This page runs netspec's "
           f"backends on the same rows, each at the paper's time for it: {len(ran)} rows with an instance "
           f"([models/table1.toml](../models/table1.toml) lists all {len(rows)}; "
           + "; ".join(f"{r['name']} has none: {r['missing']}" for r in rows if not r["spec"]) + ")."))
    w("")
    w("## What the rows are")
    w("")
    w("Every instance is a reconstruction: the paper's size class, weights and switches (the rules of")
    w("each figure), not the paper's meshes, which are not published. Each street row (Fig. 1a–c, 5,")
    w("7a–e, 8) is one level of a city example's streets — level 2 collector roads, level 3 local roads,")
    w("level 4 cul-de-sacs — frozen from a `netspec city` run")
    w("([scripts/freeze-street-levels.py](../scripts/freeze-street-levels.py)): levels 3 and 4 are built")
    w("on the network that run found at the level before, so every backend solves the same model,")
    w("though not the paper's. The paper publishes no objective values, so no design here can be said")
    w("to match or beat the paper's: only times are set against the paper's, as ratios, on the rows")
    w("proven here.")
    w("")
    w("## Protocol")
    w("")
    w(f"- **Limits.** Each row runs at min(paper time, {cap:g} s) (`--paper-limits --time-limit {cap:g}`); a run")
    w(f"  still going {grace:g} s past its limit is killed (`--grace {grace:g}`)"
      + (f"; {words(killed, 'run was', 'runs were')} killed." if killed else "; no run was killed."))
    w("  One run per row and column, with each backend's default seed.")
    w("- **Columns.** A backend with a formulation recipe ([docs/spec.md](spec.md)): `strong`, netspec's own, and")
    w("  `paper`, the paper's model as written. The `strong` MILP columns measure the MILP alone")
    w("  (`strong:lns=off`): the large-neighbourhood search that `strong` runs first from 60,000")
    w("  nonzeros is measured on the open rows in [docs/benchmarks.md](benchmarks.md).")
    w("")
    w("  | column | backend | threads | settings |")
    w("  |---|---|---|---|")
    presolve_off = [r["name"] for r in ran if "highs.presolve=off" in (by.get((r["name"], "highs/strong")) or {}).get("solver_hints") or []]
    notes = {
        "highs/strong": "the recipe's HiGHS settings: pseudocost branching from the first node and the parallel tree search (`parallel=on`)"
        + (f"; on the symmetric grids {listing(presolve_off)} no cutsets and presolve off, so that HiGHS finds the symmetry" if presolve_off else ""),
        "scip/strong": "netspec's cutset constraint handler, which runs in SCIP's sequential solve",
        "highs/paper": "the paper's recipe, HiGHS's default settings",
        "cbc/strong": "",
        "anneal/strong": "the paper's stochastic search (§6), no MILP: no bound, no start; its designs are checked against the `strong` formulation",
    }
    for c in cols:
        b = c.split("/")[0]
        v = ", ".join(sorted(versions.get(b, []))) if b != "anneal" else ""
        name = {"highs": "HiGHS", "scip": "SCIP", "cbc": "CBC", "anneal": "netspec's `anneal`"}.get(b, b)
        w(f"  | {c} | {name}{' ' + v if v else ''} | {colinfo[c].get('threads') or '-'} | {notes.get(c, '')} |")
    w("")
    w("- **Start.** Every MILP run starts from the construction heuristic's design")
    w("  ([docs/heuristics.md](heuristics.md)), checked row by row before it is handed over; the")
    w("  heuristic's time counts in the run's. When the solver ends with nothing better, the start is")
    w("  the design returned.")
    w("- **Times** are the wall time of the whole `netspec solve` process: model, start, solve and")
    w("  checks.")
    w("- **Objectives** are the design's own, recomputed by netspec from the network (the solver's value")
    w("  of the formulation's objective can be higher where an indicator is not at its bound); the")
    w("  gap is the solver's, (objective − bound) / objective, and the bound its dual bound.")
    w("- **Valid** means the design passed both of netspec's checks: every row and bound of the MILP at")
    w("  the returned point, and the design's own checks in plain graph code that never reads the MILP")
    w("  (no islands, coverage, forbidden configurations, obstacles, forced elements, paths).")
    w("- **Proven** means a valid design whose solver proved it optimal (to 1e-6), or which ended within")
    w("  a gap of 1e-4 (Gurobi's default `MIPGap`; the paper names no gap), or a proof of infeasibility.")
    w(f"- **Machines.** 2-core x86-64 machines (AMD EPYC and Intel Xeon). † marks the {shared} of")
    w(f"  {len(recs)} runs that ran while another run shared the machine's two cores; the others had it")
    w("  to themselves.")
    w("")
    w("## Commands")
    w("")
    w("One comparison per column (each run in its own process, recorded as it ends; rerun to resume):")
    w("")
    w("```sh")
    for c in cols:
        if colinfo[c].get("command"):
            w(colinfo[c]["command"])
    w("```")
    w("")
    w("Their records, one per run, are [docs/table1/results.json](table1/results.json) (each run's")
    w("`run.json`, with the design's own objective, the start, the recipe's backend settings and the")
    w("shared-machine mark from its `result.json` and the protocol). This page and the charts are")
    w("regenerated from that file alone:")
    w("")
    w("```sh")
    w("NETSPEC=~/.cache/netspec/target/release/netspec   # the binary of ./dev's release build")
    w("scripts/table1-report.py --netspec $NETSPEC        # writes this page and docs/img/table1/*.svg")
    w("scripts/table1-check.sh $NETSPEC                   # exit 1, naming the file, if one is out of date")
    w("```")
    w("")
    w("The charts are `netspec compare --merge docs/table1 --manifest models/table1.toml --out DIR`'s.")
    w("`scripts/table1-report.py --import out/t1-highs-strong` puts a comparison's runs into the")
    w("results file, replacing the cells they rerun. Rerunning a column solves every row again with")
    w("the current netspec; the records keep the settings each cell was made with, and the new cells")
    w("can differ.")
    w("")

    # The table.
    w("## Per row")
    w("")
    w("Each column's cell: the status and the design's own objective, with the time where proven,")
    w("else the gap and the bound; *best design* is the lowest objective of any column, *best bound*")
    w("the highest bound. *Edges*: our mesh's (the paper's, given on level 2 for the street rows).")
    w("")
    w("| row | edges | paper variables | paper s | limit s | " + " | ".join(cols) + " | best design | best bound |")
    w("|---|---|---|---|---|" + "---|" * (len(cols) + 2))
    for row in rows:
        n, p = row["name"], row["paper"]
        paper_t = p["time"] or "-"
        pe = "-" if p["edges"] is None else str(p["edges"])
        pv = "-" if p["variables"] is None else str(p["variables"])
        if not row["spec"]:
            w(f"| {n} | - ({pe}) | {pv} | {paper_t} | - | " + " | ".join("no instance" for _ in cols) + " | - | - |")
            continue
        rs = [by.get((n, c)) for c in cols]
        edges = next((r["edges"] for r in rs if r and r.get("edges") is not None), None)
        limit = next((r["time_limit"] for r in rs if r and r.get("time_limit")), None)
        b, bd = best[n], bound[n]
        w(f"| {n} | {edges if edges is not None else '-'} ({pe}) | {pv} | {paper_t} | {fmt(limit)} | "
          + " | ".join(cell(r) for r in rs) + f" | {fmt(b[0]) if b else '-'} | {fmt(bd[0]) if bd else '-'} |")
    w("")
    w("† ran while another run shared the machine's two cores.")
    w("")

    # Per column.
    w("## Per column")
    w("")
    w("| column | threads | rows | proven | valid design | best design of the row (ties count) | shifted geometric mean of time (shift 10 s, not proven = its limit) | time / paper time on its proven rows (geometric mean) | start: given / improved / returned |")
    w("|---|---|---|---|---|---|---|---|---|")
    summary = {s["solver"]: s for s in summarize(recs, cols)}
    for c in cols:
        mine = [by[(r["name"], c)] for r in ran if (r["name"], c) in by]
        done = [r for r in mine if proven(r)]
        valid = [r for r in mine if r["design_objective"] is not None]
        best_count = sum(1 for r in valid
                         if r["design_objective"] <= best[r["instance"]][0] + TOL * max(1.0, abs(best[r["instance"]][0])))
        ratios = [r["wall_time"] / paper_s[r["instance"]] for r in done if paper_s.get(r["instance"])]
        g = sgm(ratios, 0.0)
        starts = [r for r in mine if r["start_objective"] is not None]
        improved = sum(1 for r in starts if r["design_objective"] is not None and r["design_objective"] < r["start_objective"] - TOL * max(1.0, abs(r["start_objective"])))
        returned = sum(1 for r in starts if r["start_returned"])
        st = f"{len(starts)} / {improved} / {returned}" if starts else "-"
        ratio = "-" if g is None else f"{g:.2f} ({words(len(ratios), 'row')})"
        w(f"| {c} | {colinfo[c].get('threads') or '-'} | {len(mine)} | {len(done)} | {len(valid)} | {best_count} | "
          f"{summary[c]['sgm_time']:.1f} s | {ratio} | {st} |")
    w("")
    w("*Start*: rows where the heuristic's start was checked and handed over / where the column's")
    w("design is better than it / where the start itself is the design returned.")
    w("")

    # Against the paper's times.
    w("## Against the paper's times")
    w("")
    w(wrap(f"**{len(proven_rows)} of {len(ran)} rows are proven by some column** within min(paper time, {cap:g} s): "
           + (listing(proven_rows) if proven_rows else "none") + ".", "- ", "  "))
    w(wrap(f"**{len(ran) - len(no_design)} of {len(ran)} rows have a valid design** from some column"
           + (f" (none on {listing(no_design)})." if no_design else "."), "- ", "  "))
    pairs = [(fastest[n][0], paper_s[n], n, fastest[n][1]) for n in proven_rows if paper_s.get(n)]
    if pairs:
        ours, theirs = sgm([a for a, *_ in pairs], 10.0), sgm([b for _, b, *_ in pairs], 10.0)
        g = sgm([a / b for a, b, *_ in pairs], 0.0)
        w(wrap(f"**On the {len(pairs)} rows proven here**, the fastest proving column's time against the paper's: "
               f"shifted geometric means (shift 10 s) {ours:.1f} s against {theirs:.1f} s, **ratio {ours / theirs:.2f}**; "
               f"geometric mean of the per-row ratios {g:.2f}. Per row: "
               + ", ".join(f"{n} {a / b:.2f}× ({c})" for a, b, n, c in pairs) + ".", "- ", "  "))
    w(wrap(f"The other {len(open_rows)} rows end at their limit without a proof in every column; their times "
           "are not set against the paper's.", "- ", "  "))
    w("")

    # The recipes.
    for cs in cols:
        cp = cs.split("/")[0] + "/paper"
        if not cs.endswith("/strong") or cp not in cols:
            continue
        both = [r["name"] for r in ran if (r["name"], cs) in by and (r["name"], cp) in by]
        ob = lambda n, c: by[(n, c)]["design_objective"]
        bd = lambda n, c: by[(n, c)].get("dual_bound")
        better = sum(1 for n in both if ob(n, cs) is not None and (ob(n, cp) is None or ob(n, cs) < ob(n, cp) - TOL * max(1.0, abs(ob(n, cp)))))
        worse = sum(1 for n in both if ob(n, cp) is not None and (ob(n, cs) is None or ob(n, cp) < ob(n, cs) - TOL * max(1.0, abs(ob(n, cs)))))
        with_b = [n for n in both if bd(n, cs) is not None and bd(n, cp) is not None]
        higher = sum(1 for n in with_b if bd(n, cs) > bd(n, cp) + TOL * max(1.0, abs(bd(n, cp))))
        lower = sum(1 for n in with_b if bd(n, cs) < bd(n, cp) - TOL * max(1.0, abs(bd(n, cp))))
        pv = lambda c: [n for n in both if proven(by[(n, c)])]
        gaps = [(by[(n, cs)]["gap"], by[(n, cp)]["gap"]) for n in both
                if not proven(by[(n, cs)]) and by[(n, cs)].get("gap") is not None and by[(n, cp)].get("gap") is not None]
        med = lambda xs: sorted(xs)[len(xs) // 2]
        w(f"## The strong recipe against the paper's ({cs} and {cp})")
        w("")
        w(wrap(f"Same backend, threads and limits, on the {len(both)} rows: proven {len(pv(cs))} against {len(pv(cp))}"
               + (f" ({listing(pv(cp))} by both)" if pv(cp) else "") + f"; a better design on {words(better, 'row')}, worse on"
               f" {worse}, equal on the rest; a higher bound on {higher} of the {len(with_b)} rows where both have one,"
               f" lower on {lower}."
               + (f" On the {len(gaps)} rows {cs} does not prove where both end with a gap, the median gap is"
                  f" {100 * med([a for a, _ in gaps]):.1f} % against {100 * med([b for _, b in gaps]):.1f} %." if gaps else "")))
        w("")

    # Where the open rows stand.
    w("## Where the open rows stand")
    w("")
    og = []
    for n in open_rows:
        if best[n] and bound[n]:
            og.append(((best[n][0] - bound[n][0]) / abs(best[n][0]), n))
    og.sort()
    if og:
        w(wrap(f"Between the best design and the best bound of any column, the {len(og)} open rows"
               + (" with both" if len(og) < len(open_rows) else "") + " are open by "
               + ", ".join(f"{n} {100 * g:.1f} %" for g, n in og) + "."))
        if len(og) == len(open_rows):
            w("Every open row has a design and a bound below it; what is missing is the proof. Where tested")
        else:
            w("Where tested")
        w("(2c and 5L3), handing HiGHS the optimum as an objective bound up front did not shorten the")
        w("proof (2c: 21.6 s with it, 19.9 s without): the open rows are held by their bounds, not by the")
        w("search for designs. Hop-indexed distance labels, the textbook strengthening of a distance-flow")
        w("bound, raise the root bound of the open distance rows by less than the cuts `strong` already")
        w("adds, or only a little (7c-L3 and 2c), at 6–13 times the model's size; on 7c-L3 the MILP with")
        w("them ended its 294 s with bound 168.9, below the table's 170.5 ([docs/benchmarks.md](benchmarks.md)). The")
        w("remaining gaps lie in coverage and the no-dead-end rule rather than in the distance term.")
        w("")

    # Charts.
    w("## Charts")
    w("")
    w("Performance profile: the share of each column's rows proven within t seconds of wall time.")
    w("")
    w("![performance profile](img/table1/profile.svg)")
    w("")
    w("Time per row and column: the solver's own time, log scale; hatched bars are not proven and")
    w("carry their status and gap; the dashed line is the limit, the diamond the paper's Gurobi time.")
    w("")
    w("![time per row and column](img/table1/bars.svg)")
    w("")

    # Limits.
    w("## Limits of the comparison")
    w("")
    w("- **Hardware and solver.** The paper's times are Gurobi (2014) on a 2.4 GHz eight-core CPU;")
    w(wrap("  these are open-source backends ("
           + ", ".join(f"{ {'highs': 'HiGHS', 'scip': 'SCIP', 'cbc': 'CBC'}[b]} {', '.join(sorted(v))}" for b, v in sorted(versions.items()) if b in ("highs", "scip", "cbc"))
           + ") with one or two threads on 2-core machines.", "", "  "))
    w("- **Instances.** Reconstructions of the paper's size class and rules, not its meshes; the")
    w("  street levels 3 and 4 rest on the network of our own city run, not the paper's.")
    w("- **Objectives.** The paper publishes none, so designs cannot be compared with the paper's; only")
    w("  times are, as ratios, and only on rows proven here. The paper also says it accepted sub-optimal")
    w("  designs within reasonable time limits, so its times need not all be proofs.")
    w("- **Variation.** One run per cell. Times vary between runs, seeds and machines (HiGHS proves 2c")
    w("  in 11.7–21.4 s over seeds 0–5, against the paper's 11 s), and a run that shared the machine (†)")
    w("  is slower than alone (5–15 % where measured).")
    w(f"- **Code.** Every record names netspec {', '.join(netspec_versions)}, but the columns were not all made")
    w("  with the same build of it: the records keep each run's settings, and a rerun can differ.")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------------------------
# Charts and checks


def charts(netspec, out_dir):
    """Runs `netspec compare --merge` over the results file into out_dir; returns the charts' paths."""
    cmd = [netspec, "compare", "--merge", os.path.dirname(RESULTS), "--manifest", MANIFEST, "--out", out_dir]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr.strip()}")
    return {c: os.path.join(out_dir, os.path.basename(c)) for c in CHARTS}


def digest(parts):
    """src/io/mod.rs digest: FNV-1a over the parts, each followed by 0xff."""
    h, mask = 0xCBF29CE484222325, (1 << 64) - 1
    for part in parts:
        for b in part:
            h = ((h ^ b) * 0x100000001B3) & mask
        h = ((h ^ 0xFF) * 0x100000001B3) & mask
    return f"{h:016x}"


def spec_digest(spec):
    """src/compare.rs RunSettings::new: the spec file's bytes and its mesh file's, if it names one."""
    try:
        data = open(os.path.join(ROOT, spec), "rb").read()
    except OSError:
        return ""
    try:
        value = json.loads(data) if spec.lower().endswith(".json") else tomllib.loads(data.decode())
    except ValueError:
        value = {}
    mesh = value.get("mesh") if isinstance(value, dict) else None
    f = mesh.get("file") if isinstance(mesh, dict) else None
    extra = b""
    if isinstance(f, str):
        try:
            extra = open(os.path.join(ROOT, os.path.dirname(spec), f), "rb").read()
        except OSError:
            pass
    return digest([data, extra])


def stale_specs(res):
    """Records whose spec file has changed since the run (its digest differs)."""
    out, cache = [], {}
    for r in res["records"]:
        st = r.get("settings") or {}
        spec = st.get("spec")
        if spec and spec not in cache:
            cache[spec] = spec_digest(spec)
        if spec and cache[spec] != st.get("spec_digest"):
            out.append(f"{r['instance']} ({r['solver']}): {spec}")
    return out


def compare_file(committed, fresh):
    """None when the files are byte-identical, else a short account of the difference."""
    path = os.path.join(ROOT, committed)
    if not os.path.exists(path):
        return f"{committed}: missing (the generator writes it)"
    a, b = open(path, "rb").read(), open(fresh, "rb").read()
    if a == b:
        return None
    diff = list(difflib.unified_diff(a.decode(errors="replace").splitlines(), b.decode(errors="replace").splitlines(),
                                     f"{committed} (committed)", f"{committed} (regenerated)", n=0, lineterm=""))
    changed = sum(1 for l in diff if l[:1] in "+-" and l[:3] not in ("+++", "---"))
    changed = words(changed, "line")
    head = "\n".join("    " + l[:200] for l in diff[:14])
    return f"{committed}: differs ({changed} changed)\n{head}" + ("\n    …" if len(diff) > 14 else "")


def main():
    args = sys.argv[1:]
    if "-h" in args or "--help" in args:
        print(__doc__)
        return 0

    def option(name):
        if name not in args:
            return None
        i = args.index(name)
        if i + 1 >= len(args):
            sys.exit(f"{name} needs a value")
        v = args[i + 1]
        del args[i:i + 2]
        return v

    netspec = option("--netspec") or os.environ.get("NETSPEC") or None
    imports = option("--import")
    check = "--check" in args
    shared = "--shared-machine" in args
    args = [a for a in args if a not in ("--check", "--shared-machine")]
    if args:
        sys.exit(f"unknown arguments: {' '.join(args)}\n\n{__doc__}")
    if netspec:
        netspec = os.path.abspath(netspec)
        if not os.access(netspec, os.X_OK):
            sys.exit(f"{netspec}: not an executable netspec binary")
    if imports:
        import_runs([os.path.abspath(d) for d in imports.split(",")], shared)
        return 0
    res = json.load(open(os.path.join(ROOT, RESULTS)))
    page = render(res, load_manifest())
    with tempfile.TemporaryDirectory(prefix="table1-") as tmp:
        fresh = {PAGE: os.path.join(tmp, "table1.md")}
        open(fresh[PAGE], "w").write(page)
        if netspec:
            fresh.update(charts(netspec, os.path.join(tmp, "merged")))
        if check:
            stale = stale_specs(res)
            if stale:
                print(f"warning: {len(stale)} records ran a spec that has changed since (digest differs):\n  "
                      + "\n  ".join(stale), file=sys.stderr)
            problems = [p for p in (compare_file(k, v) for k, v in fresh.items()) if p]
            if problems:
                print("Table 1 page/charts out of date with docs/table1/results.json "
                      "(regenerate: scripts/table1-report.py --netspec NETSPEC):", file=sys.stderr)
                print("\n".join(problems), file=sys.stderr)
                return 1
            print(f"ok: {', '.join(fresh)} {'match' if len(fresh) > 1 else 'matches'} {RESULTS}" + ("" if netspec else " (charts not checked: no --netspec)"))
            return 0
        for k, v in fresh.items():
            os.makedirs(os.path.dirname(os.path.join(ROOT, k)), exist_ok=True)
            shutil.copyfile(v, os.path.join(ROOT, k))
            print(f"wrote {k}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
