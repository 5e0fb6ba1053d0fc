"""CLI: 'archquake thrust' and 'archquake friction' (JSON keys, figure, one-line errors)."""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main
from archquake.validation import paper


def test_friction_json(capsys):
    assert main(["friction", "--pulse", "step", "--magnitude", "0.5", "--duration", "0.27", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("max_friction_demand", "joint", "time", "static_friction_demand"):
        assert key in out
    assert out["joint"] == 7 and paper.FRICTION_05G.within(out["max_friction_demand"])  # p. 2131


def test_thrust_json_and_plot(tmp_path, capsys):
    fig = tmp_path / "fig8.png"
    argv = ["thrust", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.20",
            "--times", "0.2,0.8", "--plot", str(fig), "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert [s["t"] for s in out["states"]] == [0.2, 0.8]
    assert out["states"][0]["exit_joint"] == 2
    assert fig.stat().st_size > 10_000


@pytest.mark.parametrize("argv, needle", [
    (["thrust", "--pulse", "step", "--magnitude", "1", "--duration", "0.2", "--times", "-1"], "--times"),
    (["thrust", "--pulse", "step", "--magnitude", "1", "--duration", "0.27", "--times", "5"], "collapse"),
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
    argv = ["friction", "--pulse", "step", "--magnitude", "0.5", "--duration", "0.27", "--json"]
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
