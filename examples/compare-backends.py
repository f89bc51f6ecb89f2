# %% [markdown]
# # Comparing backends on the Fig. 2 rows
#
# The rows of Peng et al.'s Fig. 2 (models/fig2*.toml), built into MILPs, solved on every
# compiled backend, and drawn as a performance profile: the fraction of runs solved (optimal and
# valid, or proven infeasible) within time t. Run it as a script
# (`python examples/compare-backends.py`) or cell by cell (`# %%`) in an editor that knows the
# cells. `NETSPEC_EXAMPLE_TIME_LIMIT` (seconds per run, default 60) and `NETSPEC_EXAMPLE_ROWS`
# (comma-separated, default every Fig. 2 row) make it shorter; the picture goes to
# out/compare-backends/profile.png.

# %%
from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt

import netspec

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "compare-backends"
TIME_LIMIT = float(os.environ.get("NETSPEC_EXAMPLE_TIME_LIMIT", "60"))
ROWS = os.environ.get("NETSPEC_EXAMPLE_ROWS", "fig2a,fig2b,fig2c,fig2d,fig2e,fig2f,fig2g").split(",")

# %% [markdown]
# The rows and the size of their MILPs (the spec's own formulation, as `netspec solve` builds
# it; `--export` writes the same model).

# %%
specs = [netspec.read_spec(ROOT / "models" / f"{row}.toml") for row in ROWS]
for spec in specs:
    model = spec.build()
    print(f"{spec.name:8} {model.num_vars:6} vars {model.num_rows:6} rows {model.num_nonzeros:7} nonzeros  {spec.description}")

# %% [markdown]
# Every row on every compiled backend (the searches left out), one run after the other, as
# `netspec compare` runs them. The records have the fields of its `run.json`; `records_frame`
# gives the columns of its `results.csv`.

# %%
backends = [s["name"] for s in netspec.solvers()]
records = netspec.compare([s.path for s in specs if s.path], solvers=backends, time_limit=TIME_LIMIT, out=OUT)
frame = netspec.records_frame(records)
print(frame[["instance", "solver", "status", "objective", "gap", "wall_time", "valid"]].to_string(index=False))

# %% [markdown]
# The performance profile: for each backend, the fraction of its runs solved within t seconds.


# %%
def solved(r: dict[str, object]) -> bool:
    return (r["status"] == "optimal" and bool(r["valid"])) or r["status"] == "infeasible"


fig, ax = plt.subplots(figsize=(6, 4))
for backend in backends:
    mine = [r for r in records if r["solver"] == backend]
    times = sorted(float(str(r["wall_time"])) for r in mine if solved(r))
    xs = [0.01] + [t for t in times for _ in (0, 1)] + [TIME_LIMIT]
    ys = [0.0] + [v for i in range(len(times)) for v in (i / len(mine), (i + 1) / len(mine))] + [len(times) / len(mine)]
    ax.step(xs, ys, where="post", label=backend)
ax.set_xscale("log")
ax.set_xlim(0.01, TIME_LIMIT)
ax.set_ylim(0, 1.02)
ax.set_xlabel("time t (s)")
ax.set_ylabel("fraction solved within t")
ax.set_title(f"Fig. 2 rows, limit {TIME_LIMIT:g} s")
ax.legend()
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "profile.png", dpi=120, bbox_inches="tight")
print(f"wrote {OUT / 'profile.png'} and {OUT / 'results.csv'}")
