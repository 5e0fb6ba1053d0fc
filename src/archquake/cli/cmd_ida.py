"""``archquake ida``: incremental dynamic analysis of an arch under a record suite, with fragility.

The library does the work (`archquake.ida`); this shell reads the suite, opens the store and
the executor, draws a progress bar on stderr, and prints, plots or writes the result.
"""

from __future__ import annotations

import argparse
import math
import sys
from contextlib import AbstractContextManager, nullcontext
from pathlib import Path
from typing import Any

import numpy as np

from archquake.cli.common import (
    add_arch_arguments,
    add_impact_arguments,
    add_model_argument,
    arch_from_args,
    impact_from_args,
    model_from_args,
    number,
    path_argument,
    print_json,
    suite_from_args,
    whole,
)
from archquake.errors import ArchquakeError, InvalidParameterError

#: Measures whose first-collapse dispersion is compared (besides the one of the analysis).
DISPERSION_IMS = ("pga", "pgv", "sa:0.2", "sa:0.5", "sa:1.0", "arias", "cav")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "ida",
        help="incremental dynamic analysis of the arch under a record suite, and fragility",
        description=(
            "Scale every record of a suite up to collapse by hunt-and-fill (Vamvatsikos & "
            "Cornell 2002), finding every level at which the arch collapses up to the ceiling "
            "(collapse is not monotonic in the scale: 'resurrections' are reported), and fit "
            "lognormal fragility curves (first-collapse intensities; collapse fraction per "
            "level). Resumable through a SQLite store; local cores or a Dask cluster. "
            "Intensities in the measure's unit: g (pga, sa:T), m/s (pgv, arias, cav)."
        ),
    )
    add_arch_arguments(p)
    p.add_argument("--records", required=True, metavar="SUITE",
                   help="a suite name (see 'archquake records', e.g. near-field-pulse), a "
                        "folder of .AT2/.csv files, a .list file or one accelerogram")
    p.add_argument("--record-vertical", type=path_argument, metavar="FILE", default=None,
                   help="the vertical component (positive upward) of a --records of one record; "
                        "scaled with it (a suite's: its .list names each after its record)")
    p.add_argument("--units", metavar="UNITS", help="units of CSV/text records: g, m/s2 or cm/s2")
    p.add_argument("--dt", type=number, metavar="S", help="time step of one-column records, s")
    p.add_argument("--im", default="pga", metavar="IM",
                   help="intensity measure: pga, pgv, sa:T (T in s), arias, cav (default pga)")
    p.add_argument("--ceiling", type=number, metavar="X",
                   help="largest intensity, in the measure's unit (default: the median record's "
                        "value at PGA = 5 g)")
    p.add_argument("--precision", type=number, default=0.02, metavar="P",
                   help="relative width of every survive/collapse bracket (default 0.02 = 2 %%)")
    p.add_argument("--fill", type=number, default=0.10, metavar="F",
                   help="largest relative gap between levels run (default 0.10)")
    add_model_argument(p, extra="rigid runs its verdicts as one compiled batch per round on "
                                "every core's threads, fourlink likewise; dem a process per core")
    add_impact_arguments(p)
    from archquake.cli.loads_options import add_loads_arguments

    add_loads_arguments(p)
    p.add_argument("--store", type=path_argument, metavar="FILE",
                   help="SQLite store of the runs (default: ida.sqlite here); rerun to resume")
    p.add_argument("--workers", type=whole, metavar="N",
                   help="local worker processes (default: rigid and fourlink run in this "
                        "process, their compiled batch on all cores' threads; dem on a process "
                        "per core; 1 runs serially)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="run on the Dask cluster whose scheduler listens at this address")
    p.add_argument("--bootstrap", type=whole, default=500, metavar="N",
                   help="bootstrap resamples of the fragility fits (default 500; 0: none)")
    p.add_argument("--seed", type=whole, default=0, metavar="N",
                   help="seed of the bootstrap (default 0)")
    p.add_argument("--plot", type=path_argument, metavar="FILE",
                   help="draw the IDA and fragility curves to FILE (.png, .pdf or .svg)")
    p.add_argument("--csv", type=path_argument, metavar="FILE", help="write every run to FILE (CSV)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    p.set_defaults(func=run)


def _check(args: argparse.Namespace) -> None:
    if not 0 < args.precision < 1:
        raise InvalidParameterError(f"--precision must be in (0, 1), got {args.precision:g}")
    if not args.precision <= args.fill <= 10:
        raise InvalidParameterError(f"--fill must be in [--precision, 10], got {args.fill:g}")
    if args.ceiling is not None and not args.ceiling > 0:
        raise InvalidParameterError(f"--ceiling must be > 0 (in the measure's unit), got "
                                    f"{args.ceiling:g}")
    model_from_args(args)
    impact_from_args(args)
    if args.workers is not None and args.workers < 1:
        raise InvalidParameterError(f"--workers must be a whole number >= 1, got {args.workers}")
    if args.bootstrap < 0:
        raise InvalidParameterError(f"--bootstrap must be >= 0, got {args.bootstrap}")
    if args.scheduler is not None and "://" not in args.scheduler:
        raise InvalidParameterError(
            f"--scheduler must be an address like tcp://HOST:PORT, got {args.scheduler!r}")
    if args.plot is not None and args.plot.suffix.lower() not in (".png", ".pdf", ".svg"):
        raise InvalidParameterError(f"--plot file must end in .png, .pdf or .svg, got "
                                    f"{args.plot.name!r}")


def _model(args: argparse.Namespace):
    """The `Model` of --model (checked by `_check`)."""
    from archquake.models import Model

    return Model(args.model)


def run(args: argparse.Namespace) -> int:
    from archquake.ground.measures import parse_im
    from archquake.ida import incremental_dynamic_analysis
    from archquake.ida.fragility import dimensionless_divisor, dispersion_by_im, fragility_of
    from archquake.sweeps import ArchSpec, CaseOptions, ResultStore

    _check(args)
    try:
        im = parse_im(args.im)
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"--im: {exc}") from None
    arch = arch_from_args(args)
    spec = ArchSpec(arch.radius, arch.thickness / arch.radius, math.degrees(arch.embrace),
                    arch.voussoirs, arch.depth, arch.density)
    try:
        suite = suite_from_args(args.records, args.units, args.dt,
                                vertical=args.record_vertical)
    except ArchquakeError as exc:
        raise InvalidParameterError(f"--records: {exc}") from None
    options = CaseOptions(**impact_from_args(args))
    from archquake.cli.loads_options import dynamic_loads_from_args

    loads = dynamic_loads_from_args(args, arch, _model(args), fourlink=True)
    store_path = args.store or Path("ida.sqlite")
    bar = _Bar(disable=args.no_progress)
    with ResultStore(store_path) as store:
        try:
            with _executor(args) as (executor, n):
                result = incremental_dynamic_analysis(
                    spec, suite.records, im, store, ceiling=args.ceiling,
                    precision=args.precision, fill=args.fill, model=_model(args),
                    options=options, executor=executor, workers=n, progress=bar, loads=loads)
        except KeyboardInterrupt:
            bar.close()
            print(f"archquake: interrupted: {store.count()} runs are stored in {store.path}; "
                  "run the same command again to resume", file=sys.stderr)
            return 130
    bar.close()
    rng = np.random.default_rng(args.seed)
    fits = fragility_of(result, rng=rng, bootstrap=args.bootstrap)
    dispersion = dispersion_by_im(result, list(dict.fromkeys([im.label, *DISPERSION_IMS])))
    divisor = dimensionless_divisor(im, collapse_acceleration_g=result.collapse_acceleration_g,
                                    radius=arch.radius, g=result.g)
    if args.csv is not None:
        result.write_csv(args.csv)
    if args.plot is not None:
        from archquake.plotting.ida import save_ida

        save_ida(result, fits, args.plot)
    unit = result.unit_key
    out = result.to_dict()
    out["suite"] = suite.name
    out["fragility"] = {k: (None if fits[k] is None else fits[k].to_dict(unit))
                        for k in ("first_collapse", "collapse_fraction")}
    if divisor is not None:
        out["fragility_dimensionless"] = {
            "divisor": divisor[1], "divisor_value": divisor[0],
            **{k: (None if fits[k] is None else fits[k].scaled(divisor[0]).to_dict("dimensionless"))
               for k in ("first_collapse", "collapse_fraction")}}
    out["dispersion_by_im"] = dispersion
    if loads is not None:
        from archquake.blocks.assembly import PASSIVE_LEFT_OUT

        out["passive_pressure"] = PASSIVE_LEFT_OUT
    if args.json:
        print_json(out)
        return 0
    _print_text(result, suite, fits, dispersion, divisor, args)
    return 0


def _print_text(result, suite, fits, dispersion, divisor, args) -> None:
    from archquake import models

    a = result.arch
    im = result.im
    u = im.unit
    print(f"IDA: arch R = {a.radius:g} m, t/R = {a.thickness_ratio:.3f}, embrace "
          f"{a.embrace_deg:g} deg, {a.voussoirs} voussoirs (lambda = "
          f"{result.collapse_acceleration_g:.3f} g); {result.model.value} model"
          + (f", c_v = {result.settings['restitution']:g} (prescribed)"
             if result.settings["restitution"] is not None else "")
          + (f"; impact law {result.settings.get('impact', 'paper')}"
             if models.takes(result.model, "impact") else ""))
    if result.loads is not None:
        from archquake.blocks.assembly import PASSIVE_LEFT_OUT

        print("loads: the arch carries its fill and loads in every run (lambda is the loaded "
              f"arch's); {PASSIVE_LEFT_OUT}")
    indeterminate = sum(int(r.indeterminate.sum()) for r in result.records)
    if indeterminate:
        why = {"fourlink": "the verdict came after an impact the law does not describe",
               "rigid": "the verdict changed at half the time step"}.get(
                   result.model.value, "the arch still moved at the end of the run")
        print(f"{indeterminate} run(s) indeterminate ({why}): counted as collapses, so the "
              "fragility is an upper bound")
    print(f"suite {suite.name} ({len(result.records)} records); IM {im.label} ({u}); "
          f"hunt-and-fill to {100 * result.settings['precision']:g} % (fill "
          f"{100 * result.settings['fill']:g} %), ceiling {result.ceiling:.4g} {u}")
    print(f"{result.total} runs in {result.rounds} rounds ({result.computed} computed now, "
          f"{result.total - result.computed} from the store {result.store})")
    width = max(12, max(len(r.name) for r in result.records))
    print(f"  {'record':<{width}}  {'1st collapse':>12}  collapse intervals ({u}); "
          "resurrections")
    for r in result.records:
        first = r.first_collapse
        runs = ", ".join(f"{i.lower_edge:.3g}-{i.upper_edge:.3g}" if i.above is not None
                         else f"{i.lower_edge:.3g}-" for i in r.collapse_intervals) or "none"
        extra = f"; {len(r.resurrections)} resurrection(s)" if r.resurrections else ""
        print(f"  {r.name:<{width}}  {first.lower_edge if first else math.nan:12.4g}  "
              f"{runs}{extra}")
    for r in result.records:
        if r.ceiling < result.ceiling * (1 - 1e-9):  # its vertical lifts the arch off above
            print(f"  {r.name}: levels up to {r.ceiling:.4g} {u}, where its vertical component "
                  "reaches g downward (the arch would leave its supports)")
    levels = fits["levels"]
    print("collapse fraction per level:")
    print("  " + "  ".join(f"{x:.3g}:{p:.2f}" for x, p in zip(levels, fits["fraction"],
                                                             strict=True)))
    for key, what in (("first_collapse", "first-collapse intensities"),
                      ("collapse_fraction", "collapse fraction (binomial)")):
        fit = fits[key]
        if fit is None:
            print(f"fragility from {what}: not enough collapses to fit")
            continue
        ci = (f" [{fit.median_ci[0]:.3g}, {fit.median_ci[1]:.3g}]" if fit.median_ci else "")
        bci = (f" [{fit.beta_ci[0]:.2f}, {fit.beta_ci[1]:.2f}]" if fit.beta_ci else "")
        line = (f"fragility from {what}: median {fit.median:.4g} {u}{ci}, beta "
                f"{fit.beta:.3f}{bci}")
        if divisor is not None:
            line += f"; {im.name.upper()} {divisor[1]}: median {fit.median / divisor[0]:.3g}"
        print(line)
    if fits["first_collapse"] is not None and fits["first_collapse"].median_ci:
        print(f"  ({100 * fits['first_collapse'].confidence:g} % bootstrap intervals, "
              f"{fits['first_collapse'].bootstrap} resamples over records)")
    print("dispersion of the first-collapse intensity by IM (smallest beta predicts best):")
    for row in sorted(dispersion, key=lambda r: math.inf if r["beta"] is None else r["beta"]):
        if row["beta"] is None:
            print(f"  {row['im']:<8} not enough collapses")
        else:
            median = next(v for k, v in row.items() if k.startswith("median_"))
            print(f"  {row['im']:<8} beta {row['beta']:.3f}  median {median:.4g} {row['unit']}")
    if args.csv is not None:
        print(f"runs written to {args.csv}")
    if args.plot is not None:
        print(f"figure written to {args.plot}")


def _executor(args: argparse.Namespace) -> AbstractContextManager[tuple[Any, int | None]]:
    """Where the runs go: the analysis's own default for the four-link model and the rigid
    chain when neither --workers nor --scheduler is given (this process, the compiled batch on
    threads: 2.62 s against 3.10 s through a pool for the four-link model,
    docs/earthquakes.md), else the executor the options
    ask for (the DEM's runs are one process each: a pool of all cores by default)."""
    from archquake import models
    from archquake.parallel import open_executor

    if models.spec(_model(args)).batched and args.workers is None and args.scheduler is None:
        return nullcontext((None, None))
    return open_executor(workers=args.workers, scheduler=args.scheduler)


class _Bar:
    """A tqdm bar fed by the analysis's ``progress(stored, total_so_far, round)``; the total
    grows as hunt-and-fill proposes levels."""

    def __init__(self, *, disable: bool):
        self._disable = disable
        self._bar: Any = None  # a tqdm bar (tqdm is untyped)

    def __call__(self, done: int, total: int, rounds: int) -> None:
        if self._bar is None:
            from tqdm import tqdm

            self._bar = tqdm(total=total, initial=done, unit="run", file=sys.stderr,
                             disable=True if self._disable else None, dynamic_ncols=True,
                             desc="ida")
        self._bar.total = total
        self._bar.set_description(f"ida round {rounds}")
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
