"""``archquake capacity``: the traffic load that collapses the arch, at one position and along
the span (the adequacy factor)."""

from __future__ import annotations

import argparse

from archquake.cli.common import (
    add_arch_arguments,
    add_output_arguments,
    arch_from_args,
    describe_arch,
    number,
    print_json,
    ranged_whole,
)
from archquake.cli.loads_options import (
    add_loads_arguments,
    check_loads_on,
    loads_from_args,
    passive_text,
    traffic_from_args,
)
from archquake.errors import InvalidParameterError
from archquake.geometry.loads import Loads
from archquake.limit.kinematic import MAX_KINEMATIC_VOUSSOIRS

HELP = "traffic capacity: the load multiplier that collapses the arch, and its critical position"


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "capacity", help=HELP,
        description=(
            "The multiplier on a traffic load (an axle or a patch, kN per metre of barrel "
            "width) that turns the arch, with its fill, backing and loads, into a four-hinge "
            "mechanism (rigid blocks, no tension, no sliding, no crushing; the fill is dead "
            "weight, and resists passively only with --passive). "
            "With --position: at that position; otherwise the load is moved along the clear "
            "span and the critical position is reported, with its multiplier: the adequacy "
            "factor. Positions in m from the left springing of the intrados."),
    )
    add_arch_arguments(p)
    add_loads_arguments(p, traffic=True)
    g = p.add_argument_group("where the traffic stands")
    g.add_argument("--position", type=number, default=None, metavar="M",
                   help="one position, m along the clear span (default: scan the span)")
    g.add_argument("--positions", type=ranged_whole(2, 2000), default=None, metavar="N",
                   help="positions of the scan, evenly spaced over the clear span (2 to 2000; "
                        "default 50)")
    p.add_argument(
        "--method", choices=("auto", "static", "kinematic", "both"), default="auto",
        help="static: line-of-thrust linear program; kinematic: virtual work over every "
             f"mechanism (up to {MAX_KINEMATIC_VOUSSOIRS} voussoirs); both: check they agree; "
             "auto (default): both when the mechanisms can be enumerated, else static")
    add_output_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from archquake.limit.capacity import capacity_scan, traffic_capacity

    arch = arch_from_args(args)
    loads = loads_from_args(args) or Loads()
    check_loads_on(arch, loads)
    traffic = traffic_from_args(args)
    if args.position is not None and args.positions is not None:
        raise InvalidParameterError("--positions sets a scan; drop it with --position")
    scan = None
    if args.position is not None:
        result = traffic_capacity(arch, loads, _at(arch, traffic, args), method=args.method)
    else:
        scan = capacity_scan(arch, loads, traffic, args.positions or 50, method=args.method)
        result = scan.critical
    if args.plot is not None:
        from archquake.plotting.loads import save_capacity

        save_capacity(result, args.plot, scan)
    if args.json:
        print_json(scan.to_dict() if scan is not None else result.to_dict())
        return 0
    print(format_capacity(result, scan))
    if args.plot is not None:
        print(f"figure written to {args.plot}")
    return 0


def _at(arch, traffic, args):
    from archquake._validate import check_range
    from archquake.geometry.loads import Extrados

    span = Extrados.of(arch).clear_span
    check_range("--position", args.position, 0.0, span, "m",
                hint=f"positions run along the clear span, {span:.4g} m, from the left "
                     "springing of the intrados")
    return traffic.at(args.position)


def format_capacity(result, scan=None) -> str:
    """Text summary of a traffic capacity (and its scan)."""
    t = result.traffic
    kind = "axle" if t.length == 0 else f"patch {t.length:g} m long"
    spread = ("spread through the fill by Boussinesq (Flamant)" if t.boussinesq else
              "not spread" if t.dispersion is None
              else f"spread through the fill at {t.dispersion:g} deg")
    lines = [f"arch: {describe_arch(result.arch)}",
             f"traffic: {kind}, {t.load / 1e3:g} kN per m of width, {spread}"]
    if scan is not None:
        lines.append(f"scan: {scan.positions_m.size} positions over the clear span; critical "
                     f"position {t.position:.4g} m")
        lines.append(f"adequacy factor: {result.multiplier:.4f}")
    else:
        lines.append(f"position: {t.position:.4g} m")
        lines.append(f"collapse multiplier: {result.multiplier:.4f}")
    lines.append(f"collapse load: {result.collapse_load_N_m / 1e3:.5g} kN per m of width "
                 f"({result.collapse_load_N_m * result.arch.depth / 1e3:.5g} kN over the "
                 f"{result.arch.depth:g} m depth)")
    if result.static_multiplier is not None and result.kinematic_multiplier is not None:
        lines.append(f"  static (line of thrust) {result.static_multiplier:.6f}, kinematic "
                     f"(virtual work) {result.kinematic_multiplier:.6f}")
    n = result.arch.voussoirs
    lines.append(f"hinges (joint 0 = left springing, {n} = right springing):")
    for label, h in zip("ABCD", result.mechanism.hinges, strict=True):
        lines.append(f"  {label}  joint {h.joint:>3d}  {h.face.value:<8s}  x = {h.x:9.4f} m  "
                     f"y = {h.y:9.4f} m")
    if result.hinge_count > 4:
        lines.append(f"the collapse needs {result.hinge_count} hinges (two mechanisms at once, "
                     "with the passive pressure): the four shown are the least four-hinge "
                     f"mechanism, an upper bound at {result.kinematic_multiplier:.4f}")
    held = [int(j) for j in result.carried.held.nonzero()[0]]
    if held:
        lines.append(f"joints held by the backing: {held}")
    lines.append("assumptions: rigid blocks, no tension, no sliding or crushing; fill as dead "
                 f"weight in columns; {passive_text(result.loads)}")
    return "\n".join(lines)
