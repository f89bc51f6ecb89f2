#!/usr/bin/env python3
"""Minor-road measures of the small river map (organic streets to step 14, a grid from step 15)
over eight seeds: the 4-way junction share, orientation entropy and dead-end share of the era's
streets and the median built-up block, at the last organic step and at the end; means and
standard deviations. `--extend 0` turns the street extension off in every pattern.

    NETSPEC=target/release/netspec python3 scripts/grow-patterns.py [--extend 0]
"""
import argparse
import csv
import os
import statistics as st
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
NETSPEC = os.environ.get("NETSPEC", "netspec")
SEEDS = range(1, 9)
COLUMNS = ["four_way_share", "orientation_entropy", "dead_end_share", "block_median_m2"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--extend", type=float)
    a = ap.parse_args()
    text = open(os.path.join(ROOT, "models", "grow", "small-river.toml")).read()
    if a.extend is not None:
        text = text.replace('kind = "organic"', f'kind = "organic"\nextend = {a.extend}')
        text = text.replace('kind = "grid"', f'kind = "grid"\nextend = {a.extend}')
    rows = {14: [], 30: []}
    with tempfile.TemporaryDirectory() as work:
        ctx = os.path.join(work, "c.toml")
        open(ctx, "w").write(text)
        for seed in SEEDS:
            out = os.path.join(work, str(seed))
            subprocess.run([NETSPEC, "grow", ctx, "--seed", str(seed), "--out", out], check=True,
                           stdout=subprocess.DEVNULL)
            series = {int(r["step"]): r for r in csv.DictReader(open(os.path.join(out, "series.csv")))}
            for t in rows:
                rows[t].append([float(series[t][c]) for c in COLUMNS])
    print("| step (era) | " + " | ".join(COLUMNS) + " |")
    print("|---" * (1 + len(COLUMNS)) + "|")
    for t, era in [(14, "organic"), (30, "grid")]:
        cells = []
        for k in range(len(COLUMNS)):
            v = [r[k] for r in rows[t]]
            digits = 0 if COLUMNS[k] == "block_median_m2" else 2
            cells.append(f"{st.mean(v):.{digits}f} ± {st.stdev(v):.{digits}f}")
        print(f"| {t} ({era}) | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
