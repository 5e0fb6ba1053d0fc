"""NTC 2018 and EN 1998-1 elastic spectra against the code formulas written out by hand, and
their invariants (continuity at the corners, the plateau) over the whole parameter space.

Oracle: each branch of the code's equations evaluated in closed form here, at the corner periods
and between them (NTC 2018 eqs. 3.2.2-3.2.12, Tab. 3.2.IV-VII; EN 1998-1 eqs. 3.2-3.12, Tab.
3.2-3.4). Tolerances are floating-point (rel 1e-12) where the same arithmetic is done in another
order, and the notes' printed digits (half a unit in the last digit) for the worked site.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.codes import (
    NTCHazard,
    damping_factor,
    ec8_spectrum,
    ntc2018_soil_factors,
    ntc2018_spectrum,
    return_period_years,
)
from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import InvalidParameterError

REL = 1e-12


def _ntc_closed_form(t, ag, s, f0, tb, tc, td, eta=1.0):
    """NTC 2018 eq. 3.2.2 as printed (a_g in m/s^2)."""
    if t < tb:
        return ag * s * eta * f0 * (t / tb + (1.0 / (eta * f0)) * (1.0 - t / tb))
    if t < tc:
        return ag * s * eta * f0
    if t < td:
        return ag * s * eta * f0 * tc / t
    return ag * s * eta * f0 * tc * td / t**2


def _ec8_closed_form(t, ag, s, tb, tc, td, eta=1.0):
    """EN 1998-1 eqs. 3.2-3.5 as printed."""
    if t <= tb:
        return ag * s * (1.0 + t / tb * (2.5 * eta - 1.0))
    if t <= tc:
        return ag * s * eta * 2.5
    if t <= td:
        return ag * s * eta * 2.5 * tc / t
    return ag * s * eta * 2.5 * tc * td / t**2


# ---------------------------------------------------------------------------------------------
def test_worked_site_of_the_notes():
    """Notes §1.9: a_g 0.25 g, F0 2.4, T_C* 0.30 s, soil B, T1 -> S_S 1.16, C_C 1.3995, T_B 0.140,
    T_C 0.420, T_D 2.60 s, plateau 0.696 g (printed to 3-4 digits)."""
    spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
    s_s, c_c = ntc2018_soil_factors("B", ag_g=0.25, f0=2.4, tc_star_s=0.30)
    assert s_s == pytest.approx(1.16, abs=5e-3)
    assert c_c == pytest.approx(1.3995, abs=5e-5)
    assert spec.S == pytest.approx(1.16, abs=5e-3)
    assert spec.TB == pytest.approx(0.140, abs=5e-4)
    assert spec.TC == pytest.approx(0.420, abs=5e-4)
    assert spec.TD == pytest.approx(2.60, abs=5e-3)
    assert spec.sa(0.3)[0] / G == pytest.approx(0.696, abs=5e-4)
    # the notes' S_De(2.532 s; 8 %) = 0.161 m with g = 9.81: our g is 9.80665 (0.04 % apart)
    assert spec.sd(2.532, damping=0.08)[0] == pytest.approx(0.161, abs=5e-4)


def test_worked_site_at_the_capacity_ag_reclips_S_S():
    """Notes §1.9: at a_g = 0.167 g, S_S = 1.40 - 0.40 * 2.4 * 0.167 = 1.24 is clipped to 1.20."""
    spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
    other = spec.with_ag(0.167 * G)
    assert other.S == 1.20
    assert other.TD == pytest.approx(4 * 0.167 + 1.6, rel=REL)
    assert other.TC == spec.TC and other.F0 == spec.F0
    assert other.ag == pytest.approx(0.167 * G, rel=REL)


@pytest.mark.parametrize("soil", ["A", "B", "C", "D", "E"])
@pytest.mark.parametrize("damping", [0.05, 0.02, 0.10, 0.40])
def test_ntc_horizontal_branches_at_and_between_corners(soil, damping):
    ag_g, f0, tcs = 0.18, 2.5, 0.35
    spec = ntc2018_spectrum(ag_g=ag_g, f0=f0, tc_star_s=tcs, soil=soil, topography="T2")
    s_s, c_c = ntc2018_soil_factors(soil, ag_g=ag_g, f0=f0, tc_star_s=tcs)
    tc = c_c * tcs
    tb, td = tc / 3, 4 * ag_g + 1.6
    assert spec.S == pytest.approx(s_s * 1.2, rel=REL)
    assert (spec.TB, spec.TC, spec.TD) == pytest.approx((tb, tc, td), rel=REL)
    eta = max(math.sqrt(10 / (5 + 100 * damping)), 0.55)
    periods = [0.0, tb / 2, tb, (tb + tc) / 2, tc, (tc + td) / 2, td, 2 * td, 10.0]
    expected = [_ntc_closed_form(t, ag_g * G, s_s * 1.2, f0, tb, tc, td, eta) for t in periods]
    np.testing.assert_allclose(spec.sa(periods, damping), expected, rtol=REL)
    assert spec.sa(0.0)[0] == pytest.approx(ag_g * G * spec.S, rel=REL)   # PGA at T = 0


@pytest.mark.parametrize(("soil", "ag_g", "f0", "bound"), [
    ("B", 0.02, 2.2, 1.20),   # 1.40 - 0.40 * 0.044 = 1.38 -> 1.20
    ("B", 1.00, 2.5, 1.00),   # 1.40 - 1.00 = 0.40 -> 1.00
    ("C", 0.02, 2.2, 1.50),   # 1.70 - 0.6 * 0.044 -> 1.50
    ("C", 1.00, 2.5, 1.00),
    ("D", 0.02, 2.2, 1.80),
    ("D", 1.00, 2.5, 0.90),   # 2.40 - 3.75 -> 0.90
    ("E", 0.02, 2.2, 1.60),
    ("E", 1.00, 2.5, 1.00),
])
def test_ntc_soil_amplification_clipped_at_its_bounds(soil, ag_g, f0, bound):
    """Tab. 3.2.IV: S_S is held inside its bounds (both ends, every soil)."""
    s_s, _ = ntc2018_soil_factors(soil, ag_g=ag_g, f0=f0, tc_star_s=0.3)
    assert s_s == bound


def test_ntc_soil_amplification_between_its_bounds_is_the_line():
    # D: 2.40 - 1.50 * 2.5 * 0.3 = 1.275, inside [0.90, 1.80]
    assert ntc2018_soil_factors("D", ag_g=0.3, f0=2.5, tc_star_s=0.3)[0] == pytest.approx(1.275)


@pytest.mark.parametrize(("soil", "c", "p"), [("A", 1.0, 0.0), ("B", 1.10, -0.20),
                                              ("C", 1.05, -0.33), ("D", 1.25, -0.50),
                                              ("E", 1.15, -0.40)])
@pytest.mark.parametrize("tcs", [0.2, 0.5])
def test_ntc_corner_coefficient(soil, c, p, tcs):
    assert ntc2018_soil_factors(soil, ag_g=0.1, f0=2.5, tc_star_s=tcs)[1] == pytest.approx(
        c * tcs**p, rel=REL)


@pytest.mark.parametrize(("topography", "s_t"), [("T1", 1.0), ("T2", 1.2), ("T3", 1.2),
                                                 ("T4", 1.4)])
def test_ntc_topographic_factor(topography, s_t):
    spec = ntc2018_spectrum(ag_g=0.1, f0=2.5, tc_star_s=0.3, topography=topography)
    assert spec.S == s_t


def test_ntc_vertical():
    """NTC eqs. 3.2.8-3.2.9, Tab. 3.2.VI: F_v = 1.35 F0 sqrt(a_g/g), S = S_T, 0.05/0.15/1.0 s."""
    ag_g, f0 = 0.3, 2.4
    spec = ntc2018_spectrum(ag_g=ag_g, f0=f0, tc_star_s=0.3, soil="D", topography="T3",
                            component="vertical")
    fv = 1.35 * f0 * math.sqrt(ag_g)
    assert spec.F0 == pytest.approx(fv, rel=REL)
    assert spec.S == 1.2
    periods = [0.0, 0.025, 0.05, 0.1, 0.15, 0.5, 1.0, 3.0]
    expected = [_ntc_closed_form(t, ag_g * G, 1.2, fv, 0.05, 0.15, 1.0) for t in periods]
    np.testing.assert_allclose(spec.sa(periods), expected, rtol=REL)


@pytest.mark.parametrize("soil", ["A", "B", "C", "D", "E"])
def test_ntc_displacement_spectrum(soil):
    """Eq. 3.2.10 below T_E: S_e (T/2pi)^2; eq. 3.2.11 between T_E and T_F; d_g beyond T_F."""
    spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil=soil)
    te, tf = {"A": 4.5, "B": 5.0}.get(soil, 6.0), 10.0
    assert (spec.TE, spec.TF) == (te, tf)
    below = np.linspace(0.0, te, 50)
    np.testing.assert_allclose(spec.sd(below), spec.sa(below) * (below / (2 * math.pi)) ** 2,
                               rtol=REL)
    dg = 0.025 * 0.25 * G * spec.S * spec.TC * spec.TD
    assert spec.dg == pytest.approx(dg, rel=REL)
    eta = damping_factor(0.08)
    mid = (te + tf) / 2
    assert spec.sd(mid, 0.08)[0] == pytest.approx(
        dg * (2.4 * eta + (1 - 2.4 * eta) * 0.5), rel=REL)
    np.testing.assert_allclose(spec.sd([tf, 12.0, 20.0]), dg, rtol=REL)
    # continuous to within 1/(4 pi^2) vs 0.025 (1.3 %) at T_E, and reaches d_g at T_F
    assert spec.sd(te + 1e-9)[0] == pytest.approx(spec.sd(te)[0], rel=0.014)


@pytest.mark.parametrize(("spectrum_type", "ground", "row"), [
    (1, "A", (1.00, 0.15, 0.40, 2.0)), (1, "B", (1.20, 0.15, 0.50, 2.0)),
    (1, "C", (1.15, 0.20, 0.60, 2.0)), (1, "D", (1.35, 0.20, 0.80, 2.0)),
    (1, "E", (1.40, 0.15, 0.50, 2.0)), (2, "A", (1.00, 0.05, 0.25, 1.2)),
    (2, "B", (1.35, 0.05, 0.25, 1.2)), (2, "C", (1.50, 0.10, 0.25, 1.2)),
    (2, "D", (1.80, 0.10, 0.30, 1.2)), (2, "E", (1.60, 0.05, 0.25, 1.2)),
])
@pytest.mark.parametrize("damping", [0.05, 0.08])
def test_ec8_horizontal_branches(spectrum_type, ground, row, damping):
    s, tb, tc, td = row
    spec = ec8_spectrum(ag_g=0.2, spectrum_type=spectrum_type, ground=ground, importance=1.2)
    ag = 0.2 * 1.2 * G
    assert spec.ag == pytest.approx(ag, rel=REL)
    assert (spec.S, spec.TB, spec.TC, spec.TD) == (s, tb, tc, td)
    eta = math.sqrt(10 / (5 + 100 * damping))
    periods = [0.0, tb / 2, tb, (tb + tc) / 2, tc, (tc + td) / 2, td, 3.0, 4.0]
    expected = [_ec8_closed_form(t, ag, s, tb, tc, td, eta) for t in periods]
    np.testing.assert_allclose(spec.sa(periods, damping), expected, rtol=REL)
    np.testing.assert_allclose(spec.sd(periods, damping),
                               np.array(expected) * (np.array(periods) / (2 * math.pi)) ** 2,
                               rtol=REL)


@pytest.mark.parametrize(("spectrum_type", "ratio"), [(1, 0.90), (2, 0.45)])
def test_ec8_vertical(spectrum_type, ratio):
    """EN 1998-1 eqs. 3.8-3.11, Tab. 3.4: a_vg = 0.90 / 0.45 a_g, plateau 3.0 a_vg eta."""
    spec = ec8_spectrum(ag_g=0.3, spectrum_type=spectrum_type, ground="D", component="vertical")
    avg = ratio * 0.3 * G
    assert spec.sa(0.0)[0] == pytest.approx(avg, rel=REL)
    assert spec.sa(0.025)[0] == pytest.approx(avg * (1 + 0.5 * (3.0 - 1)), rel=REL)
    assert spec.sa(0.1)[0] == pytest.approx(3.0 * avg, rel=REL)
    assert spec.sa(0.5)[0] == pytest.approx(3.0 * avg * 0.15 / 0.5, rel=REL)
    assert spec.sa(2.0)[0] == pytest.approx(3.0 * avg * 0.15 * 1.0 / 4.0, rel=REL)


def test_ec8_with_ag_keeps_the_site():
    spec = ec8_spectrum(ag_g=0.2, spectrum_type=2, ground="C", importance=1.4)
    other = spec.with_ag(0.5 * G)
    assert other.ag == pytest.approx(0.5 * G, rel=REL)
    assert (other.S, other.TB, other.TC, other.TD) == (spec.S, spec.TB, spec.TC, spec.TD)
    np.testing.assert_allclose(other.sa([0.1, 1.0]), spec.sa([0.1, 1.0]) * 0.5 / (0.2 * 1.4),
                               rtol=1e-12)


def test_damping_factor():
    """Eq. 3.2.4: eta = sqrt(10/(5 + xi%)) floored at 0.55; 1 at 5 %."""
    assert damping_factor(0.05) == 1.0
    assert damping_factor(0.10) == pytest.approx(math.sqrt(10 / 15), rel=REL)
    assert damping_factor(0.0) == pytest.approx(math.sqrt(2), rel=REL)
    assert damping_factor(0.28) > 0.55 and damping_factor(0.281) == 0.55   # 10/0.55^2 - 5 = 28.06 %
    assert damping_factor(0.6) == 0.55


def test_to_dict_has_units_in_the_keys():
    d = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.3, soil="B").to_dict()
    assert d["ag_g"] == pytest.approx(0.25)
    assert {"S", "TB_s", "TC_s", "TD_s", "TE_s", "TF_s", "dg_m", "plateau_g"} <= set(d)
    assert d["params"]["soil"] == "B"
    assert ec8_spectrum(ag_g=0.2).to_dict()["TE_s"] is None


# ---------------------------------------------------------------------------------------------
def test_return_periods_of_the_limit_states():
    """Eq. 3.2.0 with V_N = 50 y, class II: the familiar 30, 50, 475, 975 years."""
    got = [return_period_years(s) for s in ("SLO", "SLD", "SLV", "SLC")]
    assert got == pytest.approx([30.1, 50.3, 474.6, 974.8], abs=0.05)
    assert return_period_years("slv", 100, "IV") == pytest.approx(
        -200 / math.log(0.9), rel=REL)


def test_hazard_interpolation_is_linear_in_log_log():
    hz = NTCHazard([(975, 0.32, 2.45, 0.32), (475, 0.25, 2.4, 0.30), (2475, 0.41, 2.5, 0.34)])
    ag, f0, tc = hz.at(700.0)
    w = math.log(700 / 475) / math.log(975 / 475)
    assert ag == pytest.approx(0.25 * (0.32 / 0.25) ** w, rel=1e-12)
    assert f0 == pytest.approx(2.4 * (2.45 / 2.4) ** w, rel=1e-12)
    assert tc == pytest.approx(0.30 * (0.32 / 0.30) ** w, rel=1e-12)
    assert hz.at(2475.0) == pytest.approx((0.41, 2.5, 0.34), rel=1e-12)
    assert hz.spectrum(475.0, soil="B").ag == pytest.approx(0.25 * G, rel=1e-12)
    with pytest.raises(InvalidParameterError, match=r"return_period_years must be in \[475, 2475\]"):
        hz.at(100.0)


@pytest.mark.parametrize(("call", "match"), [
    (lambda: ntc2018_spectrum(ag_g=-0.1, f0=2.4, tc_star_s=0.3), r"ag_g must be in \(0, 3\]"),
    (lambda: ntc2018_spectrum(ag_g=0.1, f0=1.8, tc_star_s=0.3), r"f0 must be in \[2.2, 4\]"),
    (lambda: ntc2018_spectrum(ag_g=0.1, f0=2.4, tc_star_s=0.0), r"tc_star_s must be in"),
    (lambda: ntc2018_spectrum(ag_g=0.05, f0=2.4, tc_star_s=1.9),
     r"tc_star_s must be in \[0.05, 0.8\]"),
    (lambda: ntc2018_spectrum(ag_g=0.1, f0=2.4, tc_star_s=0.3, soil="F"),
     r"soil must be one of A, B, C, D, E, got 'F'"),
    (lambda: ntc2018_spectrum(ag_g=0.1, f0=2.4, tc_star_s=0.3, topography="T5"), "topography"),
    (lambda: ec8_spectrum(ag_g=0.1, spectrum_type=3), "spectrum_type must be 1 or 2"),
    (lambda: ec8_spectrum(ag_g=0.1, ground="S1"), "ground must be one of"),
    (lambda: ec8_spectrum(ag_g=0.1, importance=5), r"importance must be in \[0.5, 2\]"),
    (lambda: ec8_spectrum(ag_g=0.1, component="up"), "component must be one of"),
    (lambda: ec8_spectrum(ag_g=0.1).sa(0.5, damping=1.5), r"damping must be in \[0, 1\)"),
    (lambda: ec8_spectrum(ag_g=0.1).sa([-1.0]), "periods must be"),
    (lambda: return_period_years("SLU"), "limit_state must be one of SLO, SLD, SLV, SLC"),
    (lambda: return_period_years("SLV", use_class="V"), "use_class"),
    (lambda: NTCHazard([(475, 0.25, 2.4, 0.3)]), "two or more distinct return periods"),
])
def test_bad_input_is_one_line_naming_the_argument(call, match):
    with pytest.raises(InvalidParameterError, match=match) as info:
        call()
    assert "\n" not in str(info.value)


# ---------------------------------------------------------------------------------------------
# invariants over the whole parameter space
# ---------------------------------------------------------------------------------------------
SITES = st.one_of(
    st.builds(lambda ag, f0, tc, soil, topo, comp: ntc2018_spectrum(
        ag_g=ag, f0=f0, tc_star_s=tc, soil=soil, topography=topo, component=comp),
        st.floats(0.01, 3.0), st.floats(2.2, 4.0), st.floats(0.05, 0.8),
        st.sampled_from("ABCDE"), st.sampled_from(["T1", "T2", "T3", "T4"]),
        st.sampled_from(["horizontal", "vertical"])),
    st.builds(lambda ag, typ, ground, imp, comp: ec8_spectrum(
        ag_g=ag, spectrum_type=typ, ground=ground, importance=imp, component=comp),
        st.floats(0.01, 3.0), st.sampled_from([1, 2]), st.sampled_from("ABCDE"),
        st.floats(0.5, 2.0), st.sampled_from(["horizontal", "vertical"])),
)


@settings(max_examples=200, deadline=None)
@given(SITES, st.floats(0.0, 0.5))
def test_spectrum_is_continuous_and_peaks_on_the_plateau(spec, damping):
    """Both codes' S_e is continuous at T_B, T_C, T_D (the branches meet), goes from the PGA to
    the plateau a_g S eta F0 and never exceeds the larger of the two, and falls beyond T_C. (The
    NTC vertical spectrum's F_v = 1.35 F0 sqrt(a_g/g) is below 1 where a_g < 0.088 g for
    F0 = 2.5: there eq. 3.2.8 falls from the PGA, as written.)"""
    eps = 1e-9
    for corner in (spec.TB, spec.TC, spec.TD):
        left, right = spec.sa([corner * (1 - eps), corner], damping)
        assert left == pytest.approx(right, rel=1e-6)
    plateau = spec.pga * damping_factor(damping) * spec.F0
    t = np.concatenate([np.linspace(0.0, 3 * spec.TD, 400), [spec.TB, spec.TC]])
    sa = spec.sa(t, damping)
    assert sa.max() == pytest.approx(max(plateau, spec.pga), rel=1e-12)
    assert spec.sa((spec.TB + spec.TC) / 2, damping)[0] == pytest.approx(plateau, rel=1e-12)
    tail = np.sort(t[t >= spec.TC])
    assert np.all(np.diff(spec.sa(tail, damping)) <= 1e-12 * plateau)
    assert spec.sa(0.0, damping)[0] == pytest.approx(spec.pga, rel=1e-12)


@pytest.mark.parametrize("soil", ["A", "B", "C", "D", "E"])
@pytest.mark.parametrize("tc_star", [0.05, 0.8])
def test_the_range_of_tc_star_keeps_the_corners_ordered(soil, tc_star):
    """At the ends of T_C*'s range and the smallest a_g, T_B < T_C < T_D = 1.6 s on every soil
    (the range's upper bound is chosen for this)."""
    spec = ntc2018_spectrum(ag_g=1e-6, f0=4.0, tc_star_s=tc_star, soil=soil)
    assert spec.TB < spec.TC < spec.TD
