"""A motion that never reaches the onset of hinging ends at once, ``no_hinging``: the exact onset
test (:func:`archquake.rigid.events.stays_at_rest`) and the run it gives.

Oracles: the onset multipliers found by bisection (:attr:`EventModel.onset_g`, to 1e-12 of
themselves), on either side of which the test must flip; the time stepper itself, which on the
same motion finds no hinge (its rotation stays at round-off); and the statics of the locked
arch, whose joint forces are indeterminate (none reported).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.geometry import Arch
from archquake.ground import Record, SinePulse, StepImpulse
from archquake.outcome import Outcome
from archquake.rigid import simulate_rigid
from archquake.rigid.events import EventModel, stays_at_rest
from archquake.rigid.verdict import rigid_model

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def test_the_onset_test_flips_at_the_bisected_onset():
    """Just below lambda_+ (towards -x, the paper's first mechanism) the chain stays, just above
    it moves; the same towards +x with lambda_-; a sine reaches its magnitude both ways."""
    model = rigid_model(OPPENHEIM)
    plus, minus = EventModel.of(model).onset_g
    g = 9.80665
    assert stays_at_rest(model, StepImpulse.from_g(plus * (1 - 1e-6), 0.2, direction=1), g=g)
    assert not stays_at_rest(model, StepImpulse.from_g(plus * (1 + 1e-6), 0.2, direction=1), g=g)
    assert stays_at_rest(model, SinePulse.from_g(min(plus, minus) * (1 - 1e-6), 0.3), g=g)
    assert not stays_at_rest(model, SinePulse.from_g(min(plus, minus) * (1 + 1e-6), 0.3), g=g)


@pytest.mark.parametrize("motion", [
    StepImpulse.from_g(0.0, 0.2), StepImpulse.from_g(1e-308, 0.2),
    Record(np.sin(np.linspace(0.0, 20.0, 2001)) * 0.3 * 9.80665, 0.01).scaled(1e-320),
], ids=["zero", "1e-308 g", "record x 1e-320"])
def test_a_motion_below_the_onset_takes_no_step(motion):
    run = simulate_rigid(OPPENHEIM, motion, duration=5.0)
    assert run.at_rest and run.n_steps == 0
    assert run.outcome is Outcome.NO_HINGING
    assert np.all(run.kinetic == 0.0) and np.all(run.damping == 0.0)
    assert run.to_dict()["rigid"]["below_onset"] is True


@pytest.mark.parametrize("arch", [
    Arch(10.0, 10.0, math.radians(157.5), 7),  # thickness = radius: onset 2.9 g
    Arch(10.0, 0.01, math.radians(10.0), 7),  # a flat sliver: onset 9.9 g
], ids=["thick", "flat"])
def test_stout_arches_under_1g_end_at_once(arch):
    """The arches whose runs took 15-45 s (a locked history at a step scaled with a 1 cm
    voussoir, and the joint forces of every sample) now take none."""
    from archquake.rigid.run import rigid_to_verdict

    run = rigid_to_verdict(arch, StepImpulse.from_g(1.0, 0.2))
    assert run.at_rest and run.outcome is Outcome.NO_HINGING
    forces = run.joint_forces
    assert not forces.unique.any()  # the locked arch is statically indeterminate
    assert forces.summary()["max_friction_demand"] is None


def test_the_stepper_agrees_below_the_onset(monkeypatch):
    """The oracle: the time stepper, made to step (the test switched off), finds no hinge on a
    motion the test says stays below the onset; its rotation is round-off."""
    import archquake.rigid.run as R

    plus, _ = EventModel.of(rigid_model(OPPENHEIM)).onset_g
    motion = StepImpulse.from_g(0.9 * plus, 0.2, direction=1)
    assert stays_at_rest(rigid_model(OPPENHEIM), motion)
    monkeypatch.setattr(R, "stays_at_rest", lambda *a, **k: False)
    stepped = simulate_rigid(OPPENHEIM, motion, duration=0.8)
    assert stepped.outcome is Outcome.NO_HINGING and stepped.n_steps > 0
    assert float(np.abs(stepped.rotation).max()) < 1e-9


def test_friction_keeps_stepping():
    """Coulomb joints may slip below the onset of hinging: the test does not apply."""
    run = simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.0, 0.1), duration=0.05, friction=0.8)
    assert not run.at_rest and run.n_steps > 0


def test_a_chain_that_moves_under_its_own_weight_has_onset_zero_at_once(monkeypatch):
    """The bisection's bound is relative: for a chain that moves under every load (a semicircle
    of 100 voussoirs at t/R = 0.108, at its least thickness through the projection's
    tolerances) it halved towards 0 about 1,100 times, a projection of the whole chain each
    (the verdict of `run --voussoirs 100` spent over 14 min there). Now one projection at 0
    says so. Oracle: the count of projections, each mocked to "moves"."""
    em = EventModel.build(rigid_model(Arch(10.0, 1.5, math.radians(157.5), 5)))
    calls = []
    monkeypatch.setattr(EventModel, "_moves", lambda self, ax: calls.append(ax) or True)
    assert em._bisect(1.0) == 0.0 and em._bisect(-1.0) == 0.0
    assert len(calls) <= 2


def test_a_stout_chain_has_a_finite_onset_above_20g(monkeypatch):
    """Above the first bracket (20 g) the bracket doubles: an onset of 50 g is found, not inf
    (which would let the verdict skip every step of a 40 g motion). Oracle: a mocked chain that
    moves from 50 g on."""
    em = EventModel.build(rigid_model(Arch(10.0, 1.5, math.radians(157.5), 5)))
    monkeypatch.setattr(EventModel, "_moves", lambda self, ax: abs(ax) >= 50.0)
    assert em._bisect(1.0) == pytest.approx(50.0, rel=1e-11)


def test_the_onset_projections_are_exact_next_to_the_onset():
    """Each projection of the onset bisection starts from the impulses under the arch's own
    weight: next to the onset, where from no impulses the active sets cycled and Gauss-Seidel
    finished in tens of thousands of sweeps, a few sets give the exact projection (the count
    stays within the active-set limit: no Gauss-Seidel sweep). Oracle: the solver's own count,
    and the onset, which the limit analysis of the loaded bridge gives to its tolerances."""
    import archquake.rigid._event_kernels as EK
    import archquake.rigid._step_kernels as RK
    from archquake.blocks.assembly import VOUSSOIRS, dem_assembly
    from archquake.geometry.loads import Fill, Loads
    from archquake.limit.loaded import loaded_collapse, seismic_case

    bridge = Arch(5.0, 0.6, math.pi, 15, density=1800.0)
    loads = Loads(fill=Fill(depth=1.0, density=1800.0))
    events = EventModel.of(rigid_model(dem_assembly(bridge, VOUSSOIRS, loads=loads)))
    r = events.rigid
    q, _ = r.rest()
    cfg = RK.solving(1e-9 * events.lref, 1e-13 * math.sqrt(events.lref), EK.SOLVE_SWEEPS)
    plus, minus = events.onset_g
    lam = loaded_collapse(seismic_case(bridge, loads)).multiplier
    assert plus == pytest.approx(lam, rel=1e-6) and minus == pytest.approx(lam, rel=1e-6)
    for ax in (plus, -minus):
        for factor in (1 - 1e-9, 1 - 1e-12, 1 + 1e-12, 1 + 1e-9):
            a = np.zeros((r.n_bodies, 3))
            a[:, 0] = -ax * factor
            a[:, 1] = -1.0
            count = RK.project_direct(r.chain, cfg, q, r.geometry(q), a, events._resting_impulses,
                                      np.empty(0), np.empty(0))[2]
            assert count <= RK.ACTIVE_SET_ITERATIONS, (ax, factor, count)
