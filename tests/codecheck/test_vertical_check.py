"""The code check's vertical component (NTC 2018 §7.2.2, eq. 7.3.15; EN 1998-1 §4.3.3.5.2).

Oracles: the activation written out by hand under E_x + 0.3 E_z (a_g S = a0* (1 - 0.3 a_g S_T
/ g), NTC's vertical PGA being a_g S_T); the static route, limit_analysis with a steady
vertical K, whose lambda(K) = (1 + K) lambda(0) the check must reproduce at K = -0.3 a_vg / g
(1e-9); the nonlinear check's period, lengthened by 1/sqrt(1 - k_v) (1e-12); and the code's
rule of where the vertical is taken.
"""

from __future__ import annotations

import math

import pytest

from archquake.codecheck.check import Position, kinematic_check
from archquake.codecheck.kinematic import RockingBlock, capacity_curve
from archquake.codes.spectra import ec8_spectrum, ntc2018_spectrum
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.limit import limit_analysis

G = 9.81
FC = 1.35
ARCH = Arch(5.0, 0.75, math.pi, 9)  # a semicircle, t/R 0.15


@pytest.fixture(scope="module")
def block_curve():
    return capacity_curve(RockingBlock.on_base(0.5, 5.0, density=18000.0 / G), g=G)


@pytest.fixture(scope="module")
def arch_curve():
    return capacity_curve(ARCH)


def _ntc(ag_g: float, g: float = G, topography: str = "T1"):
    return ntc2018_spectrum(ag_g=ag_g, f0=2.4, tc_star_s=0.30, soil="B", topography=topography,
                            g=g)


def test_sld_by_hand_under_e_x_plus_0_3_e_z(block_curve):
    # a_g S = (0.1 g / FC) (1 - 0.3 a_g S_T / g), S = 1.2 (S_S clipped), S_T = 1; the other
    # combination, 0.3 a_g S = a0* (1 - a_g / g), gives 0.171 g and does not govern
    a0 = 0.1 / FC
    by_hand = a0 / (1.2 + 0.3 * a0)  # 0.0606 g
    res = kinematic_check(block_curve, {"SLD": _ntc(0.25)}, vertical=True)
    assert res.check("SLD", "linear").capacity_ag_g == pytest.approx(by_hand, rel=1e-9)
    plain = kinematic_check(block_curve, {"SLD": _ntc(0.25)}, vertical=False)
    assert plain.check("SLD", "linear").capacity_ag_g == pytest.approx(a0 / 1.2, rel=1e-9)


def test_topography_enters_the_vertical(block_curve):
    # S_T = 1.2 (T2) multiplies both components: a_g 1.2 S_S = a0* (1 - 0.3 a_g 1.2 / g)
    a0 = 0.1 / FC
    res = kinematic_check(block_curve, {"SLD": _ntc(0.25, topography="T2")}, vertical=True)
    assert res.check("SLD", "linear").capacity_ag_g == pytest.approx(
        a0 / (1.2 * 1.2 + 0.3 * 1.2 * a0), rel=1e-9)


def test_arch_activation_is_the_static_route(arch_curve):
    """At the capacity a_g, the activation demand a_g S equals a0* recomputed from
    limit_analysis(arch, vertical=K) with K = -0.3 a_vg / g, a_vg = a_g S_T."""
    res = kinematic_check(arch_curve, {"SLD": _ntc(0.25, g=arch_curve.g)})
    assert res.vertical.taken
    ag_g = res.check("SLD", "linear").capacity_ag_g
    lam = limit_analysis(ARCH, vertical=-0.3 * ag_g).collapse_acceleration_g
    a0_k = lam / (arch_curve.e_star * FC)  # a0* at the weights (1 - 0.3 a_vg / g), in g
    s_s = _ntc(ag_g, g=arch_curve.g).S
    assert ag_g * s_s == pytest.approx(a0_k, rel=1e-9)


def test_nonlinear_demand_follows_the_lengthened_period(arch_curve, block_curve):
    """Weights (1 - k_v) scale a(d), so T_SLV grows by 1/sqrt(1 - k_v). The arch's T_SLV (1.48 s)
    lies between T_C and T_D, where S_De grows as T (S_S clipped at 1.2 on both sides): the
    capacity a_g falls by sqrt(1 - 0.3 a_g / g) exactly. The block's (3.5 s) lies where the
    displacement demand no longer grows with T: the vertical changes nothing there."""
    spec = _ntc(0.25, g=arch_curve.g)
    with_v = kinematic_check(arch_curve, {"SLV": spec}, vertical=True).check("SLV", "nonlinear")
    plain = kinematic_check(arch_curve, {"SLV": spec}, vertical=False).check("SLV", "nonlinear")
    assert spec.TC < plain.period_s < plain.period_s / math.sqrt(0.9) < spec.TD
    ag = with_v.capacity_ag_g
    assert ag / plain.capacity_ag_g == pytest.approx(math.sqrt(1.0 - 0.3 * ag), rel=1e-9)
    assert with_v.period_s == plain.period_s  # the code's T_SLV, at g, is what is reported
    assert "vertical" in with_v.formulas and "vertical" not in plain.formulas
    block = {v: kinematic_check(block_curve, {"SLV": _ntc(0.25)}, vertical=v)
             .check("SLV", "nonlinear").capacity_ag_g for v in (True, False)}
    assert block[True] == pytest.approx(block[False], rel=1e-12)


def test_where_the_code_asks_for_it(arch_curve, block_curve):
    ntc = {"SLV": _ntc(0.25, g=arch_curve.g)}
    assert kinematic_check(arch_curve, ntc).vertical.taken  # NTC: a thrusting structure
    assert not kinematic_check(block_curve, {"SLV": _ntc(0.25)}).vertical.taken
    ec8 = kinematic_check(arch_curve, {"SLV": ec8_spectrum(ag_g=0.3, ground="B",
                                                          g=arch_curve.g)})
    assert not ec8.vertical.taken and "4.3.3.5.2" in ec8.vertical.reason
    high = kinematic_check(arch_curve, ntc, position=Position(8.0, 10.0, 0.6))
    assert not high.vertical.taken and "C7.2.11" in high.vertical.reason
    d = kinematic_check(arch_curve, ntc).to_dict()["vertical"]
    assert d["taken"] and d["combinations"] == ["E_x + 0.3 E_z", "0.3 E_x + E_z"]


@pytest.mark.parametrize("kwargs", [{"procedure": "2009"},
                                    {"position": Position(8.0, 10.0, 0.6)}])
def test_refuses_a_vertical_it_cannot_take(arch_curve, kwargs):
    with pytest.raises(InvalidParameterError, match="vertical component"):
        kinematic_check(arch_curve, {"SLV": _ntc(0.25, g=arch_curve.g)}, vertical=True,
                        **kwargs)


def test_cli_states_the_vertical(capsys):
    from archquake.cli.main import main

    args = ["check", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
            "--soil", "B"]
    assert main(args) == 0
    assert "vertical component: taken: NTC 2018 §7.2.2" in capsys.readouterr().out
    assert main(args + ["--vertical-component", "neglect"]) == 0
    assert "vertical component: neglected, as asked" in capsys.readouterr().out
    assert main(args + ["--procedure", "2009", "--vertical-component", "take"]) == 2
    err = capsys.readouterr().err
    assert "--vertical-component take" in err and "Traceback" not in err
