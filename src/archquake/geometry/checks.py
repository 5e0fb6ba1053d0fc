"""The arch's parameters checked in one place: their ranges and the rules that tie them.

The arch (`Arch` and the other builders), the command line
(`archquake.cli.common.arch_from_args`) and the study files
(`ArchSpec`) all check an arch here. Each names a parameter as
its user typed it, through a `Wording`: ``radius`` for an argument or a study key
(``radius must be in [0.001, 10000] (m), got 0``), ``--radius`` on the command line
(``--radius must be in [0.001, 10000] m, got 0``). The generic checks are those of the
project's validation layer (`archquake._validate`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from archquake._validate import (
    check_range,
    check_whole,
    require_int,
    require_positive,
    require_range,
)
from archquake.errors import InvalidParameterError

#: Largest density, kg/m^3 (the densest element, osmium, is 22,590), and largest depth, m.
MAX_DENSITY = 1e5
MAX_DEPTH = 1e4
#: Least density (kg/m^3) and depth (m): far below any masonry; below them masses leave the
#: range where the impact and kernel arithmetic is sound (the CLI fuzz found 1e-300 of each
#: dividing by zero). Least thickness ratio t/R of a circular Arch: below it the limit
#: analysis's coefficients overflow.
MIN_DENSITY = 1.0
MIN_DEPTH = 1e-3
MIN_THICKNESS_RATIO = 1e-6
#: Largest thickness ratio t/R: the intrados radius R - t/2 must stay positive.
MAX_THICKNESS_RATIO = 2.0
#: Largest supported angle of embrace, degrees: deeper arches than this are horseshoe shapes
#: whose springings overhang the centre far enough that a two-support, four-hinge description
#: stops being a sensible model.
MAX_EMBRACE_DEG = 240.0
#: The same in rad. Compare degrees with `MAX_EMBRACE_DEG` (degrees(radians(240)) is
#: 239.99999999999997, so converting the bound back would refuse the documented maximum).
MAX_EMBRACE = math.radians(MAX_EMBRACE_DEG)
#: Least angle of embrace, degrees: a flatter ring is a straight beam, and below it (5e-324 rad
#: reached a division by zero) the joint angles pi/2 +- embrace/2 of thousands of voussoirs stop
#: being distinct in double precision.
MIN_EMBRACE_DEG = 1e-3
#: The same in rad.
MIN_EMBRACE = math.radians(MIN_EMBRACE_DEG)
#: Least and most voussoirs accepted (limit analysis enumerates joint quadruples).
MIN_VOUSSOIRS = 3
MAX_VOUSSOIRS = 2000
#: Radii accepted, m: from a 1 mm laboratory model to a 10 km arch. Beyond them nothing is
#: gained physically, and masses (rho d beta R t) and inertias (~ m R^2) would leave the range
#: where the limit analysis's linear programme and the time steps are well conditioned.
RADIUS_RANGE = (1e-3, 1e4)
#: Courses (blocks) of a pier.
PIER_COURSES_RANGE = (1, 500)
#: Shapes `ShapedArch` knows ("segmental" is the circular arch with
#: f < L/2).
SHAPES = ("circular", "segmental", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
#: Joint patterns.
JOINTS = ("radial", "vertical")


@dataclass(frozen=True)
class Wording:
    """How a check names a parameter and words its range.

    Parameters
    ----------
    option : bool
        False: an argument or a study key, the unit in parentheses after the range
        (``radius must be in [0.001, 10000] (m), got 0``); True: a command-line option, the unit
        bare after the range (``--radius must be in [0.001, 10000] m, got 0``).
    names : mapping of str to str
        The name shown for a parameter's key where it is not the key itself (an argument or a
        study key) or ``--`` and the key with dashes (an option), e.g. ``{"embrace_deg":
        "--embrace"}``.

    Examples
    --------
    >>> OPTIONS.name("pier_height"), KEYS.name("pier_height")
    ('--pier-height', 'pier_height')
    """

    option: bool = False
    names: Mapping[str, str] = field(default_factory=dict)

    def name(self, key: str) -> str:
        """The parameter ``key`` as its user typed it."""
        if key in self.names:
            return self.names[key]
        return "--" + key.replace("_", "-") if self.option else key

    def range(self, key: str, value: object, low: float, high: float, unit: str = "", *,
              low_open: bool = False, high_open: bool = False) -> float:
        """``value`` inside its range (closed ends unless told), as a float."""
        if self.option:
            return check_range(self.name(key), float(value),  # type: ignore[arg-type]
                               low, high, unit, low_open=low_open, high_open=high_open)
        return require_range(self.name(key), value, low, high, unit, low_open=low_open,
                             high_open=high_open)

    def whole(self, key: str, value: object, low: int, high: int) -> int:
        """A whole number ``value`` from ``low`` to ``high``."""
        if self.option:
            return check_whole(self.name(key), int(value), low, high)  # type: ignore[call-overload]
        return require_int(self.name(key), value, low, high)

    def positive(self, key: str, value: object, unit: str = "") -> float:
        """A finite number > 0."""
        return require_positive(self.name(key), value, unit)


#: Arguments and study keys, named by their keys.
KEYS = Wording()
#: Command-line options, named ``--key-with-dashes`` (the embrace in degrees is ``--embrace``).
OPTIONS = Wording(option=True, names={"embrace_deg": "--embrace"})


def check_radius(radius: object, wording: Wording = KEYS) -> float:
    """Centreline radius R, m, in `RADIUS_RANGE`."""
    return wording.range("radius", radius, *RADIUS_RANGE, "m")


def check_thickness(thickness: object, radius: float, wording: Wording = KEYS) -> float:
    """Ring thickness t, m, of a circular arch of radius ``radius`` (m):
    MIN_THICKNESS_RATIO R <= t < 2 R."""
    thin, thick = MIN_THICKNESS_RATIO * radius, MAX_THICKNESS_RATIO * radius
    name = wording.name("thickness")
    if not wording.option:
        t = require_positive(name, thickness, "m")
        if t >= thick:
            raise InvalidParameterError(
                f"{name} must be less than 2 x radius = {thick:g} m (the intrados radius "
                f"R - t/2 must stay positive), got {t:g} m")
    else:
        t = float(thickness)  # type: ignore[arg-type]
    if not thin <= t < thick:
        raise InvalidParameterError(
            f"{name} must be in [{MIN_THICKNESS_RATIO:g} x radius, 2 x radius) = "
            f"[{thin:g}, {thick:g}) m, got {t:g}")
    return t


def check_thickness_ratio(ratio: object, wording: Wording = KEYS) -> float:
    """Thickness ratio t/R, dimensionless: MIN_THICKNESS_RATIO <= t/R < 2."""
    return wording.range("thickness_ratio", ratio, MIN_THICKNESS_RATIO, MAX_THICKNESS_RATIO,
                         high_open=True)


def check_embrace_deg(embrace_deg: object, wording: Wording = KEYS) -> float:
    """Angle of embrace, degrees, from `MIN_EMBRACE_DEG` to `MAX_EMBRACE_DEG`."""
    return wording.range("embrace_deg", embrace_deg, MIN_EMBRACE_DEG, MAX_EMBRACE_DEG, "degrees")


def check_embrace(embrace: object, name: str = "embrace") -> float:
    """Angle of embrace, rad (an argument of the library), from `MIN_EMBRACE` to
    `MAX_EMBRACE`; the range is shown in degrees and rad."""
    return require_range(name, embrace, MIN_EMBRACE, MAX_EMBRACE, "", low_open=False,
                         high_open=False,
                         shown=f"[{MIN_EMBRACE_DEG:g}, {MAX_EMBRACE_DEG:g}] degrees = "
                               f"[{MIN_EMBRACE:.4g}, {MAX_EMBRACE:.6g}] rad")


def check_voussoirs(voussoirs: object, wording: Wording = KEYS, *, least: int = MIN_VOUSSOIRS
                    ) -> int:
    """Number of voussoirs, from ``least`` (3; 4 for vertical joints) to `MAX_VOUSSOIRS`."""
    return wording.whole("voussoirs", voussoirs, least, MAX_VOUSSOIRS)


def check_depth(depth: object, wording: Wording = KEYS) -> float:
    """Out-of-plane depth, m, from `MIN_DEPTH` to `MAX_DEPTH`."""
    return wording.range("depth", depth, MIN_DEPTH, MAX_DEPTH, "m")


def check_density(density: object, wording: Wording = KEYS) -> float:
    """Density, kg/m^3, from `MIN_DENSITY` to `MAX_DENSITY`."""
    return wording.range("density", density, MIN_DENSITY, MAX_DENSITY, "kg/m^3")


def check_shape(shape: object, wording: Wording = KEYS) -> str:
    """One of `SHAPES` (``_`` read as ``-``, any case)."""
    word = str(shape).replace("_", "-").lower()
    if word not in SHAPES:
        raise InvalidParameterError(
            f"{wording.name('shape')} must be one of {', '.join(SHAPES)}, got {shape!r}")
    return word


def check_joints(joints: object, wording: Wording = KEYS) -> str:
    """``radial`` or ``vertical`` (`JOINTS`)."""
    if joints not in JOINTS:
        raise InvalidParameterError(
            f"{wording.name('joints')} must be {' or '.join(JOINTS)}, got {joints!r}")
    return str(joints)


def check_piers(height: object | None, width: object | None, courses: object | None = None,
                wording: Wording = KEYS) -> bool:
    """Whether piers are given: their height and width (m) go together, and their courses
    only with them. The values themselves are checked by
    `Piers` (or `check_pier_values`)."""
    if height is None and width is None:
        if courses is not None and wording.option:
            raise InvalidParameterError(f"{wording.name('pier_courses')} needs "
                                        f"{wording.name('pier_height')} and "
                                        f"{wording.name('pier_width')}")
        return False
    if height is None or width is None:
        h, w = wording.name("pier_height"), wording.name("pier_width")
        raise InvalidParameterError(f"piers need both {h} and {w} (m)" if wording.option
                                    else f"{h} and {w} go together (m)")
    return True


def check_pier_values(height: object, width: object, courses: object,
                      wording: Wording = KEYS) -> tuple[float, float, int]:
    """A pier's height and width, m (> 0), and courses (1 to 500)."""
    return (wording.positive("pier_height", height, "m"),
            wording.positive("pier_width", width, "m"),
            check_pier_courses(courses, wording))


def check_pier_courses(courses: object, wording: Wording = KEYS) -> int:
    """Courses of a pier, from 1 to 500 (`PIER_COURSES_RANGE`)."""
    return wording.whole("pier_courses", courses, *PIER_COURSES_RANGE)


__all__ = [
    "JOINTS",
    "KEYS",
    "MAX_DENSITY",
    "MAX_DEPTH",
    "MAX_EMBRACE",
    "MAX_EMBRACE_DEG",
    "MAX_THICKNESS_RATIO",
    "MAX_VOUSSOIRS",
    "MIN_DENSITY",
    "MIN_DEPTH",
    "MIN_EMBRACE",
    "MIN_EMBRACE_DEG",
    "MIN_THICKNESS_RATIO",
    "MIN_VOUSSOIRS",
    "OPTIONS",
    "PIER_COURSES_RANGE",
    "RADIUS_RANGE",
    "SHAPES",
    "Wording",
    "check_density",
    "check_depth",
    "check_embrace",
    "check_embrace_deg",
    "check_joints",
    "check_pier_courses",
    "check_pier_values",
    "check_piers",
    "check_radius",
    "check_shape",
    "check_thickness",
    "check_thickness_ratio",
    "check_voussoirs",
]
