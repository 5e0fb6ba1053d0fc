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
    """Oracle: archquake check's library call on the bridge carrying its fill and backing
    (every carried mass in alpha0, M* and e*, C8.7.1), to 1e-12."""
    from archquake.codecheck.kinematic import LoadedFourHingeMechanism

    cfg = load_config(EXAMPLE)
    arch = cfg.build_arch()
    ctx = SimpleNamespace(config=cfg, arch=arch, figures=tmp_path)
    res = section_code_check(ctx)
    assert (tmp_path / "codecheck.png").is_file()
    spectra = limit_state_spectra(NTCHazard(HAZARD), soil="B")
    ref = kinematic_check(capacity_curve(LoadedFourHingeMechanism.of(arch, cfg.dead_loads)),
                          spectra, knowledge="LC1")
    bare = kinematic_check(capacity_curve(arch), spectra, knowledge="LC1")
    assert res.data["carried_mass_kg"] > 0
    assert res.data["alpha0"] == pytest.approx(ref.curve.alpha0, rel=1e-12)
    assert abs(res.data["alpha0"] / bare.curve.alpha0 - 1.0) > 0.1  # the loads change it
    # the block table: each moving voussoir, then what it carries, numbered as the arch's blocks
    blocks = res.data["blocks"]
    voussoirs = [b for b in blocks if b["part"] == "voussoir"]
    carried = [b for b in blocks if b["part"] == "carried"]
    assert [b["block"] for b in voussoirs] == [b["block"] for b in carried]
    assert sum(b["mass_kg"] for b in carried) == pytest.approx(
        res.data["mass_kg"] - sum(float(arch.voussoir_masses[b["block"] - 1]) for b in voussoirs),
        rel=1e-9)
    sx = sum(b["m_dx_kg_m"] for b in blocks)
    assert sum(b["m_dy_kg_m"] for b in blocks) / sx == pytest.approx(res.data["alpha0"], rel=1e-9)
    got = {(c["limit_state"], c["method"]): c["capacity_ag_g"] for c in res.data["limit_states"]}
    for c in ref.checks:
        assert got[(c.limit_state, c.method)] == pytest.approx(c.capacity_ag_g, rel=1e-12)
    assert len(res.data["verdicts"]) == 3
    el: list = []
    report_code_check(el, SimpleNamespace(sections={"codecheck": res}), res.data)
    assert el[0][0] == "h2" and "Code check" in el[0][2]
    assert sum(1 for e in el if e[0] == "table") == 3  # numbers, blocks, limit states
    # NTC 2018 §7.2.2 asks for the vertical component for an arch: the report says it is taken
    assert res.data["vertical"]["taken"]
    assert any(e[0] == "p" and e[1].startswith("Vertical component: taken: NTC 2018 §7.2.2")
               for e in el)


def test_block_table_reconciles_alpha0_e_star_and_the_masses(tmp_path):
    """Oracle: the static analysis (the limit-analysis LP, an independent computation) for
    alpha0 = sum m delta_y / sum m delta_x; the curve's own e* and M for the block sums; and
    the masses of section 1: M is the moving blocks' part of the arch's total (the bare ring)."""
    from archquake.limit import limit_analysis

    from .conftest import bare_bridge

    cfg = bare_bridge()
    arch = cfg.build_arch()
    res = section_code_check(SimpleNamespace(config=cfg, arch=arch, figures=tmp_path))
    blocks = res.data["blocks"]
    sx = sum(b["m_dx_kg_m"] for b in blocks)
    sy = sum(b["m_dy_kg_m"] for b in blocks)
    sxx = sum(b["m_dx2_kg_m2"] for b in blocks)
    mass = sum(b["mass_kg"] for b in blocks)
    assert sy / sx == pytest.approx(limit_analysis(arch).collapse_acceleration_g, rel=1e-6)
    assert sx * sx / (mass * sxx) == pytest.approx(res.data["e_star"], rel=1e-12)
    assert mass == pytest.approx(res.data["mass_kg"], rel=1e-12)
    assert res.data["m_star_kg"] < mass < res.data["arch_mass_kg"]
    assert res.data["arch_mass_kg"] == pytest.approx(float(sum(arch.voussoir_masses)))
    masses = list(arch.voussoir_masses)
    for b in blocks:  # numbered as section 1 numbers them
        assert b["mass_kg"] == pytest.approx(masses[b["block"] - 1], rel=1e-12)
    el: list = []
    report_code_check(el, SimpleNamespace(sections={"codecheck": res}), res.data)
    text = " ".join(e[1] for e in el if e[0] == "p")
    assert f"{res.data['arch_mass_kg']:.0f} kg, section 1" in " ".join(
        str(c) for e in el if e[0] == "table" for row in e[2] for c in row)
    assert f"= {sy / sx:.4f};" in text


@pytest.mark.parametrize("table, words", [
    ({"hazard": HAZARD, "colour": 1}, "[site] colour is not a known key"),
    ({"hazard": HAZARD, "ag_g": 0.2}, "[site] hazard and ag_g exclude each other"),
    ({"ag_g": 0.2}, "[site] f0 is missing"),
    ({}, "[site] ag_g is missing"),
    ({"hazard": HAZARD, "soil": "B", "knowledge": "LC4"}, "[site] knowledge must be one of"),
    ({"hazard": HAZARD, "soil": "B", "height_m": 30, "building_height_m": 20, "building_period_s": 0.5},
     "[site] height_m must be in [0, 20] m"),
    ({"hazard": HAZARD, "soil": "B", "height_m": 5}, "[site] height_m > 0 needs building_height_m"),
    ({"hazard": HAZARD, "soil": "B", "building_period_s": 0.5}, "[site] building_period_s applies only"),
    ({"hazard": [[975, 0.19, 2.5, 0.31], [2475, 0.25, 2.5, 0.33]], "soil": "B"},
     "[site] hazard must span the SLV's return period, which sets the site's demand on the "
     "dynamic sections: the SLV needs the return period 475 years"),
    ({"hazard": HAZARD}, "[site] soil is missing"),
    ({"code": "ec8", "ag_g": 0.2}, "[site] ground is missing"),
    ({"hazard": HAZARD, "soil": "B", "limit_state": "SLC"}, "[site] limit_state applies to one "
                                                            "spectrum"),
    ({"ag_g": 0.2, "f0": 2.4, "tc_star_s": 0.3, "soil": "B", "limit_state": "SLO"},
     "[site] limit_state must be one of"),
    ({"code": "ec8", "ag_g": 0.2, "soil": "B"}, "[site] soil does not apply"),
    ({"hazard": HAZARD, "soil": "B", "procedure": "2009", "height_m": 5, "building_height_m": 20,
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
    with_site = parse_config({**base, "site": {"hazard": HAZARD, "soil": "B"}, "seismic":
                              {"site_pga_g": 0.18}})
    assert with_site.digest != plain.digest


# ----------------------------------------------------------------- one site, one demand
ARCH = {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180, "voussoirs": 15,
        "friction": 0.6}


def test_site_table_sets_the_dynamic_demand_on_soil():
    """Oracle: NTC 2018 eq. 3.2.2 at T = 0 and Tab. 3.2.IV by hand. At the SLV (T_R 474.6 y,
    V_N 50, class II) the hazard gives a_g = 0.1499 g (log-log between 50 and 475 years), F0
    2.4499; soil B: S_S = 1.40 - 0.40 F0 a_g = 1.253, clipped to 1.20; T1: S_T = 1. The
    dynamic sections run at a_g S_S S_T = 0.1799 g, not the rock 0.15 g."""
    cfg = parse_config({"arch": ARCH, "site": {"hazard": HAZARD, "soil": "B"}})
    spec = cfg.site.spectra()["SLV"]
    ag = spec.ag / spec.g
    assert ag == pytest.approx(0.15, rel=2e-3)
    assert cfg.site_pga_g == pytest.approx(ag * 1.2 * 1.0, rel=1e-12)
    assert "a_g S_S S_T" in cfg.site_pga_source and "x 1.2 x 1 =" in cfg.site_pga_source
    # on a ridge (T3: S_T = 1.2) the topography enters too
    top = parse_config({"arch": ARCH, "site": {"hazard": HAZARD, "soil": "B",
                                               "topography": "T3"}})
    assert top.site_pga_g == pytest.approx(ag * 1.2 * 1.2, rel=1e-12)


def test_example_bridge_runs_at_the_soil_pga():
    cfg = load_config(EXAMPLE)
    assert cfg.site_pga_g == pytest.approx(0.1799, abs=1e-4)


@pytest.mark.parametrize("given, ok", [(0.1799, True), (0.18, True), (0.15, False)])
def test_site_pga_beside_the_site_table_must_agree(given, ok):
    data = {"arch": ARCH, "seismic": {"site_pga_g": given},
            "site": {"hazard": HAZARD, "soil": "B"}}
    if ok:
        assert parse_config(data).site_pga_g == given
        return
    with pytest.raises(StudyFileError) as exc:
        parse_config(data, source="x.toml")
    text = str(exc.value)
    assert text.startswith("x.toml: [seismic] site_pga_g = 0.15 g differs from the [site] "
                           "table's a_g S_S S_T")
    assert "site_pga_override" in text and "\n" not in text


def test_stated_override_is_used_and_printed():
    cfg = parse_config({"arch": ARCH, "seismic": {"site_pga_g": 0.15, "site_pga_override": True},
                        "site": {"hazard": HAZARD, "soil": "B"}})
    assert cfg.site_pga_g == 0.15
    assert any("overrides the [site] table's 0.1799 g" in n for n in cfg.notes)
    with pytest.raises(StudyFileError, match=r"site_pga_override applies only with a \[site\]"):
        parse_config({"arch": ARCH, "seismic": {"site_pga_g": 0.15, "site_pga_override": True}})


def test_each_limit_state_only_at_its_own_hazard():
    """Points at 50 and 475 years span the SLD (50.3 y) and the SLV (474.6 y), not the SLC
    (974.8 y): the SLC is not checked, and never against the SLV's a_g."""
    site = parse_site({"hazard": HAZARD[:2], "soil": "B"})
    assert sorted(site.spectra()) == ["SLD", "SLV"]
    assert "975 years" in site.not_checked()["SLC"]
    one = parse_site({"ag_g": 0.15, "f0": 2.45, "tc_star_s": 0.3, "soil": "B"})
    assert list(one.spectra()) == ["SLV"] and sorted(one.not_checked()) == ["SLC", "SLD"]
    sld = parse_site({"ag_g": 0.05, "f0": 2.5, "tc_star_s": 0.26, "soil": "B",
                      "limit_state": "SLD"})
    assert list(sld.spectra()) == ["SLD"] and sld.dynamic_limit_state == "SLD"


def test_section_reports_the_limit_states_not_checked(tmp_path):
    cfg = parse_config({"arch": ARCH, "site": {"hazard": HAZARD[:2], "soil": "B"}})
    ctx = SimpleNamespace(config=cfg, arch=cfg.build_arch(), figures=tmp_path)
    res = section_code_check(ctx)
    assert {c["limit_state"] for c in res.data["limit_states"]} == {"SLD", "SLV"}
    el: list = []
    report_code_check(el, SimpleNamespace(sections={"codecheck": res}), res.data)
    items = next(e[1] for e in el if e[0] == "ul")
    assert any(i.startswith("SLC: not checked") for i in items)


def test_time_history_route_in_the_code_check_section(tmp_path, monkeypatch):
    """[site] time_history runs the route beside the static one in the section and the report
    (the rigid chain replaced by a stand-in that collapses the arch once a record's PGA passes
    0.06 g: the plumbing, not the physics, which tests/codecheck/test_timehistory.py holds)."""
    import numpy as np

    import archquake.codecheck.timehistory as th
    from archquake.assess.sections import Mode
    from archquake.ground.suites import fema_available

    if not fema_available():
        pytest.skip("needs the FEMA P695 records")

    def stand_in(arch, motion):
        if float(np.max(np.abs(motion.accelerations))) / 9.80665 > 0.06:
            return SimpleNamespace(outcome="collapse")
        pos = np.zeros((2, 2 + len(arch.voussoir_centroids), 3))
        pos[:, 2:, :2] = arch.voussoir_centroids[None, :, :]
        return SimpleNamespace(outcome="no_hinging", positions=pos,
                               base_displacement=np.zeros(2))

    monkeypatch.setattr(th, "_default_run", stand_in)
    cfg = parse_config({"arch": ARCH, "site": {"hazard": HAZARD, "soil": "B",
                                               "time_history": "far-field"}})
    assert cfg.site.time_history == "fema-p695-far-field"
    lines: list[str] = []
    ctx = SimpleNamespace(config=cfg, arch=cfg.build_arch(), figures=tmp_path,
                          mode=Mode(True), say=lines.append)
    res = section_code_check(ctx)
    routes = res.data["time_history"]
    assert [r["limit_state"] for r in routes] == ["SLV", "SLC"]
    for r in routes:
        lo, hi = r["capacity"]["bracket_g"]
        assert lo < r["capacity_ag_g"] < hi and len(r["records"]) == 7
    assert any("SLV time-history route" in line for line in lines)
    el: list = []
    report_code_check(el, SimpleNamespace(sections={"codecheck": res}), res.data)
    items = [i for e in el if e[0] == "ul" for i in e[1]]
    assert any(i.startswith("SLV (time histories): capacity a_g") for i in items)


def test_time_history_suite_is_checked_with_the_file(tmp_path):
    with pytest.raises(StudyFileError, match=r"\[site\] time_history 'nowhere' is not a file"):
        parse_config({"arch": ARCH, "site": {"hazard": HAZARD, "soil": "B",
                                             "time_history": "nowhere"}}, base_dir=tmp_path)


def test_ec8_site_pga_is_gamma_i_a_gr_s():
    """Oracle: EN 1998-1 §3.2.2.2, a_g = gamma_I a_gR and ground C's S = 1.15 (Tab. 3.2)."""
    cfg = parse_config({"arch": ARCH, "site": {"code": "ec8", "ag_g": 0.2, "ground": "C",
                                               "importance": 1.2}})
    assert cfg.site_pga_g == pytest.approx(1.2 * 0.2 * 1.15, rel=1e-12)
    assert cfg.site_pga_source.startswith("gamma_I a_gR S = 1.2 x 0.2 g x 1.15 = 0.276 g")
