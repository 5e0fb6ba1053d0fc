"""``archquake check`` through the real entry point: the mechanism's numbers and each limit
state in text and JSON, the hazard route, and every bad input as one line with exit status 2.

Oracles: Oppenheim's collapse acceleration (paper p. 2126: 0.37 g) for alpha0, and the library's
check (tests/codecheck/test_check.py holds it to the rocking block by hand)."""

from __future__ import annotations

import json

import pytest

from archquake.cli import main as cli_main
from archquake.validation import paper

SITE = ["--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3", "--soil", "B"]
HAZARD = ["--code", "ntc2018", "--soil", "B", "--hazard", "50,0.08,2.45,0.27",
          "--hazard", "475,0.25,2.4,0.30", "--hazard", "975,0.32,2.45,0.32"]


def test_check_json(capsys):
    assert cli_main.main(["check", *SITE, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert paper.ONSET_ACCELERATION.within(data["alpha0"])
    for key in ("e_star", "m_star_kg", "a0_star_g", "d0_m"):
        assert data[key] > 0
    assert data["a0_star_g"] == pytest.approx(data["alpha0"] / (data["e_star"] * 1.35))
    states = {(c["limit_state"], c["method"]): c for c in data["limit_states"]}
    assert set(states) == {("SLD", "linear"), ("SLV", "linear"), ("SLV", "nonlinear"),
                           ("SLC", "nonlinear")}
    for c in states.values():
        assert c["ratio"] == pytest.approx(c["capacity_ag_g"] / c["demand_ag_g"])
        assert c["demand_ag_g"] == pytest.approx(0.25)
    assert states[("SLV", "nonlinear")]["capacity_m"] == pytest.approx(0.4 * data["d0_m"])
    assert states[("SLV", "linear")]["capacity_ag_g"] == pytest.approx(
        2 * states[("SLD", "linear")]["capacity_ag_g"])


def test_check_text_and_hazard(capsys):
    assert cli_main.main(["check", *HAZARD, "--knowledge", "lc3"]) == 0
    out = capsys.readouterr().out
    assert "alpha0 = 0.3700" in out and "FC = 1.00" in out
    assert "SLD T_R 50 y" in out and "SLV T_R 475 y" in out and "SLC T_R 975 y" in out
    assert "verdict:" in out


def test_check_at_height(capsys):
    assert cli_main.main(["check", *SITE, "--height", "6", "--building-height", "12",
                          "--building-period", "0.4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    sld = data["limit_states"][0]
    assert sld["demand_m_s2"] == pytest.approx(0.25 * 1.16 * 9.80665 * 1.5)  # a_g S (1 + Z/H)


@pytest.mark.parametrize("argv, words", [
    (["--knowledge", "LC4"], "--knowledge"),
    (["--height", "30", "--building-height", "20", "--building-period", "0.5"],
     "--height must be in [0, 20] m"),
    (["--height", "5"], "--height 5 needs --building-height H and --building-period T1"),
    (["--building-period", "0.5"], "--building-period applies only with --height"),
    (["--procedure", "2011"], "--procedure"),
    (["--procedure", "2009", "--height", "5", "--building-height", "20", "--building-period",
      "0.5"], "--procedure 2009 is implemented at the ground only"),
    (["--nominal-life", "100"], "--nominal-life applies only with --hazard"),
    (["--building-period", "-1"], "--building-period"),
])
def test_bad_input_is_one_line(capsys, argv, words):
    assert cli_main.main(["check", *SITE, *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err


@pytest.mark.parametrize("argv, words", [
    ([], "the site is needed"),
    (["--code", "ntc2018", "--hazard", "475,0.25,2.4,0.3"], "two or more"),
    (["--code", "ntc2018", "--hazard", "475,0.25,2.4"], "--hazard"),
    ([*HAZARD, "--ag", "0.2"], "--ag and --hazard exclude each other"),
    (["--code", "ntc2018", "--hazard", "475,0.25,2.4,0.3", "--hazard", "975,0.3,2.4,0.3"],
     "SLD needs the return period 50 years"),
])
def test_bad_site_is_one_line(capsys, argv, words):
    assert cli_main.main(["check", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err
