"""The site's elastic spectrum on the command line: one option group for every command that needs
it (``archquake spectrum``, ``archquake records select``, the code check).

NTC 2018: ``--code ntc2018 --ag G --f0 F --tc-star S --soil A|B|C|D|E [--topography T1..T4]``;
EN 1998-1: ``--code ec8 --ag G --type 1|2 --ground A|B|C|D|E [--importance GAMMA]``;
both: ``[--component horizontal|vertical]``. Accelerations in g, periods in s.
"""

from __future__ import annotations

import argparse

from archquake.cli.common import ranged, refuse_unless
from archquake.errors import InvalidParameterError
from archquake.ranges import (
    EC8_GROUNDS,
    IMPORTANCE_RANGE,
    NTC_F0_RANGE,
    NTC_SOILS,
    NTC_TC_STAR_RANGE_S,
    NTC_TOPOGRAPHIES,
    SITE_AG_RANGE_G,
    SPECTRUM_COMPONENTS,
)

#: The codes ``--code`` offers (archquake.codes.spectra.CODES, without importing it here).
SITE_CODES = ("ntc2018", "ec8")


def _upper(text: str) -> str:
    return text.strip().upper()


def add_site_options(parser: argparse.ArgumentParser, *, required: bool = True) -> None:
    """Add the site spectrum's options to ``parser`` (one argument group).

    Parameters
    ----------
    parser : argparse.ArgumentParser
    required : bool
        Whether ``--code`` and ``--ag`` must be given (a command may make the site optional).
    """
    grp = parser.add_argument_group(
        "site elastic spectrum (NTC 2018 §3.2 or EN 1998-1 §3.2.2; accelerations in g)")
    grp.add_argument("--code", choices=SITE_CODES, required=required,
                     help="ntc2018 (with --f0, --tc-star, --soil) or ec8 (with --type, --ground)")
    low, high = SITE_AG_RANGE_G
    grp.add_argument("--ag", metavar="G", required=required,
                     type=ranged(low, high, "g", low_open=True),
                     help="peak ground acceleration on type A ground a_g, g (EN 1998-1: a_gR, "
                          "the reference value before the importance factor)")
    grp.add_argument("--f0", metavar="F", type=ranged(*NTC_F0_RANGE),
                     help="NTC F0, the plateau's amplification on rock (from the hazard grid)")
    grp.add_argument("--tc-star", metavar="S", type=ranged(*NTC_TC_STAR_RANGE_S, unit="s"),
                     help="NTC T_C*, s (from the hazard grid)")
    grp.add_argument("--soil", type=_upper, choices=NTC_SOILS,
                     help="NTC subsoil category (Tab. 3.2.II; default A)")
    grp.add_argument("--topography", type=_upper, choices=NTC_TOPOGRAPHIES,
                     help="NTC topographic category (Tab. 3.2.III; default T1)")
    grp.add_argument("--type", dest="spectrum_type", type=int, choices=(1, 2),
                     help="EN 1998-1 spectrum type (default 1; 2 where M_s <= 5.5 dominates)")
    grp.add_argument("--ground", type=_upper, choices=EC8_GROUNDS,
                     help="EN 1998-1 ground type (Tab. 3.1; default A)")
    grp.add_argument("--importance", metavar="GAMMA", type=ranged(*IMPORTANCE_RANGE),
                     help="EN 1998-1 importance factor gamma_I (default 1.0): a_g = gamma_I a_gR")
    grp.add_argument("--component", choices=SPECTRUM_COMPONENTS, default="horizontal",
                     help="spectrum component (default horizontal)")


def spectrum_from_args(args: argparse.Namespace):
    """The :class:`~archquake.codes.spectra.ElasticSpectrum` the site options describe.

    Options of the other code are refused with one line; NTC needs ``--f0`` and ``--tc-star``.
    Returns None when the options were optional and ``--code`` was not given.
    """
    from archquake.codes.spectra import ec8_spectrum, ntc2018_spectrum

    if args.code is None:
        refuse_unless(site_options_given(args), False, "with --code ntc2018 or --code ec8")
        return None
    if args.ag is None:
        raise InvalidParameterError(f"--code {args.code} needs --ag G (a_g in g)")
    from archquake.cli.input_warnings import warn_pga

    warn_pga("--ag", args.ag)
    ntc = {"--f0": args.f0, "--tc-star": args.tc_star, "--soil": args.soil,
           "--topography": args.topography}
    ec8 = {"--type": args.spectrum_type, "--ground": args.ground, "--importance": args.importance}
    if args.code == "ntc2018":
        refuse_unless(ec8, False, "with --code ec8")
        missing = [name for name in ("--f0", "--tc-star") if ntc[name] is None]
        if missing:
            raise InvalidParameterError(
                f"--code ntc2018 needs {' and '.join(missing)} (read them off the hazard grid "
                f"with a_g at the site's return period)")
        return ntc2018_spectrum(ag_g=args.ag, f0=args.f0, tc_star_s=args.tc_star,
                                soil=args.soil or "A", topography=args.topography or "T1",
                                component=args.component)
    refuse_unless(ntc, False, "with --code ntc2018")
    return ec8_spectrum(ag_g=args.ag, spectrum_type=args.spectrum_type or 1,
                        ground=args.ground or "A",
                        importance=1.0 if args.importance is None else args.importance,
                        component=args.component)


def site_options_given(args: argparse.Namespace) -> dict[str, object]:
    """The site options besides ``--code`` and ``--component`` by name as typed (None: not
    given), for :func:`archquake.cli.common.refuse_unless`."""
    return {"--ag": args.ag, "--f0": args.f0, "--tc-star": args.tc_star, "--soil": args.soil,
            "--topography": args.topography, "--type": args.spectrum_type,
            "--ground": args.ground, "--importance": args.importance}


__all__ = ["SITE_CODES", "add_site_options", "site_options_given", "spectrum_from_args"]
