#!/usr/bin/env python3
"""Traffic measures of grown networks (`netspec grow` output directories): per chosen step the
overflow, trade routes and routes per pair, major-road length and lane-kilometres (from
`series.csv`), and at the end the major-road length by lanes (from `network.json`). Markdown
tables on standard output, one column group per directory.

    python3 scripts/grow-measures.py out/grow/river-before out/grow/river --steps 0,30,40,50,60,80,100
"""
import argparse
import csv
import json
import math
import os
from collections import defaultdict


def series(d):
    with open(os.path.join(d, "series.csv")) as f:
        return {int(r["step"]): r for r in csv.DictReader(f)}


def lanes(d):
    net = json.load(open(os.path.join(d, "network.json")))
    pos = {n["id"]: (n["x"], n["y"]) for n in net["nodes"]}
    km = defaultdict(float)
    for s in net["segments"]:
        if s["class"] != "minor":
            km[s["width"]] += math.dist(pos[s["a"]], pos[s["b"]]) / 1000.0
    pairs = {tuple(r["pair"]) for r in net["routes"]}
    return km, len(pairs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--steps", default="0,10,20,30,40,50,60,80,100")
    a = ap.parse_args()
    steps = [int(s) for s in a.steps.split(",")]
    data = [(d, series(d), *lanes(d)) for d in a.dirs]
    cols = ["overflow", "trade routes", "routes/pair", "major km", "lane-km"]
    print("| step | " + " | ".join(f"{c} ({os.path.basename(d.rstrip('/'))})" for d, *_ in data for c in cols) + " |")
    print("|---" * (1 + len(cols) * len(data)) + "|")
    for t in steps:
        row = [str(t)]
        for _, s, _, pairs in data:
            r = s.get(t)
            if r is None:
                row += ["–"] * len(cols)
                continue
            row += [r["overflow"], r["trade_routes"], f"{int(r['trade_routes']) / pairs:.1f}", r["major_km"],
                    r.get("lane_km", "–")]
        print("| " + " | ".join(row) + " |")
    print()
    widths = sorted({w for _, _, km, _ in data for w in km})
    print("| lanes | " + " | ".join(f"major km ({os.path.basename(d.rstrip('/'))})" for d, *_ in data) + " |")
    print("|---" * (1 + len(data)) + "|")
    for w in widths:
        print(f"| {w:g} | " + " | ".join(f"{km.get(w, 0.0):.1f}" for _, _, km, _ in data) + " |")


if __name__ == "__main__":
    main()
