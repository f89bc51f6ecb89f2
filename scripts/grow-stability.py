#!/usr/bin/env python3
"""The §3.5 stability claim of Beneš et al. on the small river map: the final measures of
`netspec grow models/grow/small-river.toml` over five seeds, against the same measures with each
of five parameters moved by ±10 % (two seeds each). Prints the coefficient of variation of each.

    NETSPEC=target/release/netspec python3 scripts/grow-stability.py
"""
import os
import statistics as st
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BASE = open(os.path.join(ROOT, "models", "grow", "small-river.toml")).read()
NETSPEC = os.environ.get("NETSPEC", "netspec")
PARAMS = {"demand": 0.6, "block_area": 20000, "slope_cut": 0.15, "nb": 20, "stitch": 40}
SEEDS = [7, 11, 13, 17, 19]
KEYS = {"built_up_ha": 2, "blocks": 3, "minor_km": 4, "major_km": 5, "four_way_share": 12}


def context(over):
    text = BASE.replace("demand = 0.6", f"demand = {over.get('demand', 0.6)}")
    text = text.replace("block_area = 20000", f"block_area = {over.get('block_area', 20000)}")
    extra = "".join(f"{k} = {v}\n" for k, v in over.items() if k not in ("demand", "block_area"))
    return text.replace("[params]\n", "[params]\n" + extra)


def run(work, text, seed, tag):
    path = os.path.join(work, f"{tag}.toml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, f"out-{tag}")
    subprocess.run([NETSPEC, "grow", path, "--out", out, "--seed", str(seed)], check=True, capture_output=True)
    last = open(os.path.join(out, "series.csv")).read().strip().split("\n")[-1].split(",")
    return {k: float(last[i]) for k, i in KEYS.items()}


def cv(xs):
    m = st.mean(xs)
    return st.pstdev(xs) / m if m else 0.0


with tempfile.TemporaryDirectory() as work:
    by_seed = [run(work, context({}), s, f"s{s}") for s in SEEDS]
    perturbed = []
    for k, v in PARAMS.items():
        for f in (0.9, 1.1):
            for s in SEEDS[:2]:
                perturbed.append(run(work, context({k: round(v * f, 4)}), s, f"{k}-{f}-{s}"))
    print("| measure | CV over 5 seeds | CV over ±10 % of 5 parameters (2 seeds) |")
    print("|---|---|---|")
    for k in KEYS:
        print(f"| {k} | {cv([r[k] for r in by_seed]):.3f} | {cv([r[k] for r in perturbed]):.3f} |")
