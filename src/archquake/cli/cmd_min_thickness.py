"""``archquake min-thickness``: least t/R for which an arch stands under its own weight."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import number, print_json, whole
from archquake.cli.loads_options import (
    add_loads_arguments,
    check_loads_on,
    loads_from_args,
    passive_text,
)
from archquake.errors import InvalidParameterError
from archquake.geometry.checks import (
    MAX_EMBRACE_DEG,
    MAX_VOUSSOIRS,
    MIN_EMBRACE_DEG,
    OPTIONS,
    check_embrace_deg,
    check_voussoirs,
)
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
                   help=f"angle of embrace, degrees ({MIN_EMBRACE_DEG:g} to {MAX_EMBRACE_DEG:g}; "
                        "default 180)")
    p.add_argument("--voussoirs", type=whole, default=200,
                   help=f"number of voussoirs (3 to {MAX_VOUSSOIRS}; default 200)")
    from archquake.geometry.shapes import JOINTS, SHAPES

    g = p.add_argument_group(
        "other arches (lengths in m): any of these gives the minimum thickness t_min in m of that "
        "shape, and with --thickness the geometric factor of safety t / t_min")
    g.add_argument("--shape", choices=SHAPES, help="arch shape (with --span and --rise)")
    g.add_argument("--span", type=number, help="centreline span, m")
    g.add_argument("--rise", type=number, help="centreline rise, m")
    g.add_argument("--eccentricity", type=number, help="pointed arch instead of --rise")
    g.add_argument("--radius", type=number, help="circular arch by embrace: radius R, m")
    g.add_argument("--thickness", type=number,
                   help="the arch's ring thickness, m: reports t / t_min")
    g.add_argument("--joints", choices=JOINTS, default="radial",
                   help="radial (default) or vertical joints")
    g.add_argument("--pier-height", type=number, help="piers under the springings: height, m")
    g.add_argument("--pier-width", type=number, help="pier width, m")
    g.add_argument("--pier-courses", type=whole, help="courses in each pier (default 1)")
    g.add_argument("--density", type=number, default=None,
                   help="masonry density, kg/m^3 (default 2000; it matters only beside the "
                        "density of a fill)")
    add_loads_arguments(p)
    p.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    p.set_defaults(func=run)


_SHAPE_OPTIONS = ("shape", "span", "rise", "eccentricity", "radius", "thickness", "pier_height",
                  "pier_width", "pier_courses", "density")
_LOAD_OPTIONS = ("fill_depth", "fill_level", "fill_density", "backing", "backing_right",
                 "point_load", "distributed_load")


def _run_shape(args: argparse.Namespace) -> int:
    """Minimum thickness (m) of any arch, and t / t_min when --thickness is given."""
    from archquake.cli.common import arch_from_args, describe_arch
    from archquake.limit import min_thickness

    ns = argparse.Namespace(**vars(args))
    ns.depth, ns.blocks, ns._arch_defaults = 1.0, None, False
    ns.density = 2000.0 if args.density is None else args.density
    loads = loads_from_args(args)
    if args.shape in (None, "circular") and args.span is None:
        ns.radius = 1.0 if args.radius is None else args.radius
        ns.thickness = 0.5 * ns.radius if args.thickness is None else args.thickness
    else:
        ns.embrace = None
        if args.span is None:
            raise InvalidParameterError(f"a {args.shape} arch needs --span (m)")
        if args.thickness is None:  # a probe: only the shape matters for t_min
            ns.thickness = 0.01 * args.span
    arch = arch_from_args(ns)
    check_loads_on(arch, loads)
    if loads is None:
        t_min = min_thickness(arch)
    else:
        from archquake.limit.loaded import min_thickness_loaded

        t_min = min_thickness_loaded(arch, loads)
    out = {"arch": arch.describe(), "min_thickness_m": t_min,
           "min_thickness_ratio": t_min / arch.radius, "length_scale_m": arch.radius}
    if loads is not None:
        out["loads"] = loads.to_dict()
    if args.thickness is not None:
        out["thickness_m"] = args.thickness
        out["geometric_safety_factor"] = args.thickness / t_min if t_min > 0 else math.inf
    if args.json:
        print_json(out)
        return 0
    carried = "self-weight only" if loads is None else (
        f"self-weight and the loads it carries; {passive_text(loads)}")
    print(f"minimum thickness: t_min = {t_min:.5g} m (t_min / R = {t_min / arch.radius:.5f}, R = "
          f"{arch.radius:.5g} m the characteristic length; {carried})")
    if args.thickness is not None:
        print(f"geometric factor of safety: t / t_min = {out['geometric_safety_factor']:.3f} "
              f"({describe_arch(arch)})")
    return 0


def run(args: argparse.Namespace) -> int:
    if any(getattr(args, k, None) is not None for k in _LOAD_OPTIONS) and args.radius is None \
            and args.span is None:
        raise InvalidParameterError("loads are in m and kN: give the arch's size too (--radius, "
                                    "or --shape with --span and --rise)")
    if any(getattr(args, k, None) is not None for k in _SHAPE_OPTIONS) or args.joints != "radial":
        return _run_shape(args)
    check_embrace_deg(args.embrace, OPTIONS)
    check_voussoirs(args.voussoirs, OPTIONS)
    ratio = min_thickness_ratio(math.radians(args.embrace), args.voussoirs)
    if args.json:
        print_json({"min_thickness_ratio": ratio, "embrace_deg": args.embrace,
                    "voussoirs": args.voussoirs})
    else:
        print(f"minimum thickness: t/R = {ratio:.5f} (embrace {args.embrace:g} deg, "
              f"{args.voussoirs} voussoirs, self-weight only)")
    return 0
