#!/usr/bin/env python3
"""Freezes the street levels of the single-region city examples as standalone instances for
models/table1.toml: copies out/city/<fig>/regions/00-*/L<n>/{spec.json,mesh.json} (written by
`netspec city`, each level built on the previous level's network from that run) to
models/streets/<fig>/L<n>/ and points the street rows of models/table1.toml at them, one row per
level (1a-L2 ... 8-L4, 5L3, 5L4).

Usage: scripts/freeze-street-levels.py [FIG...]
  (after `netspec city models/city/<fig>.toml --out out/city/<fig>`; FIG as fig7a; default: every
  street figure). Only the chosen figures' rows change: their `spec` (or `missing`, with the
  reason, when the city run has no such level) and the comment naming the city run's own solve.
  Every other line of models/table1.toml — its header, the other rows, the paper's figures — is
  kept as it is.
"""
import glob, json, os, re, shutil, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MANIFEST = os.path.join(ROOT, "models/table1.toml")
STREETS = {"1a": "fig1a", "1b": "fig1b", "1c": "fig1c", "7a": "fig7a", "7b": "fig7b", "7c": "fig7c",
           "7d": "fig7d", "7e": "fig7e", "8": "fig8", "5": "fig5"}


def street_level(name):
    """(figure directory, level) of a street row's name (`7a-L3`, `5L4`), else None."""
    m = re.fullmatch(r"(\w+?)-?L(\d)", name)
    if not m or m.group(1) not in STREETS:
        return None
    return STREETS[m.group(1)], int(m.group(2))


def level_dir(fig, n):
    hits = sorted(glob.glob(os.path.join(ROOT, "out/city", fig, "regions", "00-*", f"L{n}", "state.json")))
    return os.path.dirname(hits[0]) if hits else None


def freeze(fig, n):
    """Copies one level; returns (spec path relative to models/, the city run's report), or
    (None, why there is no instance)."""
    src = level_dir(fig, n)
    if not src:
        prev = level_dir(fig, n - 1)
        if prev:
            o = json.load(open(os.path.join(prev, "state.json")))["report"]
            if o["state"] not in ("solved", "reused"):
                return None, f"no level-{n} instance: level {n - 1} of the city run ended without a network ({o['termination'] or o['message']}, {o['wall_time']:.0f} s)"
        return None, f"no level-{n} instance yet: run `netspec city models/city/{fig}.toml --out out/city/{fig}`"
    state = json.load(open(os.path.join(src, "state.json")))
    dst = os.path.join(ROOT, "models/streets", fig, f"L{n}")
    os.makedirs(dst, exist_ok=True)
    for f in ("spec.json", "mesh.json"):
        shutil.copy(os.path.join(src, f), os.path.join(dst, f))
    return os.path.relpath(os.path.join(dst, "spec.json"), os.path.join(ROOT, "models")), state["report"]


def main():
    figs = sys.argv[1:] or sorted(set(STREETS.values()))
    unknown = [f for f in figs if f not in STREETS.values()]
    if unknown or any(a.startswith("-") for a in figs):
        sys.exit(__doc__)
    text = open(MANIFEST).read()
    # Blocks: the header, then one per [[row]] table (up to the next).
    parts = re.split(r"(?m)^(?=\[\[row\]\]\s*$)", text)
    out, changed = [parts[0]], 0
    for block in parts[1:]:
        name = re.search(r'(?m)^name = "([^"]*)"', block).group(1)
        level = street_level(name)
        # Rows the paper has no level for (time "-") stay as they are.
        if not level or level[0] not in figs or re.search(r'(?m)^paper = .*time = "-"', block):
            out.append(block)
            continue
        fig, n = level
        keep = [l for l in block.split("\n")
                if not re.match(r"(spec|missing) = ", l) and not l.startswith("# frozen from")]
        spec, info = freeze(fig, n)
        new = []
        if spec:
            new.append(f'spec = "{spec}"')
            if info.get("termination"):
                obj = "-" if info["objective"] is None else f"{info['objective']:.6g}"
                new.append(f"# frozen from `netspec city models/city/{fig}.toml`; that run's own solve: "
                           f"{info['termination']}, objective {obj}")
        else:
            new.append(f'missing = "{info}"')
        i = next(i for i, l in enumerate(keep) if l.startswith("name = ")) + 1
        out.append("\n".join(keep[:i] + new + keep[i:]))
        changed += 1
        print(f"{name}: {spec or info}")
    open(MANIFEST, "w").write("".join(out))
    print(f"models/table1.toml: {changed} street rows of {', '.join(figs)} written")


if __name__ == "__main__":
    main()
