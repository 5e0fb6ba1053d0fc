"""``archquake capacity`` and ``archquake static`` with loads, through the real entry point."""

from __future__ import annotations

import json
import math

import pytest

from archquake.cli import main as cli_main
from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, Traffic
from archquake.limit import limit_analysis
from archquake.limit.capacity import traffic_capacity

BRIDGE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15",
          "--density", "1800"]
ARCH = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)


def _json(capsys, argv):
    assert cli_main.main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_static_with_fill_is_the_api_in_the_clis_units(capsys):
    out = _json(capsys, ["static", *BRIDGE, "--fill-depth", "1", "--fill-density", "1800"])
    api = limit_analysis(ARCH, method="both", loads=Loads(fill=Fill(depth=1.0, density=1800.0)))
    assert out["collapse_acceleration_g"] == pytest.approx(api.collapse_acceleration_g, rel=1e-12)
    assert out["loads"]["passive_pressure"] == "off (not modelled)"
    assert out["collapse_acceleration_towards_minus_x_g"] == pytest.approx(
        api.collapse_acceleration_g, rel=1e-9)
    assert len(out["carried"]["carried_mass_kg"]) == 15


def test_static_without_loads_prints_no_loads(capsys):
    out = _json(capsys, ["static", *BRIDGE])
    assert "loads" not in out and "carried" not in out


def test_capacity_at_a_position_in_kn(capsys):
    out = _json(capsys, ["capacity", *BRIDGE, "--fill-depth", "0.5", "--axle", "100",
                         "--position", "2.5"])
    api = traffic_capacity(ARCH, Loads(fill=Fill(depth=0.5)), Traffic(100e3, 2.5))
    assert out["multiplier"] == pytest.approx(api.multiplier, rel=1e-12)
    assert out["collapse_load_kN_m"] == pytest.approx(100 * api.multiplier, rel=1e-12)
    assert out["static_multiplier"] == pytest.approx(out["kinematic_multiplier"], rel=1e-7)


def test_capacity_scan_reports_the_critical_position(capsys, tmp_path):
    plot = tmp_path / "cap.png"
    out = _json(capsys, ["capacity", *BRIDGE, "--fill-depth", "0.5", "--axle", "100",
                         "--dispersion", "26.57", "--positions", "20", "--plot", str(plot)])
    mus = out["scan"]["multiplier"]
    assert len(mus) == 20
    assert out["adequacy_factor"] == pytest.approx(min(mus), rel=1e-9)
    assert out["critical_position_m"] == out["scan"]["position_m"][mus.index(min(mus))]
    assert plot.stat().st_size > 0


@pytest.mark.parametrize(("argv", "message"), [
    (["static", "--fill-depth", "-1"], "--fill-depth must be in [0, 1000] m"),
    (["static", "--fill-density", "1800"], "--fill-density applies to a fill"),
    (["static", "--backing-right", "1"], "--backing-right needs --backing"),
    (["static", "--point-load", "3,x"], "--point-load"),
    (["capacity", *BRIDGE, "--axle", "0"], "--axle must be in (0, 100000]"),
    (["capacity", *BRIDGE], "give the traffic load"),
    (["capacity", *BRIDGE, "--patch", "100"], "--patch needs --patch-length"),
    (["capacity", *BRIDGE, "--axle", "100", "--dispersion", "90"], "--dispersion must be in"),
    (["capacity", *BRIDGE, "--axle", "100", "--position", "1", "--positions", "5"],
     "--positions sets a scan"),
    (["capacity", *BRIDGE, "--axle", "100", "--dispersion", "flamant"], "--dispersion"),
    (["static", *BRIDGE, "--passive", "0.3"], "--passive needs a fill"),
    (["static", *BRIDGE, "--fill-depth", "1", "--fill-friction", "30"],
     "--fill-friction applies to --passive"),
    (["static", *BRIDGE, "--fill-depth", "1", "--passive", "1.5"], "--passive must be in (0, 1]"),
    (["check", *BRIDGE, "--fill-depth", "1", "--passive", "0.3", "--code", "ntc2018", "--ag",
      "0.15", "--f0", "2.45", "--tc-star", "0.3", "--soil", "B"],
     "the code check does not model passive fill pressure"),
])
def test_bad_loads_exit_2_with_one_line(capsys, argv, message):
    assert cli_main.main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_check_with_fill_counts_the_fill(capsys):
    """archquake check with --fill-depth: alpha0 is the loaded collapse multiplier and the
    JSON lists the loads (C8.7.1: every carried mass)."""
    out = _json(capsys, ["check", *BRIDGE, "--fill-depth", "1", "--code", "ntc2018", "--ag",
                         "0.15", "--f0", "2.45", "--tc-star", "0.3", "--soil", "B"])
    api = limit_analysis(ARCH, method="both", loads=Loads(fill=Fill(depth=1.0)))
    assert out["capacity_curve"]["alpha0"] == pytest.approx(api.collapse_acceleration_g,
                                                            rel=1e-10)
    assert out["loads"]["fill"]["depth_m"] == 1.0


def test_min_thickness_with_fill(capsys):
    from archquake.limit.loaded import min_thickness_loaded

    out = _json(capsys, ["min-thickness", "--radius", "5", "--embrace", "180", "--voussoirs",
                         "15", "--density", "1800", "--fill-depth", "1"])
    probe = Arch(5.0, 2.5, math.pi, 15, 1.0, 1800.0)
    assert out["min_thickness_m"] == pytest.approx(
        min_thickness_loaded(probe, Loads(fill=Fill(depth=1.0))), rel=1e-12)
    assert cli_main.main(["min-thickness", "--fill-depth", "1"]) == 2


def test_passive_pressure_is_stated_and_used(capsys):
    from archquake.geometry.loads import Passive

    out = _json(capsys, ["static", *BRIDGE, "--fill-depth", "0.5", "--passive", "0.33"])
    api = limit_analysis(ARCH, method="both",
                         loads=Loads(fill=Fill(depth=0.5), passive=Passive(0.33, 30.0)))
    assert out["collapse_acceleration_g"] == pytest.approx(api.collapse_acceleration_g, rel=1e-12)
    assert out["loads"]["passive_pressure"]["fraction_of_kp"] == 0.33
    off = _json(capsys, ["static", *BRIDGE, "--fill-depth", "0.5"])
    assert off["loads"]["passive_pressure"] == "off (not modelled)"


def test_a_surveyed_arch_with_a_fill_level_and_a_wall(capsys, tmp_path):
    """Blocks from a file carry a fill given by its level and a point load by position: the
    same lambda and capacity as the closed-form arch with the same loads (1e-6)."""
    from archquake.geometry.loads import PointLoad

    blocks = tmp_path / "arch.json"
    blocks.write_text(json.dumps({"blocks": [p.tolist() for p in ARCH.block_polygons]}))
    level = str(ARCH.extrados_radius + 0.8)
    out = _json(capsys, ["static", "--blocks", str(blocks), "--density", "1800", "--fill-level",
                         level, "--point-load", "6.5,20"])
    loads = Loads(fill=Fill(depth=0.8), point_loads=(PointLoad(6.5, 20e3),))
    api = limit_analysis(ARCH, method="both", loads=loads)
    assert out["collapse_acceleration_g"] == pytest.approx(api.collapse_acceleration_g, rel=1e-6)
    cap = _json(capsys, ["capacity", "--blocks", str(blocks), "--density", "1800",
                         "--fill-level", level, "--point-load", "6.5,20", "--axle", "100",
                         "--position", "3"])
    assert cap["multiplier"] == pytest.approx(
        traffic_capacity(ARCH, loads, Traffic(100e3, 3.0)).multiplier, rel=1e-6)


def test_capacity_with_boussinesq(capsys):
    out = _json(capsys, ["capacity", *BRIDGE, "--fill-depth", "0.5", "--axle", "100",
                         "--dispersion", "boussinesq", "--position", "2.5"])
    api = traffic_capacity(ARCH, Loads(fill=Fill(depth=0.5)),
                           Traffic(100e3, 2.5, boussinesq=True))
    assert out["multiplier"] == pytest.approx(api.multiplier, rel=1e-12)
    assert out["traffic"]["boussinesq"] is True
