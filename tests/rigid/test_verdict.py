"""The rigid chain's verdict path (:mod:`archquake.rigid.verdict`): the same verdict
as the recorded run, at a step chosen for the verdict, guarded near a threshold, with exact
shortcuts (skip at rest, early stops) and batches equal to single runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.ground.records import Record
from archquake.outcome import RESULT_KEYS, Outcome
from archquake.rigid import simulate_rigid
from archquake.rigid.verdict import (
    GUARD_LENGTHENING,
    STEP_FACTOR,
    rigid_model,
    rigid_verdict,
    rigid_verdicts,
    verdict_time_step,
)

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
THIN = Arch(10.0, 1.1, math.radians(157.5), 7)  # t/R = 0.11
SEMICIRCLE = Arch(5.0, 0.6, math.pi, 15)  # the bridge's


@pytest.mark.parametrize("tp, outcome, half", [(0.27, "collapse", 2), (0.415, "collapse", 1),
                                               (0.20, "survives", None)])
def test_verdict_is_the_recorded_runs(tp, outcome, half):
    """Oracle: the recorded run at the same step (``simulate_rigid``, every step a sample, the
    DEM's post-processing). The verdict path steps with the same kernel, so the outcome, the
    collapse's half cycle and time, and the impacts agree exactly (collapse time to 1e-9 s);
    a survival is confirmed by the recorded run ending where the verdict stopped."""
    h = 1e-3
    v = rigid_verdict(OPPENHEIM, StepImpulse.from_g(1.0, tp), time_step=h, guard=False)
    end = v.end_time_s if v.outcome is Outcome.SURVIVES else v.end_time_s + 0.1
    r = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, tp), duration=end, time_step=h,
                       output_interval=h)
    assert v.outcome.value == r.outcome.value == outcome
    assert v.collapse_half_cycle == r.collapse_half_cycle == half
    if half is not None:
        assert v.collapse_time_s == pytest.approx(r.collapse_time, abs=1e-9)
    assert v.impacts == r.impact_times.size
    assert v.final_state == r.final_state
    d = v.to_dict()  # every model's shared keys first, the model named as --model names it
    assert tuple(d)[:len(RESULT_KEYS)] == RESULT_KEYS and d["model"] == "rigid"
    assert d["g_m_s2"] == G and d["impact_times_s"] is None
    assert abs(v.onset_time_s - r.onset_time) <= 1.5 * h  # mid-step gaps against samples


def test_oppenheim_collapses_at_a_long_pulse():
    """Figure 4(a)'s t_p = 0.415 s at 1.0 g, where the fixed-hinge model survives: the rigid
    chain (and the DEM, docs/notes/mechanism.md) collapses in its first half cycle, at its default
    step; no impact, so no guard."""
    v = rigid_verdict(OPPENHEIM, StepImpulse.from_g(1.0, 0.415))
    assert v.outcome is Outcome.COLLAPSE and v.collapse_half_cycle == 1
    assert not v.guard_ran
    assert v.time_step_s == pytest.approx(1.0e-3, rel=2e-3)


# the DEM's critical step-pulse durations (s) and the rigid chain's step pulse magnitude (g)
DEM_CRITICAL = {"oppenheim": (OPPENHEIM, 1.0, 0.253, 0.2625),
                "t/R 0.11": (THIN, 1.0, 0.140, 0.145),
                "semicircle": (SEMICIRCLE, 0.15, 0.145, 0.153)}


@pytest.mark.parametrize("name", [
    "oppenheim", "t/R 0.11", pytest.param("semicircle", marks=pytest.mark.slow)])
def test_critical_duration_within_3_percent_of_the_dem(name):
    """At the default step the first collapsing t_p lies within 3 % of the DEM's bracket
    (docs/models/dem.md: the DEM's own resolution is 2-5 ms): the chain survives at 0.97 times the
    DEM's lower end and collapses at 1.03 times its upper end (measured thresholds:
    0.2589, 0.1456, 0.1463 s, docs/notes/mechanism.md "The rigid chain's step")."""
    arch, a_g, lo, hi = DEM_CRITICAL[name]
    vs = rigid_verdicts(arch, [StepImpulse.from_g(a_g, 0.97 * lo), StepImpulse.from_g(a_g, 1.03 * hi)])
    assert [v.outcome for v in vs] == [Outcome.SURVIVES, Outcome.COLLAPSE]


@pytest.mark.slow
@pytest.mark.parametrize("name", list(DEM_CRITICAL))
def test_critical_duration_by_bisection(name):
    """The full study: the threshold by bisection to 0.5 ms at the default step (guard off, the
    raw step's verdict) lies within 3 % of the DEM's bracket."""
    arch, a_g, lo_dem, hi_dem = DEM_CRITICAL[name]
    lo, hi = 0.9 * lo_dem, 1.1 * hi_dem

    def collapses(tp):
        return rigid_verdict(arch, StepImpulse.from_g(a_g, tp), guard=False).outcome \
            is Outcome.COLLAPSE

    assert not collapses(lo) and collapses(hi)
    while hi - lo > 5e-4:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if collapses(mid) else (mid, hi)
    assert 0.97 * lo_dem <= hi and lo <= 1.03 * hi_dem


def test_guard_makes_a_threshold_case_indeterminate():
    """Constructed: Oppenheim's arch at 1.0 g, t_p = 0.2585 s, 0.1 % below the threshold
    (0.2589 s). Oracle: the two steps' own verdicts (guard off) differ, survives at h and
    collapse at h / 2; with the guard the verdict is indeterminate, says why, and records that
    the guard ran."""
    motion = StepImpulse.from_g(1.0, 0.2585)
    h = verdict_time_step(OPPENHEIM)
    at_h = rigid_verdict(OPPENHEIM, motion, guard=False)
    at_half = rigid_verdict(OPPENHEIM, motion, guard=False, time_step=0.5 * h)
    assert at_h.outcome is Outcome.SURVIVES and at_half.outcome is Outcome.COLLAPSE
    assert at_h.lengthening > GUARD_LENGTHENING  # the rule that triggers the guard
    v = rigid_verdict(OPPENHEIM, motion)
    assert v.outcome is Outcome.INDETERMINATE and v.guard_ran
    assert v.guard_outcome is Outcome.COLLAPSE
    assert "survives" in v.reason and "collapse" in v.reason
    assert v.to_dict()["guard_ran"] is True


def test_guard_stays_off_far_from_a_threshold():
    """t_p = 0.20 s (23 % below the threshold: half cycles lengthen by 1.8 at most) and a
    collapse before any impact: the guard does not run, and says so."""
    vs = rigid_verdicts(OPPENHEIM, [StepImpulse.from_g(1.0, 0.20), StepImpulse.from_g(1.0, 0.44)])
    assert [v.outcome for v in vs] == [Outcome.SURVIVES, Outcome.COLLAPSE]
    assert not any(v.guard_ran for v in vs)
    assert vs[0].lengthening < GUARD_LENGTHENING


def _quiet_start(strong: np.ndarray, seed: int = 1) -> Record:
    """3 s of noise at 0.2 g (below the onset, 0.37 g both ways), then ``strong`` (m/s^2)."""
    dt = 0.01
    noise = 0.2 * G * np.random.default_rng(seed).uniform(-1.0, 1.0, 300)
    return Record(np.r_[noise, strong, np.zeros(10)], dt, name="quiet start")


@pytest.mark.parametrize("strong", [
    pytest.param(0.9 * G * np.sin(2 * np.pi * np.arange(150) * 0.01 / 0.6)
                 * np.exp(-np.arange(150) * 0.01), id="survives"),
    pytest.param(np.full(45, 1.0 * G), id="collapses")])
def test_skip_at_rest_is_no_skipping(strong):
    """Oracle: the same run stepping every step. The chain at rest under ground accelerations
    inside its safe domain does not move, so the verdict, onset, impacts and collapse time are
    those of the full run; the peak crown drop agrees to 1e-9 of the collapse drop (what the
    skipped steps' round-off leaves: measured 2e-11). The skipped run computes fewer steps."""
    rec = _quiet_start(strong)
    a = rigid_verdict(OPPENHEIM, rec, guard=False)
    b = rigid_verdict(OPPENHEIM, rec, guard=False, skip_at_rest=False)
    assert a.outcome is b.outcome is not Outcome.INDETERMINATE
    assert a.onset_time_s == b.onset_time_s and a.impacts == b.impacts
    assert a.collapse_half_cycle == b.collapse_half_cycle
    if a.outcome is Outcome.COLLAPSE:
        assert a.collapse_time_s == pytest.approx(b.collapse_time_s, abs=1e-9)
    assert a.peak_crown_drop == pytest.approx(b.peak_crown_drop, abs=1e-9)
    assert a.skipped_steps >= 2900 and a.steps < b.steps and b.skipped_steps == 0


@pytest.mark.parametrize("amplitude_g", [0.45, 0.55])
def test_a_chain_set_moving_is_not_at_rest(amplitude_g):
    """Oracle: the same run stepping every step. 1 s of quiet, then 2 s of noise whose samples
    pass the onset (0.370 g) one at a time: the chain starts to move with little kinetic
    energy, settles, and is pushed again. Skipping may not treat it as at rest (zeroing its
    velocity): the verdict, onset, impacts and peak crown drop are those of the full run
    (measured: equal, the drop to 8e-11 of the collapse drop). Zeroing the velocity of a chain
    just set moving (rest counted from t = 0) gave 4 impacts instead of 1 at 0.55 g; zeroing it
    after it had settled gave no_hinging instead of survives at 0.45 g."""
    noise = amplitude_g * G * np.random.default_rng(2).uniform(-1.0, 1.0, 200)
    rec = Record(np.r_[np.zeros(100), noise, np.zeros(10)], 0.01, name="late noise")
    a = rigid_verdict(OPPENHEIM, rec, guard=False)
    b = rigid_verdict(OPPENHEIM, rec, guard=False, skip_at_rest=False)
    assert a.outcome is b.outcome is Outcome.SURVIVES
    assert a.onset_time_s == b.onset_time_s and a.impacts == b.impacts
    assert a.peak_crown_drop == pytest.approx(b.peak_crown_drop, abs=1e-9)
    assert a.skipped_steps >= 900  # the quiet second


def test_motion_below_the_onset_costs_no_step():
    """A record whose peak (0.3 g) stays below the chain's onset accelerations (0.370 g both
    ways, the limit-analysis multiplier): no hinge, proven at t = 0 without a step."""
    rec = Record(0.3 * G * np.sin(np.linspace(0.0, 20.0, 500)), 0.01, name="weak")
    v = rigid_verdict(OPPENHEIM, rec)
    assert v.outcome is Outcome.NO_HINGING and v.rest_proven
    assert v.steps == 0 and v.end_time_s == 0.0


def test_batch_is_one_by_one():
    """Oracle: each history alone. Threads share nothing but the model's arrays, so the batch
    of verdicts (two threads, mixed durations and outcomes) equals the single runs exactly."""
    motions = [StepImpulse.from_g(a, tp) for a, tp in
               [(1.0, 0.2), (1.0, 0.415), (0.5, 0.6), (0.3, 0.5), (1.0, 0.3), (1.5, 0.1)]]
    batch = rigid_verdicts(OPPENHEIM, motions, threads=2)
    single = [rigid_verdict(OPPENHEIM, m) for m in motions]
    assert [b.to_dict() for b in batch] == [s.to_dict() for s in single]
    assert {b.outcome for b in batch} >= {Outcome.SURVIVES, Outcome.COLLAPSE,
                                          Outcome.NO_HINGING}


def test_step_rule_scales_with_the_arch():
    """Oracle: similitude. A 1:20 model of Oppenheim's arch under the same pulse in g with t_p
    scaled by sqrt(1/20) moves as the full arch with time scaled by sqrt(1/20); the default
    step scales the same way, so the two verdicts are one discrete history: collapse times in
    the ratio sqrt(1/20) to 1e-9 (round-off)."""
    s = 1.0 / 20.0
    small = Arch(10.0 * s, 1.5 * s, math.radians(157.5), 7)
    assert verdict_time_step(small) == pytest.approx(math.sqrt(s) * verdict_time_step(OPPENHEIM),
                                                     rel=1e-12)
    assert verdict_time_step(OPPENHEIM) == pytest.approx(STEP_FACTOR * math.sqrt(1.5 / G))
    big = rigid_verdict(OPPENHEIM, StepImpulse.from_g(1.0, 0.415))
    lab = rigid_verdict(small, StepImpulse.from_g(1.0, 0.415 * math.sqrt(s)))
    assert lab.outcome is big.outcome is Outcome.COLLAPSE
    assert lab.collapse_time_s == pytest.approx(math.sqrt(s) * big.collapse_time_s, rel=1e-9)


def test_models_are_built_once():
    """An arch is frozen: its chain is built once and shared."""
    assert rigid_model(OPPENHEIM) is rigid_model(Arch(10.0, 1.5, math.radians(157.5), 7))


def test_bad_inputs_name_the_option():
    from archquake.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match="time_step"):
        rigid_verdict(OPPENHEIM, StepImpulse.from_g(1.0, 0.2), time_step=-1.0)
    with pytest.raises(InvalidParameterError, match="threads"):
        rigid_verdicts(OPPENHEIM, [StepImpulse.from_g(1.0, 0.2)], threads=0)
    with pytest.raises(InvalidParameterError, match="duration"):
        rigid_verdicts(OPPENHEIM, [StepImpulse.from_g(1.0, 0.2)], duration=[1.0, 2.0])


def test_mean_acceleration_of_a_piecewise_constant_pulse_is_the_sub_sampled_mean():
    """Oracle: the 16 mid-point sub-samples of every step, averaged (what `mean_acceleration`
    does for any motion). For the step impulse and the rectangular pulse only the steps across
    a breakpoint are sub-sampled, and the others must equal that mean to the bit (a sum of equal
    values is exact): the verdicts' digests rest on it. Steps that do not divide the pulse, and
    starts before, at and after its breakpoints."""
    from archquake.ground.pulses import RectangularPulse
    from archquake.rigid.model import ACC_SAMPLES, mean_acceleration

    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    for motion in (StepImpulse.from_g(1.0, 0.27), StepImpulse.from_g(0.731, 0.1234567, 1),
                   RectangularPulse(-7.3, 0.283)):
        for h in (1e-3, 1e-4, 0.00123456):
            for t0 in (0.0, -0.01, 0.13, 0.27):
                n = int(1.0 / h)
                t = t0 + h * (np.arange(n)[:, None] + sub[None, :])
                plain = motion.acceleration(t.ravel()).reshape(n, ACC_SAMPLES).mean(1)
                assert np.array_equal(mean_acceleration(motion, t0, h, n), plain)
