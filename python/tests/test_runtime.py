"""A solve from Python behaves like one from the command line: Ctrl-C stops the backend and
keeps its best design, progress reaches a callback, and the GIL is released while it runs."""

from __future__ import annotations

import os
import signal
import threading
import time

import netspec
from conftest import LONG


def test_keyboard_interrupt_returns_the_best_design_within_two_seconds() -> None:
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    try:
        r = netspec.solve(LONG, time_limit=120, threads=1)
    finally:
        timer.cancel()
    elapsed = time.monotonic() - t0
    assert r.termination == "interrupted", r.status
    assert r.valid and r.design is not None
    assert elapsed < 1.0 + 2.0, elapsed


def test_progress_reaches_the_callback_and_its_exception_stops_the_solve() -> None:
    seen: list[netspec.Progress] = []
    r = netspec.solve(LONG, time_limit=3, threads=1, on_progress=seen.append)
    assert r.termination == "limit(time)" and r.valid
    assert seen, "no progress reported"
    # HiGHS reports its bound from the root on (its incumbent once its own search has one).
    assert any(p.bound is not None for p in seen)
    assert all(p.incumbent is None or p.bound is None or p.bound <= p.incumbent + 1e-6 for p in seen)
    assert all(p.elapsed >= 0 and p.nodes >= 0 for p in seen) and "incumbent=" in repr(seen[0])

    def fail(p: netspec.Progress) -> None:
        raise ZeroDivisionError("from the callback")

    t0 = time.monotonic()
    try:
        netspec.solve(LONG, time_limit=30, threads=1, on_progress=fail)
    except ZeroDivisionError:
        pass
    else:
        raise AssertionError("the callback's exception was not raised")
    assert time.monotonic() - t0 < 15


def test_two_solves_in_two_threads_run_at_the_same_time() -> None:
    limit = 4.0
    times: list[float] = []
    results: list[netspec.Result] = []

    def one() -> None:
        t = time.monotonic()
        results.append(netspec.solve(LONG, time_limit=limit, threads=1))
        times.append(time.monotonic() - t)

    t0 = time.monotonic()
    threads = [threading.Thread(target=one) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    wall = time.monotonic() - t0
    assert len(results) == 2 and all(r.valid for r in results)
    # Each solve runs to its time limit; one after the other would take their sum.
    assert wall < 0.8 * sum(times), (wall, times)
