"""The distinct-element engine on a single block: statics, rocking onset, Housner's
overturning threshold and restitution, energy conservation, kernel against its NumPy twin."""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.constants import STANDARD_GRAVITY as G
from archquake.dem import (
    ContactLaw,
    DemSettings,
    _kernels,
    _reference,
    block_on_base,
    build_arch_assembly,
    simulate_dem,
)
from archquake.dem.run import _params, build_slots, neighbour_pairs, pack, stable_time_step
from archquake.dem.studies import (
    bisect,
    free_rocking_restitution,
    ramp_and_hold,
    rectangular_pulse,
)
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.ground.pulses import SinePulse, StepImpulse
from archquake.ground.records import Record
from archquake.validation import housner

REST = Record([0.0, 0.0], 1.0)


def test_block_settles_with_the_overlap_its_weight_implies():
    """Statics: two corner springs of k_n * depth * b/2 each carry m g, so each overlaps by
    m g / (k_n b depth); kinetic-damping settling must land on it (1 %)."""
    b, h, kn = 0.4, 2.0, 1e12
    asm = block_on_base(b, h)
    res = simulate_dem(asm, REST, DemSettings(contact=ContactLaw(kn), duration=0.01))
    expected = asm.masses[1] * G / (kn * b * asm.depth)
    np.testing.assert_allclose(-res.joint_opening[-1, 0], expected, rtol=0.01)


def test_rocking_starts_at_g_b_over_h():
    """Statics of a rigid block: the heel unloads at x_g'' = g b / h. Bisection on a
    quasi-static (ramped, then held) acceleration; rocking = rotation above 1e-3 rad."""
    b, h = 0.4, 2.0

    def rocks(a_g: float) -> bool:
        res = simulate_dem(block_on_base(b, h), ramp_and_hold(a_g * G, 0.3, 1.0),
                           DemSettings(duration=1.3, output_interval=0.01))
        return float(np.max(np.abs(res.rotation))) > 1e-3

    onset = bisect(rocks, 0.15, 0.25, rtol=2e-3)
    assert onset * G == pytest.approx(housner.onset_acceleration(b, h, g=G), rel=0.01)


def test_overturning_threshold_of_a_rectangular_pulse_matches_housner():
    """Housner (1963), linearised rocking: a rectangular pulse of duration t_p overturns the
    block (before any impact) iff a >= g alpha / (1 - exp(-p t_p)), p = sqrt(3 g / (4 R)).

    Fair choice: a slender block (alpha = 0.0997) so sin/cos linearisation errs by < 0.5 %,
    and p t_p = 1 so the threshold (1.58 g alpha) is neither the impulsive limit (where the
    block would turn far during the pulse) nor the quasi-static one (where it would linger
    at the crest). 5 % covers contact compliance and the finite bisection."""
    b, h = 0.3, 3.0
    alpha = housner.slenderness(b, h)
    tp = 1.0 / housner.frequency_parameter(b, h, g=G)
    closed = housner.rectangular_pulse_overturning(b, h, tp, g=G)
    settings = DemSettings(duration=7.0, output_interval=0.01, collapse_rotation=3 * alpha)

    def overturns(a: float) -> bool:
        res = simulate_dem(block_on_base(b, h), rectangular_pulse(-a, tp), settings)
        return res.outcome.value == "collapse" and res.first_impact_time is None

    a_min = bisect(overturns, 0.8 * closed, 1.3 * closed, rtol=5e-3)
    assert a_min == pytest.approx(closed, rel=0.05)


@pytest.mark.parametrize("width", [0.2, 0.4, 0.6])
def test_free_rocking_loses_energy_at_impact_like_housner(width):
    """With the paper's damping the impacts are plastic: the measured restitution is < 1 and
    close to Housner's 1 - 1.5 sin^2 alpha (table in docs/models/dem.md; 2 % here)."""
    r = free_rocking_restitution(width, 2.0, DemSettings())
    assert r < 1.0
    assert r == pytest.approx(housner.restitution(width, 2.0), rel=0.02)


def test_energy_is_conserved_without_damping_friction_or_impacts():
    """No damping, no sliding, no lift-off (a sine pulse at half the rocking onset): the
    leapfrog energy balance (kinetic + potential + strain - input work) holds to 1e-3 of the
    energy scale over 1 s."""
    res = simulate_dem(
        block_on_base(0.4, 2.0),
        SinePulse.from_g(0.1, 0.05),
        DemSettings(damping=(0.0, 0.0), duration=1.0, output_interval=0.001),
    )
    assert res.outcome.value == "no_hinging"
    assert float(np.max(res.kinetic)) > 0
    assert res.energy_error < 1e-3


def _twin_run(asm, motion, settings, steps):
    dt, _ = stable_time_step(asm, settings)
    runs = []
    for impl in (_kernels, _reference):
        pk = pack(asm)
        pk = build_slots(pk, neighbour_pairs(pk, 0.5))
        par = _params(asm, settings, dt, G)
        acc = np.zeros(_kernels.N_ACC)
        kind, gp = motion.kernel_spec()
        work = _kernels.scratch(pk)
        hist = []
        for n in range(steps):
            impl.step(pk, par, acc, kind, gp, n * dt, True, False, work)
            hist.append(pk.state.copy())
        runs.append((np.array(hist), pk.sl_edge.copy(), pk.sl_f.copy(), acc.copy()))
    return runs


@pytest.mark.parametrize("case", ["sliding block", "three-voussoir arch"])
def test_kernel_equals_numpy_reference(case):
    """The compiled step and its vectorised NumPy reference give the same trajectory (to
    round-off) over a few hundred steps that create, slide and drop contacts."""
    if case == "sliding block":
        asm = block_on_base(0.4, 2.0)
        settings = DemSettings(contact=ContactLaw(friction=0.3))
        motion = StepImpulse.from_g(2.0, 0.5)
    else:
        asm = build_arch_assembly(Arch(10, 1.5, math.radians(157.5), 7), cut_joints=(0, 3, 5, 7))
        settings = DemSettings()
        motion = StepImpulse.from_g(1.0, 0.44)
    (hk, ek, fk, ak), (ht, et, ft, at) = _twin_run(asm, motion, settings, 400)
    scale = np.max(np.abs(hk), axis=(0, 1))
    np.testing.assert_allclose(hk, ht, rtol=0, atol=1e-9 * float(np.max(scale)))
    np.testing.assert_array_equal(ek, et)
    np.testing.assert_allclose(fk, ft, rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(ak, at, rtol=1e-7, atol=1e-9)
    if case == "sliding block":
        assert fk[:, 4].max() > 0  # the block did slide


@pytest.mark.parametrize("case", ["collapse", "sliding"])
def test_broad_phase_changes_no_bit(case):
    """The broad phase (``P_BROAD``: corners out of reach of the other block, or coinciding
    with one of its active corners, are not scanned; slots out of reach until the next
    rebuild are not looked at) only leaves out what the exhaustive scan would reject.
    Oracle: the exhaustive scan, on Oppenheim's voussoir arch collapsing (blocks fly apart, new
    contacts form between corners and edges far from the joints, the neighbour lists are
    rebuilt) and on the arch cut at its hinges with joints that slide (mu 0.4 against a
    friction demand of 0.55: contacts slide off their edges); tolerance zero, as the claim is
    exactness."""
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)  # Oppenheim's arch
    motion = StepImpulse.from_g(1.0, 0.27)
    if case == "collapse":
        # collapses in its second half cycle, at 3.2-3.5 s as its numbers round
        body, settings = arch, DemSettings(duration=4.0, output_interval=0.002)
    else:
        body = build_arch_assembly(arch, cut_joints=(0, 3, 5, 7))
        settings = DemSettings(contact=ContactLaw(friction=0.4), duration=1.5,
                               output_interval=0.002)
    fast = simulate_dem(body, motion, settings)
    slow = simulate_dem(body, motion, settings, broad_phase=False)
    if case == "collapse":
        assert fast.outcome.value == "collapse"
    else:
        assert fast.friction[-1] > 0.0  # the joints slid
    for name in ("times", "positions", "velocities", "kinetic", "strain", "friction",
                 "damping", "input_work", "impact_times"):
        assert getattr(fast, name).tobytes() == getattr(slow, name).tobytes(), name
    assert fast.collapse_time == slow.collapse_time


def test_settings_validate_with_one_line_errors():
    with pytest.raises(InvalidParameterError, match="safety"):
        DemSettings(safety=1.5)
    with pytest.raises(InvalidParameterError, match="Rayleigh"):
        DemSettings(damping=(-1.0, 0.0))
    with pytest.raises(InvalidParameterError, match="normal_stiffness"):
        ContactLaw(normal_stiffness=0.0)
