"""Shapes of issue 12: the block chain's geometry and limit analysis on every shape.

Oracles: the circular closed forms of ``Arch`` (annular sectors), quadrature of the ring's
area and first moments (scipy), the symmetry of the shapes, the agreement of the two
independent limit-analysis methods (static LP and kinematic virtual work), and published
minimum thicknesses (Milankovitch 0.1075, Makris & Alexakis 2013 0.1095, semicircle).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.errors import InvalidParameterError
from archquake.geometry import (
    SHAPES,
    Arch,
    OnPiers,
    Piers,
    ShapedArch,
    check_tiling,
    circular,
    pointed,
    segmental,
)
from archquake.limit import limit_analysis, min_thickness

# (shape, rise over span) that each builder accepts
CASES = [("circular", 0.5), ("segmental", 0.3), ("pointed", 0.8), ("elliptical", 0.35),
         ("three-centred", 0.35), ("parabolic", 0.4), ("catenary", 0.4)]


@pytest.mark.parametrize("shape, ratio", CASES)
@pytest.mark.parametrize("joints", ["radial", "vertical"])
def test_blocks_tile_the_ring(shape, ratio, joints):
    """No gaps (consecutive blocks share their joint), no overlaps, and the blocks' areas add
    up to the ring's: the polygon bounded by the whole intrados and extrados."""
    arch = ShapedArch(shape, 10.0, 10.0 * ratio, 0.8, 9, joints)
    check_tiling(arch)
    polys = arch.block_polygons
    total = sum(0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
                for p in polys)
    assert math.isclose(total * arch.density * arch.depth, arch.mass, rel_tol=1e-12)
    assert arch.symmetric


def test_circular_shape_equals_the_closed_form_arch():
    """The sampled polygons of a circular ShapedArch against Arch's exact annular sectors:
    the faces are sampled every ~0.02 deg, so the chord sagitta costs ~(0.0003 rad)^2/12 ~ 1e-8
    of the area; joint ends are exact offsets (1e-12)."""
    exact = Arch(10.0, 1.5, math.radians(157.5), 7)
    sampled = ShapedArch("circular", exact.span, exact.rise, 1.5, 7)
    np.testing.assert_allclose(sampled.intrados_points, exact.intrados_points, atol=1e-11)
    np.testing.assert_allclose(sampled.extrados_points, exact.extrados_points, atol=1e-11)
    np.testing.assert_allclose(sampled.voussoir_masses, exact.voussoir_masses, rtol=1e-7)
    np.testing.assert_allclose(sampled.voussoir_centroids, exact.voussoir_centroids, atol=1e-6)
    np.testing.assert_allclose(sampled.voussoir_inertias, exact.voussoir_inertias, rtol=1e-7)
    assert sampled.radius == pytest.approx(10.0, rel=1e-14)


@pytest.mark.parametrize("shape", ["elliptical", "parabolic", "catenary", "three-centred"])
def test_block_areas_equal_thickness_times_centreline_length(shape):
    """Oracle: a ring of constant thickness t between two normals of a smooth centreline has
    area t x (centreline length between them), exactly (the offset-curve formula, t/2 below the
    least radius of curvature). The length comes from scipy quad of |c'(u)| on the analytic
    centreline; the blocks' polygons from the sampled faces. Tolerance 1e-7: the chords."""
    from scipy.integrate import quad

    arch = ShapedArch(shape, 10.0, 3.5, 0.6, 8, "radial")
    a, f = 5.0, 3.5
    if shape == "elliptical":
        speed = lambda u: math.hypot(a * math.sin(u), f * math.cos(u))  # noqa: E731
        half = quad(speed, 0.0, math.pi / 2, epsabs=0, epsrel=1e-13)[0]
    elif shape == "parabolic":
        half = quad(lambda x: math.hypot(1.0, 2 * f * x / a**2), -a, 0.0, epsrel=1e-13)[0]
    elif shape == "catenary":
        k = arch._catenary_k()
        half = quad(lambda x: math.cosh(x / k), -a, 0.0, epsrel=1e-13)[0]
    else:
        r1, r2 = arch._three_centred()
        half = r1 * math.radians(60.0) + r2 * math.radians(30.0)
    areas = arch.voussoir_masses / (arch.density * arch.depth)
    np.testing.assert_allclose(areas, 0.6 * 2 * half / 8, rtol=1e-7)
    # the mirror symmetry of the shape: block k's centroid mirrors block n-1-k's
    c = arch.voussoir_centroids
    np.testing.assert_allclose(c[::-1] * [-1, 1], c, atol=1e-12 * arch.radius)


def test_segmental_from_span_and_rise_is_the_circular_arch():
    """Same R and embrace, built from the engineer's span and rise: equal to round-off."""
    ref = Arch(8.0, 0.6, math.radians(120.0), 11)
    arch = segmental(span=ref.span, rise=ref.rise, thickness=0.6, voussoirs=11)
    assert isinstance(arch, Arch)
    assert arch.radius == pytest.approx(8.0, rel=1e-14)
    assert arch.embrace == pytest.approx(ref.embrace, rel=1e-14)
    np.testing.assert_allclose(arch.voussoir_centroids, ref.voussoir_centroids, atol=1e-13)
    a, b = limit_analysis(arch), limit_analysis(ref)
    assert a.collapse_acceleration_g == pytest.approx(b.collapse_acceleration_g, rel=1e-12)
    assert a.mechanism.joints == b.mechanism.joints


def test_pointed_arch_tends_to_the_semicircle():
    """As the eccentricity goes to 0 the pointed arch becomes the semicircle: lambda and the
    minimum thickness converge to the closed-form Arch's (the difference shrinks with e; at
    e = 1e-6 it is below the faces' sampling error, ~1e-6)."""
    semi = Arch(5.0, 0.8, math.pi, 15)
    lam0 = limit_analysis(semi).collapse_acceleration_g
    diffs = []
    for e in (0.1, 0.01, 1e-6):
        p = pointed(span=10.0, eccentricity=e, thickness=0.8, voussoirs=15)
        diffs.append(abs(limit_analysis(p).collapse_acceleration_g - lam0))
    assert diffs[0] > diffs[1] > diffs[2]
    assert diffs[2] < 1e-6
    tmin0 = min_thickness(Arch(5.0, 0.8, math.pi, 15))
    tmin = min_thickness(pointed(span=10.0, eccentricity=1e-6, thickness=0.8, voussoirs=15))
    assert tmin == pytest.approx(tmin0, rel=1e-5)


@settings(max_examples=12, deadline=None)
@given(
    shape_ratio=st.sampled_from(CASES),
    joints=st.sampled_from(["radial", "vertical"]),
    t_over_span=st.floats(0.06, 0.14),
    n=st.integers(6, 14),
)
def test_static_and_kinematic_agree_on_every_shape(shape_ratio, joints, t_over_span, n):
    """The two independent bounds meet (lower = upper) to 1e-6 on every shape, joint pattern
    and voussoir count (arches too thin to stand, or failing otherwise than by four hinges,
    are skipped: both methods report them)."""
    from archquake.errors import ArchquakeError

    shape, ratio = shape_ratio
    try:
        arch = ShapedArch(shape, 10.0, 10.0 * ratio, 10.0 * t_over_span, n, joints)
        res = limit_analysis(arch, method="both")
    except ArchquakeError:
        return
    assert abs(res.static_collapse_acceleration_g - res.kinematic_collapse_acceleration_g) <= 1e-6


def test_semicircle_min_thickness_radial_and_vertical_joints():
    """200 voussoirs: radial joints give Milankovitch's t/R = 0.1075; vertical joints give
    Makris & Alexakis (2013)'s 0.1095 (their continuum value, vertical stereotomy). Tolerance
    0.0005: the discrete joints (200) against the continuum."""
    radial = min_thickness(ShapedArch("circular", 2.0, 1.0, 0.2, 200, "radial"))
    vertical = min_thickness(ShapedArch("circular", 2.0, 1.0, 0.2, 200, "vertical"))
    assert radial == pytest.approx(0.1075, abs=5e-4)
    assert vertical == pytest.approx(0.1095, abs=5e-4)
    assert vertical > radial


def test_bad_geometry_is_one_line():
    with pytest.raises(InvalidParameterError, match="--rise of a segmental arch"):
        segmental(span=10.0, rise=6.0, thickness=0.5, voussoirs=9)
    with pytest.raises(InvalidParameterError, match="--rise of a pointed arch"):
        pointed(span=10.0, rise=4.0, thickness=0.5, voussoirs=9)
    with pytest.raises(InvalidParameterError, match="--thickness must be less than"):
        ShapedArch("elliptical", 10.0, 1.0, 0.5, 9)
    with pytest.raises(InvalidParameterError, match="--shape must be one of"):
        ShapedArch("gothic", 10.0, 6.0, 0.5, 9)
    with pytest.raises(InvalidParameterError, match="--pier-width"):
        OnPiers(Arch(5.0, 0.6, math.pi, 9), Piers(3.0, 0.3, 2))
    assert set(SHAPES) >= {"circular", "pointed", "segmental", "elliptical", "three-centred",
                           "parabolic", "catenary"}
    assert circular(span=10.0, rise=5.0, thickness=0.5, voussoirs=9).radius == pytest.approx(5.0)


@pytest.mark.parametrize("shape", ["parabolic", "catenary"])
def test_block_centroid_and_inertia_equal_quadrature(shape):
    """Oracle: scipy dblquad over the block in its own curvilinear coordinates (u along the
    analytic centreline, nu along its normal, Jacobian |d(x, y)/d(u, nu)| by central
    differences), independent of the sampled polygon. Left-half blocks of radial joints have
    their joint centres on the centreline at u = 1 + x/(L/2). Tolerance 1e-7 relative: the
    faces' chords (areas agree to ~1e-8)."""
    from scipy.integrate import dblquad

    arch = ShapedArch(shape, 10.0, 4.0, 0.6, 8, "radial")
    mid = arch.joint_mid_points
    half_t = 0.5 * arch.thickness

    def point(u, nu):
        p, n = arch._half(np.array([u]))
        return p[0] + nu * n[0]

    def jac(u, nu):
        h = 1e-6
        du = (point(min(u + h, 1.0), nu) - point(max(u - h, 0.0), nu)) / (min(u + h, 1.0) - max(u - h, 0.0))
        _, n = arch._half(np.array([u]))
        return abs(du[0] * n[0, 1] - du[1] * n[0, 0])

    for k in (0, 2):
        u0, u1 = 1.0 + mid[k, 0] / 5.0, 1.0 + mid[k + 1, 0] / 5.0

        def integral(f, u0=u0, u1=u1):
            return dblquad(lambda nu, u: f(point(u, nu)) * jac(u, nu), u0, u1, -half_t, half_t,
                           epsabs=0, epsrel=1e-11)[0]

        area = integral(lambda p: 1.0)
        c = np.array([integral(lambda p: p[0]), integral(lambda p: p[1])]) / area
        polar = integral(lambda p, c=c: (p[0] - c[0]) ** 2 + (p[1] - c[1]) ** 2)
        cx, cy = c
        rho = arch.density * arch.depth
        assert arch.voussoir_masses[k] == pytest.approx(rho * area, rel=1e-7)
        np.testing.assert_allclose(arch.voussoir_centroids[k], [cx, cy], atol=1e-7 * arch.radius)
        assert arch.voussoir_inertias[k] == pytest.approx(rho * polar, rel=1e-7)
