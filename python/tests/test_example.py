"""The example runs (shortened: one row, a short limit, matplotlib's Agg backend) and the
package's stubs, the example and the tests pass mypy."""

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
            str(ROOT / "python" / "tests"),
            str(ROOT / "python" / "bench"),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT / "python",
    )
    assert run.returncode == 0, run.stdout + run.stderr
