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

from archquake._json import to_jsonable
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import (
    MAX_DENSITY,
    MAX_DEPTH,
    MAX_EMBRACE_DEG,
    MAX_VOUSSOIRS,
    RADIUS_RANGE,
    Arch,
)
from archquake.ground import GroundMotion, Record, SinePulse, StepImpulse, read_record
from archquake.ground.records import UNITS


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


#: Oppenheim's arch, the default when no shape option is given (m, degrees).
OPPENHEIM_DEFAULTS = {"radius": 10.0, "thickness": 1.5, "embrace": 157.5, "voussoirs": 7}


def add_arch_arguments(parser: argparse.ArgumentParser, *, defaults: bool = True) -> None:
    """The arch: a shape (--shape, --span, --rise, --thickness, --voussoirs, --joints; circular
    arches also by --radius and --embrace), optional piers (--pier-height, --pier-width,
    --pier-courses), or blocks from a file (--blocks); --depth and --density.

    With no shape option the arch is Oppenheim's (R = 10 m, t = 1.5 m, 157.5 degrees,
    7 voussoirs; ``defaults=False`` leaves it unset).
    """
    from archquake.geometry.shapes import JOINTS, SHAPES

    g = parser.add_argument_group(
        "arch (lengths in m, angles in degrees; default: Oppenheim's arch, R = 10 m, t = 1.5 m, "
        "157.5 deg, 7 voussoirs)")
    g.add_argument("--shape", choices=SHAPES, default=None,
                   help="arch shape (default circular); every shape but circular-by-radius takes "
                        "--span and --rise of the centreline")
    g.add_argument("--span", type=number, default=None,
                   help="centreline span between the springings, m (> 0)")
    g.add_argument("--rise", type=number, default=None,
                   help="centreline rise from the springing line to the crown, m (> 0; <= span/2 "
                        "for segmental, >= span/2 for pointed, < span/2 for three-centred)")
    g.add_argument("--eccentricity", type=number, default=None,
                   help="pointed arch instead of --rise: distance of the two centres from the axis "
                        "over the half-span (0 semicircle, 1 equilateral, < 1 drop, > 1 lancet)")
    g.add_argument("--radius", type=number, default=None,
                   help=f"circular arch: centreline radius R, m ({RADIUS_RANGE[0]:g} to "
                        f"{RADIUS_RANGE[1]:g}; default 10)")
    g.add_argument("--thickness", type=number, default=None,
                   help="ring thickness t, m (0 < t < 2R; default 1.5 for the default arch)")
    g.add_argument("--embrace", type=number, default=None,
                   help=f"circular arch: angle of embrace, degrees (0 < embrace <= "
                        f"{MAX_EMBRACE_DEG:g}; default 157.5)")
    g.add_argument("--voussoirs", type=whole, default=None,
                   help=f"number of voussoirs (3 to {MAX_VOUSSOIRS}; default 7)")
    g.add_argument("--joints", choices=JOINTS, default="radial",
                   help="joints normal to the centreline (radial, default) or vertical")
    g.add_argument("--pier-height", type=number, default=None,
                   help="piers under the springings: height from the rigid base to the intrados "
                        "springing, m (> 0; with --pier-width)")
    g.add_argument("--pier-width", type=number, default=None,
                   help="pier width, m (at least the springing joint's horizontal extent)")
    g.add_argument("--pier-courses", type=whole, default=None,
                   help="number of courses (blocks) in each pier (1 to 500; default 1)")
    g.add_argument("--blocks", type=Path, default=None, metavar="FILE",
                   help="the arch's blocks from a surveyed file: .json, .csv or .dxf (see "
                        "docs/geometry.md)")
    g.add_argument("--depth", type=number, default=1.0, help="out-of-plane depth, m (default 1)")
    g.add_argument("--density", type=number, default=2000.0,
                   help="density, kg/m^3 (default 2000)")
    parser.set_defaults(_arch_defaults=defaults)


def _given(args: argparse.Namespace, *names: str) -> list[str]:
    return ["--" + n.replace("_", "-") for n in names if getattr(args, n, None) is not None]


def arch_from_args(args: argparse.Namespace):
    """Build the arch (any :class:`~archquake.geometry.VoussoirChain`) from the options of
    :func:`add_arch_arguments`; every inconsistent combination is one line naming the option."""
    from archquake.geometry import OnPiers, Piers
    from archquake.geometry.shapes import ShapedArch, pointed

    if not 0 < args.depth <= MAX_DEPTH:
        raise InvalidParameterError(f"--depth must be in (0, {MAX_DEPTH:g}] m, got {args.depth:g}")
    if not 0 < args.density <= MAX_DENSITY:
        raise InvalidParameterError(
            f"--density must be in (0, {MAX_DENSITY:g}] kg/m^3, got {args.density:g}")
    shape = getattr(args, "shape", None)
    blocks = getattr(args, "blocks", None)
    joints = getattr(args, "joints", "radial") or "radial"
    if blocks is not None:
        clash = _given(args, "shape", "span", "rise", "eccentricity", "radius", "embrace",
                       "thickness", "voussoirs")
        if clash:
            raise InvalidParameterError(f"--blocks gives the whole geometry; drop {', '.join(clash)}")
        from archquake.geometry.survey import read_blocks

        arch = read_blocks(blocks, depth=args.depth, density=args.density)
    elif shape in (None, "circular") and (getattr(args, "span", None) is None
                                          and getattr(args, "rise", None) is None):
        if _given(args, "eccentricity"):
            raise InvalidParameterError("--eccentricity applies to --shape pointed")
        arch = _circular_from_args(args, joints)
    else:
        shape = shape or "circular"
        clash = _given(args, "radius", "embrace")
        if clash:
            raise InvalidParameterError(
                f"{', '.join(clash)} apply to a circular arch given by radius and embrace; a "
                f"{shape} arch takes --span and --rise")
        if args.span is None:
            raise InvalidParameterError(f"a {shape} arch needs --span (m)")
        if args.thickness is None:
            raise InvalidParameterError(f"a {shape} arch needs --thickness (m)")
        voussoirs = 7 if args.voussoirs is None else args.voussoirs
        if shape == "pointed" and args.eccentricity is not None:
            if args.rise is not None:
                raise InvalidParameterError("give --rise or --eccentricity, not both")
            arch = pointed(span=args.span, eccentricity=args.eccentricity, thickness=args.thickness,
                           voussoirs=voussoirs, joints=joints, depth=args.depth,
                           density=args.density)
        else:
            if _given(args, "eccentricity"):
                raise InvalidParameterError("--eccentricity applies to --shape pointed")
            if args.rise is None:
                raise InvalidParameterError(f"a {shape} arch needs --rise (m)")
            arch = ShapedArch(shape, args.span, args.rise, args.thickness, voussoirs, joints,
                              args.depth, args.density)
            if shape in ("circular", "segmental") and joints == "radial":
                r, beta = arch._circle()
                arch = Arch(r, args.thickness, beta, voussoirs, args.depth, args.density)
    height, width = getattr(args, "pier_height", None), getattr(args, "pier_width", None)
    courses = getattr(args, "pier_courses", None)
    if height is None and width is None:
        if courses is not None:
            raise InvalidParameterError("--pier-courses needs --pier-height and --pier-width")
        return arch
    if height is None or width is None:
        raise InvalidParameterError("piers need both --pier-height and --pier-width (m)")
    return OnPiers(arch, Piers(height, width, 1 if courses is None else courses))


def _circular_from_args(args: argparse.Namespace, joints: str):
    """The circular arch by radius and embrace (Oppenheim's by default), checking the
    degree-valued embrace here so the message is in degrees."""
    use = OPPENHEIM_DEFAULTS if getattr(args, "_arch_defaults", True) else {}
    values = {k: getattr(args, k) if getattr(args, k) is not None else use.get(k)
              for k in ("radius", "thickness", "embrace", "voussoirs")}
    missing = [k for k, v in values.items() if v is None]
    if missing:
        raise InvalidParameterError(
            f"a circular arch needs {', '.join('--' + k for k in missing)}")
    radius, thickness, embrace, voussoirs = (values[k] for k in ("radius", "thickness", "embrace",
                                                                  "voussoirs"))
    if not (0.0 < embrace <= MAX_EMBRACE_DEG):
        raise InvalidParameterError(
            f"--embrace must be in (0, {MAX_EMBRACE_DEG:g}] degrees, got {embrace:g}"
        )
    if voussoirs < 3 or voussoirs > MAX_VOUSSOIRS:
        raise InvalidParameterError(
            f"--voussoirs must be a whole number from 3 to {MAX_VOUSSOIRS}, got {voussoirs}"
        )
    low, high = RADIUS_RANGE
    if not low <= radius <= high:
        raise InvalidParameterError(f"--radius must be in [{low:g}, {high:g}] m, got {radius:g}")
    if thickness <= 0 or thickness >= 2 * radius:
        raise InvalidParameterError(
            f"--thickness must be in (0, 2 x radius) = (0, {2 * radius:g}) m, "
            f"got {thickness:g}"
        )
    if joints == "vertical":
        from archquake.geometry.shapes import circular

        return circular(radius=radius, embrace=math.radians(embrace), thickness=thickness,
                        voussoirs=voussoirs, joints=joints, depth=args.depth, density=args.density)
    return Arch(
        radius=radius,
        thickness=thickness,
        embrace=math.radians(embrace),
        voussoirs=voussoirs,
        depth=args.depth,
        density=args.density,
    )


def describe_arch(arch) -> str:
    """One line describing any arch for the text output (m, degrees)."""
    d = arch.describe()
    if "radius_m" in d and "shape" not in d:
        text = (f"R = {d['radius_m']:g} m, t = {d['thickness_m']:g} m (t/R = "
                f"{d['thickness_ratio']:.4g}), embrace {d['embrace_deg']:g} deg, "
                f"{d['voussoirs']} voussoirs")
    else:
        text = (f"{d.get('shape', 'blocks')}, span {d['span_m']:.4g} m, rise {d['rise_m']:.4g} m, "
                f"t = {d['thickness_m']:.4g} m, {d['voussoirs']} voussoirs"
                + (f", {d['joints']} joints" if "joints" in d else ""))
    if "pier_height_m" in d:
        text += (f", on piers {d['pier_height_m']:g} m high x {d['pier_width_m']:g} m wide "
                 f"({d['pier_courses']} courses)")
    return text


def add_impact_arguments(parser: argparse.ArgumentParser) -> None:
    """--restitution and --impact: the impact of the analytical model (every command that runs a
    time history; :func:`impact_from_args` reads them)."""
    from archquake.mechanism.impact import IMPACT_LAWS

    g = parser.add_argument_group("impact (analytical model)")
    g.add_argument("--restitution", type=number, default=None, metavar="CV",
                   help="prescribe the coefficient of restitution c_v on the angular velocity, "
                        "in [0, 1] (0 = perfectly plastic), instead of the impact law's")
    g.add_argument("--impact", choices=IMPACT_LAWS, default=None,
                   help="impact law: 'paper' (the paper's Eq. 4, default), 'chain' (chain of "
                        "rigid voussoirs: maximum restitution, never creates energy) or 'mirror' "
                        "(chain law, mirror mechanism forced); see docs/mechanism.md")


def impact_from_args(args: argparse.Namespace) -> dict[str, Any]:
    """``{"restitution": c_v or None, "impact": law or None}`` from :func:`add_impact_arguments`'s
    options, checked (one line naming --restitution and its range)."""
    from archquake.mechanism.impact import check_restitution

    return {"restitution": check_restitution(getattr(args, "restitution", None), "--restitution"),
            "impact": getattr(args, "impact", None)}


def impact_line(law: str, validity: str, described: bool, prescribed: bool = False) -> str:
    """One line of text: the impact law, its validity and what that means for the verdict."""
    from archquake.mechanism.impact import VALIDITY_MEANING

    meaning = VALIDITY_MEANING.get(validity, "")
    if not described:
        verdict = "; verdicts reached after an impact are indeterminate"
    elif prescribed and law == "paper" and validity == "outside":
        verdict = "; the prescribed c_v replaces Eq. 4's, and verdicts rest on that assumption"
    else:
        verdict = ""
    return f"impact law          {law}, validity {validity}: {meaning}{verdict}"


def add_output_arguments(parser: argparse.ArgumentParser, *, plot: bool = True) -> None:
    parser.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    if plot:
        parser.add_argument("--plot", metavar="FILE", type=Path,
                            help="draw the result to FILE (.png, .pdf or .svg)")


def quiet_dask() -> None:
    """Keep Dask's own log lines (tracebacks from its client thread when a scheduler or worker
    goes away) off the user's terminal: archquake reports a lost cluster in one line."""
    import logging

    try:
        import distributed  # noqa: F401  (configures its loggers on import: quiet them after)
    except ImportError:
        return
    prefixes = ("distributed", "tornado", "asyncio")
    names = [n for n in logging.root.manager.loggerDict if n.split(".")[0] in prefixes]
    for name in (*prefixes, *names):
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)


def print_json(obj: Any) -> None:
    json.dump(to_jsonable(obj), sys.stdout, indent=2, allow_nan=False)
    sys.stdout.write("\n")



#: Units the CLI accepts for a CSV record's acceleration column (the default is g).
RECORD_UNITS = UNITS


def add_ground_motion_arguments(parser: argparse.ArgumentParser) -> None:
    """--pulse, --magnitude (g), --duration, --period, --record, --units, --scale, --mirror."""
    grp = parser.add_argument_group(
        "excitation (a pulse or a record; accelerations in g; a pulse's first lobe is a ground "
        "acceleration towards -x, which drives the paper's first mechanism)"
    )
    grp.add_argument("--pulse", choices=("step", "sine"),
                     help="analytical pulse: 'step' = Oppenheim's step impulse (a for t_p, then "
                          "-a/2 for 2 t_p), 'sine' = one cycle of a sin(2 pi t/T); the first lobe "
                          "is a ground acceleration towards -x (see --mirror)")
    grp.add_argument("--magnitude", type=number, metavar="A",
                     help="pulse magnitude a, in g (>= 0)")
    grp.add_argument("--duration", type=number, metavar="TP",
                     help="step impulse: duration t_p of the first lobe, s (> 0)")
    grp.add_argument("--period", type=number, metavar="T",
                     help="sine pulse: period T, s (> 0)")
    grp.add_argument("--record", type=Path, metavar="FILE",
                     help="recorded accelerogram: PEER .AT2 (in g) or .csv/.txt with two columns "
                          "time (s), acceleration (units from --units); positive = towards +x")
    grp.add_argument("--units", choices=RECORD_UNITS, default=None,
                     help="units of a CSV record's acceleration column (default g; .AT2 files "
                          "are always in g)")
    grp.add_argument("--scale", type=number, metavar="S",
                     help="factor applied to every value of the record (> 0; default 1)")
    grp.add_argument("--mirror", action="store_true",
                     help="reverse the excitation: pulses start towards +x instead of -x; a "
                          "record is multiplied by -1")


def record_from_args(path: Path, units: str | None, scale: float | None, *,
                     g: float = STANDARD_GRAVITY, dt: float | None = None) -> Record:
    """Read a record given on the command line: CSV units default to g here (and only here,
    where ``--help`` says so); ``--scale`` must be > 0 (``--mirror`` reverses a record);
    ``--dt`` (s, > 0) is the step of a one-column text file."""
    scale = 1.0 if scale is None else scale
    if scale <= 0:
        raise InvalidParameterError(
            f"--scale must be > 0, got {scale:g}; use --mirror to reverse the record"
        )
    if dt is not None and dt <= 0:
        raise InvalidParameterError(f"--dt must be > 0 s, got {dt:g}")
    if units is None and path.suffix.lower() in (".csv", ".txt"):
        units = "g"
    return read_record(path, units=units, dt=dt, scale=scale, g=g)


def ground_motion_from_args(args: argparse.Namespace, *,
                            g: float = STANDARD_GRAVITY) -> GroundMotion:
    """Build the excitation chosen by :func:`add_ground_motion_arguments` (g -> m/s^2 here).

    Every option that does not apply to the chosen excitation is an error rather than being
    silently ignored.
    """
    pulse, record = args.pulse, args.record
    if pulse is not None and record is not None:
        raise InvalidParameterError("--record excludes --pulse: choose a pulse or a record")
    if pulse is None and record is None:
        raise InvalidParameterError(
            "no excitation: give --pulse step|sine with --magnitude, or --record FILE"
        )
    if record is not None:
        for option in ("magnitude", "duration", "period"):
            if getattr(args, option) is not None:
                raise InvalidParameterError(
                    f"--{option} applies to --pulse, not to --record; scale a record with --scale"
                )
        motion = record_from_args(record, args.units, args.scale, g=g)
        return motion.mirrored() if args.mirror else motion
    for option in ("units", "scale"):
        if getattr(args, option) is not None:
            raise InvalidParameterError(
                f"--{option} applies to --record, not to --pulse; set the pulse with --magnitude"
            )
    if args.magnitude is None:
        raise InvalidParameterError(f"--pulse {pulse} needs --magnitude A (g, >= 0)")
    if args.magnitude < 0:
        raise InvalidParameterError(
            f"--magnitude must be >= 0 g, got {args.magnitude:g}; use --mirror to reverse the pulse"
        )
    direction = 1 if args.mirror else -1
    if pulse == "step":
        if args.period is not None:
            raise InvalidParameterError("--period applies to --pulse sine; the step impulse "
                                        "takes --duration TP (s)")
        if args.duration is None:
            raise InvalidParameterError("--pulse step needs --duration TP (s, > 0): the length "
                                        "t_p of its first lobe")
        if args.duration <= 0:
            raise InvalidParameterError(f"--duration must be > 0 s, got {args.duration:g}")
        return StepImpulse.from_g(args.magnitude, args.duration, direction, g=g)
    if args.duration is not None:
        raise InvalidParameterError("--duration applies to --pulse step; the sine pulse takes "
                                    "--period T (s)")
    if args.period is None:
        raise InvalidParameterError("--pulse sine needs --period T (s, > 0)")
    if args.period <= 0:
        raise InvalidParameterError(f"--period must be > 0 s, got {args.period:g}")
    return SinePulse.from_g(args.magnitude, args.period, direction, g=g)


def parse_durations(text: str) -> np.ndarray:
    """argparse type: ``START:STOP:COUNT`` (s) to COUNT evenly spaced durations, or one duration."""
    try:
        return _durations(text)
    except InvalidParameterError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _durations(text: str) -> np.ndarray:
    parts = text.split(":")
    if len(parts) == 1:
        try:
            single = float(parts[0])
        except ValueError:
            single = math.nan
        return _positive(np.array([single]), text)
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InvalidParameterError(
            f"expected START:STOP:COUNT in s (e.g. 0.05:1.5:40) or one duration, got {text!r}"
        ) from None
    if count < 1:
        raise InvalidParameterError(f"COUNT must be >= 1 in START:STOP:COUNT, got {text!r}")
    if count > 1 and not stop > start:
        raise InvalidParameterError(f"STOP must exceed START in START:STOP:COUNT, got {text!r}")
    return _positive(np.linspace(start, stop, count), text)


def _positive(values: np.ndarray, text: str) -> np.ndarray:
    if not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise InvalidParameterError(f"durations must be finite and > 0 s, got {text!r}")
    return values



__all__ = [
    "add_arch_arguments",
    "add_ground_motion_arguments",
    "add_output_arguments",
    "arch_from_args",
    "describe_arch",
    "ground_motion_from_args",
    "number",
    "parse_durations",
    "print_json",
    "record_from_args",
    "to_jsonable",
    "whole",
]
