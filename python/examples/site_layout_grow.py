# %% [markdown]
# # A site laid out, a context grown, both measured
#
# Lays out a GeoJSON site by domain splitting (`netspec layout`), grows a road network from a
# context (`netspec grow`), and puts the street statistics of both (`netspec stats`) side by
# side in a pandas DataFrame. Outputs go to `out/site-layout-grow/` (or
# `$NETSPEC_EXAMPLE_OUT`); `$NETSPEC_EXAMPLE_STEPS` shortens the growth (the tests run it with
# a few steps).

# %%
from __future__ import annotations

import os
from pathlib import Path

import netspec

ROOT = Path(__file__).resolve().parents[2]
OUT = Path(os.environ.get("NETSPEC_EXAMPLE_OUT", str(ROOT / "out" / "site-layout-grow")))
STEPS = int(os.environ.get("NETSPEC_EXAMPLE_STEPS", "20"))
REGION = ROOT / "models" / "layout" / "irregular.geojson"
CONTEXT = ROOT / "models" / "grow" / "small-lake.toml"

# %% [markdown]
# ## The layout of the site
#
# One layout, checked independently (`violations` is empty when it passes); the progress
# callback hears the share of the area settled.

# %%
settled: list[float] = []
(layout,) = netspec.layout(REGION, out=OUT / "layout", on_progress=lambda k, share: settled.append(share))
m = layout["metrics"]
print(
    f"layout of {layout['name']}: {len(layout['streets'])} streets, {m['parcels']} parcels, "
    f"{len(layout['violations'])} violations, {len(settled)} progress reports"
)

# %% [markdown]
# ## A grown network
#
# The context's map grown for `STEPS` steps; the summary holds the last step's measures.

# %%
grown = netspec.grow(CONTEXT, OUT / "grow", steps=STEPS)
last = grown["summary"]["last"]
print(
    f"grown for {last['step']} steps: {last['blocks']} blocks, {last['minor_km']:.1f} km minor, "
    f"{last['major_km']:.1f} km major road"
)

# %% [markdown]
# ## Side by side
#
# `netspec.stats` measures both designs as `netspec stats --json` does; `stats_frame` makes a
# row per design. The numeric statistics, a column per design, are written to `stats.csv`.

# %%
designs = netspec.stats([OUT / "layout", OUT / "grow"], labels=["layout", "grown"])
frame = netspec.stats_frame(designs).set_index("label").select_dtypes("number")
frame.T.to_csv(OUT / "stats.csv")
print(frame.T.to_string())
