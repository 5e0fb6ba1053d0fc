"""The rigid-block chain (issue 16): rigid voussoirs, unilateral plastic no-slip joints,
Moreau-Jean time stepping.

Oracles: Housner's closed forms for a rocking block (exact quadrature of the rigid block's
equation of motion for the times, r = 1 - 1.5 sin^2 alpha at the impact); the chain law's cone
projection (an independent SLSQP on joint rotations) for a simultaneous closure; the four-link
kernel (`simulate`, Eq. 2) on the arch cut at its hinges and on the voussoir arch while its
four-hinge mechanism is admissible; the upper-bound theorem (onset just above lambda);
energy conservation in free motion; mirror symmetry; self-convergence in the time step.
"""

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.blocks.assembly import block_on_base, build_arch_assembly
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import StepImpulse
from archquake.ground.records import Record
from archquake.limit import hinges_of
from archquake.mechanism.impact_chain import cone_projection, mechanism_field
from archquake.mechanism.prepared import PreparedMechanism
from archquake.rigid import RigidModel, simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
REST = Record(np.array([0.0, 0.0]), 1.0)


def _label(hinges):
    return " ".join(f"{j}{f[0]}" for j, f in hinges)


# ----------------------------------------------------------------------------- rocking block
def _rocking_block(h: float, released_block):
    """The block released from rest at half its slenderness, run through two impacts."""
    model, initial, ref = released_block()
    run = simulate_rigid(model, REST, duration=ref["t2"] + 0.1, time_step=h, output_interval=h,
                         initial=initial)
    return run, ref


@pytest.fixture(scope="module")
def block_run(released_block):
    return _rocking_block(2.5e-5, released_block)


def test_rocking_block_reproduces_housner(block_run):
    """Free rocking of a rigid block (b 0.4 m, h 2 m, released at alpha/2): the time to the first
    impact and between the first two (exact quadrature, 1e-4 relative), the angular velocity
    ratio across the impact (Housner's r = 1 - 1.5 sin^2 alpha, 1e-3: one step of gravity on
    either side), and the peak on the other side (from r, 1e-3)."""
    run, ref = block_run
    res = run
    th, t, w = res.positions[:, 1, 2], res.times, res.velocities[:, 1, 2]
    k = int(np.flatnonzero(th >= 0)[0])
    ti = t[k - 1] + (t[k] - t[k - 1]) * (-th[k - 1]) / (th[k] - th[k - 1])
    after = th[k:]
    back = int(np.flatnonzero(after <= 0)[0])
    k2 = k + back
    ti2 = t[k2 - 1] + (t[k2] - t[k2 - 1]) * th[k2 - 1] / (th[k2 - 1] - th[k2])
    assert ti == pytest.approx(ref["t1"], rel=1e-4)
    assert ti2 == pytest.approx(ref["t2"], rel=1e-4)
    assert w[k + 1] / w[k - 2] == pytest.approx(ref["r"], rel=1e-3)
    assert float(after[:back].max()) == pytest.approx(ref["th1"], rel=1e-3)


def test_rocking_block_energy_conserved_before_the_impact(block_run):
    """Free rocking about one corner: kinetic + potential constant to 1e-5 of the released
    energy (measured 1.6e-7 at h = 2.5e-5 s, 1.2e-6 at 1e-4 s), and the corner does not sink
    by more than 1e-5 of the block width."""
    run, ref = block_run
    res = run
    th = res.positions[:, 1, 2]
    k = int(np.flatnonzero(th >= 0)[0])
    e = res.kinetic + res.potential
    assert np.max(np.abs(e[: k - 1] - e[0])) < 1e-5 * ref["e0"]
    assert run.max_penetration_m < 1e-5 * 0.4


# ----------------------------------------------------------------------------- impact = chain law
def test_simultaneous_closure_is_the_cone_projection():
    """At phi = 0, every joint closed, one contact projection of the closing mechanism's velocity
    (-u_P) is the chain law's exact response (`impact_chain.cone_projection`): the kinetic
    energy of the difference below 1e-12 of the response's (measured 4e-19)."""
    m = RigidModel.build(OPPENHEIM)
    mech = hinges_of(OPPENHEIM)
    vel, spin = mechanism_field(mech.points, mech.rates, mech.joints, OPPENHEIM)
    q, _ = m.rest()
    v_post, _ = m.project(q, np.column_stack([-vel, -spin]))
    cv, cs, _ = cone_projection(OPPENHEIM, -vel, -spin)
    ref = np.column_stack([cv, cs])
    assert m.kinetic_energy(v_post - ref) < 1e-12 * m.kinetic_energy(ref)


# ----------------------------------------------------------------------------- four-link kernel
def _blocks_field(model, arch, mech, rate):
    """The mechanism's velocity field per block of ``model`` (blocks of whole voussoirs):
    momentum-weighted, exact for a rigid link."""
    vel, spin = mechanism_field(mech.points, mech.rates, mech.joints, arch)
    asm = model.assembly
    cuts = asm.meta.get("cut_joints", list(range(arch.voussoirs + 1)))
    vm = arch.voussoir_masses
    out = np.zeros((model.n_bodies, 3))
    for k, (j0, j1) in enumerate(zip(cuts, cuts[1:])):
        sl = slice(j0, j1)
        out[k, :2] = (vm[sl, None] * vel[sl]).sum(0) / vm[sl].sum()
        out[k, 2] = spin[j0]
    return rate * out


def test_three_block_arch_rocks_as_the_four_link_mechanism():
    """The arch cut at its hinges (0, 3, 5, 7) is the four-link mechanism: started at phi = 0
    with phi' = 0.08 rad/s and no ground motion, its peak rotation and first impact time equal
    `simulate(..., initial_rate=0.08)` (Eq. 2, DOP853), 1e-3; kinetic + potential conserved to
    1e-4 of the initial energy before the impact."""
    mech = hinges_of(OPPENHEIM)
    asm = build_arch_assembly(OPPENHEIM, cut_joints=mech.joints)
    m = RigidModel.build(asm)
    rate = 0.08
    q, _ = m.rest()
    v = _blocks_field(m, OPPENHEIM, mech, rate)
    ref = simulate(PreparedMechanism.build(OPPENHEIM), REST, initial_rate=rate, t_end=4.0)
    t_imp = float(ref.impact_times[0])
    run = simulate_rigid(asm, REST, duration=t_imp + 0.05, time_step=5e-5, initial=(q, v))
    res = run
    assert float(res.impact_times[0]) == pytest.approx(t_imp, rel=1e-3)
    assert float(res.peak_rotation[0]) == pytest.approx(float(ref.peak_rotation[0]), rel=1e-3)
    e = res.kinetic + res.potential
    before = res.times < t_imp - 0.01
    assert np.max(np.abs(e[before] - e[0])) < 1e-4 * e[0]


def simulate(*args, **kwargs):
    from archquake.mechanism import SolverOptions
    from archquake.mechanism import simulate as sim

    return sim(*args, options=SolverOptions(output_interval=0.0), **kwargs)


def test_voussoir_arch_follows_the_four_link_mechanism_while_it_is_admissible():
    """Oppenheim's seven voussoirs under a 0.40 g step (lambda = 0.37 g): the four-hinge
    mechanism is admissible until t_p = 0.20 s (docs/notes/mechanism.md, `first_exit`), and in that
    time the rigid chain's rotation measure equals Eq. 2's phi to 1e-5 of its value (measured
    1.3e-6 at h = 1e-4 s, 3e-7 at 2.5e-5 s: first order), with the limit-analysis hinges open."""
    from archquake.compare.snapshots import dem_hinges

    motion = StepImpulse.from_g(0.40, 0.2)
    times = np.linspace(0.05, 0.19, 8)
    ref = simulate(OPPENHEIM, motion, t_eval=times, t_end=0.25)
    run = simulate_rigid(OPPENHEIM, motion, duration=0.2, time_step=1e-4, output_interval=1e-4)
    res = run
    phi = np.interp(times, res.times, res.rotation)
    exact = ref.evaluated.signed_rotation
    assert np.all(exact > 0)
    assert np.max(np.abs(phi / exact - 1.0)) < 1e-5
    assert _label(dem_hinges(res, 0.2)) == _label(zip(hinges_of(OPPENHEIM).joints,
                                                       (f.value for f in
                                                        hinges_of(OPPENHEIM).faces)))


# ----------------------------------------------------------------------------- onset, symmetry
def test_onset_just_above_lambda_opens_the_limit_analysis_hinges():
    """A constant ground acceleration of -1.05 lambda g from rest opens exactly the
    limit-analysis mechanism (upper-bound theorem: only the mechanism of least lambda is
    driven)."""
    from archquake.compare.snapshots import dem_hinges
    from archquake.dem.studies import ramp_and_hold

    prep = PreparedMechanism.build(OPPENHEIM)
    a = -1.05 * prep.collapse_acceleration_g * G
    run = simulate_rigid(OPPENHEIM, ramp_and_hold(a, 1e-3, 1.0), duration=0.6, time_step=1e-4)
    mech = prep.mechanism
    want = " ".join(f"{j}{f.value[0]}" for j, f in zip(mech.joints, mech.faces))
    assert _label(dem_hinges(run, 0.6)) == want


def test_mirror_symmetry():
    """The mirrored pulse gives the mirrored motion (voussoir k <-> n-1-k, x -> -x,
    theta -> -theta) through the onset, a five-hinge phase and a migration (0.8 s), to 1e-6 of
    the thickness (the Gauss-Seidel sweep order is not symmetric: its tolerance is the
    limit)."""
    from archquake.ground.pulses import RectangularPulse

    pulse = RectangularPulse(-2.0 * 0.37 * G, 0.283)
    a = simulate_rigid(OPPENHEIM, pulse, duration=0.8, time_step=1e-4)
    b = simulate_rigid(OPPENHEIM, pulse.mirrored(), duration=0.8, time_step=1e-4)
    pa = a.positions[:, 2:, :]
    pb = b.positions[:, 2:, :][:, ::-1, :] * np.array([-1.0, 1.0, -1.0])
    scale = np.array([1.0, 1.0, OPPENHEIM.radius])
    assert np.max(np.abs((pa - pb) * scale)) < 1e-6 * OPPENHEIM.thickness
    assert np.max(np.abs(a.rotation)) > 0.01  # it did rock


def test_a_pivot_in_persistent_contact_does_not_slip():
    """The model has no sliding, so a joint's tangential offset stays zero while it touches
    (oracle: the model itself, and its event-driven integration, 1.3e-11 m here). Under a strong
    pulse (parabolic arch, 3 lambda, t_p 0.5 s) the pivot of joint 0 rotates fast enough that a
    step's second-order drift (7e-8 m open) passed the contact tolerance and the stepper slid
    33 mm by 0.29 s; with the position-level correction and its hold (``_step_kernels.run``)
    the largest offset before 0.29 s is 2.3e-9 m (bound 1e-6 m, the size of one re-entry's
    slip before)."""
    from archquake.geometry.shapes import shaped
    from archquake.limit import limit_analysis

    arch = shaped("parabolic", span=10, rise=4, thickness=0.8, voussoirs=10)
    motion = StepImpulse.from_g(3.0 * limit_analysis(arch).collapse_acceleration_g, 0.5)
    for solver in ("direct", "events"):
        res = simulate_rigid(arch, motion, duration=0.3, solver=solver)
        early = res.times < 0.29
        assert np.max(np.abs(res.joint_slip[early])) < 1e-6, solver
        assert np.max(res.joint_opening[early]) > 0.05  # it did rock: a hinge open 5 cm


def test_direct_solve_is_the_converged_gauss_seidel():
    """The exact active-set solve (``solver="direct"``, the default) against the plain projected
    Gauss-Seidel stepper driven to a 100 times tighter tolerance (an independent solver of the
    same projection) through the onset, a five-hinge phase and a migration (0.8 s): positions
    equal to 1e-10 of the thickness (measured 9e-13; Gauss-Seidel at the default tolerance
    differs from both by 2.3e-7)."""
    from archquake.ground.pulses import RectangularPulse

    pulse = RectangularPulse(-2.0 * 0.37 * G, 0.283)
    a = simulate_rigid(OPPENHEIM, pulse, duration=0.8, time_step=1e-4, solver="direct")
    b = simulate_rigid(OPPENHEIM, pulse, duration=0.8, time_step=1e-4, solver="pgs",
                       solver_tolerance=1e-13)
    scale = np.array([1.0, 1.0, OPPENHEIM.radius])
    diff = (a.positions - b.positions)[:, 2:, :] * scale
    assert np.max(np.abs(diff)) < 1e-10 * OPPENHEIM.thickness
    assert np.max(np.abs(a.rotation)) > 0.01  # it did rock


def test_energy_kept_converges_in_the_time_step():
    """Self-convergence: the energy kept over Oppenheim's first half cycle (the comparison's
    protocol) changes by < 0.01 from h = 2e-4 s to 1e-4 s (measured 0.5354 -> 0.5358; 0.5354 at
    5e-5 s; 0.543 -> 0.536 before the position-level correction)."""
    from archquake.compare.rigid import rigid_half_cycle

    k1 = rigid_half_cycle(OPPENHEIM, time_step=2e-4)[0].kept
    k2 = rigid_half_cycle(OPPENHEIM, time_step=1e-4)[0].kept
    assert abs(k1 - k2) < 0.01


def test_dynamic_similarity():
    """Every length x4, the pulse duration and the time step x2 (same acceleration): the same
    motion at twice the times (rotation measure to 1e-7 rad, energy fractions to 1e-7; the
    gap and solver tolerances are relative to the reference length, so the scheme itself is
    similar)."""
    from archquake.ground.pulses import RectangularPulse

    a = -2.0 * 0.37 * G
    small = simulate_rigid(OPPENHEIM, RectangularPulse(a, 0.283), duration=0.9, time_step=1e-4,
                           output_interval=1e-3)
    big = simulate_rigid(OPPENHEIM.scaled(4.0), RectangularPulse(a, 0.566), duration=1.8,
                         time_step=2e-4, output_interval=2e-3)
    rs, rb = small, big
    assert np.allclose(rb.times, 2.0 * rs.times)
    assert np.max(np.abs(rb.rotation - rs.rotation)) < 1e-7
    es = (rs.kinetic + rs.potential) / (rs.kinetic + rs.potential).max()
    eb = (rb.kinetic + rb.potential) / (rb.kinetic + rb.potential).max()
    assert np.max(np.abs(es - eb)) < 1e-7


@pytest.mark.slow
def test_critical_step_duration_on_oppenheim():
    """The first collapsing t_p at 1.0 g lies in (0.2586, 0.2606] s (measured; DEM 0.2531-0.2550
    at the paper's stiffness, 0.2569-0.2588 at 100 times it: docs/notes/mechanism.md "The rigid
    limit")."""
    from archquake.compare.rigid import step_collapses

    assert not step_collapses("rigid", OPPENHEIM, 1.0, 0.2586)
    assert step_collapses("rigid", OPPENHEIM, 1.0, 0.2606)


@pytest.mark.parametrize("a_g, slides", [(0.2, False), (0.5, True)])
def test_coulomb_block_slides_as_a_particle(a_g, slides):
    """A squat block (b 2 m, h 0.4 m: it would rock only above 5 g) on a base with mu = 0.3,
    ground acceleration a for 0.5 s: below mu g it sticks (slip < 1e-9 m); above, it slides with
    the relative acceleration (a - mu g) of a particle on a rough plane, displacement
    (a - mu g) T^2 / 2 to 1e-3."""
    from archquake.ground.pulses import RectangularPulse

    mu, t_end = 0.3, 0.5
    run = simulate_rigid(block_on_base(2.0, 0.4), RectangularPulse(a_g * G, t_end),
                         duration=t_end, time_step=1e-4, friction=mu)
    res = run
    rel = res.positions[-1, 1, 0] - res.base_displacement[-1]
    if not slides:
        assert abs(rel) < 1e-9
    else:
        assert -rel == pytest.approx(0.5 * (a_g - mu) * G * t_end**2, rel=1e-3)
    assert abs(res.positions[-1, 1, 2]) < 1e-9  # no rocking


def test_unknown_solver_is_refused():
    """The solver option names its two values."""
    from archquake.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match="solver"):
        simulate_rigid(OPPENHEIM, REST, duration=0.01, solver="lu")


def test_step_with_the_kept_factor_is_the_full_solve_to_the_tolerance():
    """The compiled run keeps its work arrays from step to step (``_step_kernels.workspace``),
    and with them the last active set's Cholesky factor, the refinement's preconditioner while
    the set holds and is regular, and the set's impulses of the last steps, extrapolated as the
    solve's start (``_step_kernels.project_direct``). Oracle: the full solve of the same step
    (``geometry``, ``project_direct``: fresh arrays, the set assembled and factorised), taken
    from Python on the run's own state at every step, on Oppenheim's arch under a step pulse
    that opens and closes joints (t_p = 0.27 s at 1.0 g, 0.6 s: onset, a half cycle, an
    impact). Tolerance: each of the two velocities meets the set's equalities to the solver's
    ``tol`` (m/s), so they may differ by about twice that; 4 ``tol`` is asked, 1.8 ``tol``
    measured at worst. The warm start and the joints' reference offsets (the state the
    correction reads) are the full solve's own, step after step, and must stay the run's: at
    the end the same corners push and the offsets agree to 1e-9 L. The run must have
    used the kept factor: steps that differ from the full solve in their last bits (nearly all
    of them; none before the factor was kept)."""
    import archquake.rigid._step_kernels as RK
    from archquake.rigid.model import GAP_TOLERANCE, HOLD_TOLERANCE, MAX_SWEEPS, SOLVER_TOLERANCE

    m = RigidModel.build(OPPENHEIM)
    h, n = 1e-3, 600
    lref = m.assembly.reference_length
    tol = SOLVER_TOLERANCE * math.sqrt(G * lref)
    gap_tol, hold = GAP_TOLERANCE * lref, HOLD_TOLERANCE * lref
    acc = -G * np.where(np.arange(n) * h < 0.27, 1.0, 0.0)
    q0, v0 = m.rest()
    run_p = np.zeros((m.ja.size, 3))
    run_slip = np.full(m.ja.size, np.nan)
    oq, ov = np.zeros((n, m.n_bodies, 3)), np.zeros((n, m.n_bodies, 3))
    cfg = RK.stepping(h, G, gap_tol, tol, MAX_SWEEPS, 0.0, RK.METHOD_DIRECT, True, hold)
    RK.run(m.chain, cfg, RK.State(q0.copy(), v0.copy(), run_p, run_slip), acc, np.empty(0),
           RK.Record(1, oq, ov, np.zeros((n, RK.N_DIAG))), np.zeros(RK.N_DIAG))
    q, v = q0, v0
    p_warm = np.zeros((m.ja.size, 3))
    slip = np.full(m.ja.size, np.nan)
    moved = 0
    differ = 0
    worst = 0.0
    for k in range(n):
        qm = q + 0.5 * h * v
        vf = v.copy()
        vf[:, 0] -= h * acc[k]
        vf[:, 1] -= h * G
        geo = m.geometry(qm)
        vn, imp, _, _ = RK.project_direct(m.chain, cfg, qm, geo, vf, p_warm, slip, np.zeros(1))
        p_warm = imp.copy()
        worst = max(worst, float(np.abs(vn - ov[k]).max()))
        differ += not np.array_equal(vn, ov[k])
        moved += bool(np.any(geo.gaps > 1e-3 * lref))
        q, v = oq[k], ov[k]  # the run's state: the next step from it
    assert worst <= 4.0 * tol, f"{worst / tol:.2f} tol"
    np.testing.assert_array_equal(np.isnan(run_slip), np.isnan(slip))  # the same contacts
    ok = ~np.isnan(slip)
    assert np.abs(run_slip[ok] - slip[ok]).max() <= 1e-9 * lref
    assert np.array_equal(run_p > 0.0, p_warm > 0.0)  # the same corners pushing at the end
    assert differ > n // 2  # the kept factor served (the old, full solve at every step: 0)
    assert moved > 100  # the run did open joints: the test saw contacts change


def test_contacts_at_rest_book_half_m_g2_h_per_second(monkeypatch):
    """The time stepper's energy-balance residual is its bookkeeping, not a loss of motion:
    every step the contacts that hold the blocks up absorb the gravity impulse M g h, and the
    kinetic energy of that impulse, 1/2 M (g h)^2, is booked as dissipated. An arch at rest
    (REST: no ground motion) books 1/2 M g^2 h per second (closed form), halving with h, and
    never moves. (The stepper itself: the onset test, which ends such a run before any step,
    is switched off.)"""
    import archquake.rigid.run as R

    monkeypatch.setattr(R, "stays_at_rest", lambda *a, **k: False)
    model = RigidModel.build(OPPENHEIM)
    mass = float(np.sum(model.mass))
    for h in (1e-3, 5e-4):
        run = simulate_rigid(model, REST, duration=1.0, time_step=h)
        booked = float(run.damping[-1])
        expected = 0.5 * mass * G**2 * h * float(run.times[-1])
        assert booked == pytest.approx(expected, rel=2e-3)
        assert run.kinetic.max() < 1e-12 * mass * G * OPPENHEIM.thickness
