"""The bad-input campaign in the suite: every command's options with degenerate and extreme
values (0, 1e-308, 1e308, nan, a thin and a thick arch, a long record), and the command lines
that once hung or gave a false reason.

Oracle: the CLI's promise (:func:`fuzz_harness.problem`): exit 0, or exit 2 with one stderr line
``archquake: error: ...``; no traceback; nothing past the time bound. The time bound catches a
hang, not a slow run: it is far above what any case costs (no timing is asserted otherwise).

``test_degenerate_values_sample`` (default suite) runs a fixed, deterministic sample of the
campaign; ``test_degenerate_values_campaign`` (slow) runs all of it.
"""

from __future__ import annotations

import json
import math
import sqlite3
import sys
from pathlib import Path

import pytest
from fuzz_harness import call, problem

#: Time bound of one call, s: a hang, not a slow run (the first call also loads the kernels).
TIMEOUT = 90.0

PULSE = ["--pulse", "step", "--magnitude", "1", "--duration", "0.2"]
DEGENERATE = ["0", "-0", "1e-308", "5e-324", "1e308", "-1e308", "nan", "inf", "-1"]

#: command -> (its base command line, the options the campaign varies)
BASES: dict[str, tuple[list[str], list[str]]] = {
    "run": (["run", *PULSE, "--json"],
            ["--magnitude", "--duration", "--thickness", "--radius", "--embrace", "--voussoirs",
             "--t-end", "--friction", "--depth", "--density"]),
    "run-fourlink": (["run", "--model", "fourlink", *PULSE, "--json"],
                     ["--magnitude", "--duration", "--thickness", "--embrace", "--t-end",
                      "--restitution"]),
    "friction": (["friction", *PULSE, "--json"],
                 ["--magnitude", "--duration", "--thickness", "--radius", "--embrace"]),
    "thrust": (["thrust", *PULSE, "--times", "0.1", "--json"],
               ["--magnitude", "--thickness", "--radius", "--embrace", "--times"]),
    "static": (["static", "--json"], ["--thickness", "--radius", "--embrace", "--voussoirs"]),
    "domain": (["domain", "--durations", "0.3", "--scan", "3", "--precision", "0.2",
                "--max-magnitude", "1", "--json"],
               ["--thickness", "--embrace", "--durations", "--max-magnitude", "--precision"]),
    "spectrum": (["spectrum", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star",
                  "0.3", "--json"], ["--ag", "--periods", "--damping"]),
    "record": (["record", "quake.csv", "--units", "g", "--json"], ["--scale", "--periods"]),
    "min-thickness": (["min-thickness", "--voussoirs", "20", "--json"],
                      ["--embrace", "--voussoirs"]),
    "check": (["check", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
               "--json"], ["--ag", "--thickness", "--embrace", "--height", "--building-height",
                           "--building-period"]),
}

#: Whole arches at the ends of the geometry (thin, thick, flat, deep): each under the base.
ARCHES = [["--thickness", "0.01", "--embrace", "10"], ["--thickness", "10", "--radius", "10"],
          ["--thickness", "0.01"], ["--embrace", "240"], ["--voussoirs", "3"]]


def campaign() -> list[tuple[str, list[str]]]:
    """Every (command, argv) of the campaign, in a fixed order."""
    cases = []
    for name, (base, options) in BASES.items():
        for option in options:
            for text in DEGENERATE:
                cases.append((name, [*base, f"{option}={text}"]))
        if name in ("run", "friction", "thrust", "static", "check"):
            for arch in ARCHES:
                cases.append((name, [*base, *arch]))
    cases.append(("run", ["run", "--record", "long.csv", "--units", "g", "--json"]))
    cases.append(("run", ["run", "--record", "quake.csv", "--units", "g", "--scale", "1e-320",
                          "--json"]))
    return cases


def _check(argv: list[str]) -> None:
    result = call(argv, TIMEOUT)
    trouble = problem(result)
    assert trouble is None, f"{' '.join(argv)}: {trouble}"
    if result.code == 0 and "--json" in argv:
        json.loads(result.out)


@pytest.fixture(scope="module")
def long_record(scratch) -> Path:
    """A 150 s record (longer than the 120 s the chain was once limited to), weak: 0.01 g."""
    path = scratch / "long.csv"
    path.write_text("time,acc\n" + "\n".join(
        f"{0.05 * i:.2f},{0.01 * math.sin(0.5 * i):.6f}" for i in range(3001)) + "\n")
    return path


#: Every 25th case of the campaign: a deterministic sample over the commands (a few seconds).
SAMPLE = campaign()[::25]


@pytest.mark.parametrize("case", SAMPLE, ids=[" ".join(a[1:]) for _, a in SAMPLE])
def test_degenerate_values_sample(scratch, long_record, case):
    _check(case[1])


@pytest.mark.slow
@pytest.mark.parametrize("case", campaign(), ids=[" ".join(a[1:]) for _, a in campaign()])
def test_degenerate_values_campaign(scratch, long_record, case):
    _check(case[1])


# ------------------------------------------------------------------------------------------
# the command lines that hung (each > 60 s, nothing printed): now each ends, most at once
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("argv", [
    ["run", "--pulse", "step", "--magnitude", "0", "--duration", "0.2"],
    ["run", "--pulse", "step", "--magnitude", "1e-308", "--duration", "0.2"],
    ["run", "--record", "quake.csv", "--units", "g", "--scale", "1e-320"],
    ["run", *PULSE, "--thickness", "0.01", "--embrace", "10"],
    ["friction", *PULSE, "--thickness", "0.01", "--embrace", "10"],
    ["thrust", *PULSE, "--thickness", "0.01", "--embrace", "10"],
    ["friction", *PULSE, "--thickness", "10", "--radius", "10"],
    ["thrust", *PULSE, "--thickness", "10", "--radius", "10"],
    ["run", *PULSE, "--thickness", "10", "--radius", "10"],
], ids=lambda a: " ".join(a))
def test_below_the_onset_nothing_is_integrated(scratch, argv):
    """Each motion stays below the arch's onset of hinging: ``no_hinging``, with no step
    taken (the JSON says ``below_onset``), within the bound (these took 15-45 s each)."""
    result = call([*argv, "--json"], 30.0)
    assert problem(result) is None, problem(result)
    out = json.loads(result.out)
    outcome = out.get("outcome")
    if argv[0] == "run":
        assert outcome == "no_hinging" and out["rigid"]["below_onset"] is True
        assert out["guard"]["ran"] is False  # nothing to guard: no step was taken
    elif argv[0] == "friction":
        assert outcome == "no_hinging" and out["max_friction_demand"] is None


def test_run_refuses_the_work_friction_refuses(scratch):
    """200 voussoirs on a semicircle: ``friction`` refused it (~91 min) while ``run`` went on
    silently; both now refuse in one line with the estimate, naming the options (without
    --t-end, the run lasts the pulse and a tail: --duration)."""
    argv = [*PULSE, "--thickness", "1.08", "--embrace", "180", "--voussoirs", "200"]
    for command in ("run", "friction"):
        result = call([command, *argv], 60.0)
        assert problem(result) is None and result.code == 2, problem(result)
        line = result.error_lines[0]
        assert "min" in line and "--voussoirs" in line and "--duration" in line, line


def test_a_long_record_runs_by_default(scratch, long_record):
    """A record longer than 120 s runs with the default --t-end (--help allows 10,000 s)."""
    result = call(["run", "--record", str(long_record), "--units", "g", "--json"], 60.0)
    assert problem(result) is None and result.code == 0, (problem(result), result.err)
    assert json.loads(result.out)["outcome"] == "no_hinging"


def test_spectrum_periods_have_an_upper_bound(scratch):
    result = call(["spectrum", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star",
                   "0.3", "--periods", "1e308"], 30.0)
    assert problem(result) is None and result.code == 2
    assert "--periods" in result.err and "20 s" in result.err


def test_a_locked_store_is_called_locked(scratch, monkeypatch):
    """A store another process holds a write lock on is not called damaged (after a wait
    shortened from the store's 5 s, so that the test does not sleep)."""
    from archquake.sweeps import store as S

    monkeypatch.setattr(S, "LOCK_WAIT_S", 0.2)
    store = scratch / "locked.sqlite"
    argv = ["sweep", "study.toml", "--workers", "1", "--no-progress", "--store", str(store)]
    assert call(argv, 60.0).code == 0
    db = sqlite3.connect(store)
    db.execute("BEGIN EXCLUSIVE")
    try:
        result = call(argv, 60.0)
    finally:
        db.rollback()
        db.close()
    assert problem(result) is None and result.code == 2
    assert "locked by another process" in result.err and "damaged" not in result.err


def test_a_read_only_store_is_called_read_only(tmp_path, monkeypatch):
    """SQLite's write error on a read-only store gives that reason (checked through the
    reason's helper: the suite may run as root, who can write anything)."""
    from archquake.sweeps import store as S

    path = tmp_path / "s.sqlite"
    path.write_bytes(b"")
    monkeypatch.setattr(S.os, "access", lambda p, mode: Path(p) != path)
    why = S._not_damaged(path, sqlite3.OperationalError("attempt to write a readonly database"))
    assert why is not None and "read-only" in why
    monkeypatch.setattr(S.os, "access", lambda p, mode: True)
    assert S._not_damaged(path, sqlite3.DatabaseError("file is not a database")) is None


@pytest.mark.parametrize("arch", [["--thickness", "1.0"],
                                  ["--thickness", "1.2", "--embrace", "180", "--voussoirs", "5"],
                                  ["--thickness", "0.8", "--voussoirs", "5"]],
                         ids=lambda a: " ".join(a))
def test_domain_takes_arches_cut_above_the_springing(scratch, arch):
    """Arches whose three-voussoir cut (at the four-link hinges) puts a hinge above the
    springing, so that its base takes in voussoirs: refused with API wording ("use
    solver='direct'"); now the domain is found, and the rigid chain's first-half-cycle boundary
    is the four-link mechanism's to the search's bracket (0.2 g)."""
    result = call(["domain", "--durations", "0.3", "--scan", "3", "--precision", "0.2",
                   "--max-magnitude", "1.5", *arch, "--json"], 60.0)
    assert problem(result) is None and result.code == 0, (problem(result), result.err)
    first = next(r for r in json.loads(result.out)["rows"] if r["boundary"] == "first_half_cycle")
    assert abs(first["block_g"] - first["fourlink_g"]) <= 0.2


@pytest.mark.skipif(not Path("/dev/shm").is_dir(), reason="no /dev/shm to look in")
def test_workers_hold_no_named_semaphore():
    """A pool worker's only named semaphore (numba's lock) is unlinked as it starts, so a
    worker ended by SIGTERM leaves nothing for the resource tracker to call leaked."""
    from fuzz_harness import numba_lock_on_disk

    from archquake.parallel import process_pool

    pool = process_pool(1)
    try:
        name, linked = pool.submit(numba_lock_on_disk).result(timeout=120)
    finally:
        pool.shutdown(wait=True)
    assert name is None or not linked


@pytest.mark.slow
def test_sigterm_with_two_workers_leaks_no_semaphore(tmp_path):
    """The interruption itself: a sweep with --workers 2 ended by SIGTERM mid-run says how to
    resume and nothing about leaked semaphores."""
    import subprocess
    import time

    from fuzz_harness import STUDY

    study = tmp_path / "study.toml"
    study.write_text(STUDY.replace("magnitude_g = 0.5",
                                   "magnitude_g = {start = 0.3, stop = 2.0, num = 4000}"))
    proc = subprocess.Popen(
        [sys.executable, "-m", "archquake.cli.main", "sweep", str(study), "--workers", "2",
         "--no-progress", "--store", str(tmp_path / "s.sqlite")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(8.0)
    proc.terminate()
    _, err = proc.communicate(timeout=120)
    assert "leaked semaphore" not in err, err


@pytest.mark.slow
def test_a_long_record_is_judged_to_its_end(scratch):
    """A 200 s record whose only strong part (two cycles of 0.6 g, above the onset of 0.37 g)
    comes in its last second: the verdict's window no longer ends with the record (its own
    default stops at 120 s or the record's end), where the arch still rocks; it goes on, as
    --help says, to the end of the excitation + 60 sqrt(R/g), and sees the arch at rest."""
    path = scratch / "late.csv"
    path.write_text("time,acc\n" + "\n".join(
        f"{0.01 * i:.2f},"
        f"{0.6 * math.sin(2 * math.pi * 0.01 * i / 0.4) if 19900 < i < 19980 else 0.0:.6f}"
        for i in range(20001)) + "\n")
    result = call(["run", "--record", str(path), "--units", "g", "--json"], 300.0)
    assert problem(result) is None and result.code == 0, (problem(result), result.err)
    out = json.loads(result.out)
    assert out["onset_time_s"] > 199.0
    assert out["outcome"] == "survives", out["verdict"]


def test_a_long_run_below_the_bound_says_so_and_its_progress(capsys):
    """Below the work bound a run estimated above 10 s prints its estimate, then a line at each
    quarter of its steps (the progress simulate_rigid reports after each chunk); a short one
    prints nothing. Oracle: the estimate's arithmetic, 400,000 steps x 31^3 x 1.1e-9 s."""
    from archquake.cli.common import rigid_work
    from archquake.geometry import Arch
    from archquake.ground import StepImpulse

    arch = Arch(10.0, 1.5, math.radians(157.5), 30)
    motion = StepImpulse.from_g(0.45, 0.2)
    progress = rigid_work("run", arch, motion, 40.0, 1e-4)
    assert progress is not None
    for done in range(0, 400_001, 20_000):
        progress(done, 400_000)
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("archquake: run: 30 voussoirs over 400,000 time steps")
    assert f"about {400_000 * 31**3 * 1.1e-9 / 60:.2g} min" in lines[0]
    assert [line.split(": ")[-1] for line in lines[1:]] == [
        f"{k:,} of at most 400,000 time steps" for k in (100_000, 200_000, 300_000)]
    assert rigid_work("run", arch, motion, 1.0, 1e-4) is None
    assert capsys.readouterr().err == ""
