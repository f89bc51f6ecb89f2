"""The urban methods as functions: `layout`, `field`, `grow` (and its window) and `traffic`
return what the command writes, write the same files with `out`, and refuse bad arguments
naming them."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path
from typing import Any

import pytest

import netspec
from conftest import ROOT

#: A small GeoJSON site (about a second to lay out).
REGION = ROOT / "models" / "layout" / "irregular.geojson"
#: A TOML region of a few parcels (a quarter of a second).
SMALL_REGION = ROOT / "models" / "layout" / "fig7.toml"
#: A 1.26 km square map with a lake; a few steps grow in a fraction of a second.
CONTEXT = ROOT / "models" / "grow" / "small-lake.toml"
#: A window of that map.
WINDOW = (200.0, 300.0, 800.0, 900.0)


def read_json(path: Path) -> Any:
    return json.loads(path.read_text())


@pytest.fixture(scope="session")
def sumo() -> None:
    """SUMO, installed by `scripts/setup.sh sumo` as the Rust traffic tests do (required, not
    skipped: it is a no-op once installed)."""
    run = subprocess.run(["bash", str(ROOT / "scripts" / "setup.sh"), "sumo"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def test_layout_returns_each_variation_as_written(tmp_path: Path) -> None:
    heard: list[tuple[int, float]] = []
    layouts = netspec.layout(REGION, out=tmp_path, variations=2, on_progress=lambda k, f: heard.append((k, f)))
    assert len(layouts) == 2
    first, second = layouts
    assert first == read_json(tmp_path / "layout.json")
    assert second == read_json(tmp_path / "variation-2" / "layout.json")
    assert first["name"] == "irregular" and first["seed"] == 5 and second["seed"] == 6
    assert first["selection"] == "best" and second["selection"] == "random"
    assert first["violations"] == [] and first["metrics"]["parcels"] == len(first["parcels"]) > 100
    assert len(first["streets"]) > 10 and first["origin"] is not None
    for f in ["layout.svg", "layout.png", "layout.geojson", "run.json", "variation-2/histograms.png"]:
        assert (tmp_path / f).is_file(), f
    # Each draws itself in a notebook: the picture `layout.svg` holds.
    assert isinstance(first, netspec.Drawn) and isinstance(first, dict)
    assert first._repr_svg_() == first.svg == (tmp_path / "layout.svg").read_text()
    assert second.svg == (tmp_path / "variation-2" / "layout.svg").read_text() != first.svg
    # Progress of both variations, each settling its whole area.
    assert {k for k, _ in heard} == {0, 1}
    assert max(f for k, f in heard if k == 1) == pytest.approx(1.0)


def test_layout_without_out_writes_nothing_and_matches_the_command(tmp_path: Path, netspec_bin: Path) -> None:
    (layout,) = netspec.layout(SMALL_REGION, seed=3, mode="random", field="smooth")
    assert list(tmp_path.iterdir()) == []
    run = subprocess.run(
        [str(netspec_bin), "layout", str(SMALL_REGION), "--seed", "3", "--mode", "random", "--field", "smooth"]
        + ["--out", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    assert layout == read_json(tmp_path / "layout.json")


def test_layout_refuses_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="^variations: must be 1 to 1000, got 0"):
        netspec.layout(SMALL_REGION, variations=0)
    with pytest.raises(ValueError, match="^optimise: must be 0 to 100"):
        netspec.layout(SMALL_REGION, optimise=101)
    with pytest.raises(ValueError, match="^mode: "):
        netspec.layout(SMALL_REGION, mode="worst")
    with pytest.raises(ValueError, match="^field: "):
        netspec.layout(SMALL_REGION, field="wavy")
    with pytest.raises(ValueError, match="^from_layout: "):
        netspec.layout(SMALL_REGION, relayout="0")
    with pytest.raises(ValueError, match="^variations: cannot be used with a relayout"):
        netspec.layout(SMALL_REGION, from_layout=tmp_path / "layout.json", relayout="0", variations=2)
    with pytest.raises(netspec.NetspecError, match="no-such-region.toml"):
        netspec.layout(tmp_path / "no-such-region.toml")
    assert list(tmp_path.iterdir()) == []


def test_field_returns_field_json(tmp_path: Path, netspec_bin: Path) -> None:
    f = netspec.field(REGION, tmp_path / "py", h=10.0)
    assert f == read_json(tmp_path / "py" / "field.json")
    assert f["method"] == "distance" and f["vertices"] == len(f["field"]["points"]) == len(f["field"]["theta"]) > 100
    assert all(set(s) == {"x", "y", "index"} for s in f["singularities"])
    assert (tmp_path / "py" / "field.png").is_file()
    run = subprocess.run(
        [str(netspec_bin), "field", str(REGION), "--h", "10", "--out", str(tmp_path / "cli")],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "cli" / "field.json").read_bytes() == (tmp_path / "py" / "field.json").read_bytes()
    smooth = netspec.field(REGION, tmp_path / "smooth", method="smooth")
    assert smooth["method"] == "smooth"


def test_field_refuses_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="^h: must be a positive number of metres, got -1"):
        netspec.field(REGION, tmp_path, h=-1.0)
    with pytest.raises(ValueError, match="^method: "):
        netspec.field(REGION, tmp_path, method="wavy")
    assert list(tmp_path.iterdir()) == []


def test_grow_then_window(tmp_path: Path) -> None:
    heard: list[tuple[int, int]] = []
    out = tmp_path / "grown"
    g = netspec.grow(CONTEXT, out, steps=3, every=3, on_progress=lambda k, n: heard.append((k, n)))
    assert heard == [(0, 3), (1, 3), (2, 3), (3, 3)]
    s = g["summary"]
    assert g["window"] is None
    assert s["seed"] == 5 and s["last"]["step"] == 3 and s["violations"] == []
    network = read_json(out / "network.json")
    assert network["violations"] == s["violations"]
    assert s["last"]["blocks"] > 0 and s["last"]["major_km"] > 0
    for f in s["files"]:
        assert Path(f).is_file(), f
    assert (out / "step-003.svg").is_file() and (out / "series.csv").is_file()
    assert len((out / "series.csv").read_text().splitlines()) == 1 + 4
    assert isinstance(g, netspec.Drawn) and g._repr_svg_() == (out / "network.svg").read_text()

    # The window of the grown network: only windowed, nothing grown.
    w = netspec.grow(out, tmp_path / "win", window=WINDOW)
    assert w["summary"] is None
    win = w["window"]
    trade = read_json(tmp_path / "win" / "trade.json")
    assert win["flows"] == len(trade["flows"]) and trade["window"] == list(WINDOW)
    assert win["roads"] > 0 and win["regions"] >= 1
    assert sorted(Path(f).name for f in win["files"]) == ["city.toml", "trade.json"]
    assert 'name = "win"' in (tmp_path / "win" / "city.toml").read_text()

    # Grown and windowed in one call: the same window.
    both = netspec.grow(CONTEXT, tmp_path / "both", steps=3, window=WINDOW)
    assert both["summary"]["last"] == s["last"]
    assert {k: v for k, v in both["window"].items() if k != "files"} == {
        k: v for k, v in win.items() if k != "files"
    }


def test_grow_refuses_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="^every: must be at least 1"):
        netspec.grow(CONTEXT, tmp_path, every=0)
    with pytest.raises(ValueError, match="^context: .* is a directory"):
        netspec.grow(tmp_path, tmp_path / "out")
    bad = tmp_path / "bad.toml"
    bad.write_text(CONTEXT.read_text().replace("spacing = 20", "spacing = -20"))
    with pytest.raises(netspec.SpecError) as e:
        netspec.grow(bad, tmp_path / "out")
    assert e.value.field == "spacing" and e.value.path == str(bad)
    with pytest.raises(netspec.NetspecError, match="network.json"):
        netspec.grow(tmp_path, tmp_path / "out", window=WINDOW)


@pytest.mark.usefixtures("sumo")
def test_traffic_returns_traffic_json_and_the_comparison(tmp_path: Path) -> None:
    (tmp_path / "designs").mkdir()
    netspec.layout(SMALL_REGION, out=tmp_path / "designs" / "fig7")
    netspec.grow(CONTEXT, tmp_path / "designs" / "lake", steps=2)
    one = netspec.traffic(
        [tmp_path / "designs" / "fig7"], out=tmp_path / "one", duration=300.0, through_rate=120.0, local_rate=240.0
    )
    assert one == read_json(tmp_path / "one" / "traffic.json")
    assert one["vehicles"]["loaded"] >= 10 and one["vehicles"]["arrived"] == one["vehicles"]["inserted"]
    assert one["demand"]["settings"]["duration"] == 300.0 and one["demand"]["placed"] == one["vehicles"]["loaded"]
    for f in ["volume.png", "traveltime.svg", "sumo/net.net.xml"]:
        assert (tmp_path / "one" / f).is_file(), f
    both = netspec.traffic(
        [tmp_path / "designs" / "fig7", tmp_path / "designs" / "lake"],
        out=tmp_path / "both",
        labels=["layout", "grown"],
        duration=300.0,
        through_rate=120.0,
        local_rate=240.0,
    )
    assert both == read_json(tmp_path / "both" / "comparison.json")
    assert [d["label"] for d in both["designs"]] == ["layout", "grown"]
    assert both["designs"][0]["report"]["demand"] == one["demand"]
    assert both["designs"][1]["report"]["vehicles"]["loaded"] >= 10
    assert (tmp_path / "both" / "grown" / "traffic.json").is_file()
    assert "| layout |" in (tmp_path / "both" / "comparison.md").read_text()


@pytest.mark.usefixtures("sumo")
def test_traffic_refuses_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="^designs: give at least one"):
        netspec.traffic([], out=tmp_path)
    with pytest.raises(ValueError, match="^level: must be 1 to 4, got 7"):
        netspec.traffic([tmp_path], out=tmp_path, level=7)
    with pytest.raises(ValueError, match="^time_limit: must be a positive number of seconds, got -1"):
        netspec.traffic([tmp_path], out=tmp_path, time_limit=-1.0)
    with pytest.raises(netspec.NetspecError, match="no design here"):
        netspec.traffic([tmp_path], out=tmp_path / "out")


def test_an_exception_in_on_progress_stops_the_layouts(tmp_path: Path) -> None:
    def stop(k: int, f: float) -> None:
        raise KeyError("stop")

    with pytest.raises(KeyError, match="stop"):
        netspec.layout(REGION, out=tmp_path, variations=3, on_progress=stop)
    # The first layout is made and written; no further variation is started.
    assert (tmp_path / "layout.json").is_file()
    assert not (tmp_path / "variation-2").exists()


def test_ctrl_c_stops_grow_after_its_step_and_writes_the_network(tmp_path: Path) -> None:
    hills = ROOT / "models" / "grow" / "hills.toml"
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    try:
        g = netspec.grow(hills, tmp_path, steps=1000)
    finally:
        timer.cancel()
    elapsed = time.monotonic() - t0
    last = g["summary"]["last"]
    assert last["step"] < 1000 and elapsed < 20.0, (last["step"], elapsed)
    # The network grown so far is checked and written, its series up to the last step.
    assert read_json(tmp_path / "network.json")["violations"] == g["summary"]["violations"]
    assert len((tmp_path / "series.csv").read_text().splitlines()) == 1 + 1 + last["step"]
