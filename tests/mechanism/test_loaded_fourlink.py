"""The four-link mechanism with what the arch carries: each link carries its voussoirs' fill
columns and moving loads (:class:`~archquake.geometry.carrying.CarryingChain`), on the
loaded arch's hinges.

Oracles: the static analysis with the loads (:mod:`archquake.limit.loaded`, both bounds): the
mechanism's lambda by virtual work at phi = 0, packed for the kernel, equals it (1e-12
relative); the block assembly both block models read (the same voussoir masses, centroids and
inertias, 1e-12); no loads give the bare mechanism's packed array exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.blocks.assembly import build_arch_assembly
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.carrying import CarryingChain
from archquake.geometry.loads import Backing, Extrados, Fill, Loads, PointLoad
from archquake.limit.loaded import loaded_collapse, seismic_case
from archquake.mechanism import PreparedMechanism

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
CASES = {
    "bridge, 1 m of fill": (Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0),
                            Loads(fill=Fill(depth=1.0, density=1800.0))),
    "thick ring, fill and backing": (Arch(5.0, 0.75, math.pi, 15, 1.0, 1800.0),
                                     Loads(fill=Fill(depth=1.0, density=1800.0),
                                           backing=Backing(1.5))),
    "Oppenheim, fill and a wall on the crown": (OPPENHEIM, Loads(
        fill=Fill(depth=0.5, density=2000.0),
        point_loads=(PointLoad(0.5 * Extrados.of(OPPENHEIM).clear_span, 20e3),))),
}


@pytest.mark.parametrize("name", list(CASES))
def test_the_loaded_links_lambda_is_the_loaded_statics(name):
    arch, loads = CASES[name]
    prepared = PreparedMechanism.build(arch, loads=loads)
    collapse = loaded_collapse(seismic_case(arch, loads))
    assert prepared.collapse_acceleration_g == pytest.approx(collapse.multiplier, rel=1e-12)
    assert prepared.mechanism.joints == collapse.mechanism.joints
    assert isinstance(prepared.mechanism.arch, CarryingChain)


@pytest.mark.parametrize("name", list(CASES))
def test_the_links_carry_what_the_block_assembly_carries(name):
    arch, loads = CASES[name]
    chain = CarryingChain(arch, loads)
    asm = build_arch_assembly(arch, loads=loads)
    np.testing.assert_allclose(chain.voussoir_masses, asm.masses[2:], rtol=1e-12)
    np.testing.assert_allclose(chain.voussoir_centroids, asm.centroids[2:], rtol=1e-12)
    np.testing.assert_allclose(chain.voussoir_inertias, asm.inertias[2:], rtol=1e-12)
    np.testing.assert_array_equal(chain.intrados_points, arch.intrados_points)


def test_no_loads_give_the_bare_mechanism_exactly():
    arch = CASES["bridge, 1 m of fill"][0]
    bare = PreparedMechanism.build(arch)
    for loads in (None, Loads()):
        same = PreparedMechanism.build(arch, loads=loads)
        assert np.array_equal(same.packed, bare.packed)
        assert same.mechanism.joints == bare.mechanism.joints


def test_still_loads_are_not_masses():
    arch = CASES["bridge, 1 m of fill"][0]
    with pytest.raises(InvalidParameterError, match="still"):
        PreparedMechanism.build(arch, loads=Loads(point_loads=(PointLoad(3.0, 1e4, False),)))


def test_loads_that_break_the_symmetry_are_refused():
    """The four-link impacts hand the motion to the mirror-image mechanism: a wall off the
    crown leaves the four-link model (the block models carry it)."""
    with pytest.raises(InvalidParameterError, match="symmetric about the crown"):
        PreparedMechanism.build(OPPENHEIM, loads=Loads(point_loads=(PointLoad(5.0, 20e3),)))


@pytest.mark.parametrize("name, magnitude, tp", [
    ("bridge, 1 m of fill", 0.3, 0.15),
    ("Oppenheim, fill", 1.0, 0.3),
])
def test_the_first_half_cycle_is_the_rigid_chain_cut_at_the_loaded_hinges(name, magnitude, tp):
    """Two integrators of one motion: before the first impact the four-link mechanism's phi(t)
    (its equation of motion with the loaded links) and the rigid chain's rotation of the arch
    cut at the loaded hinges, its voussoirs carrying the same loads (Moreau-Jean steps of
    1e-4 s), agree to 2e-3 of the peak (measured 5e-4)."""
    from archquake.ground import StepImpulse
    from archquake.mechanism.simulate import simulate
    from archquake.rigid import simulate_rigid

    arch, loads = (CASES[name] if name in CASES
                   else (OPPENHEIM, Loads(fill=Fill(depth=0.5, density=2000.0))))
    mech = loaded_collapse(seismic_case(arch, loads)).mechanism
    cuts = tuple(sorted({0, *mech.joints, arch.voussoirs}))
    asm = build_arch_assembly(arch, cut_joints=cuts, mechanism=mech, hold_outside_hinges=True,
                              loads=loads)
    motion = StepImpulse.from_g(magnitude, tp)
    four = simulate(PreparedMechanism.build(arch, loads=loads), motion, t_end=2.0)
    assert four.impact_times.size and four.history is not None
    first = float(four.impact_times[0])
    chain = simulate_rigid(asm, motion, duration=first)
    t = np.linspace(0.05, 0.9 * first, 12)
    phi = np.interp(t, four.history.t, four.history.phi)
    rot = np.interp(t, chain.times, chain.rotation)
    np.testing.assert_allclose(rot, phi, atol=2e-3 * float(np.max(np.abs(phi))))
