"""``archquake run`` with what the arch carries, through the real entry point: the rigid chain
(default) and the DEM carry the fill; the four-link model and the loads the dynamics do not
carry are refused in one line with exit status 2.

Oracle: lambda of the static analysis with the loads (:mod:`archquake.limit.loaded`): the
example bridge's semicircle with 1 m of fill, 0.0819 g (bare: 0.0490 g). A long step pulse
10 % below it leaves the filled arch still (it rocks the bare arch), 30 % above it rocks it.
"""

from __future__ import annotations

import json
import math

import pytest

from archquake.cli import main as cli_main
from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, PointLoad, block_extras
from archquake.limit.loaded import loaded_collapse, seismic_case

BRIDGE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15",
          "--density", "1800"]
ARCH = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
FILL = Loads(fill=Fill(depth=1.0, density=1800.0))
LAMBDA = loaded_collapse(seismic_case(ARCH, FILL)).multiplier


def _json(capsys, argv):
    assert cli_main.main(["run", *BRIDGE, *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_lambda_of_the_oracle():
    assert LAMBDA == pytest.approx(0.0819, abs=1e-4)


@pytest.mark.parametrize("model", ["rigid", "dem"])
def test_below_the_loaded_lambda_the_filled_arch_stays_still(capsys, model):
    step = ["--pulse", "step", "--magnitude", f"{0.9 * LAMBDA:.6f}", "--duration", "0.3",
            "--t-end", "0.5", "--model", model]
    bare = _json(capsys, step)
    filled = _json(capsys, [*step, "--fill-depth", "1"])
    assert bare["onset_time_s"] is not None  # 0.074 g > 0.049 g: the bare arch rocks
    assert filled["outcome"] == "no_hinging" and filled["onset_time_s"] is None
    assert "masses" not in bare["assembly"] and "loads" not in bare["assembly"]
    masses = filled["assembly"]["masses"]
    assert masses["carried_mass_kg"] == pytest.approx(float(block_extras(ARCH, FILL).mass.sum()),
                                                      rel=1e-12)
    assert masses["masonry_mass_kg"] == pytest.approx(ARCH.mass, rel=1e-12)
    assert "not modelled" in masses["passive_pressure"]
    assert filled["assembly"]["loads"]["fill"]["depth_m"] == 1.0


@pytest.mark.parametrize("model", ["rigid", "dem"])
def test_above_the_loaded_lambda_the_filled_arch_rocks(capsys, model):
    out = _json(capsys, ["--pulse", "step", "--magnitude", f"{1.3 * LAMBDA:.6f}",
                         "--duration", "0.3", "--t-end", "0.5", "--model", model,
                         "--fill-depth", "1"])
    assert out["onset_time_s"] is not None


def test_the_text_output_names_the_carried_mass_and_the_passive_pressure(capsys):
    assert cli_main.main(["run", *BRIDGE, "--pulse", "step", "--magnitude", "0.05",
                          "--duration", "0.1", "--t-end", "0.3", "--fill-depth", "1"]) == 0
    text = capsys.readouterr().out
    assert "carried mass        40781.4 kg on 16964.6 kg of masonry" in text
    assert "passive fill pressure not modelled in the dynamics" in text


@pytest.mark.parametrize("extra, message", [
    (["--fill-depth", "1", "--passive", "0.33"], "--passive: passive fill pressure not modelled"),
    (["--point-load", "3,10,still"], "--point-load ...,still"),
    (["--distributed-load", "1,3,10,still"], "--distributed-load ...,still"),
    (["--point-load", "30,10"], "--point-load position"),
])
def test_loads_the_dynamics_do_not_carry_exit_2_with_one_line(capsys, extra, message):
    assert cli_main.main(["run", *BRIDGE, "--pulse", "step", "--magnitude", "0.3",
                          "--duration", "0.1", *extra]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


THICK = ["--radius", "5", "--thickness", "0.75", "--embrace", "180", "--voussoirs", "15",
         "--density", "1800", "--fill-depth", "1", "--backing", "1.5", "--pulse", "step",
         "--magnitude", "0.6", "--duration", "0.1"]


def test_thrust_with_fill_and_backing_numbers_the_arch_joints(capsys):
    """The joints inside the backing (0, 1 and 14, 15: their extrados ends below 1.5 m) carry
    no line of thrust; the others keep the arch's joint numbers."""
    assert cli_main.main(["thrust", *THICK, "--times", "0.05", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    state = out["states"][0]
    assert len(state["relative_eccentricity"]) == 16
    assert [j for j, e in enumerate(state["relative_eccentricity"]) if e is None] == [0, 1, 14, 15]
    assert all(2 <= j <= 13 for j in state["face_joints"])
    assert out["assembly"]["masses"]["held_by_backing"] == [0, 1, 13, 14]


def test_friction_with_loads_sets_the_loaded_statics_beside_it(capsys):
    from archquake.geometry.loads import Backing
    from archquake.limit import limit_analysis

    assert cli_main.main(["friction", *THICK, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    loads = Loads(fill=Fill(depth=1.0, density=1800.0), backing=Backing(1.5))
    static = limit_analysis(Arch(5.0, 0.75, math.pi, 15, 1.0, 1800.0), loads=loads)
    assert out["static_friction_demand"] == pytest.approx(static.min_friction, rel=1e-9)
    assert 2 <= out["joint"] <= 13
    assert out["assembly"]["loads"]["backing"] == {"left_m": 1.5, "right_m": 1.5}


def test_domain_with_fill_starts_at_the_loaded_lambda_and_says_what_the_chain_does(capsys):
    """The rigid chain's domain of the filled bridge at t_p = 0.3 s: no hinging below the
    loaded lambda (1e-12), and single runs of the same chain either side of the boundary
    (0.01 g brackets) collapse above it and not below."""
    from archquake.blocks.assembly import build_arch_assembly
    from archquake.compare.domains import DOMAIN_TAIL
    from archquake.constants import STANDARD_GRAVITY as G
    from archquake.ground import StepImpulse
    from archquake.rigid import rigid_verdict

    assert cli_main.main(["domain", *BRIDGE, "--fill-depth", "1", "--durations", "0.3",
                          "--workers", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    point = out["block_governing"]["points"][0]
    assert point["no_hinging_g"] == pytest.approx(LAMBDA, rel=1e-12)
    assert out["fourlink"][0]["no_hinging_g"] == pytest.approx(LAMBDA, rel=1e-12)
    assert out["assembly"]["masses"]["carried_mass_kg"] > 0
    asm = build_arch_assembly(ARCH, loads=FILL)
    window = 3 * 0.3 + DOMAIN_TAIL * math.sqrt(ARCH.radius / G)

    def outcome(magnitude):
        return rigid_verdict(asm, StepImpulse.from_g(magnitude, 0.3), duration=window
                             ).outcome.value

    assert outcome(point["collapse_g"]) == "collapse"
    assert outcome(point["collapse_g"] - 0.01) != "collapse"


def test_domain_with_asymmetric_loads_is_the_block_models_alone(capsys, tmp_path):
    """A wall off the crown: the four-link model (its impacts need the mirror-image mechanism)
    is not set beside the rigid chain, whose domain starts at the loaded lambda."""
    loads = Loads(fill=FILL.fill, point_loads=(PointLoad(3.0, 20e3),))
    lam = loaded_collapse(seismic_case(ARCH, loads)).multiplier
    argv = ["domain", *BRIDGE, "--fill-depth", "1", "--point-load", "3,20", "--durations",
            "0.3", "--workers", "1"]
    assert cli_main.main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["governing"]["points"][0]["no_hinging_g"] == pytest.approx(lam, rel=1e-12)
    assert cli_main.main([*argv, "--plot", str(tmp_path / "d.png")]) == 2
    assert "--plot" in capsys.readouterr().err


def test_the_four_link_model_carries_the_fill_on_its_links(capsys):
    """run and domain with --model fourlink: lambda is the loaded statics' (1e-12), the links'
    masses add up to the masonry and the fill, and a step 10 % below lambda leaves it still."""
    out = _json(capsys, ["--model", "fourlink", "--fill-depth", "1", "--pulse", "step",
                         "--magnitude", f"{0.9 * LAMBDA:.6f}", "--duration", "0.3"])
    assert out["outcome"] == "no_hinging"
    masses = out["masses"]
    assert sum(masses["voussoir_masses_kg"]) == pytest.approx(
        ARCH.mass + float(block_extras(ARCH, FILL).mass.sum()), rel=1e-12)
    assert "not modelled" in masses["passive_pressure"] and out["loads"]["fill"]["depth_m"] == 1
    assert cli_main.main(["domain", *BRIDGE, "--model", "fourlink", "--fill-depth", "1",
                          "--durations", "0.3", "--scan", "10", "--precision", "0.01",
                          "--json"]) == 0
    dom = json.loads(capsys.readouterr().out)
    assert dom["rows"][0]["no_hinging_g"] == pytest.approx(LAMBDA, rel=1e-12)
    assert dom["masses"]["carried_mass_kg"] == pytest.approx(masses["carried_mass_kg"])
    assert cli_main.main(["thrust", *BRIDGE, "--model", "fourlink", "--fill-depth", "1",
                          "--pulse", "step", "--magnitude", "0.3", "--duration", "0.1"]) == 2
    assert "--model fourlink does not carry" in capsys.readouterr().err
