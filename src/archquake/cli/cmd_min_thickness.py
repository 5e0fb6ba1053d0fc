"""``archquake min-thickness``: least t/R for which an arch stands under its own weight."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import MAX_EMBRACE_DEG, number, print_json, whole
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import MAX_VOUSSOIRS
from archquake.limit import min_thickness_ratio


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "min-thickness",
        help="minimum thickness ratio t/R of an arch under its own weight",
        description=(
            "Least t/R for which a line of thrust fits inside a part-circular arch of equal "
            "voussoirs under self-weight alone (0.1075 for a semicircle with many voussoirs: "
            "Milankovitch, Heyman). Angles in degrees."
        ),
    )
    p.add_argument("--embrace", type=number, default=180.0,
                   help=f"angle of embrace, degrees (0 < embrace <= {MAX_EMBRACE_DEG:g}; "
                        "default 180)")
    p.add_argument("--voussoirs", type=whole, default=200,
                   help=f"number of voussoirs (3 to {MAX_VOUSSOIRS}; default 200)")
    p.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if not (0.0 < args.embrace <= MAX_EMBRACE_DEG):
        raise InvalidParameterError(
            f"--embrace must be in (0, {MAX_EMBRACE_DEG:g}] degrees, got {args.embrace:g}"
        )
    if not (3 <= args.voussoirs <= MAX_VOUSSOIRS):
        raise InvalidParameterError(
            f"--voussoirs must be a whole number from 3 to {MAX_VOUSSOIRS}, got {args.voussoirs}"
        )
    ratio = min_thickness_ratio(math.radians(args.embrace), args.voussoirs)
    if args.json:
        print_json({"min_thickness_ratio": ratio, "embrace_deg": args.embrace,
                    "voussoirs": args.voussoirs})
    else:
        print(f"minimum thickness: t/R = {ratio:.5f} (embrace {args.embrace:g} deg, "
              f"{args.voussoirs} voussoirs, self-weight only)")
    return 0
