"""The assessment's ``[site]`` table and its "Code check" section (NTC 2018 §8.7.1, Circolare
2019 C8.7.1.2: the kinematic analysis of the arch's collapse mechanism).

::

    [site]
    code = "ntc2018"            # or "ec8"
    # NTC 2018: the hazard at the limit states' return periods ...
    hazard = [[50, 0.08, 2.45, 0.27], [475, 0.25, 2.40, 0.30], [975, 0.32, 2.45, 0.32]]
                                # (T_R years, a_g g, F0, T_C* s): points whose return periods
                                # span each limit state's (V_N 50, class II: SLD 50, SLV 475,
                                # SLC 975 years); a limit state outside them is not checked
    nominal_life_years = 50     # V_N (default 50)
    use_class = "II"            # I..IV (default II)
    # ... or the spectrum of one limit state: ag_g, f0, tc_star_s, limit_state
    soil = "B"                  # A..E (required: A is rock)
    topography = "T1"           # T1..T4 (default T1)
    # EN 1998-1 (the spectrum of one limit state): ag_g, spectrum_type, ground (required),
    # importance, limit_state
    limit_state = "SLV"         # with one spectrum: the limit state it is for (default SLV)
    time_history = "far-field"  # also the time-history route (C8.7.1.2.1.9) with 7 records of
                                # this suite (a FEMA P695 set, a folder, a .list file)
    knowledge = "LC1"           # LC1, LC2, LC3: FC 1.35, 1.20, 1.00 (default LC1)
    procedure = "2019"          # or "2009" (default 2019)
    height_m = 0.0              # Z, the arch's springings above the building's foundation
    building_height_m = 12.0    # H (with height_m > 0)
    building_period_s = 0.4     # T1 (with height_m > 0)

The site's demand on the dynamic sections (pulses, records, P(collapse), the DEM check) is
the peak ground acceleration of the SLV spectrum (of the one spectrum, at its limit state):
a_g S_S S_T (EN 1998-1: gamma_I a_gR S), `SiteConfig.site_pga_g`.

Every problem is one line naming the key (``[site] ag_g``), raised as
`StudyFileError`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from archquake.errors import ArchquakeError, StudyFileError

SITE_KEYS = ("code", "hazard", "nominal_life_years", "use_class", "ag_g", "f0", "tc_star_s",
             "soil", "topography", "spectrum_type", "ground", "importance", "limit_state",
             "knowledge", "procedure", "height_m", "building_height_m", "building_period_s",
             "time_history")
#: The limit state whose demand the dynamic sections take (hazard form): the code's
#: life-safety check, the one every existing masonry building must pass (NTC 2018 §8.3).
DYNAMIC_LIMIT_STATE = "SLV"
_NTC_ONLY = ("hazard", "nominal_life_years", "use_class", "f0", "tc_star_s", "soil", "topography")
_EC8_ONLY = ("spectrum_type", "ground", "importance")


@dataclass(frozen=True)
class SiteConfig:
    """A validated ``[site]`` table (see the module docstring); None where not given."""

    code: str
    hazard: tuple[tuple[float, float, float, float], ...] | None
    nominal_life_years: float
    use_class: str
    ag_g: float | None
    f0: float | None
    tc_star_s: float | None
    soil: str
    topography: str
    spectrum_type: int
    ground: str
    importance: float
    knowledge: str
    procedure: str
    height_m: float
    building_height_m: float | None
    building_period_s: float | None
    limit_state: str | None = None
    time_history: str | None = None

    def canonical(self) -> dict:
        d = asdict(self)
        d["hazard"] = None if self.hazard is None else [list(p) for p in self.hazard]
        return d

    def _spectra_and_missing(self) -> tuple[dict, dict]:
        from archquake.codecheck.check import LIMIT_STATES, hazard_spectra
        from archquake.codes.spectra import NTCHazard, ec8_spectrum, ntc2018_spectrum

        if self.hazard is not None:
            return hazard_spectra(NTCHazard(self.hazard),
                                  nominal_life_years=self.nominal_life_years,
                                  use_class=self.use_class, soil=self.soil,
                                  topography=self.topography)
        if self.code == "ec8":
            assert self.ag_g is not None
            spec = ec8_spectrum(ag_g=self.ag_g, spectrum_type=self.spectrum_type,
                                ground=self.ground, importance=self.importance)
        else:
            assert self.ag_g is not None and self.f0 is not None and self.tc_star_s is not None
            spec = ntc2018_spectrum(ag_g=self.ag_g, f0=self.f0, tc_star_s=self.tc_star_s,
                                    soil=self.soil, topography=self.topography)
        state = self.limit_state or DYNAMIC_LIMIT_STATE
        return {state: spec}, {s: f"has no spectrum of its own (the one given is the {state}'s)"
                               for s in LIMIT_STATES if s != state}

    def spectra(self) -> dict:
        """The site's elastic spectra by limit state ('SLD', 'SLV', 'SLC'): only those with a
        hazard of their own (`not_checked` says why the others have none)."""
        return self._spectra_and_missing()[0]

    def not_checked(self) -> dict:
        """The limit states without a hazard of their own, each with a phrase saying why."""
        return self._spectra_and_missing()[1]

    @property
    def dynamic_limit_state(self) -> str:
        """The limit state whose demand the dynamic sections take: the SLV with a hazard, the
        one spectrum's own limit state otherwise."""
        return DYNAMIC_LIMIT_STATE if self.hazard is not None else (
            self.limit_state or DYNAMIC_LIMIT_STATE)

    def site_pga_g(self) -> float:
        """The site's peak ground acceleration at `dynamic_limit_state`, g: a_g S_S S_T
        (NTC 2018 eq. 3.2.2 at T = 0), gamma_I a_gR S (EN 1998-1)."""
        spec = self.spectra()[self.dynamic_limit_state]
        return float(spec.pga / spec.g)

    def describe_pga(self) -> str:
        """Where `site_pga_g` comes from, in words with its factors."""
        spec = self.spectra()[self.dynamic_limit_state]
        g = spec.g
        state = self.dynamic_limit_state
        if self.code == "ec8":
            return (f"gamma_I a_gR S = {self.importance:g} x {self.ag_g:.4g} g x {spec.S:.3g} = "
                    f"{spec.pga / g:.4g} g (EN 1998-1 ground {self.ground}, the {state}'s "
                    "spectrum of [site])")
        p = spec.params
        from archquake.codes.spectra import ntc2018_soil_factors

        s_s = ntc2018_soil_factors(self.soil, ag_g=p["ag_g"], f0=p["f0"],
                                   tc_star_s=p["tc_star_s"])[0]
        where = ("" if self.hazard is None else
                 f", T_R {_return_period(state, self.nominal_life_years, self.use_class):.0f} y")
        return (f"a_g S_S S_T = {spec.ag / g:.4g} g x {s_s:.3g} x {spec.S / s_s:.3g} = "
                f"{spec.pga / g:.4g} g ({state}{where}, soil {self.soil}, {self.topography}, "
                "from [site])")

    def position(self):
        from archquake.codecheck.check import Position

        return Position(self.height_m, self.building_height_m, self.building_period_s)

    def describe(self) -> str:
        """One line: where the spectra come from."""
        if self.code == "ec8":
            return (f"EN 1998-1 type {self.spectrum_type}, ground {self.ground}, a_gR "
                    f"{self.ag_g:g} g, gamma_I {self.importance:g} (the "
                    f"{self.dynamic_limit_state}'s spectrum)")
        if self.hazard is None:
            return (f"NTC 2018, a_g {self.ag_g:g} g, F0 {self.f0:g}, T_C* {self.tc_star_s:g} s, "
                    f"soil {self.soil}, {self.topography} (the {self.dynamic_limit_state}'s "
                    "spectrum)")
        return (f"NTC 2018 hazard ({len(self.hazard)} points), V_N {self.nominal_life_years:g} "
                f"y, use class {self.use_class}, soil {self.soil}, {self.topography}")


def _return_period(state: str, life: float, use: str) -> float:
    from archquake.codes.spectra import return_period_years

    return return_period_years(state, life, use)


def _fail(source: str, key: str, what: str) -> StudyFileError:
    return StudyFileError(f"{source}: [site] {key} {what}")


def _num(source: str, key: str, value: Any, low: float, high: float, unit: str = "",
         low_open: bool = True) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(source, key, f"must be a finite number, got {value!r}")
    v = float(value)
    if (v <= low if low_open else v < low) or v > high:
        lo = "(" if low_open else "["
        raise _fail(source, key, f"must be in {lo}{low:g}, {high:g}]{' ' + unit if unit else ''}, "
                                 f"got {v:g}")
    return v


def _word(source: str, key: str, value: Any, choices: tuple) -> str:
    if not isinstance(value, str) or value.upper() not in [str(c).upper() for c in choices]:
        raise _fail(source, key, f"must be one of {list(choices)}, got {value!r}")
    return next(str(c) for c in choices if str(c).upper() == value.upper())


def parse_site(table: dict, *, source: str = "assessment") -> SiteConfig:
    """Validate a ``[site]`` table (see the module docstring).

    Raises
    ------
    StudyFileError
        One line naming the key.
    """
    from archquake.ranges import (
        BUILDING_PERIOD_RANGE_S,
        EC8_GROUNDS,
        IMPORTANCE_RANGE,
        MECHANISM_HEIGHT_RANGE_M,
        NOMINAL_LIFE_RANGE_YEARS,
        NTC_F0_RANGE,
        NTC_SOILS,
        NTC_TC_STAR_RANGE_S,
        NTC_TOPOGRAPHIES,
        NTC_USE_CLASSES,
        SITE_AG_RANGE_G,
    )

    for key in table:
        if key not in SITE_KEYS:
            raise _fail(source, key, f"is not a known key; expected one of {list(SITE_KEYS)}")
    code = _word(source, "code", table.get("code", "ntc2018"), ("ntc2018", "ec8"))
    wrong = [k for k in (_EC8_ONLY if code == "ntc2018" else _NTC_ONLY) if k in table]
    if wrong:
        raise _fail(source, wrong[0], f"does not apply to code = {code!r}")
    ag = None
    if "ag_g" in table:
        ag = _num(source, "ag_g", table["ag_g"], *SITE_AG_RANGE_G, "g")
    hazard = None
    if "hazard" in table:
        if ag is not None:
            raise _fail(source, "hazard", "and ag_g exclude each other (the hazard gives a_g at "
                                          "each limit state's return period)")
        value = table["hazard"]
        if (not isinstance(value, list) or len(value) < 2
                or not all(isinstance(p, list) and len(p) == 4 for p in value)):
            raise _fail(source, "hazard", "must be two or more [T_R years, a_g g, F0, T_C* s]")
        rows = [[_num(source, "hazard", x, 0.0, math.inf) for x in p] for p in value]
        hazard = tuple((r[0], r[1], r[2], r[3]) for r in rows)
    elif ag is None:
        raise _fail(source, "ag_g", "is missing: give ag_g (g)"
                                    + (" or hazard" if code == "ntc2018" else ""))
    f0 = tc = None
    if code == "ntc2018" and hazard is None:
        for key in ("f0", "tc_star_s"):
            if key not in table:
                raise _fail(source, key, "is missing (read it off the hazard grid)")
        f0 = _num(source, "f0", table["f0"], *NTC_F0_RANGE)
        tc = _num(source, "tc_star_s", table["tc_star_s"], *NTC_TC_STAR_RANGE_S, "s")
    elif code == "ntc2018":
        for key in ("f0", "tc_star_s"):
            if key in table:
                raise _fail(source, key, "and hazard exclude each other")
    height = _num(source, "height_m", table.get("height_m", 0.0), *MECHANISM_HEIGHT_RANGE_M, "m",
                  low_open=False)
    bh = bt = None
    if "building_height_m" in table:
        bh = _num(source, "building_height_m", table["building_height_m"],
                  *MECHANISM_HEIGHT_RANGE_M, "m")
    if "building_period_s" in table:
        bt = _num(source, "building_period_s", table["building_period_s"],
                  *BUILDING_PERIOD_RANGE_S, "s")
    if height > 0.0:
        if bh is None or bt is None:
            raise _fail(source, "height_m", "> 0 needs building_height_m and building_period_s")
        if height > bh:
            raise _fail(source, "height_m", f"must be in [0, {bh:g}] m (building_height_m), "
                                            f"got {height:g}")
    elif bh is not None or bt is not None:
        raise _fail(source, "building_height_m" if bh is not None else "building_period_s",
                    "applies only with height_m > 0")
    stype = table.get("spectrum_type", 1)
    if stype not in (1, 2) or isinstance(stype, bool):
        raise _fail(source, "spectrum_type", f"must be 1 or 2, got {stype!r}")
    procedure = str(table.get("procedure", "2019"))
    if procedure not in ("2019", "2009"):
        raise _fail(source, "procedure", f"must be '2019' or '2009', got {procedure!r}")
    if procedure == "2009" and height > 0.0:
        raise _fail(source, "procedure", "'2009' is implemented at the ground only (height_m 0)")
    if code == "ntc2018" and "soil" not in table:
        raise _fail(source, "soil", "is missing: the subsoil category A..E (NTC 2018 Tab. "
                                    "3.2.II; A is rock, S_S = 1)")
    if code == "ec8" and "ground" not in table:
        raise _fail(source, "ground", "is missing: the ground type A..E (EN 1998-1 Tab. 3.1; "
                                      "A is rock, S = 1)")
    limit_state = None
    if "limit_state" in table:
        if hazard is not None:
            raise _fail(source, "limit_state", "applies to one spectrum (ag_g) only: the hazard "
                                               "gives each limit state its own")
        limit_state = _word(source, "limit_state", table["limit_state"], ("SLD", "SLV", "SLC"))
    site = SiteConfig(
        code=code, hazard=hazard,
        nominal_life_years=_num(source, "nominal_life_years", table.get("nominal_life_years", 50),
                                *NOMINAL_LIFE_RANGE_YEARS, "years", low_open=False),
        use_class=_word(source, "use_class", table.get("use_class", "II"), NTC_USE_CLASSES),
        ag_g=ag, f0=f0, tc_star_s=tc,
        soil=_word(source, "soil", table.get("soil", "A"), NTC_SOILS),
        topography=_word(source, "topography", table.get("topography", "T1"), NTC_TOPOGRAPHIES),
        spectrum_type=int(stype),
        ground=_word(source, "ground", table.get("ground", "A"), EC8_GROUNDS),
        importance=_num(source, "importance", table.get("importance", 1.0), *IMPORTANCE_RANGE,
                        low_open=False),
        knowledge=_word(source, "knowledge", table.get("knowledge", "LC1"),
                        ("LC1", "LC2", "LC3")),
        procedure=procedure, height_m=height, building_height_m=bh, building_period_s=bt,
        limit_state=limit_state)
    if "time_history" in table:
        if procedure != "2019":
            raise _fail(source, "time_history", "applies to procedure '2019' (C8.7.1.2.1.9)")
        # the suite is resolved and read by the assessment file's loader (paths, units)
    try:
        spectra = site.spectra()
    except ArchquakeError as exc:
        raise _fail(source, "hazard" if hazard is not None else "ag_g", f"is invalid: {exc}") from None
    state = site.dynamic_limit_state
    if state not in spectra:
        why = site.not_checked()[state]
        raise _fail(source, "hazard", f"must span the {state}'s return period, which sets the "
                                      f"site's demand on the dynamic sections: the {state} {why}")
    return site


# ----------------------------------------------------------------------------- the section
def section_code_check(ctx):
    """The code check of the arch's collapse mechanism (`archquake.codecheck.kinematic_check`)
    with the ``[site]`` table; its capacity curve against the demand in a figure."""
    import numpy as np

    from archquake.codecheck.check import kinematic_check
    from archquake.codecheck.kinematic import capacity_curve
    from archquake.plotting.codecheck import save_code_check
    from archquake.reproduce.core import Figure, StudyResult

    site: SiteConfig = ctx.config.site
    loads = ctx.config.dead_loads
    if loads is None:
        curve = capacity_curve(ctx.arch)
    else:  # every mass the arch carries (C8.7.1): its fill columns and loads on the extrados
        from archquake.codecheck.kinematic import LoadedFourHingeMechanism

        mechanism = LoadedFourHingeMechanism.of(ctx.arch, loads)
        curve = capacity_curve(mechanism)
    result = kinematic_check(curve, site.spectra(), knowledge=site.knowledge,
                             procedure=site.procedure, position=site.position())
    save_code_check(result, ctx.figures / "codecheck.png")
    data = result.to_dict()
    if site.time_history is not None:
        data["time_history_suite"] = site.time_history
        data["time_history"] = [r.to_dict() for r in _time_history_routes(ctx, result, curve)]
    data["site"] = site.describe()
    data["verdicts"] = [c.verdict() for c in result.governing]
    data["not_checked"] = site.not_checked()
    data["blocks"] = curve.block_table()
    if loads is not None:  # the moving voussoirs, then what each carries: numbered as the arch
        numbers = [int(k) + 1 for k in mechanism.base.voussoirs]
        n = len(numbers)
        data["blocks"] = [dict(row, block=numbers[i % n], part=("voussoir", "carried")[i // n])
                          for i, row in enumerate(data["blocks"][:2 * n])]
    data["arch_mass_kg"] = float(np.sum(ctx.arch.voussoir_masses))
    if loads is not None:
        from archquake.assess.masses import carried_masses

        data["carried_mass_kg"] = carried_masses(ctx.arch, loads)["carried_mass_kg"]
    return StudyResult("codecheck", "Code check", (),
                       (Figure("codecheck.png", "The capacity curve of the equivalent SDOF system "
                               "(C8.7.1.3) against the site's demand spectra at each limit "
                               "state's damping; dots: the displacement capacities."),),
                       (), data)


def _time_history_routes(ctx, result, curve) -> list:
    """The time-history route (`archquake.codecheck.timehistory.time_history_route`) of
    each nonlinear limit state checked, with the ``[site] time_history`` suite's records cut to
    their strong part plus 2 s; quick mode bisects the bracket once, the full mode three
    times."""
    from archquake.codecheck.timehistory import time_history_route
    from archquake.ground.measures import strong_motion_end
    from archquake.ground.suites import load_suite

    site: SiteConfig = ctx.config.site
    assert site.time_history is not None  # called only with one
    suite = list(load_suite(site.time_history, units=ctx.config.units))

    def trim(record):
        return record.truncated(min(float(record.duration), strong_motion_end(record) + 2.0))

    routes = []
    for c in result.governing:
        if c.method != "nonlinear" or c.period_s is None:
            continue
        ctx.say(f"  {c.limit_state} time-history route: 7 records of {site.time_history}, "
                "each level 7 time histories")
        def say(line: str, state: str = c.limit_state) -> None:
            ctx.say(f"  {state} {line}")

        routes.append(time_history_route(
            curve, result.spectra[c.limit_state], suite, c.limit_state, c.capacity_ag_g,
            c.period_s, bisections=1 if ctx.mode.quick else 3, trim=trim, progress=say))
    return routes


def report_code_check(el: list, rep, data: dict) -> None:
    """The report's "Code check" section from the section's data."""
    g = data["capacity_curve"]["g"]
    el.append(("h2", "codecheck", "7. Code check (NTC 2018 §8.7.1, Circolare "
                                  f"{data['procedure']} C8.7.1.2)"))
    pos = data["position"]
    where = ("at the ground" if not pos["height_m"] else
             f"at Z = {pos['height_m']:g} m in a building H = {pos['building_height_m']:g} m, "
             f"T1 = {pos['building_period_s']:g} s (C7.2.11 floor spectrum)")
    el.append(("p", f"Site: {data['site']}; knowledge level {data['knowledge']} (FC = "
                    f"{data['confidence_factor']:.2f}); the arch {where}. The collapse "
                    "mechanism of the static analysis, followed at large displacements, is the "
                    "local mechanism; each limit state is reported as the capacity a_g (the "
                    "least a_g on rock at which the demand reaches the capacity, the site's "
                    "spectral shape held) against the site's a_g."))
    if data.get("vertical") is not None:  # where the code asks for it (docs/code-check.md)
        el.append(("p", f"Vertical component: {data['vertical']['reason']}."))
    blocks = data.get("blocks")
    moving = ("" if not blocks else
              f" (blocks {min(b['block'] for b in blocks)}-{max(b['block'] for b in blocks)}, "
              "the blocks that move" + (" with what they carry" if "carried_mass_kg" in data
                                        else "") + "; "
              f"the arch's total is {data['arch_mass_kg']:.0f} kg"
              + ("" if "carried_mass_kg" not in data else
                 f" of masonry and {data['carried_mass_kg']:.0f} kg carried (fill and loads "
                 "on the extrados, with their blocks)")
              + ", section 1)")
    el.append(("table", ["quantity", "value", "from"], [
        ["activation multiplier alpha0", f"{data['alpha0']:.4f}", "C8.7.1.1 (static analysis)"],
        ["participating mass fraction e*", f"{data['e_star']:.4f}", "C8.7.1.5"],
        ["participating mass M*", f"{data['m_star_kg']:.0f} kg of M = {data['mass_kg']:.0f} kg"
         + moving, "e* M"],
        ["a0* = alpha0 g / (e* FC)", f"{data['a0_star_g']:.4f} g", "C8.7.1.3"],
        ["d0 (capacity curve reaches zero)", f"{data['d0_m']:.4f} m", "C8.7.1.4"],
    ]))
    if blocks:
        sx = sum(b["m_dx_kg_m"] for b in blocks)
        sy = sum(b["m_dy_kg_m"] for b in blocks)
        sxx = sum(b["m_dx2_kg_m2"] for b in blocks)
        mass = sum(b["mass_kg"] for b in blocks)
        el.append(("p", "The moving blocks behind alpha0, e* and M*: each block's mass and the "
                        "virtual displacements of its centroid per unit rotation of the "
                        "mechanism at the onset (delta_x horizontal, delta_y vertical, up "
                        f"positive). alpha0 = sum m delta_y / sum m delta_x = {sy:.1f} / "
                        f"{sx:.1f} = {sy / sx:.4f}; e* = (sum m delta_x)^2 / (M sum m "
                        f"delta_x^2) = {sx:.1f}^2 / ({mass:.0f} x {sxx:.1f}) = "
                        f"{sx * sx / (mass * sxx):.4f}."))
        el.append(("table", ["block", "mass m (kg)", "delta_x (m/rad)", "delta_y (m/rad)",
                             "m delta_x", "m delta_y", "m delta_x^2"],
                   [[f"{b['block']} (carried)" if b.get("part") == "carried" else b["block"],
                     f"{b['mass_kg']:.1f}", f"{b['dx_m_rad']:.4f}",
                     f"{b['dy_m_rad']:.4f}", f"{b['m_dx_kg_m']:.1f}", f"{b['m_dy_kg_m']:.1f}",
                     f"{b['m_dx2_kg_m2']:.1f}"] for b in blocks]
                   + [["sum", f"{mass:.1f}", "", "", f"{sx:.1f}", f"{sy:.1f}", f"{sxx:.1f}"]]))
    rows = []
    for c in data["limit_states"]:
        if "capacity_m" in c:
            cap, dem = f"d {c['capacity_m']:.4f} m", f"{c['demand_m']:.4f} m"
            extra = f"T = {c['period_s']:.3f} s, damping {c['damping']:.0%}"
        else:
            cap, dem = f"a {c['capacity_m_s2'] / g:.4f} g", f"{c['demand_m_s2'] / g:.4f} g"
            extra = ""
        rows.append([c["limit_state"], c["method"] + ("" if c["governing"] else " (info)"), cap,
                     dem, extra, f"{c['capacity_ag_g']:.4f} g", f"{c['demand_ag_g']:.4f} g",
                     f"{c['ratio']:.3f}", "passes" if c["passes"] else "FAILS"])
    el.append(("table", ["limit state", "check", "capacity", "demand at the site", "read at",
                         "capacity a_g", "site a_g", "ratio", ""], rows))
    el.append(("fig", "codecheck.png", rep.sections["codecheck"].figures[0].caption))
    missing = data.get("not_checked", {})
    el.append(("ul", list(data["verdicts"]) + [
        f"{state}: not checked, no hazard of its own: it {why}" for state, why in missing.items()]))
    routes = data.get("time_history")
    if routes is not None:
        el.append(("p", "The time-history route (C8.7.1.2.1.9) beside the static one: for each "
                        "limit state, seven records of "
                        f"{data.get('time_history_suite')} chosen and scaled so that their mean "
                        "spectrum meets the code's band around the site's spectrum, cut to their "
                        "strong part plus 2 s, run on the chain of rigid voussoirs, and scaled "
                        "together with a_g until a record takes the arch beyond d0 or the mean "
                        "peak displacement exceeds d_SLV (d_SLC)."))
        rows = []
        for r in routes:
            rows += [[r["limit_state"], n, f"{f:.3f}"] for n, f in zip(r["records"],
                                                                      r["scale_factors"],
                                                                      strict=True)]
        el.append(("table", ["limit state", "record", "scale factor to the site's spectrum"],
                   rows))
        el.append(("table", ["limit state", "a_g run (g)", "mean peak d (m)",
                             "records beyond d0", "check"],
                   [[r["limit_state"], f"{lv['ag_g']:.4f}",
                     _peak(lv["mean_peak_displacement_m"]), len(lv["records_beyond_d0"]),
                     "passes" if lv["passes"] else "FAILS"]
                    for r in routes for lv in r["capacity"]["levels"]]))
        el.append(("ul", [
            f"{r['limit_state']} (time histories): capacity a_g {r['capacity_ag_g']:.4f} g "
            f"(between {r['capacity']['bracket_g'][0]:.4f} and "
            f"{r['capacity']['bracket_g'][1]:.4f} g), site {r['site_ag_g']:.4f} g, ratio "
            f"{r['ratio']:.3f}: {'passes' if r['passes'] else 'FAILS'}; the static route "
            f"{r['static_capacity_ag_g']:.4f} g"
            + ("" if r["compatible"] else "; the records do NOT meet the code's band")
            for r in routes]))
    formulas = sorted({f"{k}: {v}" for c in data["limit_states"] for k, v in c["formulas"].items()})
    el.append(("p", "Where each number comes from: " + "; ".join(formulas) + "."))


def _peak(x) -> str:
    return "inf (collapse)" if x is None or (isinstance(x, float) and math.isinf(x)) else \
        f"{x:.4f}"


__all__ = ["SITE_KEYS", "SiteConfig", "parse_site", "report_code_check", "section_code_check"]
