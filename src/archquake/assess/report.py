"""The assessment's report: one list of elements (headings, paragraphs, tables, figures) written
as Markdown (figures linked) and as one self-contained HTML page (figures embedded; the
reproduction's style sheet and image embedding, `archquake.reproduce.report`)."""

from __future__ import annotations

import html
import math
from pathlib import Path

from archquake import __version__, models
from archquake.assess.sections import assumptions
from archquake.assess.site import report_code_check
from archquake.blocks.result import REST_KINETIC
from archquake.reproduce.report import REPORT_CSS, image_data_uri, md_cell

#: The verdict's colour follows its outcome (archquake.assess.sections.OUTCOMES), never its
#: certainty; a verdict that is not conclusive gets a dashed border in its outcome's colour.
_EXTRA_CSS = (".verdict{font-size:1.05em;padding:0.8em;border-left:6px solid #888;"
              "background:#f7f7f7}.verdict.fails{border-color:#c0392b;background:#fbecea}"
              ".verdict.at-risk{border-color:#e67e22;background:#fdf2e6}"
              ".verdict.passes{border-color:#2e7d32;background:#edf7ee}"
              ".verdict.inconclusive{border-left-style:dashed}li.serious{color:#8a1010}")


def _f(x, digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "none"
    return f"{x:.{digits}f}" if isinstance(x, float) else str(x)


def elements(rep) -> list[tuple]:
    """The report as (kind, ...) tuples: ("h1", text), ("h2", id, text), ("p", text),
    ("table", headers, rows), ("fig", file, caption), ("ul", items),
    ("verdict", text, certain, outcome). The sections are numbered as they come, and the
    header lists them from their headings."""
    cfg = rep.config
    s = {k: v.data for k, v in rep.sections.items()}
    v = rep.verdict
    verdict_el = ("verdict", v["text"], v["certain"], v.get("outcome", "open"))
    el: list[tuple] = [("h1", f"Assessment of {cfg.source}"), verdict_el]

    a = s["arch"]
    el.append(("h2", "arch", "1. The arch"))
    site = ("" if cfg.site_pga_g is None else
            f" Site PGA of the dynamic sections {cfg.site_pga_g:.3g} g: "
            f"{getattr(cfg, 'site_pga_source', None) or '[seismic] site_pga_g'}.")
    el.append(("p", "Input: " + ", ".join(f"{k} = {val}" for k, val in cfg.arch.canonical().items())
               + f"; friction coefficient {cfg.friction:g}. "
               + ("Total mass " if "masses" not in a else "Mass of the masonry ")
               + f"{a['total_mass_kg']:.0f} kg (depth {a['depth_m']:g} m)"
               + ("" if "masses" not in a else
                  f", carrying {a['masses']['carried_mass_kg']:.0f} kg (below)")
               + ", overall "
               f"{a['overall_width_m']:.2f} m wide and {a['overall_height_m']:.2f} m high."
               + site))
    notes = getattr(cfg, "notes", ())
    if notes:
        el.append(("ul", [(f"Input warning: {n}", True) for n in notes]))
    el.append(("fig", "arch.png", rep.sections["arch"].figures[0].caption))
    el.append(("table", ["block", "mass (kg)", "centroid x (m)", "centroid y (m)"],
               [[b["block"], f"{b['mass_kg']:.1f}", f"{b['centroid_x_m']:.3f}",
                 f"{b['centroid_y_m']:.3f}"] for b in a["blocks"]]))
    if "loads" in a:
        _loads(el, a)

    st = s["static"]
    el.append(("h2", "static", "2. Static capacity"))
    hinges = ", ".join(f"{'ABCD'[i]} at joint {h['joint']} ({h['face']})"
                       for i, h in enumerate(st["hinges"]))
    rows = [["collapse acceleration lambda", f"{st['collapse_acceleration_g']:.4f} g"],
            ["hinges (load towards +x)", hinges],
            ["thickness t", f"{st['thickness_m']:.3f} m"],
            ["minimum thickness t_min (same shape" + (", under the same fill and loads)"
                                                       if "loads" in st else ")"),
             "not defined: " + str(st.get("min_thickness_note")) if st["min_thickness_m"] is None
             else f"{st['min_thickness_m']:.4f} m"],
            ["geometric factor of safety t / t_min", _f(st["geometric_safety_factor"])],
            ["static friction demand max |V|/N", f"{st['static_friction_demand']:.3f} (joint "
                                                   f"{st['static_friction_joint']})"],
            ["friction coefficient given", f"{st['friction_coefficient']:g}"],
            ["sliding", "YES: the joints slide before the arch rocks" if st["sliding"]
             else "no (demand below the coefficient)"]]
    if "site_over_lambda" in st:
        rows.append(["site PGA / lambda", f"{st['site_over_lambda']:.2f}"])
    el.append(("table", ["quantity", "value"], rows))
    el.append(("fig", "static.png", rep.sections["static"].figures[0].caption))
    if "traffic" in s:
        _traffic(el, rep, s["traffic"])

    pu = s.get("pulses")
    if pu is None:
        el.append(("h2", "pulses", "3. Pulses"))
        el.append(("p", "Not run: " + str(_refusal(s)) + "."))
    else:
        _pulses(el, rep, cfg, pu)
    _records_dem_validity(el, rep, cfg, s, pu)
    if "vertical" in s:
        _vertical(el, s["vertical"])
    if "codecheck" in s:
        report_code_check(el, rep, s["codecheck"])
    el.append(("h2", "verdict", "8. Verdict"))
    el.append(verdict_el)
    el.append(("table", ["number", "value"], [[k, _f(x) if not isinstance(x, list) else
                                               ", ".join(_f(y) for y in x)]
                                              for k, x in v["numbers"].items()]))
    el.append(("p", "Assumptions: " + "; ".join(assumptions(cfg)) + ". Hinges form only at the joints "
                    "between the blocks; the ground moves horizontally in the arch's plane."))
    # numbered as they come (a file without records or a [site] table has fewer sections), and
    # the list of sections made from the headings themselves: the list and the order agree
    heads = [k for k, e in enumerate(el) if e[0] == "h2"]
    for n, k in enumerate(heads, 1):
        kind, sid, text = el[k]
        el[k] = (kind, sid, f"{n}. {text.split('. ', 1)[1]}")
    titles = [e[2].split(" (")[0] for e in el if e[0] == "h2"]
    el.insert(1, ("p", f"archquake {__version__}, {'quick' if rep.quick else 'full'} mode"
                       f"{' (indicative)' if rep.quick else ''}, computed in {rep.seconds:.0f} s"
                       f"{' (partly cached)' if any(rep.cached.values()) else ''}. "
                       "Sections: " + ", ".join(titles) + "."))
    return el


def _vertical(el: list, v: dict) -> None:
    """The vertical section: the runs with and without the vertical, side by side."""
    el.append(("h2", "vertical", "7. The vertical component"))
    el.append(("p", "The vertical ground acceleration a_v(t) acts as gravity g + a_v(t) in "
                    f"every run of the {_model_name(v['model'])}; each row gives the same runs "
                    "with and without it."))
    pu = v.get("pulses")
    if pu is not None:
        el.append(("p", f"Step pulses with a vertical part R = {v['vertical_ratio']:g} (R a s(t) "
                        "upward, s(t) the pulse's own shape): the least magnitude that collapses "
                        f"the arch on a grid {100 * pu['grid_step']:g} % apart up to "
                        f"{pu['top_g']:.3g} g (the vertical lifts the arch off at "
                        f"{pu['lift_off_g']:.3g} g)."))
        el.append(("table", ["t_p (s)", "without (g)", f"R = {v['vertical_ratio']:g} (g)",
                             "change"],
                   [[f"{r['duration_s']:.3g}", _f(r["first_collapse_g"]),
                     _f(r["first_collapse_vertical_g"]), _change(r["first_collapse_g"],
                                                                  r["first_collapse_vertical_g"])]
                    for r in pu["rows"]]))
    rows = v.get("records")
    if rows:
        el.append(("p", "Records with their vertical component: the first collapsing PGA of "
                        "the records section (both components scaled together) beside the IDA "
                        "of the horizontal alone, up to the same ceiling "
                        f"{v['records_ceiling_g']:.3g} g."))
        el.append(("table", ["record", "V/H (PGA)", "with the vertical (g)",
                             "horizontal alone (g)", "change"],
                   [[r["record"], f"{r['v_over_h_pga']:.2f}", _f(r["first_collapse_g"]),
                     _f(r["first_collapse_horizontal_only_g"]),
                     _change(r["first_collapse_horizontal_only_g"], r["first_collapse_g"])]
                    for r in rows]))


def _change(without: float | None, with_vertical: float | None) -> str:
    if without is None or with_vertical is None:
        return "-"
    return f"{100 * (with_vertical / without - 1):+.1f} %"


def _loads(el: list, a: dict) -> None:
    """What the arch carries (the ``[loads]`` table, per metre of barrel width) and the masses
    the models move."""
    lo, m = a["loads"], a["masses"]
    rows = []
    f = lo.get("fill")
    if f is not None:
        where = (f"surface {f['depth_m']:g} m over the crown's extrados" if f["depth_m"]
                 is not None else f"surface at y = {f['level_m']:g} m")
        rows.append(["fill", f"{where}, {f['density_kg_m3']:g} kg/m^3; each block carries the "
                             "column of fill above its extrados"])
    b = lo.get("backing")
    if b is not None:
        rows.append(["backing", f"{b['left_m']:g} m (left) and {b['right_m']:g} m (right) above "
                                "the springings: no hinge at joints "
                                f"{', '.join(map(str, m['held_joints']))} (joints numbered from "
                                "0 at the left springing)"
                     + (f"; blocks {', '.join(map(str, m['held_blocks']))} belong to the "
                        "support" if m.get("held_blocks") else "")])
    for p in lo.get("point_loads", []):
        rows.append(["point load", f"{p['load_N_m'] / 1e3:g} kN/m at {p['position_m']:g} m, "
                                   "its mass moving with the arch"])
    for d in lo.get("distributed_loads", []):
        rows.append(["distributed load", f"{d['pressure_Pa'] / 1e3:g} kN/m^2 from "
                                         f"{d['start_m']:g} to {d['end_m']:g} m, its mass "
                                         "moving with the arch"])
    t = lo.get("traffic")
    if t is not None:
        kind = "axle" if not t["length_m"] else f"patch {t['length_m']:g} m long"
        spread = ("Boussinesq (Flamant)" if t["boussinesq"] else "not spread"
                  if t["dispersion_deg"] is None else
                  f"spread at {t['dispersion_deg']:g} deg through the fill")
        rows.append(["traffic", f"{t['load_N_m'] / 1e3:g} kN/m {kind}, {spread}; statics only "
                                "(the traffic check), no mass"])
    rows.append(["passive fill pressure", "off (not modelled)"])
    el.append(("p", "What the arch carries (positions along the clear span from the left "
                    "springing of the intrados; loads per metre of barrel width). Every section "
                    "carries the fill, the backing and the loads on the extrados; the traffic "
                    "load enters the traffic check only."))
    el.append(("table", ["load", "as modelled"], rows))
    el.append(("table", ["mass", "kg"], [
        ["masonry (the voussoirs)", f"{m['masonry_mass_kg']:.0f}"],
        ["fill columns", f"{m['fill_mass_kg']:.0f}"],
        ["loads on the extrados (moving with the arch)", f"{m['superimposed_mass_kg']:.0f}"],
        ["carried in all", f"{m['carried_mass_kg']:.0f}"],
        ["held by the backing (masonry and carried; with the support)",
         f"{m.get('held_mass_kg', 0.0):.0f}"]]))


def _traffic(el: list, rep, t: dict) -> None:
    """The traffic check: the adequacy factor and the scan's figure."""
    el.append(("h2", "traffic", "3. Traffic check"))
    spread = ("Boussinesq (Flamant)" if t["boussinesq"] else "not spread"
              if t["dispersion_deg"] is None else f"spread at {t['dispersion_deg']:g} deg")
    el.append(("p", f"The {t['load_kN_m']:g} kN/m {t['kind']} ({spread}) moved along the clear "
                    f"span over the dead loads, at {t['positions']} positions: the multiplier on "
                    "it that collapses the arch (equilibrium and the four-hinge mechanism, "
                    "statics only). The least multiplier is the adequacy factor."))
    hinges = ", ".join(str(j) for j in t["hinge_joints"])
    crit = t["critical"]
    el.append(("table", ["quantity", "value"], [
        ["adequacy factor (least multiplier)", f"{t['adequacy_factor']:.3f}"],
        ["critical position", f"{t['critical_position_m']:.3f} m from the left springing"],
        ["collapse load there", f"{t['collapse_load_kN_m']:.1f} kN/m"],
        ["hinges (joints)", hinges],
        ["static and kinematic bounds", f"{_f(crit.get('static_multiplier'))} and "
                                        f"{_f(crit.get('kinematic_multiplier'))}"]]))
    el.append(("fig", "traffic.png", rep.sections["traffic"].figures[0].caption))


def _model_name(model: str) -> str:
    """The model in words, for the report."""
    return models.spec(model).label


def _refusal(s: dict) -> str | None:
    return next((w["meaning"] for w in s["validity"]["warnings"] if w["key"] == "asymmetric"),
                None)


def _pulses(el: list, rep, cfg, pu: dict) -> None:
    el.append(("h2", "pulses", "3. Pulses"))
    how = (f"the four-link mechanism, c_v = {pu['restitution_cv']:.3g}"
           if pu.get("restitution_cv") is not None else
           "the chain of rigid voussoirs, every voussoir a block (its first-half-cycle boundary "
           "is not searched)")
    el.append(("p", f"Failure domains of the step and the one-cycle sine pulse, {how}. Below "
                    "the governing boundary the arch survives; above it, it collapses (except "
                    "in non-monotonic bands)."))
    rows = []
    governing_only = pu.get("restitution_cv") is None  # the rigid chain's search
    for fam in ("step", "sine"):
        d = pu[fam]
        for t, c, f1 in zip(d["durations_s"], d["collapse_g"], d["first_half_cycle_g"],
                            strict=True):
            rows.append([fam, f"{t:.3f}", "none found" if _f(c) == "none" else _f(c),
                         "not searched" if governing_only and _f(f1) == "none" else _f(f1)])
    el.append(("table", ["pulse", "duration (s)", "collapse (g)", "1st half cycle (g)"], rows))
    items: list = []
    for fam in ("step", "sine"):
        d = pu[fam]
        text = f"{fam}: lowest collapse magnitude {_f(d['min_collapse_g'])} g"
        if cfg.site_pga_g is not None:
            cs = d["durations_collapsing_at_site_s"]
            text += (f"; at the site PGA {cfg.site_pga_g:.3g} g the durations "
                     + ", ".join(f"{x:.3g}" for x in cs) + " s collapse it" if cs else
                     f"; no duration scanned collapses it at the site PGA {cfg.site_pga_g:.3g} g")
        bands = d["non_monotonic_bands"]
        text += (f"; {len(bands)} non-monotonic band(s): " + ", ".join(
            f"{b['duration_s']:.3g} s: {b['lower_g']:.3f}-{b['upper_g']:.3f} g ({b['criterion']})"
            for b in bands)) if bands else "; no non-monotonic band"
        items.append(text)
    el.append(("ul", items))
    for f in rep.sections["pulses"].figures:
        el.append(("fig", f.file, f.caption))


def _records_dem_validity(el: list, rep, cfg, s: dict, pu: dict | None) -> None:

    if "records" in s:
        r = s["records"]
        el.append(("h2", "records", "4. Records"))
        fit = r["fragility"]["first_collapse"]
        how = (f"the four-link mechanism, c_v = {r['restitution_cv']:.3g}"
               if r.get("restitution_cv") is not None else "the chain of rigid voussoirs")
        text = (f"Incremental dynamic analysis (PGA) of {len(r['records_used'])} of the "
                f"{r['records_in_suite']} records of {r['suite']} ({r['runs']} time histories, "
                f"{how}); {r['records_collapsing']} collapse the arch below the ceiling "
                f"{r['ceiling_g']:.2f} g.")
        if fit is not None:
            ci = fit.get("median_ci_g")
            text += (f" Fragility (first collapse, lognormal): median {fit['median_g']:.3f} g"
                     + (f" [{ci[0]:.3f}, {ci[1]:.3f}]" if ci else "")
                     + f", beta {fit['beta']:.2f}.")
        if "p_collapse_at_site" in r:
            ci = r.get("p_collapse_at_site_ci")
            text += (f" P(collapse | PGA = {cfg.site_pga_g:.3g} g) = {r['p_collapse_at_site']:.3f}"
                     + (f" (90 % bootstrap interval over the records {ci[0]:.3f} to {ci[1]:.3f})"
                        if ci else "") + f"; fraction of the records collapsing at that level "
                     f"{r['fraction_collapsing_at_site']:.2f}.")
        if rep.quick and len(r["records_used"]) < r["records_in_suite"]:
            text += (f" Quick mode: {len(r['records_used'])} of the {r['records_in_suite']} "
                     "records, so this probability is indicative; the full mode runs them all.")
        el.append(("p", text))
        el.append(("table", ["record", "first collapse PGA (g)"],
                   [[n, _f(x)] for n, x in zip(r["records_used"], r["first_collapse_g"],
                                               strict=True)]))
        el.append(("fig", "records.png", rep.sections["records"].figures[0].caption))

    if "dem" in s:
        d = s["dem"]
        el.append(("h2", "dem", "5. The DEM check"))
        who = _model_name(d.get("model", "fourlink"))
        el.append(("p", "The distinct-element model (every voussoir a rigid block on Coulomb "
                        "contacts, the paper's stiffness and damping) on the governing cases: a "
                        f"step pulse on the {who}'s domain boundary and the record whose first "
                        "collapse is nearest the fragility median, run at fractions of the "
                        f"{who}'s collapse level (where it survives)."
                   + (f" The DEM runs the pulse up to {d['dem_pulse_tail_s']:.1f} s after it "
                      f"(twice the {who}'s window: its elastic contacts take longer to come "
                      "to rest)." if "dem_pulse_tail_s" in d else "")
                   + (f" The record is cut where 95 % of its Arias intensity has arrived "
                      f"({d['record_cut_s']:.1f} s), and both models run it to 3 s after the "
                      f"cut ({d['record_window_s']:.1f} s), so that the DEM can come to rest."
                      if "record_cut_s" in d else "")
                   + " Every DEM run ends once collapsed or at rest after the ground motion "
                     f"(the kinetic energy below {REST_KINETIC:g} W L over a still window): its "
                     "verdict is then the one the rest of the window would give."))
        if rep.quick:
            el.append(("p", f"Quick mode: one DEM run per case, at 0.85 x the {who}'s level; "
                            "the full mode runs 1.0, 0.85 and 0.7 x."))
        rows = []
        for c in d["cases"]:
            for run in c["runs"]:
                rows.append([c["case"], f"{run['factor']:g}", f"{run['level_g']:.4f}",
                             run["model_outcome"], run["dem_outcome"]])
        el.append(("table", ["case", f"x {who}'s collapse level", "magnitude / PGA (g)",
                             who, "DEM"], rows))
        if any(run["factor"] == 1.0 for c in d["cases"] for run in c["runs"]):
            el.append(("p", f"The 1.0 x rows are at the {who}'s own collapse level, a "
                            "threshold: there the DEM's verdict can turn on the last bits of "
                            "its arithmetic (a change of 1e-12 in a record's scale has turned "
                            "it), so read them as the threshold and the lower rows as the "
                            "check."))
        items = []
        for c in d["cases"]:
            below = c.get("model_collapses_below_its_level_factor")
            if below is not None:
                items.append(f"{c['case']}: the {who} itself collapses at {below:g} x the "
                             f"level its search reported ({c['model_level_g']:.4f} g): the "
                             "search missed a band of collapses below that level, so the "
                             "capacity there is lower than reported.")
            dem_below = [r["factor"] for r in c["runs"]
                         if r["factor"] < 1.0 and r["dem_outcome"] == "collapse"]
            if c["dem_more_vulnerable"]:
                items.append(f"{c['case']}: the DEM is more vulnerable: it collapses at "
                             f"{c['lowest_dem_collapse_factor']:g} x the {who}'s level "
                             f"({c['model_level_g']:.4f} g); the {who}'s result is "
                             f"UNCONSERVATIVE there by at least "
                             f"{100 * c['unconservative_by_at_least']:.0f} %.")
            elif dem_below:
                items.append(f"{c['case']}: the DEM collapses at {min(dem_below):g} x the "
                             f"{who}'s reported level, and so does the {who}: the two models "
                             "agree there.")
            else:
                at_one = [r for r in c["runs"] if r["factor"] >= 1.0]
                more = (f" The DEM survives even at the {who}'s collapse level, a threshold "
                        "where one run's verdict can turn on rounding: weak evidence that the "
                        f"{who}'s result is conservative there." if at_one and
                        at_one[0]["dem_outcome"] != "collapse" else "")
                items.append(f"{c['case']}: the DEM does not collapse below the {who}'s "
                             f"level ({c['model_level_g']:.4f} g) at the fractions run: "
                             f"no sign that its result is unconservative.{more}")
        el.append(("ul", items))

    va = s["validity"]
    el.append(("h2", "validity", "6. Validity"))
    imp = va["impact"]
    if va.get("model") is not None and models.spec(va["model"]).blocks:
        el.append(("p", "Impacts: the chain of rigid voussoirs' plastic corner contacts (no "
                        "coefficient of restitution to choose)."))
    elif "law_restitution_cv" not in imp:
        el.append(("p", f"Impact law '{imp['law']}': not evaluated (no time history is run)."))
    else:
        el.append(("p", f"Impact law '{imp['law']}': c_v = {imp['law_restitution_cv']:.4g}, "
                        f"c_T = "
                        f"{imp['law_restitution_ct']:.4g}, validity '{imp['law_validity']}'"
                   + (", creates energy" if imp["law_energy_gain"] else "")
                   + (f"; prescribed c_v = {imp['prescribed_restitution_cv']:g} used"
                      if imp["prescribed_restitution_cv"] is not None else "")
                   + ". c_v used by every four-link time history: "
                   + f"{imp['used_restitution_cv']:.4g}."))
    warned: list = [(f"{w['warning']}: {w['meaning']}.", w["serious"]) for w in va["warnings"]]
    el.append(("ul", warned or ["no warning raised"]))
    steps = va.get("step_sensitivity", [])
    if steps:
        which = ("the two scanned durations of each family whose boundary is nearest it"
                 if rep.quick else "every scanned duration")
        el.append(("p", f"What the verdicts rest on: each pulse of the site PGA "
                        f"({cfg.site_pga_g:.3g} g) at {which} (and the governing "
                        f"record scaled to it) run at the time step "
                        f"{steps[0]['time_step_s']:.3g} s, at half of it, and with Coulomb "
                        f"joints of mu = {steps[0]['friction_coefficient']:g} at the same step "
                        "(a friction verdict that differs from the no-slip one is run again at "
                        f"{steps[0].get('friction_recheck_time_step_s', 1e-4):.3g} s and that "
                        "one kept, its step in brackets)."))
        el.append(("table", ["case", "step", "half step", "friction"],
                   [[r["case"], r["default_step"], r["half_step"], r["friction"] + (
                       f" ({r['friction_time_step_s']:.3g} s)"
                       if r.get("friction_time_step_s", r["time_step_s"]) != r["time_step_s"]
                       else "")] for r in steps]))
    if va["restitution_sensitivity"] and pu is not None:
        rows = [[f"{e['restitution_cv']:.3g}"] + [
            f"{_f(e[f]['min_collapse_g'])} g, {'collapses' if e[f]['collapses_at_site'] else 'survives'}"
            for f in ("step", "sine")] for e in va["restitution_sensitivity"]]
        rows.insert(0, [f"{pu['restitution_cv']:.3g} (used)"] + [
            f"{_f(pu[f]['min_collapse_g'])} g, "
            f"{'collapses' if pu[f]['collapses_at_site'] else 'survives'}"
            for f in ("step", "sine")])
        el.append(("p", "Restitution sensitivity: the lowest collapse magnitude of each pulse "
                        "family and the verdict at the site PGA, at c_v and c_v +- 0.1."))
        el.append(("table", ["c_v", "step", "sine"], rows))
    ida = va.get("restitution_sensitivity_ida", [])
    if ida:
        el.append(("p", f"Restitution sensitivity of the records: the IDA of the same records "
                        f"rerun at c_v +- 0.1 (clipped to [0, 1]), P(collapse | PGA = "
                        f"{cfg.site_pga_g:.3g} g) from each first-collapse fit."))
        el.append(("table", ["c_v", "P(collapse | site PGA)", "fragility median (g)",
                             "records collapsing"],
                   [[f"{e['restitution_cv']:.3g}" + (" (used)" if e["section"] == "records"
                                                     else ""),
                     _f(e["p_collapse_at_site"]), _f(e["fragility_median_g"]),
                     e["records_collapsing"]] for e in ida]))


def write_markdown(rep, path: Path) -> Path:
    lines: list[str] = []
    for e in elements(rep):
        kind = e[0]
        if kind == "h1":
            lines += [f"# {e[1]}", ""]
        elif kind == "h2":
            lines += [f"## {e[2]}", ""]
        elif kind == "p":
            lines += [e[1], ""]
        elif kind == "verdict":
            lines += [f"> **Verdict:** {e[1]}", ""]
        elif kind == "ul":
            lines += [f"- {x[0] if isinstance(x, tuple) else x}" for x in e[1]] + [""]
        elif kind == "table":
            lines.append("| " + " | ".join(e[1]) + " |")
            lines.append("| " + " | ".join("---" for _ in e[1]) + " |")
            lines += ["| " + " | ".join(md_cell(c) for c in row) + " |" for row in e[2]]
            lines.append("")
        elif kind == "fig":
            lines += [f"![{e[2]}](figures/{e[1]})", "", f"*{e[2]}*", ""]
    path.write_text("\n".join(lines) + "\n")
    return path


def _serious(flag: bool) -> str:
    return "serious" if flag else "note"


def write_html(rep, path: Path) -> Path:
    esc = html.escape
    figures = Path(rep.out) / "figures"
    title = f"archquake assessment: {rep.config.source}"
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             f"<title>{esc(title)}</title>", f"<style>{REPORT_CSS}{_EXTRA_CSS}</style></head><body>"]
    open_section = False
    for e in elements(rep):
        kind = e[0]
        if kind == "h1":
            parts.append(f"<h1>{esc(e[1])}</h1>")
        elif kind == "h2":
            if open_section:
                parts.append("</section>")
            parts.append(f'<section id="{esc(e[1])}"><h2>{esc(e[2])}</h2>')
            open_section = True
        elif kind == "p":
            parts.append(f"<p>{esc(e[1])}</p>")
        elif kind == "verdict":
            cls = e[3] + ("" if e[2] else " inconclusive")
            head, _, rest = e[1].partition(". ")
            parts.append(f'<p class="verdict {cls}"><b>Verdict: {esc(head)}.</b> '
                         f"{esc(rest)}</p>")
        elif kind == "ul":
            parts.append("<ul>" + "".join(
                f'<li class="{_serious(x[1])}">{esc(x[0])}</li>'
                if isinstance(x, tuple) else f"<li>{esc(x)}</li>" for x in e[1]) + "</ul>")
        elif kind == "table":
            parts.append("<table><thead><tr>" + "".join(f"<th>{esc(h)}</th>" for h in e[1])
                         + "</tr></thead><tbody>")
            parts += ["<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>"
                      for row in e[2]]
            parts.append("</tbody></table>")
        elif kind == "fig":
            parts.append(f'<figure><img alt="{esc(e[2])}" src="{image_data_uri(figures / e[1])}">'
                         f"<figcaption>{esc(e[2])}</figcaption></figure>")
    if open_section:
        parts.append("</section>")
    parts.append("</body></html>")
    path.write_text("\n".join(parts) + "\n")
    return path


__all__ = ["elements", "write_html", "write_markdown"]
