"""The Python package's overhead: `netspec.solve(spec, threads=1, start=False)` against the
same solve through the library in Rust (examples/solve_timing.rs, `netspec::run::solve_loaded`,
timed inside its process), alternately, on a small and a large spec; prints a Markdown table of
the medians of wall time and of CPU time (all threads) for docs/python.md. Without the MIP
start's time budget both solves take the same path (one thread: the same nodes).

    python python/bench/overhead.py [RUNS]   (with the package installed and
                                              $CARGO_TARGET_DIR/release/examples/solve_timing built)
"""

from __future__ import annotations

import os
import resource
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


def rust(spec: Path) -> tuple[float, float, str]:
    """Wall seconds (inside the process), CPU seconds (the whole process) and the objective."""
    def children() -> float:
        u = resource.getrusage(resource.RUSAGE_CHILDREN)
        return u.ru_utime + u.ru_stime

    c0 = children()
    out = subprocess.run([str(TIMING), str(spec), "1", "--no-start"], capture_output=True, text=True, check=True)
    words = out.stdout.split()
    return float(words[0]), children() - c0, words[1]


def python(spec: Path) -> tuple[float, float, str]:
    t0, c0 = time.perf_counter(), time.process_time()
    r = netspec.solve(spec, threads=1, start=False)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    return seconds, cpu, "-" if r.objective is None else repr(r.objective)


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    print("| spec | | Rust (median s) | Python (median s) | difference | objective |")
    print("|---|---|---:|---:|---:|---|")
    for spec in SPECS:
        walls: tuple[list[float], list[float]] = ([], [])
        cpus: tuple[list[float], list[float]] = ([], [])
        objectives = set()
        for _ in range(runs):
            for side, run in enumerate((rust, python)):
                wall, cpu, objective = run(spec)
                walls[side].append(wall)
                cpus[side].append(cpu)
                objectives.add(float(objective))
        for what, (rs, ps) in (("wall", walls), ("CPU", cpus)):
            r, p = statistics.median(rs), statistics.median(ps)
            print(
                f"| {spec.stem} | {what} | {r:.3f} | {p:.3f} | {1000 * (p - r):+.0f} ms ({100 * (p - r) / r:+.1f} %) | "
                f"{', '.join(f'{o:g}' for o in sorted(objectives))} |"
            )


if __name__ == "__main__":
    main()
