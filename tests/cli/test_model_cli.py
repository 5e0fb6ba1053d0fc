"""``--model rigid|fourlink|dem`` on every command that runs a time history: the chain of rigid
voussoirs is the default, the four-link mechanism gives the numbers it always gave, the
retired spellings (``--model analytical``, ``--hinges``) get one line pointing at the new one,
and each model's own options are refused with another model (exit status 2).

Oracles: the DEM's Figure 4(a) collapse time (1.508 s, docs/notes/mechanism.md), which the rigid
chain, its rigid limit, matches within 3 %; the four-link model's Figure 4(d) numbers as the
README shows them (first impact 0.601 s, c_v = 0.8754: the paper's about 0.6 s); the flat API
called directly."""

from __future__ import annotations

import json

import pytest

import archquake
from archquake.cli.main import main
from archquake.outcome import RESULT_KEYS

FIG4A = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.44"]
FIG4D = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.20"]


def _json(capsys, *args):
    assert main([*args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_rigid_chain_is_the_default_of_run(capsys):
    """Figure 4(a), Oppenheim's arch: the default run collapses in the first half cycle with no
    impact at the DEM's 1.508 s (within 0.03 s, 2 %); the JSON has every model's keys, names the
    model as --model does, and equals the flat API's run."""
    out = _json(capsys, "run", *FIG4A, "--t-end", "2.0")
    assert out == _json(capsys, "run", "--model", "rigid", *FIG4A, "--t-end", "2.0") | {
        "rigid": out["rigid"]}  # the same run but its wall time
    for key in RESULT_KEYS:
        assert key in out
    assert out["model"] == "rigid"
    assert out["outcome"] == "collapse" and out["collapse_half_cycle"] == 1
    assert out["impact_times_s"] == [] and abs(out["collapse_time_s"] - 1.508) < 0.03
    api = archquake.simulate_rigid(archquake.Arch(10.0, 1.5, 2.748893571891069, 7),
                                   archquake.StepImpulse.from_g(1.0, 0.44), duration=2.0)
    assert api.to_dict()["collapse_time_s"] == out["collapse_time_s"]


def test_fourlink_gives_the_numbers_it_always_gave(capsys):
    """Figure 4(d) under --model fourlink: survives, first impact 0.601 s, c_v = 0.8754 (the
    README's output; the paper's first impact is about 0.6 s)."""
    out = _json(capsys, "run", "--model", "fourlink", *FIG4D)
    assert out["model"] == "fourlink" and out["outcome"] == "survives"
    assert out["impact_times_s"][0] == pytest.approx(0.601, abs=5e-4)
    assert out["restitution_cv"] == pytest.approx(0.8754, abs=5e-5)


def test_rigid_text_output_and_files(capsys, tmp_path):
    """Text like the four-link run's, with the hinge sets; the rotation plot (with the hinge
    sets below it) and the animation (hinges marked) of the DEM, reused."""
    plot, gif = tmp_path / "r.png", tmp_path / "r.gif"
    assert main(["run", *FIG4A, "--t-end", "1.6", "--plot", str(plot), "--animate",
                 str(gif)]) == 0
    text = capsys.readouterr().out
    assert "rigid: chain of rigid voussoirs" in text and "collapse in half cycle 1" in text
    assert "hinge sets" in text and "onset" in text
    assert plot.stat().st_size > 10_000 and gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")


def test_hinge_sets_and_joint_forces_in_json(capsys):
    """Every hinge set with its time and degrees of freedom, keyed as the four-link model's
    ``mechanisms``; under Figure 4(a)'s pulse the arch opens 0i 2e 5i 7e (the DEM's too)."""
    out = _json(capsys, "run", *FIG4A, "--t-end", "1.0")
    sets = out["mechanisms"]
    assert sets[0]["kind"] == "onset"
    assert all(e["degrees_of_freedom"] == max(len(e["hinges"].split()) - 3, 0) for e in sets)
    assert "0i 2e 5i 7e" in [e["hinges"] for e in sets]
    jf = out["joint_forces"]  # the mechanism's own thrust line and friction demand
    assert 0.0 < jf["max_friction_demand"] < 1.0 and "rule" in jf


def test_integrated_from_event_to_event(capsys):
    """``--integrator events``: the same chain integrated from contact event to contact event
    gives Figure 4(a)'s collapse in the first half cycle at the time steps' instant (within
    0.03 s), and its JSON lists every event from the onset on."""
    out = _json(capsys, "run", "--integrator", "events", *FIG4A, "--t-end", "2.0")
    steps = _json(capsys, "run", "--integrator", "steps", *FIG4A, "--t-end", "2.0")
    assert out["outcome"] == steps["outcome"] == "collapse" and out["collapse_half_cycle"] == 1
    assert abs(out["collapse_time_s"] - steps["collapse_time_s"]) < 0.03
    rig = out["rigid"]
    assert rig["solver"] == "events" and rig["time_step_s"] is None
    log = rig["events"]["log"]
    assert log[0]["kind"] == "onset" and log[0]["time_s"] == 0.0 and log[0]["hinges_after"] >= 4
    assert main(["run", "--integrator", "events", *FIG4A, "--t-end", "2.0"]) == 0
    assert "from event to event" in capsys.readouterr().out


ARCH = ["--radius", "10", "--thickness", "1.5", "--embrace", "157.5", "--voussoirs", "7"]
IDA = ["ida", "--records", "near-field-pulse"]


@pytest.mark.parametrize("argv, message", [
    (["run", "--hinges", "moving", *FIG4A], "--hinges is retired: use --model rigid"),
    (["run", "--model", "analytical", "--hinges", "fixed", *FIG4A],
     "--hinges is retired: use --model fourlink"),
    (["run", "--model", "fem", *FIG4A], "--model must be one of rigid, fourlink, dem, got 'fem'"),
    (["run", *FIG4A, "--impact", "chain"], "--impact applies only to --model fourlink"),
    (["run", *FIG4A, "--restitution", "0.5"], "--restitution applies only to --model fourlink"),
    (["run", "--model", "dem", *FIG4A, "--restitution", "0.5"], "--restitution applies only"),
    (["run", "--model", "fourlink", "--integrator", "events", *FIG4A],
     "--integrator applies only to --model rigid"),
    (["run", "--model", "dem", "--integrator", "steps", *FIG4A], "--integrator applies only"),
    (["run", *FIG4A, "--stiffness", "1e9"], "--stiffness"),
    (["run", "--model", "fourlink", *FIG4A, "--friction", "0.5"], "--friction"),
    (["run", *FIG4A, "--t-end", "10001"], "--t-end"),
    (["run", "--integrator", "events", "--friction", "0.5", *FIG4A],
     "--integrator events has no sliding"),
    ([*IDA, "--hinges", "moving"], "--hinges is retired: use --model rigid"),
    ([*IDA, "--restitution", "0.5"], "--restitution applies only to --model fourlink"),
    (["domain", "--impact", "chain"], "--impact applies only to --model fourlink"),
    (["domain", "--model", "fourlink", "--workers", "2"], "--workers"),
    (["friction", *FIG4A, "--model", "dem"], "--model must be rigid or fourlink here"),
    (["thrust", *FIG4A, "--plot", "t.png"], "--plot applies only with --model fourlink"),
])
def test_bad_combinations_are_one_line_exit_2(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main([*argv, *ARCH]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_run_to_a_verdict_prints_the_guarded_verdict_at_the_scaled_step(capsys):
    """Without --t-end the chain is integrated once, at the step scaled with the arch (1e-3 s
    on Oppenheim's arch), and its verdict is guarded. Oracle: the DEM's Figure 4(a) collapse
    (first half cycle, 1.508 s), which the rigid chain matches within 3 % (docs/mechanism.md);
    a collapse in the first half cycle (no impact) is not near a threshold: no rerun."""
    out = _json(capsys, "run", *FIG4A)
    v = out["guard"]
    assert v["time_step_s"] == pytest.approx(1.0e-3, rel=0.01)
    assert out["rigid"]["time_step_s"] == v["time_step_s"]
    assert out["outcome"] == "collapse" and not v["ran"] and v["outcome"] is None
    assert "rigid_verdict" not in out and "history_outcome" not in out
    assert out["collapse_half_cycle"] == 1
    assert out["collapse_time_s"] == pytest.approx(1.508, rel=0.03)
    assert main(["run", *FIG4A]) == 0
    assert "verdict's step      0.001 s" in capsys.readouterr().out


def test_the_words_of_the_last_release_warn_and_map(capsys):
    """``--model analytical`` (the four-link model's earlier name) still runs the four-link
    model for one release, with one warning line on stderr. Oracle: the same command under
    ``--model fourlink``."""
    assert main(["run", *FIG4A, "--model", "fourlink", "--json"]) == 0
    now = capsys.readouterr()
    assert main(["run", *FIG4A, "--model", "analytical", "--json"]) == 0
    old = capsys.readouterr()
    assert old.out == now.out and now.err == ""
    assert old.err.strip() == ("archquake: warning: --model analytical is deprecated and will "
                               "be removed in the next release: use --model fourlink")
