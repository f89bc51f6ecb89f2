#!/usr/bin/env python3
"""The levels table (docs/levels.md): the annealer over seeds and the exact model on the
reconstructed inputs of Ma et al. 2014, Table 1 (models/levels/).

    python3 scripts/levels-table.py --netspec "$CARGO_TARGET_DIR/release/netspec" [--seeds 50] [--time-limit 20]
    python3 scripts/levels-table.py --netspec "$CARGO_TARGET_DIR/release/netspec" --scaling
    python3 scripts/levels-table.py --netspec "$CARGO_TARGET_DIR/release/netspec" --families [--print]

Writes docs/levels/results.json (or docs/levels/families.json) and prints the markdown table;
`--families --print` prints the families table from the committed file without running."""
import argparse, json, subprocess, tempfile, pathlib, time

MODELS = ["fig1", "fig7-top", "fig7-bottom", "fig8", "fig9"]
# Ma et al. 2014, Table 1: success first/tenth, time to first (avg/med), time to ten (avg/med), s.
PAPER = {
    "fig1": ("1/0.94", "4.9/2.3", "10.9/6.8"),
    "fig7-top": ("1/1", "1.1/0.4", "1.8/1.2"),
    "fig7-bottom": ("0.94/0.84", "23/18", "48/40"),
    "fig8": ("0.98/0.98", "80/55", "94/73"),
    "fig9": ("1/1", "1.7/0.3", "2/0.6"),
}


def merged(a, b):
    """level.json with run.json's measured values put back at their places."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = dict(a)
        for k, v in b.items():
            out[k] = merged(a[k], v) if k in a else v
        return out
    return b


def read_level(d):
    d = pathlib.Path(d)
    level = json.loads((d / "level.json").read_text())
    return merged(level, json.loads((d / "run.json").read_text()))


def run(netspec, model, args, output="level.json"):
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([netspec, "level", f"models/levels/{model}.toml", "--out", d, *args],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if output == "level.json":
            return read_level(d)
        return json.loads((pathlib.Path(d) / output).read_text())


def avg_med(m, unit=1.0):
    """A mean/median pair of netspec's summary.json."""
    return f"{m['mean'] / unit:.2g}/{m['median'] / unit:.2g}" if m else "–"


SQUARE = 'door_width = 0.6\n[[block]]\nname = "square"\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n'


def star_with_tail(leaves, tail):
    """A hub of unit squares with `leaves` leaves (infeasible from 5 at w = 0.6), the last leaf
    continued by a path of `tail` more squares."""
    n = 1 + leaves + tail
    t = SQUARE + "".join(f'[[node]]\nname = "n{i}"\n' for i in range(n))
    edges = [(0, i) for i in range(1, leaves + 1)] + [(i, i + 1) for i in range(leaves, leaves + tail)]
    return t + "".join(f'[[edge]]\nnodes = ["n{a}", "n{b}"]\n' for a, b in edges)


def scaling(netspec, limit):
    """The MILP on growing graphs: 4-leaf stars (feasible) and 5-leaf stars (infeasible) with tails."""
    print("| graph | nodes | MILP answer (HiGHS, 60 s) |")
    print("|---|---|---|")
    for leaves in (4, 5):
        for tail in (0, 5, 10, 20):
            with tempfile.TemporaryDirectory() as d:
                spec = pathlib.Path(d) / "g.toml"
                spec.write_text(star_with_tail(leaves, tail))
                subprocess.run([netspec, "level", str(spec), "--method", "milp", "--time-limit", str(limit),
                                "--no-explain", "--out", d], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                m = read_level(d)["milp"]
            t = m["time_to_first"] if m["status"] == "feasible" else m["time_to_proof"]
            ans = m["status"] + (f" in {t:.2g} s" if t is not None else "")
            print(f"| star of {leaves} + path of {tail} | {1 + leaves + tail} | {ans} |", flush=True)


# Graph families of unit squares at door width 0.5 (`netspec level-gen`), growing sizes.
FAMILIES = {
    "path": ["path:100", "path:300", "path:1000", "path:3000", "path:10000"],
    "cycle": ["cycle:20", "cycle:50", "cycle:200", "cycle:500", "cycle:2000"],
    "ladder": ["ladder:10", "ladder:20", "ladder:50", "ladder:100", "ladder:500"],
    "grid": ["grid:5x5", "grid:10x10", "grid:20x20", "grid:30x30", "grid:50x50"],
    "caterpillar": ["caterpillar:20x2", "caterpillar:100x2", "caterpillar:300x2", "caterpillar:1000x2"],
    "tree": ["tree:15", "tree:31", "tree:63", "tree:127"],
}
METHODS = ["anneal", "milp", "both"]


def family_run(netspec, family, method, limit):
    """One `netspec level` run on a generated family member: status, wall seconds, why."""
    with tempfile.TemporaryDirectory() as d:
        spec = pathlib.Path(d) / "g.toml"
        subprocess.run([netspec, "level-gen", family, "--out", str(spec)], check=True)
        t0 = time.monotonic()
        p = subprocess.run([netspec, "level", str(spec), "--method", method, "--time-limit", str(limit),
                            "--threads", "1", "--out", d], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall = time.monotonic() - t0
        if p.returncode == 1:
            return {"status": "refused", "wall": wall, "why": p.stderr.strip().splitlines()[-1][:200]}
        lv = read_level(d)
        return {"status": lv["status"], "wall": round(wall, 3)}


def families(netspec, limit):
    """Each family's members by each method, up to the first that is not answered."""
    out = {}
    for fam, members in FAMILIES.items():
        for method in METHODS:
            rows = []
            for m in members:
                r = family_run(netspec, m, method, limit)
                rows.append({"graph": m, **r})
                print(fam, method, m, r, flush=True)
                if r["status"] not in ("feasible", "infeasible"):
                    break
            out.setdefault(fam, {})[method] = rows
    path = pathlib.Path("docs/levels/families.json")
    path.write_text(json.dumps({"time_limit": limit, "door_width": 0.5, "results": out}, indent=1) + "\n")
    return out


def largest(rows, within):
    ok = [r for r in rows if r["status"] in ("feasible", "infeasible") and r["wall"] <= within]
    return f"{ok[-1]['graph'].split(':')[1]} ({ok[-1]['wall']:.2g} s)" if ok else "–"


def print_families(results):
    """Largest member of each family answered within 10 s and 60 s (wall time of the command)."""
    print("| family | annealer ≤ 10 s | annealer ≤ 60 s | MILP ≤ 10 s | MILP ≤ 60 s | both ≤ 10 s | both ≤ 60 s |")
    print("|---|---|---|---|---|---|---|")
    for fam, by in results.items():
        cells = [largest(by.get(m, []), w) for m in METHODS for w in (10, 60)]
        print(f"| {fam} | " + " | ".join(cells) + " |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--netspec", required=True)
    ap.add_argument("--seeds", type=int, default=50)
    ap.add_argument("--time-limit", type=float, default=20.0)
    ap.add_argument("--milp-time-limit", type=float, default=60.0)
    ap.add_argument("--models", nargs="*", default=MODELS)
    ap.add_argument("--scaling", action="store_true", help="only the MILP on growing star graphs")
    ap.add_argument("--families", action="store_true", help="graph families by every method")
    ap.add_argument("--print", action="store_true", help="with --families: the table from the committed file")
    a = ap.parse_args()
    if a.families:
        if a.print:
            results = json.loads(pathlib.Path("docs/levels/families.json").read_text())["results"]
        else:
            results = families(a.netspec, 60.0)
        print_families(results)
        return
    if a.scaling:
        scaling(a.netspec, a.milp_time_limit)
        return
    results = {}
    for m in a.models:
        # The annealer over seeds 1..N in one run: netspec's summary.json has every seed's run and
        # the figures over them.
        summary = run(a.netspec, m, ["--method", "anneal", "--count", "10", "--seed", "1", "--seeds", str(a.seeds),
                                     "--time-limit", str(a.time_limit)], "summary.json")
        milp = run(a.netspec, m, ["--method", "milp", "--time-limit", str(a.milp_time_limit), "--no-explain"])["milp"]
        results[m] = {"anneal": summary["runs"], "summary": {k: v for k, v in summary.items() if k != "runs"},
                      "milp": {k: milp[k] for k in ("status", "time_to_first", "time_to_proof", "size", "note")}}
    out = pathlib.Path("docs/levels/results.json")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"seeds": a.seeds, "time_limit": a.time_limit, "results": results}, indent=1) + "\n")
    print("| input | success first/tenth | #layouts | first, s avg/med | ten, s avg/med | trials to ten avg/med | paper: success | paper: first | paper: ten | MILP (60 s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for m, r in results.items():
        s = r["summary"]
        mi = r["milp"]
        milp = {"feasible": f"layout in {mi['time_to_first']:.2g} s" if mi["time_to_first"] else "",
                "infeasible": f"infeasible, proof {mi['time_to_proof']:.2g} s" if mi["time_to_proof"] else "",
                "unknown": "no answer"}[mi["status"]]
        milp += f" ({mi['size'][0]} vars, {mi['size'][1]} rows)"
        p = PAPER[m]
        print(f"| {m} | {s['success_first']:.2g}/{s['success_count']:.2g} | {s['mean_layouts']:.3g} | "
              f"{avg_med(s['time_to_first'])} | {avg_med(s['time_to_count'])} | "
              f"{avg_med(s['trials_to_count'], 1000)}k | {p[0]} | {p[1]} | {p[2]} | {milp} |")


if __name__ == "__main__":
    main()
