"""The assessment's sections side by side: each starts only once the sections it reads first
are done (oracle: the data each section function reads of ``ctx.prior``, listed by reading the
code into ``NEEDS``; of those, `LATER`'s are read only after a section has started, and the read
waits for them), a failure reaches the caller, and the DEM check's warnings land in the validity
section where the report lists them, whichever of the two finished first."""

from __future__ import annotations

import inspect
import re
import threading
import time

import pytest

from archquake.assess.runner import LATER, NEEDS, _run_sections
from archquake.assess.sections import SECTIONS, with_dem_warnings
from archquake.reproduce.core import StudyResult

NAMES = ["arch", "static", "pulses", "records", "dem", "validity", "codecheck"]


def test_needs_cover_what_each_section_reads():
    """Every ``ctx.prior[...]`` / ``ctx.prior.get(...)`` key a section function (and the helpers
    it calls in the same module) reads is in its NEEDS, except the DEM check's data, which the
    validity section no longer reads (it is folded in afterwards)."""
    import archquake.assess.sections as sec

    source = inspect.getsource(sec)
    funcs = dict(SECTIONS)
    for name, fn in funcs.items():
        body = inspect.getsource(fn)
        called = set(re.findall(r"\b(_\w+)\(ctx", body))
        body += "".join(inspect.getsource(getattr(sec, c)) for c in called if hasattr(sec, c))
        read = set(re.findall(r"ctx\.prior(?:\.get\(|\[)\"(\w+)\"", body))
        assert read <= set(NEEDS[name]), (name, read - set(NEEDS[name]))
    assert "dem" not in re.findall(r"ctx\.prior(?:\.get\(|\[)\"(\w+)\"", source)


def _fake(results: dict, log: list, delay: dict, fail: str | None = None):
    lock = threading.Lock()

    def run(k: int, name: str, prior: dict) -> None:
        with lock:
            log.append(("start", name, sorted(prior)))
        time.sleep(delay.get(name, 0.0))
        for dep in sorted(prior):  # each section reads the data it needs
            assert prior[dep] == {"name": dep}
            with lock:
                log.append(("read", name, dep))
        if name == fail:
            raise RuntimeError(f"{name} failed")
        results[name] = StudyResult(name, name, (), (), (), {"name": name})
        with lock:
            log.append(("end", name))

    return run


@pytest.mark.parametrize("side_by_side", [False, True])
def test_each_section_starts_after_what_it_needs(side_by_side):
    results: dict = {}
    log: list = []
    # the slow records section would hold the pulses back if they ran one after another
    run = _fake(results, log, {"records": 0.3, "pulses": 0.05, "dem": 0.1, "validity": 0.1})
    _run_sections(NAMES, run, results, side_by_side)
    assert set(results) == set(NAMES)
    ends = [e[1] for e in log if e[0] == "end"]
    for event in log:
        if event[0] != "start":
            continue
        name, prior = event[1], event[2]
        assert prior == sorted(NEEDS[name])  # exactly the data it reads
        started = log.index(event)
        done_before = {e[1] for e in log[:started] if e[0] == "end"}
        assert set(NEEDS[name]) - set(LATER.get(name, ())) <= done_before
    for event in log:  # every read returns the section's data once that section is done
        if event[0] == "read":
            assert log.index(("end", event[2])) < log.index(event)
    if side_by_side:  # the pulses finished while the records ran; DEM and validity overlapped
        assert ends.index("pulses") < ends.index("records")
        assert log.index(("start", "validity", ["pulses", "records", "static"])) < log.index(
            ("end", "dem"))
        # the DEM check and the validity section started while the records ran
        for name in ("dem", "validity"):
            assert log.index(("start", name, sorted(NEEDS[name]))) < log.index(("end", "records"))
    else:
        assert ends == NAMES


def test_a_failing_section_stops_the_assessment():
    results: dict = {}
    with pytest.raises(RuntimeError, match="records failed"):
        _run_sections(NAMES, _fake(results, [], {}, fail="records"), results, True)
    assert "dem" not in results and "validity" not in results  # they needed the records


def test_a_section_reading_a_failed_one_stops_with_the_first_failure():
    """The DEM check starts before the records end (it reads them later); the records fail:
    its read fails too, and the caller gets the records' own error."""
    results: dict = {}
    log: list = []
    with pytest.raises(RuntimeError, match="records failed"):
        _run_sections(NAMES, _fake(results, log, {"records": 0.2}, fail="records"), results,
                      True)
    assert ("start", "dem", ["pulses", "records", "static"]) in log
    assert not any(e[0] == "read" and e[2] == "records" for e in log)


def test_dem_warnings_fold_into_validity_in_report_order():
    """Oracle: the order the validity section listed its warnings in when it read the DEM check
    itself (after the resurrections, before the time step's and friction's)."""
    validity = {"warnings": [
        {"key": "sliding", "warning": "w", "meaning": "m", "serious": False},
        {"key": "time_step", "warning": "w", "meaning": "m", "serious": False}],
        "serious": False}
    dem = {"cases": [
        {"case": "step pulse t_p = 0.3 s", "dem_more_vulnerable": True,
         "lowest_dem_collapse_factor": 0.85, "model_level_g": 0.2,
         "unconservative_by_at_least": 0.15},
        {"case": "record X", "dem_more_vulnerable": False, "lowest_dem_collapse_factor": None,
         "model_level_g": 0.1, "unconservative_by_at_least": 0.0}]}
    out = with_dem_warnings(validity, dem, "rigid")
    assert [w["key"] for w in out["warnings"]] == ["sliding", "dem", "time_step"]
    assert "0.85 x the rigid model's collapse level (0.2 g)" in out["warnings"][1]["warning"]
    assert "by at least 15 %" in out["warnings"][1]["meaning"]
    assert out["serious"] is True
    assert with_dem_warnings(out, dem, "rigid") == out  # a resumed run does not add it twice
    assert with_dem_warnings(validity, None, "rigid") == validity
    assert validity["warnings"][1]["key"] == "time_step"  # the input is not changed
    dem["cases"][1]["model_collapses_below_its_level_factor"] = 0.85
    keys = [w["key"] for w in with_dem_warnings(validity, dem, "rigid")["warnings"]]
    assert keys == ["sliding", "dem", "model_below_level", "time_step"]



def test_a_shared_value_reaches_its_readers_before_its_section_ends():
    """The records section shares its governing record before its figures and bootstrap
    intervals (`Context.share`); the DEM check's and the validity section's reads of it
    (`Context.early`) return then, not when the records section ends. Oracle: the records
    section ends only once both readers have the value (it would wait forever, here 5 s, if
    they waited for its end), and a section that never shares reads as its data once done."""
    from archquake.assess.runner import _Shared

    shared = _Shared()
    results: dict = {}
    got: dict = {}
    both = threading.Barrier(3, timeout=5.0)

    def run(k, name, prior):
        if name == "records":
            shared.put("records", "governing", {"record": "R"})
            both.wait()  # the two readers have it while this section still runs
            data = {"governing": {"record": "R"}, "other": 1}
        elif name in ("dem", "validity"):
            governing = prior.early("records", "governing")
            both.wait()
            # a key the section does not share: its data, once it is done
            got[name] = (governing, prior.early("records", "other"),
                         prior.early("codecheck", "anything", "absent"))
            data = {}
        else:
            data = {}
        results[name] = StudyResult(name, name, (), (), (), data)

    _run_sections(NAMES, run, results, True, shared)
    for name in ("dem", "validity"):
        assert got[name] == ({"record": "R"}, 1, "absent")
