"""The arches engineers have, built from the quantities they quote.

Every shape is a ring of constant thickness t about a centreline of span L and rise f (the
centreline's: the clear span between the intrados springings is smaller by the springing
joints' horizontal extent), cut into ``voussoirs`` blocks of equal centreline length:

==============  ===================================================================================
shape           centreline (left half, from the springing to the crown)
==============  ===================================================================================
circular        an arc of radius R = (L^2/4 + f^2) / (2f) (segmental when f < L/2)
pointed         two arcs of radius rho = L/2 + c centred on the springing line at x = +-c, with
                c = (f^2 - L^2/4) / L >= 0; eccentricity e = 2c/L: 0 semicircle, 1 equilateral
                (rho = L), < 1 drop arch, > 1 lancet
elliptical      a semi-ellipse of semi-axes L/2 and f
three-centred   a basket handle: haunch arcs of 60 degrees, radius r1, centred on the springing
                line, and a crown arc of radius r2 tangent to them
parabolic       y = f (1 - (2x/L)^2)
catenary        y = f + k - k cosh(x/k), k from k (cosh(L/2k) - 1) = f
==============  ===================================================================================

Faces: intrados and extrados are the centreline offset by -t/2 and +t/2 along its normal (the
two arcs of a pointed arch are trimmed or extended to meet on the axis). Joints:

- ``radial``: normal to the centreline (the crown joint of a pointed arch is vertical);
- ``vertical``: the springing joints stay normal to the centreline (the skewbacks), joints 1
  and n-1 are vertical through the intrados springing points (the springers, bedded on the
  skewbacks, reach to them), and joints 2..n-2 are vertical through centreline points equally
  spaced between. A vertical joint nearer the springing than the intrados springing point
  would miss the intrados (its lower end would be on the support), which is why the springers
  carry the first part of the ring.

Blocks are polygons whose curved faces are sampled every ~0.02 degrees of turning, so their
mass properties equal the curved blocks' to a relative 1e-8 (tests/geometry hold them to
quadrature and to the circular closed forms). The origin is the centre of the circle for
circular arches (as `Arch`), else the mid-point of the
springing line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from archquake._validate import require_positive, require_range
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain, three_point_radius
from archquake.geometry.checks import (  # noqa: F401  (SHAPES and JOINTS are re-exported here)
    JOINTS,
    SHAPES,
    Wording,
    check_density,
    check_depth,
    check_joints,
    check_shape,
    check_voussoirs,
)

#: The shape's and joints' names in the messages of `ShapedArch` (as the options).
_NAMES = Wording(names={"shape": "--shape", "joints": "--joints"})
#: Turning of the three-centred arch's haunch arcs, rad.
HAUNCH_ANGLE = math.radians(60.0)
#: Samples of the half centreline for its arc length, and of each half face.
_ARC_SAMPLES = 20001
_FACE_SAMPLES = 4501


@dataclass(frozen=True)
class ShapedArch(VoussoirChain):
    """A symmetric arch of any shape in `SHAPES`, ring thickness t, n voussoirs.

    Parameters
    ----------
    shape : str
        One of `SHAPES`.
    span : float
        Centreline span L between the springings, m.
    rise : float
        Centreline rise f from the springing line to the crown, m.
    thickness : float
        Ring thickness t, normal to the centreline, m.
    voussoirs : int
        Number of blocks n (3..2000; >= 4 with vertical joints).
    joints : {"radial", "vertical"}
    depth, density : float
        Out-of-plane depth (m) and density (kg/m^3).

    Examples
    --------
    An equilateral pointed arch (rise = L sqrt(3)/2):

    >>> a = ShapedArch("pointed", 10.0, 10.0 * 3**0.5 / 2, 1.0, 20)
    >>> round(a.eccentricity, 12), round(a._pointed()[1], 12)  # arcs of radius L
    (1.0, 10.0)
    """

    shape: str
    span: float
    rise: float
    thickness: float
    voussoirs: int
    joints: str = "radial"
    depth: float = 1.0
    density: float = 2000.0

    def __post_init__(self) -> None:
        shape = check_shape(self.shape, _NAMES)
        if str(self.joints).lower() not in JOINTS:
            check_joints(self.joints, _NAMES)
        joints = str(self.joints).lower()
        L = require_range("span", self.span, 1e-3, 2e4, "m", low_open=False, high_open=False)
        f = require_positive("rise", self.rise, "m")
        t = require_positive("thickness", self.thickness, "m")
        check_voussoirs(self.voussoirs, least=4 if joints == "vertical" else 3)
        check_depth(self.depth)
        check_density(self.density)
        if shape == "segmental" and f > 0.5 * L:
            raise InvalidParameterError(
                f"--rise of a segmental arch must be at most half the span ({0.5 * L:g} m), got {f:g} m"
            )
        if shape == "pointed" and f < 0.5 * L * (1 - 1e-12):
            raise InvalidParameterError(
                f"--rise of a pointed arch must be at least half the span ({0.5 * L:g} m), got {f:g} m"
            )
        if shape == "circular" and f > 0.5 * L + 1e-12 * L:
            # a horseshoe: allowed up to the Arch's 240 degrees of embrace
            r = (0.25 * L * L + f * f) / (2 * f)
            if 2 * math.atan2(0.5 * L, r - f) > math.radians(240.0) + 1e-12:
                raise InvalidParameterError(
                    f"--rise {f:g} m makes a horseshoe of more than 240 degrees on a {L:g} m span"
                )
        if shape == "three-centred" and f >= 0.5 * L:
            raise InvalidParameterError(
                f"--rise of a three-centred (basket-handle) arch must be below half the span "
                f"({0.5 * L:g} m), got {f:g} m"
            )
        for name, value in (("span", L), ("rise", f), ("thickness", t), ("depth", self.depth),
                            ("density", self.density)):
            object.__setattr__(self, name, float(value))
        object.__setattr__(self, "shape", shape)
        object.__setattr__(self, "joints", joints)
        object.__setattr__(self, "voussoirs", int(self.voussoirs))
        rho_min = self._min_curvature_radius()
        if t >= 2.0 * rho_min * (1 - 1e-12):
            raise InvalidParameterError(
                f"--thickness must be less than {2 * rho_min:.4g} m for this {shape} arch (twice "
                f"its centreline's smallest radius of curvature, where the intrados would fold), "
                f"got {t:g} m"
            )

    # ------------------------------------------------------------------ shape parameters
    @property
    def eccentricity(self) -> float:
        """Pointed arch: 2c/L, the centres' distance from the axis over the half-span
        (0 semicircle, 1 equilateral, < 1 drop, > 1 lancet); 0 for other shapes."""
        if self.shape != "pointed":
            return 0.0
        return 2.0 * self._pointed()[0] / self.span

    def _circle(self) -> tuple[float, float]:
        """Radius and embrace of a circular arch, m and rad."""
        L, f = self.span, self.rise
        r = (0.25 * L * L + f * f) / (2.0 * f)
        return r, 2.0 * math.atan2(0.5 * L, r - f)

    def _pointed(self) -> tuple[float, float]:
        """Centre offset c and radius rho of a pointed arch's arcs, m."""
        L, f = self.span, self.rise
        c = max((f * f - 0.25 * L * L) / L, 0.0)
        return c, 0.5 * L + c

    def _three_centred(self) -> tuple[float, float]:
        """Haunch radius r1 and crown radius r2, m."""
        a, f, al = 0.5 * self.span, self.rise, HAUNCH_ANGLE
        d = (a - f) / (math.cos(al) + math.sin(al) - 1.0)
        r1 = f - d * (1.0 - math.sin(al))
        if r1 <= 0.0:
            f_min = a * (1 - math.sin(al)) / math.cos(al)
            raise InvalidParameterError(
                f"--rise of a three-centred arch with 60 degree haunch arcs must exceed "
                f"{f_min:.4g} m on a {self.span:g} m span, got {f:g} m"
            )
        return r1, r1 + d

    def _catenary_k(self) -> float:
        a, f = 0.5 * self.span, self.rise
        g = lambda k: k * (math.cosh(a / k) - 1.0) - f  # noqa: E731
        lo = a / 700.0
        from scipy.optimize import brentq  # (lazy: scipy is slow to import)

        return brentq(g, lo, 1e6 * (a + f), xtol=1e-14 * a, rtol=1e-15, maxiter=500)

    def _min_curvature_radius(self) -> float:
        s = self.shape
        if s in ("circular", "segmental"):
            return self._circle()[0]
        if s == "pointed":
            return self._pointed()[1]
        if s == "three-centred":
            return self._three_centred()[0]
        if s == "elliptical":
            a, b = 0.5 * self.span, self.rise
            return min(a * a / b, b * b / a)
        if s == "parabolic":
            return self.span**2 / (8.0 * self.rise)
        return self._catenary_k()

    # ------------------------------------------------------------------ left half
    def _half(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Centreline points and unit outward normals at u in [0, 1] (left springing to crown)."""
        s = self.shape
        u = np.asarray(u, dtype=float)
        if s in ("circular", "segmental"):
            r, beta = self._circle()
            th = 0.5 * math.pi + 0.5 * beta * (1.0 - u)
            n = np.column_stack([np.cos(th), np.sin(th)])
            return r * n, n
        if s == "pointed":
            c, rho = self._pointed()
            th_end = math.acos(-c / rho)
            th = math.pi + (th_end - math.pi) * u
            n = np.column_stack([np.cos(th), np.sin(th)])
            return np.column_stack([c + rho * n[:, 0], rho * n[:, 1]]), n
        if s == "three-centred":
            r1, r2 = self._three_centred()
            a, al = 0.5 * self.span, HAUNCH_ANGLE
            total = math.pi / 2
            th = math.pi - total * u  # turning angle of the normal, pi -> pi/2
            n = np.column_stack([np.cos(th), np.sin(th)])
            haunch = th >= math.pi - al
            cx = np.where(haunch, -(a - r1), 0.0)
            cy = np.where(haunch, 0.0, self.rise - r2)
            rr = np.where(haunch, r1, r2)
            return np.column_stack([cx + rr * n[:, 0], cy + rr * n[:, 1]]), n
        a, f = 0.5 * self.span, self.rise
        if s == "elliptical":
            ang = 0.5 * math.pi * u
            p = np.column_stack([-a * np.cos(ang), f * np.sin(ang)])
            n = np.column_stack([-np.cos(ang) / a, np.sin(ang) / f])
        else:
            x = -a * (1.0 - u)
            if s == "parabolic":
                y = f * (1.0 - (x / a) ** 2)
                slope = -2.0 * f * x / (a * a)
            else:
                k = self._catenary_k()
                y = f + k - k * np.cosh(x / k)
                slope = -np.sinh(x / k)
            p = np.column_stack([x, y])
            n = np.column_stack([-slope, np.ones_like(x)])
        return p, n / np.hypot(n[:, 0], n[:, 1])[:, None]

    def _half_face(self, side: float) -> np.ndarray:
        """Dense polyline of the intrados (side -1) or extrados (+1), left springing to x = 0."""
        u = np.linspace(0.0, 1.0, _FACE_SAMPLES)
        if self.shape == "pointed":
            c, rho = self._pointed()
            r = rho + side * 0.5 * self.thickness
            th = np.linspace(math.pi, math.acos(-c / r), _FACE_SAMPLES)
            pts = np.column_stack([c + r * np.cos(th), r * np.sin(th)])
            pts[-1, 0] = 0.0
            return pts
        p, n = self._half(u)
        pts = p + side * 0.5 * self.thickness * n
        pts[-1, 0] = 0.0
        return pts

    # ------------------------------------------------------------------ layout
    def _build_layout(self):
        n = self.voussoirs
        u = np.linspace(0.0, 1.0, _ARC_SAMPLES)
        p, _ = self._half(u)
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])
        half = s[-1]
        faces = []
        for side in (-1.0, 1.0):
            left = self._half_face(side)
            right = left[-2::-1] * np.array([-1.0, 1.0])
            faces.append(np.vstack([left, right]))
        intrados, extrados = faces

        def at(sj: float) -> tuple[np.ndarray, np.ndarray]:
            """Centreline point and normal at arc length sj from the left springing."""
            mirror = sj > half
            sl = 2 * half - sj if mirror else sj
            uj = float(np.interp(sl, s, u))
            pj, nj = self._half(np.array([uj]))
            pj, nj = pj[0], nj[0]
            if uj >= 1.0 - 1e-15:
                pj, nj = np.array([0.0, pj[1]]), np.array([0.0, 1.0])
            if mirror:
                pj, nj = pj * [-1.0, 1.0], nj * [-1.0, 1.0]
            return pj, nj

        lines = []
        if self.joints == "radial":
            for j in range(n + 1):
                lines.append(at(2 * half * j / n))
        else:
            x_spring = float(intrados[0, 0])
            s1 = float(np.interp(x_spring, p[:, 0], s))  # centreline length to x = x_spring
            lines.append(at(0.0))
            up = np.array([0.0, 1.0])
            lines.append((np.array([x_spring, 0.0]), up))
            for k in range(2, n - 1):
                pj, _ = at(s1 + (2 * half - 2 * s1) * (k - 1) / (n - 2))
                lines.append((pj, up))
            lines.append((np.array([-x_spring, 0.0]), up))
            lines.append(at(2 * half))
        rows: list[list[np.ndarray]] = []
        idx: list[list[int]] = []
        last = len(intrados) - 2
        for j, (c, d) in enumerate(lines):
            if j in (0, n):  # the springing joints are the faces' end points, exactly
                k = 0 if j == 0 else -1
                rows.append([intrados[k], extrados[k]])
                idx.append([0 if j == 0 else last, 0 if j == 0 else last])
                continue
            ends, where = [], []
            for side, face in zip((-1.0, 1.0), faces):
                q, i = _line_crossing(face, c, d, j)
                smooth = self.joints == "radial" and not (self.shape == "pointed" and 2 * j == n)
                ends.append(c + side * 0.5 * self.thickness * d if smooth else q)  # exact offset
                where.append(i)
            rows.append(ends)
            idx.append(where)
        joints = np.array(rows)
        # the first vertical joints pass exactly through the intrados springing points
        if self.joints == "vertical":
            joints[1, 0], joints[n - 1, 0] = intrados[0], intrados[-1]
            idx[1][0], idx[n - 1][0] = 0, last
            joints[1, 0, 1] = joints[n - 1, 0, 1] = intrados[0, 1]
        blocks = []
        for k in range(n):
            (i0, e0), (i1, e1) = idx[k], idx[k + 1]
            poly = np.vstack([
                joints[k, 0][None], intrados[i0 + 1 : i1 + 1], joints[k + 1, 0][None],
                joints[k + 1, 1][None], extrados[e1 : e0 : -1], joints[k, 1][None],
            ])
            blocks.append(_dedupe(poly))
        return joints, tuple(blocks)

    # ------------------------------------------------------------------ the chain's scalars
    @property
    def radius(self) -> float:
        """Characteristic length: the radius of the circle through the centreline's springing
        points and crown, m (R for circular arches)."""
        if self.shape in ("circular", "segmental"):
            return self._circle()[0]
        L, f = self.span, self.rise
        return (0.25 * L * L + f * f) / (2.0 * f)

    @property
    def embrace(self) -> float:
        """Angle between the centreline's normals at the springings, rad."""
        _, n = self._half(np.array([0.0]))
        return 2.0 * math.atan2(-n[0, 0], n[0, 1])

    @property
    def springing_y(self) -> float:
        p, _ = self._half(np.array([0.0]))
        return float(p[0, 1])

    @property
    def clear_span(self) -> float:
        """Distance between the intrados springing points, m."""
        return float(self.intrados_points[-1, 0] - self.intrados_points[0, 0])

    def describe(self) -> dict:
        out = {
            "shape": self.shape,
            "span_m": self.span,
            "rise_m": self.rise,
            "thickness_m": self.thickness,
            "voussoirs": self.voussoirs,
            "joints": self.joints,
            "length_scale_m": self.radius,
            "thickness_ratio": self.thickness_ratio,
            "depth_m": self.depth,
            "density_kg_m3": self.density,
        }
        if self.shape == "pointed":
            out["eccentricity"] = self.eccentricity
        return out

    def scaled(self, factor: float) -> ShapedArch:
        require_positive("scale factor", factor)
        f = float(factor)
        return replace(self, span=self.span * f, rise=self.rise * f, thickness=self.thickness * f,
                       depth=self.depth * f)

    def with_thickness(self, thickness: float) -> ShapedArch:
        return replace(self, thickness=thickness)


def _line_crossing(face: np.ndarray, c: np.ndarray, d: np.ndarray, j: int) -> tuple[np.ndarray, int]:
    """Where the line through ``c`` along ``d`` crosses the polyline ``face`` nearest to ``c``:
    the point and the index of the segment's first vertex."""
    g = d[0] * (face[:, 1] - c[1]) - d[1] * (face[:, 0] - c[0])
    hits = np.nonzero((g[:-1] * g[1:] <= 0.0) & (g[:-1] != g[1:]))[0]
    if hits.size == 0:
        raise InvalidParameterError(
            f"joint {j} does not reach both faces of the ring (the ring is too thick for these "
            "joints); reduce --thickness or use --joints radial"
        )
    w = g[hits] / (g[hits] - g[hits + 1])
    pts = face[hits] + w[:, None] * (face[hits + 1] - face[hits])
    i = int(np.argmin(np.hypot(*(pts - c).T)))
    return pts[i], int(hits[i])


def _dedupe(poly: np.ndarray) -> np.ndarray:
    keep = np.ones(len(poly), dtype=bool)
    scale = np.ptp(poly, axis=0).max()
    d = np.hypot(*(poly - np.roll(poly, 1, axis=0)).T)
    keep &= d > 1e-12 * scale
    return poly[keep]


# ---------------------------------------------------------------------- builders
def circular(
    *, thickness: float, voussoirs: int, span: float | None = None, rise: float | None = None,
    radius: float | None = None, embrace: float | None = None, joints: str = "radial",
    depth: float = 1.0, density: float = 2000.0,
) -> VoussoirChain:
    """A circular arch (full or segmental) from span and rise (m), or radius (m) and embrace
    (rad). With radial joints it is the closed-form `Arch`."""
    if radius is not None or embrace is not None:
        if radius is None or embrace is None or span is not None or rise is not None:
            raise InvalidParameterError("give either --span and --rise, or --radius and --embrace")
        if joints == "radial":
            return Arch(radius, thickness, embrace, voussoirs, depth, density)
        return ShapedArch("circular", 2 * radius * math.sin(0.5 * embrace),
                          radius * (1 - math.cos(0.5 * embrace)), thickness, voussoirs, joints,
                          depth, density)
    if span is None or rise is None:
        raise InvalidParameterError("a circular arch needs --span and --rise (or --radius and --embrace)")
    probe = ShapedArch("circular", span, rise, thickness, voussoirs, joints, depth, density)
    if joints == "radial":
        r, beta = probe._circle()
        return Arch(r, thickness, beta, voussoirs, depth, density)
    return probe


def segmental(*, span: float, rise: float, thickness: float, voussoirs: int,
              joints: str = "radial", depth: float = 1.0, density: float = 2000.0) -> VoussoirChain:
    """A segmental arch (rise <= span/2) from span and rise, m: the circular arch of radius
    (L^2/4 + f^2)/(2f) and embrace 2 atan(L / (2 (R - f)))."""
    ShapedArch("segmental", span, rise, thickness, voussoirs, joints, depth, density)  # validates
    return circular(span=span, rise=rise, thickness=thickness, voussoirs=voussoirs, joints=joints,
                    depth=depth, density=density)


def pointed(*, span: float, thickness: float, voussoirs: int, rise: float | None = None,
            eccentricity: float | None = None, joints: str = "radial", depth: float = 1.0,
            density: float = 2000.0) -> ShapedArch:
    """A pointed (two-centred) arch from span and rise, or span and eccentricity e = 2c/L
    (0 semicircle, 1 equilateral, < 1 drop, > 1 lancet)."""
    if (rise is None) == (eccentricity is None):
        raise InvalidParameterError("a pointed arch needs either --rise or --eccentricity")
    if eccentricity is not None:
        e = require_range("eccentricity", eccentricity, 0.0, 100.0, low_open=False, high_open=False)
        c = 0.5 * span * e
        rise = math.sqrt(0.25 * span * span + span * c)
    assert rise is not None  # exactly one of rise and eccentricity is given
    return ShapedArch("pointed", span, rise, thickness, voussoirs, joints, depth, density)


def shaped(shape: str, **kwargs) -> VoussoirChain:
    """Build any shape by name (`SHAPES`) from keyword arguments (see the builders)."""
    shape = str(shape).replace("_", "-").lower()
    if shape == "circular":
        return circular(**kwargs)
    if shape == "segmental":
        return segmental(**kwargs)
    if shape == "pointed":
        return pointed(**kwargs)
    check_shape(shape, _NAMES)
    extra = set(kwargs) - {"span", "rise", "thickness", "voussoirs", "joints", "depth", "density"}
    if extra:
        raise InvalidParameterError(f"a {shape} arch takes --span and --rise, not {sorted(extra)}")
    return ShapedArch(shape, **kwargs)


__all__ = ["HAUNCH_ANGLE", "JOINTS", "SHAPES", "ShapedArch", "circular", "pointed", "segmental",
           "shaped", "three_point_radius"]
