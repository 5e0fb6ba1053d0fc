"""Sweep cases with what the arch carries: the loads enter a case's id only when given (bare
cases keep their ids, so stores resume), and each model evaluates the arch carrying them.

Oracle: lambda of the static analysis with the loads (:mod:`archquake.limit.loaded`): the
example bridge's semicircle with 1 m of fill, 0.0819 g (bare 0.0490 g). A step 10 % below it
leaves the filled arch still in every model, and rocks the bare one.
"""

from __future__ import annotations

import math

import pytest

from archquake._json import canonical_json
from archquake.errors import InvalidParameterError, StudyFileError
from archquake.geometry.arch import Arch
from archquake.geometry.loads import Fill, Loads, Traffic
from archquake.limit.loaded import loaded_collapse, seismic_case
from archquake.sweeps.cases import ArchSpec, Case, CaseOptions, ExcitationSpec
from archquake.sweeps.evaluate import evaluate_case
from archquake.sweeps.study import parse_study

SPEC = ArchSpec(5.0, 0.12, 180.0, 15, 1.0, 1800.0)
FILL = Loads(fill=Fill(depth=1.0, density=1800.0))
LAMBDA = loaded_collapse(seismic_case(Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0), FILL)).multiplier
STEP = ExcitationSpec("step", magnitude_g=round(0.9 * LAMBDA, 6), duration_s=0.3)


def test_bare_cases_keep_their_ids_and_loaded_ones_differ():
    bare = Case(SPEC, STEP)
    assert Case(SPEC, STEP, loads=None).case_id == bare.case_id
    assert Case(SPEC, STEP, loads=Loads()).case_id == bare.case_id
    filled = Case(SPEC, STEP, loads=FILL)
    assert filled.case_id != bare.case_id
    assert filled.canonical_json == canonical_json(filled.canonical())
    deeper = Case(SPEC, STEP, loads=Loads(fill=Fill(depth=1.5, density=1800.0)))
    assert deeper.case_id not in (bare.case_id, filled.case_id)


def test_statics_loads_are_not_a_cases():
    with pytest.raises(InvalidParameterError, match="statics only"):
        Case(SPEC, STEP, loads=Loads(fill=FILL.fill, traffic=Traffic(1e5, 3.0)))


@pytest.mark.parametrize("model", ["rigid", "fourlink", "dem"])
def test_each_model_evaluates_the_arch_carrying_its_fill(model):
    # the DEM run past the step's three lobes (0.9 s); the others to their verdicts
    options = CaseOptions(t_end_s=1.0 if model == "dem" else None)
    filled = evaluate_case(Case(SPEC, STEP, model, options, FILL))
    bare = evaluate_case(Case(SPEC, STEP, model, options))
    assert filled["outcome"] == "no_hinging"
    assert bare["outcome"] != "no_hinging"


def test_a_study_files_loads_table(tmp_path):
    study = {"study": {"name": "filled"},
             "arches": {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180.0,
                        "voussoirs": 15, "density": 1800.0},
             "excitation": {"type": "step", "magnitude_g": [0.2, 0.3], "duration_s": 0.2},
             "loads": {"fill_depth": 1.0, "fill_density": 1800.0}}
    cases = parse_study(study, source="filled.toml").cases
    assert len(cases) == 2 and all(c.loads == FILL for c in cases)
    study["loads"] = {"fill_depth": 1.0, "traffic": {"axle_kN": 100.0}}
    with pytest.raises(StudyFileError, match=r"filled.toml: loads .*statics only"):
        parse_study(study, source="filled.toml")
    study["loads"] = {"fill_depth": -1.0}
    with pytest.raises(StudyFileError, match=r"\[loads\]"):
        parse_study(study, source="filled.toml")


def test_archquake_sweep_with_a_loads_table(tmp_path, capsys, monkeypatch):
    """0.07 g, below the filled arch's lambda and above the bare one's: no hinging; 0.3 g for
    0.2 s collapses it; the summary lists the loads."""
    import json

    from archquake.cli.main import main

    monkeypatch.chdir(tmp_path)
    (tmp_path / "filled.toml").write_text(
        '[study]\nname = "filled"\n[arches]\nradius = 5.0\nthickness_ratio = 0.12\n'
        'embrace_deg = 180.0\nvoussoirs = 15\ndensity = 1800.0\n[excitation]\ntype = "step"\n'
        'magnitude_g = [0.07, 0.3]\nduration_s = 0.2\n[loads]\nfill_depth = 1.0\n')
    assert main(["sweep", "filled.toml", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcomes"] == {"collapse": 1, "no_hinging": 1}
    assert out["loads"]["fill"]["depth_m"] == 1.0 and "not modelled" in out["passive_pressure"]
