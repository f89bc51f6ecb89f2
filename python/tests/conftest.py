"""Shared paths of the Python package's tests: the repository, the test specs, the `netspec`
binary the results are compared against (NETSPEC_BIN, set by `./dev test`)."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"
#: Solved to optimality in about a second.
SMALL = DATA / "small_6x6.toml"
#: Found infeasible before the solve.
INFEASIBLE = DATA / "infeasible_6x6.toml"
#: A spec error in `user.forced_vertices[0]`.
BAD = DATA / "bad_forced.toml"
#: The 4 × 4 instance of the compare tests (tight formulation).
TINY = ROOT / "fixtures" / "specs" / "tiny_network.toml"
#: Fig. 2a: far from solved within a minute (the long solves of the interrupt and thread tests).
LONG = ROOT / "models" / "fig2a.toml"


@pytest.fixture(scope="session")
def netspec_bin() -> Path:
    """The `netspec` binary of the same build."""
    env = os.environ.get("NETSPEC_BIN")
    candidates = [Path(env)] if env else []
    target = os.environ.get("CARGO_TARGET_DIR")
    if target:
        candidates.append(Path(target) / "release" / "netspec")
    which = shutil.which("netspec")
    if which:
        candidates.append(Path(which))
    for c in candidates:
        if c.is_file():
            return c
    pytest.skip("no netspec binary (set NETSPEC_BIN)")
    raise AssertionError  # unreachable
