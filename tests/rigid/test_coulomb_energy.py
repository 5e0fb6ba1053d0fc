"""The rigid chain's Coulomb joints never create energy, and its energy balance closes.

Oracles: a block sliding on a rough base (the closed form of a particle on a rough plane: the
slip (a - mu g) T^2 / 2, the friction's work mu N times the slip, all the input work dissipated
once it stops); the no-sliding chain (with a coefficient above the joints' demand every step
sticks, and the history is the no-sliding one bit for bit until the no-sliding chain's own
demand first exceeds mu); the DEM's verdict on Oppenheim's arch with mu 0.5 (survives:
docs/models/rigid.md, "Coulomb joints"); and the discrete balance T + V + D - W = const, which
the Moreau-Jean step satisfies exactly (``_step_kernels`` docstring, "Energy"), so that its
residual is rounding (measured 1e-12 to 1e-11 of the scale; asked below 1e-6, far under the
5 % a run warns at).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.blocks.assembly import block_on_base
from archquake.compare.rigid import oppenheim, step_collapses
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground.pulses import RectangularPulse, SinePulse, StepImpulse
from archquake.outcome import Outcome
from archquake.rigid import RigidModel, simulate_rigid
from archquake.rigid.run import rigid_to_verdict

#: Oppenheim's arch at 1.0 g, t_p 0.2 s: the case where the Coulomb joints once created
#: megajoules and collapsed the arch.
STEP = StepImpulse.from_g(1.0, 0.2, -1)


def assert_balanced(run, residual: float = 1e-6) -> None:
    """The contacts' work is >= 0 at every sample, its two parts at the end, and the balance
    closes to ``residual`` of its scale. ">= 0" to 1e-7 of the scale: a persistent contact's
    work in one step, -p^T H (v_k + v_k+1) / 2, has H at the step's mid-point and v_k from the
    previous one (H v_k = O(h)), so it can be slightly negative (measured: -7.7e-4 J in the
    first hundredth of a second on Oppenheim's arch, 8.5e-9 of the scale)."""
    e = run.energy
    tiny = 1e-7 * max(e.scale_J, 1.0)
    assert e.residual < residual
    assert run.contact_work.min() >= -tiny
    assert run.friction_work.min() >= -tiny
    assert e.contacts_J >= -tiny and e.impacts_J >= -tiny and e.friction_J >= -tiny
    assert e.warning is None


@pytest.fixture(scope="module")
def no_sliding():
    """The no-sliding chain on :data:`STEP` at 1e-4 s (the step ``run --friction`` uses)."""
    return rigid_to_verdict(oppenheim(), STEP, time_step=1e-4)


@pytest.mark.parametrize("solver", ["direct", "pgs"])
def test_sliding_block_dissipates_mu_n_times_its_slip(solver):
    """The squat block (b 2 m, h 0.4 m: it rocks only above 5 g) on a base with mu 0.3 under
    0.5 g for 0.5 s, then at rest until 1 s. Closed form (a particle on a rough plane): it
    slides with the relative acceleration (a - mu g) to the slip (a - mu g) T^2 / 2 at 0.5 s,
    then decelerates at mu g and stops at 0.83 s; the friction's work is mu m g times the slip
    at every sample, and at rest it equals the input work m a x (the kinetic energy is back to
    0). The slip to 1e-3 (the step's error, first order in h = 1e-4 s); the work to 1e-6: the
    normal impulse is m g h to the solve's tolerance, and the step in which the block stops
    sticks, so its half step of slip, h v_k / 2 (1.2e-8 of the whole), is counted with the
    rest of the contacts' work."""
    mu, a, tp = 0.3, 0.5 * G, 0.5
    model = RigidModel.build(block_on_base(2.0, 0.4))
    run = simulate_rigid(model, RectangularPulse(a, tp), duration=1.0, time_step=1e-4,
                         friction=mu, solver=solver)
    res = run
    mass = float(model.mass[0])
    slip = -(res.positions[:, 1, 0] - res.base_displacement)
    k = int(np.searchsorted(res.times, tp))
    assert slip[k] == pytest.approx(0.5 * (a - mu * G) * tp**2, rel=1e-3)
    np.testing.assert_allclose(run.friction_work, mu * mass * G * slip,
                               rtol=1e-6, atol=1e-9 * mu * mass * G * slip[-1])
    assert res.kinetic[-1] < 1e-12 * res.kinetic.max()
    assert run.energy.friction_J == pytest.approx(run.energy.input_work_J, rel=1e-6)
    assert run.energy.impacts_J == pytest.approx(0.0, abs=1e-6 * run.energy.friction_J)
    assert_balanced(run)


@pytest.mark.parametrize("mu", [0.5, 0.6, 0.8, 2.0])
def test_oppenheim_survives_the_step_pulse_with_coulomb_joints(mu):
    """1.0 g, t_p 0.2 s: the no-sliding chain survives, so does the DEM with mu 0.5; with
    Coulomb joints of any of these coefficients the chain survives too, and the contacts
    dissipate (they once did -4.6e6 J of work at mu 0.8 and collapsed the arch)."""
    run = rigid_to_verdict(oppenheim(), STEP, friction=mu, time_step=1e-4)
    assert run.outcome is Outcome.SURVIVES
    assert_balanced(run)
    assert run.energy.contacts_J > 0.5 * run.energy.input_work_J  # it came to rest


@pytest.mark.parametrize("mu, t_slip", [(0.8, 0.4635), (2.0, 1.714)])
def test_above_the_demand_the_history_is_the_no_sliding_chains(no_sliding, mu, t_slip):
    """Every step whose no-sliding impulses lie in the cones is kept as it is (it satisfies
    Coulomb's law), so the history equals the no-sliding chain's bit for bit until the
    no-sliding chain's own friction demand (impulsive steps included: a hinge closing or
    releasing, where the normal impulse vanishes) first reaches mu: at 0.4635 s for mu 0.8 and
    1.714 s for mu 2.0 (measured). From there the joints slip where the no-sliding chain's would
    leave their cone; the verdict stays, and so do the first three half cycles' peak rotations
    (to 3 %; measured 1.8 % and 0.1 %): the later, smaller half cycles are where the slips
    show."""
    run = rigid_to_verdict(oppenheim(), STEP, friction=mu, time_step=1e-4)
    demand = no_sliding.friction_demand
    k = int(np.flatnonzero(demand >= mu)[0])
    assert no_sliding.times[k] == pytest.approx(t_slip, abs=1e-9)
    np.testing.assert_array_equal(run.positions[:k], no_sliding.positions[:k])
    assert run.outcome is no_sliding.outcome is Outcome.SURVIVES
    np.testing.assert_allclose(run.peak_rotation[:3], no_sliding.peak_rotation[:3], rtol=0.03)


def test_critical_duration_with_mu_08_is_the_no_sliding_chains():
    """The no-sliding chain's first collapsing t_p at 1.0 g lies in (0.2591, 0.2594] s at
    1e-4 s (measured; ``test_chain``'s slow check brackets it at the default step); with mu 0.8
    the chain survives 3 % below it and collapses 3 % above it (measured: the same bracket to
    0.3 ms, ``test_critical_duration_bisection_with_mu_08``)."""
    arch = oppenheim()
    assert not step_collapses("rigid", arch, 1.0, 0.97 * 0.2591, time_step=1e-4, friction=0.8)
    assert step_collapses("rigid", arch, 1.0, 1.03 * 0.2594, time_step=1e-4, friction=0.8)


@pytest.mark.slow
def test_critical_duration_bisection_with_mu_08():
    """The bisection to 0.5 ms gives the same bracket with mu 0.8 as without sliding."""
    from archquake.compare.rigid import critical_step_duration

    kw = dict(resolution=0.0005, time_step=1e-4)
    ref = critical_step_duration("rigid", oppenheim(), 1.0, 0.24, 0.28, **kw)
    got = critical_step_duration("rigid", oppenheim(), 1.0, 0.24, 0.28, friction=0.8, **kw)
    assert got == ref


def _random_cases(n: int, seed: int):
    """``n`` (arch, pulse, mu) drawn from a fixed generator: semicircular to shallow arches of
    5-15 voussoirs, t/R 0.1-0.2, step and sine pulses of 0.2-1.2 g, half with Coulomb joints
    (mu 0.3-1.0)."""
    rng = np.random.default_rng(seed)
    cases = []
    for k in range(n):
        radius = float(rng.uniform(2.0, 10.0))
        arch = Arch(radius=radius, thickness=float(rng.uniform(0.1, 0.2)) * radius,
                    embrace=math.radians(float(rng.uniform(120.0, 180.0))),
                    voussoirs=int(rng.integers(5, 16)))
        a_g, tp = float(rng.uniform(0.2, 1.2)), float(rng.uniform(0.05, 0.4))
        pulse = (StepImpulse.from_g(a_g, tp, -1) if k % 2 else SinePulse.from_g(a_g, tp, -1))
        mu = None if k % 4 < 2 else float(rng.uniform(0.3, 1.0))
        cases.append((arch, pulse, mu))
    return cases


RANDOM = _random_cases(20, 2026)


@pytest.mark.parametrize("arch, pulse, mu", RANDOM[:4])
def test_random_runs_balance_quick(arch, pulse, mu):
    """The first 4 of the 20 random runs (:func:`test_random_runs_balance`), 0.8 s each."""
    run = simulate_rigid(arch, pulse, duration=0.8, time_step=1e-4, friction=mu)
    assert_balanced(run)


@pytest.mark.slow
@pytest.mark.parametrize("arch, pulse, mu", RANDOM)
def test_random_runs_balance(arch, pulse, mu):
    """20 random runs to a verdict (:func:`_random_cases`): the contacts' work >= 0 and the
    balance closed (docs/validation.md, "Energy balance of the rigid chain")."""
    run = rigid_to_verdict(arch, pulse, friction=mu, time_step=1e-4)
    assert_balanced(run)


def test_a_chain_that_never_moves_dissipates_nothing():
    """0.01 g for 0.1 s is far below Oppenheim's arch's onset (about 0.3 g): no joint opens, the
    chain moves with the ground, and the contacts' work, the input work and the residual are 0
    (to the contact solve's tolerance, 1e-9 of m g L)."""
    model = RigidModel.build(oppenheim())
    run = simulate_rigid(model, RectangularPulse(0.01 * G, 0.1), duration=0.3, time_step=1e-4,
                         friction=0.8)
    e = run.energy
    mgl = float(model.mass.sum()) * G * 10.0
    assert abs(e.contacts_J) < 1e-9 * mgl and abs(e.input_work_J) < 1e-9 * mgl
    assert run.to_dict(joint_forces=False)["dissipated_contacts_J"] == e.contacts_J


def test_the_balance_warns_and_names_the_term_that_is_off():
    """Synthetic books (oracle: arithmetic). A balanced run has no warning; 10 % of the input
    work missing from the contacts' work from t = 0.5 s on is a residual of 0.1 of the scale,
    and the warning names that term and that time; contacts that did 5 % of the scale's work
    (a kinetic energy with no input) are named as such; a run with no motion at all has scale 0
    and residual 0."""
    from archquake.rigid.run import energy_balance

    t = np.linspace(0.0, 1.0, 11)
    w = 100.0 * t  # input work, J
    kin = 50.0 * np.sin(math.pi * t)
    pot = np.zeros_like(t)
    d = w - kin
    zero = np.zeros_like(t)
    assert energy_balance(t, kin, pot, d, zero, w).warning is None
    broken = np.where(t >= 0.5, d - 10.0, d)
    e = energy_balance(t, kin, pot, broken, zero, w)
    assert e.residual == pytest.approx(0.1) and e.scale_J == pytest.approx(100.0)
    assert "the work done on the contacts" in e.warning and "t = 0.5 s" in e.warning
    gain = energy_balance(t, 5.0 * t, pot, -5.0 * t, zero, zero, ground_kinetic=100.0)
    assert gain.residual == 0.0 and "positive work" in gain.warning
    still = energy_balance(t, zero, zero, zero, zero, zero)
    assert still.scale_J == 0.0 and still.residual == 0.0 and still.warning is None


def test_the_json_reports_the_contacts_work_not_damping():
    """``to_dict`` of a rigid run: the contacts' work and its two parts, the balance's scale
    and residual; no ``dissipated_damping_J`` (the chain has no damping). ``to_table`` (the
    ``--history`` CSV): the contacts' work and its friction part in place of the DEM's
    strain, damping and friction columns."""
    run = simulate_rigid(block_on_base(2.0, 0.4), RectangularPulse(0.5 * G, 0.2), duration=0.3,
                         time_step=1e-4, friction=0.3)
    out = run.to_dict(joint_forces=False)
    assert "dissipated_damping_J" not in out
    e = run.energy
    assert out["dissipated_contacts_J"] == e.contacts_J > 0.0
    assert out["dissipated_friction_J"] == e.friction_J > 0.0
    assert out["dissipated_impacts_J"] == e.impacts_J
    assert out["energy_error"] == e.residual and out["energy_scale_J"] == e.scale_J > 0.0
    assert out["input_work_J"] == e.input_work_J and out["energy_warning"] is None
    table = run.to_table()  # what --history writes
    assert not {"damping_J", "strain_J", "friction_J"} & set(table)
    np.testing.assert_array_equal(table["dissipated_contacts_J"], run.contact_work)
    np.testing.assert_array_equal(table["dissipated_friction_J"], run.friction_work)
