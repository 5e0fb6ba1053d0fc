"""--restitution and --impact on every command that runs a history, and the honest verdict.

Oracles: the library call with the same law and c_v (the CLI must print what the API returns);
the one-line-error convention (exit 2, the option named with its range).
"""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main

BRIDGE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15"]
STEP = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.27"]
#: each command that runs a time history, with the smallest arguments that make it quick
COMMANDS = {
    "run": ["run", "--model", "fourlink", *STEP],
    "domain": ["domain", "--model", "fourlink", "--durations", "0.27", "--scan", "4",
               "--precision", "0.05"],
    "thrust": ["thrust", "--model", "fourlink", *STEP, "--times", "0.5"],
    "friction": ["friction", "--model", "fourlink", "--pulse", "step", "--magnitude", "0.5",
                 "--duration", "0.27"],
}


@pytest.mark.parametrize("name", [*COMMANDS, "ida"])
@pytest.mark.parametrize("bad", ["-0.1", "1.01"])
def test_restitution_outside_0_1_is_one_line(capsys, name, bad):
    args = COMMANDS.get(name, ["ida", "--model", "fourlink", "--records", "nowhere.AT2"])
    assert main([*args, "--restitution", bad]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "--restitution must be in [0, 1]" in err and bad in err


@pytest.mark.parametrize("name", list(COMMANDS))
def test_every_history_command_takes_both_options(capsys, name):
    assert main([*COMMANDS[name], "--impact", "chain", "--restitution", "0.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    if name == "run":
        assert out["impact_law"] == "chain" and out["restitution_cv"] == 0.5
        assert out["restitution_prescribed"] is True
    elif name == "domain":
        assert out["model"] == "fourlink" and out["rows"][0]["impact_law"] == "chain"
    elif name == "friction":
        assert out["impact_law"] == "chain" and out["restitution_cv"] == 0.5


def test_run_perfectly_plastic(capsys):
    assert main(["run", "--model", "fourlink", *STEP, "--restitution", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["restitution_cv"] == 0.0 and len(out["impact_times_s"]) == 1
    assert out["outcome"] == "survives"


def test_bridge_arch_under_eq4_prints_indeterminate_not_a_verdict(capsys):
    """Issue 10's semicircle under the paper's law (c_v = 49.9): collapse after the impact is
    computed but not claimed."""
    args = ["run", "--model", "fourlink", *BRIDGE, "--pulse", "step", "--magnitude", "0.15",
            "--duration", "0.1"]
    assert main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcome"] == "indeterminate" and out["computed_outcome"] == "collapse"
    assert out["impact_validity"] == "outside" and out["impact_described"] is False
    assert main(args) == 0
    text = capsys.readouterr().out
    verdict = next(line for line in text.splitlines() if line.startswith("outcome"))
    assert verdict.split()[1] == "indeterminate:"
    assert "validity outside" in text and "indeterminate" in text
    # no line states collapse or survival as the verdict
    assert not any(line.split()[:2] in (["outcome", "collapse"], ["outcome", "survives"])
                   for line in text.splitlines())


@pytest.mark.parametrize("model", [[], ["--model", "rigid"], ["--model", "dem"]])
def test_block_models_refuse_the_four_link_impact_options(capsys, model):
    """The rigid chain (the default) and the DEM take their impacts from their contacts."""
    assert main(["run", *model, *STEP, "--impact", "chain"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--impact applies only to --model fourlink" in err and len(err.splitlines()) == 1


def test_unknown_law_is_refused(capsys):
    assert main(["run", "--model", "fourlink", *STEP, "--impact", "elastic"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--impact" in err and len(err.splitlines()) == 1
