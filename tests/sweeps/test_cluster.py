"""A real Dask cluster on loopback: a scheduler and two workers started with the ``dask``
command line. The cluster's stored results equal a local serial run's; killing a worker
(SIGKILL) while tasks are in flight loses no case and stores none twice (Dask reruns the lost
tasks; the store's primary key guards the rest).

Bounded: every wait has a timeout, processes are torn down in a finally, < ~20 s in all.
"""

from __future__ import annotations

import os
import signal
import socket
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import NamedTuple

import pytest
import sweep_fake_model
from test_runner import stored

from archquake.cli import cmd_sweep
from archquake.parallel import SerialExecutor
from archquake.sweeps import ResultStore, run_sweep

pytest.importorskip("distributed")
DASK = Path(sys.executable).parent / "dask"
HERE = Path(__file__).parent


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_port(port: int, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.1)
    raise TimeoutError(f"no Dask scheduler on 127.0.0.1:{port} after {timeout} s")


class Cluster(NamedTuple):
    address: str
    workers: list
    scheduler: subprocess.Popen


@pytest.fixture
def cluster(tmp_path):
    """A fresh loopback cluster (address, worker processes, scheduler process) with two
    1-thread workers.

    Workers run without a nanny, so SIGKILL on a worker's pid removes it for good; they find
    the test's case functions on PYTHONPATH.
    """
    if not DASK.exists():
        pytest.skip(f"no dask command at {DASK}")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")])}
    log = (tmp_path / "dask.log").open("w")
    procs: list[subprocess.Popen] = []
    try:
        procs.append(subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port",
                                       str(port), "--no-dashboard"], stdout=log, stderr=log,
                                      env=env))
        wait_for_port(port, 20)
        for _ in range(2):
            procs.append(subprocess.Popen(
                [str(DASK), "worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                 "--nworkers", "1", "--no-nanny", "--no-dashboard", "--death-timeout", "20"],
                stdout=log, stderr=log, env=env))
        from distributed import Client

        with Client(address, timeout=20) as client:
            client.wait_for_workers(2, timeout=30)
        yield Cluster(address, procs[1:], procs[0])
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in reversed(procs):
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=5)
        log.close()


def test_cluster_equals_local_and_survives_a_killed_worker(cluster, tmp_path, small_study_file,
                                                           small_cases, monkeypatch, capsys):
    address, workers = cluster.address, cluster.workers
    from archquake.cli import main as cli_main

    # Local reference: serial, the same (fast) function.
    local = tmp_path / "local.sqlite"
    with ResultStore(local) as store:
        run_sweep(small_cases, store, evaluate=sweep_fake_model.fake_evaluate,
                  executor=SerialExecutor())

    # 1. The plain cluster run through the command line.
    monkeypatch.setattr(cli_main, "COMMANDS", ("sweep",))
    monkeypatch.setattr(cmd_sweep, "case_function",
                        lambda model: sweep_fake_model.fake_evaluate)
    plain = tmp_path / "plain.sqlite"
    assert cli_main.main(["sweep", str(small_study_file), "--scheduler", address,
                          "--store", str(plain), "--json"]) == 0
    capsys.readouterr()
    assert stored(plain) == stored(local)

    # 2. Slow cases (50 ms each, 2 per task, 12 tasks over 2 workers: ~0.6 s in all); kill one
    #    worker as soon as the first batch is in the store, while others are in flight.
    monkeypatch.setattr(cmd_sweep, "case_function",
                        lambda model: sweep_fake_model.slow_fake_evaluate)
    killed = tmp_path / "killed.sqlite"
    at_kill: list[int] = []

    def killer():
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            if killed.exists():
                try:
                    with sqlite3.connect(killed, timeout=1) as db:
                        n = db.execute("SELECT COUNT(*) FROM results").fetchone()[0]
                except sqlite3.OperationalError:  # table not created yet
                    n = 0
                if n > 0:
                    at_kill.append(n)
                    os.kill(workers[0].pid, signal.SIGKILL)
                    return
            time.sleep(0.01)

    thread = threading.Thread(target=killer, daemon=True)
    thread.start()
    t0 = time.monotonic()
    assert cli_main.main(["sweep", str(small_study_file), "--scheduler", address,
                          "--store", str(killed), "--chunk-size", "2", "--json"]) == 0
    thread.join(timeout=5)
    elapsed = time.monotonic() - t0
    assert at_kill and at_kill[0] < 24, "the worker was not killed mid-sweep"
    assert workers[0].wait(timeout=5) == -signal.SIGKILL
    with sqlite3.connect(killed) as db:
        ids = [r[0] for r in db.execute("SELECT case_id FROM results")]
    assert len(ids) == len(set(ids)) == 24  # every case, exactly once
    assert stored(killed) == stored(local)
    assert elapsed < 30


def _kill_when_stored(store: Path, victims) -> threading.Thread:
    """SIGKILL ``victims`` as soon as the store holds a row (tasks are then in flight)."""
    def killer():
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            if store.exists():
                try:
                    with sqlite3.connect(store, timeout=1) as db:
                        n = db.execute("SELECT COUNT(*) FROM results").fetchone()[0]
                except sqlite3.OperationalError:
                    n = 0
                if n > 0:
                    for v in victims:
                        os.kill(v.pid, signal.SIGKILL)
                    return
            time.sleep(0.01)

    thread = threading.Thread(target=killer, daemon=True)
    thread.start()
    return thread


@pytest.mark.parametrize("lose", ["scheduler", "workers"])
def test_a_lost_cluster_ends_the_sweep_in_one_line_and_keeps_the_rows(
        lose, cluster, tmp_path, small_study_file, monkeypatch, capsys):
    """The scheduler killed mid-sweep, or every worker killed: one line, exit 2, every case
    completed before is in the store exactly once (issue 15: 'a dead scheduler gives a
    traceback', 'with every worker gone, the sweep waits forever in silence')."""
    from archquake.cli import main as cli_main

    monkeypatch.setattr(cli_main, "COMMANDS", ("sweep",))
    monkeypatch.setattr(cmd_sweep, "case_function",
                        lambda model: sweep_fake_model.slow_fake_evaluate)
    study = tmp_path / "many.toml"
    study.write_text(small_study_file.read_text().replace("num = 4", "num = 40"))  # 240 cases
    store = tmp_path / "lost.sqlite"
    victims = [cluster.scheduler] if lose == "scheduler" else cluster.workers
    thread = _kill_when_stored(store, victims)
    t0 = time.monotonic()
    code = cli_main.main(["sweep", str(study), "--scheduler", cluster.address, "--store",
                          str(store), "--chunk-size", "2", "--worker-wait", "2"])
    elapsed = time.monotonic() - t0
    thread.join(timeout=5)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert len(err) == 1 and err[0].startswith("archquake: error: ")
    assert "run the same command again to resume" in err[0]
    assert ("scheduler went away" in err[0]) if lose == "scheduler" else ("no worker for 2 s" in err[0])
    with sqlite3.connect(store) as db:
        ids = [r[0] for r in db.execute("SELECT case_id FROM results")]
    assert 0 < len(ids) == len(set(ids)) < 240
    assert f"{len(ids)} of 240 cases are stored" in err[0]
    assert elapsed < 40
