"""`netspec stats` checked against OSMnx itself (pinned in requirements-dev.txt; no downloads).

Each case builds a street graph by hand in a transverse Mercator frame, gives it to OSMnx
(`simplify_graph`, `count_streets_per_node`, `basic_stats` with the area and
`clean_int_tol=10`, `orientation_entropy` of the undirected graph weighted by length) and, as a
GeoJSON of streets naming their end nodes (`u`, `v`), to `netspec stats --json`, and asserts
that the two agree:

* counts (nodes, edges, streets per node, intersections, clean intersections, streets) exactly;
* lengths, averages, circuity, densities and the entropy to a relative 1e-6 (the streets pass
  through WGS 84 with 1e-9° of rounding, and netspec measures in its own projection of them).

Two places where the definitions could differ only in floating point are kept out of the test
graphs by construction, and said here: OSMnx measures bearings on the sphere (great-circle initial
bearing between the end nodes) where netspec measures them in the local plane — they differ by
the meridian convergence, under 0.01° within a kilometre of the frame's centre — so no street's
bearing is within 0.05° of a bin edge; and OSMnx merges intersections whose 64-gon buffers of
radius 10 m overlap where netspec uses exact discs, so no two junctions are 19.5–20.5 m apart.
"""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np
import osmnx as ox
import pyproj
import pytest
from shapely.geometry import LineString

LON0, LAT0 = 24.94, 60.17
TM = pyproj.CRS.from_proj4(
    f"+proj=tmerc +lat_0={LAT0} +lon_0={LON0} +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs"
)
TO_LL = pyproj.Transformer.from_crs(TM, "EPSG:4326", always_xy=True)


class Graph:
    """Nodes (metres) and streets: (u, v, polyline, oneway)."""

    def __init__(self) -> None:
        self.nodes: dict[int, tuple[float, float]] = {}
        self.streets: list[tuple[int, int, list[tuple[float, float]], bool]] = []

    def node(self, i: int, x: float, y: float) -> None:
        self.nodes[i] = (x, y)

    def street(self, u: int, v: int, bend: tuple[float, float] | None = None, oneway: bool = False) -> None:
        pts = [self.nodes[u]] + ([bend] if bend else []) + [self.nodes[v]]
        self.streets.append((u, v, pts, oneway))


def length(pts: list[tuple[float, float]]) -> float:
    return sum(math.dist(a, b) for a, b in zip(pts, pts[1:]))


def grid(k: int = 6, s: float = 100.0, midpoints: bool = True) -> Graph:
    """A k × k grid of two-way streets; horizontal streets pass through a mid-block node; a
    30 m stub leaves each corner westwards or eastwards (so that no corner is merged into an L
    whose chord runs at 45°, a bin edge)."""
    g = Graph()
    for j in range(k):
        for i in range(k):
            g.node(j * k + i, i * s, j * s)
    for n, (i, j) in enumerate([(0, 0), (k - 1, 0), (0, k - 1), (k - 1, k - 1)]):
        g.node(20_000 + n, i * s + (30.0 if i else -30.0), j * s)
        g.street(j * k + i, 20_000 + n)
    mid = 10_000
    for j in range(k):
        for i in range(k):
            if i + 1 < k:
                if midpoints:
                    g.node(mid, (i + 0.5) * s, j * s)
                    g.street(j * k + i, mid)
                    g.street(mid, j * k + i + 1)
                    mid += 1
                else:
                    g.street(j * k + i, j * k + i + 1)
            if j + 1 < k:
                g.street(j * k + i, (j + 1) * k + i)
    return g


def perturbed(seed: int) -> Graph:
    """A 6 × 6 grid with jittered nodes, bent streets and a fifth of the streets removed."""
    rng = np.random.default_rng(seed)
    k, s = 6, 110.0
    g = Graph()
    for j in range(k):
        for i in range(k):
            g.node(j * k + i, i * s + rng.uniform(-25, 25), j * s + rng.uniform(-25, 25))
    for j in range(k):
        for i in range(k):
            for di, dj in ((1, 0), (0, 1)):
                if i + di < k and j + dj < k and rng.uniform() > 0.2:
                    u, v = j * k + i, (j + dj) * k + i + di
                    (ax, ay), (bx, by) = g.nodes[u], g.nodes[v]
                    bend = ((ax + bx) / 2 + rng.uniform(-15, 15), (ay + by) / 2 + rng.uniform(-15, 15))
                    g.street(u, v, bend)
    return g


def tree(seed: int) -> Graph:
    """A random tree of 40 streets grown from one node: dead ends and 3- and 4-way nodes."""
    rng = np.random.default_rng(seed)
    g = Graph()
    g.node(0, 0.0, 0.0)
    for n in range(1, 41):
        parent = int(rng.integers(0, n))
        px, py = g.nodes[parent]
        a = rng.uniform(0, 2 * math.pi)
        r = rng.uniform(60, 120)
        g.node(n, px + r * math.cos(a), py + r * math.sin(a))
        g.street(parent, n)
    return g


def near_junctions() -> Graph:
    """A grid whose junctions come in pairs 6–14 m apart on some streets (a dual carriageway's
    crossings), a pair 30 m apart (not merged), a one-way row and a loop at a dead end."""
    g = grid(5, 120.0, midpoints=False)
    g.node(500, 240.0 + 8.0, 240.0 + 6.0)  # 10 m from junction (240, 240)
    g.street(12, 500)
    g.node(501, 248.0 + 40.0, 246.0)
    g.street(500, 501)
    g.node(506, 251.0, 300.0)
    g.street(500, 506)
    g.node(502, 360.0 + 14.0, 120.0)  # 14 m east of junction (360, 120) on the street
    g.node(503, 360.0 + 44.0, 120.0)  # 30 m further east
    g.node(504, 374.0, 170.0)
    g.node(505, 404.0, 60.0)
    g.street(502, 504)
    g.street(503, 505)
    g.streets = [t for t in g.streets if not (t[0] == 8 and t[1] == 9)]
    g.street(8, 502)
    g.street(502, 503)
    g.street(503, 9)
    # One-way: the bottom row runs east.
    g.streets = [(u, v, p, True if (u < 5 and v < 5) else o) for u, v, p, o in g.streets]
    # A loop at the end of a cul-de-sac.
    g.node(600, 480.0 + 50.0, 480.0)
    g.street(24, 600)
    g.streets.append((600, 600, [(530.0, 480.0), (570.0, 500.0), (570.0, 460.0), (530.0, 480.0)], True))
    return g


CASES = {
    "grid": lambda: grid(),
    "perturbed": lambda: perturbed(3),
    "tree": lambda: tree(2),
    "near": near_junctions,
}


def bin_edge_distance(bearings: list[float]) -> float:
    """The smallest distance (degrees) of a bearing from a bin edge (5° + 10°k)."""
    return min([180.0] + [min((b - 5.0) % 10.0, 10.0 - (b - 5.0) % 10.0) for b in bearings])


def junction_gaps(g: Graph) -> list[float]:
    deg: dict[int, int] = {}
    for u, v, _, _ in g.streets:
        deg[u] = deg.get(u, 0) + 1
        deg[v] = deg.get(v, 0) + 1
    js = [g.nodes[n] for n, d in deg.items() if d >= 2]
    return [math.dist(a, b) for i, a in enumerate(js) for b in js[i + 1 :]]


def region(g: Graph) -> list[tuple[float, float]]:
    xs = [p[0] for p in g.nodes.values()]
    ys = [p[1] for p in g.nodes.values()]
    x0, x1, y0, y1 = min(xs) - 50, max(xs) + 50, min(ys) - 50, max(ys) + 50
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def ll(p: tuple[float, float]) -> list[float]:
    lon, lat = TO_LL.transform(*p)
    return [round(lon, 9), round(lat, 9)]


def geojson(g: Graph) -> dict[str, Any]:
    ring = region(g)
    feats = [
        {
            "type": "Feature",
            "properties": {"kind": "region", "origin": [LON0, LAT0]},
            "geometry": {"type": "Polygon", "coordinates": [[ll(p) for p in ring + ring[:1]]]},
        }
    ]
    for u, v, pts, oneway in g.streets:
        feats.append(
            {
                "type": "Feature",
                "properties": {"kind": "street", "u": u, "v": v, "oneway": oneway, "level": 3},
                "geometry": {"type": "LineString", "coordinates": [ll(p) for p in pts]},
            }
        )
    return {"type": "FeatureCollection", "features": feats}


def osmnx_stats(g: Graph) -> tuple[dict[str, Any], float, list[float]]:
    G = nx.MultiDiGraph(crs=TM)
    for n, (x, y) in g.nodes.items():
        G.add_node(n, x=x, y=y)
    for k, (u, v, pts, oneway) in enumerate(g.streets):
        attrs = {"osmid": k, "length": length(pts), "oneway": oneway}
        G.add_edge(u, v, geometry=LineString(pts), **attrs)
        if not oneway:
            G.add_edge(v, u, geometry=LineString(pts[::-1]), **attrs)
    G.remove_nodes_from([n for n in list(G.nodes) if G.degree(n) == 0])
    G = ox.simplification.simplify_graph(G)
    nx.set_node_attributes(G, ox.stats.count_streets_per_node(G), name="street_count")
    ring = region(g)
    area = abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(ring, ring[1:] + ring[:1]))) / 2
    stats = ox.stats.basic_stats(G, area=area, clean_int_tol=10)
    Gll = ox.projection.project_graph(G, to_latlong=True)
    Gll = ox.bearing.add_edge_bearings(Gll)
    entropy = ox.bearing.orientation_entropy(ox.convert.to_undirected(Gll), num_bins=36, weight="length")
    bearings = [float(d["bearing"]) for u, v, d in Gll.edges(data=True) if u != v]
    return stats, float(entropy), bearings


@pytest.mark.parametrize("case", sorted(CASES))
def test_netspec_stats_agree_with_osmnx(case: str, netspec_bin: Path, tmp_path: Path) -> None:
    g = CASES[case]()
    theirs, entropy, bearings = osmnx_stats(g)
    assert bin_edge_distance(bearings) > 0.05, "a bearing sits on a bin edge: the case cannot tell definitions apart"
    assert not [d for d in junction_gaps(g) if 19.5 < d < 20.5], "junctions at the 64-gon's edge"
    path = tmp_path / f"{case}.geojson"
    path.write_text(json.dumps(geojson(g)))
    out = subprocess.run(
        [str(netspec_bin), "stats", str(path), "--json"], check=True, capture_output=True, text=True
    ).stdout
    ours = json.loads(out.splitlines()[0])["stats"]
    exact = ["n", "m", "intersection_count", "clean_intersection_count", "street_segment_count"]
    for key in exact:
        assert ours[key] == theirs[key], f"{case}: {key} netspec {ours[key]} OSMnx {theirs[key]}"
    counts = {int(k): v for k, v in ours["streets_per_node_counts"].items()}
    assert counts == {k: v for k, v in theirs["streets_per_node_counts"].items() if v}, case
    close = [
        "k_avg", "edge_length_total", "edge_length_avg", "streets_per_node_avg", "street_length_total",
        "street_length_avg", "circuity_avg", "self_loop_proportion", "node_density_km",
        "intersection_density_km", "clean_intersection_density_km", "edge_density_km", "street_density_km",
    ]
    for key in close:
        assert ours[key] == pytest.approx(theirs[key], rel=1e-6, abs=1e-9), f"{case}: {key}"
    for k, share in theirs["streets_per_node_proportions"].items():
        assert ours["streets_per_node_proportions"].get(str(k), 0.0) == pytest.approx(share, rel=1e-9), case
    assert ours["orientation_entropy"] == pytest.approx(entropy, rel=1e-6), case
    phi = 1 - ((entropy - math.log(4)) / (math.log(36) - math.log(4))) ** 2
    assert ours["orientation_order"] == pytest.approx(phi, rel=1e-6), case
