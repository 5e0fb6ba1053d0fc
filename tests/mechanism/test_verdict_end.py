"""A run cut by ``t_end`` states only what it shows (``archquake.outcome.conclude``).

Oppenheim's arch (R = 10 m, t/R = 0.15, 157.5 deg, 7 voussoirs) under Eq. 4 (one mechanism, c_T
0.766) and the step impulse of 1.0 g: t_p = 0.20 s survives (first impact 0.601 s, after the
excitation's end 3 t_p = 0.60 s), t_p = 0.27 s collapses in half cycle 2 (paper Figure 4c).

Oracles: the full run to the default end (the verdict a cut run must not contradict), and the
crest barrier computed here from :func:`archquake.mechanism.kinematics.potential` on a grid of
rotations from 0 to the toggle (not from the packed crest ``phi_crit`` the kernel uses), with the
kinetic energy ``1/2 m_eff(0) phi'^2`` of the recorded impact rates.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from archquake import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.mechanism.kinematics import PHI_TOGGLE, potential
from archquake.outcome import Outcome

G = 9.80665


@pytest.fixture(scope="module")
def prepared():
    return PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7), "paper")


def barrier_by_scan(prepared) -> float:
    """g [max V - V(0)] over 0 <= phi < toggle, the least over the table's rows, J."""
    out = math.inf
    for packed in prepared.table.packed:
        phis = np.linspace(0.0, float(packed[PHI_TOGGLE]) * (1.0 - 1e-9), 4001)
        v = np.array([potential(packed, float(p)) for p in phis])
        out = min(out, G * (float(v.max()) - float(v[0])))
    return out


def energy_fraction(prepared, rate: float) -> float:
    """Kinetic energy at phi = 0 on row 0 over the scanned barrier."""
    return 0.5 * float(prepared.table.meff0()[0]) * rate * rate / barrier_by_scan(prepared)


def test_default_end_survives_at_rest(prepared):
    r = simulate(prepared, StepImpulse.from_g(1.0, 0.20), g=G)
    assert r.outcome is Outcome.SURVIVES and r.final_state.value == "rest"
    assert "at rest after the excitation" in r.verdict_reason


def test_cut_mid_rocking_above_barrier_is_indeterminate(prepared):
    """Cut between the end of the excitation (0.60 s) and the first impact (0.601 s): the half
    cycle closing then carries more energy than the crest barrier (it is conserved after the
    excitation up to the impact: the full run's rate before it), so nothing is shown."""
    full = simulate(prepared, StepImpulse.from_g(1.0, 0.20), g=G)
    t_imp = float(full.impact_times[0])
    assert 0.60 < t_imp < 0.61
    assert energy_fraction(prepared, float(full.impact_rates[0, 0])) > 1.0
    cut = simulate(prepared, StepImpulse.from_g(1.0, 0.20), t_end=0.5 * (0.60 + t_imp), g=G)
    assert cut.final_state.value == "moving" and cut.impact_times.size == 0
    assert cut.outcome is Outcome.INDETERMINATE
    assert cut.computed_outcome is Outcome.SURVIVES
    assert "still rocking" in cut.verdict_reason
    d = json.loads(json.dumps(cut.to_dict()))
    assert (d["outcome"], d["computed_outcome"]) == ("indeterminate", "survives")
    assert "run longer" in d["verdict"]


def test_cut_after_impact_below_barrier_survives(prepared):
    """Cut at 1.5 s, after the first impact (0.601 s, after the excitation): that impact left
    0.84 of the scanned barrier, so the arch cannot reach its crest again: survives, as the
    full run (which ends at rest) says."""
    cut = simulate(prepared, StepImpulse.from_g(1.0, 0.20), t_end=1.5, g=G)
    assert cut.final_state.value == "moving" and cut.impact_times.size == 1
    assert cut.impact_times[0] >= 0.60
    fraction = energy_fraction(prepared, float(cut.impact_rates[0, 1]))
    assert 0.8 < fraction < 0.9
    assert cut.outcome is Outcome.SURVIVES
    assert f"({fraction:.3g} of it)" in cut.verdict_reason


def test_cut_after_impact_above_barrier_is_not_survival(prepared):
    """t_p = 0.27 s cut at 1.5 s: the impact at 0.861 s (after the excitation, 0.81 s) left more
    than the barrier, and indeed the full run collapses: the cut run must not say survives."""
    pulse = StepImpulse.from_g(1.0, 0.27)
    full = simulate(prepared, pulse, g=G)
    assert full.outcome is Outcome.COLLAPSE and full.collapse_half_cycle == 2
    cut = simulate(prepared, pulse, t_end=1.5, g=G)
    assert cut.impact_times.size == 1 and cut.impact_times[0] > 0.81
    assert energy_fraction(prepared, float(cut.impact_rates[0, 1])) > 1.0
    assert cut.outcome is Outcome.INDETERMINATE and cut.computed_outcome is Outcome.SURVIVES


@pytest.mark.parametrize("tp, a_g, computed", [(0.20, 1.0, Outcome.SURVIVES),
                                               (0.20, 0.1, Outcome.NO_HINGING)])
def test_cut_before_excitation_ends_is_indeterminate(prepared, tp, a_g, computed):
    """t_end = 0.3 s < 3 t_p = 0.6 s: the rest of the pulse may still open hinges or bring
    collapse (0.1 g is below lambda, so the full run has no hinging; the cut one cannot know)."""
    cut = simulate(prepared, StepImpulse.from_g(a_g, tp), t_end=0.3, g=G)
    assert cut.outcome is Outcome.INDETERMINATE and cut.computed_outcome is computed
    assert "before the excitation ended" in cut.verdict_reason
    full = simulate(prepared, StepImpulse.from_g(a_g, tp), g=G)
    assert full.outcome is computed


@pytest.mark.parametrize("tp, expected", [(0.20, Outcome.SURVIVES),
                                          (0.27, Outcome.INDETERMINATE)])
def test_stalled_by_max_impacts(prepared, tp, expected):
    """max_impacts = 1 locks the arch at its first impact, after the excitation: survives only
    if that impact left less than the barrier (0.84 of it at 0.20 s; above it at 0.27 s, whose
    full run collapses)."""
    r = simulate(prepared, StepImpulse.from_g(1.0, tp), options=SolverOptions(max_impacts=1),
                 g=G)
    assert r.final_state.value == "stalled"
    assert r.outcome is expected and r.computed_outcome is Outcome.SURVIVES
