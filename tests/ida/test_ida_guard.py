"""The rigid chain's half-step guard in incremental dynamic analysis: the levels that decide each
record's trace are rerun at half the step, and a level whose two verdicts differ is
``indeterminate`` (counted as a collapse).

Oracles: the trace's definition for :func:`deciding_levels` (both ends of every change between
survival and collapse, made-up traces); the two steps' own verdicts (:func:`rigid_verdict`,
guard off, at the verdict's step and at half of it) for the IDA's outcome at each deciding level
of the bridge example under LANDERS-LCN_239, a record whose verdict at one of them changes with
the step (0.16 g on a grid: collapse at h, survival at h/2 and h/4, docs/notes/mechanism.md); the
case ids the store held before the option existed.
"""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from archquake.errors import InvalidParameterError
from archquake.ground.measures import im_value
from archquake.ida import incremental_dynamic_analysis
from archquake.ida.analysis import deciding_levels
from archquake.rigid import rigid_verdict
from archquake.rigid.verdict import verdict_time_step
from archquake.sweeps import ArchSpec, Case, CaseOptions, ExcitationSpec, ResultStore


@dataclass(frozen=True)
class _Rec:
    outcome: str


def _trace(pairs):
    return {x: _Rec(o) for x, o in pairs}


@pytest.mark.parametrize("pairs, expected", [
    # first collapse bracket only
    ([(0.1, "survives"), (0.2, "survives"), (0.3, "collapse"), (0.4, "collapse")], [0.2, 0.3]),
    # a resurrection: both of its transitions
    ([(0.1, "no_hinging"), (0.2, "collapse"), (0.3, "survives"), (0.4, "collapse")],
     [0.1, 0.2, 0.3, 0.4]),
    # an indeterminate level counts as a collapse
    ([(0.1, "survives"), (0.2, "indeterminate"), (0.3, "collapse")], [0.1, 0.2]),
    # collapsing from the first level: that level decides; never collapsing: the ceiling does
    ([(0.1, "collapse"), (0.2, "collapse")], [0.1]),
    ([(0.1, "survives"), (0.2, "survives")], [0.2]),
    ([], []),
])
def test_deciding_levels_are_the_ends_of_every_transition(pairs, expected):
    assert deciding_levels(_trace(pairs)) == expected


@pytest.mark.parametrize("at_h, at_half, expected", [
    ("survives", "survives", "survives"), ("survives", "no_hinging", "survives"),
    ("collapse", "collapse", "collapse"), ("survives", "collapse", "indeterminate"),
    ("collapse", "survives", "indeterminate"), ("collapse", "indeterminate", "indeterminate"),
    ("indeterminate", "collapse", "indeterminate"),
])
def test_guarded_record_follows_the_two_steps(at_h, at_half, expected):
    """The rule, case by case: confirmed where both steps survive (``no_hinging`` is a
    survival) or both collapse, ``indeterminate`` otherwise, the rerun recorded."""
    from archquake.ida.analysis import guarded_record
    from archquake.sweeps.store import CaseRecord

    raw = {"outcome": at_h, "time_step_s": 6.3e-4, "verdict_reason": "why",
           "collapse_half_cycle": 3 if at_h == "collapse" else None, "guard_ran": False}
    half = CaseRecord("half", "ok", {"outcome": at_half, "time_step_s": 3.15e-4}, at_half)
    rec = guarded_record(CaseRecord("id", "ok", raw, at_h), half)
    assert rec.outcome == rec.outputs["outcome"] == expected
    assert rec.outputs["guard_ran"] is True and rec.outputs["guard_outcome"] == at_half
    assert raw["guard_ran"] is False  # the stored record's outputs are not modified


def test_unguarded_levels_have_their_own_case_ids():
    """The default options keep the canonical form (and so the case ids) they had before the
    guard and the step fraction became options; unguarded verdicts, and the guard's reruns at
    half the step, are stored under other ids."""
    from archquake.ida.analysis import half_step_case

    assert "guard" not in CaseOptions().canonical()
    assert "step_fraction" not in CaseOptions().canonical()
    assert CaseOptions(guard=False).canonical()["guard"] is False
    arch = ArchSpec(10, 0.15, 157.5, 7)
    exc = ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25)
    level = Case(arch, exc, "rigid", CaseOptions(guard=False))
    assert Case(arch, exc, "rigid").case_id != level.case_id
    half = half_step_case(level)
    assert half.options.canonical()["step_fraction"] == 0.5
    assert len({Case(arch, exc, "rigid").case_id, level.case_id, half.case_id}) == 3


@pytest.mark.parametrize("fraction", [0.0, -0.5, 1.5, float("nan")])
def test_a_step_fraction_outside_0_1_is_refused(fraction):
    with pytest.raises(InvalidParameterError, match="step_fraction"):
        CaseOptions(step_fraction=fraction)


def test_only_the_rigid_batches_take_a_step_fraction():
    """The four-link batches and the case-by-case evaluator refuse a step fraction, in one
    line, instead of running the case at their own step."""
    from archquake.ida.batch import evaluate_cases
    from archquake.sweeps.evaluate import evaluate_case

    arch = ArchSpec(10, 0.15, 157.5, 7)
    exc = ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25)
    options = CaseOptions(step_fraction=0.5)
    (out,) = evaluate_cases([Case(arch, exc, "fourlink", options)])
    assert isinstance(out, InvalidParameterError) and "step_fraction" in str(out)
    with pytest.raises(InvalidParameterError, match="step_fraction"):
        evaluate_case(Case(arch, exc, "dem", options))


suites = pytest.importorskip("archquake.ground.suites")
needs_records = pytest.mark.skipif(not suites.fema_available(),
                                   reason="the FEMA P695 records are not installed")

BRIDGE = ArchSpec(radius=5.0, thickness_ratio=0.12, embrace_deg=180, voussoirs=15, density=1800)


@needs_records
def test_a_level_where_the_steps_disagree_is_indeterminate():
    """Quick: LANDERS-LCN_239 at 0.16 g, where the bridge collapses at the verdict's step and
    survives at half of it (the study's grid). Oracle: the two steps' own verdicts, guard
    off; the guarded record of the level is indeterminate and names both, and a level where they
    agree (0.20 g, collapse at both) is confirmed as it was."""
    from archquake.ida.analysis import guarded_record, half_step_case
    from archquake.ida.batch import evaluate_rigid_cases
    from archquake.sweeps.store import CaseRecord

    record = next(r for r in suites.load_suite("near-field-pulse").records
                  if r.name == "LANDERS-LCN_239")
    pga = im_value(record, "pga")
    arch = BRIDGE.build()
    h = verdict_time_step(arch)
    options = CaseOptions(guard=False)
    for level, expected in ((0.16, "indeterminate"), (0.20, "collapse")):
        motion = record.scaled(level / pga)
        at_h = rigid_verdict(arch, motion, guard=False).outcome.value
        at_half = rigid_verdict(arch, motion, guard=False, time_step=0.5 * h).outcome.value
        assert (at_h != at_half) == (expected == "indeterminate"), (level, at_h, at_half)
        case = Case(BRIDGE, ExcitationSpec("record", motion=record, scale=level / pga),
                    "rigid", options)
        raw, half = evaluate_rigid_cases([case, half_step_case(case)])
        assert raw["outcome"] == at_h and half["outcome"] == at_half
        assert half["time_step_s"] == 0.5 * h
        rec = guarded_record(CaseRecord(case.case_id, "ok", raw, raw["outcome"]),
                             CaseRecord("half", "ok", half, half["outcome"]))
        assert rec.outcome == rec.outputs["outcome"] == expected
        assert rec.outputs["guard_ran"] and rec.outputs["guard_outcome"] == at_half
        if expected == "indeterminate":
            assert at_h in rec.outputs["verdict_reason"] and at_half in rec.outputs[
                "verdict_reason"]


@needs_records
@pytest.mark.slow
def test_deciding_levels_are_flagged_where_the_steps_disagree(tmp_path):
    """The whole IDA of one record (about 20 s of CPU): every deciding level of the converged
    trace is indeterminate exactly where the two steps' own verdicts differ."""
    record = next(r for r in suites.load_suite("near-field-pulse").records
                  if r.name == "LANDERS-LCN_239")
    with ResultStore(tmp_path / "ida.sqlite") as store:
        res = incremental_dynamic_analysis(BRIDGE, [record], "pga", store, ceiling=0.25,
                                           precision=0.05, fill=0.25)
    (trace,) = res.records
    done = {float(x): _Rec(o) for x, o in zip(trace.levels, trace.outcomes, strict=True)}
    deciding = deciding_levels(done)
    assert res.guarded >= len(deciding) > 0
    arch = BRIDGE.build()
    h = verdict_time_step(arch)
    pga = im_value(record, "pga")
    flagged = 0
    for x in deciding:
        motion = record.scaled(x / pga)
        at_h = rigid_verdict(arch, motion, guard=False).outcome.value
        at_half = rigid_verdict(arch, motion, guard=False, time_step=0.5 * h).outcome.value
        survived = ("survives", "no_hinging")
        disagree = (at_h in survived) != (at_half in survived)
        assert (done[x].outcome == "indeterminate") == disagree, (x, at_h, at_half)
        if not disagree:
            assert done[x].outcome == at_h
        flagged += disagree
    # the record's trace crosses a level where the steps disagree (docs/notes/mechanism.md)
    assert flagged >= 1
