"""Arch geometry against closed forms and an independent numerical integration."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.errors import InvalidParameterError
from archquake.geometry import Arch, Face, HingeMechanism
from archquake.validation import paper

ratios = st.floats(0.02, 0.6)
embraces = st.floats(math.radians(30), math.radians(240))
counts = st.integers(3, 40)


def _sector_by_quadrature(arch: Arch, k: int, nr: int = 400, na: int = 400):
    """Mass, centroid and inertia of voussoir k by midpoint quadrature in polar coordinates."""
    a0, a1 = arch.joint_angles[k + 1], arch.joint_angles[k]
    r = arch.intrados_radius + (np.arange(nr) + 0.5) / nr * arch.thickness
    a = a0 + (np.arange(na) + 0.5) / na * (a1 - a0)
    rr, aa = np.meshgrid(r, a)
    da = rr * (arch.thickness / nr) * ((a1 - a0) / na)
    x, y = rr * np.cos(aa), rr * np.sin(aa)
    mass = arch.density * arch.depth * da.sum()
    cx, cy = (x * da).sum() / da.sum(), (y * da).sum() / da.sum()
    inertia = arch.density * arch.depth * (((x - cx) ** 2 + (y - cy) ** 2) * da).sum()
    return mass, np.array([cx, cy]), inertia


@given(ratios, embraces, counts)
@settings(max_examples=30, deadline=None)
def test_total_mass_is_rho_depth_beta_R_t(ratio, embrace, n):
    arch = Arch.from_ratio(ratio, embrace, n, radius=3.0, density=1800.0, depth=0.7)
    expected = 1800.0 * 0.7 * embrace * 3.0 * (ratio * 3.0)  # annulus sector area = beta R t
    assert arch.mass == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("k", [0, 3, 6])
def test_voussoir_properties_match_quadrature(oppenheim, k):
    mass, centroid, inertia = _sector_by_quadrature(oppenheim, k)
    # midpoint rule on a 400 x 400 grid: relative error O(1e-5)
    assert oppenheim.voussoir_masses[k] == pytest.approx(mass, rel=1e-6)
    assert np.allclose(oppenheim.voussoir_centroids[k], centroid, rtol=0, atol=1e-5)
    assert oppenheim.voussoir_inertias[k] == pytest.approx(inertia, rel=1e-4)


def test_joints_are_symmetric_and_radial(oppenheim):
    ip, ep = oppenheim.intrados_points, oppenheim.extrados_points
    n = oppenheim.voussoirs
    assert np.allclose(ip[::-1] * [-1, 1], ip)
    assert np.allclose(np.linalg.norm(ep - ip, axis=1), oppenheim.thickness)
    assert np.allclose(ip[:, 0] * ep[:, 1] - ip[:, 1] * ep[:, 0], 0.0, atol=1e-12)  # radial joints
    assert ip[0, 0] < 0 < ip[n, 0]


def test_span_and_rise(oppenheim):
    b = math.radians(157.5)
    assert oppenheim.span == pytest.approx(20 * math.sin(b / 2))
    assert oppenheim.rise == pytest.approx(10 * (1 - math.cos(b / 2)))


def test_scaled_arch_is_similar(oppenheim):
    big = oppenheim.scaled(2.0)
    assert big.thickness_ratio == pytest.approx(oppenheim.thickness_ratio)
    assert np.allclose(big.voussoir_centroids, 2 * oppenheim.voussoir_centroids)
    # inertia ~ rho * L^2 * L^2 * depth(L): factor 2^5 with depth scaled too
    assert np.allclose(big.voussoir_inertias, 32 * oppenheim.voussoir_inertias)


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        (dict(radius=10, thickness=-1, embrace=1, voussoirs=7), "thickness must be > 0"),
        (dict(radius=10, thickness=20, embrace=1, voussoirs=7), "thickness must be less than 2 x radius"),
        (dict(radius=0, thickness=1, embrace=1, voussoirs=7), "radius must be in [0.001, 10000]"),
        (dict(radius=10, thickness=1, embrace=0, voussoirs=7), "embrace must be in [0.001, 240]"),
        (dict(radius=10, thickness=1, embrace=5, voussoirs=7), "embrace must be in [0.001, 240]"),
        (dict(radius=10, thickness=1, embrace=1, voussoirs=2), "voussoirs must be >= 3"),
        (dict(radius=10, thickness=1, embrace=1, voussoirs=7.5), "voussoirs must be a whole number"),
        (dict(radius="ten", thickness=1, embrace=1, voussoirs=7), "radius must be a number"),
        (dict(radius=float("nan"), thickness=1, embrace=1, voussoirs=7), "radius must be a finite"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, needle):
    with pytest.raises(InvalidParameterError) as info:
        Arch(**kwargs)
    assert needle in str(info.value)
    assert "\n" not in str(info.value)


def test_oppenheim_mechanism_virtual_work(oppenheim):
    # The hinge set found by the limit analysis for Oppenheim's arch (A..D at joints 0,3,5,7).
    faces = (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS)
    mech = HingeMechanism(oppenheim, (0, 3, 5, 7), faces)
    assert mech.load_direction == +1
    assert paper.ONSET_ACCELERATION.within(mech.collapse_acceleration_g)  # p. 2126
    mirror = mech.mirrored()
    assert mirror.joints == (0, 2, 4, 7)
    assert mirror.load_direction == -1
    assert mirror.collapse_acceleration_g == pytest.approx(mech.collapse_acceleration_g, rel=1e-12)
    assert not mech.symmetric


def test_inadmissible_faces_are_rejected(oppenheim):
    with pytest.raises(InvalidParameterError, match="admissible"):
        HingeMechanism(oppenheim, (0, 3, 5, 7), (Face.INTRADOS,) * 4)


def test_centroid_of_a_vanishingly_thin_arch_is_the_circular_arc_centroid():
    """t -> 0: the voussoir is an arc of radius R, centroid at R sin(h)/h (closed form). At the
    thinnest ring an Arch takes (t/R = 1e-6) the exact centroid is R (1 + (t/R)^2 / 12) sin(h)/h:
    8e-14 off, inside the tolerance."""
    arch = Arch(10.0, 1e-5, math.radians(157.5), 7)
    h = 0.5 * arch.voussoir_angle
    assert arch.centroid_radius == pytest.approx(10.0 * math.sin(h) / h, rel=1e-12)


@pytest.mark.parametrize("name", ["density", "depth"])
def test_vanishing_density_or_depth_is_refused_in_one_line(name):
    """density or depth = 1e-300 once divided by zero in the impact solution (issue 15)."""
    kwargs = dict(radius=10, thickness=1.5, embrace=2.7, voussoirs=7)
    with pytest.raises(InvalidParameterError) as info:
        Arch(**kwargs, **{name: 1e-300})
    assert str(info.value).startswith(f"{name} must be in [") and "\n" not in str(info.value)


def test_the_circular_arch_layout_equals_its_closed_forms():
    """Arch's joint ends and outlines through the base class's layout are its closed forms
    (the one chain interface: an Arch read as a generic VoussoirChain gives the same joints)."""
    from archquake.geometry.chain import VoussoirChain

    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    joints, polygons = arch._build_layout()
    np.testing.assert_array_equal(joints[:, 0], arch.intrados_points)
    np.testing.assert_array_equal(joints[:, 1], arch.extrados_points)
    assert len(polygons) == arch.voussoirs
    with pytest.raises(TypeError):
        VoussoirChain()  # abstract: describe, scaled and the layout come from each shape
