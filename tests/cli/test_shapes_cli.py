"""Shape options of every arch-taking command (issue 12), through the real entry point.

Oracle: the library builders (the CLI must build the same arch and give the same lambda);
bad geometry is one line naming the option, exit 2.
"""

from __future__ import annotations

import json
import math

import pytest

from archquake.cli import main as cli_main
from archquake.geometry import Arch, OnPiers, Piers, ShapedArch
from archquake.limit import limit_analysis


def _static(capsys, *args):
    assert cli_main.main(["static", "--json", *args]) == 0
    return json.loads(capsys.readouterr().out)


def test_pointed_arch_by_span_and_rise(capsys):
    data = _static(capsys, "--shape", "pointed", "--span", "10", "--rise", "7", "--thickness",
                   "0.8", "--voussoirs", "15")
    ref = limit_analysis(ShapedArch("pointed", 10.0, 7.0, 0.8, 15)).collapse_acceleration_g
    assert data["collapse_acceleration_g"] == pytest.approx(ref, rel=1e-12)
    assert data["arch"]["shape"] == "pointed"


def test_segmental_by_span_and_rise_is_the_circular_arch(capsys):
    ref = Arch(10.0, 1.5, math.radians(157.5), 7)
    data = _static(capsys, "--shape", "segmental", "--span", repr(ref.span), "--rise",
                   repr(ref.rise), "--thickness", "1.5", "--voussoirs", "7")
    assert data["arch"]["radius_m"] == pytest.approx(10.0, rel=1e-12)
    assert data["collapse_acceleration_g"] == pytest.approx(0.3700097380218764, rel=1e-10)


def test_default_arch_is_still_oppenheims(capsys):
    assert _static(capsys)["collapse_acceleration_g"] == pytest.approx(0.3700097380218764, rel=1e-12)


def test_arch_on_piers_and_vertical_joints(capsys):
    data = _static(capsys, "--radius", "5", "--embrace", "180", "--thickness", "0.75",
                   "--voussoirs", "21", "--pier-height", "4", "--pier-width", "1.5",
                   "--pier-courses", "4")
    ref = limit_analysis(OnPiers(Arch(5.0, 0.75, math.pi, 21), Piers(4.0, 1.5, 4)))
    assert data["collapse_acceleration_g"] == pytest.approx(ref.collapse_acceleration_g, rel=1e-12)
    assert data["arch"]["pier_courses"] == 4
    data = _static(capsys, "--shape", "circular", "--span", "10", "--rise", "5", "--thickness",
                   "0.8", "--voussoirs", "15", "--joints", "vertical")
    assert data["arch"]["joints"] == "vertical"


@pytest.mark.parametrize("args, message", [
    (["--shape", "segmental", "--span", "10", "--rise", "6", "--thickness", "0.5"],
     "--rise of a segmental arch must be at most half the span"),
    (["--shape", "pointed", "--span", "10", "--thickness", "0.5"], "needs --rise"),
    (["--shape", "elliptical", "--span", "10", "--rise", "3", "--radius", "4", "--thickness", "1"],
     "--radius apply to a circular arch"),
    (["--radius", "5", "--embrace", "180", "--thickness", "0.75", "--voussoirs", "21",
      "--pier-height", "8", "--pier-width", "1.5"], "the piers are too slender"),
    (["--radius", "5", "--embrace", "180", "--thickness", "0.75", "--pier-height", "8"],
     "need both --pier-height and --pier-width"),
    (["--shape", "circular", "--span", "10", "--rise", "5", "--thickness", "0.3", "--voussoirs",
      "30"], "needs t/R >= 0.1075"),
    (["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "0.2", "--voussoirs",
      "30"], "its minimum thickness is"),
    (["--blocks", "nowhere.json"], "--blocks nowhere.json: no such file"),
])
def test_bad_geometry_is_one_line_exit_2(args, message, capsys):
    assert cli_main.main(["static", *args]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_min_thickness_of_shapes_and_safety_factor(capsys):
    """Vertical joints: Makris & Alexakis's 0.1095 (200 voussoirs, R = 1 m); a given thickness
    reports t / t_min."""
    assert cli_main.main(["min-thickness", "--joints", "vertical", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["min_thickness_ratio"] == pytest.approx(0.1095, abs=5e-4)
    assert cli_main.main(["min-thickness", "--shape", "pointed", "--span", "10", "--rise", "7",
                          "--voussoirs", "30", "--thickness", "0.6", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["geometric_safety_factor"] == pytest.approx(0.6 / data["min_thickness_m"])
    assert data["geometric_safety_factor"] > 1.0
