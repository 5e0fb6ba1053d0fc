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
