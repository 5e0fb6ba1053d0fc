"""Limit analysis under a constant vertical ground acceleration.

Oracle: the exact law lambda(c) = (1 + c) lambda(0) for an arch whose loads are all body
forces (only the direction of the body-force field decides the collapse), checked between the
line-of-thrust program with scaled weights and the bare arch's own analysis, to 1e-9; the
closed form lambda0 / (1 + r lambda0) of EN 1998-5's coupled k_v = r k_h.
"""

from __future__ import annotations

import math

import pytest

from archquake._json import to_jsonable
from archquake.cli.main import main
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, Passive, PointLoad
from archquake.limit import coupled_vertical_analysis, limit_analysis

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
BRIDGE = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)


@pytest.mark.parametrize("method", ["static", "kinematic", "both"])
@pytest.mark.parametrize("c", [-0.6, -0.3, 0.25, 1.0])
def test_bare_arch_lambda_scales_by_one_plus_c(method, c):
    lam0 = limit_analysis(OPPENHEIM, method=method)
    res = limit_analysis(OPPENHEIM, method=method, vertical=c)
    assert res.collapse_acceleration_g == pytest.approx((1 + c) * lam0.collapse_acceleration_g,
                                                        rel=1e-9)
    assert res.mechanism.joints == lam0.mechanism.joints
    assert res.vertical_g == c
    # the friction demand |V|/N at collapse is lambda over gravity's share: unchanged ratio
    assert res.min_friction == pytest.approx(lam0.min_friction, rel=1e-6)


@pytest.mark.parametrize("c", [-0.4, 0.5])
def test_fill_and_passive_scale_with_gravity(c):
    """Fill weights and the passive pressure (the fill's weight) are body forces: the law
    holds both ways."""
    loads = Loads(fill=Fill(depth=0.5), passive=Passive(0.33, 30.0))
    lam0 = limit_analysis(BRIDGE, method="static", loads=loads)
    res = limit_analysis(BRIDGE, method="static", loads=loads, vertical=c)
    assert res.collapse_acceleration_g == pytest.approx(
        (1 + c) * lam0.collapse_acceleration_g, rel=1e-7)
    assert res.opposite_collapse_acceleration_g == pytest.approx(
        (1 + c) * lam0.opposite_collapse_acceleration_g, rel=1e-7)


def test_a_load_whose_mass_does_not_move_keeps_its_weight():
    """A dead load without mass is not scaled: dividing every force by 1 + c, lambda(c) with
    the load P is (1 + c) times lambda(0) with the load P / (1 + c)."""
    c, p = 0.3, 2e4

    def lam(load, vertical):
        loads = Loads(fill=Fill(depth=0.5), point_loads=(PointLoad(1.0, load, False),))
        return limit_analysis(BRIDGE, method="static", loads=loads,
                              vertical=vertical).collapse_acceleration_g

    assert lam(p, c) == pytest.approx((1 + c) * lam(p / (1 + c), 0.0), rel=1e-7)
    assert lam(p, c) != pytest.approx((1 + c) * lam(p, 0.0), rel=1e-3)


def test_zero_vertical_is_today():
    assert repr(to_jsonable(limit_analysis(OPPENHEIM, method="both", vertical=0.0).to_dict())) == \
        repr(to_jsonable(limit_analysis(OPPENHEIM, method="both").to_dict()))
    assert "vertical_g" not in limit_analysis(OPPENHEIM).to_dict()


@pytest.mark.parametrize("ratio", [0.33, 0.5])
def test_en1998_5_coupled_vertical_closed_form(ratio):
    lam0 = limit_analysis(OPPENHEIM).collapse_acceleration_g
    res = coupled_vertical_analysis(OPPENHEIM, ratio)
    assert res.collapse_acceleration_g == pytest.approx(lam0 / (1 + ratio * lam0), rel=1e-8)
    assert res.vertical_g == pytest.approx(-ratio * res.collapse_acceleration_g, rel=1e-12)


@pytest.mark.parametrize("c", [-1.0, -2.0, 6.0, math.nan])
def test_vertical_out_of_range(c):
    with pytest.raises(InvalidParameterError, match="vertical"):
        limit_analysis(OPPENHEIM, vertical=c)


@pytest.mark.parametrize("argv, word", [(["--vertical", "-1"], "--vertical must be in (-1, 5]"),
                                        (["--vertical-ratio", "1.5"], "--vertical-ratio")])
def test_cli_bad_vertical(argv, word, capsys):
    assert main(["static", *argv]) == 2
    err = capsys.readouterr().err
    assert word in err and "Traceback" not in err


def test_cli_vertical_json(capsys):
    assert main(["static", "--vertical", "0.5", "--json"]) == 0
    out = capsys.readouterr().out
    assert '"vertical_g": 0.5' in out
