"""``archquake record FILE``: read an accelerogram and summarise it before a run."""

from __future__ import annotations

import argparse
from pathlib import Path

from archquake.cli.common import (
    RECORD_UNITS,
    add_output_arguments,
    number,
    print_json,
    record_from_args,
)
from archquake.constants import STANDARD_GRAVITY


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "record",
        help="check an accelerogram file (.AT2 or CSV): points, dt, duration, PGA",
        description=(
            "Read a recorded ground acceleration and print what archquake understood: name, "
            "number of points, time step, duration and peak ground acceleration (in g and m/s^2). "
            "Positive values are ground accelerations towards +x."
        ),
    )
    p.add_argument("file", type=Path, metavar="FILE",
                   help="PEER .AT2 (values in g) or .csv/.txt with two columns: time (s), "
                        "acceleration")
    p.add_argument("--units", choices=RECORD_UNITS, default=None,
                   help="units of a CSV file's acceleration column (default g; .AT2 files are "
                        "always in g)")
    p.add_argument("--scale", type=number, metavar="S",
                   help="factor applied to every value (> 0; default 1)")
    add_output_arguments(p, plot=False)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    record = record_from_args(args.file, args.units, args.scale)
    g = STANDARD_GRAVITY
    summary = record.to_dict(g=g)
    is_csv = args.file.suffix.lower() in (".csv", ".txt")
    summary["units_in_file"] = (args.units or "g") if is_csv else "g"
    summary["g_m_s2"] = g
    if args.json:
        print_json(summary)
        return 0
    signed = float(record.accelerations[int(round(record.time_of_peak / record.dt))])
    units_note = summary["units_in_file"]
    if is_csv and args.units is None:
        units_note += " (default; use --units m/s2 if the file is in m/s^2)"
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
    print("\n".join(lines))
    return 0
