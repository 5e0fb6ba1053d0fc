"""`archquake.models.to_dict`: a library user gets the dict that ``archquake run --json``
prints, for each model.

Oracle: the command line's own output, through the real entry point, on the same arch, motion
and options. The comparison is exact (the same floats, through the same JSON conversion),
except the rigid stepper's wall time (``rigid.wall_s``), a clock reading. The loaded cases are
those where the library completes the result's ``to_dict()``: the rigid chain's joint forces
numbered as the arch's joints (a backing 2 m high holds voussoirs 0 and 6 of Oppenheim's arch,
and the joints inside it are not recorded), the four-link model's loads and link masses.
"""

from __future__ import annotations

import json
import math

import pytest

from archquake import models
from archquake._json import to_jsonable
from archquake.cli import main as cli_main
from archquake.geometry import Arch
from archquake.geometry.loads import Backing, Fill, Loads
from archquake.ground import StepImpulse
from archquake.rigid.forces import joint_numbers

ARCH = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
MOTION = StepImpulse.from_g(1.0, 0.27)
STEP = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.27"]
LOADED = Loads(fill=Fill(depth=0.3, density=1800.0), backing=Backing(2.0))


def _cli(capsys, argv: list[str]) -> dict:
    assert cli_main.main(["run", *STEP, *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _library(model: str, body, options: models.RunOptions):
    """The result of ``models.run`` and its ``models.to_dict`` through JSON."""
    result = models.run(model, body, MOTION, options=options)
    return result, json.loads(json.dumps(to_jsonable(models.to_dict(result, ARCH, MOTION)),
                                         allow_nan=False))


def _without_wall_time(out: dict) -> dict:
    if "rigid" in out:
        out = {**out, "rigid": {k: v for k, v in out["rigid"].items() if k != "wall_s"}}
    return out


@pytest.mark.parametrize("loaded", [False, True])
def test_the_rigid_chain_to_a_verdict(capsys, loaded):
    argv = ["--fill-depth", "0.3", "--backing", "2.0"] if loaded else []
    cli = _cli(capsys, ["--model", "rigid", *argv])
    result, lib = _library("rigid", ARCH, models.RunOptions(loads=LOADED if loaded else None))
    assert "guard" in cli and cli["joint_forces"]["samples"] > 0
    assert _without_wall_time(lib) == _without_wall_time(cli)
    if loaded:  # voussoirs 0 and 6 held: the springing joints 0 and 7 are not recorded, and
        # the recorded joint k is the arch's joint k + 1
        assert joint_numbers(result.run) == [1, 2, 3, 4, 5, 6]
        recorded = result.run.joint_forces.summary()["max_friction_demand_joint"]
        assert lib["joint_forces"]["max_friction_demand_joint"] == recorded + 1
    else:
        assert joint_numbers(result.run) is None


def test_the_rigid_chain_with_friction_for_a_given_time(capsys):
    cli = _cli(capsys, ["--friction", "0.6", "--t-end", "1.0"])
    _, lib = _library("rigid", ARCH, models.RunOptions(friction=0.6, t_end=1.0))
    assert _without_wall_time(lib) == _without_wall_time(cli)


@pytest.mark.parametrize("loaded", [False, True])
def test_the_four_link_mechanism(capsys, loaded):
    argv = ["--fill-depth", "0.3", "--backing", "2.0"] if loaded else []
    cli = _cli(capsys, ["--model", "fourlink", *argv])
    _, lib = _library("fourlink", ARCH, models.RunOptions(loads=LOADED if loaded else None))
    assert ("masses" in cli) is loaded and ("loads" in cli) is loaded
    if loaded:  # the voussoirs' masses add up to the masonry's and the carried (to rounding)
        masses = cli["masses"]
        assert sum(masses["voussoir_masses_kg"]) == pytest.approx(
            masses["masonry_mass_kg"] + masses["carried_mass_kg"], rel=1e-12)
        assert sum(masses["carried_masses_kg"]) == pytest.approx(masses["carried_mass_kg"],
                                                                 rel=1e-12)
    assert lib == cli


def test_the_distinct_element_model(capsys):
    from archquake.cli.dem_options import DEFAULT_RAYLEIGH, DEFAULT_STIFFNESS
    from archquake.compare import dem_assembly
    from archquake.dem import ContactLaw, DemSettings

    cli = _cli(capsys, ["--model", "dem", "--t-end", "0.05"])
    settings = DemSettings(contact=ContactLaw(normal_stiffness=DEFAULT_STIFFNESS),
                           damping=DEFAULT_RAYLEIGH, duration=0.05)
    _, lib = _library("dem", dem_assembly(ARCH, "voussoirs"),
                   models.RunOptions(t_end=0.05, dem=settings))
    assert lib == cli
