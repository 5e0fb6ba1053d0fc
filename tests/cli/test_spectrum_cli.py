"""``archquake spectrum``, ``record --spectrum`` and ``records SUITE --spectrum/--select`` through
the real entry point.

Oracles: the library's spectra (themselves held to the code equations and to eqsig in
tests/codes and tests/ground); for a selection, the band checked here from the records read
independently, the printed scale factors and the code spectrum. Bad input: exit status 2 and
one line naming the option.
"""

from __future__ import annotations

import importlib.resources
import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

from archquake.cli import main as cli_main
from archquake.codes import ec8_spectrum, ntc2018_spectrum
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import read_record
from archquake.ground.measures import response_spectrum


@pytest.fixture(autouse=True)
def _registered_commands(monkeypatch):
    """The real COMMANDS, less any sibling command whose module is not written yet."""
    present = tuple(name for name in cli_main.COMMANDS
                    if importlib.util.find_spec(f"archquake.cli.cmd_{name}") is not None)
    monkeypatch.setattr(cli_main, "COMMANDS", present)


@pytest.fixture(scope="module")
def samples():
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource) as path:
        yield Path(path)


NTC_SITE = ["--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.30",
            "--soil", "B"]


def test_spectrum_json_is_the_library_spectrum(capsys):
    assert cli_main.main(["spectrum", *NTC_SITE, "--damping", "8", "--periods", "0:3:0.5",
                          "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
    periods = np.arange(7) * 0.5
    assert data["periods_s"] == pytest.approx(periods)
    assert data["sa_g"] == pytest.approx(spec.sa(periods, 0.08) / G, rel=1e-12)
    assert data["sd_m"] == pytest.approx(spec.sd(periods, 0.08), rel=1e-12)
    assert data["S"] == pytest.approx(1.16) and data["TC_s"] == pytest.approx(spec.TC)
    assert data["damping_ratio"] == 0.08


def test_spectrum_text_and_plot(tmp_path, capsys):
    out = tmp_path / "ec8.png"
    assert cli_main.main(["spectrum", "--code", "ec8", "--ag", "0.2", "--type", "2",
                          "--ground", "c", "--importance", "1.2", "--plot", str(out)]) == 0
    text = capsys.readouterr().out
    spec = ec8_spectrum(ag_g=0.2, spectrum_type=2, ground="C", importance=1.2)
    assert "EN 1998-1 Type 2 horizontal" in text and "TC 0.250 s" in text
    assert f"{spec.pga / G:.4f}" in text
    assert out.stat().st_size > 0


@pytest.mark.parametrize(("argv", "fragment"), [
    (["--code", "ntc2018", "--ag", "0.25"], "--code ntc2018 needs --f0 and --tc-star"),
    ([*NTC_SITE, "--ground", "B"], "--ground applies only with --code ec8"),
    (["--code", "ec8", "--ag", "0.25", "--soil", "B"], "--soil applies only with --code ntc2018"),
    (["--code", "ec8", "--ag", "-0.1"], "argument --ag: must be in (0, 3] g"),
    (["--code", "ntc2018", "--ag", "0.2", "--f0", "1.5", "--tc-star", "0.3"],
     "argument --f0: must be in [2.2, 4]"),
    ([*NTC_SITE[:-1], "F"], "argument --soil: invalid choice: 'F'"),
    (["--code", "ec8", "--ag", "0.2", "--type", "3"], "argument --type: invalid choice"),
    (["--code", "ec8", "--ag", "0.2", "--damping", "100"], "argument --damping: must be in [0, 100)"),
    (["--code", "ec8", "--ag", "0.2", "--periods", "2:1"], "argument --periods"),
    (["--ag", "0.2"], "the following arguments are required: --code"),
])
def test_spectrum_bad_input_exit_2_one_line(argv, fragment, capsys):
    assert cli_main.main(["spectrum", *argv]) == 2
    err = capsys.readouterr().err
    assert fragment in err and err.count("\n") == 1


def test_record_spectrum_json(samples, capsys):
    path = samples / "Northridge_1994_PAC-175.csv"
    assert cli_main.main(["record", str(path), "--units", "g", "--spectrum", "--periods",
                          "0:1:0.25",
                          "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    expected = response_spectrum(read_record(path, units="g"), np.arange(5) * 0.25) / G
    assert data["sa_g"] == pytest.approx(expected, rel=1e-12)


def test_suite_spectrum_mean(samples, capsys):
    assert cli_main.main(["records", str(samples), "--units", "g", "--spectrum", "--periods",
                          "0.5,1",
                          "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    rows = np.array([r["sa_g"] for r in data["records"]])
    assert len(rows) == 18
    assert data["mean_sa_g"] == pytest.approx(rows.mean(axis=0), rel=1e-12)


@pytest.mark.parametrize("site", [
    NTC_SITE,
    ["--code", "ec8", "--ag", "0.3", "--type", "1", "--ground", "C"],
])
def test_select_from_a_folder_meets_the_band(samples, site, tmp_path, capsys):
    """7 of the 18 sample records (each its own event as far as the folder says) chosen and
    scaled; their mean, recomputed here from the files, lies in the code's band at every
    period (EN 1998-1: and the mean PGA >= a_g S at T = 0)."""
    out = tmp_path / "sel.png"
    argv = ["records", str(samples), "--units", "g", "--select", *site, "--periods", "0.2:1.0:0.1",
            "--count", "7", "--scale-range", "0.25,4", "--json", "--plot", str(out)]
    assert cli_main.main(argv) == 0
    data = json.loads(capsys.readouterr().out)["selection"]
    assert data["compatible"] is True and out.stat().st_size > 0
    periods = np.array(data["periods_s"])
    mean = np.zeros_like(periods)
    for rec in data["records"]:
        path = next(samples.glob(f"{rec['name']}.*"))
        mean += rec["scale_factor"] * response_spectrum(read_record(path, units="g"), periods)
    mean /= len(data["records"])
    if site[1] == "ec8":
        target = ec8_spectrum(ag_g=0.3, ground="C")
        assert periods[0] == 0.0 and mean[0] >= target.pga * (1 - 1e-9)
        lower, upper = 0.9, np.inf
    else:
        target = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
        lower, upper = 0.9, 1.3
    ratio = mean / target.sa(periods)
    assert np.all(ratio[periods > 0] >= lower - 1e-9) and np.all(ratio <= upper + 1e-9)
    assert all(0.25 <= r["scale_factor"] <= 4.0 for r in data["records"])


def test_select_deterministic_and_says_when_it_cannot(samples, capsys):
    argv = ["records", str(samples), "--units", "g", "--select", *NTC_SITE, "--periods",
            "0.2:1.0:0.2",
            "--json", "--seed", "4"]
    assert cli_main.main(argv) == 0
    first = json.loads(capsys.readouterr().out)["selection"]["records"]
    assert cli_main.main(argv) == 0
    again = json.loads(capsys.readouterr().out)["selection"]["records"]
    assert [(r["name"], r["scale_factor"]) for r in first] == [
        (r["name"], r["scale_factor"]) for r in again]
    # a site ten times stronger with the records unscaled: no set can match
    strong = ["--code", "ntc2018", "--ag", "2.5", "--f0", "2.4", "--tc-star", "0.3"]
    assert cli_main.main(["records", str(samples), "--units", "g", "--select", *strong, "--periods",
                          "0.2:1.0:0.2", "--scale-range", "1,1"]) == 2
    err = capsys.readouterr().err
    assert "no set of 7 records meets the band: the best mean is below the band" in err
    assert err.count("\n") == 1


@pytest.mark.parametrize(("argv", "fragment"), [
    (["--select", *NTC_SITE], "--select needs --periods"),
    (["--select", "--periods", "0.1:1"], "--select needs the site spectrum"),
    ([*NTC_SITE], "--code, --ag, --f0, --tc-star, --soil apply only with --select"),
    (["--plot", "x.png"], "--plot applies only with --spectrum or --select"),
    (["--select", *NTC_SITE, "--periods", "0.1:1", "--scale-range", "2,3"],
     "argument --scale-range: must satisfy"),
    (["--select", *NTC_SITE, "--periods", "0.1:1", "--count", "0"], "argument --count"),
    (["--select", *NTC_SITE, "--periods", "0.1:1", "--count", "30"],
     "fewer than count = 30"),
])
def test_records_select_bad_input_exit_2(samples, argv, fragment, capsys):
    assert cli_main.main(["records", str(samples), "--units", "g", *argv]) == 2
    err = capsys.readouterr().err
    assert fragment in err and err.count("\n") == 1
