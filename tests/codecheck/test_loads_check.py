"""The code check's mechanism with what the arch carries (C8.7.1: every carried mass counts).

Oracles: the bare mechanism (no loads), the loaded equivalent static analysis (another method:
the linear program and the 4 x 4 equilibrium through the hinges), and a hand computation of e*
from the mechanism's rigid-body velocities.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.codecheck.kinematic import LoadedFourHingeMechanism, capacity_curve
from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, PointLoad, block_extras
from archquake.geometry.planar import perp
from archquake.limit import limit_analysis

BRIDGE = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
LOADS = {
    "fill": Loads(fill=Fill(depth=1.0)),
    "fill and a wall that moves": Loads(fill=Fill(depth=0.5), point_loads=(PointLoad(6.0, 40e3),)),
    "fill and a weight that does not": Loads(fill=Fill(depth=1.0),
                                           point_loads=(PointLoad(7.0, 30e3, False),)),
}


def test_no_loads_is_the_bare_check():
    """1e-12: the same kinematics, with carried blocks of zero mass beside the voussoirs."""
    bare = capacity_curve(BRIDGE)
    loaded = capacity_curve(LoadedFourHingeMechanism.of(BRIDGE, Loads()))
    for key in ("alpha0", "e_star", "m_star_kg", "mass_kg", "d0_m", "phi0_rad"):
        assert getattr(loaded, key) == pytest.approx(getattr(bare, key), rel=1e-12), key


@pytest.mark.parametrize("name", list(LOADS))
def test_alpha0_is_the_loaded_collapse_multiplier(name):
    """alpha0 by the code check's virtual work equals lambda of the loaded equivalent static
    analysis (1e-10: rounding of two different computations)."""
    loads = LOADS[name]
    curve = capacity_curve(LoadedFourHingeMechanism.of(BRIDGE, loads))
    lam = limit_analysis(BRIDGE, method="both", loads=loads).collapse_acceleration_g
    assert curve.alpha0 == pytest.approx(lam, rel=1e-10)
    assert curve.alphas[0] == pytest.approx(lam, rel=1e-10) and curve.alphas[-1] == 0.0


@pytest.mark.parametrize("name", list(LOADS))
def test_every_carried_mass_counts_in_m_and_e_star(name):
    """M is the moving voussoirs' mass plus what they carry that moves (exact); e* from the
    hand formula (C8.7.1.5) with the rigid-body velocities of each link (1e-10)."""
    loads = LOADS[name]
    mech = LoadedFourHingeMechanism.of(BRIDGE, loads)
    curve = capacity_curve(mech)
    hinges = limit_analysis(BRIDGE, method="both", loads=loads).mechanism
    extras = block_extras(BRIDGE, loads)
    moving = np.arange(hinges.joints[0], hinges.joints[3])
    assert curve.mass_kg == pytest.approx(
        BRIDGE.voussoir_masses[moving].sum() + extras.mass[moving].sum(), rel=1e-12)
    pts, w = hinges.points, hinges.rates
    vb = w[0] * perp(pts[1] - pts[0])
    masses, dx = [], []
    for link, rng in enumerate(hinges.link_voussoirs):
        pivot = pts[(0, 1, 3)[link]]
        for k in rng:
            for m, c in ((BRIDGE.voussoir_masses[k], BRIDGE.voussoir_centroids[k]),
                         (extras.mass[k], extras.centroid[k])):
                v = w[link] * perp(c - pivot) + (vb if link == 1 else 0.0)
                masses.append(m)
                dx.append(v[0])
    m, d = np.array(masses), np.array(dx)
    e_star = (m @ d) ** 2 / (m.sum() * (m @ d**2))
    assert curve.e_star == pytest.approx(e_star, rel=1e-10)
    assert curve.m_star_kg == pytest.approx(e_star * m.sum(), rel=1e-10)


def test_a_weight_that_does_not_move_adds_no_mass():
    moving = capacity_curve(LoadedFourHingeMechanism.of(BRIDGE, LOADS["fill"]))
    still = capacity_curve(LoadedFourHingeMechanism.of(
        BRIDGE, LOADS["fill and a weight that does not"]))
    assert still.mass_kg == pytest.approx(moving.mass_kg, rel=1e-12)
    assert still.alpha0 > moving.alpha0
