"""The Python package's overhead: `netspec.solve(spec)` against the same solve through the
library in Rust (examples/solve_timing.rs, `netspec::run::solve_loaded`, timed inside its
process), alternately, on a small and a large spec; prints a Markdown table (docs/python.md).

    python python/bench/overhead.py [RUNS]   (with the package installed and
                                              $CARGO_TARGET_DIR/release/examples/solve_timing built)
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import netspec

ROOT = Path(__file__).resolve().parents[2]
SPECS = [ROOT / "python" / "tests" / "data" / "small_6x6.toml", ROOT / "models" / "fig2d.toml"]
TARGET = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
TIMING = TARGET / "release" / "examples" / "solve_timing"


def rust(spec: Path) -> tuple[float, str]:
    out = subprocess.run([str(TIMING), str(spec), "1"], capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), out[1]


def python(spec: Path) -> tuple[float, str]:
    t0 = time.perf_counter()
    r = netspec.solve(spec, threads=1)
    seconds = time.perf_counter() - t0
    return seconds, "-" if r.objective is None else repr(r.objective)


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    print("| spec | Rust (median s) | Python (median s) | difference | objective |")
    print("|---|---:|---:|---:|---|")
    for spec in SPECS:
        rs: list[float] = []
        ps: list[float] = []
        objectives = set()
        for _ in range(runs):
            t, o = rust(spec)
            rs.append(t)
            objectives.add(float(o))
            t, o = python(spec)
            ps.append(t)
            objectives.add(float(o))
        r, p = statistics.median(rs), statistics.median(ps)
        print(
            f"| {spec.stem} | {r:.3f} | {p:.3f} | {1000 * (p - r):+.0f} ms ({100 * (p - r) / r:+.1f} %) | "
            f"{', '.join(f'{o:g}' for o in sorted(objectives))} |"
        )


if __name__ == "__main__":
    main()
