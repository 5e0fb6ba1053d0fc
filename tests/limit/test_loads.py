"""Limit analysis with what the arch carries: fill, backing, loads on the extrados, traffic.

Oracles: the bare arch (no loads), a scaling law (masonry and fill densities together), the
two bounds against each other, closed-form fill areas, and a hand calculation of the virtual
work of the fill columns integrated by quadrature on the circular extrados.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from archquake.errors import InvalidParameterError
from archquake.geometry import Arch, segmental
from archquake.geometry.loads import (
    Backing,
    DistributedLoad,
    Fill,
    Loads,
    PointLoad,
    Traffic,
    block_extras,
)
from archquake.geometry.planar import perp
from archquake.limit import limit_analysis
from archquake.limit.capacity import capacity_scan, traffic_capacity

G = 9.80665
BRIDGE = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)  # examples/bridge.toml's semicircle


def fill(depth=1.0, density=1800.0):
    return Loads(fill=Fill(depth=depth, density=density))


# ------------------------------------------------------------------ the bare arch
@pytest.mark.parametrize("method", ["static", "kinematic", "both"])
@pytest.mark.parametrize("arch", [BRIDGE, Arch(10.0, 1.5, math.radians(157.5), 7)])
def test_no_loads_and_weightless_fill_give_the_bare_arch(arch, method):
    """Oracle: the bare analysis (another code path); 1e-12 relative: both solve the same 4 x 4
    equilibrium through the same hinges, scaled differently (rounding only)."""
    bare = limit_analysis(arch, method=method)
    for loads in (Loads(), fill(1.0, 0.0)):
        res = limit_analysis(arch, method=method, loads=loads)
        assert res.mechanism.joints == bare.mechanism.joints
        assert res.collapse_acceleration_g == pytest.approx(bare.collapse_acceleration_g,
                                                            rel=1e-12)
        np.testing.assert_allclose(res.thrust_line, bare.thrust_line, rtol=0, atol=1e-12 * 10)


def test_scaling_masonry_and_fill_densities_together_leaves_lambda():
    """Oracle: body forces only, so lambda depends on the density ratio alone (exact law;
    1e-10 for rounding)."""
    ref = limit_analysis(BRIDGE, method="both", loads=fill(0.8, 1800.0)).collapse_acceleration_g
    for k in (0.25, 3.0):
        arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0 * k)
        lam = limit_analysis(arch, method="both",
                             loads=fill(0.8, 1800.0 * k)).collapse_acceleration_g
        assert lam == pytest.approx(ref, rel=1e-10)
    # a traffic load is not a body force: it breaks the law (the check can fail)
    light = traffic_capacity(Arch(5.0, 0.6, math.pi, 15, 1.0, 900.0), fill(0.8, 900.0),
                             Traffic(100e3, 2.5)).multiplier
    heavy = traffic_capacity(BRIDGE, fill(0.8, 1800.0), Traffic(100e3, 2.5)).multiplier
    assert heavy == pytest.approx(2 * light, rel=1e-10)


# ------------------------------------------------------------------ the two bounds
@pytest.mark.parametrize("arch", [
    BRIDGE,
    Arch(5.0, 0.75, math.radians(157.5), 15, 1.0, 1800.0),
    segmental(span=8.0, rise=2.0, thickness=0.45, voussoirs=16, density=2000.0),
])
@pytest.mark.parametrize("loads", [
    fill(0.5),
    Loads(fill=Fill(depth=1.0), backing=Backing(0.5, 0.3)),
    Loads(fill=Fill(depth=0.3), point_loads=(PointLoad(2.0, 20e3),),
          distributed_loads=(DistributedLoad(0.5, 3.0, 5e3, moves_with_arch=False),)),
])
def test_static_and_kinematic_bounds_agree_with_loads(arch, loads):
    """Oracle: lower bound = upper bound (the uniqueness theorem); 1e-7 relative is the linear
    program's optimality tolerance."""
    res = limit_analysis(arch, method="both", loads=loads)
    assert res.static_collapse_acceleration_g == pytest.approx(
        res.kinematic_collapse_acceleration_g, rel=1e-7)
    assert res.joint_forces.admissible(rtol=1e-7) or np.any(res.carried.held)
    held = np.flatnonzero(res.carried.held)
    assert not set(res.mechanism.joints) & set(held.tolist())
    span = arch.intrados_points[-1, 0] - arch.intrados_points[0, 0]
    for pos in (0.25 * span, 0.4 * span):
        cap = traffic_capacity(arch, loads, Traffic(50e3, pos, dispersion=30.0), method="both")
        assert cap.static_multiplier == pytest.approx(cap.kinematic_multiplier, rel=1e-7)
        assert cap.multiplier > 0


# ------------------------------------------------------------------ the hand calculation
def _hand_lambda(arch: Arch, depth: float, density: float, mechanism) -> float:
    """Virtual work of the voussoirs and of the fill columns (quadrature on the circle
    x^2 + y^2 = Re^2) in the mechanism's opening motion: lambda = sum m v_y / sum m v_x."""
    num, den = _hand_work(arch, depth, density, mechanism)
    return num / den


def _hand_work(arch: Arch, depth: float, density: float, mechanism) -> tuple[float, float]:
    """(sum m v_y, sum m v_x) of the voussoirs and the fill columns, kg m/s per unit rate."""
    re = arch.extrados_radius
    ys = re + depth
    ye = lambda x: math.sqrt(max(re * re - x * x, 0.0))  # noqa: E731
    xe = arch.extrados_points[:, 0]
    masses, cents = [], []
    for k in range(arch.voussoirs):
        a, b = xe[k], xe[k + 1]
        area = quad(lambda x: ys - ye(x), a, b, epsabs=1e-13)[0]
        mx = quad(lambda x: x * (ys - ye(x)), a, b, epsabs=1e-13)[0]
        my = quad(lambda x: 0.5 * (ys * ys - ye(x) ** 2), a, b, epsabs=1e-13)[0]
        masses.append(density * arch.depth * area)
        cents.append((mx / area, my / area))
    fill_m, fill_c = np.array(masses), np.array(cents)
    pts = mechanism.points
    w = mechanism.rates
    vb = w[0] * perp(pts[1] - pts[0])
    num = den = 0.0
    for link, rng in enumerate(mechanism.link_voussoirs):
        pivot = pts[(0, 1, 3)[link]]
        for k in rng:
            for m, c in ((arch.voussoir_masses[k], arch.voussoir_centroids[k]),
                         (fill_m[k], fill_c[k])):
                v = w[link] * perp(np.asarray(c) - pivot) + (vb if link == 1 else 0.0)
                num += m * v[1]
                den += m * v[0]
    return num, den


@pytest.mark.parametrize(("arch", "bare_g", "change"), [
    (BRIDGE, 0.049, +0.68),                                           # the example bridge
    (Arch(5.0, 0.75, math.radians(157.5), 15, 1.0, 1800.0), 0.356, -0.25),  # thick, t/R 0.15
])
def test_one_metre_of_fill_against_a_hand_calculation(arch, bare_g, change):
    """Oracle: the hand calculation above, for the hinges the analysis finds (1e-5: the
    extrados is sampled every 0.05 degrees in the blocks' outlines); and the change that an
    independent hand check found: +68 % on the semicircle of t/R 0.12, about -25 % on the
    thick arch of 157.5 degrees (2 percentage points: its rounding)."""
    bare = limit_analysis(arch, method="both").collapse_acceleration_g
    res = limit_analysis(arch, method="both", loads=fill(1.0, 1800.0))
    lam = res.collapse_acceleration_g
    assert lam == pytest.approx(_hand_lambda(arch, 1.0, 1800.0, res.mechanism), rel=1e-5)
    assert bare == pytest.approx(bare_g, abs=5e-4)
    assert lam / bare - 1 == pytest.approx(change, abs=0.02)
    # symmetric fill: the load towards -x gives the mirror mechanism
    assert res.opposite_collapse_acceleration_g == pytest.approx(lam, rel=1e-9)


def test_fill_area_is_the_closed_form():
    """Oracle: the area between a semicircular extrados and a line d above its crown is
    2 Re (Re + d) - pi Re^2 / 2 (1e-6: the sampled arcs)."""
    ex = block_extras(BRIDGE, fill(1.0, 1800.0))
    re = BRIDGE.extrados_radius
    assert ex.mass.sum() / 1800.0 == pytest.approx(2 * re * (re + 1.0) - math.pi * re**2 / 2,
                                                   rel=1e-6)
    # symmetric columns
    np.testing.assert_allclose(ex.mass, ex.mass[::-1], rtol=1e-12)


# ------------------------------------------------------------------ backing and loads
def test_backing_holds_the_joints_below_its_top():
    """A backing below the first joint's extrados end changes nothing; a higher one holds the
    joints below it, which never hinge, and stiffens the arch (lambda rises)."""
    bare = limit_analysis(BRIDGE, method="both", loads=fill(0.5))
    low = limit_analysis(BRIDGE, method="both", loads=Loads(fill=Fill(depth=0.5),
                                                                 backing=Backing(0.0)))
    assert low.collapse_acceleration_g == bare.collapse_acceleration_g
    high = limit_analysis(BRIDGE, method="both", loads=Loads(fill=Fill(depth=0.5),
                                                                  backing=Backing(2.5)))
    held = set(np.flatnonzero(high.carried.held).tolist())
    assert held == {0, 1, 2, 13, 14, 15}
    assert not held & set(high.mechanism.joints)
    assert high.collapse_acceleration_g > bare.collapse_acceleration_g


def test_an_unsymmetric_load_differs_by_direction():
    """A wall on the right haunch: the two directions of the earthquake differ; a load that
    does not move with the arch adds weight but no inertia."""
    moving = Loads(fill=Fill(depth=0.5), point_loads=(PointLoad(7.0, 30e3),))
    still = Loads(fill=Fill(depth=0.5), point_loads=(PointLoad(7.0, 30e3, False),))
    a = limit_analysis(BRIDGE, method="both", loads=moving)
    b = limit_analysis(BRIDGE, method="both", loads=still)
    assert a.collapse_acceleration_g != pytest.approx(a.opposite_collapse_acceleration_g,
                                                      rel=1e-3)
    assert b.collapse_acceleration_g != pytest.approx(a.collapse_acceleration_g, rel=1e-6)


# ------------------------------------------------------------------ along the span
def test_a_dispersed_load_multiplier_is_continuous_along_the_span():
    """Oracle: continuity. Halving the step halves the largest jump between neighbours (a
    Lipschitz function), and the least multiplier of the scan equals the one found again at
    its critical position."""
    loads = fill(0.5)
    traffic = Traffic(100e3, 0.0, dispersion=26.57)
    coarse = capacity_scan(BRIDGE, loads, traffic, np.linspace(1.0, 8.4, 75))
    fine = capacity_scan(BRIDGE, loads, traffic, np.linspace(1.0, 8.4, 149))
    jump_c = np.max(np.abs(np.diff(coarse.multipliers)))
    jump_f = np.max(np.abs(np.diff(fine.multipliers)))
    assert jump_f < 0.6 * jump_c
    assert coarse.adequacy_factor == pytest.approx(coarse.multipliers.min(), rel=1e-9)


@pytest.mark.parametrize("arch", [BRIDGE, Arch(5.0, 0.75, math.radians(157.5), 15, 1.0,
                                                   1800.0)])
@pytest.mark.parametrize("loads", [Loads(), fill(0.5)])
def test_an_axle_multiplier_is_continuous_across_the_joint_ends(arch, loads):
    """An undispersed axle passes from one block to the next where it crosses a joint's
    extrados end. Oracle: continuity; 0.2 um either side of every joint end on the clear span
    the multipliers agree to 1e-5 (the slope times 0.4 um is below 1e-6)."""
    span = arch.intrados_points[-1, 0] - arch.intrados_points[0, 0]
    ends = arch.extrados_points[:, 0] - arch.intrados_points[0, 0]
    ends = ends[(ends > 1e-6) & (ends < span - 1e-6)]
    pos = np.column_stack([ends - 2e-7, ends + 2e-7]).ravel()
    mu = capacity_scan(arch, loads, Traffic(50e3), pos).multipliers.reshape(-1, 2)
    np.testing.assert_allclose(mu[:, 0], mu[:, 1], rtol=1e-5)


def test_capacity_scales_inversely_with_the_traffic_load():
    """mu P is the collapse load: it does not depend on P (exact)."""
    a = traffic_capacity(BRIDGE, fill(0.5), Traffic(50e3, 2.4))
    b = traffic_capacity(BRIDGE, fill(0.5), Traffic(200e3, 2.4))
    assert a.collapse_load_N_m == pytest.approx(b.collapse_load_N_m, rel=1e-10)


@pytest.mark.parametrize(("make", "name"), [
    (lambda: Fill(depth=-1.0), "fill depth"),
    (lambda: Fill(depth=1.0, density=-5.0), "fill density"),
    (lambda: Fill(), "fill"),
    (lambda: Backing(-0.1), "backing height"),
    (lambda: PointLoad(-1.0, 1e3), "point load position"),
    (lambda: DistributedLoad(3.0, 1.0, 1e3), "distributed load end"),
    (lambda: Traffic(0.0), "traffic load"),
    (lambda: Traffic(1e3, 1.0, dispersion=80.0), "traffic dispersion"),
])
def test_bad_loads_name_themselves(make, name):
    with pytest.raises(InvalidParameterError, match=name):
        make()


def test_a_position_beyond_the_span_is_refused():
    with pytest.raises(InvalidParameterError, match="traffic position must be from 0 to the "
                                                    "clear span"):
        traffic_capacity(BRIDGE, Loads(), Traffic(1e3, 20.0))


# ------------------------------------------------------------------ surveys and study files
def test_a_surveyed_arch_carries_the_same_loads():
    """Oracle: the same arch given as blocks (a survey) and as the circular closed form: the
    same lambda and capacity with a fill level and a point load by position (1e-6: the survey's
    outlines are the sampled arcs, its mass properties the polygons')."""
    from archquake.geometry.survey import chain_from_polygons

    survey = chain_from_polygons(BRIDGE.block_polygons, depth=1.0, density=1800.0)
    level = BRIDGE.extrados_radius + 0.7
    for arch in (BRIDGE, survey):
        assert Loads(fill=Fill(level=level)).fill.surface(arch) == pytest.approx(level)
    loads_a = Loads(fill=Fill(depth=0.7), point_loads=(PointLoad(6.5, 20e3),))
    loads_s = Loads(fill=Fill(level=level), point_loads=(PointLoad(6.5, 20e3),))
    a = limit_analysis(BRIDGE, method="both", loads=loads_a)
    s = limit_analysis(survey, method="both", loads=loads_s)
    assert s.collapse_acceleration_g == pytest.approx(a.collapse_acceleration_g, rel=1e-6)
    assert s.mechanism.joints == a.mechanism.joints
    ca = traffic_capacity(BRIDGE, loads_a, Traffic(80e3, 3.0, dispersion=30.0))
    cs = traffic_capacity(survey, loads_s, Traffic(80e3, 3.0, dispersion=30.0))
    assert cs.multiplier == pytest.approx(ca.multiplier, rel=1e-6)
    with pytest.raises(InvalidParameterError, match="fill level must be at or above"):
        Fill(level=level - 1.0).surface(survey)


def test_a_loads_table_reads_the_clis_units():
    from archquake.errors import StudyFileError
    from archquake.geometry.loads import loads_from_table

    loads = loads_from_table({
        "fill_depth": 1.0, "fill_density": 1900, "backing": 1.2, "backing_right": 0.8,
        "point_loads": [{"position": 7.0, "load_kN": 30.0, "moves_with_arch": False}],
        "distributed_loads": [{"start": 1.0, "end": 3.0, "load_kN_m": 10.0}],
        "traffic": {"patch_kN": 100.0, "patch_length": 0.3, "position": 2.5,
                    "dispersion_deg": 26.57}, "passive": 0.33, "fill_friction_deg": 35})
    assert loads.passive is not None and loads.passive.friction == 35.0
    assert loads.fill == Fill(depth=1.0, density=1900.0)
    assert loads.backing == Backing(1.2, 0.8)
    assert loads.point_loads == (PointLoad(7.0, 30e3, False),)
    assert loads.distributed_loads == (DistributedLoad(1.0, 3.0, 10e3),)
    assert loads.traffic == Traffic(100e3, 2.5, 0.3, 26.57)
    for table, key in (({"fill_depth": -1}, "fill depth"), ({"fil_depth": 1}, "fil_depth"),
                       ({"traffic": {"axle_kN": 1, "patch_kN": 2}}, "traffic"),
                       ({"point_loads": [{"position": 1}]}, "point_loads")):
        with pytest.raises(StudyFileError, match=r"\[loads\].*" + key):
            loads_from_table(table)


def test_min_thickness_with_fill():
    """Oracle: the bare minimum thickness without loads (to the bisection's 1e-7), and the
    definition: at t_min a line of thrust fits with the fill, 0.1 % thinner it does not."""
    from archquake.limit import min_thickness
    from archquake.limit.loaded import min_thickness_loaded, seismic_case, stands

    bare = min_thickness(BRIDGE)
    assert min_thickness_loaded(BRIDGE, Loads()) == pytest.approx(bare, rel=1e-6)
    loads = fill(1.0)
    t_min = min_thickness_loaded(BRIDGE, loads)
    assert t_min < 0.9 * bare  # the haunch fill helps this semicircle (0.087 R against 0.106 R)
    assert stands(seismic_case(BRIDGE.with_thickness(t_min), loads))
    assert not stands(seismic_case(BRIDGE.with_thickness(0.999 * t_min), loads))


# ------------------------------------------------------------------ passive fill pressure
def _velocity_x(mechanism, k: int, y: np.ndarray) -> np.ndarray:
    """Horizontal velocity of points at heights y on block k (per unit opening rate)."""
    pts, w = mechanism.points, mechanism.rates
    for link, rng in enumerate(mechanism.link_voussoirs):
        if k in rng:
            pivot = pts[(0, 1, 3)[link]]
            base = w[0] * perp(pts[1] - pts[0])[0] if link == 1 else 0.0
            return base - w[link] * (y - pivot[1])
    return np.zeros_like(y)


def _hand_passive(arch: Arch, depth: float, density: float, fraction: float, phi_deg: float,
                  mechanism) -> float:
    """Power the passive pressure absorbs: on each block's face turned to the left and to the
    right, integral of sigma_h(y) v_x(y) dy (trapezoid on 2000 points of the circle), counted
    where the face moves into the fill."""
    re = arch.extrados_radius
    ys = re + depth
    kp = math.tan(math.radians(45 + phi_deg / 2)) ** 2
    coeff = fraction * kp * density * G * arch.depth
    absorbed = 0.0
    a = arch.joint_angles
    for k in range(arch.voussoirs):
        ang = np.linspace(a[k], a[k + 1], 2001)
        x, y = re * np.cos(ang), re * np.sin(ang)
        for face in (x < 0, x > 0):  # faces left (towards -x), faces right
            if face.sum() < 2:
                continue
            yy = y[face]
            order = np.argsort(yy)
            yy = yy[order]
            work = np.trapezoid(coeff * (ys - yy) * _velocity_x(mechanism, k, yy), yy)
            direction = 1.0 if x[face][0] < 0 else -1.0
            absorbed += max(0.0, -direction * work)
    return absorbed


@pytest.mark.parametrize("fraction", [0.33, 1.0])
def test_passive_pressure_against_a_hand_calculation(fraction):
    """Oracle: virtual work with the passive pressure integrated on the circular extrados of
    each face (1e-5: the sampled outlines); both bounds agree (1e-7); off, nothing changes."""
    from archquake.geometry.loads import Passive

    off = limit_analysis(BRIDGE, method="both", loads=fill(0.5))
    loads = Loads(fill=Fill(depth=0.5), passive=Passive(fraction, 30.0))
    res = limit_analysis(BRIDGE, method="both", loads=loads)
    assert res.static_collapse_acceleration_g == pytest.approx(
        res.kinematic_collapse_acceleration_g, rel=1e-7)
    num, den = _hand_work(BRIDGE, 0.5, 1800.0, res.mechanism)
    absorbed = _hand_passive(BRIDGE, 0.5, 1800.0, fraction, 30.0, res.mechanism)
    assert res.collapse_acceleration_g == pytest.approx((num + absorbed / G) / den, rel=1e-5)
    assert res.collapse_acceleration_g > off.collapse_acceleration_g
    cap_off = traffic_capacity(BRIDGE, fill(0.5), Traffic(100e3, 2.5))
    cap = traffic_capacity(BRIDGE, loads, Traffic(100e3, 2.5), method="both")
    assert cap.static_multiplier == pytest.approx(cap.kinematic_multiplier, rel=1e-7)
    assert cap.multiplier > cap_off.multiplier


def test_passive_pressure_can_make_a_five_hinge_collapse():
    """With passive pressure the fill's resistance is convex in the motion, so a load at the
    crown collapses the arch by two four-hinge mechanisms at once. Oracles: the lower-bound
    theorem (the program's line of thrust at its multiplier is admissible everywhere) and the
    upper bound (the least four-hinge mechanism is not below it)."""
    from archquake.geometry.loads import Passive

    loads = Loads(fill=Fill(depth=0.5), passive=Passive(0.33, 30.0))
    cap = traffic_capacity(BRIDGE, loads, Traffic(100e3, 4.7, dispersion=26.57), method="both")
    assert cap.hinge_count == 5
    assert cap.kinematic_multiplier > cap.static_multiplier * (1 + 1e-4)
    assert cap.multiplier == cap.static_multiplier
    assert cap.joint_forces.admissible(rtol=1e-6)
    with pytest.raises(InvalidParameterError, match="more than four hinges"):
        traffic_capacity(BRIDGE, loads, Traffic(100e3, 4.7), method="kinematic")


def test_friction_demand_leaves_out_the_joints_the_backing_holds():
    res = limit_analysis(BRIDGE, method="both", loads=Loads(fill=Fill(depth=1.0),
                                                                backing=Backing(1.5)))
    held = np.flatnonzero(res.carried.held)
    assert held.size and np.all(np.isnan(res.friction_ratios[held]))
    assert res.min_friction_joint not in held
    free = np.delete(res.joint_forces.friction_ratio, held)
    assert res.min_friction == pytest.approx(float(np.max(free)), rel=1e-15)


# ------------------------------------------------------------------ Boussinesq dispersion
def test_boussinesq_spread_against_quadrature():
    """Oracle: Flamant's sigma_z = 2 P z^3 / (pi (d^2 + z^2)^2) at the extrados's depth,
    integrated by adaptive quadrature over each block's column on the circle and scaled to the
    whole load (1e-4: the 400-point trapezoid); every newton of the axle reaches the arch."""
    from archquake.geometry.loads import traffic_actions

    loads = fill(0.5)
    traffic = Traffic(100e3, 3.1, boussinesq=True)
    force, moment, _ = traffic_actions(BRIDGE, loads, traffic)
    assert -force[:, 1].sum() == pytest.approx(100e3, rel=1e-12)
    re = BRIDGE.extrados_radius
    ys = re + 0.5
    x0 = BRIDGE.intrados_points[0, 0] + 3.1
    edges = BRIDGE.extrados_points[:, 0]

    def sigma(x):
        z = ys - math.sqrt(max(re * re - x * x, 0.0))
        return 2 / math.pi * z**3 / ((x - x0) ** 2 + z * z) ** 2

    parts = [quad(sigma, a, b, epsabs=1e-12, limit=200)[0] for a, b in zip(edges[:-1], edges[1:])]
    arms = [quad(lambda x: x * sigma(x), a, b, epsabs=1e-12, limit=200)[0]
            for a, b in zip(edges[:-1], edges[1:])]
    share = 100e3 * np.array(parts) / sum(parts)
    np.testing.assert_allclose(-force[:, 1], share, rtol=1e-4, atol=1e-3)
    np.testing.assert_allclose(-moment, 100e3 * np.array(arms) / sum(parts), rtol=1e-4, atol=1e-2)


def test_boussinesq_capacity_bounds_and_symmetry():
    """Both bounds agree; a load and its mirror image along the span give one multiplier."""
    loads = fill(0.5)
    a = traffic_capacity(BRIDGE, loads, Traffic(100e3, 2.0, boussinesq=True), method="both")
    b = traffic_capacity(BRIDGE, loads, Traffic(100e3, 9.4 - 2.0, boussinesq=True))
    assert a.static_multiplier == pytest.approx(a.kinematic_multiplier, rel=1e-7)
    assert a.multiplier == pytest.approx(b.multiplier, rel=1e-9)
    with pytest.raises(InvalidParameterError, match="not both"):
        Traffic(100e3, dispersion=30.0, boussinesq=True)
