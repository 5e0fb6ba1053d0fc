"""``archquake run --model fourlink``: the paper's Figure 4 cases through the command line, JSON
keys, files, and one-line errors with exit status 2 (the default model, the rigid chain, is
tested in test_rigid_default.py)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from archquake.cli.main import main
from archquake.outcome import RESULT_KEYS
from archquake.validation import paper


def _run_json(capsys, *args):
    assert main(["run", "--model", "fourlink", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_keys_and_figure4c(capsys):
    out = _run_json(capsys, "--radius", "10", "--thickness", "1.5", "--embrace", "157.5", "--voussoirs", "7",
                    "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27")
    for key in (*RESULT_KEYS, "restitution_cv"):
        assert key in out
    assert out["outcome"] == "collapse" and out["collapse_half_cycle"] == 2
    msg = paper.FIGURE4C_FIRST_IMPACT.check(out["impact_times_s"][0], "first impact")  # Figure 4(c)
    assert msg is None, msg
    assert len(out["peak_rotation_rad"]) == 2


def test_survival_has_null_collapse_half_cycle(capsys):
    out = _run_json(capsys, "--pulse", "step", "--magnitude", "1.0", "--duration", "0.20")
    assert out["outcome"] == "survives" and out["collapse_half_cycle"] is None


def test_no_hinging_below_the_collapse_acceleration(capsys):
    out = _run_json(capsys, "--pulse", "sine", "--magnitude", "0.35", "--period", "1.0")
    assert out["outcome"] == "no_hinging" and out["impact_times_s"] == []


def test_prescribed_restitution_is_used(capsys):
    out = _run_json(capsys, "--pulse", "step", "--magnitude", "1.0", "--duration", "0.2",
                    "--restitution", "0.5")
    assert out["restitution_cv"] == 0.5 and out["restitution_ct"] == 0.25


def test_files_written(tmp_path, capsys):
    plot, gif, hist = tmp_path / "r.png", tmp_path / "r.gif", tmp_path / "h.csv"
    assert main(["run", "--model", "fourlink", "--pulse", "step", "--magnitude", "1.0",
                 "--duration", "0.44", "--plot", str(plot),
                 "--animate", str(gif), "--history", str(hist)]) == 0
    text = capsys.readouterr().out
    assert "collapse in half cycle 1" in text
    assert plot.stat().st_size > 10_000 and gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    rows = hist.read_text().splitlines()
    assert rows[0].startswith("time_s,crown_dx_m,crown_dy_m,rotation_rad") and len(rows) > 50


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--thickness", "-1", "--pulse", "step", "--magnitude", "1", "--duration", "0.2"], "--thickness"),
        (["--embrace", "300", "--pulse", "step", "--magnitude", "1", "--duration", "0.2"], "--embrace"),
        (["--pulse", "step", "--magnitude", "1"], "--duration"),
        (["--pulse", "step", "--magnitude", "abc", "--duration", "0.2"], "--magnitude"),
        (["--pulse", "step", "--magnitude", "1", "--duration", "0.2", "--restitution", "-0.1"],
         "--restitution"),
        (["--pulse", "step", "--magnitude", "1", "--duration", "0.2", "--t-end", "0"], "--t-end"),
        (["--record", "no/such/file.AT2"], "file.AT2"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, args, needle):
    assert main(["run", "--model", "fourlink", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and "\n" not in err and "Traceback" not in err


def test_installed_command_exits_2_without_traceback():
    proc = subprocess.run([sys.executable, "-m", "archquake.cli.main", "run", "--voussoirs", "2",
                           "--pulse", "step", "--magnitude", "1", "--duration", "0.2"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "--voussoirs" in proc.stderr
