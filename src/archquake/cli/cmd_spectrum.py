"""``archquake spectrum``: a site's elastic response spectrum (NTC 2018 or EN 1998-1)."""

from __future__ import annotations

import argparse

from archquake.cli.common import add_output_arguments, periods_list, print_json, ranged
from archquake.cli.site_options import add_site_options, spectrum_from_args
from archquake.ranges import DAMPING_RATIO_RANGE_PERCENT

#: Periods printed unless --periods says otherwise: start, stop, step (s).
DEFAULT_GRID_S = (0.0, 4.0, 0.1)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "spectrum",
        help="a site's elastic spectrum (NTC 2018, EN 1998-1): Sa (g) and Sd (m) against T (s)",
        description=(
            "The elastic response spectrum of NTC 2018 §3.2.3.2 or EN 1998-1 §3.2.2 at one site: "
            "spectral acceleration S_e (g) and displacement S_De (m) at each period, with the "
            "code's parameters (S, T_B, T_C, T_D, ...). Example: archquake spectrum --code "
            "ntc2018 --ag 0.25 --f0 2.4 --tc-star 0.30 --soil B."
        ),
    )
    add_site_options(p)
    low, high = DAMPING_RATIO_RANGE_PERCENT
    p.add_argument("--damping", metavar="PCT", type=ranged(low, high, "%", high_open=True),
                   default=5.0, help="viscous damping, percent of critical (default 5)")
    p.add_argument("--periods", type=periods_list, metavar="START:STOP:STEP",
                   help="periods, s (0, or 0.001 to 20): a grid START:STOP:STEP or a list T,T,... (default "
                        f"{DEFAULT_GRID_S[0]:g}:{DEFAULT_GRID_S[1]:g}:{DEFAULT_GRID_S[2]:g})")
    add_output_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from archquake.ground.periods import period_grid

    spectrum = spectrum_from_args(args)
    damping = args.damping / 100.0
    periods = (np.asarray(args.periods, dtype=float) if args.periods
               else period_grid(*DEFAULT_GRID_S))
    sa = spectrum.sa(periods, damping)
    sd = spectrum.sd(periods, damping)
    if args.plot is not None:
        from archquake.plotting.spectra import save_elastic_spectrum

        save_elastic_spectrum(spectrum, periods, args.plot, damping=damping)
    if args.json:
        print_json({**spectrum.to_dict(), "damping_ratio": damping, "periods_s": periods,
                    "sa_g": sa / spectrum.g, "sd_m": sd,
                    "plot": str(args.plot) if args.plot else None})
        return 0
    d = spectrum.to_dict()
    print(f"{spectrum.label()}, {args.damping:g} % damping")
    corners = "  ".join(f"{k[:-2]} {d[k]:.3f} s" for k in ("TB_s", "TC_s", "TD_s", "TE_s", "TF_s")
                        if d[k] is not None)
    print(f"S {d['S']:.3f}  F0 {d['F0']:.3f}  {corners}")
    print(f"PGA {d['pga_g']:.4f} g  plateau {d['plateau_g'] * _eta(damping):.4f} g  "
          f"d_g {d['dg_m']:.4f} m")
    print(f"{'T s':>7s} {'Sa g':>9s} {'Sd m':>9s}")
    for t, a, u in zip(periods, sa / spectrum.g, sd):
        print(f"{t:7.3f} {a:9.4f} {u:9.4f}")
    if args.plot is not None:
        print(f"plot: {args.plot}")
    return 0


def _eta(damping: float) -> float:
    from archquake.codes.spectra import damping_factor

    return damping_factor(damping)
