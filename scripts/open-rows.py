#!/usr/bin/env python3
"""Writes the study of Table 1's open rows in docs/benchmarks.md (between its `open-rows`
markers) from docs/table1/results.json (the paper-limit records of every backend) and
docs/table1/open-rows.json (each open row's root LP and its `lns` solve).

Usage (from anywhere; paths are the repository's):
  scripts/open-rows.py
      Write the section of docs/benchmarks.md.
  scripts/open-rows.py --check
      Regenerate it and compare with the committed page; exit 1 when they differ.
  scripts/open-rows.py --import-lns DIR [DIR ...]
      Record `netspec solve SPEC --solver highs --threads 2 --time-limit LIMIT
      --formulation strong:lns=on --out DIR` runs: DIR's name is the row, its result.json the
      run (a run of another row replaces nothing else).
  scripts/open-rows.py --import-root FILE [FILE ...]
      Record `netspec solve SPEC --solver highs --threads 2 --relax > FILE` runs: FILE's name
      without its extension is the row, its `LP bound` line the root LP.
  scripts/open-rows.py --import-long DIR [DIR ...]
      Record `netspec solve SPEC --solver highs --threads 2 --time-limit 1200 --formulation
      strong --out DIR` runs (the longer run: the default recipe, its search included): DIR's
      name is the row.
  scripts/open-rows.py --run-long --netspec BIN [--rows A,B,...] [--out DIR]
      Run the longer run on every open row (or the named ones) that has none recorded yet, one
      at a time, into DIR/ROW (default out/open-rows-long), recording each and rewriting the
      section as it ends: an interrupted sequence resumes where it stopped.

A row is open when no column of docs/table1/results.json proves it (optimal, or a gap of at
most 1e-4). Standard library only.
"""
import difflib, importlib.util, json, os, re, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Table 1's report script: what counts as proven is its (src/compare.rs solved()).
_spec = importlib.util.spec_from_file_location("table1_report", os.path.join(ROOT, "scripts", "table1-report.py"))
table1 = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(table1)
proven = table1.proven
RESULTS = "docs/table1/results.json"
STUDY = "docs/table1/open-rows.json"
PAGE = "docs/benchmarks.md"
BEGIN, END = "<!-- open-rows: begin (scripts/open-rows.py) -->", "<!-- open-rows: end -->"
COLUMN = "highs/strong"  # the column the study is about
LNS_COMMAND = ("netspec solve SPEC --solver highs --threads 2 --time-limit LIMIT "
               "--formulation strong:lns=on")
ROOT_COMMAND = "netspec solve SPEC --solver highs --threads 2 --relax --time-limit 60"
LONG_LIMIT = 1200
LONG_LABEL = f"{LONG_LIMIT // 60} min"
LONG_COMMAND = f"netspec solve SPEC --solver highs --threads 2 --time-limit {LONG_LIMIT} --formulation strong"
PARTS = (("lns", LNS_COMMAND), ("root", ROOT_COMMAND), ("long", LONG_COMMAND))
# Objectives closer than this (relative, at least 1) count as equal.
TOL = 1e-6


def path(p):
    return os.path.join(ROOT, p)


def fmt(v):
    """An objective or bound as the tables show it."""
    if v is None:
        return "none"
    return f"{v:.6g}" if v != int(v) else f"{int(v)}"


def pct(v):
    return f"{100 * v:.1f} %"


def same(a, b):
    return abs(a - b) <= TOL * max(1.0, abs(a), abs(b))


def load_study():
    """The study's records, with an empty part for each part not recorded yet."""
    p = path(STUDY)
    study = json.load(open(p)) if os.path.exists(p) else {}
    for part, command in PARTS:
        study.setdefault(part, {"command": command, "rows": {}})
    return study


def dump_study(study):
    """Compact: a row per line, rows in name order."""
    j = lambda v: json.dumps(v, ensure_ascii=False, separators=(", ", ": "))
    lines = ["{"]
    parts = [part for part, _ in PARTS if study[part]["rows"]]
    for i, part in enumerate(parts):
        s = study[part]
        rows = sorted(s["rows"].items())
        lines.append(f'"{part}": {{"command": {j(s["command"])}, "rows": {{')
        lines += [f"  {j(k)}: {j(v)}" + ("," if n < len(rows) - 1 else "") for n, (k, v) in enumerate(rows)]
        lines.append("}}" + ("," if i < len(parts) - 1 else ""))
    lines.append("}")
    open(path(STUDY), "w").write("\n".join(lines) + "\n")
    print(f"wrote {STUDY}")


def run_record(d):
    """The study's record of a `netspec solve … --out DIR` run."""
    f = os.path.join(d, "result.json")
    if not os.path.exists(f):
        sys.exit(f"{f}: no such file (DIR is a `netspec solve --out DIR` directory)")
    r = json.load(open(f))
    s, lns = r["solve"], r.get("lns") or {}
    return {
        "start": r["start"]["objective"] if r.get("start") else None,
        "design": r["objective"]["total"] if r.get("design_found") is True else None,
        "bound": s.get("dual_bound"),
        "valid": bool((r.get("validity") or {}).get("valid")),
        "windows": lns.get("windows", 0),
        "improving": lns.get("improvements", 0),
        "search_seconds": round(lns.get("seconds", 0.0), 1),
        "wall_seconds": round(s["wall_time"], 1),
        "proven": s["termination"]["reason"] == "optimal" or (s.get("gap") is not None and s["gap"] <= table1.PROVEN_GAP),
        "solver_version": s.get("solver_version"),
    }


def import_runs(part, dirs):
    """Records each run under `part`, its directory's name the row."""
    study = load_study()
    for d in dirs:
        study[part]["rows"][os.path.basename(os.path.normpath(d))] = run_record(d)
    dump_study(study)


def run_long(args):
    """Runs the longer run on the open rows that have none (or the named ones), one at a time,
    recording each as it ends."""
    opts = dict(zip(args[::2], args[1::2]))
    if len(args) % 2 or set(opts) - {"--netspec", "--rows", "--out"} or "--netspec" not in opts:
        sys.exit(f"--run-long needs --netspec BIN, and takes --rows A,B,... and --out DIR\n\n{__doc__}")
    res = json.load(open(path(RESULTS)))
    specs = {m["name"]: m["spec"] for m in res["settings"]["manifest"]["row"]}
    open_rows = [n for n, _ in rows_by(res, False)]
    wanted = opts["--rows"].split(",") if "--rows" in opts else open_rows
    unknown = [n for n in wanted if n not in open_rows]
    if unknown:
        sys.exit(f"not open rows of {RESULTS}: {', '.join(unknown)} (open: {', '.join(open_rows)})")
    done = load_study()["long"]["rows"]
    todo = [n for n in wanted if n not in done]
    out = opts.get("--out", path("out/open-rows-long"))
    print(f"{len(todo)} of {len(wanted)} rows to run, {LONG_LIMIT} s each: {', '.join(todo) or 'none'}", flush=True)
    for k, name in enumerate(todo, 1):
        d = os.path.join(out, name)
        cmd = [opts["--netspec"], "solve", path(specs[name]), "--solver", "highs", "--threads", "2",
               "--time-limit", str(LONG_LIMIT), "--formulation", "strong", "--out", d]
        print(f"[{k}/{len(todo)}] {name}: {' '.join(cmd)}", flush=True)
        if subprocess.run(cmd).returncode != 0 or not os.path.exists(os.path.join(d, "result.json")):
            sys.exit(f"{name}: the run failed; nothing recorded for it")
        import_runs("long", [d])
        page = page_with(render(res, load_study()))
        open(path(PAGE), "w").write(page)


ROOT_LINE = re.compile(r"LP bound\s+(\S+) as written, (\S+) after (\d+) cut rounds \((\d+) rows\), ([0-9.]+) s")


def import_root(files):
    study = load_study()
    for f in files:
        m = ROOT_LINE.search(open(f).read())
        if not m:
            sys.exit(f"{f}: no `LP bound … as written, … after … cut rounds` line")
        name = os.path.splitext(os.path.basename(f))[0]
        study["root"]["rows"][name] = {"as_written": float(m[1]), "after_cuts": float(m[2]), "rounds": int(m[3]),
                                       "rows": int(m[4]), "seconds": float(m[5])}
    dump_study(study)


def rows_by(res, proven_by_some):
    """The rows some column proves (or none does), in the manifest's order, each with its
    records by column."""
    by = {}
    for r in res["records"]:
        by.setdefault(r["instance"], {})[r["solver"]] = r
    names = [m["name"] for m in res["settings"]["manifest"]["row"]]
    return [(n, by[n]) for n in names if n in by and any(proven(r) for r in by[n].values()) == proven_by_some]


def render(res, study):
    rows = rows_by(res, False)
    lns, root, long = study["lns"]["rows"], study["root"]["rows"], study["long"]["rows"]
    out = [BEGIN, ""]
    # --- Where each open row's gap sits.
    out += [
        f"**Where the gap sits.** The {len(rows)} rows no backend proves at the paper's limits, each with",
        f"its root LP (`{ROOT_COMMAND}`: as written → after the recipe's cut rounds, their",
        f"time), the {COLUMN} run of the records, and the best design and bound any run knows — every",
        "column of the records, the `lns` solve and the longer run below. The gap of the highs/strong run,",
        "(design − bound) / design, splits into the part above the best known design and the part",
        "below it:",
        "",
        "| row | limit (s) | nonzeros | root LP (s) | highs/strong: design / bound | best design (by) | best bound (by) | gap above best design | gap below it |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    split = {"design": 0, "bound": 0}
    best_design = {}
    for name, recs in rows:
        h = recs[COLUMN]
        designs = [(r["design_objective"], c) for c, r in recs.items() if r["valid"] and r.get("design_objective") is not None]
        bounds = [(r["dual_bound"], c) for c, r in recs.items() if r.get("dual_bound") is not None and not r.get("killed")]
        for label, runs in (("lns", lns), (LONG_LABEL, long)):
            l = runs.get(name)
            if l and l["valid"] and l["design"] is not None:
                designs.append((l["design"], label))
            if l and l["bound"] is not None and label == LONG_LABEL:
                bounds.append((l["bound"], label))
        best_d = min(designs, key=lambda x: x[0]) if designs else None
        best_b = max(bounds, key=lambda x: x[0]) if bounds else None
        best_design[name] = best_d[0] if best_d else None
        by = lambda best, xs: ", ".join(sorted({c for v, c in xs if same(v, best[0])}))
        rt = root.get(name)
        rcell = f"{fmt(round(rt['as_written'], 2))} → {fmt(round(rt['after_cuts'], 2))} ({rt['seconds']:.1f})" if rt else "—"
        d, b = h.get("design_objective") if h["valid"] else None, h.get("dual_bound")
        if d is not None and b is not None and best_d:
            above, below = (d - best_d[0]) / d, (best_d[0] - b) / d
            split["design" if above > below else "bound"] += 1
            parts = f"{pct(above)} | {pct(below)}"
        else:
            parts = "— | —"
        out.append(
            f"| {name} | {fmt(h['time_limit'])} | {h['nonzeros']:,} | {rcell} | {fmt(d)} / {fmt(b)} | "
            f"{fmt(best_d[0]) + ' (' + by(best_d, designs) + ')' if best_d else 'none'} | "
            f"{fmt(best_b[0]) + ' (' + by(best_b, bounds) + ')' if best_b else 'none'} | {parts} |")
    out += ["", f"The larger part is the bound's on {split['bound']} rows (what is left to gain there is in the bound) "
            f"and the design's on {split['design']}.", ""]
    # --- lns against the plain MILP.
    measured = [(n, recs[COLUMN], lns[n]) for n, recs in rows if n in lns]
    measured.sort(key=lambda x: x[1]["nonzeros"])
    out += [
        f"**`lns` on the open rows** (`{LNS_COMMAND}`, the row's spec and",
        "limit), beside the plain run of the records, by model size; *start returned* marks the plain",
        "runs that end with the heuristic's start unimproved:",
        "",
        "| row | limit (s) | nonzeros | plain: design / bound | `lns`: start / design / bound | windows (improving) | design |",
        "|---|---|---|---|---|---|---|",
    ]
    count = {"better": [], "same": [], "worse": []}
    for name, h, l in measured:
        pd = h.get("design_objective") if h["valid"] else None
        ld = l["design"] if l["valid"] else None
        if pd is None or ld is None:
            verdict = "better" if ld is not None and pd is None else "same" if ld == pd else "worse"
        else:
            verdict = "same" if same(pd, ld) else "better" if ld < pd else "worse"
        count[verdict].append((name, h["nonzeros"]))
        start = h.get("start_objective")
        mark = ", start returned" if pd is not None and start is not None and same(pd, start) else ""
        out.append(
            f"| {name} | {fmt(h['time_limit'])} | {h['nonzeros']:,} | {fmt(pd)} / {fmt(h.get('dual_bound'))}{mark} | "
            f"{fmt(l['start'])} / {fmt(ld)} / {fmt(l['bound'])} | {l['windows']} ({l['improving']}) | {verdict} |")
    big = lambda xs, k: sum(1 for _, nz in xs if nz >= k)
    out += [
        "",
        f"Of {len(measured)} open rows measured, `lns` returns a better design on {len(count['better'])}, the same on "
        f"{len(count['same'])} and a worse one on {len(count['worse'])}; from 60,000 nonzeros "
        f"(the size from which `strong` searches unless told not to) {big(count['better'], 60000)} better, "
        f"{big(count['same'], 60000)} the same, {big(count['worse'], 60000)} worse.",
        "",
    ]
    out += render_long(rows, long, best_design)
    # --- Proven rows of that size: does the search cost their proofs?
    done = []
    for name, recs in rows_by(res, True):
        h = recs[COLUMN]
        if name in lns and proven(h):
            done.append((name, h, lns[name]))
    if done:
        out += [
            "Rows the records prove, solved the same way (from 60,000 nonzeros `strong` searches on them by default):",
            "",
            "| row | limit (s) | nonzeros | plain: design, proven in (s) | `lns`: design / bound, time (s) | windows (improving) |",
            "|---|---|---|---|---|---|",
        ]
        for name, h, l in sorted(done, key=lambda x: x[1]["nonzeros"]):
            status = "proven in" if l["proven"] else "not proven,"
            out.append(
                f"| {name} | {fmt(h['time_limit'])} | {h['nonzeros']:,} | {fmt(h['design_objective'])}, {h['wall_time']:.1f} | "
                f"{fmt(l['design'])} / {fmt(l['bound'])}, {status} {l['wall_seconds']:.1f} | {l['windows']} ({l['improving']}) |")
        out.append("")
    out.append(END)
    return "\n".join(out)


def gain(old, new, sign):
    """The relative change from `old` to `new`, as a percentage (`sign` −1: a fall is a gain)."""
    return "—" if old is None or new is None else pct(sign * (new - old) / max(abs(old), 1e-9) + 0.0)


def render_long(rows, long, best_design):
    """The longer run beside the records' highs/strong run: what more time buys, on each side
    (`best_design`: the best design any run knows, per row)."""
    ran = [(n, recs[COLUMN], long[n]) for n, recs in rows if n in long]
    out = [
        f"**A longer run** (`{LONG_COMMAND}`: the default recipe, which searches from 60,000 nonzeros)",
        f"beside the highs/strong run of the records at the paper's limit, on {len(ran)} of the {len(rows)} open rows;",
        "the gap left after it splits as above, against the best design and bound any run knows",
        "(`scripts/open-rows.py --run-long --netspec BIN` runs the rows not recorded yet, one at a time):",
        "",
    ]
    if not ran:
        return out + ["(no row run yet)", ""]
    out += [
        f"| row | limit (s) | paper's limit: design / bound | {LONG_LABEL}: design / bound | design gained | bound gained | gap left above best design | gap left below it |",
        "|---|---|---|---|---|---|---|---|",
    ]
    moved = {"design": 0, "bound": 0, "proven": 0}
    for name, h, l in ran:
        d0, b0 = h.get("design_objective") if h["valid"] else None, h.get("dual_bound")
        d1, b1 = l["design"] if l["valid"] else None, l["bound"]
        moved["design"] += d0 is not None and d1 is not None and d1 < d0 and not same(d0, d1)
        moved["bound"] += b0 is not None and b1 is not None and b1 > b0 and not same(b0, b1)
        moved["proven"] += bool(l["proven"])
        best_d = best_design.get(name)
        if d1 is not None and b1 is not None and best_d is not None:
            parts = f"{pct((d1 - best_d) / d1)} | {pct((best_d - b1) / d1)}"
        else:
            parts = "— | —"
        status = ", proven" if l["proven"] else ""
        out.append(f"| {name} | {fmt(h['time_limit'])} | {fmt(d0)} / {fmt(b0)} | {fmt(d1)} / {fmt(b1)}{status} | "
                   f"{gain(d0, d1, -1)} | {gain(b0, b1, 1)} | {parts} |")
    out += ["", f"Of the {len(ran)} run longer, the design improves on {moved['design']}, the bound on {moved['bound']}; "
            f"{moved['proven']} proven.", ""]
    return out


def page_with(section):
    text = open(path(PAGE)).read()
    if BEGIN not in text or END not in text:
        sys.exit(f"{PAGE}: no `{BEGIN}` … `{END}` markers")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    return head + section + tail


def main():
    args = sys.argv[1:]
    if "-h" in args or "--help" in args:
        print(__doc__)
        return 0
    if args[:1] == ["--import-lns"] and len(args) > 1:
        import_runs("lns", args[1:])
        return 0
    if args[:1] == ["--import-long"] and len(args) > 1:
        import_runs("long", args[1:])
        return 0
    if args[:1] == ["--run-long"]:
        run_long(args[1:])
        return 0
    if args[:1] == ["--import-root"] and len(args) > 1:
        import_root(args[1:])
        return 0
    if args not in ([], ["--check"]):
        sys.exit(f"unknown arguments: {' '.join(args)}\n\n{__doc__}")
    res = json.load(open(path(RESULTS)))
    fresh = page_with(render(res, load_study()))
    if args == ["--check"]:
        old = open(path(PAGE)).read()
        if old != fresh:
            diff = difflib.unified_diff(old.splitlines(), fresh.splitlines(), PAGE, PAGE + " (regenerated)", n=0, lineterm="")
            print(f"{PAGE}'s open-rows section is out of date with {STUDY} (regenerate: scripts/open-rows.py)",
                  *list(diff)[:14], sep="\n", file=sys.stderr)
            return 1
        print(f"ok: {PAGE}'s open-rows section matches {STUDY}")
        return 0
    open(path(PAGE), "w").write(fresh)
    print(f"wrote {PAGE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
