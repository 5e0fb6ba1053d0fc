"""Arguments shared by sub-commands and their conversion to library objects (degrees and g
are converted here, at the edge)."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.arch import MAX_EMBRACE, MAX_VOUSSOIRS, Arch

MAX_EMBRACE_DEG = math.degrees(MAX_EMBRACE)


def number(text: str) -> float:
    """argparse type: a finite float (the parser names the option on failure)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def whole(text: str) -> int:
    """argparse type: an integer."""
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None


def add_arch_arguments(parser: argparse.ArgumentParser, *, defaults: bool = True) -> None:
    """--radius, --thickness, --embrace (degrees), --voussoirs, --depth, --density.

    Defaults are Oppenheim's arch (R = 10 m, t = 1.5 m, 157.5 degrees, 7 voussoirs).
    """
    g = parser.add_argument_group("arch (defaults: Oppenheim's arch)")
    g.add_argument("--radius", type=number, default=10.0 if defaults else None,
                   help="centreline radius R, m (> 0; default 10)")
    g.add_argument("--thickness", type=number, default=1.5 if defaults else None,
                   help="thickness t, m (0 < t < 2R; default 1.5)")
    g.add_argument("--embrace", type=number, default=157.5 if defaults else None,
                   help=f"angle of embrace, degrees (0 < embrace <= {MAX_EMBRACE_DEG:g}; default 157.5)")
    g.add_argument("--voussoirs", type=whole, default=7 if defaults else None,
                   help=f"number of voussoirs (3 to {MAX_VOUSSOIRS}; default 7)")
    g.add_argument("--depth", type=number, default=1.0, help="out-of-plane depth, m (default 1)")
    g.add_argument("--density", type=number, default=2000.0,
                   help="density, kg/m^3 (default 2000)")


def arch_from_args(args: argparse.Namespace) -> Arch:
    """Build the Arch, checking the degree-valued embrace here so the message is in degrees."""
    embrace = args.embrace
    if not (0.0 < embrace <= MAX_EMBRACE_DEG):
        raise InvalidParameterError(
            f"--embrace must be in (0, {MAX_EMBRACE_DEG:g}] degrees, got {embrace:g}"
        )
    if args.voussoirs < 3 or args.voussoirs > MAX_VOUSSOIRS:
        raise InvalidParameterError(
            f"--voussoirs must be a whole number from 3 to {MAX_VOUSSOIRS}, got {args.voussoirs}"
        )
    if args.radius <= 0:
        raise InvalidParameterError(f"--radius must be > 0 m, got {args.radius:g}")
    if args.thickness <= 0 or args.thickness >= 2 * args.radius:
        raise InvalidParameterError(
            f"--thickness must be in (0, 2 x radius) = (0, {2 * args.radius:g}) m, "
            f"got {args.thickness:g}"
        )
    return Arch(
        radius=args.radius,
        thickness=args.thickness,
        embrace=math.radians(embrace),
        voussoirs=args.voussoirs,
        depth=args.depth,
        density=args.density,
    )


def add_output_arguments(parser: argparse.ArgumentParser, *, plot: bool = True) -> None:
    parser.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    if plot:
        parser.add_argument("--plot", metavar="FILE", type=Path,
                            help="draw the result to FILE (.png, .pdf or .svg)")


def to_jsonable(obj: Any) -> Any:
    """Numpy arrays and scalars to lists and floats; NaN and inf to None (valid JSON)."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    if hasattr(obj, "value") and hasattr(obj, "name"):  # Enum
        return obj.value
    return obj


def print_json(obj: Any) -> None:
    json.dump(to_jsonable(obj), sys.stdout, indent=2, allow_nan=False)
    sys.stdout.write("\n")


__all__ = [
    "add_arch_arguments",
    "add_output_arguments",
    "arch_from_args",
    "number",
    "print_json",
    "to_jsonable",
    "whole",
]
