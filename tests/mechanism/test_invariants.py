"""Physics invariants of the four-link model: energy, mirror symmetry, dynamic similarity,
restitution, and the compiled path against the plain solve_ivp reference."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch, Face, HingeMechanism
from archquake.ground import SinePulse, StepImpulse
from archquake.mechanism import Outcome, PreparedMechanism, SolverOptions, simulate, solve_impact
from archquake.mechanism.kinematics import PHI_CRIT, eom_terms, potential
from archquake.mechanism.reference import simulate_reference

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.fixture(scope="module")
def prepared():
    return PreparedMechanism.build(OPPENHEIM)


def _energy(packed, phi, rate):
    return 0.5 * eom_terms(packed, phi)[1] * rate**2 + G * potential(packed, phi)


def test_free_rocking_conserves_energy_between_impacts(prepared):
    """Without excitation, E = m_eff phi'^2 / 2 + V(phi) is constant within each half cycle.

    Checked at the integrator's accepted steps (rtol 1e-11): 1e-8 relative is the requirement;
    the dense-output interpolant is not held to it (see SolverOptions.output_interval).
    """
    packed = prepared.packed
    m0 = eom_terms(packed, 0.0)[1]
    v0 = 0.7 * math.sqrt(2 * G * potential(packed, packed[PHI_CRIT]) / m0)  # below the crest
    r = simulate(prepared, StepImpulse(0.0, 1.0), initial_rate=v0, t_end=4.0,
                 options=SolverOptions(rtol=1e-11, output_interval=-1))
    assert r.impact_times.size >= 5
    h = r.history
    segment = np.searchsorted(r.impact_times, h.t, side="left")
    checked = 0
    for k in np.unique(segment):
        sel = (segment == k) & (h.phi > 0)
        if sel.sum() < 3:
            continue
        e = np.array([_energy(packed, p, v) for p, v in zip(h.phi[sel], h.phi_dot[sel])])
        assert np.ptp(e) / e.max() < 1e-8
        checked += 1
    assert checked >= 5
    # each impact removes the fraction 1 - c_T of the kinetic energy, nothing else does
    before, after = r.impact_rates[:, 0], r.impact_rates[:, 1]
    assert np.allclose(after / -before, r.restitution_cv, rtol=1e-12)
    assert np.allclose(-before[1:] / after[:-1], 1.0, rtol=1e-7)


def test_impact_restitution_of_oppenheims_arch():
    sol = solve_impact(PreparedMechanism.build(OPPENHEIM).mechanism)
    assert sol.residual < 1e-12
    assert sol.restitution_ct == pytest.approx(sol.restitution_cv**2, rel=1e-12)  # Eq. 7
    assert 0.0 < sol.restitution_cv < 1.0
    assert not sol.energy_gain


@given(st.floats(0.1, 100.0), st.floats(500.0, 5000.0), st.floats(0.2, 3.0))
@settings(max_examples=15, deadline=None)
def test_restitution_independent_of_scale_density_and_depth(radius, density, depth):
    arch = Arch(radius, 0.15 * radius, math.radians(157.5), 7, depth=depth, density=density)
    mech = HingeMechanism(arch, (0, 3, 5, 7), (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS))
    ref = HingeMechanism(OPPENHEIM, mech.joints, mech.faces)
    assert solve_impact(mech).restitution_cv == pytest.approx(solve_impact(ref).restitution_cv, rel=1e-10)


def test_restitution_falls_as_the_arch_thickens():
    """Paper p. 2125: as t/R increases the coefficient of restitution decreases."""
    faces = (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS)
    cvs = [solve_impact(HingeMechanism(Arch.from_ratio(r, math.radians(157.5), 7, radius=10), (0, 3, 5, 7),
                                       faces)).restitution_cv for r in (0.13, 0.15, 0.17, 0.19)]
    assert np.all(np.diff(cvs) < 0)


def test_energy_gain_is_reported_not_hidden():
    """With Oppenheim's hinge set on a thinner arch the five balances give c_T > 1."""
    faces = (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS)
    thin = Arch.from_ratio(0.11, math.radians(157.5), 7, radius=10)
    sol = solve_impact(HingeMechanism(thin, (0, 3, 5, 7), faces))
    assert sol.restitution_cv > 1.0 and sol.energy_gain
    result = simulate(HingeMechanism(thin, (0, 3, 5, 7), faces), StepImpulse.from_g(0.5, 0.1), t_end=3.0)
    assert result.energy_gain and result.to_dict()["energy_gain"] is True


@pytest.mark.parametrize("motion", [StepImpulse.from_g(1.0, 0.2), StepImpulse.from_g(1.0, 0.27),
                                    SinePulse.from_g(0.6, 2.0)])
def test_mirrored_pulse_gives_the_mirrored_response(prepared, motion):
    a = simulate(prepared, motion, t_end=5.0)
    b = simulate(prepared, motion.mirrored(), t_end=5.0)
    assert a.outcome is b.outcome and a.collapse_half_cycle == b.collapse_half_cycle
    np.testing.assert_allclose(a.impact_times, b.impact_times, rtol=0, atol=1e-12)
    np.testing.assert_allclose(a.peak_rotation, b.peak_rotation, rtol=1e-12)
    # the mirror-image mechanism moves first
    assert a.history.side[a.history.side != 0][0] == 1
    assert b.history.side[b.history.side != 0][0] == -1
    np.testing.assert_allclose(a.history.signed_rotation, -b.history.signed_rotation, atol=1e-12)


@pytest.mark.parametrize("k", [0.1, 0.5, 2.0, 4.0])
def test_exact_dynamic_similarity(prepared, k):
    """R -> kR with time -> sqrt(k) time (same accelerations) gives the same response."""
    big = PreparedMechanism.build(OPPENHEIM.scaled(k))
    s = math.sqrt(k)
    for motion, scaled in [(StepImpulse.from_g(1.0, 0.2), StepImpulse.from_g(1.0, 0.2 * s)),
                           (StepImpulse.from_g(1.0, 0.27), StepImpulse.from_g(1.0, 0.27 * s)),
                           (SinePulse.from_g(0.7, 1.5), SinePulse.from_g(0.7, 1.5 * s))]:
        a = simulate(prepared, motion, t_end=5.0)
        b = simulate(big, scaled, t_end=5.0 * s)
        assert a.outcome is b.outcome and a.collapse_half_cycle == b.collapse_half_cycle
        np.testing.assert_allclose(b.impact_times, s * a.impact_times, rtol=1e-9)
        np.testing.assert_allclose(b.peak_rotation, a.peak_rotation, rtol=1e-7, atol=1e-12)


cases = st.tuples(st.floats(0.38, 1.6), st.floats(0.05, 1.2), st.sampled_from(["step", "sine"]))


@given(cases)
@settings(max_examples=12, deadline=None)
def test_compiled_path_equals_solve_ivp_reference(case):
    """Two implementations of the same model and event logic (DOPRI5 in numba vs SciPy DOP853)."""
    a_g, dur, family = case
    motion = StepImpulse.from_g(a_g, dur) if family == "step" else SinePulse.from_g(a_g, 3 * dur)
    prep = PreparedMechanism.build(OPPENHEIM)
    fast = simulate(prep, motion, t_end=6.0, options=SolverOptions(rtol=1e-11))
    ref = simulate_reference(prep, motion, t_end=6.0)
    assert fast.outcome is ref.outcome
    assert fast.collapse_half_cycle == ref.collapse_half_cycle
    n = min(8, ref.impact_times.size)
    np.testing.assert_allclose(fast.impact_times[:n], ref.impact_times[:n], atol=1e-6)
    if fast.outcome is Outcome.COLLAPSE:
        assert fast.collapse_time == pytest.approx(ref.collapse_time, abs=1e-6)


def test_inadmissible_impact_is_reported_and_treated_as_plastic():
    """A thick, shallow arch for which Eqs. 4a-4e give c_v < 0 (the mirror mechanism would start
    closing): flagged, and the compiled and reference drivers both stop the arch at the impact."""
    arch = Arch(10.0, 3.17, math.radians(106.8), 20)
    prep = PreparedMechanism.build(arch)
    assert prep.impact.restitution_cv < 0 and not prep.impact.admissible
    assert prep.restitution == 0.0
    lam = prep.mechanism.collapse_acceleration_g
    motion = StepImpulse.from_g(1.5 * lam, 0.3)
    r = simulate(prep, motion)
    assert not r.impact_admissible and r.impact_model_cv == prep.impact.restitution_cv
    assert r.restitution_cv == 0.0 and r.to_dict()["impact_admissible"] is False
    if r.computed_outcome is not Outcome.COLLAPSE:
        assert r.impact_times.size == 1 and r.final_state.value == "rest"
        # the arch stopped at an impact Eq. 4 cannot describe: no survival is claimed
        assert r.outcome is Outcome.INDETERMINATE and not r.impact_described
    ref = simulate_reference(prep, motion)
    assert ref.outcome is r.computed_outcome and ref.impact_times.size == r.impact_times.size
