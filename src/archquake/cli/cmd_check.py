"""``archquake check``: the code check of the arch's collapse mechanism by kinematic analysis
(NTC 2018 §8.7.1, Circolare 2019 C8.7.1.2.1; the 2009 procedure C8A.4 as an option)."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import (
    add_arch_arguments,
    add_output_arguments,
    arch_from_args,
    comma_numbers,
    describe_arch,
    print_json,
    ranged,
)
from archquake.cli.loads_options import add_loads_arguments, check_loads_on, loads_from_args
from archquake.cli.site_options import add_site_options, spectrum_from_args
from archquake.errors import InvalidParameterError
from archquake.ranges import (
    BUILDING_PERIOD_RANGE_S,
    MECHANISM_HEIGHT_RANGE_M,
    NOMINAL_LIFE_RANGE_YEARS,
    NTC_USE_CLASSES,
)


def _hazard_point(text: str) -> tuple[float, float, float, float]:
    values = comma_numbers(text, 4, "TR,AG,F0,TCSTAR (years, g, -, s)")
    return (values[0], values[1], values[2], values[3])


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "check",
        help="code check of the arch's collapse mechanism (NTC 2018 §8.7.1 kinematic analysis)",
        description=(
            "The kinematic analysis of local mechanisms of NTC 2018 §8.7.1, done as the "
            "Circolare 2019 C8.7.1.2 describes: the activation multiplier alpha0 (the collapse "
            "acceleration of the equivalent static analysis), the participating mass e* M, the "
            "capacity curve of the four-hinge mechanism at large displacements down to d0, and "
            "per limit state the capacity a_g (the least peak ground acceleration on rock the "
            "mechanism fails at, the site's spectral shape held) against the site's a_g. "
            "SLD: activation; SLV: linear (q = 2) and nonlinear (0.4 d0); SLC: nonlinear "
            "(0.6 d0). The site's spectrum is given by the site options and is the spectrum "
            "of one limit state (--limit-state, default SLV); with --hazard each limit state "
            "whose return period the points span gets its own spectrum (--nominal-life, "
            "--use-class). A limit state without a hazard of its own is not checked, and the "
            "output says so. Accelerations in g, lengths in m, periods in s."
        ),
    )
    add_arch_arguments(p)
    add_loads_arguments(p)
    add_site_options(p, required=False)
    grp = p.add_argument_group("code check (NTC 2018 §8.7.1, Circolare 2019 C8.7.1.2)")
    grp.add_argument("--hazard", metavar="TR,AG,F0,TCSTAR", type=_hazard_point, action="append",
                     help="NTC hazard point: return period (years), a_g (g), F0, T_C* (s); "
                          "give points whose return periods span each limit state's (V_N 50 y, "
                          "class II: SLD 50, SLV 475, SLC 975 years, e.g. the grid's 50, 475 "
                          "and 975 years): each is checked at its own return period, one "
                          "outside the points is not checked (with --code ntc2018; replaces "
                          "--ag, --f0, --tc-star)")
    grp.add_argument("--limit-state", type=str.upper, choices=("SLD", "SLV", "SLC"),
                     help="the limit state whose spectrum --ag (--f0, --tc-star) gives "
                          "(default SLV); the others are not checked")
    grp.add_argument("--nominal-life", metavar="YEARS", type=ranged(*NOMINAL_LIFE_RANGE_YEARS,
                                                                    unit="years"),
                     help="nominal life V_N with --hazard, years (default 50)")
    grp.add_argument("--use-class", type=str.upper, choices=NTC_USE_CLASSES,
                     help="use class with --hazard (default II: C_U = 1)")
    grp.add_argument("--knowledge", type=str.upper, choices=("LC1", "LC2", "LC3"), default="LC1",
                     help="knowledge level: confidence factor FC 1.35 (LC1, default), 1.20 (LC2), "
                          "1.00 (LC3)")
    grp.add_argument("--procedure", choices=("2019", "2009"), default="2019",
                     help="Circolare 2019 (default) or the superseded 2009 C8A.4 (at the "
                          "ground only, no SLC)")
    grp.add_argument("--height", metavar="Z", type=ranged(*MECHANISM_HEIGHT_RANGE_M, unit="m"),
                     default=0.0,
                     help="height of the arch's springings above the foundation of the building "
                          "it belongs to, m (default 0: at the ground; > 0 needs "
                          "--building-height and --building-period)")
    grp.add_argument("--building-height", metavar="H",
                     type=ranged(*MECHANISM_HEIGHT_RANGE_M, unit="m", low_open=True),
                     help="the building's height H, m (with --height)")
    grp.add_argument("--building-period", metavar="T1",
                     type=ranged(*BUILDING_PERIOD_RANGE_S, unit="s", low_open=True),
                     help="the building's fundamental period T1, s (with --height; NTC eq. "
                          "7.3.6 or a pushover)")
    grp.add_argument("--vertical-component", choices=("code", "take", "neglect"),
                     default="code",
                     help="the vertical component of the seismic action: 'code' (default) as "
                          "the code asks (NTC 2018 takes it for an arch, a thrusting "
                          "structure; EN 1998-1 does not, an arch not being among the members "
                          "it names), 'take' or 'neglect'; taken, each limit state is checked "
                          "under E_x + 0.3 E_z and 0.3 E_x + E_z at the ground, the weights "
                          "scaled by (1 - k_v)")
    th = p.add_argument_group(
        "time-history route (Circolare 2019 C8.7.1.2.1.9), beside the static one")
    th.add_argument("--time-history", metavar="SUITE",
                    help="also check the SLV and the SLC by time histories of the chain of rigid "
                         "voussoirs: 7 records of SUITE (a FEMA P695 set, e.g. far-field, or a "
                         "folder of .AT2 files) chosen and scaled to the site's spectrum of "
                         "each, then scaled with a_g until no record may take the arch beyond d0 "
                         "and the mean peak displacement stays below d_SLV (d_SLC): the capacity "
                         "a_g of this route. Minutes: each level is 7 time histories")
    th.add_argument("--bisections", metavar="N", type=int, default=2,
                    help="halvings of the capacity's bracket once found (default 2: within "
                         "about 12 %% of itself; each costs one level)")
    th.add_argument("--no-progress", action="store_true",
                    help="no progress lines on stderr for the time-history route")
    add_output_arguments(p)
    p.set_defaults(func=run)


def _position(args: argparse.Namespace):
    from archquake.codecheck.check import Position

    z, h, t1 = args.height, args.building_height, args.building_period
    if z == 0.0:
        if h is not None or t1 is not None:
            given = [n for n, v in (("--building-height", h), ("--building-period", t1)) if v]
            raise InvalidParameterError(
                f"{', '.join(given)} applies only with --height Z > 0 (the arch in a building)")
        return Position()
    missing = [n for n, v in (("--building-height H", h), ("--building-period T1", t1))
               if v is None]
    if missing:
        raise InvalidParameterError(f"--height {z:g} needs {' and '.join(missing)}")
    if z > h:
        raise InvalidParameterError(
            f"--height must be in [0, {h:g}] m (not above --building-height), got {z:g}")
    return Position(z, h, t1)


def site_spectra(args: argparse.Namespace) -> tuple[dict, str, dict]:
    """The spectra by limit state the options describe, a line saying where they come from,
    and the limit states not checked (each with a phrase saying why)."""
    from archquake.codecheck.check import LIMIT_STATES, hazard_spectra
    from archquake.codes.spectra import NTCHazard, return_period_years

    if args.hazard is None:
        for name, value in (("--nominal-life", args.nominal_life), ("--use-class", args.use_class)):
            if value is not None:
                raise InvalidParameterError(f"{name} applies only with --hazard")
        if args.code is None:
            raise InvalidParameterError(
                "the site is needed: --code ntc2018 --ag G --f0 F --tc-star S --soil X, "
                "--code ec8 --ag G --ground X, or --code ntc2018 --soil X --hazard "
                "TR,AG,F0,TCSTAR (points spanning each limit state's return period)")
        _require_soil(args)
        spectrum = spectrum_from_args(args)
        state = args.limit_state or "SLV"
        missing = {s: f"has no spectrum of its own (--ag gives the {state}'s; --hazard gives "
                      "each limit state its own)" for s in LIMIT_STATES if s != state}
        return {state: spectrum}, f"the {state}'s spectrum: {spectrum.label()}", missing
    if args.code != "ntc2018":
        raise InvalidParameterError("--hazard needs --code ntc2018 (the NTC hazard grid)")
    for name in ("ag", "f0", "tc_star", "limit_state"):
        if getattr(args, name) is not None:
            raise InvalidParameterError(
                f"--{name.replace('_', '-')} and --hazard exclude each other (the hazard gives "
                "a_g, F0 and T_C* at each limit state's return period)")
    _require_soil(args)
    hazard = NTCHazard(args.hazard)
    life = 50.0 if args.nominal_life is None else args.nominal_life
    use = args.use_class or "II"
    try:
        spectra, missing = hazard_spectra(hazard, nominal_life_years=life, use_class=use,
                                          soil=args.soil, topography=args.topography or "T1",
                                          component=args.component)
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"--hazard: {exc}") from None
    if not spectra:
        periods = ", ".join(f"{s} {return_period_years(s, life, use):.0f}" for s in LIMIT_STATES)
        raise InvalidParameterError(
            f"--hazard points ({hazard.points[0][0]:g} to {hazard.points[-1][0]:g} years) span "
            f"no limit state's return period ({periods} years): give points on both sides of "
            "at least one")
    lines = [f"{state} T_R {return_period_years(state, life, use):.0f} y a_g "
             f"{spectrum.ag / spectrum.g:.4f} g" for state, spectrum in spectra.items()]
    return spectra, f"NTC hazard, V_N {life:g} y, class {use}: " + "; ".join(lines), missing


def _require_soil(args: argparse.Namespace) -> None:
    """The site's ground must be stated: rock (A) is a finding, not a default."""
    if args.code == "ntc2018" and args.soil is None:
        raise InvalidParameterError("--code ntc2018 needs --soil A|B|C|D|E (the subsoil "
                                    "category, NTC 2018 Tab. 3.2.II; A is rock)")
    if args.code == "ec8" and args.ground is None:
        raise InvalidParameterError("--code ec8 needs --ground A|B|C|D|E (the ground type, "
                                    "EN 1998-1 Tab. 3.1; A is rock)")


def run(args: argparse.Namespace) -> int:
    from archquake.codecheck.check import kinematic_check
    from archquake.codecheck.kinematic import capacity_curve

    position = _position(args)
    spectra, source, missing = site_spectra(args)
    if args.procedure == "2009" and not position.at_ground:
        raise InvalidParameterError(
            "--procedure 2009 is implemented at the ground only (--height 0); use 2019")
    suite = _time_history_suite(args)  # read and checked before anything is computed
    arch = arch_from_args(args)
    loads = loads_from_args(args)
    check_loads_on(arch, loads)
    if loads is None:
        curve = capacity_curve(arch)
    else:
        from archquake.codecheck.kinematic import LoadedFourHingeMechanism

        curve = capacity_curve(LoadedFourHingeMechanism.of(arch, loads))
    vertical = {"code": None, "take": True, "neglect": False}[args.vertical_component]
    try:
        result = kinematic_check(curve, spectra, knowledge=args.knowledge,
                                 procedure=args.procedure, position=position, vertical=vertical)
    except InvalidParameterError as exc:
        if vertical and "vertical component" in str(exc):
            raise InvalidParameterError(f"--vertical-component take: {exc}") from None
        raise
    routes = _time_history(args, result, curve, suite) if suite is not None else []
    if args.plot is not None:
        from archquake.plotting.codecheck import save_code_check

        save_code_check(result, args.plot)
    if args.json:
        out = result.to_dict()
        out["arch"] = arch.describe()
        if loads is not None:
            out["loads"] = loads.to_dict()
        out["site"] = source
        out["not_checked"] = missing
        if args.time_history is not None:
            out["time_history"] = [r.to_dict() for r in routes]
        print_json(out)
    else:
        print(format_result(result, arch, source, missing))
        if args.time_history is not None:
            print(format_time_history(routes, args.time_history))
        if args.plot is not None:
            print(f"figure written to {args.plot}")
    _warn_implausible(args)
    return 0


def _warn_implausible(args: argparse.Namespace) -> None:
    """The site's a_g far outside practice, on stderr once the check has succeeded
    (`archquake.cli.input_warnings`)."""
    from archquake.cli.input_warnings import warn_pga

    top = None if args.hazard is None else max(p[1] for p in args.hazard)
    warn_pga("--ag", args.ag)
    warn_pga("--hazard a_g", top)


def _time_history_suite(args: argparse.Namespace) -> list | None:
    """The records of ``--time-history`` (None without it), read and checked with its options
    before anything is computed (one line naming the option)."""
    from archquake.errors import ArchquakeError
    from archquake.ground.suites import load_suite

    if args.time_history is None:
        return None
    if args.bisections < 0 or args.bisections > 8:
        raise InvalidParameterError(f"--bisections must be in [0, 8], got {args.bisections}")
    if args.procedure != "2019":
        raise InvalidParameterError("--time-history applies to --procedure 2019 (C8.7.1.2.1.9)")
    try:
        return list(load_suite(args.time_history))
    except ArchquakeError as exc:
        raise InvalidParameterError(f"--time-history {args.time_history}: {exc}") from None


def _time_history(args: argparse.Namespace, result, curve, suite: list) -> list:
    """The time-history route of the SLV and SLC checked (`time_history_route`), each
    starting from its static capacity."""
    import sys

    from archquake.codecheck.timehistory import time_history_route
    from archquake.ground.measures import strong_motion_end

    states = [c for c in result.governing if c.method == "nonlinear"]
    if not states:
        raise InvalidParameterError("--time-history checks the SLV and the SLC: the site gives "
                                    "neither (see --limit-state, --hazard)")

    def trim(record):  # the strong part and 2 s after it: the rest adds almost no energy
        return record.truncated(min(float(record.duration), strong_motion_end(record) + 2.0))

    routes = []
    for c in states:
        def say(line: str, state: str = c.limit_state) -> None:
            if not args.no_progress:
                print(f"[check] {state} time histories, {line}", file=sys.stderr, flush=True)

        assert c.period_s is not None
        routes.append(time_history_route(curve, result.spectra[c.limit_state], suite,
                                         c.limit_state, c.capacity_ag_g, c.period_s,
                                         bisections=args.bisections, trim=trim,
                                         progress=say))
    return routes


def format_time_history(routes: list, suite: str) -> str:
    """The time-history route as text: per limit state its records and their scale factors,
    and the capacity a_g beside the static route's."""
    lines = [f"time-history route (C8.7.1.2.1.9), records of {suite} on the chain of rigid "
             "voussoirs:"]
    for r in routes:
        lines.append(f"  {r.limit_state}: {len(r.records)} records scaled to the site's "
                     f"spectrum over {r.periods_s[0]:g}-{r.periods_s[1]:.3g} s"
                     + ("" if r.compatible else " (NOT compatible with the code's band)") + ": "
                     + ", ".join(f"{n} x {f:.3g}" for n, f in zip(r.records, r.scale_factors,
                                                                   strict=True)))
        for level, ag in zip(r.capacity.levels, r.capacity.ag_g, strict=True):
            lines.append(f"    a_g {ag:.4f} g: {level.verdict()}")
        lines.append("  " + r.verdict())
    return "\n".join(lines)


def format_result(result, arch, source: str, missing: dict | None = None) -> str:
    """The check as text: the mechanism's numbers, then one line per limit state (and one per
    limit state not checked, ``missing``: why)."""
    curve = result.curve
    g = curve.g
    pos = result.position
    where = ("at the ground" if pos.at_ground else
             f"at Z = {pos.height_m:g} m in a building H = {pos.building_height_m:g} m, "
             f"T1 = {pos.building_period_s:g} s (C7.2.11 floor spectrum)")
    lines = [
        f"arch: {describe_arch(arch)}",
        f"site: {source}",
        f"procedure: Circolare {result.procedure.value}, {result.knowledge.value} "
        f"(FC = {result.confidence_factor:.2f}), {where}",
        f"mechanism: alpha0 = {curve.alpha0:.4f} (C8.7.1.1), e* = {curve.e_star:.4f} "
        f"(C8.7.1.5), M* = {curve.m_star_kg:.5g} kg of {curve.mass_kg:.5g} kg",
        f"  a0* = alpha0 g / (e* FC) = {result.a0_star / g:.4f} g "
        f"({result.a0_star:.4f} m/s^2, C8.7.1.3)",
        f"  d0 = {curve.d0_m:.4f} m (alpha = 0 at rotation {curve.phi0_rad:.4f} rad; control "
        "point: centre of mass of the moving voussoirs, C8.7.1.4)",
    ]
    lines.append(f"vertical component: {result.vertical.reason}")
    governing = result.governing
    for c in result.checks:
        lines.append(c.verdict() + ("" if c in governing else "  (not governing)"))
        if c.quantity == "displacement":
            lines.append(f"    d capacity {c.capacity:.4f} m, demand at the site {c.demand:.4f} m "
                         f"at T = {c.period_s:.3f} s, damping {c.damping:.0%}")
        else:
            lines.append(f"    a capacity {c.capacity / g:.4f} g, demand at the site "
                         f"{c.demand / g:.4f} g")
    for state, why in (missing or {}).items():
        lines.append(f"{state}: not checked: it {why}")
    worst = min(governing, key=lambda c: c.ratio)
    ratio = "inf" if math.isinf(worst.ratio) else f"{worst.ratio:.3f}"
    checked = ", ".join(c.limit_state for c in governing)
    lines.append(f"verdict: {'passes' if result.passes else 'FAILS'} "
                 f"(least ratio {ratio}, {worst.limit_state} {worst.method}; "
                 f"{'checked: ' + checked if missing else 'every limit state checked'})")
    return "\n".join(lines)
