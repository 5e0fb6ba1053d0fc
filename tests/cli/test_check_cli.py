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
    # one spectrum is the SLV's: the SLD and the SLC have no hazard of their own, and are not
    # checked against the SLV's a_g
    assert set(states) == {("SLV", "linear"), ("SLV", "nonlinear")}
    assert sorted(data["not_checked"]) == ["SLC", "SLD"]
    for c in states.values():
        assert c["ratio"] == pytest.approx(c["capacity_ag_g"] / c["demand_ag_g"])
        assert c["demand_ag_g"] == pytest.approx(0.25)
    assert states[("SLV", "nonlinear")]["capacity_m"] == pytest.approx(0.4 * data["d0_m"])
    # the linear SLV is q = 2 times the activation a_g on the same spectrum
    assert states[("SLV", "linear")]["capacity_m_s2"] == pytest.approx(
        data["a0_star_m_s2"])


def test_one_spectrum_at_its_own_limit_state(capsys):
    assert cli_main.main(["check", *SITE, "--limit-state", "SLD", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [c["limit_state"] for c in data["limit_states"]] == ["SLD"]
    assert cli_main.main(["check", *SITE]) == 0
    out = capsys.readouterr().out
    assert "SLD: not checked" in out and "SLC: not checked" in out
    assert "checked: SLV" in out


def test_hazard_points_at_50_and_475_years_check_sld_and_slv(capsys):
    """The points the grid gives at 50 and 475 years span the SLD (50.3 y) and the SLV
    (474.6 y): both are checked, the SLC (974.8 y) is not, and it is said."""
    argv = ["check", "--code", "ntc2018", "--soil", "B", "--hazard", "50,0.08,2.45,0.27",
            "--hazard", "475,0.25,2.4,0.30"]
    assert cli_main.main(argv) == 0
    out = capsys.readouterr().out
    assert "SLD (linear)" in out and "SLV (nonlinear)" in out
    assert "SLC: not checked: it needs the return period 975 years" in out


def test_implausible_ag_is_warned(capsys):
    argv = ["check", "--code", "ntc2018", "--ag", "2.55", "--f0", "2.4", "--tc-star", "0.3",
            "--soil", "B", "--json"]
    assert cli_main.main(argv) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--ag 2.55 g is above 1.5 g" in err[0]


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
    (["--code", "ntc2018", "--soil", "B", "--hazard", "475,0.25,2.4,0.3"], "two or more"),
    (["--code", "ntc2018", "--hazard", "475,0.25,2.4"], "--hazard"),
    ([*HAZARD, "--ag", "0.2"], "--ag and --hazard exclude each other"),
    (["--code", "ntc2018", "--soil", "B", "--hazard", "1000,0.25,2.4,0.3", "--hazard",
      "2475,0.3,2.4,0.3"], "span no limit state's return period"),
    (["--code", "ntc2018", "--ag", "0.2", "--f0", "2.4", "--tc-star", "0.3"],
     "--code ntc2018 needs --soil"),
    (["--code", "ec8", "--ag", "0.2"], "--code ec8 needs --ground"),
])
def test_bad_site_is_one_line(capsys, argv, words):
    assert cli_main.main(["check", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err


def test_time_history_route_beside_the_static_one(capsys, monkeypatch):
    """The route's plumbing through the real entry point, with the rigid chain replaced by a
    stand-in that collapses the arch once a record's PGA passes 0.08 g and leaves it at rest
    below (the chain itself is held to the capacity curve in tests/codecheck/test_timehistory.py).
    Oracle: then the capacity a_g is the a_g at which the strongest scaled record reaches
    0.08 g, bracketed: it must lie in the reported bracket, the records must be 7 distinct ones
    of the far-field set, scaled to the SLV spectrum within the code's band."""
    from types import SimpleNamespace

    import numpy as np

    import archquake.codecheck.timehistory as th
    from archquake.ground.suites import fema_available

    if not fema_available():
        pytest.skip("needs the FEMA P695 records")
    peaks: list[float] = []

    def stand_in(arch, motion):
        pga = float(np.max(np.abs(motion.accelerations))) / 9.80665
        peaks.append(pga)
        if pga > 0.08:
            return SimpleNamespace(outcome="collapse")
        cen = arch.voussoir_centroids
        pos = np.zeros((3, 2 + len(cen), 3))
        pos[:, 2:, :2] = cen[None, :, :]
        return SimpleNamespace(outcome="no_hinging", positions=pos,
                               base_displacement=np.zeros(3))

    monkeypatch.setattr(th, "_default_run", stand_in)
    argv = ["check", *SITE, "--time-history", "far-field", "--bisections", "1", "--json",
            "--no-progress"]
    assert cli_main.main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    (route,) = data["time_history"]  # one spectrum: the SLV's
    assert route["limit_state"] == "SLV" and len(set(route["records"])) == 7
    assert route["compatible"] and route["site_ag_g"] == pytest.approx(0.25)
    lo, hi = route["capacity"]["bracket_g"]
    levels = route["capacity"]["levels"]
    assert [lv["passes"] for lv in levels if lv["ag_g"] <= lo] == \
        [True] * sum(lv["ag_g"] <= lo for lv in levels)
    assert all(not lv["passes"] for lv in levels if lv["ag_g"] >= hi)
    assert lo < route["capacity_ag_g"] < hi
    assert route["static_capacity_ag_g"] == pytest.approx(next(
        c["capacity_ag_g"] for c in data["limit_states"]
        if c["limit_state"] == "SLV" and c["method"] == "nonlinear"))
    assert cli_main.main(["check", *SITE, "--time-history", "far-field", "--bisections", "0",
                          "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "time-history route (C8.7.1.2.1.9)" in out and "(static route" in out


@pytest.mark.parametrize("argv, words", [
    (["--time-history", "no-such-set"], "--time-history no-such-set"),
    (["--time-history", "far-field", "--bisections", "9"], "--bisections must be in [0, 8]"),
    (["--time-history", "far-field", "--limit-state", "SLD"], "--time-history checks the SLV"),
])
def test_time_history_bad_input_is_one_line(capsys, argv, words):
    assert cli_main.main(["check", *SITE, *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err
