"""The assessment's [site] table and its "Code check" section.

Oracles: the library's check (tests/codecheck/test_check.py holds it to the rocking block by hand)
run on the same arch and spectra; every bad key as one line naming it."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from archquake.assess.config import load_config, parse_config
from archquake.assess.site import parse_site, report_code_check, section_code_check
from archquake.codecheck.check import kinematic_check, limit_state_spectra
from archquake.codecheck.kinematic import capacity_curve
from archquake.codes.spectra import NTCHazard
from archquake.errors import StudyFileError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bridge.toml"
HAZARD = [[50, 0.05, 2.50, 0.26], [475, 0.15, 2.45, 0.30], [975, 0.19, 2.50, 0.31]]


def test_example_has_a_site():
    cfg = load_config(EXAMPLE)
    assert cfg.site is not None and cfg.site.knowledge == "LC1" and cfg.site.soil == "B"
    spectra = cfg.site.spectra()
    assert spectra["SLV"].ag / spectra["SLV"].g == pytest.approx(0.15, rel=2e-3)  # T_R 475
    assert cfg.canonical()["site"]["hazard"] == HAZARD


def test_section_is_the_library_check(tmp_path):
    cfg = load_config(EXAMPLE)
    arch = cfg.build_arch()
    ctx = SimpleNamespace(config=cfg, arch=arch, figures=tmp_path)
    res = section_code_check(ctx)
    assert (tmp_path / "codecheck.png").is_file()
    spectra = limit_state_spectra(NTCHazard(HAZARD), soil="B")
    ref = kinematic_check(capacity_curve(arch), spectra, knowledge="LC1")
    got = {(c["limit_state"], c["method"]): c["capacity_ag_g"] for c in res.data["limit_states"]}
    for c in ref.checks:
        assert got[(c.limit_state, c.method)] == pytest.approx(c.capacity_ag_g, rel=1e-12)
    assert len(res.data["verdicts"]) == 3
    el: list = []
    report_code_check(el, SimpleNamespace(sections={"codecheck": res}), res.data)
    assert el[0][0] == "h2" and "Code check" in el[0][2]
    assert sum(1 for e in el if e[0] == "table") == 2


@pytest.mark.parametrize("table, words", [
    ({"hazard": HAZARD, "colour": 1}, "[site] colour is not a known key"),
    ({"hazard": HAZARD, "ag_g": 0.2}, "[site] hazard and ag_g exclude each other"),
    ({"ag_g": 0.2}, "[site] f0 is missing"),
    ({}, "[site] ag_g is missing"),
    ({"hazard": HAZARD, "knowledge": "LC4"}, "[site] knowledge must be one of"),
    ({"hazard": HAZARD, "height_m": 30, "building_height_m": 20, "building_period_s": 0.5},
     "[site] height_m must be in [0, 20] m"),
    ({"hazard": HAZARD, "height_m": 5}, "[site] height_m > 0 needs building_height_m"),
    ({"hazard": HAZARD, "building_period_s": 0.5}, "[site] building_period_s applies only"),
    ({"hazard": [[475, 0.15, 2.45, 0.30], [975, 0.19, 2.5, 0.31]]},
     "SLD needs the return period 50 years"),
    ({"code": "ec8", "ag_g": 0.2, "soil": "B"}, "[site] soil does not apply"),
    ({"hazard": HAZARD, "procedure": "2009", "height_m": 5, "building_height_m": 20,
      "building_period_s": 0.5}, "[site] procedure '2009' is implemented at the ground only"),
])
def test_bad_site_is_one_line(table, words):
    with pytest.raises(StudyFileError) as exc:
        parse_site(table, source="x.toml")
    text = str(exc.value)
    assert words in text and "\n" not in text


def test_site_alone_is_a_valid_seismic_input():
    cfg = parse_config({"arch": {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180,
                                 "voussoirs": 15, "friction": 0.6},
                        "site": {"code": "ec8", "ag_g": 0.2, "ground": "B"}})
    assert cfg.site is not None and cfg.site.code == "ec8"


def test_a_file_without_site_keeps_its_digest():
    base = {"arch": {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180,
                     "voussoirs": 15, "friction": 0.6}, "seismic": {"site_pga_g": 0.15}}
    plain = parse_config(base)
    assert "site" not in plain.canonical()
    with_site = parse_config({**base, "site": {"hazard": HAZARD, "soil": "B"}})
    assert with_site.digest != plain.digest
