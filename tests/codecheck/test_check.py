"""The code check of a local mechanism (Circolare 2019 C8.7.1.2.1; 2009 C8A.4).

Oracle: the rocking block of docs/code-check.md ("A worked example"), every number by hand from
the closed forms of the block (alpha(d) = tan(asin(sin beta - d/R)), e* = 1, d0 = b/2) and of
NTC 2018's spectrum written out here branch by branch (T_D < T_SLV < T_E: S_De is
a_g S eta F0 T_C T_D / 4 pi^2, so each capacity a_g is the root of a polynomial in a_g, solved
by numpy.roots, independently of the check's scan and Brent search). Tolerance 1e-9 relative:
the check's Brent search stops at 1e-13 m/s^2 and 4 eps.
"""

import math

import numpy as np
import pytest

from archquake.codecheck.check import (
    KnowledgeLevel,
    Position,
    floor_spectrum,
    kinematic_check,
    peak_demand,
)
from archquake.codecheck.kinematic import RockingBlock, capacity_curve
from archquake.codes.spectra import ntc2018_spectrum
from archquake.errors import InvalidParameterError

G = 9.81
B, H = 0.5, 5.0
FC = 1.35
F0, TC_STAR = 2.4, 0.30
TC = 1.10 * TC_STAR**-0.20 * TC_STAR  # soil B: C_C T_C*


@pytest.fixture(scope="module")
def curve():
    # a 18 kN/m^3 wall 0.5 m thick, 5 m high, 1 m wide: W = 45 kN
    return capacity_curve(RockingBlock.on_base(B, H, density=18000.0 / G), g=G)


@pytest.fixture(scope="module")
def spectrum():
    return ntc2018_spectrum(ag_g=0.25, f0=F0, tc_star_s=TC_STAR, soil="B", g=G)


@pytest.fixture(scope="module")
def result(curve, spectrum):
    spectra = {"SLD": spectrum, "SLV": spectrum, "SLC": spectrum}
    return kinematic_check(curve, spectra, knowledge="LC1")


def _alpha(d):
    beta, radius = math.atan2(B, H), 0.5 * math.hypot(B, H)
    return math.tan(math.asin(math.sin(beta) - d / radius))


def _soil_b(ag_g):
    return min(max(1.40 - 0.40 * F0 * ag_g, 1.0), 1.2)


def test_mechanism_numbers(curve, result):
    assert curve.m_star_kg * G == pytest.approx(45000.0, rel=1e-12)
    assert result.a0_star == pytest.approx(0.1 * G / FC, rel=1e-12)  # 0.7267 m/s^2
    assert result.to_dict()["a0_star_g"] == pytest.approx(0.1 / FC, rel=1e-12)


def test_sld_by_hand(result):
    # a_g S = a0*, with S_S = 1.2 (clipped) for a_g < 0.5 / F0 g
    ag_g = 0.1 / FC / 1.2
    assert _soil_b(ag_g) == 1.2
    c = result.check("SLD", "linear")
    assert c.capacity_ag_g == pytest.approx(ag_g, rel=1e-9)  # 0.0617 g
    assert c.demand == pytest.approx(0.25 * 1.16 * G, rel=1e-12)
    assert c.ratio == pytest.approx(ag_g / 0.25, rel=1e-9)
    assert not c.passes
    lin = result.check("SLV", "linear")
    assert lin.capacity_ag_g == pytest.approx(2 * ag_g, rel=1e-9)  # q = 2: 0.123 g


def _cubic_ag(d, eta, period_factor, fraction):
    """a_g (g) with d = a_g g S(a_g) eta F0 T_C T_D(a_g) / 4 pi^2, T_D = 4 a_g + 1.6, S on the
    sloping branch or clipped at 1.2: the smallest positive real root consistent with S."""
    k = G * eta * F0 * TC / (4 * math.pi**2)
    roots = []
    # S = 1.2: 1.2 k a (4 a + 1.6) = d
    roots += [(r, 1.2) for r in np.roots([4.8 * k, 1.92 * k, -d])]
    # S = 1.4 - 0.96 a: k a (1.4 - 0.96 a)(4 a + 1.6) = d
    roots += [(r, None) for r in np.roots(k * np.array([-3.84, 5.6 - 1.536, 2.24, 0.0]) - [0, 0, 0, d])]
    ok = [r.real for r, s in roots if abs(r.imag) < 1e-12 and r.real > 0
          and (_soil_b(r.real) == 1.2) == (s == 1.2)]
    return min(ok)


@pytest.mark.parametrize("state, fraction, period_factor, damping",
                         [("SLV", 0.4, 1.68, 0.08), ("SLC", 0.6, 1.56, 0.10)])
def test_nonlinear_2019_by_hand(result, state, fraction, period_factor, damping):
    d = fraction * B / 2
    a = _alpha(d) * G / FC
    period = period_factor * math.pi * math.sqrt(d / a)
    eta = math.sqrt(10 / (5 + 100 * damping))
    ag_g = _cubic_ag(d, eta, period_factor, fraction)
    td = 4 * ag_g + 1.6
    assert td < period < 5.0  # the branch the hand formula assumes (T_E = 5 s on soil B)
    c = result.check(state, "nonlinear")
    assert c.capacity == pytest.approx(d, rel=1e-12)
    assert c.period_s == pytest.approx(period, rel=1e-9)
    assert c.damping == damping
    assert c.capacity_ag_g == pytest.approx(ag_g, rel=1e-9)
    # the demand at the site's own a_g (0.25 g, S = 1.16, T_D = 2.6 s): S_De grows as T up
    # to T_D, then stays (a_g S eta F0 T_C min(T, T_D) / 4 pi^2)
    site = 0.25 * G * 1.16 * eta * F0 * TC * min(period, 2.6) / (4 * math.pi**2)
    assert c.demand == pytest.approx(site, rel=1e-9)


def test_worked_example_numbers(result):
    # the numbers of docs/code-check.md, to the digits printed there
    slv = result.check("SLV", "nonlinear")
    assert round(slv.period_s, 3) == 2.532 and round(slv.demand, 3) == 0.161
    assert round(slv.capacity_ag_g, 3) == 0.167
    assert round(result.check("SLC", "nonlinear").period_s, 3) == 3.528


def test_2009_by_hand(curve, spectrum):
    res = kinematic_check(curve, {"SLD": spectrum, "SLV": spectrum}, knowledge="LC1",
                          procedure="2009")
    a0 = 0.1 * G / FC
    d_u = 0.4 * B / 2
    d_s = 0.4 * d_u
    a_s = a0 * (1 - d_s / (B / 2))
    period = 2 * math.pi * math.sqrt(d_s / a_s)  # 1.608 s
    c = res.check("SLV", "nonlinear")
    assert c.period_s == pytest.approx(period, rel=1e-12)
    # T_C < T_s < T_D: S_De = a_g S F0 T_C T_s / 4 pi^2 (5 %), S = 1.2
    ag_g = d_u * 4 * math.pi**2 / (G * 1.2 * F0 * TC * period)
    assert _soil_b(ag_g) == 1.2 and TC < period < 4 * ag_g + 1.6
    assert c.capacity_ag_g == pytest.approx(ag_g, rel=1e-9)
    assert c.demand == pytest.approx(0.25 * G * 1.16 * F0 * TC * period / (4 * math.pi**2),
                                     rel=1e-9)  # 0.117 m > 0.10 m
    assert {(x.limit_state, x.method) for x in res.checks} == {
        ("SLD", "linear"), ("SLV", "linear"), ("SLV", "nonlinear")}


def test_knowledge_levels_scale_capacity(curve, spectrum):
    # FC divides the capacity acceleration: a_g,SLD scales as 1/FC while S_S stays clipped
    sld = {k: kinematic_check(curve, {"SLD": spectrum}, knowledge=k).checks[0].capacity_ag_g
           for k in ("LC1", "LC2", "LC3")}
    assert sld["LC3"] / sld["LC1"] == pytest.approx(1.35, rel=1e-9)
    assert sld["LC3"] / sld["LC2"] == pytest.approx(1.20, rel=1e-9)
    assert KnowledgeLevel.LC2.confidence_factor == 1.20


def test_floor_spectrum_c7_2_11(spectrum):
    pos = Position(6.0, 12.0, 0.4)  # T1 < 0.5 s: a = 0.8, b = 1.4, a_p = 5
    top = spectrum.pga * 1.5 * 5.0
    assert peak_demand(spectrum, pos) == pytest.approx(spectrum.pga * 1.5, rel=1e-12)
    assert floor_spectrum(spectrum, 0.4, pos)[0] == pytest.approx(top, rel=1e-12)
    t = 0.5 * 0.8 * 0.4
    assert floor_spectrum(spectrum, t, pos)[0] == pytest.approx(top / (1 + 4 * 0.25), rel=1e-12)
    assert floor_spectrum(spectrum, 20.0, pos)[0] == pytest.approx(spectrum.pga, rel=1e-12)


def test_at_height_demands_more(curve, spectrum):
    ground = kinematic_check(curve, {"SLV": spectrum})
    high = kinematic_check(curve, {"SLV": spectrum}, position=Position(8.0, 10.0, 0.6))
    for key in (("SLV", "linear"), ("SLV", "nonlinear")):
        assert high.check(*key).capacity_ag_g < ground.check(*key).capacity_ag_g
    # rigidly restrained activation at height: a_g S (1 + Z/H) = a0*
    assert high.check("SLV", "linear").capacity_ag_g == pytest.approx(
        ground.check("SLV", "linear").capacity_ag_g / 1.8, rel=1e-9)


@pytest.mark.parametrize("kwargs, match", [
    ({"knowledge": "LC4"}, "knowledge level must be one of LC1, LC2, LC3"),
    ({"procedure": "2008"}, "procedure must be 2019 or 2009"),
])
def test_bad_input(curve, spectrum, kwargs, match):
    with pytest.raises(InvalidParameterError, match=match):
        kinematic_check(curve, {"SLV": spectrum}, **kwargs)


def test_bad_position():
    with pytest.raises(InvalidParameterError, match=r"height must be in \[0, 10\] m"):
        Position(12.0, 10.0, 0.5)
    with pytest.raises(InvalidParameterError, match="needs the building's height"):
        Position(5.0)


def test_2009_linear_slv_by_hand(curve, spectrum):
    # a0* >= a_g S / q: a_g S(a_g) = 2 a0* = 1.4533 m/s^2; with S = 1.4 - 0.96 a_g (a_g in g)
    # above 0.2083 g: 0.96 a^2 - 1.4 a + 2 a0*/g = 0 (smaller root), if S is not clipped there
    res = kinematic_check(curve, {"SLV": spectrum}, procedure="2009")
    target = 2 * 0.1 / FC
    clipped = target / 1.2
    if _soil_b(clipped) == 1.2:
        ag_g = clipped
    else:
        ag_g = (1.4 - math.sqrt(1.96 - 4 * 0.96 * target)) / (2 * 0.96)
    assert res.check("SLV", "linear").capacity_ag_g == pytest.approx(ag_g, rel=1e-9)
    assert res.check("SLV", "linear").capacity == pytest.approx(2 * 0.1 * G / FC, rel=1e-12)


def test_governing_check_per_limit_state(result):
    # the nonlinear check governs SLV (0.167 g beats the linear 0.123 g here); SLD is linear
    gov = {c.limit_state: c for c in result.governing}
    assert set(gov) == {"SLD", "SLV", "SLC"}
    assert gov["SLV"].method == "nonlinear" and gov["SLD"].method == "linear"
    assert result.passes is all(c.passes for c in gov.values())
