"""The rigid chain as the default sweep model, and the models' words.

Oracles: :func:`archquake.rigid.simulate_rigid` called directly with the window
``archquake run`` documents (the end of the excitation + 5 sqrt(R/g), on until rest up to the
end of the excitation + 60 sqrt(R/g)); the pinned id of an existing four-link case."""

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
    """The default model of a case is the rigid chain, run to a verdict."""
    case = Case(OPPENHEIM, STEP)
    assert case.model is Model.RIGID
    out = evaluate_case(case)
    arch, motion = OPPENHEIM.build(), STEP.build()
    cap = motion.duration + 60 * math.sqrt(arch.radius / STANDARD_GRAVITY)
    ref = simulate_rigid(arch, motion, duration=default_dem_duration(arch, motion),
                         until_rest=cap).to_dict(joint_forces=False)
    for key in ("outcome", "collapse_half_cycle", "collapse_time_s", "impact_times_s",
                "peak_rotation_rad", "end_time_s", "verdict", "model"):
        assert out[key] == ref[key], key
    assert out["model"] == "rigid" and "joint_forces" not in out
    # the window went past the first 5 sqrt(R/g) only if the arch still moved: a verdict either way
    assert out["outcome"] in ("survives", "collapse", "no_hinging")


def test_rigid_case_refuses_impact_options_and_keeps_existing_ids():
    for opts in (CaseOptions(restitution=0.5), CaseOptions(impact="chain")):
        with pytest.raises(InvalidParameterError, match="applies to model fourlink only"):
            evaluate_case(Case(OPPENHEIM, STEP, Model.RIGID, opts))
    # a four-link case keeps the pinned id of its stores (tests/sweeps/test_cases.py), the
    # rigid one differs
    assert Case(OPPENHEIM, STEP, "fourlink").case_id == "aec2e12de1ef622838a5"
    assert Case(OPPENHEIM, STEP).case_id != "aec2e12de1ef622838a5"


def test_model_of_uses_the_words_of_run():
    """``--model rigid|fourlink|dem``, default rigid; the retired words point at the new ones."""
    assert model_of() is Model.RIGID
    assert model_of("fourlink") is Model.FOURLINK
    assert model_of("dem") is Model.DEM
    for words, match in ((("analytical",), "^--model analytical is retired: use --model fourlink"),
                         ((None, "moving"), "^--hinges is retired: use --model rigid$"),
                         ((None, "fixed"), "^--hinges is retired: use --model fourlink$"),
                         (("rigid_chain",), "^--model rigid_chain is retired: use --model rigid"),
                         (("fem",), "^--model must be one of rigid, fourlink, dem, got 'fem'")):
        with pytest.raises(InvalidParameterError, match=match):
            model_of(*words, model_name="--model", hinges_name="--hinges")


def _study(**study) -> dict:
    return {"study": {"name": "s", **study},
            "arches": {"radius": 10, "thickness_ratio": 0.15, "embrace_deg": 157.5,
                       "voussoirs": 7},
            "excitation": {"type": "step", "magnitude_g": 0.5, "duration_s": 0.25}}


def test_study_model_words():
    assert parse_study(_study()).model is Model.RIGID
    assert parse_study(_study(model="fourlink")).cases[0].case_id == "aec2e12de1ef622838a5"
    for bad, match in (({"hinges": "moving"}, "study.hinges is retired: use study.model rigid"),
                       ({"model": "analytical"}, "study.model analytical is retired"),
                       ({"model": "fem"}, "study.model must be one of rigid, fourlink, dem")):
        with pytest.raises(StudyFileError, match=match):
            parse_study(_study(**bad))
