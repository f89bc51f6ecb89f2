#!/usr/bin/env python3
"""The levels table (docs/levels.md): the annealer over seeds and the exact model on the
reconstructed inputs of Ma et al. 2014, Table 1 (models/levels/).

    python3 scripts/levels-table.py --netspec "$CARGO_TARGET_DIR/release/netspec" [--seeds 50] [--time-limit 20]
    python3 scripts/levels-table.py --netspec "$CARGO_TARGET_DIR/release/netspec" --scaling

Writes docs/levels/results.json and prints the markdown table."""
import argparse, json, subprocess, tempfile, pathlib

MODELS = ["fig1", "fig7-top", "fig7-bottom", "fig8", "fig9"]
# Ma et al. 2014, Table 1: success first/tenth, time to first (avg/med), time to ten (avg/med), s.
PAPER = {
    "fig1": ("1/0.94", "4.9/2.3", "10.9/6.8"),
    "fig7-top": ("1/1", "1.1/0.4", "1.8/1.2"),
    "fig7-bottom": ("0.94/0.84", "23/18", "48/40"),
    "fig8": ("0.98/0.98", "80/55", "94/73"),
    "fig9": ("1/1", "1.7/0.3", "2/0.6"),
}


def run(netspec, model, args, output="level.json"):
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([netspec, "level", f"models/levels/{model}.toml", "--out", d, *args],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
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
                m = json.loads((pathlib.Path(d) / "level.json").read_text())["milp"]
            t = m["time_to_first"] if m["status"] == "feasible" else m["time_to_proof"]
            ans = m["status"] + (f" in {t:.2g} s" if t is not None else "")
            print(f"| star of {leaves} + path of {tail} | {1 + leaves + tail} | {ans} |", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--netspec", required=True)
    ap.add_argument("--seeds", type=int, default=50)
    ap.add_argument("--time-limit", type=float, default=20.0)
    ap.add_argument("--milp-time-limit", type=float, default=60.0)
    ap.add_argument("--models", nargs="*", default=MODELS)
    ap.add_argument("--scaling", action="store_true", help="only the MILP on growing star graphs")
    a = ap.parse_args()
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
