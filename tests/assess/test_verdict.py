"""One honest verdict, built from the sections' data (no time history run: the data below are
what the sections write, so the rules are checked one by one).

Oracles: the rules the report states: the verdict opens with its level word; its colour follows
the outcome (collapse likely or a failing code check: "fails"), never the certainty; it carries
the code check and marks quick mode as indicative; a warning that can only make collapse likelier
does not turn "collapse likely" into "not conclusive"; the report's list of sections is its
headings, in their order."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from archquake.assess.report import elements, write_html, write_markdown
from archquake.assess.sections import OUTCOMES, verdict


def _config(site=0.18):
    return SimpleNamespace(site_pga_g=site, friction=0.6, source="arch.toml", site=object(),
                           site_pga_source="a_g S_S S_T = 0.15 g x 1.2 x 1 = 0.18 g (SLV)",
                           notes=())


def _prior(p=0.95, warnings=(), code_passes=None):
    prior = {
        "static": {"collapse_acceleration_g": 0.05, "geometric_safety_factor": 1.3,
                   "sliding": False},
        "pulses": {f: {"collapses_at_site": True, "durations_collapsing_at_site_s": [0.5, 1.0],
                       "durations_s": [0.1, 0.5, 1.0], "min_collapse_g": 0.06}
                   for f in ("step", "sine")},
        "records": {"p_collapse_at_site": p, "p_collapse_at_site_ci": [0.8, 1.0],
                    "suite": "fema-p695-near-field-pulse", "records_used": ["a", "b", "c", "d"],
                    "records_in_suite": 28,
                    "fragility": {"first_collapse": {"median_g": 0.1}}},
        "validity": {"warnings": list(warnings), "step_sensitivity": []},
    }
    if code_passes is not None:
        prior["codecheck"] = {"limit_states": [
            {"limit_state": s, "method": "nonlinear", "governing": True,
             "passes": code_passes, "ratio": 1.4 if code_passes else 0.3}
            for s in ("SLV", "SLC")], "not_checked": {"SLD": "needs the return period 50 years"}}
    return prior


FRICTION = {"key": "friction_collapse", "warning": "with Coulomb joints the arch collapses "
            "where the no-slip chain does not", "meaning": "m", "serious": True}
STEP = {"key": "time_step", "warning": "the verdict changes at half the time step",
        "meaning": "m", "serious": True}


@pytest.mark.parametrize("p, level, outcome", [
    (0.95, "Collapse likely", "fails"), (0.3, "At risk", "at-risk"),
    (0.02, "Rocks but survives", "passes")])
def test_opens_with_its_level_word_and_colours_by_outcome(p, level, outcome):
    v = verdict(_config(), _prior(p))
    assert v["text"].startswith(level) and v["outcome"] == outcome and outcome in OUTCOMES
    assert v["certain"]


def test_a_failing_code_check_is_in_the_verdict_and_its_colour():
    v = verdict(_config(), _prior(0.02, code_passes=False))
    assert v["text"].startswith("Rocks but survives; code check FAILS at SLV, SLC.")
    assert "SLD not checked" in v["text"] and v["outcome"] == "fails"
    assert v["numbers"]["code_check_passes"] is False
    ok = verdict(_config(), _prior(0.02, code_passes=True))
    assert ok["text"].startswith("Rocks but survives; code check passes")
    assert ok["outcome"] == "passes"


def test_quick_mode_is_marked_indicative():
    v = verdict(_config(), _prior(0.95), quick=True)
    assert v["text"].startswith("Collapse likely, indicative") and v["indicative"]
    assert "4 of the 28 records" in v["text"]
    assert not verdict(_config(), _prior(0.95))["indicative"]


def test_a_warning_that_only_makes_collapse_likelier_keeps_collapse_likely_conclusive():
    v = verdict(_config(), _prior(0.99, [FRICTION]))
    assert v["certain"] and v["text"].startswith("Collapse likely.")
    assert "can only make collapse likelier" in v["text"]
    # ... but not a verdict of survival, nor a warning that cuts both ways
    assert not verdict(_config(), _prior(0.02, [FRICTION]))["certain"]
    both = verdict(_config(), _prior(0.99, [FRICTION, STEP]))
    assert not both["certain"] and both["text"].startswith("Collapse likely, NOT CONCLUSIVE.")
    assert both["text"].count("NOT CONCLUSIVE") == 1
    assert both["outcome"] == "fails"  # the colour follows the outcome, not the certainty


def test_at_risk_from_the_pulses_alone_stays_conclusive_under_friction():
    """The nave example: no records, pulses of the site PGA collapse it (at risk, the highest
    level the pulses give), and Coulomb joints collapse it under one more pulse: the friction
    check can only make collapse likelier, not change the level."""
    prior = _prior(0.3, [FRICTION])
    del prior["records"]
    v = verdict(_config(), prior)
    assert v["level"] == "at risk" and v["certain"] and v["outcome"] == "at-risk"
    # with records, at risk could still become collapse likely: not conclusive
    assert not verdict(_config(), _prior(0.3, [FRICTION]))["certain"]


def _report(tmp_path: Path, quick=True):
    from archquake.assess.site import report_code_check  # noqa: F401  (the section's writer)

    cfg = _config()
    cfg.arch = SimpleNamespace(canonical=lambda: {"radius": 5.0})
    prior = _prior(0.95, code_passes=False)
    st = prior["static"]
    st.update({"hinges": [], "thickness_m": 0.6, "min_thickness_m": 0.5,
               "static_friction_demand": 0.3, "static_friction_joint": 1,
               "friction_coefficient": 0.6})
    sections = {"arch": SimpleNamespace(data={"total_mass_kg": 1.0, "depth_m": 1.0,
                                              "overall_width_m": 1.0, "overall_height_m": 1.0,
                                              "blocks": []},
                                        figures=[SimpleNamespace(file="arch.png", caption="a")]),
                "static": SimpleNamespace(data=st, figures=[SimpleNamespace(file="static.png",
                                                                            caption="s")]),
                "validity": SimpleNamespace(data={"impact": {}, "model": "rigid",
                                                  "warnings": [],
                                                  "restitution_sensitivity": []})}
    return SimpleNamespace(config=cfg, sections=sections, quick=quick, seconds=1.0,
                           cached={"arch": False}, verdict=verdict(cfg, prior, quick=quick),
                           out=tmp_path)


def test_report_lists_its_sections_in_their_order_and_colours_the_verdict(tmp_path):
    rep = _report(tmp_path)
    el = elements(rep)
    heads = [e[2] for e in el if e[0] == "h2"]
    header = next(e[1] for e in el if e[0] == "p" and "Sections:" in e[1])
    assert header.endswith("Sections: " + ", ".join(heads) + ".")
    assert "quick mode (indicative)" in header
    md = write_markdown(rep, tmp_path / "report.md").read_text()
    assert "> **Verdict:** Collapse likely, indicative; code check FAILS" in md
    (tmp_path / "figures").mkdir()
    for f in ("arch.png", "static.png"):
        (tmp_path / "figures" / f).write_bytes(b"\x89PNG\r\n\x1a\n")
    page = write_html(rep, tmp_path / "report.html").read_text()
    assert '<p class="verdict fails"><b>Verdict: Collapse likely, indicative; code check ' \
           'FAILS at SLV, SLC.</b>' in page
    assert "verdict certain" not in page


def _colour_pixels(png, rgb, tol=12) -> int:
    import numpy as np
    from PIL import Image

    img = np.asarray(Image.open(png).convert("RGB"), dtype=int)
    return int(np.sum(np.all(np.abs(img - np.array(rgb)) <= tol, axis=-1)))


@pytest.mark.parametrize("p, code_passes, red", [(0.95, False, True), (0.02, True, False)])
def test_the_verdict_bar_is_red_for_collapse_in_a_real_browser(p, code_passes, red, tmp_path):
    """Chromium renders the report: the verdict's bar is red (#c0392b) where collapse is likely
    and the code check fails, green (#2e7d32) where the arch survives and the code check
    passes (it was green at P(collapse) = 0.95: coloured by certainty, not outcome)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "reproduce"))
    from test_browser import CHROMIUM, _chromium

    if CHROMIUM is None:
        pytest.skip("chromium is not installed")
    rep = _report(tmp_path)
    rep.verdict = verdict(rep.config, _prior(p, code_passes=code_passes), quick=True)
    (tmp_path / "figures").mkdir()
    for f in ("arch.png", "static.png"):
        (tmp_path / "figures" / f).write_bytes(b"\x89PNG\r\n\x1a\n")
    page = write_html(rep, tmp_path / "report.html")
    shot = tmp_path / "shot.png"
    run = _chromium(tmp_path, f"--screenshot={shot}", "--window-size=1000,700", page.as_uri())
    assert run.returncode == 0 and shot.is_file(), run.stderr[-2000:]
    red_px = _colour_pixels(shot, (0xC0, 0x39, 0x2B))
    green_px = _colour_pixels(shot, (0x2E, 0x7D, 0x32))
    if red:
        assert red_px > 300 and green_px == 0
    else:
        assert green_px > 300 and red_px == 0


def test_sections_are_numbered_as_they_come(tmp_path):
    """Without records, the DEM check or a code check the report's sections are 1 to 5, in
    order, with no gap where an absent section would be."""
    rep = _report(tmp_path)
    heads = [e[2] for e in elements(rep) if e[0] == "h2"]
    assert [h.split(". ")[0] for h in heads] == [str(n) for n in range(1, len(heads) + 1)]
    assert heads[-1].endswith("Verdict")


def _dem_section(factors):
    """The DEM check's data as `section_dem` writes it: one record case, run at ``factors``
    of the model's level, surviving in both models at every one."""
    runs = [{"factor": f, "level_g": 0.5 * f, "duration_s": 17.0, "dem_outcome": "survives",
             "model_outcome": "survives"} for f in factors]
    case = {"case": "record R", "model_level_g": 0.5, "lowest_dem_collapse_factor": None,
            "dem_more_vulnerable": False, "unconservative_by_at_least": 0.0,
            "model_collapses_below_its_level_factor": None, "runs": runs}
    return SimpleNamespace(data={"model": "rigid", "factors": list(factors), "cases": [case],
                                 "record_case": True, "record_cut_s": 14.0,
                                 "record_window_s": 17.0},
                           figures=[])


@pytest.mark.parametrize("quick, factors", [(False, (1.0, 0.85, 0.7)), (True, (0.85,))])
def test_the_dem_checks_threshold_row_is_read_as_a_threshold(tmp_path, quick, factors):
    """Oracle: the DEM check's 1.0 x run is at the model's own collapse level, where a DEM
    verdict can turn on a 1e-12 change of a record's scale (docs/assess.md): the report says
    so under the table when that row is there (full mode), and does not draw a conclusion
    from it alone; quick mode runs no such row."""
    rep = _report(tmp_path, quick=quick)
    rep.sections["dem"] = _dem_section(factors)
    text = " ".join(str(e[1]) if e[0] == "p" else " ".join(map(str, e[1])) if e[0] == "ul"
                    else "" for e in elements(rep))
    assert ("The 1.0 x rows are at the" in text) is (not quick)
    if not quick:
        assert "weak evidence that the" in text and "is conservative there" in text
        assert "its result is conservative there." not in text
