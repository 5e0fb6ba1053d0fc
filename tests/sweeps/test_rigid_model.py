"""The rigid chain (hinges moving) as a sweep model (issue 16).

Oracles: :func:`archquake.rigid.simulate_rigid` called directly with the window
``run --hinges moving`` documents (the end of the excitation + 5 sqrt(R/g), on until rest up to
the end of the excitation + 60 sqrt(R/g)); the pinned id of an existing analytical case."""

from __future__ import annotations

import math

import pytest

from archquake.compare import default_dem_duration
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError, StudyFileError
from archquake.rigid import simulate_rigid
from archquake.sweeps import (
    ArchSpec,
    Case,
    CaseOptions,
    ExcitationSpec,
    Model,
    evaluate_case,
    model_of,
)
from archquake.sweeps.study import parse_study

OPPENHEIM = ArchSpec(10, 0.15, 157.5, 7)
STEP = ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25)


def test_rigid_case_equals_simulate_rigid():
    case = Case(OPPENHEIM, STEP, Model.RIGID)
    out = evaluate_case(case)
    arch, motion = OPPENHEIM.build(), STEP.build()
    cap = motion.duration + 60 * math.sqrt(arch.radius / STANDARD_GRAVITY)
    ref = simulate_rigid(arch, motion, duration=default_dem_duration(arch, motion),
                         until_rest=cap).to_dict(joint_forces=False)
    for key in ("outcome", "collapse_half_cycle", "collapse_time_s", "impact_times_s",
                "peak_rotation_rad", "end_time_s", "verdict", "model", "hinges_model"):
        assert out[key] == ref[key], key
    assert out["model"] == "rigid_chain" and "joint_forces" not in out
    # the window went past the first 5 sqrt(R/g) only if the arch still moved: a verdict either way
    assert out["outcome"] in ("survives", "collapse", "no_hinging")


def test_rigid_case_refuses_impact_options_and_keeps_existing_ids():
    for opts in (CaseOptions(restitution=0.5), CaseOptions(impact="chain")):
        with pytest.raises(InvalidParameterError, match="hinges fixed only"):
            evaluate_case(Case(OPPENHEIM, STEP, Model.RIGID, opts))
    # an existing case keeps its pinned id (tests/sweeps/test_cases.py), the rigid one differs
    assert Case(OPPENHEIM, STEP).case_id == "aec2e12de1ef622838a5"
    assert Case(OPPENHEIM, STEP, "rigid").case_id != "aec2e12de1ef622838a5"


def test_model_of_uses_the_words_of_run():
    assert model_of() is Model.ANALYTICAL
    assert model_of("analytical", "fixed") is Model.ANALYTICAL
    assert model_of("analytical", "moving") is Model.RIGID
    assert model_of("dem") is Model.DEM
    with pytest.raises(InvalidParameterError, match="^--hinges moving applies only"):
        model_of("dem", "moving", model_name="--model", hinges_name="--hinges")
    with pytest.raises(InvalidParameterError, match="with hinges moving"):
        model_of("rigid")


def _study(**study) -> dict:
    return {"study": {"name": "s", **study},
            "arches": {"radius": 10, "thickness_ratio": 0.15, "embrace_deg": 157.5,
                       "voussoirs": 7},
            "excitation": {"type": "step", "magnitude_g": 0.5, "duration_s": 0.25}}


def test_study_hinges_moving_is_the_rigid_model():
    assert parse_study(_study(hinges="moving")).model is Model.RIGID
    assert parse_study(_study(hinges="fixed")).cases[0].case_id == "aec2e12de1ef622838a5"
    for bad, match in (({"model": "dem", "hinges": "moving"}, "study.hinges moving applies"),
                       ({"model": "rigid"}, "study.model must be analytical or dem"),
                       ({"hinges": "loose"}, "study.hinges must be fixed or moving")):
        with pytest.raises(StudyFileError, match=match):
            parse_study(_study(**bad))
