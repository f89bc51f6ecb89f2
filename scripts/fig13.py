#!/usr/bin/env python3
"""Fig. 13 of Peng et al. 2016, reproduced: the paper's stochastic search against the IP.

For each example, with the `netspec` binary:
  - the MILP: `netspec solve --solver highs --no-start` (the IP alone, as in the paper's figure)
    on the spec with the default (strong) formulation, once per time limit in LIMITS; each point is the objective of the *valid* design the run
    returns at that limit (a run that returns none is plotted as missing);
  - the stochastic search: `netspec solve --solver anneal --time-limit ANNEAL` (the best of
    several seeded passes; its result carries the best objective over time);
  - the construction heuristic with local search, for reference: `--solver heuristic`.
Writes OUT/<name>/…, OUT/fig13.csv, OUT/fig13.json and OUT/fig13.svg (objective over time, one
panel per example, log time axis).

usage: scripts/fig13.py [--bin target/release/netspec] [--out docs/fig13] [--anneal 600]
                        [--limits 2,5,10,30,60,120,300] [--threads 2]
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

EXAMPLES = [
    # (name, spec, title)
    ("fig2b", "models/fig2b.toml", "Fig. 2b network (312 edges, distance)"),
    ("fig7b-L2", "models/streets/fig7b/L2/spec.json", "Fig. 7b street level 2 (537 edges, distance)"),
    ("fig9b4", "models/fig9b4.toml", "Fig. 9b4 floor plan (526 edges, length)"),
]


def strong_copy(spec, out_dir):
    """A copy of the spec with the default (strong) formulation, next to its mesh file."""
    os.makedirs(out_dir, exist_ok=True)
    base = os.path.dirname(spec)
    if spec.endswith(".json"):
        with open(spec) as f:
            s = json.load(f)
        s["formulation"] = "strong"
        mesh = s.get("mesh", {}).get("file")
        if mesh:
            shutil.copy(os.path.join(base, mesh), os.path.join(out_dir, os.path.basename(mesh)))
            s["mesh"]["file"] = os.path.basename(mesh)
        path = os.path.join(out_dir, "spec.json")
        with open(path, "w") as f:
            json.dump(s, f, indent=1)
    else:
        with open(spec) as f:
            text = f.read()
        lines = [l for l in text.splitlines() if not l.startswith("formulation")]
        path = os.path.join(out_dir, "spec.toml")
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")  # no formulation key: the default (strong)
    return path


def solve(binary, spec, solver, limit, out, threads, seed=None):
    cmd = [binary, "solve", spec, "--solver", solver, "--time-limit", str(limit), "--out", out]
    if threads and solver not in ("heuristic", "anneal"):
        cmd += ["--threads", str(threads)]
    if solver not in ("heuristic", "anneal"):
        cmd += ["--no-start"]  # the IP alone, as in the paper's figure
    if seed is not None:
        cmd += ["--seed", str(seed)]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    try:
        with open(os.path.join(out, "result.json")) as f:
            r = json.load(f)
    except OSError:
        sys.exit(f"{' '.join(cmd)} wrote no result:\n{p.stdout}\n{p.stderr}")
    return r, wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"), "release", "netspec"))
    ap.add_argument("--out", default="docs/fig13")
    ap.add_argument("--anneal", type=float, default=600)
    ap.add_argument("--heuristic", type=float, default=60)
    ap.add_argument("--limits", default="2,5,10,30,60,120,300")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    limits = [float(x) for x in a.limits.split(",")]
    os.makedirs(a.out, exist_ok=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    results = {"commit": commit, "anneal_seconds": a.anneal, "milp_limits": limits, "threads": a.threads, "examples": []}
    rows = []
    for name, spec, title in EXAMPLES:
        if a.only and name not in a.only.split(","):
            continue
        d = os.path.join(a.out, name)
        s = strong_copy(spec, os.path.join(d, "spec"))
        ex = {"name": name, "title": title, "spec": spec, "milp": [], "anneal": None, "heuristic": None}
        for t in limits:
            r, wall = solve(a.bin, s, "highs", t, os.path.join(d, f"milp-{t:g}"), a.threads)
            obj = r["objective"]["total"] if r["network"] and r["validity"]["valid"] else None
            ex["milp"].append({"limit": t, "objective": obj, "status": r["solve"]["termination"], "bound": r["solve"]["dual_bound"], "wall": wall})
            rows.append([name, "milp", t, obj, wall])
            print(f"{name:10} milp {t:6g} s: {obj} ({wall:.1f} s wall)", flush=True)
        for method, limit in (("anneal", a.anneal), ("heuristic", a.heuristic)):
            r, wall = solve(a.bin, s, method, limit, os.path.join(d, method), 0, seed=1)
            obj = r["objective"]["total"] if r["network"] and r["validity"]["valid"] else None
            trace = r["solve"]["trace"]
            ex[method] = {"limit": limit, "objective": obj, "valid": r["validity"]["valid"], "trace": trace, "stats": r["solve"]["stats"], "wall": wall}
            for p in trace:
                rows.append([name, method, p["seconds"], p["objective"], ""])
            print(f"{name:10} {method} {limit:g} s: {obj} (first at {trace[0]['seconds'] if trace else '-'} s)", flush=True)
        results["examples"].append(ex)
    with open(os.path.join(a.out, "fig13.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(a.out, "fig13.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["example", "method", "seconds", "objective", "wall"])
        w.writerows(rows)
    with open(os.path.join(a.out, "fig13.svg"), "w") as f:
        f.write(plot(results))


def plot(results):
    """Objective over time, one panel per example: the MILP's valid design at each time limit
    (squares), the stochastic search's and the heuristic's best design so far (step lines)."""
    exs = results["examples"]
    pw, ph, left, top, gap = 330, 250, 60, 40, 70
    w = left + len(exs) * (pw + gap)
    h = top + ph + 90
    colors = {"milp": "#1f77b4", "anneal": "#d62728", "heuristic": "#2ca02c"}
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="DejaVu Sans, sans-serif" font-size="11">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="{left}" y="18" font-size="13" font-weight="bold">Fig. 13 reproduced: objective of the best valid design over time (lower is better)</text>']
    for i, ex in enumerate(exs):
        x0 = left + i * (pw + gap)
        pts = [(m["limit"], m["objective"]) for m in ex["milp"] if m["objective"] is not None]
        for meth in ("anneal", "heuristic"):
            if ex[meth]:
                pts += [(p["seconds"], p["objective"]) for p in ex[meth]["trace"]]
        tmax = max([ex["anneal"]["limit"] if ex["anneal"] else 1] + [m["limit"] for m in ex["milp"]])
        tmin = 0.01
        ys = [p[1] for p in pts] or [0, 1]
        ylo, yhi = min(ys), max(ys)
        pad = (yhi - ylo) * 0.08 or 1
        ylo, yhi = ylo - pad, yhi + pad
        X = lambda t: x0 + pw * (math.log10(max(t, tmin)) - math.log10(tmin)) / (math.log10(tmax) - math.log10(tmin))
        Y = lambda v: top + ph * (1 - (v - ylo) / (yhi - ylo))
        out.append(f'<rect x="{x0}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>')
        out.append(f'<text x="{x0}" y="{top - 8}" font-weight="bold">{ex["title"]}</text>')
        k = math.floor(math.log10(tmin))
        while 10 ** k <= tmax * 1.0001:
            t = 10 ** k
            if t >= tmin:
                out.append(f'<line x1="{X(t):.1f}" y1="{top}" x2="{X(t):.1f}" y2="{top + ph}" stroke="#eee"/>'
                           f'<text x="{X(t):.1f}" y="{top + ph + 14}" text-anchor="middle">{t:g}</text>')
            k += 1
        for j in range(5):
            v = ylo + (yhi - ylo) * j / 4
            out.append(f'<text x="{x0 - 4}" y="{Y(v) + 4:.1f}" text-anchor="end">{v:.4g}</text>')
        out.append(f'<text x="{x0 + pw / 2}" y="{top + ph + 30}" text-anchor="middle">seconds (log scale)</text>')
        for meth in ("anneal", "heuristic"):
            m = ex[meth]
            if not m or not m["trace"]:
                continue
            tr = m["trace"]
            d = f'M{X(tr[0]["seconds"]):.1f} {Y(tr[0]["objective"]):.1f}'
            for a, b in zip(tr, tr[1:]):
                d += f' H{X(b["seconds"]):.1f} V{Y(b["objective"]):.1f}'
            d += f' H{X(m["limit"]):.1f}'
            out.append(f'<path d="{d}" fill="none" stroke="{colors[meth]}" stroke-width="2"/>')
        for m in ex["milp"]:
            if m["objective"] is not None:
                out.append(f'<rect x="{X(m["limit"]) - 4:.1f}" y="{Y(m["objective"]) - 4:.1f}" width="8" height="8" fill="{colors["milp"]}"/>')
            else:
                out.append(f'<text x="{X(m["limit"]):.1f}" y="{top + ph - 6}" text-anchor="middle" fill="{colors["milp"]}">×</text>')
    ly = h - 30
    for j, (meth, label) in enumerate((("milp", "IP (HiGHS, strong formulation): valid design at each time limit (× none)"),
                                       ("anneal", "paper's stochastic search: best of its passes so far"),
                                       ("heuristic", "construction + local search (netspec heuristic)"))):
        x = left + j * 380
        out.append(f'<rect x="{x}" y="{ly - 9}" width="14" height="10" fill="{colors[meth]}"/><text x="{x + 20}" y="{ly}">{label}</text>')
    out.append(f'<text x="{left}" y="{h - 8}" fill="#555">netspec commit {results["commit"]}; {results["threads"]} threads for HiGHS, one for the searches</text>')
    out.append("</svg>\n")
    return "\n".join(out)


if __name__ == "__main__":
    main()
