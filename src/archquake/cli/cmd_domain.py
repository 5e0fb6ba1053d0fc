"""``archquake domain``: the failure domain of an arch for a pulse family: the rigid chain's by
default, or the distinct-element model's (``--model dem``), each beside the four-link
mechanism's (Figures 6, 11); ``--model fourlink`` the four-link domain alone (paper Figures 5,
11)."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import (
    add_arch_arguments,
    add_impact_arguments,
    add_model_argument,
    add_output_arguments,
    arch_from_args,
    impact_from_args,
    impact_line,
    model_from_args,
    output_file,
    parse_durations,
    print_json,
    ranged,
    ranged_whole,
    refuse_unless,
)
from archquake.errors import InvalidParameterError
from archquake.ranges import (
    CSV_SUFFIXES,
    DEM_T_END_MAX_S,
    MAGNITUDE_RANGE_G,
    PRECISION_RANGE_G,
    SCAN_RANGE,
    WORKERS_RANGE,
)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "domain",
        help="failure domain: pulse magnitudes (g) and durations (s) that collapse the arch",
        description=(
            "Failure domain of the arch for a pulse family (paper Figures 5 and 11): for each "
            "duration (t_p of the step impulse, period T of the sine pulse, in s) the no-hinging "
            "limit, the smallest magnitude that collapses the arch in the 1st half cycle and the "
            "smallest that collapses it at all, in g, to --precision; magnitude bands where a "
            "larger pulse survives although a smaller one collapses are reported."
        ),
    )
    add_arch_arguments(p)
    p.add_argument("--pulse", choices=("step", "sine"), default="step",
                   help="pulse family: 'step' (Oppenheim's step impulse, duration t_p) or 'sine' "
                        "(one sine cycle, duration = period T); default step")
    p.add_argument("--durations", type=parse_durations, default=None,
                   metavar="START:STOP:COUNT",
                   help="durations in s, evenly spaced (default 0.1:0.8:4; with --model "
                        "fourlink 0.05:1.5:40), or one duration")
    p.add_argument("--max-magnitude", type=ranged(*MAGNITUDE_RANGE_G, "g", low_open=True),
                   default=None, metavar="G",
                   help="ceiling of the magnitude scan, g (above the no-hinging limit, at most "
                        f"{MAGNITUDE_RANGE_G[1]:g}; default 2; with --model fourlink 5); "
                        "boundaries above it are null")
    p.add_argument("--precision", type=ranged(*PRECISION_RANGE_G, "g"), default=None, metavar="G",
                   help=f"width of the final brackets, g ({PRECISION_RANGE_G[0]:g} to "
                        f"{PRECISION_RANGE_G[1]:g}; default 0.01; with --model fourlink 0.001)")
    p.add_argument("--scan", type=ranged_whole(*SCAN_RANGE), default=None, metavar="N",
                   help="magnitudes in the coarse scan (default 8, the fine scan 1/2 of it; with "
                        "--model fourlink 60 and 2/3)")
    add_model_argument(p, extra="rigid and dem search the block model's domain (its "
                                "1st-half-cycle boundary on the arch cut at the four-link "
                                "hinges, its governing boundary with every voussoir a block) "
                                "beside the four-link one, one time history per point (~10-100 ms "
                                "each for rigid, ~1-2 min per duration on 2 cores for dem); fourlink "
                                "alone is its compiled batch (paper Figures 5, 11)")
    p.add_argument("--workers", type=ranged_whole(*WORKERS_RANGE), default=None, metavar="N",
                   help="with --model rigid or dem: worker processes for the block "
                        "model's runs (default: all cores)")
    add_impact_arguments(p)
    from archquake.cli.loads_options import add_loads_arguments

    add_loads_arguments(p)
    add_output_arguments(p)
    p.add_argument("--csv", type=output_file(*CSV_SUFFIXES), metavar="FILE",
                   help="write the domain as CSV to FILE (.csv)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from archquake import models
    from archquake.domains import DomainSettings, failure_domain

    model = model_from_args(args)
    arch = arch_from_args(args)
    blocks = models.spec(model).blocks
    refuse_unless({"--workers": args.workers}, blocks,
                  "with --model rigid or dem (the four-link domain runs in this process); "
                  "leave it out")
    impact = impact_from_args(args)
    from archquake.cli.loads_options import dynamic_loads_from_args

    loads = dynamic_loads_from_args(args, arch, model, fourlink=True)
    if blocks:
        return _run_dem(args, arch, model.value, loads)
    if args.durations is None:
        args.durations = parse_durations("0.05:1.5:40")
    args.scan = 60 if args.scan is None else args.scan
    args.precision = 1e-3 if args.precision is None else args.precision
    args.max_magnitude = 5.0 if args.max_magnitude is None else args.max_magnitude
    _check_search(arch, args.scan, args.precision, args.max_magnitude, loads)
    settings = DomainSettings(max_magnitude_g=args.max_magnitude, coarse_points=args.scan,
                              fine_points=max(2 * args.scan // 3, 1), precision_g=args.precision)
    subject = arch
    if loads is not None:  # the links carry the loads, on the loaded arch's hinges
        from archquake.mechanism import PreparedMechanism

        subject = PreparedMechanism.build(arch, impact["impact"], loads=loads)
    dom = failure_domain(subject, args.pulse, args.durations, settings=settings, **impact,
                         model="fourlink")
    if args.csv:
        dom.write_csv(args.csv)
    if args.plot:
        from archquake.plotting.domains import save_domain

        save_domain(dom, args.plot)
    if args.json:
        extra = {}
        if loads is not None:
            from archquake.mechanism.prepared import link_masses

            extra = {"loads": loads.to_dict(), "masses": link_masses(subject.mechanism)}
        print_json({"model": model.value, **dom.summary(), "rows": dom.to_dict(), **extra})
        return 0
    sym = dom.family.duration_symbol
    print(f"failure domain, {dom.family.value} pulse; arch R = {arch.radius:g} m, "
          f"t/R = {arch.thickness_ratio:.3f}, embrace {math.degrees(arch.embrace):g} deg, "
          f"{arch.voussoirs} voussoirs; c_v = {dom.restitution_cv:.4f}"
          + (" (prescribed)" if dom.restitution_prescribed else "")
          + ("  (> 1: impact model gains energy)" if dom.energy_gain else ""))
    print(impact_line(dom.impact_law, dom.impact_validity, dom.impact_described,
                      dom.restitution_prescribed))
    if not dom.impact_described:
        print("  only lambda and the 1st-half-cycle boundary are certain; a collapse after an "
              "impact is the law's computation, marked '?' (indeterminate)")
    print(f"{sym + ' [s]':>9} {'no hinging':>11} {'1st half':>9} {'collapse':>9} {'in half':>7}  (g)")

    def fmt(x: float) -> str:
        return f"{x:9.3f}" if math.isfinite(x) else f"{'-':>9}"

    for i, d in enumerate(dom.durations):
        h = int(dom.collapse_half_cycle[i])
        doubt = "?" if dom.collapse_verdict[i] == "indeterminate" else ""
        print(f"{d:9.4g} {dom.no_hinging_g[i]:11.3f} {fmt(dom.first_half_cycle_g[i])} "
              f"{fmt(dom.collapse_g[i])} {h if h else '-':>7}{doubt}")
    if dom.non_monotonic_bands:
        print("non-monotonic bands (survives although a smaller magnitude collapses):")
        for b in dom.non_monotonic_bands:
            print(f"  {sym} = {b.duration:.4g} s: {b.criterion} absent for "
                  f"{b.lower_g:.3f} to {b.upper_g:.3f} g" + (" (to the ceiling)" if b.upper_open else ""))
    else:
        print("non-monotonic bands: none found at this scan resolution")
    if loads is not None:
        from archquake.cli.loads_options import print_loads
        from archquake.mechanism.prepared import link_masses

        print_loads({"masses": link_masses(subject.mechanism)})
    for f in (args.csv, args.plot):
        if f:
            print(f"wrote {f}")
    return 0


def _check_search(arch, scan: int, precision: float, ceiling: float, loads=None) -> None:
    """The magnitude search's options, in g, against each other and the arch's onset (with
    ``loads``, the loaded arch's)."""
    from archquake.cli.common import check_range, check_whole
    from archquake.mechanism import PreparedMechanism

    check_whole("--scan", scan, *SCAN_RANGE)
    check_range("--precision", precision, *PRECISION_RANGE_G, "g")
    check_range("--max-magnitude", ceiling, *MAGNITUDE_RANGE_G, "g", low_open=True)
    if loads is None:
        lam = PreparedMechanism.build(arch).collapse_acceleration_g
    else:
        from archquake.limit.loaded import loaded_collapse, seismic_case

        lam = loaded_collapse(seismic_case(arch, loads)).multiplier
    if not ceiling > lam:
        raise InvalidParameterError(
            f"--max-magnitude must exceed the arch's no-hinging limit {lam:.4f} g, got {ceiling:g}")
    if precision >= ceiling:
        raise InvalidParameterError(
            f"--precision must be below --max-magnitude ({ceiling:g} g), got {precision:g} g")


def _run_dem(args: argparse.Namespace, arch, model: str = "dem", loads=None) -> int:
    """``--model rigid`` (the default) or ``dem``: the block model's failure domain beside the
    four-link one (paper Figures 6 and 11), through `archquake.compare.compare_domains`,
    searched the same way on the same assemblies for either model."""
    import csv

    from archquake.compare import DEM_DOMAIN_SETTINGS, compare_domains
    from archquake.domains import DomainSettings

    durations = args.durations if args.durations is not None else parse_durations("0.1:0.8:4")
    scan = DEM_DOMAIN_SETTINGS.coarse_points if args.scan is None else args.scan
    precision = DEM_DOMAIN_SETTINGS.precision_g if args.precision is None else args.precision
    ceiling = DEM_DOMAIN_SETTINGS.max_magnitude_g if args.max_magnitude is None else args.max_magnitude
    _check_search(arch, scan, precision, ceiling, loads)
    beside = loads is None or _symmetric_with(arch, loads)
    if not beside and args.plot:
        raise InvalidParameterError("--plot draws the block model beside the four-link model, "
                                    "which needs loads symmetric about the crown: leave it out "
                                    "(--csv, --json)")
    flag = f"--model {model}"
    from archquake import models

    who = models.spec(model).short
    lobes = 3.0 if args.pulse == "step" else 1.0  # a step impulse lasts 3 t_p, a sine pulse T
    if lobes * float(max(durations)) > DEM_T_END_MAX_S:
        raise InvalidParameterError(
            f"--durations up to {float(max(durations)):g} s make {who} runs longer than "
            f"{DEM_T_END_MAX_S:g} s of simulated time; with {flag} keep them <= "
            f"{DEM_T_END_MAX_S / lobes:g} s")
    settings = DomainSettings(max_magnitude_g=ceiling, coarse_points=scan,
                              scan_reference_g=DEM_DOMAIN_SETTINGS.scan_reference_g,
                              fine_points=max(scan // 2, 1), precision_g=precision, early=False)
    workers = args.workers
    if workers is not None:  # never more processes than cores or runs (a line says so)
        import sys

        from archquake.parallel import cap_workers

        workers, note = cap_workers(workers, 2 * len(durations))
        if note is not None:
            print(f"archquake: --workers: {note}", file=sys.stderr)
    if not beside:
        return _loaded_domain(args, arch, model, loads, durations, settings, workers)
    comp = compare_domains(arch, args.pulse, durations, settings=settings, workers=workers,
                           model=model, loads=loads)
    rows = comp.rows()
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["boundary", "assembly", "duration_s", "fourlink_g", f"{model}_g",
                        "relative"])
            for r in rows:
                w.writerow([r["boundary"], r["assembly"], f"{r['duration_s']:.6g}",
                            *("" if r[k] is None else f"{r[k]:.4f}"
                              for k in ("fourlink_g", "block_g", "relative"))])
    if args.plot:
        from archquake.plotting.compare import domain_comparison_figure

        domain_comparison_figure([comp], args.plot)
    assembly = None
    if loads is not None:
        from archquake.blocks.assembly import VOUSSOIRS, dem_assembly

        assembly = dem_assembly(arch, VOUSSOIRS, loads=loads).to_dict()
    if args.json:
        extra = {} if assembly is None else {"loads": loads.to_dict(), "assembly": assembly}
        print_json({"model": model, **comp.to_dict(), **extra})
        return 0
    an = comp.fourlink
    sym = an.family.duration_symbol
    print(f"failure domain, {an.family.value} pulse, "
          + models.spec(model).kind + " beside the four-link "
          "mechanism; arch "
          f"R = {arch.radius:g} m, t/R = {arch.thickness_ratio:.3f}, embrace "
          f"{math.degrees(arch.embrace):g} deg, {arch.voussoirs} voussoirs")
    print(f"{who} search: {scan} + {settings.fine_points} magnitudes, brackets {precision:g} g; "
          f"four-link brackets {an.settings.precision_g:g} g; no hinging below "
          f"{an.no_hinging_g[0]:.3f} g")
    print(f"{sym + ' [s]':>9} {'1st: 4-link':>11} {who + ' hinges':>12} {'gov.: 4-link':>12} "
          f"{who + ' vouss.':>12}  (g)")

    def fmt(x, width):
        return f"{x:{width}.3f}" if x is not None and math.isfinite(x) else f"{'-':>{width}}"

    for i, d in enumerate(an.durations):
        f = comp.first.boundary_g[i] if comp.first else None
        g = comp.governing.boundary_g[i] if comp.governing else None
        print(f"{d:9.4g} {fmt(an.first_half_cycle_g[i], 11)} {fmt(f, 12)} "
              f"{fmt(an.collapse_g[i], 12)} {fmt(g, 12)}")
    for dd in (comp.first, comp.governing):
        if dd is not None:
            print(f"{who} {dd.assembly}: {dd.runs} runs in {dd.seconds:.0f} s on {dd.workers} worker(s)")
    bands = [b for dd in (comp.first, comp.governing) if dd for b in dd.domain.non_monotonic_bands]
    if bands:
        print(f"{who} non-monotonic bands: " + "; ".join(
            f"{sym} = {b.duration:.3g} s {b.criterion} {b.lower_g:.3f}-{b.upper_g:.3f} g" for b in bands))
    if assembly is not None:
        from archquake.cli.loads_options import print_loads

        print_loads(assembly)
    for f in (args.csv, args.plot):
        if f:
            print(f"wrote {f}")
    return 0


def _symmetric_with(arch, loads) -> bool:
    """True if ``arch`` carrying ``loads`` is its own mirror image (what the four-link model's
    impacts need)."""
    from archquake.geometry.carrying import CarryingChain

    return bool(arch.symmetric and CarryingChain(arch, loads).symmetric)


def _loaded_domain(args: argparse.Namespace, arch, model: str, loads, durations, settings,
                   workers) -> int:
    """The block model's domain of the arch carrying loads that break its symmetry: every
    voussoir a block with what it carries, searched from the loaded arch's lambda (the
    four-link model needs symmetric loads, so there is nothing beside it)."""
    import csv

    from archquake import models
    from archquake.blocks.assembly import VOUSSOIRS, dem_assembly
    from archquake.compare import dem_failure_domain

    who = models.spec(model).short
    dd = dem_failure_domain(arch, args.pulse, durations, assembly=VOUSSOIRS, settings=settings,
                            workers=workers, model=model, loads=loads)
    dom = dd.domain
    assembly = dem_assembly(arch, VOUSSOIRS, loads=loads).to_dict()
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["duration_s", "no_hinging_g", "first_half_cycle_g", "collapse_g"])
            for i, d in enumerate(dom.durations):
                w.writerow([f"{d:.6g}", *("" if not math.isfinite(x) else f"{x:.4f}" for x in (
                    dom.no_hinging_g[i], dom.first_half_cycle_g[i], dom.collapse_g[i]))])
    if args.json:
        print_json({"model": model, "loads": loads.to_dict(), "assembly": assembly,
                    "governing": dd.to_dict()})
        return 0
    sym = dom.family.duration_symbol
    print(f"failure domain, {dom.family.value} pulse, "
          + models.spec(model).kind
          + f" with every voussoir a block carrying its loads; arch R = {arch.radius:g} m, "
          f"t/R = {arch.thickness_ratio:.3f}, embrace {math.degrees(arch.embrace):g} deg, "
          f"{arch.voussoirs} voussoirs")
    print(f"{who} search: {settings.coarse_points} + {settings.fine_points} magnitudes, "
          f"brackets {settings.precision_g:g} g; no hinging below {dom.no_hinging_g[0]:.3f} g "
          "(the static analysis with the loads); the four-link model needs loads symmetric "
          "about the crown")
    print(f"{sym + ' [s]':>9} {'1st half cycle':>15} {'collapse':>10}  (g)")

    def fmt(x, width):
        return f"{x:{width}.3f}" if math.isfinite(x) else f"{'-':>{width}}"

    for i, d in enumerate(dom.durations):
        print(f"{d:9.4g} {fmt(dom.first_half_cycle_g[i], 15)} {fmt(dom.collapse_g[i], 10)}")
    print(f"{who} voussoirs: {dd.runs} runs in {dd.seconds:.0f} s on {dd.workers} worker(s)")
    from archquake.cli.loads_options import print_loads

    print_loads(assembly)
    if args.csv:
        print(f"wrote {args.csv}")
    return 0
