"""Oppenheim's arch in the distinct-element model: statics, the builder, and the four-link
first half cycle (the paper's Figure 4 outcomes and friction thresholds: tests/paper)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.dem import DemSettings, build_arch_assembly, simulate_dem
from archquake.geometry import Arch
from archquake.ground.pulses import StepImpulse


@pytest.fixture(scope="module")
def arch() -> Arch:
    return Arch(10.0, 1.5, math.radians(157.5), 7)


def run(arch, tp, duration, cut=None):
    asm = build_arch_assembly(arch, cut_joints=cut) if cut else arch
    return simulate_dem(asm, StepImpulse.from_g(1.0, tp), DemSettings(duration=duration))


def test_arch_stands_under_gravity_and_below_the_static_threshold(arch):
    """Limit analysis: no hinge below lambda = 0.37 g (here 0.3 g held for 0.4 s)."""
    res = simulate_dem(arch, StepImpulse.from_g(0.3, 0.4), DemSettings(duration=0.5))
    assert res.outcome.value == "no_hinging"
    assert res.onset_time is None


def test_builder_uses_exact_merged_mass_properties(arch):
    asm = build_arch_assembly(arch, cut_joints=(0, 3, 5, 7))
    free = asm.free_blocks
    assert asm.masses[free].sum() == pytest.approx(arch.mass, rel=1e-12)
    first = arch.voussoir_masses[:3] @ arch.voussoir_centroids[:3] / arch.voussoir_masses[:3].sum()
    np.testing.assert_allclose(asm.centroids[free[0]], first, rtol=1e-12)
    assert asm.meta["mechanism_joints"] == [0, 3, 5, 7]


def test_three_voussoir_arch_follows_the_fourlink_first_half_cycle(arch):
    """Paper, Figure 4(b): a DEM arch cut at the four-link hinges (0, 3, 5, 7) reproduces
    the four-link phi(t) before impact. Oracle: the first half cycle of the four-link
    mechanism (Eq. 2), here its values at 0.2 s and 0.6 s (phi = 0.0072, 0.0806 rad,
    archquake.mechanism), to 3 % (contact compliance)."""
    res = run(arch, 0.44, 0.7, cut=(0, 3, 5, 7))
    phi = np.interp([0.2, 0.6], res.times, res.rotation)
    np.testing.assert_allclose(phi, [0.0072, 0.0806], rtol=0.03)
