"""CLI: 'archquake thrust' and 'archquake friction' (JSON keys, figure, one-line errors), under
the four-link model (--model fourlink: the paper's numbers) and the default rigid chain (its
joint forces, :mod:`archquake.rigid.forces`)."""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main
from archquake.validation import paper


def test_friction_json(capsys):
    assert main(["friction", "--model", "fourlink", "--pulse", "step", "--magnitude", "0.5",
                 "--duration", "0.27", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "fourlink"
    for key in ("max_friction_demand", "joint", "time", "static_friction_demand"):
        assert key in out
    assert out["joint"] == 7 and paper.FRICTION_05G.within(out["max_friction_demand"])  # p. 2131


def test_thrust_json_and_plot(tmp_path, capsys):
    fig = tmp_path / "fig8.png"
    argv = ["thrust", "--model", "fourlink", "--pulse", "step", "--magnitude", "1.0",
            "--duration", "0.20", "--times", "0.2,0.8", "--plot", str(fig), "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert [s["t"] for s in out["states"]] == [0.2, 0.8]
    assert out["states"][0]["exit_joint"] == 2
    assert fig.stat().st_size > 10_000


def _hinges(text: str) -> dict[int, float]:
    """'0i 2e 5i' -> {0: -1.0, 2: +1.0, 5: -1.0}: a hinge at the extrados puts the line of
    thrust on the extrados face (e / (d/2) = +1), at the intrados on the intrados (-1)."""
    return {int(h[:-1]): (1.0 if h[-1] == "e" else -1.0) for h in text.split()}


def test_rigid_thrust_touches_the_faces_where_the_hinges_are_open(capsys):
    """The default model: at 0.2 and 0.5 s of a 0.5 g, t_p = 0.4 s step on Oppenheim's arch,
    every hinge the run's kinematics list as open then (its hinge set, from the contact gaps)
    is a joint where the line of thrust (from the joint forces) reaches a face, on the hinge's
    face: two independent readings of one state (measured: the same joints, 0i 2e 3e 5i 7e;
    in general a closed joint loaded on one corner only, a hinge about to open, is at a face
    too)."""
    pulse = ["--pulse", "step", "--magnitude", "0.5", "--duration", "0.4"]
    assert main(["thrust", *pulse, "--times", "0.2,0.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "rigid" and out["outcome"] is not None
    assert main(["run", *pulse, "--t-end", "0.6", "--json"]) == 0
    sets = json.loads(capsys.readouterr().out)["mechanisms"]
    for state in out["states"]:
        now = [e for e in sets if e["time_s"] <= state["sample_time_s"]][-1]["hinges"]
        expected = _hinges(now)
        assert set(expected) <= set(state["face_joints"])
        for j, face in expected.items():
            assert state["relative_eccentricity"][j] == pytest.approx(face, abs=1e-6)


def test_rigid_friction_json(capsys):
    """The default model: the friction the joints need over the run, while the ground moves, and
    the equivalent static analysis's (the same limit analysis as the four-link command's: 0.495
    at joint 7, README); the largest over the run bounds the one while the ground moves."""
    assert main(["friction", "--pulse", "step", "--magnitude", "0.5", "--duration", "0.27",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "rigid"
    assert out["static_friction_demand"] == pytest.approx(0.495, abs=5e-4)
    assert out["static_joint"] == 7
    assert out["max_friction_demand"] >= out["max_friction_demand_excitation"] > 0
    assert out["joint_forces"]["max_friction_demand"] == out["max_friction_demand"]


@pytest.mark.parametrize("argv, needle", [
    (["thrust", "--pulse", "step", "--magnitude", "1", "--duration", "0.2", "--times", "-1"], "--times"),
    (["thrust", "--pulse", "step", "--magnitude", "1", "--duration", "0.27", "--times", "5"], "collapse"),
    (["thrust", "--model", "fourlink", "--pulse", "step", "--magnitude", "1", "--duration", "0.27",
      "--times", "5"], "collapse"),
    (["thrust", "--pulse", "step", "--magnitude", "1", "--duration", "0.2", "--times", "a,b"], "times"),
    (["friction", "--pulse", "step", "--duration", "0.27"], "--magnitude"),
])
def test_one_line_errors(capsys, argv, needle):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and needle in err


class _Terminal:
    """A stderr that says it is a terminal and keeps what is written to it."""

    def __init__(self):
        self.text = ""

    def isatty(self):
        return True

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_friction_progress_on_a_terminal_only(monkeypatch, capsys):
    """The bar goes to stderr when it is a terminal (the instants examined, up to all of them),
    never to stdout: the JSON stays parseable; with stderr redirected nothing is drawn."""
    argv = ["friction", "--model", "fourlink", "--pulse", "step", "--magnitude", "0.5",
            "--duration", "0.27", "--json"]
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    term = _Terminal()
    monkeypatch.setattr("sys.stderr", term)
    assert main(argv) == 0
    json.loads(capsys.readouterr().out)
    assert "instants" in term.text


def test_friction_demand_reports_its_progress():
    import math

    from archquake import Arch
    from archquake.ground import StepImpulse
    from archquake.thrust.friction import friction_demand

    calls = []
    fd = friction_demand(Arch(10.0, 1.5, math.radians(157.5), 7), StepImpulse.from_g(0.5, 0.27),
                         progress=lambda done, total: calls.append((done, total)))
    total = calls[0][1]
    assert [c[0] for c in calls] == list(range(total)) and {c[1] for c in calls} == {total}
    assert fd.times.size == total
