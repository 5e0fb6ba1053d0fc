"""The quick assessment of examples/bridge.toml: every section present in the three outputs,
every number checked against the API run again on the same input (the oracle: the library's
own functions called directly, not through the assessment), the full mode's static numbers
equal to the quick mode's, and a rerun served from the cache. The HTML report in headless
Chromium, with the reproduction's browser helper: the seven sections in the DOM, every figure
embedded as a PNG, a screenshot that is not blank (in this file, so that one test worker builds
the assessment they share)."""

from __future__ import annotations

import base64
import json
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from archquake.assess.sections import Context, Mode, prepared_mechanism, section_arch, section_static

from .conftest import bare_bridge

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "reproduce"))
from test_browser import CHROMIUM, _chromium  # noqa: E402  (the reproduction's helper)

needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed")

SECTIONS = ("arch", "static", "pulses", "records", "dem", "validity", "codecheck")
TITLES = ("1. The arch", "2. Static capacity", "3. Pulses", "4. Records", "5. The DEM check",
          "6. Validity", "7. Code check (NTC 2018 §8.7.1, Circolare 2019 C8.7.1.2)", "8. Verdict")
#: The bridge's site PGA: a_g S_S S_T at the SLV of its [site] table (0.1499 g x 1.2 x 1).
SITE = bare_bridge().site_pga_g


def test_every_section_is_present(bridge):
    rep, res, out, _ = bridge
    assert tuple(res["sections"]) == SECTIONS
    md = (out / "report.md").read_text()
    html = (out / "report.html").read_text()
    for title in TITLES:
        assert f"## {title}" in md and f"<h2>{title}</h2>" in html
    for fig in ("arch.png", "static.png", "domain_step.png", "domain_sine.png", "records.png"):
        assert (out / "figures" / fig).is_file() and f"figures/{fig}" in md
    assert "Verdict" in md and "Assumptions" in md
    assert res["verdict"]["text"] in md.replace("> **Verdict:** ", "")
    assert "4 of the 28 records, so this probability is indicative" in md  # quick mode
    # the list of sections in the header is the headings, in their order
    assert "Sections: " + ", ".join(t.split(" (")[0] for t in TITLES) + "." in md
    assert [md.index(f"## {t}") for t in TITLES] == sorted(md.index(f"## {t}") for t in TITLES)


def test_keys_carry_units(bridge):
    _, res, _, _ = bridge
    assert res["input"]["site_pga_g"] == pytest.approx(SITE)
    assert res["site_pga_source"].startswith("a_g S_S S_T = 0.1499 g x 1.2 x 1")
    assert res["input_warnings"] == []
    st = res["sections"]["static"]
    assert {"collapse_acceleration_g", "min_thickness_m", "thickness_m"} <= set(st)
    block = res["sections"]["arch"]["blocks"][0]
    assert {"mass_kg", "centroid_x_m", "centroid_y_m"} == set(block) - {"block"}
    assert {"durations_s", "collapse_g"} <= set(res["sections"]["pulses"]["step"])


def test_static_numbers_equal_the_api(bridge):
    from archquake.limit import geometric_safety_factor, limit_analysis, min_thickness

    _, res, out, _ = bridge
    arch = bare_bridge().build_arch()
    la = limit_analysis(arch)
    st = res["sections"]["static"]
    assert st["collapse_acceleration_g"] == la.collapse_acceleration_g
    assert st["min_thickness_m"] == min_thickness(arch)
    assert st["geometric_safety_factor"] == geometric_safety_factor(arch)
    assert st["static_friction_demand"] == la.min_friction
    assert st["sliding"] == (la.min_friction > 0.6)
    assert [h["joint"] for h in st["hinges"]] == list(la.mechanism.joints)
    a = res["sections"]["arch"]
    assert math.isclose(a["total_mass_kg"], arch.mass, rel_tol=1e-12)
    assert [b["mass_kg"] for b in a["blocks"]] == list(arch.voussoir_masses)
    md = (out / "report.md").read_text()
    assert f"{la.collapse_acceleration_g:.4f} g" in md
    assert f"{min_thickness(arch):.4f} m" in md


def test_pulse_domain_equals_the_api(bridge):
    """The step domain at one duration, searched again with the same settings and c_v."""
    from archquake.domains import failure_domain

    _, res, _, _ = bridge
    pu = res["sections"]["pulses"]
    arch = bare_bridge().build_arch()
    assert pu["restitution_cv"] == 0.8  # the example's prescribed value
    k = 2
    d = failure_domain(prepared_mechanism(arch, "paper"), "step",
                       [pu["step"]["durations_s"][k]], settings=Mode(True).domain_settings,
                       restitution=0.8)
    assert pu["step"]["collapse_g"][k] == pytest.approx(float(d.collapse_g[0]), rel=1e-12)
    site = SITE
    assert site == pytest.approx(0.1799, abs=1e-4)
    coll = np.array([np.nan if x is None else x for x in pu["step"]["collapse_g"]], dtype=float)
    assert pu["step"]["collapses_at_site"] == bool(np.any(coll <= site))


def test_records_numbers_follow_from_the_fit(bridge):
    """P(collapse) at the site is the lognormal fit's value at the site PGA; the fit is the
    first-collapse MLE of the listed first-collapse levels (refitted here)."""
    from archquake.ida.fragility import LognormalFit, fit_first_collapse

    _, res, _, _ = bridge
    r = res["sections"]["records"]
    fit = r["fragility"]["first_collapse"]
    p = LognormalFit(fit["median_g"], fit["beta"], "first_collapse", fit["records"]).probability(SITE)
    assert r["p_collapse_at_site"] == pytest.approx(float(p), rel=1e-12)
    first = np.array([np.nan if x is None else x for x in r["first_collapse_g"]])
    again = fit_first_collapse(first, ceiling=r["ceiling_g"], bootstrap=0)
    assert again.median == pytest.approx(fit["median_g"], rel=1e-9)
    assert again.beta == pytest.approx(fit["beta"], rel=1e-9)
    lo, hi = r["p_collapse_at_site_ci"]
    assert 0 <= lo <= hi <= 1
    assert len(r["records_used"]) == 4 and r["records_in_suite"] == 28


def test_validity_reports_the_paper_law_and_the_sensitivity(bridge):
    """The semicircle's paper-law c_v (49.9, creating energy) is reported, and the verdict is
    recomputed at c_v = 0.7 and 0.9."""
    from archquake.mechanism.prepared import PreparedMechanism

    _, res, _, _ = bridge
    va = res["sections"]["validity"]
    own = PreparedMechanism.build(bare_bridge().build_arch()).impact
    assert va["impact"]["law_restitution_cv"] == own.restitution_cv
    assert va["impact"]["law_energy_gain"] and va["impact"]["used_restitution_cv"] == 0.8
    assert any(w["key"] == "impact_law" for w in va["warnings"])
    assert [round(e["restitution_cv"], 6) for e in va["restitution_sensitivity"]] == [0.7, 0.9]


def test_verdict_is_not_certain_when_a_serious_warning_is_raised(bridge):
    from archquake.assess.sections import verdict

    rep, res, _, _ = bridge
    prior = {k: dict(v.data) for k, v in rep.sections.items()}
    prior["validity"] = dict(prior["validity"], warnings=[
        {"key": "x", "warning": "outside", "meaning": "m", "serious": True}])
    v = verdict(rep.config, prior)
    assert not v["certain"] and f"{v['level']}, NOT CONCLUSIVE".lower() in v["text"].lower()
    assert v["text"].lower().startswith(v["level"])
    assert res["verdict"]["certain"] == (not any(w["serious"] for w in
                                               res["sections"]["validity"]["warnings"]))


def test_full_and_quick_agree_on_the_static_numbers(bridge, tmp_path):
    rep, res, _, _ = bridge
    cfg = bare_bridge()
    ctx = Context(cfg, cfg.build_arch(), Mode(False), tmp_path, tmp_path)
    full = json.loads(json.dumps(section_static(ctx).to_dict()))["data"]
    quick = res["sections"]["static"]
    for key, value in full.items():
        assert quick[key] == value, key
    arch_full = json.loads(json.dumps(section_arch(ctx).to_dict()))["data"]
    assert arch_full["blocks"] == res["sections"]["arch"]["blocks"]


def test_rerun_is_served_from_the_cache(bridge):
    from archquake.assess import run_assessment

    rep, res, out, _ = bridge
    lines: list[str] = []
    again = run_assessment(rep.config, out, quick=True, progress=lines.append)
    assert all(again.cached.values()) and all("cached" in line for line in lines)
    assert again.verdict == rep.verdict
    assert json.loads((out / "results.json").read_text())["sections"]["static"] == \
        res["sections"]["static"] | {"cached": True}


def test_restitution_sensitivity_reruns_the_ida(bridge, tmp_path):
    """P(collapse | site PGA) of the records at c_v = 0.7, 0.8 and 0.9: three values, the middle
    one the records section's own; the c_v = 0.9 one equal to the library's IDA of the same four
    records run here again (serially, a fresh store) and its first-collapse fit at the site PGA.
    Physics: a larger c_v keeps more kinetic energy through each impact, so P(collapse) should
    not fall as c_v grows; where it does, the validity section must say so (warning
    restitution_ida_order), and only then."""
    from archquake.ground.suites import load_suite
    from archquake.ida import incremental_dynamic_analysis
    from archquake.ida.fragility import fit_first_collapse
    from archquake.parallel import SerialExecutor
    from archquake.sweeps import CaseOptions, ResultStore

    _, res, out, _ = bridge
    va = res["sections"]["validity"]
    ida = va["restitution_sensitivity_ida"]
    assert [round(e["restitution_cv"], 6) for e in ida] == [0.7, 0.8, 0.9]
    rec = res["sections"]["records"]
    assert ida[1]["p_collapse_at_site"] == rec["p_collapse_at_site"]
    assert ida[1]["fragility_median_g"] == rec["fragility"]["first_collapse"]["median_g"]
    ps = [e["p_collapse_at_site"] for e in ida]
    assert all(p is not None and 0.0 <= p <= 1.0 for p in ps)
    ordered = ps[0] <= ps[1] <= ps[2]
    keys = [w["key"] for w in va["warnings"]]
    assert ordered or "restitution_ida_order" in keys
    assert ordered != ("restitution_ida_order" in keys)
    for e in ida:  # each P is a lognormal CDF at the site PGA: below 1/2 iff the median is above
        assert (e["p_collapse_at_site"] < 0.5) == (e["fragility_median_g"] > SITE)
    cfg = rep_config = bare_bridge()
    suite = load_suite(cfg.suite)
    records = Mode(True).records(suite.records)
    assert [r.name for r in records] == rec["records_used"]
    with ResultStore(tmp_path / "ida.sqlite") as store:
        again = incremental_dynamic_analysis(rep_config.arch, records, "pga", store,
                                             model="fourlink",
                                             options=CaseOptions(restitution=0.9),
                                             executor=SerialExecutor(), workers=1,
                                             **Mode(True).ida)
    fit = fit_first_collapse(list(again.first_collapse_levels), ceiling=again.ceiling,
                             bootstrap=0)
    assert ida[2]["p_collapse_at_site"] == pytest.approx(float(fit.probability(SITE)), rel=1e-9)
    md = (out / "report.md").read_text()
    assert "Restitution sensitivity of the records" in md
    for e in ida:
        assert f"{e['p_collapse_at_site']:.3f}" in md
    assert "P(collapse) of the records is" in res["verdict"]["text"]


# ------------------------------------------------------------------ the report in a browser
@needs_chromium
def test_dom_has_every_section_and_embedded_figures(tmp_path, bridge):
    _, _, out, _ = bridge
    run = _chromium(tmp_path, "--dump-dom", (out / "report.html").as_uri())
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    for sid in ("arch", "static", "pulses", "records", "dem", "validity", "codecheck", "verdict"):
        assert f'<section id="{sid}">' in dom, sid
    srcs = re.findall(r'<img[^>]*src="(data:image/png;base64,[^"]+)"', dom)
    assert len(srcs) == 6  # the five figures of the dynamics, and the code check's capacity curve
    for s in srcs:
        assert base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    assert "src=\"figures/" not in dom and "http" not in dom.split("<body>")[1][:200]


@needs_chromium
def test_screenshot_is_not_blank(tmp_path, bridge):
    from PIL import Image

    _, _, out, _ = bridge
    shot = tmp_path / "shot.png"
    run = _chromium(tmp_path, f"--screenshot={shot}", "--window-size=1200,1600",
                    (out / "report.html").as_uri())
    assert run.returncode == 0 and shot.is_file(), run.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert img.std() > 10 and len(np.unique(img)) > 50
