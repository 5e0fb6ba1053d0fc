"""Arguments shared by sub-commands and their conversion to library objects (degrees and g
are converted here, at the edge)."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

from archquake._json import to_jsonable
from archquake._validate import check_range, check_whole  # noqa: F401  (the CLI's wording)
from archquake.cli.input_warnings import warn_input, warn_pga
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.checks import (  # the one place where an arch is checked
    MAX_DENSITY,
    MAX_DEPTH,
    MAX_EMBRACE_DEG,
    MAX_VOUSSOIRS,
    MIN_DENSITY,
    MIN_DEPTH,
    OPTIONS,
    RADIUS_RANGE,
    check_density,
    check_depth,
    check_embrace_deg,
    check_piers,
    check_radius,
    check_thickness,
    check_voussoirs,
)
from archquake.ground import GroundMotion, Record, SinePulse, StepImpulse, read_record
from archquake.ground.base import check_lift_off, check_motion_lift_off
from archquake.ground.periods import check_periods, period_grid
from archquake.ground.pulses import MAX_VERTICAL_RATIO
from archquake.ground.records import UNITS
from archquake.ranges import (  # the one place of every range
    FIGURE_SUFFIXES,
    MAGNITUDE_RANGE_G,
    MAX_DURATIONS,
    PLAUSIBLE_PGA_G,
    PLAUSIBLE_PULSE_S,
    PLAUSIBLE_RADIUS_M,
    PULSE_TIME_RANGE_S,
    RADIANS_EMBRACE_DEG,
    RECORD_DT_RANGE_S,
    SCALE_RANGE,
    T_END_RANGE_S,
)


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


# ---------------------------------------------------------------------------------------------
# Checks of a value against its range (archquake.ranges), named as the user typed the option
# (archquake._validate.check_range and check_whole; the arch's in archquake.geometry.checks).
# ---------------------------------------------------------------------------------------------


def ranged(low: float, high: float, unit: str = "", *, low_open: bool = False,
           high_open: bool = False, hint: str = ""):
    """argparse type: a finite number in a range (argparse names the option on failure)."""

    def parse(text: str) -> float:
        value = number(text)
        try:
            return check_range("value", value, low, high, unit, low_open=low_open,
                               high_open=high_open, hint=hint)
        except InvalidParameterError as exc:
            raise argparse.ArgumentTypeError(str(exc).replace("value must", "must", 1)) from None

    parse.__name__ = "number"
    return parse


def ranged_whole(low: int, high: int, hint: str = ""):
    """argparse type: a whole number from ``low`` to ``high``."""

    def parse(text: str) -> int:
        value = whole(text)
        try:
            return check_whole("value", value, low, high, hint)
        except InvalidParameterError as exc:
            raise argparse.ArgumentTypeError(str(exc).replace("value must", "must", 1)) from None

    parse.__name__ = "whole number"
    return parse


def comma_numbers(text: str, count: int | None, what: str) -> list[float]:
    """``A,B,...``: finite numbers, no empty item; exactly ``count`` of them when given."""
    items = text.split(",")
    if any(not item.strip() for item in items):
        raise argparse.ArgumentTypeError(f"empty item in {text!r}: expected {what}")
    try:
        values = [float(item) for item in items]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
    if not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected finite numbers ({what}), got {text!r}")
    if count is not None and len(values) != count:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
    return values


# ---------------------------------------------------------------------------------------------
# Output paths: checked when the command line is parsed, before any computation.
# ---------------------------------------------------------------------------------------------


def check_output_file(path: Path, suffixes: tuple[str, ...] | None, *,
                      create_parents: bool = False) -> Path:
    """``path`` as a file this command can write, or `InvalidParameterError` saying why.

    Refused: an empty name, an existing directory, a suffix outside ``suffixes`` (None: any),
    a parent folder that does not exist (unless ``create_parents``: then the nearest existing
    ancestor must be a folder), a place the process cannot write. The path is written exactly
    as given: no suffix is added.
    """
    text = str(path)
    if not text.strip() or text.endswith(("/", "\\")) or path.name in ("", ".", ".."):
        raise InvalidParameterError(f"{text!r} is not a file name")
    if path.is_dir():
        raise InvalidParameterError(f"{text} is a directory; give a file name"
                                    + (f" ending in {_either(suffixes)}" if suffixes else ""))
    if suffixes is not None and path.suffix.lower() not in suffixes:
        raise InvalidParameterError(
            f"{text}: unknown file type {path.suffix or '(no suffix)'!r}; use {_either(suffixes)}")
    parent = path.parent
    if not parent.is_dir():
        if not create_parents:
            raise InvalidParameterError(f"{text}: folder {str(parent)!r} does not exist; create it first")
        ancestor = parent
        while not ancestor.exists() and ancestor != ancestor.parent:
            ancestor = ancestor.parent
        if not ancestor.is_dir():
            raise InvalidParameterError(f"{text}: {str(ancestor)!r} is a file, not a folder")
        _check_writable_folder(text, ancestor)
        return path
    if path.exists():
        if not os.access(path, os.W_OK):
            raise InvalidParameterError(f"{text}: the file is read-only")
        return path
    _check_writable_folder(text, parent)
    return path


def check_output_folder(path: Path, option: str = "") -> Path:
    """``path`` as a folder this command can create (with its parents) and write into
    (``option``, e.g. ``--out``, starts the message when given)."""
    try:
        return _check_output_folder(path)
    except InvalidParameterError as exc:
        if option:
            raise InvalidParameterError(f"{option}: {exc}") from None
        raise


def _check_output_folder(path: Path) -> Path:
    text = str(path)
    if not text.strip():
        raise InvalidParameterError(f"{text!r} is not a folder name")
    if path.exists() and not path.is_dir():
        raise InvalidParameterError(f"{text} is a file, not a folder")
    ancestor = path
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise InvalidParameterError(f"{text}: {str(ancestor)!r} is a file, not a folder")
    _check_writable_folder(text, ancestor)
    return path


def _check_writable_folder(text: str, folder: Path) -> None:
    """Create and remove a scratch file in ``folder`` (os.access is wrong for root, read-only
    mounts and /proc-like file systems)."""
    import tempfile

    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".archquake-probe-"):
            pass
    except OSError as exc:
        raise InvalidParameterError(
            f"{text}: cannot write in folder {str(folder)!r} ({exc.strerror or exc})") from None


def _either(suffixes: tuple[str, ...] | None) -> str:
    if not suffixes:
        return "any suffix"
    return ", ".join(suffixes[:-1]) + (" or " if len(suffixes) > 1 else "") + suffixes[-1]


def output_file(*suffixes: str, create_parents: bool = False):
    """argparse type: an output file checked by `check_output_file` at parse time, so a
    bad path fails before any computation (argparse names the option)."""

    def parse(text: str) -> Path:
        if not text.strip():  # Path("") is ".", the working folder
            raise argparse.ArgumentTypeError("an empty path is not a file name")
        try:
            return check_output_file(Path(text), suffixes or None, create_parents=create_parents)
        except InvalidParameterError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

    parse.__name__ = "file name"
    return parse


def path_argument(text: str) -> Path:
    """argparse type: a path that is not empty (``Path("")`` would be ".", the working folder)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty path is not a file name")
    return Path(text)


def output_folder(text: str) -> Path:
    """argparse type: an output folder checked by `check_output_folder`."""
    if not text.strip():  # Path("") is ".": the working folder would take the output
        raise argparse.ArgumentTypeError("an empty path is not a folder name")
    try:
        return check_output_folder(Path(text))
    except InvalidParameterError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def refuse_unless(options: dict[str, object], applies: bool, why: str) -> None:
    """Refuse every option of ``options`` (``{"--stiffness": args.stiffness, ...}``, None when
    not given) that the user gave although it does not apply (``applies`` False); ``why`` says
    what to do, e.g. "add --model dem"."""
    if applies:
        return
    given = [name for name, value in options.items() if value is not None and value is not False]
    if given:
        raise InvalidParameterError(f"{', '.join(given)} {'applies' if len(given) == 1 else 'apply'} "
                                    f"only {why}")


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
    g.add_argument("--blocks", type=path_argument, default=None, metavar="FILE",
                   help="the arch's blocks from a surveyed file: .json, .csv or .dxf (see "
                        "docs/geometry.md)")
    g.add_argument("--depth", type=number, default=1.0,
                   help=f"out-of-plane depth, m ({MIN_DEPTH:g} to {MAX_DEPTH:g}; default 1)")
    g.add_argument("--density", type=number, default=2000.0,
                   help=f"density, kg/m^3 ({MIN_DENSITY:g} to {MAX_DENSITY:g}; default 2000)")
    parser.set_defaults(_arch_defaults=defaults)


def _given(args: argparse.Namespace, *names: str) -> list[str]:
    return ["--" + n.replace("_", "-") for n in names if getattr(args, n, None) is not None]


def arch_from_args(args: argparse.Namespace):
    """Build the arch (any `VoussoirChain`) from the options of
    `add_arch_arguments`; every inconsistent combination is one line naming the option."""
    from archquake.geometry import OnPiers, Piers
    from archquake.geometry.shapes import ShapedArch, circular, pointed

    check_depth(args.depth, OPTIONS)
    check_density(args.density, OPTIONS)
    shape = getattr(args, "shape", None)
    blocks = getattr(args, "blocks", None)
    joints = getattr(args, "joints", "radial") or "radial"
    if blocks is not None:
        clash = _given(args, "shape", "span", "rise", "eccentricity", "radius", "embrace",
                       "thickness", "voussoirs")
        if clash:
            raise InvalidParameterError(f"--blocks gives the whole geometry; drop {', '.join(clash)}")
        from archquake.geometry.survey import read_blocks

        arch: VoussoirChain = read_blocks(blocks, depth=args.depth, density=args.density)
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
                # its circle, as the library builds it (the shape above checked the rise)
                arch = circular(span=args.span, rise=args.rise, thickness=args.thickness,
                                voussoirs=voussoirs, joints=joints, depth=args.depth,
                                density=args.density)
    height, width = getattr(args, "pier_height", None), getattr(args, "pier_width", None)
    courses = getattr(args, "pier_courses", None)
    if not check_piers(height, width, courses, OPTIONS):
        return arch
    assert height is not None and width is not None  # check_piers: both or neither
    return OnPiers(arch, Piers(height, width, 1 if courses is None else courses))


def _circular_from_args(args: argparse.Namespace, joints: str):
    """The circular arch by radius and embrace (Oppenheim's by default), checking the
    degree-valued embrace here so the message is in degrees."""
    use = OPPENHEIM_DEFAULTS if getattr(args, "_arch_defaults", True) else {}
    values: dict[str, Any] = {k: getattr(args, k) if getattr(args, k) is not None else use.get(k)
              for k in ("radius", "thickness", "embrace", "voussoirs")}
    missing = [k for k, v in values.items() if v is None]
    if missing:
        raise InvalidParameterError(
            f"a circular arch needs {', '.join('--' + k for k in missing)}")
    radius, thickness, embrace, voussoirs = (values[k] for k in ("radius", "thickness", "embrace",
                                                                  "voussoirs"))
    check_embrace_deg(embrace, OPTIONS)
    if getattr(args, "embrace", None) is not None and embrace <= RADIANS_EMBRACE_DEG:
        raise InvalidParameterError(
            f"--embrace {embrace:g} looks like radians ({math.degrees(embrace):.4g} degrees): "
            f"--embrace is in degrees, e.g. 180 for a semicircle (a ring flatter than "
            f"{RADIANS_EMBRACE_DEG:.3g} degrees is a beam)")
    check_voussoirs(voussoirs, OPTIONS)
    check_radius(radius, OPTIONS)
    if getattr(args, "radius", None) is not None and radius < PLAUSIBLE_RADIUS_M:
        warn_input("--radius", f"{radius:g} m is below {PLAUSIBLE_RADIUS_M:g} m, smaller than "
                               "any masonry arch: is it in m?")
    check_thickness(thickness, radius, OPTIONS)
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


#: What each model is, for the help of ``--model``.
MODEL_HELP = ("'rigid' (default), the chain of rigid voussoirs: hinges open, migrate and close "
              "anywhere, impacts follow from plastic contacts, no coefficient of restitution; "
              "'fourlink', the paper's four-link mechanism, hinges fixed between impacts, "
              "restitution from Eq. 4 or --restitution (fast); 'dem', the distinct-element "
              "model (see docs/models/choosing.md)")


def add_model_argument(parser: argparse.ArgumentParser, models: tuple[str, ...] = (),
                       extra: str = "") -> None:
    """``--model rigid|fourlink|dem`` (default rigid; ``models`` limits the choice), read by
    `model_from_args`. The retired ``--hinges`` stays hidden so that it gets a pointer to
    ``--model`` instead of argparse's bare 'unrecognized arguments'."""
    from archquake.models import Model

    names = models or tuple(m.value for m in Model)
    parser.add_argument("--model", default=None, metavar="{" + ",".join(names) + "}",
                        help=f"the model: {MODEL_HELP}" + (f"; {extra}" if extra else ""))
    parser.add_argument("--hinges", default=None, help=argparse.SUPPRESS)


def model_from_args(args: argparse.Namespace, models: tuple[str, ...] = ()):
    """The `Model` of ``--model`` (default rigid), with every
    model-specific option given to another model refused in one line: ``--impact`` and
    ``--restitution`` belong to fourlink, ``--integrator`` to rigid. ``args.model`` is set to
    the model's word. ``models`` limits the choice (a command that lacks one)."""
    from archquake.models import model_of, takes

    model = model_of(args.model, getattr(args, "hinges", None), model_name="--model",
                     hinges_name="--hinges")
    if models and model.value not in models:
        raise InvalidParameterError(f"--model must be {' or '.join(models)} here, got "
                                    f"{model.value!r}")
    refuse_unless({"--impact": getattr(args, "impact", None),
                   "--restitution": getattr(args, "restitution", None)},
                  takes(model, "restitution"),
                  f"to --model fourlink (with --model {model.value} the impacts follow from the "
                  "contacts): add --model fourlink, or leave it out")
    refuse_unless({"--integrator": getattr(args, "integrator", None)},
                  takes(model, "integrator"),
                  "to --model rigid (how the chain of rigid voussoirs is integrated): leave it "
                  "out")
    args.model = model.value
    return model


def add_impact_arguments(parser: argparse.ArgumentParser) -> None:
    """--restitution and --impact: the impact of the four-link model (every command that runs a
    time history; `impact_from_args` reads them)."""
    from archquake.ranges import IMPACT_LAWS

    g = parser.add_argument_group("impact (--model fourlink only)")
    g.add_argument("--restitution", type=number, default=None, metavar="CV",
                   help="prescribe the coefficient of restitution c_v on the angular velocity, "
                        "in [0, 1] (0 = perfectly plastic), instead of the impact law's")
    g.add_argument("--impact", choices=IMPACT_LAWS, default=None,
                   help="impact law: 'paper' (the paper's Eq. 4, default), 'chain' (chain of "
                        "rigid voussoirs: maximum restitution, never creates energy) or 'mirror' "
                        "(chain law, mirror mechanism forced); see docs/models/fourlink.md")


def impact_from_args(args: argparse.Namespace) -> dict[str, Any]:
    """``{"restitution": c_v or None, "impact": law or None}`` from `add_impact_arguments`'s
    options, checked (one line naming --restitution and its range)."""
    restitution = getattr(args, "restitution", None)
    if restitution is not None:  # (the four-link package is imported only to check one)
        from archquake.mechanism.impact import check_restitution

        restitution = check_restitution(restitution, "--restitution")
    return {"restitution": restitution, "impact": getattr(args, "impact", None)}


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
        parser.add_argument("--plot", metavar="FILE", type=output_file(*FIGURE_SUFFIXES),
                            help=f"draw the result to FILE ({_either(FIGURE_SUFFIXES)})")


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
                     help=f"pulse magnitude a, in g (0 to {MAGNITUDE_RANGE_G[1]:g})")
    grp.add_argument("--duration", type=number, metavar="TP",
                     help="step impulse: duration t_p of the first lobe, s "
                          f"({PULSE_TIME_RANGE_S[0]:g} to {PULSE_TIME_RANGE_S[1]:g})")
    grp.add_argument("--period", type=number, metavar="T",
                     help=f"sine pulse: period T, s ({PULSE_TIME_RANGE_S[0]:g} to "
                          f"{PULSE_TIME_RANGE_S[1]:g})")
    grp.add_argument("--record", type=path_argument, metavar="FILE",
                     help="recorded accelerogram: PEER .AT2 (in g) or .csv/.txt with two columns "
                          "time (s), acceleration (units from --units); positive = towards +x")
    grp.add_argument("--record-vertical", type=path_argument, metavar="FILE", default=None,
                     help="the record's vertical component (same formats and --units; "
                          "positive upward); --scale scales both, --mirror reverses the "
                          "horizontal only. Read by the rigid chain (the default model)")
    grp.add_argument("--units", choices=RECORD_UNITS, default=None,
                     help="units of a CSV record's acceleration column, required with a "
                          "CSV or text record (a CSV file does not say); .AT2 files are always "
                          "in g")
    grp.add_argument("--scale", type=number, metavar="S",
                     help=f"factor applied to every value of the record (> 0 and <= "
                          f"{SCALE_RANGE[1]:g}; default 1)")
    grp.add_argument("--mirror", action="store_true",
                     help="reverse the excitation: pulses start towards +x instead of -x; a "
                          "record is multiplied by -1")
    grp.add_argument("--vertical", type=number, metavar="R", default=None,
                     help="the pulse's vertical part: R a s(t) upward, s(t) the pulse's own "
                          "shape with its first lobe +1 (the step: +1 for t_p, -1/2 for 2 t_p); "
                          f"R in [-{MAX_VERTICAL_RATIO:g}, {MAX_VERTICAL_RATIO:g}], may be "
                          "negative (default 0: none). Read by the rigid chain (the default) "
                          "and the four-link model")


def record_from_args(path: Path, units: str | None, scale: float | None, *,
                     g: float = STANDARD_GRAVITY, dt: float | None = None) -> Record:
    """Read a record given on the command line: a CSV or text file needs ``--units`` (the file
    does not say); ``--scale`` must be > 0 (``--mirror`` reverses a record); ``--dt`` (s, > 0)
    is the step of a one-column text file. A peak above ``ranges.PLAUSIBLE_PGA_G`` is warned
    about, naming ``--scale`` (or ``--units``)."""
    scale = 1.0 if scale is None else scale
    if dt is not None:
        check_range("--dt", dt, *RECORD_DT_RANGE_S, "s")
    check_range("--scale", scale, *SCALE_RANGE, low_open=True,
                hint="use --mirror to reverse the record" if scale < 0 else "")
    if units is None and path.suffix.lower() in (".csv", ".txt"):
        raise InvalidParameterError(
            f"{path.name} needs --units {{{','.join(RECORD_UNITS)}}}: the units of its "
            "acceleration column (a CSV file does not say)")
    if path.suffix.lower() == ".at2" and units not in (None, "g"):
        raise InvalidParameterError(f"--units {units} does not apply to {path.name}: PEER .AT2 "
                                    "files are in g; leave --units out")
    try:
        with np.errstate(all="ignore"):  # an overflow is refused in one line, not warned about
            record = read_record(path, units=units, dt=dt, scale=scale, g=g)
    except GroundMotionFormatError:
        raise  # names the file and line already
    except InvalidParameterError as exc:  # the samples themselves (non-finite once in m/s^2, ...)
        raise InvalidParameterError(f"{path}: {exc}") from None
    low, high = RECORD_DT_RANGE_S
    if not low <= record.dt <= high:
        raise InvalidParameterError(
            f"{path}: time step DT = {record.dt:g} s is outside [{low:g}, {high:g}] s")
    if record.duration > T_END_RANGE_S[1]:
        raise InvalidParameterError(f"{path}: the record lasts {record.duration:g} s, more than "
                                    f"{T_END_RANGE_S[1]:g} s")
    peak_g = record.peak / g
    if not peak_g <= MAGNITUDE_RANGE_G[1]:
        raise InvalidParameterError(
            f"{path}: peak {peak_g:g} g (after --scale {scale:g}) is above "
            f"{MAGNITUDE_RANGE_G[1]:g} g; lower --scale")
    if peak_g > PLAUSIBLE_PGA_G:
        what = (f"a PGA of {peak_g:.3g} g, above {PLAUSIBLE_PGA_G:g} g, beyond design practice: "
                "is it in g?")
        if scale != 1.0:
            warn_input(f"--scale {scale:g}", f"gives {path.name} {what}")
        elif units is not None:
            warn_input(f"--units {units}", f"gives {path.name} {what}")
        else:  # a PEER file, in g: its own values
            warn_input(path.name, f"has {what}")
    return record


def suite_from_args(name: str, units: str | None, dt: float | None, *,
                    vertical: Path | None = None, **kwargs: Any):
    """`archquake.ground.suites.load_suite` on the command line: a CSV or text file of
    the suite without ``--units`` is refused naming ``--units`` and its choices. ``vertical``
    (``--record-vertical``) is the vertical component of a suite of one record."""
    from archquake.ground.suites import MISSING_UNITS, Suite, load_suite

    try:
        suite = load_suite(name, units=units, dt=dt, **kwargs)
    except InvalidParameterError as exc:
        if units is None and str(exc).startswith(MISSING_UNITS):
            raise InvalidParameterError(
                f"--units {{{','.join(RECORD_UNITS)}}} is needed: {exc}") from None
        raise
    if vertical is None:
        return suite
    from archquake.ground.vertical import WithVertical

    if len(suite) != 1 or not isinstance(suite.records[0], Record):
        raise InvalidParameterError(
            f"--record-vertical pairs with one record, but {name} holds {len(suite)}; give "
            "a suite's vertical components in a .list file, each after its record on one line")
    both = WithVertical(suite.records[0], record_from_args(vertical, units, None, dt=dt))
    return Suite(suite.name, (both,), suite.description + ", with its vertical component",
                 suite.source, suite.metadata)


def ground_motion_from_args(args: argparse.Namespace, *,
                            g: float = STANDARD_GRAVITY) -> GroundMotion:
    """Build the excitation chosen by `add_ground_motion_arguments` (g -> m/s^2 here).

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
        if getattr(args, "vertical", None) is not None:
            raise InvalidParameterError("--vertical applies to --pulse (a pulse's vertical "
                                        "part), not to --record")
        motion = record_from_args(record, args.units, args.scale, g=g)
        motion = motion.mirrored() if args.mirror else motion
        up = getattr(args, "record_vertical", None)
        if up is None:
            return motion
        from archquake.ground.vertical import WithVertical

        both = WithVertical(motion, record_from_args(up, args.units, args.scale, g=g))
        check_motion_lift_off(both, g)
        return both
    for option in ("units", "scale", "record_vertical"):
        if getattr(args, option, None) is not None:
            raise InvalidParameterError(
                f"--{option.replace('_', '-')} applies to --record, not to --pulse; set the "
                "pulse with --magnitude (and its vertical with --vertical)"
            )
    if args.magnitude is None:
        raise InvalidParameterError(f"--pulse {pulse} needs --magnitude A (g, >= 0)")
    check_range("--magnitude", args.magnitude, *MAGNITUDE_RANGE_G, "g",
                hint="use --mirror to reverse the pulse" if args.magnitude < 0 else "")
    warn_pga("--magnitude", args.magnitude)
    direction = 1 if args.mirror else -1
    vertical = getattr(args, "vertical", None)
    vertical = 0.0 if vertical is None else vertical
    check_range("--vertical", vertical, -MAX_VERTICAL_RATIO, MAX_VERTICAL_RATIO)
    if pulse == "step":
        if args.period is not None:
            raise InvalidParameterError("--period applies to --pulse sine; the step impulse "
                                        "takes --duration TP (s)")
        if args.duration is None:
            raise InvalidParameterError("--pulse step needs --duration TP (s, > 0): the length "
                                        "t_p of its first lobe")
        check_range("--duration", args.duration, *PULSE_TIME_RANGE_S, "s")
        _warn_long_pulse("--duration", args.duration)
        return _lifts_off(StepImpulse.from_g(args.magnitude, args.duration, direction, g=g,
                                             vertical=vertical), g)
    if args.duration is not None:
        raise InvalidParameterError("--duration applies to --pulse step; the sine pulse takes "
                                    "--period T (s)")
    if args.period is None:
        raise InvalidParameterError("--pulse sine needs --period T (s, > 0)")
    check_range("--period", args.period, *PULSE_TIME_RANGE_S, "s")
    _warn_long_pulse("--period", args.period)
    return _lifts_off(SinePulse.from_g(args.magnitude, args.period, direction, g=g,
                                       vertical=vertical), g)


def _lifts_off(motion: GroundMotion, g: float) -> GroundMotion:
    """The pulse, unless its vertical part lifts the arch off (one line naming --vertical)."""
    kind, params = motion.kernel_spec()
    try:
        check_lift_off(kind, params, g)
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"--vertical {params[3]:g} with --magnitude "
                                    f"{params[0] / g:g}: {exc}") from None
    return motion


def _warn_long_pulse(option: str, seconds: float) -> None:
    if seconds > PLAUSIBLE_PULSE_S:
        warn_input(option, f"{seconds:g} s is longer than {PLAUSIBLE_PULSE_S:g} s, beyond any "
                           "recorded pulse: is it in s (not ms)?")


def length_option(args: argparse.Namespace) -> str:
    """The option that sets how long a run of ``args`` lasts, as typed, for
    `rigid_work`: ``--t-end`` when given, else the excitation's (``--duration``,
    ``--period``, ``--record``), whose end the run outlasts by its tail."""
    if getattr(args, "t_end", None) is not None:
        return "--t-end"
    return excitation_option(args) + " (the run lasts the excitation and then 60 sqrt(R/g))"


def excitation_option(args: argparse.Namespace) -> str:
    """The option that sets how long the excitation of ``args`` lasts, as typed: ``--duration``
    (step impulse), ``--period`` (sine pulse) or ``--record``."""
    if getattr(args, "record", None) is not None:
        return "--record"
    return "--period" if getattr(args, "pulse", None) == "sine" else "--duration"


#: Step of ``--periods START:STOP`` when none is given, s.
DEFAULT_PERIOD_STEP_S = 0.05


#: A run of the rigid chain estimated above this many seconds says so on stderr before it
#: starts (what it integrates and about how long), so that a long run is never silent.
ANNOUNCE_WORK_S = 10.0


def rigid_work(command: str, arch, motion, duration: float, time_step: float, *,
               passes: int = 1, length: str = "--t-end"):
    """The one work estimate of every command that integrates the chain of rigid voussoirs
    (`archquake.rigid.model.check_work`, the bound of ``simulate_rigid``): refused in one
    line naming the options to change, with the time it would take, above
    ``ranges.RIGID_MAX_WORK`` (at once: before the onset test, whose projections of the whole
    chain cost seconds for hundreds of voussoirs); below it, a run estimated above
    `ANNOUNCE_WORK_S` prints one line on stderr first, unless the motion never reaches the
    onset of hinging (`archquake.rigid.events.stays_at_rest`: no step is taken), and
    returns a ``progress(steps_done, steps_at_most)`` for ``simulate_rigid`` that prints a line
    at each quarter of the steps (None for a short run)."""
    from archquake.rigid.events import stays_at_rest
    from archquake.rigid.model import check_work
    from archquake.rigid.verdict import rigid_model

    model = rigid_model(arch)
    # the bound first: it is arithmetic, while the onset test projects the whole chain (seconds
    # for hundreds of voussoirs)
    seconds = check_work(model.n_bodies, duration, time_step, passes=passes,
                         change=f"give fewer --voussoirs or a shorter {length}")
    if seconds <= ANNOUNCE_WORK_S or stays_at_rest(model, motion):
        return None
    steps = math.ceil(duration / time_step)
    print(f"archquake: {command}: {model.n_bodies} voussoirs over {steps:,} time steps of "
          f"{time_step:.3g} s" + (f", {passes} times" if passes > 1 else "")
          + f": about {seconds / 60:.2g} min at most", file=sys.stderr, flush=True)
    said: set[int] = set()

    def progress(done: int, total: int) -> None:
        quarter = 4 * done // max(total, 1)
        if 0 < quarter < 4 and quarter not in said:
            said.add(quarter)
            print(f"archquake: {command}: {done:,} of at most {total:,} time steps",
                  file=sys.stderr, flush=True)

    return progress


def periods_list(text: str) -> tuple[float, ...]:
    """argparse type: comma-separated periods in s (>= 0), e.g. '0.2,0.5,1', or a grid
    START:STOP:STEP (s; STOP included), e.g. '0:4:0.02'; START:STOP steps by 0.05 s."""
    if ":" in text:
        parts = text.replace(" ", "").split(":")
        try:
            if len(parts) not in (2, 3):
                raise ValueError
            values = [float(x) for x in parts]
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"expected START:STOP:STEP in s (e.g. 0:4:0.02) or periods separated by commas, "
                f"got {text!r}") from None
        step = values[2] if len(values) == 3 else DEFAULT_PERIOD_STEP_S
        try:
            return tuple(float(t) for t in period_grid(values[0], values[1], step))
        except InvalidParameterError as exc:
            raise argparse.ArgumentTypeError(f"{exc} (in {text!r})") from None
    out = []
    for tok in (t for t in text.replace(" ", "").split(",") if t):
        try:
            out.append(float(tok))
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"expected periods in s separated by commas (e.g. 0.2,0.5,1), got {text!r}"
            ) from None
    try:
        return tuple(float(t) for t in check_periods(out))
    except InvalidParameterError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def parse_durations(text: str) -> np.ndarray:
    """argparse type: ``START:STOP:COUNT`` (s) to COUNT evenly spaced durations, or one duration;
    durations past ``ranges.PLAUSIBLE_PULSE_S`` are warned about (``--durations``)."""
    try:
        values = _durations(text)
    except InvalidParameterError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    longest = float(values.max())
    if longest > PLAUSIBLE_PULSE_S:
        warn_input("--durations", f"{text} reaches {longest:g} s, longer than "
                                  f"{PLAUSIBLE_PULSE_S:g} s, beyond any recorded pulse: is it in "
                                  "s (not ms)?")
    return values


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
    if not 1 <= count <= MAX_DURATIONS:
        raise InvalidParameterError(
            f"COUNT must be from 1 to {MAX_DURATIONS} in START:STOP:COUNT, got {text!r}")
    if count > 1 and not stop > start:
        raise InvalidParameterError(f"STOP must exceed START in START:STOP:COUNT, got {text!r}")
    return _positive(np.linspace(start, stop, count), text)


def _positive(values: np.ndarray, text: str) -> np.ndarray:
    low, high = PULSE_TIME_RANGE_S
    if not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise InvalidParameterError(f"durations must be finite and > 0 s, got {text!r}")
    if np.any(values < low) or np.any(values > high):
        raise InvalidParameterError(f"durations must be in [{low:g}, {high:g}] s, got {text!r}")
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
    "periods_list",
    "rigid_work",
    "print_json",
    "excitation_option",
    "length_option",
    "record_from_args",
    "suite_from_args",
    "to_jsonable",
    "whole",
]
