"""Solves from two Python threads give the CLI's bytes; Python runs on while one solves (the
GIL is released), and Ctrl-C stops a long solve within a second."""

import os
import signal
import threading
import time

import pytest

import gbxc
from conftest import ROOT, cli

SPECS = [ROOT / "specs" / "helical_reducer.gbx", ROOT / "specs" / "spur_resonance.gbx"]


def test_two_threads_give_the_clis_bytes():
    expected = [cli("solve", str(s), "--format", "json", "--no-timings", "-q")[0] for s in SPECS]
    results = [None] * len(SPECS)

    def run(i):
        results[i] = gbxc.solve(str(SPECS[i]), timings=False, jobs=2).to_json()

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(SPECS))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == expected


def test_python_runs_while_a_solve_runs():
    done = threading.Event()
    ticks = 0

    def solve():
        gbxc.solve(str(SPECS[0]), timings=False)
        done.set()

    t = threading.Thread(target=solve)
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    assert ticks > 10


def test_ctrl_c_stops_a_long_solve_within_a_second():
    spec = ROOT / "specs" / "marine_reducer.gbx"  # a minute of optimisation
    for after in (0.5, 1.0, 2.0, 4.0):  # inside the stage filter's ratings and after it
        timer = threading.Timer(after, os.kill, (os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            gbxc.solve(str(spec), timings=False)
        stopped = time.monotonic() - start
        timer.join()
        assert stopped < after + 1.0, f"Ctrl-C at {after} s stopped the solve at {stopped:.2f} s"
    # The process solves again afterwards, with nothing left of the interrupt.
    again = gbxc.solve(str(SPECS[0]), timings=False)
    assert again.to_json() == cli("solve", str(SPECS[0]), "--format", "json", "--no-timings", "-q")[0]


def test_ctrl_c_stops_its_own_solve_not_the_next_one():
    expected = cli("solve", str(SPECS[0]), "--format", "json", "--no-timings", "-q")[0]
    queued = {}

    def second():
        queued["json"] = gbxc.solve(str(SPECS[0]), timings=False).to_json()

    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    other = threading.Thread(target=second)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        other.start()  # waits for the long solve below, then solves
        gbxc.solve(str(ROOT / "specs" / "marine_reducer.gbx"), timings=False)
    other.join()
    timer.join()
    assert queued["json"] == expected


def test_jobs_are_worker_threads_from_any_thread():
    """A solve from a thread of Python's, not the main one, shares its work over `jobs`
    threads: more threads run during it than the one solving."""
    task = "/proc/self/task"
    before = set(os.listdir(task))
    seen = set()
    result = {}

    def run():
        result["report"] = gbxc.solve(str(ROOT / "specs" / "marine_tolerances.gbx"), timings=False, jobs=2)

    t = threading.Thread(target=run)
    t.start()
    while t.is_alive():
        seen |= set(os.listdir(task))
        time.sleep(0.002)
    t.join()
    assert result["report"].ok
    assert len(seen - before) >= 3  # the waiting thread, the solving thread and a worker or more
