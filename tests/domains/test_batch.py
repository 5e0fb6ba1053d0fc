"""The fast path (parallel batch over the compiled kernel, with the energy-proof early stop) against
the scalar path (:func:`archquake.mechanism.simulate`), point by point.

Oracle: the scalar path itself; the outcome and the collapse half cycle are discrete, so they must
agree exactly.
"""

from __future__ import annotations

import numpy as np
import pytest

from archquake.domains import evaluate_pulses
from archquake.domains.batch import evaluate_pulses_scalar
from archquake.ground import StepImpulse
from archquake.mechanism import simulate
from archquake.mechanism.simulate import default_t_end
from archquake.outcome import Outcome


def _grid(family):
    if family == "step":
        durations = np.array([0.12, 0.2, 0.27, 0.44, 0.8, 1.4])
    else:
        durations = np.array([0.4, 0.9, 1.6, 2.5, 3.6])
    mags = np.array([0.36, 0.371, 0.39, 0.45, 0.6, 0.8, 1.0, 1.4, 2.2, 3.5])
    a, d = np.meshgrid(mags, durations)
    return a.ravel(), d.ravel()


@pytest.mark.parametrize("family", ["step", "sine"])
@pytest.mark.parametrize("early", [True, False])
def test_batch_equals_scalar_point_by_point(oppenheim_prepared, family, early):
    a, d = _grid(family)
    fast = evaluate_pulses(oppenheim_prepared, family, a, d, early=early)
    slow = evaluate_pulses_scalar(oppenheim_prepared, family, a, d)
    # the grid must exercise every outcome and both half cycles, or the test proves little
    # (Eq. 4 describes Oppenheim's impacts, c_v = 0.875: nothing is indeterminate there)
    assert set(Outcome) - {Outcome.INDETERMINATE} == set(slow.outcome.tolist())
    assert {1, 2} <= set(slow.collapse_half_cycle.tolist())
    np.testing.assert_array_equal(fast.outcome, slow.outcome)
    np.testing.assert_array_equal(fast.collapse_half_cycle, slow.collapse_half_cycle)


def test_early_stop_is_used_for_survivors(oppenheim_prepared):
    # surviving cases are decided from a run capped at a few impacts (one run), not run to rest
    r = evaluate_pulses(oppenheim_prepared, "step", [0.5, 0.8], [0.2, 0.2])
    assert r.outcome.tolist() == [Outcome.SURVIVES] * 2 and (r.runs == 1).all()


def test_paper_figure4_pulses(oppenheim_prepared):
    # paper p. 2127: a = 1.0 g; t_p = 0.44 s collapses in the 1st half cycle, 0.27 s in the 2nd,
    # 0.20 s survives
    r = evaluate_pulses(oppenheim_prepared, "step", 1.0, [0.44, 0.27, 0.20])
    assert r.collapse_half_cycle.tolist() == [1, 2, 0]
    assert r.outcome.tolist() == [Outcome.COLLAPSE, Outcome.COLLAPSE, Outcome.SURVIVES]


def test_analysis_end_matches_simulate_default(oppenheim_prepared):
    # the batch must integrate over the same window as simulate's default, or late collapses differ
    r = simulate(oppenheim_prepared, StepImpulse.from_g(0.5, 0.3))
    ours = default_t_end(np.array([0.9]), 10.0, r.g)[0]
    assert ours == pytest.approx(r.stats["t_end"], rel=1e-14)


def test_plugged_outcomes_are_outcome_values():
    """A model plugged into the domain search speaks Outcome (or its strings), never the
    kernel's integer codes."""
    from archquake.domains import PulseOutcomes

    ok = PulseOutcomes(np.ones(2), np.ones(2), ["collapse", Outcome.SURVIVES], np.array([1, 0]),
                       np.ones(2, int))
    assert ok.outcome.tolist() == [Outcome.COLLAPSE, Outcome.SURVIVES]
    assert ok.collapses.tolist() == [True, False] and ok.collapses_first.tolist() == [True, False]
    with pytest.raises(ValueError):
        PulseOutcomes(np.ones(1), np.ones(1), [2], np.array([1]), np.ones(1, int))


def test_bad_input_is_one_line(oppenheim_prepared):
    with pytest.raises(ValueError, match="durations must be finite and > 0 s"):
        evaluate_pulses(oppenheim_prepared, "step", 1.0, [0.0])
    with pytest.raises(ValueError, match="pulse family must be 'step' or 'sine'"):
        evaluate_pulses(oppenheim_prepared, "ramp", 1.0, [0.2])


def test_batch_equals_scalar_where_verdicts_are_indeterminate():
    """The semicircle R = 5 m, t = 0.6 m, 15 voussoirs under Eq. 4 (c_v = 49.9: energy gain):
    the batch and simulate agree on the qualified verdict case by case, a collapse after an
    impact is indeterminate and one in the first half cycle stays a collapse."""
    import math

    from archquake.geometry import Arch

    arch = Arch(5.0, 0.6, math.pi, 15)
    a = np.array([0.06, 0.1, 0.15, 0.15, 0.3])
    d = np.array([0.2, 0.1, 0.1, 0.3, 0.3])
    fast = evaluate_pulses(arch, "step", a, d, impact="paper")
    slow = evaluate_pulses_scalar(arch, "step", a, d, impact="paper")
    np.testing.assert_array_equal(fast.outcome, slow.outcome)
    np.testing.assert_array_equal(fast.collapse_half_cycle, slow.collapse_half_cycle)
    assert Outcome.INDETERMINATE in set(fast.outcome.tolist())
    for o, h, ind, col in zip(fast.outcome, fast.collapse_half_cycle, fast.indeterminate,
                              fast.collapses, strict=True):
        assert ind == (o is Outcome.INDETERMINATE)
        assert col == (h > 0)  # the law's computed collapse, certain or not
        if h == 1:
            assert o is Outcome.COLLAPSE
        if h >= 2:
            assert o is Outcome.INDETERMINATE


@pytest.mark.parametrize("early", [True, False])
def test_batch_equals_scalar_under_the_followed_chain_law(early):
    """The chain law followed over its reachable set (Oppenheim: 2 rows; the semicircle
    n = 15: 10 rows, its first impact 'outside'): the batch (table stack, least crest barrier
    over the rows, per-impact validity) and simulate agree case by case."""
    import math

    from archquake.geometry import Arch

    for arch, a, d in [(Arch(10.0, 1.5, math.radians(157.5), 7), [1.0, 1.0, 1.0, 0.6, 1.0],
                        [0.44, 0.27, 0.20, 0.35, 0.30]),
                       (Arch(5.0, 0.6, math.pi, 15), [0.1, 0.15, 0.15, 0.15, 0.3],
                        [0.2, 0.1, 0.15, 0.3, 0.3])]:
        fast = evaluate_pulses(arch, "step", a, d, impact="chain", early=early)
        slow = evaluate_pulses_scalar(arch, "step", a, d, impact="chain")
        np.testing.assert_array_equal(fast.outcome, slow.outcome)
        np.testing.assert_array_equal(fast.collapse_half_cycle, slow.collapse_half_cycle)


@pytest.mark.parametrize("early", [True, False])
def test_batch_states_a_run_locked_by_max_impacts_as_simulate_does(oppenheim_prepared, early):
    """max_impacts = 1 on Oppenheim's arch under Eq. 4 (step impulses of 1.0 g, t_p = 0.27,
    0.20 s; 0.4 g, t_p = 0.1 s). Oracle: simulate, case by case, whose rule
    (outcome.conclude) is checked here on its final states: t_p = 0.27 s impacts at 0.861 s,
    after the excitation (0.81 s), with more energy than the crest barrier (the full run
    collapses in half cycle 2, paper Figure 4c), so the run locked at that impact is
    ``stalled`` and indeterminate, not a survival; t_p = 0.20 s impacts at 0.601 s (after
    0.60 s) below the barrier: ``stalled`` but shown to survive; 0.4 g reaches the cap during
    the excitation and ends at rest: ``stalled`` by the cap, indeterminate."""
    from archquake.domains import PulseFamily
    from archquake.mechanism import SolverOptions

    a, d = np.array([1.0, 1.0, 0.4]), np.array([0.27, 0.20, 0.10])
    options = SolverOptions(max_impacts=1)
    fast = evaluate_pulses(oppenheim_prepared, "step", a, d, options=options, early=early)
    slow = evaluate_pulses_scalar(oppenheim_prepared, "step", a, d, options=options)
    np.testing.assert_array_equal(fast.outcome, slow.outcome)
    np.testing.assert_array_equal(fast.collapse_half_cycle, slow.collapse_half_cycle)
    assert slow.outcome.tolist() == [Outcome.INDETERMINATE, Outcome.SURVIVES,
                                     Outcome.INDETERMINATE]
    runs = [simulate(oppenheim_prepared, PulseFamily.STEP.motion(ai, di),
                     options=SolverOptions(max_impacts=1, output_interval=0.0))
            for ai, di in zip(a, d, strict=True)]
    assert [r.final_state.value for r in runs] == ["stalled", "stalled", "rest"]
    assert [r.impact_times[0] > 3 * di for r, di in zip(runs, d, strict=True)] == [True, True,
                                                                                   False]
    full = evaluate_pulses_scalar(oppenheim_prepared, "step", a[:1], d[:1])
    assert full.outcome.tolist() == [Outcome.COLLAPSE] and full.collapse_half_cycle[0] == 2
