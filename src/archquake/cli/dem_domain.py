"""``archquake domain --model dem``: the distinct-element failure domain beside the analytical one
(paper Figures 6 and 11), through :func:`archquake.compare.compare_domains`."""

from __future__ import annotations

import argparse
import csv
import math

from archquake.errors import InvalidParameterError


def run_dem_domain(args: argparse.Namespace, arch) -> int:
    from archquake.cli.cmd_domain import parse_durations
    from archquake.cli.common import print_json
    from archquake.compare import DEM_DOMAIN_SETTINGS, compare_domains
    from archquake.domains import DomainSettings

    durations = args.durations if args.durations is not None else parse_durations("0.1:0.8:4")
    scan = DEM_DOMAIN_SETTINGS.coarse_points if args.scan is None else args.scan
    precision = DEM_DOMAIN_SETTINGS.precision_g if args.precision is None else args.precision
    ceiling = DEM_DOMAIN_SETTINGS.max_magnitude_g if args.max_magnitude is None else args.max_magnitude
    if scan < 2:
        raise InvalidParameterError(f"--scan must be >= 2, got {scan}")
    if precision <= 0:
        raise InvalidParameterError(f"--precision must be > 0 g, got {precision:g}")
    if ceiling <= 0:
        raise InvalidParameterError(f"--max-magnitude must be > 0 g, got {ceiling:g}")
    if args.workers is not None and args.workers < 1:
        raise InvalidParameterError(f"--workers must be a whole number >= 1, got {args.workers}")
    settings = DomainSettings(max_magnitude_g=ceiling, coarse_points=scan,
                              fine_points=max(scan // 2, 1), precision_g=precision, early=False)
    comp = compare_domains(arch, args.pulse, durations, settings=settings, workers=args.workers)
    rows = comp.rows()
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["boundary", "assembly", "duration_s", "analytical_g", "dem_g", "relative"])
            for r in rows:
                w.writerow([r["boundary"], r["assembly"], f"{r['duration_s']:.6g}",
                            *("" if r[k] is None else f"{r[k]:.4f}"
                              for k in ("analytical_g", "dem_g", "relative"))])
    if args.plot:
        from archquake.plotting.compare import domain_comparison_figure

        domain_comparison_figure([comp], args.plot)
    if args.json:
        print_json(comp.to_dict())
        return 0
    an = comp.analytical
    sym = an.family.duration_symbol
    print(f"failure domain, {an.family.value} pulse, analytical and distinct-element; arch "
          f"R = {arch.radius:g} m, t/R = {arch.thickness_ratio:.3f}, embrace "
          f"{math.degrees(arch.embrace):g} deg, {arch.voussoirs} voussoirs")
    print(f"DEM search: {scan} + {settings.fine_points} magnitudes, brackets {precision:g} g; "
          f"analytical brackets {an.settings.precision_g:g} g; no hinging below "
          f"{an.no_hinging_g[0]:.3f} g")
    print(f"{sym + ' [s]':>9} {'1st: anal.':>10} {'DEM hinges':>10} {'gov.: anal.':>11} "
          f"{'DEM vouss.':>10}  (g)")

    def fmt(x, width):
        return f"{x:{width}.3f}" if x is not None and math.isfinite(x) else f"{'-':>{width}}"

    for i, d in enumerate(an.durations):
        f = comp.first.boundary_g[i] if comp.first else None
        g = comp.governing.boundary_g[i] if comp.governing else None
        print(f"{d:9.4g} {fmt(an.first_half_cycle_g[i], 10)} {fmt(f, 10)} "
              f"{fmt(an.collapse_g[i], 11)} {fmt(g, 10)}")
    for dd in (comp.first, comp.governing):
        if dd is not None:
            print(f"DEM {dd.assembly}: {dd.runs} runs in {dd.seconds:.0f} s on {dd.workers} worker(s)")
    bands = [b for dd in (comp.first, comp.governing) if dd for b in dd.domain.non_monotonic_bands]
    if bands:
        print("DEM non-monotonic bands: " + "; ".join(
            f"{sym} = {b.duration:.3g} s {b.criterion} {b.lower_g:.3f}-{b.upper_g:.3f} g" for b in bands))
    for f in (args.csv, args.plot):
        if f:
            print(f"wrote {f}")
    return 0


__all__ = ["run_dem_domain"]
