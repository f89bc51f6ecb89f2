"""The examples run (shortened: one row, a short limit, matplotlib's Agg backend; a few growth
steps) and the package's stubs, the examples and the tests pass mypy."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT


def test_the_compare_backends_example_runs(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    pytest.importorskip("pandas")
    env = dict(os.environ, MPLBACKEND="Agg", NETSPEC_EXAMPLE_TIME_LIMIT="2", NETSPEC_EXAMPLE_ROWS="fig2d")
    run = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "compare-backends.py")],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert run.returncode == 0, run.stderr
    assert "fig2d" in run.stdout and "highs" in run.stdout
    assert (ROOT / "out" / "compare-backends" / "profile.png").is_file()


def test_the_site_layout_grow_example_runs(tmp_path: Path) -> None:
    pytest.importorskip("pandas")
    env = dict(os.environ, NETSPEC_EXAMPLE_OUT=str(tmp_path), NETSPEC_EXAMPLE_STEPS="3")
    run = subprocess.run(
        [sys.executable, str(ROOT / "python" / "examples" / "site_layout_grow.py")],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert run.returncode == 0, run.stderr
    assert "layout of irregular:" in run.stdout and "grown for 3 steps" in run.stdout
    assert (tmp_path / "layout" / "layout.json").is_file() and (tmp_path / "grow" / "network.json").is_file()
    rows = {line.split(",")[0]: line.split(",")[1:] for line in (tmp_path / "stats.csv").read_text().splitlines()}
    assert rows[""] == ["layout", "grown"]
    assert all(float(v) > 0 for v in rows["intersection_count"] + rows["street_length_total"] + rows["blocks"])


def test_mypy_passes_on_the_stubs_the_example_and_the_tests() -> None:
    pytest.importorskip("mypy")
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--strict",
            "--ignore-missing-imports",
            str(ROOT / "python" / "netspec"),
            str(ROOT / "examples" / "compare-backends.py"),
            str(ROOT / "python" / "examples" / "site_layout_grow.py"),
            str(ROOT / "python" / "tests"),
            str(ROOT / "python" / "bench"),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT / "python",
    )
    assert run.returncode == 0, run.stdout + run.stderr
