#!/usr/bin/env python3
"""Freezes the street levels of the single-region city examples as standalone instances for
models/table1.toml: copies out/city/<fig>/regions/00-*/L<n>/{spec.json,mesh.json} (written by
`netspec city`, each level built on the previous level's network from that run) to
models/streets/<fig>/L<n>/ and rewrites the street rows of models/table1.toml, one per level.

Usage: scripts/freeze-street-levels.py   (after `netspec city models/city/<fig>.toml --out out/city/<fig>`)
"""
import csv, glob, json, os, re, shutil, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STREETS = {"1a": "fig1a", "1b": "fig1b", "1c": "fig1c", "7a": "fig7a", "7b": "fig7b", "7c": "fig7c",
           "7d": "fig7d", "7e": "fig7e", "8": "fig8", "5L3": "fig5", "5L4": "fig5"}

def level_dir(fig, n):
    hits = sorted(glob.glob(os.path.join(ROOT, "out/city", fig, "regions", "00-*", f"L{n}", "state.json")))
    return os.path.dirname(hits[0]) if hits else None

def freeze(fig, n):
    src = level_dir(fig, n)
    if not src:
        prev = level_dir(fig, n - 1)
        if prev:
            o = json.load(open(os.path.join(prev, "state.json")))["outcome"]
            if not o["state"] in ("solved", "reused"):
                return None, f"no level-{n} instance: level {n - 1} of the city run ended without a network ({o['termination'] or o['message']}, {o['wall_time']:.0f} s)"
        return None, f"no level-{n} instance yet: run `netspec city models/city/{fig}.toml --out out/city/{fig}`"
    state = json.load(open(os.path.join(src, "state.json")))
    dst = os.path.join(ROOT, "models/streets", fig, f"L{n}")
    os.makedirs(dst, exist_ok=True)
    for f in ("spec.json", "mesh.json"):
        shutil.copy(os.path.join(src, f), os.path.join(dst, f))
    return os.path.relpath(os.path.join(dst, "spec.json"), os.path.join(ROOT, "models")), state["outcome"]

def main():
    table = list(csv.DictReader(open(os.path.join(ROOT, "../shared/table1.csv"))))
    out = ["# The rows of the paper's Table 1 (Peng et al. 2016; Gurobi 2014 on a 2.4 GHz eight-core CPU),",
           "# for `netspec compare --manifest models/table1.toml`. Every row is listed; rows that cannot run",
           "# say why and show as missing. All specs are labelled reconstructions.",
           "# Street rows have one entry per level (the paper times level 2 / 3 / 4 separately). Their",
           "# instances are frozen from `netspec city` runs (scripts/freeze-street-levels.py): level n is",
           "# built on the network that run found at level n − 1, so every backend solves the same model.",
           "# The paper's edges and variables are given on the level-2 entry.", ""]
    for r in table:
        fig = r["figure"]
        paper = lambda time, full: "paper = { " + (f"edges = {r['mesh_edges']}, variables = {r['variables']}, " if full else "") + f'time = "{time}" }}'
        if fig in STREETS:
            name = STREETS[fig]
            if fig.startswith("5L"):
                levels = [(int(fig[2]), r["time_s"], True)]
            else:
                times = r["time_s"].split("/")
                levels = [(2 + i, t, i == 0) for i, t in enumerate(times)]
            for n, t, full in levels:
                row = f"{fig}-L{n}" if not fig.startswith("5L") else fig
                out.append("[[row]]")
                out.append(f'name = "{row}"')
                if t.strip() == "-":
                    out.append(f'missing = "the paper reports no level {n} for Fig. {fig}"')
                else:
                    spec, info = freeze(name, n)
                    if spec:
                        out.append(f'spec = "{spec}"')
                        if info.get("termination"):
                            obj = "-" if info["objective"] is None else f"{info['objective']:.6g}"
                            out.append(f"# frozen from a `netspec city` run; that run's own solve: {info['termination']}, objective {obj}")
                    else:
                        out.append(f'missing = "{info}"')
                out.append(paper(t, full))
                out.append("")
        else:
            spec = f"fig{fig}.toml"
            out += ["[[row]]", f'name = "{fig}"', f'spec = "{spec}"', paper(r["time_s"], True), ""]
    text = "\n".join(l for l in out if l is not None)
    text = re.sub(r"\n\n+", "\n\n", text)
    open(os.path.join(ROOT, "models/table1.toml"), "w").write(text.rstrip() + "\n")

if __name__ == "__main__":
    main()
