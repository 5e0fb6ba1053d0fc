"""The DEM check and the validity section start their pulse runs before the records' IDA ends,
and read the governing record only once it has: the same data as when the records were there
from the start. Oracle: each section run after the records section, as one after another
(a plain ``prior``), the DEM runs and the friction runs replaced by a function of the motion
(in threads) and the rigid chain's verdicts computed for real on the bare bridge."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from archquake.assess import sections
from archquake.assess.runner import NEEDS, _Prior
from archquake.assess.sections import Context, Mode
from archquake.constants import STANDARD_GRAVITY
from archquake.reproduce.core import StudyResult

from .conftest import bare_bridge


def _threads(workers: int):
    """`archquake.parallel.interruptible_pool` in threads: the fakes below need no pickling."""
    return ThreadPoolExecutor(workers)


def _prior(quick: bool) -> dict:
    """The data the two sections read: the bare bridge's lambda, pulse boundaries at the mode's
    durations, and the suite's first record as the governing one (one resurrection)."""
    from archquake.ground.suites import fema_available, load_suite

    if not fema_available():
        pytest.skip("the governing record is a FEMA P695 record (archquake[records])")
    rec = load_suite("near-field-pulse").records[0]
    durs = Mode(quick).durations
    coll = np.linspace(0.09, 0.3, durs.size)
    pulse = {"durations_s": list(durs), "collapse_g": list(coll), "non_monotonic_bands": []}
    return {"static": {"collapse_acceleration_g": 0.0491, "sliding": False},
            "pulses": {"step": pulse, "sine": dict(pulse, collapse_g=list(coll[::-1]))},
            "records": {"records_with_resurrections": 1,
                        "governing": {"record": rec.name, "index": 0, "first_collapse_g": 0.12,
                                      "survives_below_g": 0.118,
                                      "pga_unscaled_g": rec.peak / STANDARD_GRAVITY}}}


def _late(name: str, prior: dict, started: threading.Event) -> _Prior:
    """``prior`` as the runner hands it side by side while the records run: the records' data
    arrives only once ``started`` is set (a pulse run was started), or after 60 s."""
    results = {k: StudyResult(k, k, (), (), (), v) for k, v in prior.items() if k != "records"}
    done = {k: threading.Event() for k in prior}
    for k in results:
        done[k].set()

    def records() -> None:
        started.wait(60.0)
        results["records"] = StudyResult("records", "records", (), (), (), prior["records"])
        done["records"].set()

    threading.Thread(target=records, daemon=True).start()
    return _Prior(NEEDS[name], results, done, {})


def _pulse_started(started: threading.Event, seen: list):
    def note(motion) -> None:
        seen.append((type(motion).__name__, started.is_set()))
        if type(motion).__name__ != "Record":
            started.set()
    return note


def _plain_and_late(tmp_path, monkeypatch, section: str, quick: bool, replace):
    """Section ``section``'s result with the records' data there from the start and with it
    arriving only once a pulse run was started, its runs replaced by ``replace(note)``'s
    (name, fake); returns (plain, late, the motions the late one ran: (kind, records there))."""
    cfg = bare_bridge()
    arch = cfg.build_arch()
    prior = _prior(quick=quick)
    started = threading.Event()
    seen: list = []
    name, fake = replace(_pulse_started(started, seen))
    monkeypatch.setattr(sections, name, fake)
    monkeypatch.setattr(sections, "interruptible_pool", _threads)
    run = getattr(sections, f"section_{section}")
    plain = run(Context(cfg, arch, Mode(quick), tmp_path, tmp_path, prior))
    started.clear()
    seen.clear()
    late = run(Context(cfg, arch, Mode(quick), tmp_path, tmp_path,
                       _late(section, prior, started)))
    return plain, late, seen


def test_dem_check_starts_the_pulse_before_the_records_and_reports_alike(tmp_path, monkeypatch):
    def replace(note):
        def dem(body, motion, duration):  # a DEM verdict that depends on the motion and window
            note(motion)
            peak = getattr(motion, "peak", None) or motion.magnitude
            return "collapse" if peak * duration > 4.0 else "survives"

        return "_dem_outcome", dem

    plain, late, seen = _plain_and_late(tmp_path, monkeypatch, "dem", False, replace)
    assert late.data == plain.data
    assert len(plain.data["cases"]) == 2  # the pulse's and the record's, 3 factors each
    # the pulse's runs were started before the records' data came; the record's after
    assert ("StepImpulse", False) in seen
    assert all(ready for kind, ready in seen if kind == "Record")


def test_validity_starts_the_pulses_before_the_records_and_reports_alike(tmp_path,
                                                                          monkeypatch):
    def replace(note):
        def slid(arch_, motion, friction, time_step, loads=None):  # sliding: the record only
            note(motion)
            return "collapse" if type(motion).__name__ == "Record" else "no_hinging"

        return "_rigid_friction_outcome", slid

    plain, late, seen = _plain_and_late(tmp_path, monkeypatch, "validity", True, replace)
    assert late.data == plain.data
    rows = plain.data["step_sensitivity"]
    assert len(rows) == 5 and rows[-1]["case"].startswith("record")  # 2 + 2 pulses, 1 record
    keys = [w["key"] for w in plain.data["warnings"]]
    assert "resurrections" in keys and ("friction_survival" in keys or "friction_collapse" in keys)
    # the records' warning keeps its place before the sensitivity runs'
    assert keys.index("resurrections") < min(keys.index(k) for k in keys
                                             if k.startswith("friction") or k == "time_step")
    assert ("StepImpulse", False) in seen
    assert all(ready for kind, ready in seen if kind == "Record")
