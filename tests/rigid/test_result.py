"""What the rigid chain (issue 16) reports: the hinge sets it passed through, an honest verdict,
and the joint forces of the mechanism in use.

Oracles: the four-link mechanism (Eq. 2, limit-analysis hinges) while it is admissible;
mirror symmetry of the hinge sequence; the thrust line of the moving four-link mechanism
(`thrust.states.state_at`, an independent statics solve) where the rigid chain's joint forces
are unique.
"""

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.blocks.result import rest_threshold, settled
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import StepImpulse
from archquake.ground.pulses import RectangularPulse
from archquake.outcome import Outcome
from archquake.rigid import simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.fixture(scope="module")
def four_hinge_run():
    """0.40 g step (lambda = 0.37 g): the limit-analysis mechanism, admissible until t_p."""
    return simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.40, 0.2), duration=0.2,
                          output_interval=1e-3)


@pytest.fixture(scope="module")
def mirrored_runs():
    pulse = RectangularPulse(-2.0 * 0.37 * G, 0.283)
    return (simulate_rigid(OPPENHEIM, pulse, duration=0.8),
            simulate_rigid(OPPENHEIM, pulse.mirrored(), duration=0.8))


def test_hinge_sets_of_the_four_link_phase(four_hinge_run):
    """The first set is an onset; until t_p the arch moves on the limit-analysis mechanism
    0i 3e 5i 7e, one degree of freedom. Its hinges are reported as their openings pass the
    threshold (``hinge_opening`` t), so under this slow onset they appear one by one: every
    set is a subset of the mechanism's."""
    sets = four_hinge_run.hinge_sets()
    assert sets[0].kind == "onset"
    assert all(set(e.hinges.split()) <= {"0i", "3e", "5i", "7e"} for e in sets)
    last = sets[-1]
    assert (last.hinges, last.degrees_of_freedom) == ("0i 3e 5i 7e", 1)
    assert last.time_s < 0.15
    out = four_hinge_run.to_dict()["mechanisms"]
    assert set(out[-1]) >= {"time_s", "hinges", "kind"}  # MechanismEvent's keys
    assert out[-1]["hinges"] == "0i 3e 5i 7e"


def _mirror(label: str, n_joints: int) -> str:
    parts = [(n_joints - 1 - int(h[:-1]), h[-1]) for h in label.split()]
    return " ".join(f"{j}{f}" for j, f in sorted(parts))


def test_hinge_sets_are_mirror_symmetric(mirrored_runs):
    """The mirrored pulse passes through the mirrored hinge sets (joint j <-> n - j, same face),
    at the same times, through the onset, a five-hinge phase (2 dof) and migrations."""
    a, b = (r.hinge_sets() for r in mirrored_runs)
    nj = len(mirrored_runs[0].assembly.joints)
    assert [(e.time_s, _mirror(e.hinges, nj), e.kind) for e in a] == [
        (e.time_s, e.hinges, e.kind) for e in b]
    assert max(e.degrees_of_freedom for e in a) >= 2  # a five-hinge phase
    assert len(a) >= 4


# ----------------------------------------------------------------------------- verdict
@pytest.fixture(scope="module")
def rocking_cut_short():
    """Figure 4's 0.20 s step at 1.0 g: rocking with impacts at 0.64, 1.73, 2.46, 2.90 s...;
    cut at 3 s, while the arch still rocks."""
    return simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.20), duration=3.0,
                          output_interval=1e-3)


def test_a_run_cut_short_while_rocking_is_not_survival(rocking_cut_short):
    """The verdict: 'survives' only at rest after the excitation; cut while rocking, the rigid
    chain reports 'indeterminate' with the reason."""
    res = rocking_cut_short
    assert res.impact_times.size >= 4 and res.collapse_time is None
    assert res.outcome is Outcome.INDETERMINATE and res.final_state == "moving"
    out = rocking_cut_short.to_dict()
    assert out["outcome"] == "indeterminate" and "still moving" in out["verdict"]


def test_until_rest_extends_the_run_to_a_verdict():
    """With ``until_rest`` the same run goes on until the arch is at rest (kinetic energy below
    1e-6 W L over sqrt(L/g)), and then it survives; the extension stops there, well before
    the cap."""
    run = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.20), duration=3.0,
                         output_interval=1e-3, until_rest=30.0)
    res = run
    assert res.outcome is Outcome.SURVIVES and res.final_state == "rest"
    assert 3.5 < res.end_time < 8.0
    k_max, window = rest_threshold(res.assembly, res.g)
    assert res.kinetic[res.times >= res.end_time - window].max() <= k_max
    assert res.kinetic[res.times < 3.0].max() > 1e4 * k_max  # it did rock


def test_settled_needs_the_whole_window_after_the_excitation(rocking_cut_short):
    """The rule itself: a still window that starts before the excitation ends, or is shorter
    than sqrt(L/g), is not rest; a zero of the kinetic energy at a reversal is not rest."""
    res = rocking_cut_short
    k_max, window = rest_threshold(res.assembly, res.g)
    t = np.linspace(0.0, 2.0 * window, 101)
    still = np.zeros_like(t)
    assert settled(res.assembly, res.g, t, still, excitation_end=0.5 * window)
    assert not settled(res.assembly, res.g, t, still, excitation_end=1.5 * window)
    assert not settled(res.assembly, res.g, t[:40], still[:40], excitation_end=None)
    reversal = np.abs(np.sin(2 * np.pi * t / window)) * 1e3 * k_max  # zero at instants only
    assert not settled(res.assembly, res.g, t, reversal, excitation_end=0.0)


# ----------------------------------------------------------------------------- joint forces
def test_forces_of_the_four_link_phase_are_its_statics(four_hinge_run):
    """While the arch moves on the four-hinge mechanism its joint forces are determinate, and
    the rigid chain's (corner impulses / h) equal the four-link mechanism's
    (`thrust.states.state_at` at Eq. 2's exact state: an independent statics solve): normal
    force, line of thrust, friction demand at every joint."""
    from archquake.mechanism import SolverOptions, simulate
    from archquake.mechanism.prepared import PreparedMechanism
    from archquake.thrust.states import state_at

    motion = four_hinge_run.ground_motion
    times = np.array([0.12, 0.15, 0.18])
    ref = simulate(OPPENHEIM, motion, t_eval=times, t_end=0.25,
                   options=SolverOptions(output_interval=0.0)).evaluated
    prep = PreparedMechanism.build(OPPENHEIM)
    f = four_hinge_run.joint_forces
    for i, t in enumerate(times):
        s = state_at(prep, t, float(ref.phi[i]), float(ref.phi_dot[i]), int(ref.side[i]),
                     float(motion.acceleration(t)))
        k = int(np.argmin(np.abs(f.times - t)))
        assert abs(f.times[k] - t) < 1e-9 and f.unique[k] and not f.impulsive[k]
        n_ref = s.forces.normal
        assert np.max(np.abs(f.normal[k] - n_ref)) < 1e-5 * n_ref.max()
        assert np.max(np.abs(f.eccentricity[k] - s.forces.eccentricity)) < 1e-5 * f.half_depth.max()
        assert np.max(np.abs(f.friction_demand[k] - s.friction_demand)) < 1e-4


@pytest.mark.parametrize("friction", [None, 0.6])
def test_the_compiled_force_probe_is_its_plain_twin(friction):
    """The compiled probe (all samples in one call, the rank test batched by active set) against
    its plain loop (`joint_forces_reference`: one projection and one SVD per sample): the same
    projections in the same order, so the forces agree to 1e-12 of the largest (double
    rounding only) and the flags exactly. The history rocks, impacts and all (warm starts,
    holds, impulsive and indeterminate samples), with and without Coulomb friction."""
    from archquake.rigid.forces import joint_forces, joint_forces_reference

    run = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.27), duration=1.2,
                         friction=friction, output_interval=1e-3)
    fast = joint_forces(run, run.ground_motion)
    plain = joint_forces_reference(run, run.ground_motion)
    assert plain.impulsive.any() and plain.unique.any() and not plain.unique.all()  # exercised
    assert np.array_equal(fast.unique, plain.unique)
    assert np.array_equal(fast.impulsive, plain.impulsive)
    for name in ("normal", "shear", "eccentricity"):
        a, b = getattr(fast, name), getattr(plain, name)
        assert np.array_equal(np.isnan(a), np.isnan(b))
        scale = np.nanmax(np.abs(b))
        assert np.nanmax(np.abs(a - b)) <= 1e-12 * scale, name
    assert fast.summary() == plain.summary()


def test_at_rest_the_forces_are_indeterminate_but_in_equilibrium():
    """Below lambda (0.30 g step, lambda = 0.37 g) the closed arch is three times statically
    indeterminate: one distribution of many, so none is reported (the thrust line at rest is
    not the rigid chain's to choose: `thrust.states` picks the least-friction one). What is
    determinate holds: the springings carry the weight and the ground's inertia force."""
    motion = StepImpulse.from_g(0.30, 0.2)
    run = simulate_rigid(OPPENHEIM, motion, duration=0.3, output_interval=1e-2)
    assert run.outcome is Outcome.NO_HINGING
    f = run.joint_forces
    assert not f.unique.any() and run.to_dict()["joint_forces"]["max_friction_demand"] is None
    model = run.assembly
    n0, t0 = [], []
    for jt in (model.joints[0], model.joints[-1]):
        p = np.asarray(jt.points, float)
        tan = (p[1] - p[0]) / np.linalg.norm(p[1] - p[0])
        nrm = np.array([tan[1], -tan[0]])
        if np.dot(model.centroids[jt.right] - model.centroids[jt.left], nrm) < 0:
            nrm = -nrm
        n0.append(nrm)
        t0.append(tan)
    for k in (5, 15, 25):  # during the pulse (0.30 g towards -x) and after it
        on_arch = (f.normal[k, 0] * n0[0] + f.shear[k, 0] * t0[0]
                   - f.normal[k, -1] * n0[1] - f.shear[k, -1] * t0[1])
        a_g = float(np.mean(motion.acceleration(f.times[k] + run.time_step * (np.arange(16) + 0.5) / 16)))
        assert on_arch[1] == pytest.approx(f.weight, rel=1e-6)
        assert on_arch[0] == pytest.approx(f.weight / G * a_g, abs=1e-6 * f.weight)


def test_closure_spikes_are_not_reported_as_demand(rocking_cut_short):
    """Under Figure 4(d)'s pulse the stepper's |p_T| / p_N reaches 6 at isolated closure steps
    (impacts); the reported demand leaves out impulsive and indeterminate samples and nearly
    unloaded joints, and is what the swing needs: below 1 (0.84 measured), its 99th
    percentile 0.55."""
    run = rocking_cut_short
    f = run.joint_forces
    assert run.max_friction_demand > 2.9
    s = run.to_dict()["joint_forces"]
    assert s["impulsive_samples"] > 0
    assert 0.5 < s["max_friction_demand"] < 1.0
    assert np.nanpercentile(f.friction_demand, 99) < 0.6
    assert 0.9 < s["max_relative_eccentricity_closed"] < 1.0


def test_the_rank_certificate_never_contradicts_the_svd():
    """`rank_certificate` (a Cholesky bound) against the oracle it stands in for, the SVD of
    the same rows (`forces._rows`, `forces._independent`): over random sets of active corners
    of Oppenheim's arch, displaced at random, a certified 1 is independent by the SVD and a
    certified 0 dependent; most sets are settled (the bound is not vacuous)."""
    from archquake.rigid import _force_kernels as FK
    from archquake.rigid import _step_kernels as RK
    from archquake.rigid.forces import _independent, _rows
    from archquake.rigid.model import RigidModel

    model = RigidModel.build(OPPENHEIM)
    isq_m, isq_i = np.sqrt(1.0 / model.mass), np.sqrt(1.0 / model.inertia)
    rng = np.random.default_rng(7)
    settled = {0: 0, 1: 0}
    q0, _ = model.rest()
    for _ in range(300):
        q = q0 + rng.normal(scale=[1e-3, 1e-3, 1e-3], size=q0.shape)
        act = rng.random((len(model.ja), 2)) < rng.uniform(0.2, 0.9)
        _, nrm, tan, pts = RK.geometry(q, model.ja, model.jb, model.arm_a, model.arm_b,
                                       model.n0, model.t0)
        gaps = np.where(act, 0.0, 1.0)  # active exactly where asked
        svd = _independent(_rows(q, model.ja, model.jb, gaps, nrm, tan, pts, 0.5, isq_m, isq_i))
        cert = FK.rank_certificate(q, act, model.ja, model.jb, nrm, tan, pts, isq_m, isq_i)
        if cert >= 0:
            assert bool(cert) == svd
            settled[cert] += 1
    assert settled[1] > 150 and settled[0] > 10
