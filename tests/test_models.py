"""`archquake.models.run`, the one way into the three models.

Oracles: each model's own driver called directly (`archquake.mechanism.simulate`,
`archquake.rigid.simulate_rigid`, `archquake.rigid.rigid_verdict`), whose results the seam must
give byte for byte; the compiled verdict path's guard (`rigid_verdict`), against which the
once-integrated run's guard (`run_guarded`) is held; the command line's default model.
"""

from __future__ import annotations

import math

import pytest

import archquake
from archquake import Arch, StepImpulse
from archquake.errors import InvalidParameterError
from archquake.models import DEFAULT_MODEL, MODELS, Model, RunOptions, run, summary, takes
from archquake.outcome import RESULT_KEYS
from archquake.rigid import rigid_verdict, simulate_rigid
from archquake.rigid.run import GuardedRun, lengthening, run_guarded

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
PULSE = StepImpulse.from_g(1.0, 0.27)  # the paper's Figure 4(c): collapse in half cycle 2


def test_the_four_link_run_is_simulate():
    from archquake.mechanism import PreparedMechanism, SolverOptions
    from archquake.mechanism.simulate import simulate

    prep = PreparedMechanism.build(OPPENHEIM)
    assert run("fourlink", OPPENHEIM, PULSE).to_dict() == simulate(prep, PULSE).to_dict()
    ref = simulate(prep, PULSE, restitution=0.5, options=SolverOptions(output_interval=0.0))
    got = run(Model.FOURLINK, OPPENHEIM, PULSE, options=RunOptions(restitution=0.5),
              to_verdict=True)
    assert summary(got) == ref.to_dict(include_history=False)


def test_the_rigid_runs_are_the_rigid_drivers():
    verdict = run("rigid", OPPENHEIM, PULSE, to_verdict=True)
    assert verdict.to_dict() == rigid_verdict(OPPENHEIM, PULSE).to_dict()
    got = summary(run("rigid", OPPENHEIM, PULSE, options=RunOptions(t_end=1.0)))
    ref = simulate_rigid(OPPENHEIM, PULSE, duration=1.0).to_dict(joint_forces=False)
    for out in (got, ref):
        del out["rigid"]["wall_s"]  # the only number that is not the model's
    assert got == ref


def test_the_default_is_the_command_line_s_and_every_summary_starts_alike():
    assert DEFAULT_MODEL is Model.RIGID
    default = run(DEFAULT_MODEL, OPPENHEIM, PULSE)
    assert isinstance(default, GuardedRun)
    assert isinstance(default, archquake.ModelResult)  # the shared interface, through the run
    for model in Model:
        if model is Model.DEM:
            continue  # a DEM run costs seconds; its keys are held in tests/dem
        out = summary(run(model, OPPENHEIM, PULSE, to_verdict=True))
        assert tuple(out)[:len(RESULT_KEYS)] == RESULT_KEYS and out["model"] == model.value


def test_the_flat_api_runs_the_default_model():
    assert archquake.run is run and archquake.Model is Model
    out = archquake.run(DEFAULT_MODEL, OPPENHEIM, PULSE, to_verdict=True)
    assert out.outcome.value == "collapse" and out.collapse_half_cycle == 2


@pytest.mark.parametrize("model, options, named", [
    ("rigid", RunOptions(restitution=0.5), "restitution applies to model fourlink only"),
    ("dem", RunOptions(impact="chain"), "impact applies to model fourlink only"),
    ("fourlink", RunOptions(friction=0.6), "friction applies to model rigid and dem only"),
    ("fourlink", RunOptions(integrator="events"), "integrator applies to model rigid only"),
    ("dem", RunOptions(guard=False), "guard applies to model rigid only"),
    ("rigid", RunOptions(time_step=1e-4, guard=False), "guard applies to a rigid run"),
    ("fem", RunOptions(), "model must be one of rigid, fourlink, dem, got 'fem'"),
])
def test_an_option_a_model_does_not_take_is_refused_in_one_line(model, options, named):
    with pytest.raises(InvalidParameterError, match=f"^{named}") as err:
        run(model, OPPENHEIM, PULSE, options=options)
    assert "\n" not in str(err.value)


def test_each_option_belongs_to_a_model():
    """Every option but the shared ones is taken by some model (none is dead)."""
    taken = set().union(*(spec.takes for spec in MODELS.values()))
    assert taken == {"restitution", "impact", "friction", "integrator", "time_step", "guard",
                     "dem"}
    assert takes("fourlink", "loads") and not takes("fourlink", "dem") and takes("rigid", "dem")


@pytest.mark.parametrize("magnitude, tp", [(1.0, 0.27), (0.7, 0.44), (1.5, 0.2), (0.5, 0.6)])
def test_the_once_integrated_run_guards_as_the_verdict_path(magnitude, tp):
    """The recorded run at the verdict's step gives the compiled verdict path's outcome, and
    its guard reruns where the verdict path's does; its lengthening is the kernel's to the
    recorded impacts' sampling (5e-4 s over a first half cycle of about 1 s)."""
    motion = StepImpulse.from_g(magnitude, tp)
    v = rigid_verdict(OPPENHEIM, motion)
    g = run_guarded(OPPENHEIM, motion)
    assert g.outcome is v.outcome and g.guard_ran == v.guard_ran
    assert g.guard_outcome is v.guard_outcome and g.time_step_s == v.time_step_s
    assert lengthening(g.run) == pytest.approx(v.lengthening, abs=0.02)
    assert g.to_dict()["guard"]["ran"] == v.guard_ran


def test_a_dem_run_to_a_verdict_needs_a_radius():
    """The DEM's default window scales with sqrt(R/g): a block on its base has no R, so the
    run asks for its end in one line (it raised a TypeError)."""
    from archquake.dem import block_on_base

    block = block_on_base(0.2, 1.0)
    assert block.radius is None
    with pytest.raises(InvalidParameterError, match="^give t_end"):
        run("dem", block, PULSE)


def test_a_word_of_the_last_release_warns_at_the_caller_s_line():
    """``run("analytical", ...)`` runs the four-link model for one more release; the
    DeprecationWarning points at the line that called `run` (so Python's default filters show
    it in a script). Oracle: the same run under ``fourlink``."""
    with pytest.warns(DeprecationWarning, match="model analytical is deprecated") as caught:
        old = run("analytical", OPPENHEIM, PULSE, to_verdict=True)
    assert caught[0].filename == __file__
    assert old.to_dict() == run("fourlink", OPPENHEIM, PULSE, to_verdict=True).to_dict()
