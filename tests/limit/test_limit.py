"""Equivalent static analysis: the static (lower-bound) and kinematic (upper-bound) methods
held to each other, to the scalar virtual-work reference, and to dimensional analysis."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.errors import ArchquakeError, InvalidParameterError, UnstableArchError
from archquake.geometry import Arch, Face, HingeMechanism
from archquake.limit import (
    MAX_KINEMATIC_VOUSSOIRS,
    collapse_state,
    kinematic_collapse,
    limit_analysis,
    mechanism_multipliers,
    min_thickness_ratio,
    static_collapse,
)
from archquake.validation import paper

FACES = (Face.INTRADOS, Face.EXTRADOS)


def _brute_force(arch: Arch) -> dict:
    """Every admissible mechanism driven by a load towards +x, through HingeMechanism (the
    scalar reference, one mechanism at a time)."""
    out = {}
    for joints in itertools.combinations(range(arch.voussoirs + 1), 4):
        for faces in itertools.product(FACES, repeat=4):
            try:
                mech = HingeMechanism(arch, joints, faces)
            except InvalidParameterError:
                continue
            if mech.load_direction == 1:
                out[(joints, tuple(int(f is Face.EXTRADOS) for f in faces))] = (
                    mech.collapse_acceleration_g
                )
    return out


@pytest.mark.parametrize("ratio, embrace_deg, n", [(0.15, 157.5, 7), (0.12, 180.0, 9),
                                                   (0.25, 130.0, 6), (0.3, 220.0, 8)])
def test_vectorised_enumeration_equals_scalar_reference(ratio, embrace_deg, n):
    """Same admissible set and the same multiplier, mechanism by mechanism (1e-9: round-off
    of two algebraically identical virtual-work sums)."""
    arch = Arch.from_ratio(ratio, math.radians(embrace_deg), n)
    joints, faces, lam = mechanism_multipliers(arch)
    fast = {(tuple(map(int, j)), tuple(map(int, f))): x for j, f, x in zip(joints, faces, lam,
                                                                            strict=True)}
    ref = _brute_force(arch)
    assert fast.keys() == ref.keys()
    assert max(abs(fast[k] - ref[k]) for k in ref) < 1e-9


def test_oppenheim_both_methods(oppenheim):
    """Paper p. 2126: 0.37 g; the two bounds meet (1e-6: the LP's optimality tolerance)."""
    res = limit_analysis(oppenheim, method="both")
    assert paper.ONSET_ACCELERATION.within(res.collapse_acceleration_g)
    assert res.static_collapse_acceleration_g == pytest.approx(
        res.kinematic_collapse_acceleration_g, abs=1e-6)
    assert res.mechanism.joints == (0, 3, 5, 7)
    assert res.mechanism.faces == (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS)
    assert res.mechanism.load_direction == 1
    assert not res.symmetric
    # the brute-force search over HingeMechanism gives the same governing mechanism
    ref = _brute_force(oppenheim)
    best = min(ref, key=ref.get)
    assert best == ((0, 3, 5, 7), (0, 1, 0, 1))
    assert ref[best] == pytest.approx(res.collapse_acceleration_g, abs=1e-12)


def test_collapse_thrust_line_touches_the_four_hinges(oppenheim):
    """At collapse the line of thrust is inside the section everywhere, in compression, and
    on the hinge faces at A, B, C, D; the 4 x 4 hinge equilibrium equals virtual work."""
    res = limit_analysis(oppenheim)
    jf = res.joint_forces
    assert jf.admissible(rtol=1e-9)
    assert np.all(jf.normal > 0)
    for hinge in res.mechanism.hinges:
        assert np.allclose(res.thrust_line[hinge.joint], [hinge.x, hinge.y], atol=1e-9)
    assert collapse_state(res.mechanism)[0] == pytest.approx(
        res.mechanism.collapse_acceleration_g, abs=1e-12)
    # global equilibrium: the two support reactions balance the loads
    total = oppenheim.mass * res.g
    assert np.allclose(jf.force[-1] - jf.force[0],
                       [res.collapse_acceleration_g * total, -total], atol=1e-6 * total)


def test_mirror_load_gives_mirror_mechanism(oppenheim):
    """A load towards -x is resisted by the mirrored mechanism at the same multiplier."""
    mech = limit_analysis(oppenheim).mechanism.mirrored()
    assert mech.load_direction == -1
    assert mech.collapse_acceleration_g == pytest.approx(0.3700097, abs=1e-6)


@st.composite
def enumerable_arches(draw):
    """Arches in the four-hinge regime: embrace 135..240 deg, n <= 12, t/R from just above
    the minimum to 0.3 or 1.5 x the minimum (thick arches of small embrace, e.g. 3 voussoirs, t/R = 0.3 at 130
    degrees, fail instead by lift-off of a springing; see test_lift_off_is_reported)."""
    embrace = math.radians(draw(st.floats(135.0, 240.0)))
    n = draw(st.integers(3, 12))
    t_min = min_thickness_ratio(embrace, n, rtol=1e-4)
    low = max(t_min * 1.02, 0.02)  # three voussoirs stand at any thickness (t_min = 0)
    ratio = low + draw(st.floats(0.0, 1.0)) * (max(0.3, 1.5 * low) - low)
    return Arch.from_ratio(ratio, embrace, n)


@given(enumerable_arches())
@settings(max_examples=40, deadline=None)
def test_static_equals_kinematic(arch):
    """Lower-bound and upper-bound theorems meet at the collapse load (1e-6 absolute in g:
    the LP's optimality tolerance) with the same hinges."""
    lam_s, mech_s = static_collapse(arch)
    lam_k, mech_k = kinematic_collapse(arch)
    assert lam_s == pytest.approx(lam_k, abs=1e-6)
    assert mech_s == mech_k


@given(st.floats(0.5, 50.0), st.floats(500.0, 5000.0), st.floats(0.2, 5.0),
       st.floats(0.12, 0.25), st.floats(140.0, 180.0), st.integers(4, 12))
@settings(max_examples=25, deadline=None)
def test_multiplier_is_independent_of_scale_density_and_depth(radius, density, depth,
                                                                ratio, embrace_deg, n):
    """Equivalent static analysis depends on geometry only (paper p. 2120): lambda is
    dimensionless and every force scales with the weight."""
    embrace = math.radians(embrace_deg)
    ref = limit_analysis(Arch.from_ratio(ratio, embrace, n))
    other = limit_analysis(Arch.from_ratio(ratio, embrace, n, radius=radius, density=density,
                                           depth=depth))
    assert other.collapse_acceleration_g == pytest.approx(ref.collapse_acceleration_g, abs=1e-9)
    assert other.mechanism.joints == ref.mechanism.joints
    assert other.min_friction == pytest.approx(ref.min_friction, rel=1e-7)


def test_too_thin_raises_naming_the_minimum():
    arch = Arch.from_ratio(0.09, math.pi, 40, radius=10.0)
    with pytest.raises(UnstableArchError) as info:
        limit_analysis(arch)
    t_min = min_thickness_ratio(math.pi, 40)
    assert info.value.min_thickness_ratio == pytest.approx(t_min)
    msg = str(info.value)
    assert "\n" not in msg and f"{t_min:.4f}" in msg and f"{t_min * 10:.4g} m" in msg
    with pytest.raises(UnstableArchError):
        limit_analysis(arch, method="kinematic")


def test_stability_threshold_is_sharp():
    """Just above the minimum thickness the arch stands, with a tiny collapse multiplier."""
    t_min = min_thickness_ratio(math.pi, 30)
    res = limit_analysis(Arch.from_ratio(t_min * 1.001, math.pi, 30), method="both")
    assert 0 < res.collapse_acceleration_g < 0.01


def test_lift_off_is_reported():
    """A thick shallow arch fails by lifting off a springing, not by four hinges: the static
    method says so, and the four-hinge mechanisms give a strictly higher upper bound."""
    arch = Arch.from_ratio(0.36, math.radians(111.7), 11)
    with pytest.raises(ArchquakeError, match="opens on both faces"):
        static_collapse(arch)
    lam_k, _ = kinematic_collapse(arch)
    assert lam_k > 3.68  # the static optimum of this arch is 3.680 g


def test_kinematic_refuses_large_n():
    arch = Arch.from_ratio(0.15, math.radians(157.5), MAX_KINEMATIC_VOUSSOIRS + 1)
    with pytest.raises(InvalidParameterError, match="voussoirs <= 60"):
        limit_analysis(arch, method="kinematic")
    res = limit_analysis(arch)  # the static method has no such limit
    assert 0.3 < res.collapse_acceleration_g < 0.4


def test_to_dict_keys(oppenheim):
    d = limit_analysis(oppenheim).to_dict()
    assert {"collapse_acceleration_g", "hinges", "symmetric", "min_friction"} <= d.keys()
    assert [h["face"] for h in d["hinges"]] == ["intrados", "extrados", "intrados", "extrados"]
    assert [h["joint"] for h in d["hinges"]] == [0, 3, 5, 7]


def test_min_thickness_of_a_shape_refuses_an_unbounded_tolerance():
    """rtol <= 0 or nan once never ended, or returned nonsense (issue 15)."""
    from archquake.geometry.shapes import pointed
    from archquake.limit.static import min_thickness

    arch = pointed(span=10.0, rise=7.0, thickness=0.8, voussoirs=12)
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(InvalidParameterError, match="rtol"):
            min_thickness(arch, rtol=bad)
