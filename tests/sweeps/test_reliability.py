"""Sweeps under careless input and failing machinery (issue 15): every bad study file is one
line, grids too large are refused before they are expanded, workers are bounded, worker
processes never outlive a killed sweep, and a Dask cluster that goes away ends the sweep in one
line with every completed case kept.

Oracles: the canonical case JSON (ids must not change: they key every existing store), the
process table (/proc), and the store's rows.
"""

from __future__ import annotations

import json
import math
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sweep_fake_model import SMALL_STUDY

from archquake.errors import StudyFileError
from archquake.parallel import cap_workers, threads_per_worker, usable_cores
from archquake.sweeps import load_study
from archquake.sweeps.cases import ArchSpec, Case, CaseOptions, ExcitationSpec, canonical_json
from archquake.sweeps.study import MAX_CASES

HERE = Path(__file__).parent

finite = st.floats(min_value=0.01, max_value=100, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(radius=st.floats(1e-3, 1e4), ratio=st.floats(0.01, 1.9), embrace=st.floats(1, 240),
       n=st.integers(3, 200), mag=st.floats(0, 50), dur=finite, sine=st.booleans(),
       direction=st.sampled_from([-1, 1]),
       restitution=st.one_of(st.none(), st.floats(0.01, 1)), t_end=st.one_of(st.none(), finite))
def test_assembled_case_json_is_the_canonical_json(radius, ratio, embrace, n, mag, dur, sine,
                                                    direction, restitution, t_end):
    """The fast id (specs' cached JSON joined) hashes the very string json.dumps writes for the
    whole case, so ids of existing stores do not move."""
    exc = (ExcitationSpec("sine", magnitude_g=mag, period_s=dur, direction=direction) if sine
           else ExcitationSpec("step", magnitude_g=mag, duration_s=dur, direction=direction))
    case = Case(ArchSpec(radius, ratio, embrace, n), exc,
                options=CaseOptions(restitution=restitution, t_end_s=t_end))
    assert case.canonical_json == canonical_json(case.canonical())


def _study(tmp_path: Path, text: str | bytes, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


def test_a_grid_over_the_bound_is_refused_before_expansion(tmp_path):
    big = SMALL_STUDY.replace("radius = [1, 5, 10]",
                              "radius = {start = 1, stop = 20, num = 10000}").replace(
        "num = 4", "num = 10000")
    t0 = time.perf_counter()
    with pytest.raises(StudyFileError) as err:
        load_study(_study(tmp_path, big))
    assert f"{MAX_CASES:,}" in str(err.value) and "split it" in str(err.value)
    assert "\n" not in str(err.value)
    assert time.perf_counter() - t0 < 30  # refused, not built (a 2e8 grid would take hours)


def test_a_range_num_beyond_the_bound_is_refused(tmp_path):
    with pytest.raises(StudyFileError, match=r"range num must be a whole number from 1 to"):
        load_study(_study(tmp_path, SMALL_STUDY.replace("num = 4", "num = 1000000000")))


@pytest.mark.parametrize("text, expected", [
    (SMALL_STUDY.replace('name = "small"', 'name = "small" # caf\xe9').encode("latin-1"),
     r"s.toml: line 2: byte 0xe9 is not UTF-8"),
    (SMALL_STUDY.replace("voussoirs = 7", "voussoirs = nan"),
     r"arches.voussoirs must be .* \(finite\), got nan"),
    (SMALL_STUDY.replace("thickness_ratio = 0.15", "thickness_ratio = inf"),
     r"arches.thickness_ratio must be .* \(finite\), got inf"),
    (SMALL_STUDY.replace("radius = [1, 5, 10]", "radius = 1e200"),
     r"arches.radius is invalid: radius must be in \[0.001, 10000\] \(m\), got 1e\+200"),
    (SMALL_STUDY.replace("radius = [1, 5, 10]", "radius = 1e-300"),
     r"arches.radius is invalid: radius must be in \[0.001, 10000\]"),
])
def test_bad_study_files_are_one_line(tmp_path, text, expected):
    with pytest.raises(StudyFileError, match=expected) as err:
        load_study(_study(tmp_path, text))
    assert "\n" not in str(err.value)


def test_the_documented_maximum_embrace_is_accepted(tmp_path):
    """degrees(radians(240)) = 239.99999999999997 once made 240 itself out of range."""
    study = load_study(_study(tmp_path, SMALL_STUDY.replace("embrace_deg = 157.5",
                                                            "embrace_deg = 240")))
    assert study.cases[0].arch.build().embrace == pytest.approx(math.radians(240), abs=0)


def test_cap_workers_at_cores_and_cases():
    cores = usable_cores()
    assert cap_workers(None, 1000) == (cores, None)
    n, note = cap_workers(1_000_000, 1000)
    assert n == cores and "not 1000000" in note and "usable core" in note
    n, note = cap_workers(max(2, cores), 1)
    assert n == 1 and "1 case to compute" in note
    assert cap_workers(1, 0) == (1, None)


def test_sweep_workers_beyond_the_cores_is_capped_with_a_line(small_study_file, capsys, sweep_cli):
    assert sweep_cli(["sweep", str(small_study_file), "--workers", "1000000", "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["computed_now"] == 24
    lines = [ln for ln in captured.err.splitlines() if "--workers" in ln]
    assert len(lines) == 1 and "not 1000000" in lines[0]


DRIVER = """
import sys
sys.path.insert(0, {here!r})
import sweep_fake_model
from archquake.cli import cmd_sweep, main as cli_main
cmd_sweep.case_function = lambda model: sweep_fake_model.slow_fake_evaluate
sys.exit(cli_main.main(["sweep", {study!r}, "--store", {store!r}, "--workers", "2",
                        "--chunk-size", "1", "--no-progress"]))
"""


def _descendants(pid: int) -> set[int]:
    """Every process below ``pid`` (a fork server's workers are its grandchildren)."""
    parent_of = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            parent_of[int(entry.name)] = int(fields[1])
    out: set[int] = set()
    frontier = {pid}
    while frontier:
        frontier = {p for p, pp in parent_of.items() if pp in frontier} - out
        out |= frontier
    return out


def _rows(store: Path) -> int:
    try:
        db = sqlite3.connect(f"file:{store}?mode=ro", uri=True)
    except sqlite3.Error:  # not created yet
        return 0
    try:
        return db.execute("SELECT COUNT(*) FROM results").fetchone()[0]
    except sqlite3.Error:  # no table yet
        return 0
    finally:
        db.close()


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


@pytest.mark.skipif(not Path("/proc").is_dir() or usable_cores() < 2, reason="needs /proc and 2 cores")
def test_worker_processes_end_with_a_killed_sweep(tmp_path):
    """SIGKILL on `archquake sweep` (which cannot clean up) still ends its worker processes
    (every process below it: a fork server's workers are its grandchildren) within seconds, so
    none keeps computing or holds the terminal's pipes."""
    study = tmp_path / "s.toml"
    study.write_text(SMALL_STUDY.replace("num = 4", "num = 40"))  # 240 cases of 50 ms
    store = tmp_path / "s.sqlite"
    proc = subprocess.Popen([sys.executable, "-c", DRIVER.format(here=str(HERE), study=str(study),
                                                                 store=str(store))],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    workers: set[int] = set()
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not _rows(store):  # workers are computing
            time.sleep(0.05)
        workers = _descendants(proc.pid)
        assert _rows(store) and len(workers) >= 2, "the sweep did not start its worker processes"
        proc.kill()
        proc.wait(timeout=10)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.1)
        assert not any(_alive(w) for w in workers), "worker processes outlived the sweep"
    finally:
        if proc.poll() is None:
            proc.kill()
        for w in _descendants(proc.pid) | workers:
            if _alive(w):
                os.kill(w, signal.SIGKILL)


def test_threads_per_worker_share_the_cores():
    """Oracle: the arithmetic of the cap, workers x threads <= cores with at least one each."""
    for cores in (1, 2, 3, 8, 64):
        for workers in (1, 2, 3, 5, 100):
            t = threads_per_worker(workers, cores=cores)
            assert t >= 1 and (workers * t <= cores or t == 1)
            assert workers * (t + 1) > cores  # the largest such share
    assert threads_per_worker(1) == usable_cores()


@pytest.mark.skipif(usable_cores() < 2, reason="needs 2 cores (one core: 1 thread either way)")
def test_pool_workers_run_numba_on_their_share_of_the_cores():
    """A pool of 2 workers: each worker's numba thread count (read inside the worker, in the
    thread that runs its tasks) is at most half the usable cores, not numba's default of all of
    them (which the parent keeps); oracle: numba.get_num_threads in the worker."""
    import numba

    from archquake.parallel import process_pool

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("NUMBA_NUM_THREADS < 2: 1 thread per worker either way")
    pool = process_pool(2)
    try:
        inside = {pool.submit(numba.get_num_threads).result(timeout=120) for _ in range(4)}
    finally:
        pool.shutdown(wait=True)
    assert 1 <= min(inside) and max(inside) <= max(1, usable_cores() // 2)


@pytest.mark.skipif(not Path("/proc").is_dir() or usable_cores() < 2, reason="needs /proc and 2 cores")
def test_sigterm_ends_every_worker_with_output_to_a_pipe(tmp_path):
    """SIGTERM on a sweep whose output goes to a pipe, read to its end and not yet reaped (as
    ``subprocess.communicate`` and a shell pipeline do): the fork server and the workers held
    the pipe past 75 s, waiting on a parent that was a zombie. Now every process below the
    sweep is gone within 5 s and the pipe closes; oracle: the process table (/proc)."""
    import threading

    study = tmp_path / "s.toml"
    study.write_text(SMALL_STUDY.replace("num = 4", "num = 40"))  # 240 cases of 50 ms
    store = tmp_path / "s.sqlite"
    proc = subprocess.Popen([sys.executable, "-c", DRIVER.format(here=str(HERE), study=str(study),
                                                                 store=str(store))],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    below: set[int] = set()
    eof = threading.Event()

    def drain() -> None:  # what a reader of the pipe does: read until every writer closed it
        proc.stdout.read()
        eof.set()

    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not _rows(store):  # workers are computing
            time.sleep(0.05)
        below = _descendants(proc.pid)
        assert _rows(store) and len(below) >= 2, "the sweep did not start its worker processes"
        threading.Thread(target=drain, daemon=True).start()
        proc.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and (any(_alive(p) for p in below) or not eof.is_set()):
            time.sleep(0.1)
        alive = [p for p in below if _alive(p)]
        assert not alive, f"{len(alive)} processes below the sweep outlived SIGTERM by 5 s"
        assert eof.is_set(), "the output pipe was still held 5 s after SIGTERM"
        assert proc.wait(timeout=10) != 0
    finally:
        if proc.poll() is None:
            proc.kill()
        for p in _descendants(proc.pid) | below:
            if _alive(p):
                os.kill(p, signal.SIGKILL)


# ------------------------------------------------------- a result lost with its worker
class _LosesFirstResults:
    """An executor whose first attempt at each task fails with an error that is not the
    task's (as Dask's executor raises a ValueError of its own when a worker dies while its
    finished result is fetched), and whose later attempts compute the task."""

    def __init__(self, always: bool = False) -> None:
        self.attempts: dict[int, int] = {}
        self.always = always

    def submit(self, fn, item):
        from concurrent.futures import Future

        key = item[0]
        self.attempts[key] = self.attempts.get(key, 0) + 1
        f: Future = Future()
        if self.attempts[key] == 1 or self.always:
            f.set_exception(ValueError("not enough values to unpack (expected 3, got 2)"))
        else:
            f.set_result(fn(item))
        return f


def test_a_result_lost_with_its_worker_is_computed_again_on_a_cluster():
    """On a cluster (a check given), a task whose result cannot be read is submitted once
    more, and every item's result arrives once; a second failure propagates. Without a
    cluster (a process pool) the first failure propagates: the task's own errors are bugs.
    Oracle: the items themselves (the task doubles them)."""
    from archquake.sweeps.runner import _map_window

    items = [[k] for k in range(5)]
    ex = _LosesFirstResults()
    got = list(_map_window(ex, lambda it: 2 * it[0], iter(items), 2, check=lambda: None))
    assert sorted(got) == [0, 2, 4, 6, 8]
    assert ex.attempts == {k: 2 for k in range(5)}
    with pytest.raises(ValueError, match="unpack"):
        list(_map_window(_LosesFirstResults(always=True), lambda it: it[0], iter(items), 2,
                         check=lambda: None))
    with pytest.raises(ValueError, match="unpack"):
        list(_map_window(_LosesFirstResults(), lambda it: it[0], iter(items), 2))
