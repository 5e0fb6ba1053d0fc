"""``archquake record FILE`` through the real entry point."""

from __future__ import annotations

import importlib.resources
import importlib.util
import json
from pathlib import Path

import pytest

from archquake.cli import main as cli_main


@pytest.fixture(autouse=True)
def _registered_commands(monkeypatch):
    """The real COMMANDS, less any sibling command whose module is not written yet (several
    commands are developed in parallel); 'record' itself must be registered."""
    assert "record" in cli_main.COMMANDS
    present = tuple(name for name in cli_main.COMMANDS
                    if importlib.util.find_spec(f"archquake.cli.cmd_{name}") is not None)
    monkeypatch.setattr(cli_main, "COMMANDS", present)


@pytest.fixture(scope="module")
def northridge_csv():
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource / "Northridge_1994_PAC-175.csv") as path:
        yield Path(path)


def test_text_summary(northridge_csv, capsys):
    assert cli_main.main(["record", str(northridge_csv), "--units", "g"]) == 0
    out = capsys.readouterr().out
    assert "Northridge_1994_PAC-175" in out
    assert "points     1000" in out
    assert "dt         0.02 s" in out
    assert "duration   19.98 s" in out
    assert "0.4153 g = 4.073 m/s^2" in out  # PGA 0.415325 g (pyslammer's file)
    assert "units      g\n" in out


def test_json_summary_with_scale(northridge_csv, capsys):
    assert cli_main.main(["record", str(northridge_csv), "--units", "g", "--scale", "2",
                          "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["points"] == 1000 and data["dt_s"] == 0.02
    assert data["pga_g"] == pytest.approx(2 * 0.415325, rel=1e-12)
    assert data["pga_m_s2"] == pytest.approx(2 * 0.415325 * 9.80665, rel=1e-12)
    assert data["scale"] == 2.0 and data["units_in_file"] == "g"


def test_units_m_s2(tmp_path, capsys):
    path = tmp_path / "si.txt"
    path.write_text("0 0.5\n0.01 -9.80665\n0.02 1.0\n")
    assert cli_main.main(["record", str(path), "--units", "m/s2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["pga_g"] == pytest.approx(1.0, rel=1e-15)
    assert data["time_of_pga_s"] == pytest.approx(0.01)


@pytest.mark.parametrize(
    ("name", "content", "fragment"),
    [
        ("uneven.csv", "0,1\n0.01,2\n0.03,3\n", "uneven.csv: line 3: time 0.03 s"),
        ("short.AT2", "PEER\nEVENT\nACCELERATION IN UNITS OF G\nNPTS=  3, DT= .01 SEC\n1 2\n",
         "short.AT2: line 4: the header says NPTS = 3 but the file holds 2"),
        ("missing.csv", None, "missing.csv: no such file"),
    ],
)
def test_malformed_file_exits_2_with_one_line(tmp_path, capsys, name, content, fragment):
    path = tmp_path / name
    if content is not None:
        path.write_text(content)
    assert cli_main.main(["record", str(path), "--units", "g"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    err = captured.err.strip()
    assert err.startswith("archquake: error: ")
    assert "\n" not in err
    assert fragment in err


def test_bad_scale_exits_2(northridge_csv, capsys):
    assert cli_main.main(["record", str(northridge_csv), "--scale", "-1"]) == 2
    assert "--scale must be in (0, 1000]" in capsys.readouterr().err


def test_record_vertical_measures(tmp_path, capsys):
    """The vertical's intensity measures are those of the file read alone (`intensity_measures`
    of `read_record`), and V/H their ratio to the horizontal's."""
    import numpy as np

    from archquake.ground import read_record
    from archquake.ground.measures import intensity_measures

    t = np.arange(0.0, 4.0 + 1e-9, 0.01)
    h = 0.3 * np.sin(2 * np.pi * 2 * t) * np.exp(-((t - 1.5) / 0.6) ** 2)
    v = 0.2 * np.sin(2 * np.pi * 7 * t) * np.exp(-((t - 1.2) / 0.4) ** 2)
    np.savetxt(tmp_path / "h.csv", np.column_stack([t, h]), delimiter=",")
    np.savetxt(tmp_path / "v.csv", np.column_stack([t, v]), delimiter=",")
    args = ["record", str(tmp_path / "h.csv"), "--units", "g", "--record-vertical",
            str(tmp_path / "v.csv"), "--periods", "0.2"]
    assert cli_main.main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    alone = intensity_measures(read_record(tmp_path / "v.csv", units="g"), periods=[0.2])
    assert out["vertical"]["intensity_measures"]["pga_g"] == alone.pga_g
    assert out["vertical"]["intensity_measures"]["arias_m_s"] == alone.arias_m_s
    assert out["vertical"]["v_over_h"]["pga"] == alone.pga_g / out["intensity_measures"]["pga_g"]
    assert cli_main.main(args) == 0
    assert "V/H" in capsys.readouterr().out
    assert cli_main.main([*args, "--spectrum"]) == 2
    assert "--record-vertical applies only without --spectrum" in capsys.readouterr().err
