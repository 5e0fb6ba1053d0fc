"""The rigid-block chain integrated from event to event (issue 16, ``solver="events"``).

Oracles: Housner's rocking block (exact quadrature of the times, r = 1 - 1.5 sin^2 alpha at
the impact, the onset at b / h); the limit analysis (the onset threshold is the upper-bound
collapse multiplier, and the same towards both sides); the time stepper of the same model
(the event times and the verdicts); energy conservation in free motion between closures (to
1e-8) and the energy balance; mirror symmetry and dynamic similarity of the event sequence.
"""

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis
from archquake.rigid import RigidModel, simulate_rigid
from archquake.rigid import _event_kernels as EK
from archquake.rigid.events import FALLBACK_WINDOW, EventModel, run_events

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.fixture(scope="module")
def opp():
    return EventModel.of(RigidModel.build(OPPENHEIM))


def _events(out, kinds=(EK.N_CLOSURES,)):
    log = out["log"]
    return log[log[:, 1] == 1] if kinds == (EK.N_CLOSURES,) else log


def test_onset_is_the_limit_analysis_multiplier(opp):
    """Upper-bound theorem: the locked rigid chain starts to move exactly when the ground
    acceleration exceeds the least collapse multiplier of the limit analysis; mirror: the same
    towards -x."""
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    plus, minus = opp.onset_g
    assert plus == pytest.approx(lam, rel=1e-3)
    assert minus == pytest.approx(plus, rel=1e-9)


def test_event_times_are_the_time_steppers(opp):
    """Same model, two integrations: the joint 3 opening when the pulse turns (t_p) and the
    first closure (joint 2) at the time the Moreau-Jean stepper (h = 1e-4 s) closes it."""
    motion = StepImpulse.from_g(1.0, 0.20)
    out = run_events(opp, motion, duration=0.5, output_interval=5e-4)
    log = out["log"]
    opening = log[log[:, 1] == 2][0]
    assert opening[2] == 3 and opening[0] == pytest.approx(0.20, abs=1e-9)
    closure = log[log[:, 1] == 1][0]
    assert closure[2] == 2
    run = simulate_rigid(RigidModel.build(OPPENHEIM), motion, duration=0.5, output_interval=1e-4)
    op = run.joint_opening[:, 2]  # (nt, 2) corners
    t = run.times
    # the corner open at 0.3 s closes (the other one, the pivot, opens a step later: a sample
    # with both shut need not exist)
    corner = int(np.argmax(op[np.searchsorted(t, 0.3)]))
    closed = t[(t > 0.3) & (op[:, corner] < 1e-6)][0]
    assert closure[0] == pytest.approx(closed, abs=2e-4)


def test_energy_between_closures_is_conserved(opp):
    """Free rocking after a pulse: between two closures (openings of joints included) the
    kinetic plus potential energy is constant to 1e-8 of the energy the free motion started
    with (at the end of the pulse; measured 1e-9 to 2e-9 on this run)."""
    motion = StepImpulse.from_g(0.45, 0.15)
    out = run_events(opp, motion, duration=2.5, output_interval=5e-4)
    log, t, e = out["log"], out["times"], out["e"]
    energy = e[:, 0] + e[:, 1]
    scale = energy[np.searchsorted(t, 3 * 0.15)]
    lossy = np.sort(np.r_[log[np.isin(log[:, 1], (1, 5, 6)), 0], out["windows_s"]])
    window = FALLBACK_WINDOW * math.sqrt(OPPENHEIM.thickness / G) + 2e-3
    checked = 0
    for a, b in zip(lossy[:-1], lossy[1:]):
        if a < 3 * 0.15:
            continue
        sel = (t > a + 1e-9) & (t < b - 1e-9)
        for w in out["windows_s"]:
            sel &= ~((t >= w - 1e-9) & (t <= w + window))
        if sel.sum() < 3:
            continue
        checked += 1
        seg = energy[sel]
        assert (seg.max() - seg.min()) <= 1e-8 * scale
    assert checked > 20


def test_energy_balance_and_verdict_agree_with_the_stepper(opp):
    """Kinetic + potential + dissipated = work of the inertial load (measured: to 6e-8 of it,
    through 187 closures with no hand-over to the stepper; the closure's projection after
    every step and the snap of a closing hinge to zero are not counted), and the collapse
    (t_p = 0.27 s at 1.0 g, above the threshold 0.2586-0.2606 s) at the stepper's time within
    10 ms."""
    motion = StepImpulse.from_g(1.0, 0.27)
    model = RigidModel.build(OPPENHEIM)
    ev = simulate_rigid(model, motion, duration=4.5, solver="events")
    assert ev.events["windows_s"] == []
    e = ev.events["e"]
    assert np.abs(e[:, 0] + e[:, 1] + e[:, 2] - e[:, 3]).max() <= 2e-7 * e[:, 3].max()
    st = simulate_rigid(model, motion, duration=4.5)
    assert ev.outcome.value == st.outcome.value == "collapse"
    assert ev.collapse_time == pytest.approx(st.collapse_time, abs=0.01)
    forces = ev.to_dict()["joint_forces"]
    assert forces is not None and forces["max_friction_demand"] is not None
    summary = ev.to_dict()["rigid"]
    assert summary["solver"] == "events" and summary["time_step_s"] is None
    assert summary["events"]["closures"] == int(ev.events["counters"][EK.N_CLOSURES]) > 100


def _joint_times(out, n_events):
    log = out["log"]
    log = log[np.isin(log[:, 1], (1, 2))][:n_events]
    return log[:, 0], log[:, 2].astype(int)


def test_mirror_symmetry(opp):
    """The mirrored pulse moves the mirrored arch: joint j <-> n - j, same times (1e-9 s), over
    the first twelve openings and closures."""
    motion = StepImpulse.from_g(1.0, 0.20)
    a = run_events(opp, motion, duration=0.7, output_interval=5e-4)
    b = run_events(opp, motion.mirrored(), duration=0.7, output_interval=5e-4)
    ta, ja = _joint_times(a, 12)
    tb, jb = _joint_times(b, 12)
    assert len(ta) == 12
    np.testing.assert_allclose(tb, ta, atol=1e-9)
    np.testing.assert_array_equal(jb, 7 - ja)


def test_dynamic_similarity():
    """An arch four times larger under the same acceleration with t_p twice as long: the same
    joints open and close at twice the times (1e-7 relative)."""
    small = EventModel.of(RigidModel.build(OPPENHEIM))
    big = EventModel.of(RigidModel.build(Arch(40.0, 6.0, math.radians(157.5), 7)))
    a = run_events(small, StepImpulse.from_g(1.0, 0.20), duration=0.7, output_interval=5e-4)
    b = run_events(big, StepImpulse.from_g(1.0, 0.40), duration=1.4, output_interval=1e-3)
    ta, ja = _joint_times(a, 10)
    tb, jb = _joint_times(b, 10)
    np.testing.assert_array_equal(jb, ja)
    np.testing.assert_allclose(tb, 2 * ta, rtol=1e-7)


def test_rocking_block_reproduces_housner(released_block):
    """A free-standing block (b 0.4 m, h 2 m, an open chain of one block) released from rest at
    half its slenderness: the first two impacts at the times of the exact quadrature of its
    equation of motion (1e-8 relative), the energy the first impact removes Housner's
    (1 - r^2) with r = 1 - 1.5 sin^2 alpha (1e-8), the energy conserved between them (1e-9),
    and its onset under a ground acceleration at b / h g."""
    from archquake.ground.records import Record

    b, height = 0.4, 2.0
    model, initial, ref = released_block(b, height)
    em = EventModel.build(model)
    # measured 1.7e-8: the bisection stops where the projected rotation acceleration falls
    # below the test of motion (1e-9 g / L)
    assert em.onset_g[0] == pytest.approx(b / height, rel=1e-7)
    assert em.onset_g[1] == pytest.approx(b / height, rel=1e-7)
    t1, t2, r, e0 = ref["t1"], ref["t2"], ref["r"], ref["e0"]
    out = run_events(em, Record(np.array([0.0, 0.0]), 1.0), duration=t2 + 0.05,
                     output_interval=1e-3, initial=initial)
    closures = out["log"][out["log"][:, 1] == 1]
    assert closures[0, 0] == pytest.approx(t1, rel=1e-8)
    assert closures[1, 0] == pytest.approx(t2, rel=1e-8)
    t, e = out["times"], out["e"]
    between = (t > t1 + 1e-3) & (t < t2 - 1e-3)
    assert e[between, 2] == pytest.approx((1 - r * r) * e0, rel=1e-8)
    energy = e[between, 0] + e[between, 1]
    assert np.ptp(energy) <= 1e-9 * e0


def test_not_a_chain_is_refused():
    """The integrator needs one chain of blocks from a base; the error says what to use."""
    from archquake.blocks.assembly import Assembly
    from archquake.errors import InvalidParameterError

    asm = RigidModel.build(OPPENHEIM).assembly
    joints = asm.joints[1:] + asm.joints[:1]  # the springing's joint moved to the end
    with pytest.raises(InvalidParameterError, match="solver='direct'"):
        EventModel.build(RigidModel.build(Assembly(**{**asm.__dict__, "joints": joints})))


class _Counted(EventModel):
    """An EventModel that counts its Gauss projections."""

    def _moves(self, ax_g: float) -> bool:
        self.__dict__["calls"] = self.__dict__.get("calls", 0) + 1
        return super()._moves(ax_g)


@pytest.mark.parametrize("hint_factor", [1.0, 2.0])
def test_the_seeded_onset_is_the_plain_bisection_to_the_bit(opp, hint_factor):
    """`onset_near` replays `onset_g`'s bisection, projecting only inside a checked bracket:
    oracle, the plain bisection's numbers, exactly equal. Seeded with the limit analysis's
    multiplier it needs at most half the projections; a wrong seed (twice the multiplier) fails
    its bracket's check and lambda_+ falls back to the plain bisection, with the same numbers
    (and more projections than the right seed)."""
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    plain = _Counted.build(opp.rigid)
    seeded = _Counted.build(opp.rigid)
    assert seeded.onset_near(hint_factor * lam) == plain.onset_g
    assert seeded.onset_g == plain.onset_g  # the cached property holds the same
    if hint_factor == 1.0:
        assert seeded.calls <= plain.calls // 2
    else:
        assert seeded.calls > plain.calls // 2 + 2
