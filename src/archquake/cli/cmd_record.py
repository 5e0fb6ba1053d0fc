"""``archquake record FILE``: read an accelerogram, summarise it and print its intensity
measures before a run."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import (
    add_output_arguments,
    number,
    path_argument,
    periods_list,
    print_json,
    record_from_args,
    refuse_unless,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.measures import DEFAULT_DAMPING, intensity_measures
from archquake.ground.periods import DEFAULT_PERIOD_GRID_S, period_grid
from archquake.ground.records import UNITS, baseline_corrected, resampled
from archquake.ground.response_spectra import record_spectra
from archquake.ranges import (
    RECORD_DT_RANGE_S,
    RECORD_DURATION_MAX_S,
    RECORD_FILE_MAX_BYTES,
    SCALE_RANGE,
)

#: Sa periods printed unless --periods says otherwise, s.
DEFAULT_PERIODS = (0.2, 0.5, 1.0, 2.0)


def add_record_file_arguments(p: argparse.ArgumentParser) -> None:
    """--units, --dt: how to read CSV/text files (shared with ``archquake records``)."""
    p.add_argument("--units", choices=UNITS, default=None,
                   help="units of a CSV/text file's acceleration column: g, m/s2 or cm/s2 (= gal); "
                        "required with CSV/text files (they do not say); .AT2 files are always "
                        "in g")
    p.add_argument("--dt", type=number, metavar="S",
                   help=f"time step of a one-column file, s ({RECORD_DT_RANGE_S[0]:g} to "
                        f"{RECORD_DT_RANGE_S[1]:g}); a two-column file (time, acceleration) "
                        "gives its own")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "record",
        help="check an accelerogram file (.AT2 or CSV): points, dt, PGA, PGV, Arias, Sa(T), ...",
        description=(
            "Read a recorded ground acceleration and print what archquake understood (name, "
            "points, time step, duration) and its intensity measures: PGA (g), PGV (m/s), "
            "PGD (m), Arias intensity (m/s), CAV (m/s), significant duration D5-95 (s), mean "
            "period Tm (s) and the 5 %-damped pseudo-spectral acceleration Sa(T) (g). "
            "Positive values are ground accelerations towards +x. A record may last at most "
            f"{RECORD_DURATION_MAX_S:,.0f} s, with a time step from {RECORD_DT_RANGE_S[0]:g} to "
            f"{RECORD_DT_RANGE_S[1]:g} s, in a regular file of at most "
            f"{RECORD_FILE_MAX_BYTES / 1e6:.0f} MB."
        ),
    )
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="PEER .AT2 (values in g), .csv/.txt with two columns time (s), "
                        "acceleration, or one column of accelerations with --dt")
    add_record_file_arguments(p)
    p.add_argument("--record-vertical", type=path_argument, metavar="FILE", default=None,
                   help="the record's vertical component (same formats, --units, --dt and "
                        "--scale; positive upward): its intensity measures and V/H are "
                        "printed too")
    p.add_argument("--scale", type=number, metavar="S",
                   help=f"factor applied to every value ({SCALE_RANGE[0]:g} < S <= "
                        f"{SCALE_RANGE[1]:g}; default 1)")
    p.add_argument("--baseline", type=int, metavar="ORDER", default=None,
                   help="remove a polynomial baseline of this degree (0 to 5) from the "
                        "acceleration, fitted to the velocity (default: none)")
    p.add_argument("--resample", type=number, metavar="DT",
                   help="resample to this time step, s (> 0; anti-aliased polyphase filter)")
    p.add_argument("--periods", type=periods_list, metavar="T,T,...",
                   help="periods of Sa(T), s: comma-separated or a grid START:STOP:STEP (default "
                        f"{','.join(f'{t:g}' for t in DEFAULT_PERIODS)}; with --spectrum "
                        f"{':'.join(f'{t:g}' for t in DEFAULT_PERIOD_GRID_S)})")
    p.add_argument("--spectrum", action="store_true",
                   help="print the 5 %%-damped response spectrum Sa (g) over --periods as a table "
                        "(and draw it with --plot)")
    add_output_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    g = STANDARD_GRAVITY
    refuse_unless({"--plot": args.plot}, args.spectrum, "with --spectrum")
    if args.periods is None:
        args.periods = period_grid(*DEFAULT_PERIOD_GRID_S) if args.spectrum else DEFAULT_PERIODS
    record = _processed(record_from_args(args.file, args.units, args.scale, g=g, dt=args.dt),
                        args)
    if args.spectrum:
        refuse_unless({"--record-vertical": args.record_vertical}, False, "without --spectrum")
        return _spectrum(record, args, g)
    ims = intensity_measures(record, periods=args.periods, g=g)
    vertical = None
    if args.record_vertical is not None:
        vertical = vertical_summary(_processed(record_from_args(
            args.record_vertical, args.units, args.scale, g=g, dt=args.dt), args),
            ims, args.periods, g)
    summary = record.to_dict(g=g)
    is_text = args.file.suffix.lower() in (".csv", ".txt")
    summary["units_in_file"] = args.units if is_text else "g"  # a text file needs --units
    summary["g_m_s2"] = g
    summary["baseline_order"] = args.baseline
    summary["intensity_measures"] = ims.to_dict()
    if vertical is not None:
        summary["vertical"] = vertical
    if args.json:
        print_json(summary)
        return 0
    signed = float(record.accelerations[int(round(record.time_of_peak / record.dt))])
    units_note = summary["units_in_file"]
    lines = [
        f"record     {record.name}",
        f"file       {record.source}",
        f"units      {units_note}",
        f"points     {record.points}",
        f"dt         {record.dt:g} s",
        f"duration   {record.duration:g} s",
        f"PGA        {record.peak / g:.4g} g = {record.peak:.4g} m/s^2 at t = "
        f"{record.time_of_peak:g} s (towards {'+x' if signed > 0 else '-x'})",
    ]
    if record.scale != 1.0:
        lines.append(f"scale      {record.scale:g} (applied to the file's values)")
    if args.baseline is not None:
        lines.append(f"baseline   polynomial of degree {args.baseline} removed")
    if args.resample is not None:
        lines.append(f"resampled  to dt = {record.dt:g} s")
    lines += [
        f"PGV        {ims.pgv_m_s:.4g} m/s",
        f"PGD        {ims.pgd_m:.4g} m",
        f"Arias      {ims.arias_m_s:.4g} m/s",
        f"CAV        {ims.cav_m_s:.4g} m/s",
        f"D5-95      {ims.d5_95_s:.4g} s",
        f"Tm         {ims.mean_period_s:.4g} s (mean period, 0.25-20 Hz)"
        if math.isfinite(ims.mean_period_s) else
        "Tm         undefined (no motion between 0.25 and 20 Hz)",
    ]
    for period, sa in ims.sa_g.items():
        lines.append(f"Sa({period:g} s) {' ' * max(0, 4 - len(f'{period:g}'))}{sa:.4g} g "
                     f"({100 * DEFAULT_DAMPING:g} % damping)")
    if vertical is not None:
        v = vertical["intensity_measures"]
        lines += [
            f"vertical   {vertical['name']} ({vertical['points']} points, dt "
            f"{vertical['dt_s']:g} s), positive upward",
            f"  PGA      {v['pga_g']:.4g} g (V/H {vertical['v_over_h']['pga']:.3g})",
            f"  PGV      {v['pgv_m_s']:.4g} m/s",
            f"  Arias    {v['arias_m_s']:.4g} m/s",
            f"  D5-95    {v['d5_95_s']:.4g} s",
        ]
        for period, sa in v["sa_g"].items():
            lines.append(f"  Sa({period} s) {sa:.4g} g (V/H {vertical['v_over_h']['sa'][period]:.3g})")
    print("\n".join(lines))
    return 0


def _processed(record, args: argparse.Namespace):
    """The record with --baseline and --resample applied (both components alike)."""
    if args.baseline is not None:
        if not 0 <= args.baseline <= 5:
            raise InvalidParameterError(f"--baseline must be a degree from 0 to 5, got "
                                        f"{args.baseline}")
        record = baseline_corrected(record, order=args.baseline)
    if args.resample is not None:
        if args.resample <= 0:
            raise InvalidParameterError(f"--resample must be a time step > 0 s, got "
                                        f"{args.resample:g}")
        record = resampled(record, args.resample)
    return record


def vertical_summary(vertical, horizontal_ims, periods, g: float) -> dict:
    """A vertical component's description and intensity measures for JSON, with the V/H
    ratios of its PGA and Sa(T) to the horizontal's (``horizontal_ims``)."""
    ims = intensity_measures(vertical, periods=periods, g=g)
    h = horizontal_ims

    def ratio(a: float, b: float) -> float:
        return a / b if b > 0 else math.nan

    return vertical.to_dict(g=g) | {
        "intensity_measures": ims.to_dict(),
        "v_over_h": {"pga": ratio(ims.pga_g, h.pga_g),
                     "sa": {f"{p:g}": ratio(ims.sa_g[p], h.sa_g[p]) for p in ims.sa_g}},
    }


def _spectrum(record, args: argparse.Namespace, g: float) -> int:
    """``--spectrum``: the record's response spectrum as a table, JSON or a figure."""
    spectra = record_spectra([record], args.periods, g=g)
    if args.plot is not None:
        from archquake.plotting.spectra import save_record_spectra

        save_record_spectra(spectra, args.plot, title=record.name)
    if args.json:
        print_json({"record": record.name, "file": str(record.source), "scale": record.scale,
                    "damping_ratio": spectra.damping, "periods_s": spectra.periods_s,
                    "sa_g": spectra.sa[0] / g, "g_m_s2": g,
                    "plot": str(args.plot) if args.plot else None})
        return 0
    print(f"{record.name}: response spectrum, {100 * spectra.damping:g} % damping")
    print_spectrum_table(spectra.periods_s, {"Sa g": spectra.sa[0] / g})
    if args.plot is not None:
        print(f"plot: {args.plot}")
    return 0


def print_spectrum_table(periods, columns: dict) -> None:
    """Periods (s) down the first column, one column per entry of ``columns`` (name -> values)."""
    print(f"{'T s':>7s}" + "".join(f" {name:>9s}" for name in columns))
    for i, t in enumerate(periods):
        print(f"{t:7.3f}" + "".join(f" {float(v[i]):9.4f}" for v in columns.values()))
