"""The rigid chain with Coulomb joints (``friction=mu``): the default solver keeps the exact
no-slip solution of a step when every joint's tangential impulse lies in its cone (it then
satisfies Coulomb's law: every joint sticks), and runs Gauss-Seidel with the Coulomb clamp only
where a joint slips; ``solver="pgs"`` runs the clamped Gauss-Seidel at every step.

Oracles: a block on a base, one step from a sliding velocity (the closed form of a particle on
a rough plane: the tangential velocity drops by mu g h, or to zero); the same block under a
constant ground acceleration just below and just above mu g (sticks; slides with the relative
acceleration a - mu g); Housner's free rocking with a coefficient no joint reaches (the no-slip
chain's motion, bit for bit); the clamped Gauss-Seidel stepper on the 15-voussoir bridge under
pulses whose joints reach the cone (the outcome, the impacts and the collapse time).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import archquake.rigid._step_kernels as RK
from archquake import Arch
from archquake.blocks.assembly import block_on_base
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground.pulses import RectangularPulse, SinePulse, StepImpulse
from archquake.ground.records import Record
from archquake.rigid import RigidModel, simulate_rigid
from archquake.rigid.model import GAP_TOLERANCE

REST = Record(np.array([0.0, 0.0]), 1.0)
BRIDGE = Arch(radius=5.0, thickness=0.6, embrace=math.pi, voussoirs=15, density=1800)


@pytest.mark.parametrize("method", [RK.METHOD_DIRECT, RK.METHOD_PGS])
@pytest.mark.parametrize("ratio", [0.5, 0.999, 1.001, 3.0])
def test_one_step_of_a_sliding_block_is_a_particle_on_a_rough_plane(method, ratio):
    """A squat block (b 2 m, h 0.4 m) resting on the base, one contact step from the free
    velocity (v_x, -g h, 0) with |v_x| = ratio mu g h (mu 0.3, h 1e-3 s). Closed form (a
    particle on a rough plane, the normal impulse m g h): it sticks (v_x' = 0) when ratio <= 1,
    and slides with v_x' = v_x - mu g h sign(v_x) otherwise; v_y' = 0, no spin. Tolerance 1e-9
    of mu g h: the solve is asked for 1e-15 m/s. ``ratio`` 0.999 and 1.001 sit either side of
    the cone, where the direct solver's stick test must decide."""
    mu, h = 0.3, 1e-3
    m = RigidModel.build(block_on_base(2.0, 0.4))
    q, _ = m.rest()
    geo = m.geometry(q)
    scale = mu * G * h
    cfg = RK.solving(GAP_TOLERANCE * m.assembly.reference_length, 1e-15, 100_000, mu)
    for sign in (1.0, -1.0):
        vx = sign * ratio * scale
        vf = np.array([[vx, -G * h, 0.0]])
        args = (m.chain, cfg, q, geo, vf, np.zeros((1, 3)), np.empty(0), np.empty(0))
        if method == RK.METHOD_DIRECT:  # called as the event integrator calls it
            vn, imp, _, _ = RK.project_direct(*args)
        else:
            vn, imp, _, _ = RK.project(*args)
        expected = 0.0 if ratio <= 1.0 else vx - sign * scale
        assert vn[0, 0] == pytest.approx(expected, abs=1e-9 * scale)
        assert abs(vn[0, 1]) < 1e-9 * scale and abs(vn[0, 2]) < 1e-9 * scale
        pn = imp[0, 0] + imp[0, 1]
        assert pn == pytest.approx(m.mass[0] * G * h, rel=1e-9)
        assert abs(imp[0, 2]) <= mu * pn * (1.0 + 1e-12)


@pytest.mark.parametrize("solver", ["direct", "pgs"])
@pytest.mark.parametrize("a_ratio", [0.97, 1.03])
def test_block_under_a_ground_acceleration_near_mu_g(solver, a_ratio):
    """The squat block (rocking only above 5 g) on a base with mu = 0.3 under a constant ground
    acceleration a = 0.97 mu g or 1.03 mu g for 0.5 s, the threshold of the closed form (a
    particle on a rough plane): below it the block sticks (relative slip < 1e-9 m), above it
    slides with the relative acceleration a - mu g, displacement (a - mu g) T^2 / 2 to 1e-3
    (11 mm here; the step's error, first order in h = 1e-4 s, is 2e-4 of it)."""
    mu, t_end = 0.3, 0.5
    a = a_ratio * mu * G
    run = simulate_rigid(block_on_base(2.0, 0.4), RectangularPulse(a, t_end), duration=t_end,
                         time_step=1e-4, friction=mu, solver=solver)
    res = run
    rel = res.positions[-1, 1, 0] - res.base_displacement[-1]
    if a_ratio < 1.0:
        assert abs(rel) < 1e-9
    else:
        assert -rel == pytest.approx(0.5 * (a - mu * G) * t_end**2, rel=1e-3)
    assert abs(res.positions[-1, 1, 2]) < 1e-9  # no rocking
    assert run.max_friction_demand <= mu * (1.0 + 1e-9)  # Coulomb's cone


def test_rocking_with_a_large_coefficient_is_the_no_slip_chain(released_block):
    """Housner's free rocking (b 0.4 m, h 2 m, released at half its slenderness) needs a
    friction demand below 0.25 (measured); with mu = 1 no joint reaches its cone, every step's
    no-slip solution sticks and is kept: the same motion as the no-slip chain, bit for bit, and
    so Housner's time of the first impact to 1e-4 (the no-slip chain's own test). The clamped
    Gauss-Seidel (``solver="pgs"``) reaches the same motion to its tolerance (1e-9 rad)."""
    model, initial, ref = released_block()
    runs = {key: simulate_rigid(model, REST, duration=ref["t2"] + 0.1, time_step=1e-4,
                                output_interval=1e-4, initial=initial, friction=mu, solver=solver)
            for key, mu, solver in (("none", None, "direct"), ("direct", 1.0, "direct"),
                                    ("pgs", 1.0, "pgs"))}
    np.testing.assert_array_equal(runs["direct"].positions,
                                  runs["none"].positions)
    assert runs["none"].max_friction_demand < 0.25
    th = runs["direct"].positions[:, 1, 2]
    t = runs["direct"].times
    k = int(np.flatnonzero(th >= 0)[0])
    t1 = t[k - 1] + (t[k] - t[k - 1]) * (-th[k - 1]) / (th[k] - th[k - 1])
    assert t1 == pytest.approx(ref["t1"], rel=1e-4)
    assert np.max(np.abs(runs["pgs"].positions[:, 1, 2] - th)) < 1e-9


def _outcome(run):
    res = run
    return (res.outcome, len(res.impact_times), res.collapse_time, res.first_impact_time)


@pytest.mark.parametrize("motion", [
    StepImpulse.from_g(0.15, 0.1259, -1),
    pytest.param(StepImpulse.from_g(0.15, 0.1585, -1), marks=pytest.mark.slow)],
    ids=["step 0.126 s (survives)", "step 0.159 s (collapses)"])
def test_bridge_verdicts_are_the_clamped_gauss_seidels(motion):
    """The bridge (R 5 m, t 0.6 m, 15 voussoirs) with mu = 0.6 at the verdict's step under two
    of the step pulses the assessment runs at 0.15 g, where joints reach the cone (friction
    demand 0.6): the default solver against the clamped Gauss-Seidel at every step (an
    independent solver of the same Coulomb step): the same outcome and number of impacts, the
    first impact and the collapse within 1e-6 s (measured: 5e-10 s; Gauss-Seidel stops at its
    tolerance or its 5000 sweeps, the direct solve is exact to the same tolerance), and no
    joint outside its cone."""
    from archquake.rigid.run import rigid_to_verdict
    from archquake.rigid.verdict import verdict_time_step

    h = verdict_time_step(BRIDGE)
    new = rigid_to_verdict(BRIDGE, motion, friction=0.6, time_step=h)
    old = rigid_to_verdict(BRIDGE, motion, friction=0.6, time_step=h, solver="pgs")
    (o_new, n_new, c_new, f_new), (o_old, n_old, c_old, f_old) = _outcome(new), _outcome(old)
    assert o_new == o_old and n_new == n_old
    for a, b in ((c_new, c_old), (f_new, f_old)):
        assert (a is None) == (b is None)
        if a is not None and math.isfinite(a):
            assert a == pytest.approx(b, abs=1e-6)
    assert new.max_friction_demand <= 0.6 * (1.0 + 1e-9)
    assert new.max_friction_demand > 0.6 * (1.0 - 1e-6)  # a joint did reach its cone
    assert old.max_sweeps > new.max_sweeps  # Gauss-Seidel did the work on the old path


@pytest.mark.slow
def test_bridge_pulse_verdicts_of_the_assessment_are_the_clamped_gauss_seidels():
    """The sliding check of ``archquake assess examples/bridge.toml`` in full mode: the bridge
    with mu = 0.6 under the 14 step and 14 sine pulses of 0.15 g (t_p, T from 0.1 to 2 s), at
    the verdict's step. Oracle: the clamped Gauss-Seidel at every step (``solver="pgs"``). The
    outcome of every case must agree (measured: 28 of 28, and the same at 1e-4 s). The impacts
    are not compared: Gauss-Seidel stops at its 5000 sweeps on the sine pulses' steps (with
    residuals up to 4e-7 m/s), and it counted 2 impacts where the default solver and
    Gauss-Seidel run to its tolerance both count 1 (T = 0.159 s), 2 where they count 3
    (T = 0.316 s); the first impacts of those agree to 1e-8 s."""
    from archquake.rigid.run import rigid_to_verdict
    from archquake.rigid.verdict import verdict_time_step

    h = verdict_time_step(BRIDGE)
    for make in (StepImpulse.from_g, SinePulse.from_g):
        for d in np.geomspace(0.1, 2.0, 14):
            motion = make(0.15, float(d), -1)
            new = rigid_to_verdict(BRIDGE, motion, friction=0.6, time_step=h)
            old = rigid_to_verdict(BRIDGE, motion, friction=0.6, time_step=h, solver="pgs")
            assert new.outcome == old.outcome, (make, d)
