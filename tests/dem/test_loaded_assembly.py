"""The block assembly of an arch with what it carries, read by both block models (the DEM and
the chain of rigid voussoirs).

Oracles: the bare assembly (no loads: the same arrays, exactly); the mass properties of the
voussoirs and the fill columns taken apart (total mass, first and second moments about the
origin, 1e-12 relative); the statics with loads (:mod:`archquake.limit.loaded`, both bounds):
the chain's onset of rocking is the loaded arch's lambda in each direction (1e-6 relative, the
onset bisection's tolerance), and the onset is unchanged when the masonry and fill densities
are scaled together; the event integrator conserves energy before the first impact.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.blocks.assembly import PASSIVE_LEFT_OUT, build_arch_assembly, dem_assembly
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.loads import (
    Backing,
    Fill,
    Loads,
    Passive,
    PointLoad,
    Traffic,
    block_extras,
)
from archquake.limit.loaded import loaded_collapse, seismic_case
from archquake.rigid import RigidModel
from archquake.rigid.events import EventModel

BRIDGE = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
THICK = Arch(5.0, 0.75, math.pi, 15, 1.0, 1800.0)
OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)

CASES = {
    "bridge, 1 m of fill": (BRIDGE, Loads(fill=Fill(depth=1.0, density=1800.0))),
    "thick ring, fill and backing": (THICK, Loads(fill=Fill(depth=1.0, density=1800.0),
                                                  backing=Backing(1.5))),
    "Oppenheim, fill and a carried wall": (OPPENHEIM, Loads(
        fill=Fill(depth=0.5, density=2000.0), point_loads=(PointLoad(5.0, 20e3),))),
}


def test_no_loads_give_the_bare_assembly_exactly():
    bare = build_arch_assembly(BRIDGE)
    for asm in (build_arch_assembly(BRIDGE, loads=Loads()), dem_assembly(BRIDGE, loads=None)):
        for name in ("masses", "inertias", "centroids", "base"):
            assert np.array_equal(getattr(asm, name), getattr(bare, name))
        assert [j.index for j in asm.joints] == [j.index for j in bare.joints]
        assert asm.meta == bare.meta and asm.to_dict() == bare.to_dict()


@pytest.mark.parametrize("name", list(CASES))
def test_each_voussoir_carries_its_column_by_the_parallel_axis_theorem(name):
    """Mass, first moment and second moment about the origin of every block equal those of
    the voussoir and of what it carries taken apart (1e-12 relative)."""
    arch, loads = CASES[name]
    asm = build_arch_assembly(arch, loads=loads)
    ex = block_extras(arch, loads)
    m = asm.masses[2:]
    c = asm.centroids[2:]
    vm, vc, vi = arch.voussoir_masses, arch.voussoir_centroids, arch.voussoir_inertias
    np.testing.assert_allclose(m, vm + ex.mass, rtol=1e-12)
    np.testing.assert_allclose(m[:, None] * c, vm[:, None] * vc + ex.mass[:, None] * ex.centroid,
                               rtol=1e-12)
    about_o = asm.inertias[2:] + m * np.sum(c**2, axis=1)
    parts = (vi + vm * np.sum(vc**2, axis=1)
             + ex.inertia + ex.mass * np.sum(ex.centroid**2, axis=1))
    np.testing.assert_allclose(about_o, parts, rtol=1e-12)
    masses = asm.meta["masses"]
    assert masses["carried_mass_kg"] == pytest.approx(float(ex.mass.sum()), rel=1e-12)
    assert masses["passive_pressure"] == PASSIVE_LEFT_OUT
    assert asm.meta["loads"] == loads.to_dict()


def test_the_backing_holds_its_voussoirs_as_part_of_the_support():
    """1.5 m of backing on the thick ring holds joints 0, 1 and 14, 15 (their extrados ends lie
    below it): voussoirs 0, 1 and 13, 14 cannot move, and no joint inside the backing is
    recorded."""
    arch, loads = CASES["thick ring, fill and backing"]
    held = block_extras(arch, loads).held
    assert list(np.flatnonzero(held)) == [0, 1, 14, 15]
    asm = build_arch_assembly(arch, loads=loads)
    assert asm.meta["held_voussoirs"] == [0, 1, 13, 14]
    assert list(np.flatnonzero(asm.base[2:])) == [0, 1, 13, 14]
    assert [j.index for j in asm.joints] == list(range(2, 14))  # voussoirs 2..12 move


@pytest.mark.parametrize("name", list(CASES))
def test_the_chains_onset_of_rocking_is_the_loaded_static_lambda(name):
    """The rigid chain's onset multipliers (its own bisection on the linear complementarity of
    the contacts, both signs of the ground acceleration) equal lambda of the static analysis
    with the loads in each direction (the kinematic and static bounds, which agree)."""
    arch, loads = CASES[name]
    onset_pos, onset_neg = EventModel.of(RigidModel.build(build_arch_assembly(arch, loads=loads))
                                         ).onset_g
    # a ground acceleration towards +x throws the masses towards -x
    lam_neg = loaded_collapse(seismic_case(arch, loads, direction=-1)).multiplier
    lam_pos = loaded_collapse(seismic_case(arch, loads, direction=+1)).multiplier
    assert onset_pos == pytest.approx(lam_neg, rel=1e-6)
    assert onset_neg == pytest.approx(lam_pos, rel=1e-6)


def test_the_fill_changes_the_onset_as_the_statics_says():
    """The example bridge: 1 m of fill raises lambda from 0.049 g to 0.082 g."""
    bare = EventModel.of(RigidModel.build(build_arch_assembly(BRIDGE))).onset_g[0]
    filled = EventModel.of(RigidModel.build(build_arch_assembly(
        BRIDGE, loads=CASES["bridge, 1 m of fill"][1]))).onset_g[0]
    assert bare == pytest.approx(0.0490, abs=5e-4)
    assert filled == pytest.approx(0.0819, abs=5e-4)


def test_scaling_both_densities_leaves_the_onset_unchanged():
    """Dimensional analysis: the onset is a ratio of forces, so scaling the masonry's and the
    fill's densities by the same factor leaves it (1e-6 relative)."""
    onsets = []
    for scale in (1.0, 3.0):
        arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0 * scale)
        loads = Loads(fill=Fill(depth=1.0, density=1800.0 * scale))
        onsets.append(EventModel.of(RigidModel.build(build_arch_assembly(arch, loads=loads))
                                    ).onset_g[0])
    assert onsets[1] == pytest.approx(onsets[0], rel=1e-6)


def test_the_event_integrator_conserves_energy_with_the_fill():
    """From event to event the chain's equations are integrated exactly: with the fill's
    masses, centroids and inertias, kinetic plus potential energy equals the ground's work
    to 1e-8 of it over the first 0.1 s of a 0.12 g step pulse (the arch rocks, one hinge
    opens on the way, no impact yet; measured 1.8e-10, the bare arch 4.0e-10)."""
    from archquake.ground import StepImpulse
    from archquake.rigid import simulate_rigid

    arch, loads = CASES["bridge, 1 m of fill"]
    run = simulate_rigid(build_arch_assembly(arch, loads=loads), StepImpulse.from_g(0.12, 0.08),
                         duration=0.1, solver="events")
    events = run.to_dict()["rigid"]["events"]
    assert run.onset_time is not None and events["closures"] == 0
    assert abs(run.energy_error) < 1e-8


def test_loads_the_dynamics_do_not_carry_are_refused_in_one_line():
    fill = Fill(depth=1.0, density=1800.0)
    for loads, word in ((Loads(fill=fill, point_loads=(PointLoad(5.0, 1e4, False),)), "still"),
                        (Loads(fill=fill, traffic=Traffic(1e5, 3.0)), "traffic"),
                        (Loads(fill=fill, passive=Passive(0.33)), "passive")):
        with pytest.raises(InvalidParameterError, match=word):
            build_arch_assembly(BRIDGE, loads=loads)


def test_the_arch_cut_at_the_loaded_hinges():
    """The three-voussoir arch with loads: cut at the loaded arch's hinges (2, 7, 12, 15 for
    the filled bridge; the bare one's are 3, 7, 12, 15), its blocks carrying the loads (the
    moving blocks' masses are their voussoirs' with what those carry, 1e-12)."""
    arch, loads = CASES["bridge, 1 m of fill"]
    asm = dem_assembly(arch, "hinges", loads=loads)
    assert asm.meta["cut_joints"] == [0, 2, 7, 12, 15] and asm.meta["held_voussoirs"] == [0, 1]
    ex = block_extras(arch, loads)
    moving = arch.voussoir_masses[2:] + ex.mass[2:]
    np.testing.assert_allclose(asm.masses[~asm.base], [moving[0:5].sum(), moving[5:10].sum(),
                                                       moving[10:13].sum()], rtol=1e-12)
