"""Real sites and street statistics from Python: `site` on an OSM extract the test writes (a
grid of residential streets, a primary road, a lake) makes the files `netspec site` makes, and
`stats` gives the dicts `netspec stats --json` prints; bad input raises, naming the argument."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path

import pytest

import netspec

LON0, LAT0 = 11.0, 48.0
BBOX = (11.002, 48.001, 11.012, 48.008)


def lonlat(x: float, y: float) -> tuple[float, float]:
    """Metres east and north of 11° E, 48° N as WGS 84 degrees."""
    return LON0 + x / (111_320.0 * math.cos(math.radians(LAT0))), LAT0 + y / 111_132.0


def town(path: Path) -> Path:
    """A small town as OSM XML: streets every 150 m, a primary road at y = 570, a lake."""
    nodes: list[tuple[int, float, float]] = []
    ways: list[tuple[list[int], dict[str, str]]] = []

    def node(x: float, y: float) -> int:
        nodes.append((len(nodes) + 1, x, y))
        return len(nodes)

    xs = [100.0 + 150.0 * i for i in range(7)]
    ys = [100.0 + 150.0 * j for j in range(6)]
    grid = [[node(x, y) for x in xs] for y in ys]
    for row in grid:
        ways.append((row, {"highway": "residential"}))
    for i in range(len(xs)):
        ways.append(([row[i] for row in grid], {"highway": "residential"}))
    ways.append(([node(0.0, 570.0), node(1100.0, 570.0)], {"highway": "primary"}))
    lake = [node(x, y) for x, y in [(420.0, 280.0), (560.0, 280.0), (560.0, 380.0), (420.0, 380.0)]]
    ways.append((lake + [lake[0]], {"natural": "water"}))
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<osm version="0.6" generator="test">']
    for i, x, y in nodes:
        lon, lat = lonlat(x, y)
        lines.append(f'  <node id="{i}" lat="{lat:.8f}" lon="{lon:.8f}"/>')
    for k, (refs, tags) in enumerate(ways):
        lines.append(f'  <way id="{1000 + k}">')
        lines += [f'    <nd ref="{r}"/>' for r in refs]
        lines += [f'    <tag k="{a}" v="{b}"/>' for a, b in tags.items()]
        lines.append("  </way>")
    lines.append("</osm>")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_site_and_its_statistics_are_the_binarys(netspec_bin: Path, tmp_path: Path) -> None:
    extract = town(tmp_path / "town.osm")
    made = netspec.site(extract, tmp_path / "py", bbox=BBOX, grow=True, name="town")
    assert made["holes"] == 1 and made["roads"][0] >= 1 and made["streets"][0] > 10
    assert 0.3 < made["land_km2"] < made["region_km2"] < 0.6
    written = {Path(f).name for f in made["files"]}
    assert {"site.geojson", "streets.geojson", "grow.toml"} <= written
    subprocess.run(
        [str(netspec_bin), "site", str(extract), "--bbox", ",".join(map(str, BBOX)), "--grow", "--name", "town", "--out", str(tmp_path / "cli")],
        check=True,
        capture_output=True,
    )
    for name in ["site.geojson", "map/streets.geojson", "grow.toml"]:
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text(), name

    region = tmp_path / "py" / "site.geojson"
    designs = netspec.stats([tmp_path / "py" / "map"], labels=["map"], region=region, out=tmp_path / "stats")
    assert [d["label"] for d in designs] == ["map"] and designs[0]["kind"] == "streets"
    assert designs[0]["stats"]["street_length_total"] > 3000 and designs[0]["stats"]["intersection_count"] > 20
    assert (tmp_path / "stats" / "stats.json").is_file()
    run = subprocess.run(
        [str(netspec_bin), "stats", str(tmp_path / "py" / "map"), "--labels", "map", "--region", str(region), "--json"],
        check=True,
        capture_output=True,
        text=True,
    )
    assert [json.loads(line) for line in run.stdout.splitlines()] == designs
    frame = netspec.stats_frame(designs)
    assert list(frame["label"]) == ["map"] and frame["street_length_total"][0] == designs[0]["stats"]["street_length_total"]


def test_bad_sites_and_designs_raise_naming_what_is_wrong(tmp_path: Path) -> None:
    extract = town(tmp_path / "town.osm")
    with pytest.raises(ValueError, match="exactly one of bbox or polygon"):
        netspec.site(extract, tmp_path / "a")
    with pytest.raises(ValueError, match="holes: `lava`"):
        netspec.site(extract, tmp_path / "a", bbox=BBOX, holes=["lava"])
    with pytest.raises(netspec.NetspecError, match="outside"):
        netspec.site(extract, tmp_path / "a", bbox=(20.0, 50.0, 20.01, 50.01))
    assert not (tmp_path / "a").exists()
    with pytest.raises(netspec.NetspecError, match="nowhere"):
        netspec.stats([tmp_path / "nowhere"])
    with pytest.raises(ValueError, match="clean_int_tol"):
        netspec.stats([tmp_path], clean_int_tol=-1.0)
