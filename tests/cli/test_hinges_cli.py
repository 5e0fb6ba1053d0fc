"""``archquake run --hinges fixed|moving``: the paper's fixed-hinge model and the chain of rigid
blocks (issue 16) on the command line and in the flat API; meaningless combinations refused in
one line with exit status 2."""

from __future__ import annotations

import json

import pytest

import archquake
from archquake.cli.main import main
from archquake.outcome import RESULT_KEYS

FIG4A = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.44"]


def _json(capsys, *args):
    assert main(["run", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_moving_hinges_run_the_rigid_chain(capsys):
    """Figure 4(a), Oppenheim's arch: the rigid chain collapses in the first half cycle with no
    impact at 1.50 s, as the DEM does (1.508 s, docs/mechanism.md); the JSON has every model's
    keys, and equals the flat API's run."""
    out = _json(capsys, "--hinges", "moving", *FIG4A, "--t-end", "2.0")
    for key in RESULT_KEYS:
        assert key in out
    assert out["model"] == "rigid_chain" and out["hinges_model"] == "moving"
    assert out["outcome"] == "collapse" and out["collapse_half_cycle"] == 1
    assert out["impact_times_s"] == [] and abs(out["collapse_time_s"] - 1.508) < 0.03
    api = archquake.simulate_rigid(archquake.Arch(10.0, 1.5, 2.748893571891069, 7),
                                   archquake.StepImpulse.from_g(1.0, 0.44), duration=2.0)
    assert api.to_dict()["collapse_time_s"] == out["collapse_time_s"]


def test_fixed_hinges_is_the_default(capsys):
    """``--hinges fixed`` is the paper's model, the same run as no --hinges."""
    a = _json(capsys, "--hinges", "fixed", *FIG4A)
    b = _json(capsys, *FIG4A)
    assert a["model"] == b["model"] == "analytical" and a == b


def test_moving_hinges_text_output_and_files(capsys, tmp_path):
    """Text like ``run``'s, with the hinge sets; the rotation plot (with the hinge sets below
    it) and the animation (hinges marked) of the DEM, reused."""
    plot, gif = tmp_path / "r.png", tmp_path / "r.gif"
    assert main(["run", "--hinges", "moving", *FIG4A, "--t-end", "1.6", "--plot", str(plot),
                 "--animate", str(gif)]) == 0
    text = capsys.readouterr().out
    assert "hinges moving: chain of rigid blocks" in text and "collapse in half cycle 1" in text
    assert "hinge sets" in text and "onset" in text
    assert plot.stat().st_size > 10_000 and gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")


def test_hinge_sets_in_json(capsys):
    """Every hinge set with its time and degrees of freedom, keyed as the fixed-hinge model's
    ``mechanisms``; under Figure 4(a)'s pulse the arch opens 0i 2e 5i 7e (the DEM's too)."""
    out = _json(capsys, "--hinges", "moving", *FIG4A, "--t-end", "1.0")
    sets = out["mechanisms"]
    assert sets[0]["kind"] == "onset"
    assert all(e["degrees_of_freedom"] == max(len(e["hinges"].split()) - 3, 0) for e in sets)
    assert "0i 2e 5i 7e" in [e["hinges"] for e in sets]
    jf = out["joint_forces"]  # the mechanism's own thrust line and friction demand
    assert 0.0 < jf["max_friction_demand"] < 1.0 and "rule" in jf


@pytest.mark.parametrize("extra, named", [
    (["--model", "dem", "--hinges", "moving"], "--hinges moving"),
    (["--model", "dem", "--hinges", "fixed"], "--hinges fixed"),
    (["--hinges", "moving", "--impact", "chain"], "--impact"),
    (["--hinges", "moving", "--restitution", "0.5"], "--restitution"),
    (["--hinges", "moving", "--stiffness", "1e9"], "--stiffness"),
    (["--hinges", "fixed", "--friction", "0.5"], "--friction"),
    (["--hinges", "moving", "--t-end", "500"], "--t-end"),
])
def test_meaningless_combinations_are_refused(capsys, extra, named):
    assert main(["run", *FIG4A, *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and named in err[0]


def test_moving_hinges_integrated_from_event_to_event(capsys):
    """``--integrator events``: the same chain integrated from contact event to contact event
    gives Figure 4(a)'s collapse in the first half cycle at the time steps' instant (1.508 s,
    within 0.03 s), and its JSON lists every event from the onset on."""
    out = _json(capsys, "--hinges", "moving", "--integrator", "events", *FIG4A, "--t-end", "2.0")
    steps = _json(capsys, "--hinges", "moving", *FIG4A, "--t-end", "2.0")
    assert out["outcome"] == steps["outcome"] == "collapse" and out["collapse_half_cycle"] == 1
    assert abs(out["collapse_time_s"] - steps["collapse_time_s"]) < 0.03
    rig = out["rigid"]
    assert rig["solver"] == "events" and rig["time_step_s"] is None
    log = rig["events"]["log"]
    assert log[0]["kind"] == "onset" and log[0]["time_s"] == 0.0 and log[0]["hinges_after"] >= 4
    assert main(["run", "--hinges", "moving", "--integrator", "events", *FIG4A,
                 "--t-end", "2.0"]) == 0
    assert "from event to event" in capsys.readouterr().out


@pytest.mark.parametrize("argv, message", [
    (["--integrator", "events"], "--integrator events applies only with --hinges moving"),
    (["--hinges", "moving", "--integrator", "events", "--friction", "0.5"],
     "--integrator events has no sliding"),
])
def test_integrator_refusals_are_one_line_exit_2(argv, message, capsys):
    assert main(["run", *argv, *FIG4A]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err
