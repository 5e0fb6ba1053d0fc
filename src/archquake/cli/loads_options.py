"""Options for what the arch carries (fill, backing, loads on the extrados, traffic), in the
CLI's units (m, kg/m^3, kN and kN/m per metre of barrel width, degrees), and their conversion
to `Loads` (SI) here, at the edge."""

from __future__ import annotations

import argparse

from archquake._validate import check_range
from archquake.cli.common import number
from archquake.errors import InvalidParameterError
from archquake.geometry.loads import (
    MAX_DISPERSION_DEG,
    MAX_LOAD_LENGTH_M,
    MAX_LOAD_N_M,
    Backing,
    DistributedLoad,
    Fill,
    Loads,
    Passive,
    PointLoad,
    Traffic,
)

#: Largest load the options take, kN (per metre of barrel width).
MAX_LOAD_KN = MAX_LOAD_N_M / 1e3
#: The word that marks a load whose mass does not move with the arch.
STILL = "still"


def _items(text: str, least: int, most: int, what: str) -> tuple[list[float], bool]:
    parts = [p.strip() for p in text.split(",")]
    still = bool(parts) and parts[-1].lower() == STILL
    if still:
        parts = parts[:-1]
    if not least <= len(parts) <= most or any(not p for p in parts):
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
    try:
        return [float(p) for p in parts], still
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None


def point_load(text: str) -> tuple[list[float], bool]:
    """argparse type: ``POSITION,KN[,still]``."""
    return _items(text, 2, 2, f"POSITION (m),LOAD (kN per m of width)[,{STILL}]")


def distributed_load(text: str) -> tuple[list[float], bool]:
    """argparse type: ``START,END,KPA[,still]``."""
    return _items(text, 3, 3, f"START (m),END (m),LOAD (kN/m per m of width)[,{STILL}]")


def dispersion(text: str) -> float | str:
    """argparse type: an angle in degrees, or the word 'boussinesq'."""
    if text.strip().lower() == "boussinesq":
        return "boussinesq"
    return number(text)


def add_loads_arguments(parser: argparse.ArgumentParser, *, traffic: bool = False) -> None:
    """--fill-depth/--fill-level, --fill-density, --backing, --backing-right, --point-load,
    --distributed-load; with ``traffic`` also --axle/--patch, --patch-length, --dispersion."""
    g = parser.add_argument_group(
        "loads the arch carries (m, kg/m^3; loads in kN per metre of barrel width; positions "
        "along the clear span from the left springing of the intrados; passive fill pressure "
        "off unless --passive)")
    g.add_argument("--fill-depth", type=number, default=None, metavar="M",
                   help="fill over the arch: depth of its horizontal surface above the crown of "
                        f"the extrados, m (0 to {MAX_LOAD_LENGTH_M:g}); each block carries the "
                        "column of fill above its extrados (weight and horizontal inertia at the "
                        "column's centroid)")
    g.add_argument("--fill-level", type=number, default=None, metavar="Y",
                   help="instead of --fill-depth (surveyed arches): the fill surface's height y, "
                        "m, at or above the extrados's highest point")
    g.add_argument("--fill-density", type=number, default=None, metavar="KG_M3",
                   help="fill density, kg/m^3 (0 to 100000; default 1800 with a fill)")
    g.add_argument("--backing", type=number, default=None, metavar="M",
                   help="solid backing up to this height above each springing, m: joints whose "
                        "extrados end lies below its top cannot hinge")
    g.add_argument("--backing-right", type=number, default=None, metavar="M",
                   help="backing height above the right springing, m, when it differs "
                        "(--backing is then the left one's)")
    g.add_argument("--point-load", type=point_load, action="append", default=None,
                   metavar="POS,KN[,still]",
                   help="a vertical load on the extrados (a wall, a truss), kN per m of width, "
                        "at POS m; its mass moves with the arch in an earthquake unless 'still' "
                        "is added (repeat for more loads)")
    g.add_argument("--distributed-load", type=distributed_load, action="append", default=None,
                   metavar="START,END,KN_M[,still]",
                   help="a uniform vertical load on the extrados from START to END m, kN/m per m "
                        "of width ('still' as for --point-load; repeatable)")
    g.add_argument("--passive", type=number, default=None, metavar="FRACTION",
                   help="passive fill pressure where the arch sways into the fill: the "
                        "mobilised fraction of Rankine's K_p, in (0, 1] (default: off; "
                        "Grandjean takes 0.33)")
    g.add_argument("--fill-friction", type=number, default=None, metavar="DEG",
                   help="the fill's friction angle for --passive, degrees, in [0, 60) "
                        "(default 30)")
    if not traffic:
        return
    t = parser.add_argument_group("traffic (kN per metre of barrel width)")
    t.add_argument("--axle", type=number, default=None, metavar="KN",
                   help=f"an axle (line) load, kN per m of width (> 0, <= {MAX_LOAD_KN:g})")
    t.add_argument("--patch", type=number, default=None, metavar="KN",
                   help="a patch load, kN per m of width in all, over --patch-length")
    t.add_argument("--patch-length", type=number, default=None, metavar="M",
                   help="length of the --patch along the span, m (> 0)")
    t.add_argument("--dispersion", type=dispersion, default=None, metavar="DEG|boussinesq",
                   help="spread the traffic through the fill at this angle from the vertical, "
                        f"degrees (0 to {MAX_DISPERSION_DEG:g}; 26.57 is the 2:1 slope, 30 "
                        "Grandjean's), or 'boussinesq': Flamant's elastic stress at the "
                        "extrados's depth, all of it on the arch (default: no spread)")


def loads_from_args(args: argparse.Namespace) -> Loads | None:
    """The loads of `add_loads_arguments` (None when none is given), each value checked in
    one line naming its option."""
    fill = None
    depth, level = args.fill_depth, args.fill_level
    if depth is not None and level is not None:
        raise InvalidParameterError("give --fill-depth or --fill-level, not both")
    density = args.fill_density
    if density is not None:
        if depth is None and level is None:
            raise InvalidParameterError("--fill-density applies to a fill: add --fill-depth")
        check_range("--fill-density", density, 0.0, 1e5, "kg/m^3")
    if depth is not None:
        check_range("--fill-depth", depth, 0.0, MAX_LOAD_LENGTH_M, "m")
        fill = Fill(depth=depth, density=1800.0 if density is None else density)
    elif level is not None:
        check_range("--fill-level", level, -MAX_LOAD_LENGTH_M, MAX_LOAD_LENGTH_M, "m")
        fill = Fill(level=level, density=1800.0 if density is None else density)
    backing = None
    if args.backing_right is not None and args.backing is None:
        raise InvalidParameterError("--backing-right needs --backing (the left one's height)")
    if args.backing is not None:
        check_range("--backing", args.backing, 0.0, MAX_LOAD_LENGTH_M, "m")
        if args.backing_right is not None:
            check_range("--backing-right", args.backing_right, 0.0, MAX_LOAD_LENGTH_M, "m")
        backing = Backing(args.backing, args.backing_right)
    points = []
    for (pos, kn), still in args.point_load or ():
        check_range("--point-load position", pos, 0.0, MAX_LOAD_LENGTH_M, "m")
        check_range("--point-load load", kn, -MAX_LOAD_KN, MAX_LOAD_KN, "kN")
        points.append(PointLoad(pos, kn * 1e3, not still))
    spread = []
    for (a, b, kn), still in args.distributed_load or ():
        check_range("--distributed-load start", a, 0.0, MAX_LOAD_LENGTH_M, "m")
        check_range("--distributed-load end", b, a, MAX_LOAD_LENGTH_M, "m", low_open=True)
        check_range("--distributed-load load", kn, -MAX_LOAD_KN, MAX_LOAD_KN, "kN/m")
        spread.append(DistributedLoad(a, b, kn * 1e3, not still))
    passive = None
    if args.fill_friction is not None and args.passive is None:
        raise InvalidParameterError("--fill-friction applies to --passive")
    if args.passive is not None:
        if fill is None:
            raise InvalidParameterError("--passive needs a fill: add --fill-depth")
        if fill.density == 0.0:
            raise InvalidParameterError("--passive needs a fill that weighs: --fill-density > 0")
        check_range("--passive", args.passive, 0.0, 1.0, "of K_p", low_open=True)
        phi = 30.0 if args.fill_friction is None else args.fill_friction
        check_range("--fill-friction", phi, 0.0, 60.0, "degrees", high_open=True)
        passive = Passive(args.passive, phi)
    loads = Loads(fill, backing, tuple(points), tuple(spread), None, passive)
    return None if loads.empty else loads


def check_loads_on(arch, loads: Loads | None) -> None:
    """Check ``loads`` against ``arch``, each problem one line naming the option as typed."""
    if loads is None:
        return
    from archquake.geometry.loads import Extrados

    try:
        ex = Extrados.of(arch)
    except InvalidParameterError as exc:
        given = "--pier-height" if "piers" in str(exc) else "--embrace"
        raise InvalidParameterError(f"{given}: {exc}") from None
    span = ex.clear_span
    hint = f"positions run along the clear span, {span:.4g} m, from the left intrados springing"
    for p in loads.point_loads:
        check_range("--point-load position", p.position, 0.0, span, "m", hint=hint)
    for d in loads.distributed_loads:
        check_range("--distributed-load start", d.start, 0.0, span, "m", hint=hint)
        check_range("--distributed-load end", d.end, 0.0, span, "m", hint=hint)
    if loads.fill is not None and loads.fill.level is not None:
        top = float(max(arch.extrados_points[:, 1].max(), arch.crown_point[1]))
        check_range("--fill-level", loads.fill.level, top, MAX_LOAD_LENGTH_M, "m",
                    hint="the fill surface lies at or above the extrados's highest point")


def passive_text(loads: Loads | None) -> str:
    """How the passive fill pressure was taken, for the text outputs."""
    if loads is None or loads.passive is None:
        return "passive fill pressure off"
    p = loads.passive
    return (f"passive fill pressure {p.fraction:g} K_p (fill friction {p.friction:g} deg, "
            f"K_p = {p.kp:.3f}) where the arch moves into the fill")


def traffic_from_args(args: argparse.Namespace, position: float = 0.0) -> Traffic:
    """The traffic of `add_loads_arguments` (``traffic=True``), at ``position`` m."""
    if (args.axle is None) == (args.patch is None):
        raise InvalidParameterError("give the traffic load: --axle KN or --patch KN with "
                                    "--patch-length M (kN per m of barrel width)")
    if args.axle is not None:
        if args.patch_length is not None:
            raise InvalidParameterError("--patch-length applies to --patch, not to --axle")
        check_range("--axle", args.axle, 0.0, MAX_LOAD_KN, "kN per m of width", low_open=True)
        load, length = args.axle, 0.0
    else:
        check_range("--patch", args.patch, 0.0, MAX_LOAD_KN, "kN per m of width", low_open=True)
        if args.patch_length is None:
            raise InvalidParameterError("--patch needs --patch-length M (m, > 0)")
        check_range("--patch-length", args.patch_length, 0.0, MAX_LOAD_LENGTH_M, "m",
                    low_open=True)
        load, length = args.patch, args.patch_length
    if args.dispersion == "boussinesq":
        return Traffic(load * 1e3, position, length, None, True)
    if args.dispersion is not None:
        check_range("--dispersion", args.dispersion, 0.0, MAX_DISPERSION_DEG, "degrees")
    return Traffic(load * 1e3, position, length, args.dispersion)


def print_loads(assembly: dict) -> None:
    """The text lines of what a model's arch carries, read from its ``masses`` (an assembly's
    ``to_dict()``, or a run's JSON; nothing for a bare arch)."""
    masses = assembly.get("masses")
    if masses is None:
        return
    held = masses["held_by_backing"]
    print(f"carried mass        {masses['carried_mass_kg']:.6g} kg on "
          f"{masses['masonry_mass_kg']:.6g} kg of masonry (fill columns and moving loads, at "
          "their centroids)"
          + (f"; voussoirs {', '.join(map(str, held))} held by the backing" if held else ""))
    print(f"passive pressure    {masses['passive_pressure']}")


def dynamic_loads_from_args(args: argparse.Namespace, arch, model, *, fourlink: bool = False):
    """The loads of the command line for a dynamic ``model`` (None without), checked against
    ``arch``; the four-link model refuses them in one line unless ``fourlink`` (the commands
    that carry them on its links)."""
    from archquake.models import spec

    loads = loads_from_args(args)
    if loads is None:
        return None
    check_loads_on(arch, loads)
    if not spec(model).blocks and not fourlink:  # the four-link model's links
        raise InvalidParameterError(
            "--model fourlink does not carry fill, backing or loads in this command: use "
            "--model rigid (the default)")
    if loads.passive is not None:
        from archquake.blocks.assembly import PASSIVE_LEFT_OUT

        raise InvalidParameterError(f"--passive: {PASSIVE_LEFT_OUT}; leave it out")
    if any(not p.moves_with_arch for p in loads.point_loads):
        raise InvalidParameterError("--point-load ...,still: a weight without mass is statics "
                                    "only; the dynamic models carry loads that move with the arch")
    if any(not d.moves_with_arch for d in loads.distributed_loads):
        raise InvalidParameterError("--distributed-load ...,still: a weight without mass is "
                                    "statics only; the dynamic models carry loads that move with "
                                    "the arch")
    return loads


__all__ = ["add_loads_arguments", "check_loads_on", "dynamic_loads_from_args", "loads_from_args",
           "passive_text", "print_loads", "traffic_from_args"]
