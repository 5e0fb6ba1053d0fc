"""Progress of the assessment's long steps: a count and the time left on stderr, nothing for a
short step, and nothing at all with --no-progress.

Oracle: a clock the test drives (no timing assertion): the time left is the time per item so
far times the items left, by hand."""

from __future__ import annotations

import pytest

from archquake.assess.sections import Progress
from archquake.cli.main import main


class Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def test_counts_and_time_left():
    lines: list[str] = []
    clock = Clock()
    tick = Progress(lines.append, "DEM runs", 10, clock=clock)
    clock.t = 1.0
    tick(1)
    assert lines == []  # under 2 s: a short step says nothing
    clock.t = 4.0
    tick(2)  # 2 s per run so far, 8 left
    assert lines == ["  DEM runs: 2/10, about 16 s left"]
    clock.t = 5.0
    tick(3)
    assert len(lines) == 1  # at most one line every 10 s
    clock.t = 200.0
    tick(4)
    assert lines[-1] == "  DEM runs: 4/10, about 5 min left"  # 50 s per run, 6 left
    clock.t = 201.0
    tick(10)
    assert lines[-1] == "  DEM runs: 10/10, done in 201 s"


def test_an_estimate_is_said_and_raised_when_passed():
    lines: list[str] = []
    clock = Clock()
    tick = Progress(lines.append, "step domain time histories", 8, estimate=True, clock=clock)
    clock.t = 3.0
    tick(10)
    assert lines == ["  step domain time histories: 10/~13, about 1 s left"]


def test_a_heartbeat_while_no_item_has_finished(monkeypatch):
    """Inside ``with``, a line every EVERY_S seconds says the count and how long the step has
    run, even when nothing finished since (the first DEM run may take minutes)."""
    import threading

    lines: list[str] = []
    clock = Clock()
    said = threading.Event()

    def say(line):
        lines.append(line)
        said.set()

    monkeypatch.setattr(Progress, "EVERY_S", 0.01)
    tick = Progress(say, "DEM runs", 2, clock=clock)
    clock.t = 30.0
    with tick:
        assert said.wait(5.0)
    assert lines[0] == "  DEM runs: 0/2, running for 30 s"


def test_silent_without_a_line_to_say():
    Progress(None, "x", 3)(2)  # no error, nothing to print to


@pytest.mark.parametrize("flag, silent", [([], False), (["--no-progress"], True)])
def test_no_progress_silences_the_lines(flag, silent, tmp_path, monkeypatch):
    import archquake.assess as assess

    seen = {}

    class Stop(Exception):
        pass

    def fake(config, out, **kwargs):
        seen.update(kwargs)
        raise Stop

    monkeypatch.setattr(assess, "run_assessment", fake)
    path = tmp_path / "arch.toml"
    path.write_text("[arch]\nradius = 5.0\nthickness_ratio = 0.12\nembrace_deg = 180\n"
                    "voussoirs = 15\nfriction = 0.6\n[seismic]\nsite_pga_g = 0.15\n")
    with pytest.raises(Stop):
        main(["assess", str(path), "--out", str(tmp_path / "out"), *flag])
    assert (seen["progress"] is None) == silent
