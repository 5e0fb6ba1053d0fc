"""``archquake static``: equivalent static analysis (collapse acceleration, hinges, friction)."""

from __future__ import annotations

import argparse

from archquake._validate import require_range
from archquake.cli.common import (
    add_arch_arguments,
    add_output_arguments,
    arch_from_args,
    describe_arch,
    print_json,
)
from archquake.cli.loads_options import (
    add_loads_arguments,
    check_loads_on,
    loads_from_args,
    passive_text,
)
from archquake.errors import InvalidParameterError
from archquake.limit import (
    MAX_KINEMATIC_VOUSSOIRS,
    coupled_vertical_analysis,
    limit_analysis,
)
from archquake.limit.analysis import MAX_VERTICAL_G


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "static",
        help="equivalent static analysis: collapse acceleration (g), hinges, friction demand",
        description=(
            "Largest uniform horizontal ground acceleration (in g) the arch resists before it "
            "becomes a four-hinge mechanism (rigid voussoirs, no tension, no sliding), the hinges "
            "A, B, C, D and the friction coefficient needed against sliding at that instant. The "
            "load acts towards +x; a load towards -x gives the mirror image. Angles in degrees. "
            "With loads (fill, backing, loads on the extrados) every mass that moves with the "
            "arch has its weight and its horizontal inertia at its own centroid, and both "
            "directions are reported."
        ),
    )
    add_arch_arguments(p)
    p.add_argument(
        "--method", choices=("auto", "static", "kinematic", "both"), default="auto",
        help="static: line-of-thrust linear program (any number of voussoirs); kinematic: "
             f"virtual work over every mechanism (up to {MAX_KINEMATIC_VOUSSOIRS} voussoirs); "
             "both: check they agree; auto (default): both when the mechanisms can be "
             "enumerated, else static",
    )
    vert = p.add_mutually_exclusive_group()
    vert.add_argument(
        "--vertical", type=float, default=0.0, metavar="K",
        help="constant vertical ground acceleration, g, upward positive (> -1): every mass "
             "that moves with the arch weighs (1 + K) times more, so the bare arch's lambda "
             "scales by 1 + K. EN 1998-1's E_x + 0.3 E_z: K = -0.3 a_vg/g (default 0)",
    )
    vert.add_argument(
        "--vertical-ratio", type=float, default=None, metavar="R",
        help="a downward vertical R times the horizontal, acting together (EN 1998-5's "
             "pseudo-static k_v = 0.5 k_h where a_vg/a_g > 0.6, else 0.33 k_h); in [0, 1]",
    )
    add_loads_arguments(p)
    add_output_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    arch = arch_from_args(args)
    loads = loads_from_args(args)
    check_loads_on(arch, loads)
    method = args.method
    if method == "auto":
        method = "both" if arch.voussoirs <= MAX_KINEMATIC_VOUSSOIRS else "static"
    elif method in ("kinematic", "both") and arch.voussoirs > MAX_KINEMATIC_VOUSSOIRS:
        raise InvalidParameterError(
            f"--method {method} enumerates the mechanisms and needs --voussoirs <= "
            f"{MAX_KINEMATIC_VOUSSOIRS}, got {arch.voussoirs}; use --method static (or auto)")
    result = _analysis(arch, method, loads, args)
    if args.plot is not None:
        from archquake.plotting.arch import save_limit_analysis

        save_limit_analysis(result, args.plot)
    if args.json:
        print_json(result.to_dict())
        return 0
    print(format_result(result))
    if args.plot is not None:
        print(f"figure written to {args.plot}")
    return 0


def _analysis(arch, method: str, loads, args: argparse.Namespace):
    if args.vertical_ratio is not None:
        require_range("--vertical-ratio", args.vertical_ratio, 0.0, 1.0, low_open=False,
                      high_open=False)
        return coupled_vertical_analysis(arch, args.vertical_ratio, method=method, loads=loads)
    if args.vertical:
        require_range("--vertical", args.vertical, -1.0, MAX_VERTICAL_G, "g",
                      high_open=False)
    return limit_analysis(arch, method=method, loads=loads, vertical=args.vertical)


def format_result(result) -> str:
    """Human-readable summary of a `LimitAnalysis`."""
    arch = result.arch
    n = arch.voussoirs
    lines = [
        f"arch: {describe_arch(arch)}",
        f"collapse acceleration: {result.collapse_acceleration_g:.4f} g "
        + ("(horizontal, load towards +x)" if result.loads is not None else
           "(horizontal, load towards +x; the mirror mechanism for -x)"),
    ]
    if result.vertical_g:
        lines.append(f"with a constant vertical ground acceleration of {result.vertical_g:+.4f} g "
                     f"(upward positive): gravity {1 + result.vertical_g:.4f} g")
    lam_static, lam_kin = result.static_collapse_acceleration_g, result.kinematic_collapse_acceleration_g
    if lam_static is not None and lam_kin is not None:
        lines.append(
            f"  static (line of thrust) {lam_static:.6f} g, kinematic (virtual work) {lam_kin:.6f} g"
        )
    where = "symmetric" if result.symmetric else "asymmetric"
    lines.append(f"hinges ({where} locations; joint 0 = left springing, {n} = right springing):")
    for label, h in zip("ABCD", result.mechanism.hinges, strict=True):
        lines.append(
            f"  {label}  joint {h.joint:>3d}  {h.face.value:<8s}  x = {h.x:9.4f} m  y = {h.y:9.4f} m"
        )
    if result.loads is not None:
        lines.extend(loads_lines(result))
    j = result.min_friction_joint
    place = {0: ", the left springing", n: ", the right springing"}.get(j, "")
    lines.append(
        f"friction demand at the onset of motion: {result.min_friction:.3f} "
        f"(largest |V|/N, at joint {j}{place})"
    )
    return "\n".join(lines)


def loads_lines(result) -> list[str]:
    """What the arch carries, and lambda towards -x (text lines)."""
    loads, carried = result.loads, result.carried
    out = [f"collapse acceleration towards -x: {result.opposite_collapse_acceleration_g:.4f} g"]
    if loads.fill is not None:
        out.append(f"fill: surface at y = {carried.surface:.4g} m, {loads.fill.density:g} kg/m^3 "
                   "(column model: each block carries the fill above its extrados)")
    if loads.backing is not None:
        held = [int(j) for j in carried.held.nonzero()[0]]
        out.append(f"backing: {loads.backing.left:g} m (left), {loads.backing.right:g} m "
                   f"(right); joints held: {held or 'none'}")
    for p in loads.point_loads:
        out.append(f"point load: {p.load / 1e3:g} kN/m at {p.position:g} m"
                   + ("" if p.moves_with_arch else " (its mass does not move)"))
    for d in loads.distributed_loads:
        out.append(f"distributed load: {d.pressure / 1e3:g} kN/m from {d.start:g} to {d.end:g} m"
                   + ("" if d.moves_with_arch else " (its mass does not move)"))
    out.append(f"mass carried by the blocks (fill and loads that move with the arch): "
               f"{carried.mass.sum():.6g} kg, beside the ring's {result.arch.mass:.6g} kg")
    out.append(passive_text(loads))
    if result.hinge_count is not None and result.hinge_count > 4:
        out.append(f"the collapse needs {result.hinge_count} hinges (two mechanisms at once, "
                   "with the passive pressure): the four shown are the least four-hinge "
                   f"mechanism, an upper bound at {result.kinematic_collapse_acceleration_g:.4f} g")
    return out

