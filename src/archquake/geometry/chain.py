"""The one description of an arch: a chain of rigid blocks between two supports.

Every analysis (limit analysis, the four-link mechanism and its dynamics, the line of thrust,
the DEM, the plots) reads an arch through this interface only, so it works on every shape:

- ``voussoirs``: the number n of blocks, numbered 0..n-1 from the left support;
- ``intrados_points`` / ``extrados_points``: the two ends of the n+1 joints, shape (n+1, 2),
  m; joint 0 is the left support, joint n the right one, block k lies between joints k and
  k+1. The "intrados" end of a joint is the one on the right of the chain's direction
  (walking from the left support to the right one): the joint's normal, the intrados-to-
  extrados vector turned clockwise, points from block k-1 into block k;
- ``block_polygons``: the outline of each block, counter-clockwise, m (curved faces sampled);
- ``voussoir_masses`` / ``voussoir_centroids`` / ``voussoir_inertias``: exact mass properties
  (kg, m, kg m^2 about the centroid);
- ``radius``: the characteristic length (m) that scales times (sqrt(R/g)) and plots: the radius
  of the circle through the centreline's springing points and crown, which is R for a
  circular arch;
- ``thickness`` (ring thickness, m), ``depth`` (m), ``density`` (kg/m^3).

`Arch` (the circular arch with radial joints, closed-form
mass properties) is one builder of this type; `archquake.geometry.shapes` holds the
others, `archquake.geometry.survey` reads blocks from files, and `OnPiers` stands
any of them on piers (the pier courses become more blocks of the same chain).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from archquake._validate import require_positive
from archquake.errors import InvalidParameterError
from archquake.geometry.checks import (  # noqa: F401  (the ranges are re-exported here)
    MAX_DENSITY,
    MAX_DEPTH,
    MIN_DENSITY,
    MIN_DEPTH,
    MIN_THICKNESS_RATIO,
    Wording,
    check_density,
    check_depth,
    check_pier_values,
)
from archquake.geometry.polygon import polygon_area, polygon_mass_properties

#: A pier's parameters in the messages of `Piers`.
_PIER_NAMES = Wording(names={"pier_height": "pier height", "pier_width": "pier width",
                             "pier_courses": "pier courses"})


class VoussoirChain(ABC):
    """Base of every arch: the interface the analyses read (see the module docstring).

    Subclasses are frozen dataclasses that provide ``voussoirs``, ``thickness``, ``depth``,
    ``density``, ``radius``, `describe`, `scaled`, and either the joint ends and
    block polygons (`_build_layout`) or closed forms overriding the properties below.
    """

    voussoirs: int
    thickness: float
    depth: float
    density: float

    # ------------------------------------------------------------------ to provide
    # (``radius``, ``span``, ``rise``, ``embrace``, ``springing_y`` are fields of some
    # subclasses, so the base never defines them: a dataclass would take an inherited
    # attribute of a field's name for its default); the type checker sees them as read-only
    if TYPE_CHECKING:
        @property
        def radius(self) -> float: ...
        @property
        def span(self) -> float: ...
        @property
        def rise(self) -> float: ...
        @property
        def embrace(self) -> float: ...
        @property
        def springing_y(self) -> float: ...

    @abstractmethod
    def _build_layout(self) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        """(joints (n+1, 2, 2): intrados end [j, 0], extrados end [j, 1]; block polygons)."""

    @abstractmethod
    def describe(self) -> dict:
        """The arch's defining quantities, for reports and JSON (lengths in m)."""

    @abstractmethod
    def scaled(self, factor: float) -> VoussoirChain:
        """The geometrically similar arch with every length multiplied by ``factor``."""

    def with_thickness(self, thickness: float) -> VoussoirChain:
        """The same shape with another ring thickness (m), for the minimum-thickness search."""
        raise InvalidParameterError(
            f"{type(self).__name__} has no ring thickness to vary (blocks read from a file); "
            "the minimum thickness needs a parametric shape"
        )

    # ------------------------------------------------------------------ layout
    @cached_property
    def _layout(self) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        return self._build_layout()

    @cached_property
    def intrados_points(self) -> np.ndarray:
        """Intrados end of each joint, m, shape (n+1, 2)."""
        return self._layout[0][:, 0].copy()

    @cached_property
    def extrados_points(self) -> np.ndarray:
        """Extrados end of each joint, m, shape (n+1, 2)."""
        return self._layout[0][:, 1].copy()

    @property
    def block_polygons(self) -> tuple[np.ndarray, ...]:
        """Outline of every block, counter-clockwise, m, each shape (m_k, 2)."""
        return self._layout[1]

    def joint_point(self, joint: int, face: str) -> np.ndarray:
        """End point of ``joint`` on ``face`` ('intrados' or 'extrados'), m, shape (2,)."""
        face = str(getattr(face, "value", face))
        if face == "intrados":
            return self.intrados_points[joint].copy()
        if face == "extrados":
            return self.extrados_points[joint].copy()
        raise ValueError(f"face must be 'intrados' or 'extrados', got {face!r}")

    # ------------------------------------------------------------------ mass properties
    @cached_property
    def _mass_properties(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        props = [polygon_mass_properties(p, self.density, self.depth) for p in self.block_polygons]
        return (
            np.array([m for m, _, _ in props]),
            np.array([c for _, c, _ in props]),
            np.array([i for _, _, i in props]),
        )

    @cached_property
    def voussoir_masses(self) -> np.ndarray:
        """Mass of each block, kg, shape (n,)."""
        return self._mass_properties[0]

    @cached_property
    def voussoir_centroids(self) -> np.ndarray:
        """Centroid of each block, m, shape (n, 2)."""
        return self._mass_properties[1]

    @cached_property
    def voussoir_inertias(self) -> np.ndarray:
        """Mass moment of inertia of each block about its centroid, kg m^2, shape (n,)."""
        return self._mass_properties[2]

    @property
    def mass(self) -> float:
        """Total mass, kg."""
        return float(self.voussoir_masses.sum())

    # ------------------------------------------------------------------ drawing
    def voussoir_outline(self, k: int, arc_points: int = 8) -> np.ndarray:
        """Closed outline of block k, counter-clockwise, m (``arc_points`` is for the circular
        closed form; here the block polygon itself)."""
        return self.block_polygons[k].copy()

    def voussoir_polygon(self, k: int) -> np.ndarray:
        """Block k as the quadrilateral of its four joint end points, m, shape (4, 2),
        counter-clockwise: intrados right, extrados right, extrados left, intrados left."""
        ip, ep = self.intrados_points, self.extrados_points
        return np.array([ip[k + 1], ep[k + 1], ep[k], ip[k]])

    # ------------------------------------------------------------------ scalars
    @property
    def thickness_ratio(self) -> float:
        """t / R (ring thickness over the characteristic length), dimensionless."""
        return self.thickness / self.radius

    @property
    def joint_mid_points(self) -> np.ndarray:
        """Centre of every joint, m, shape (n+1, 2)."""
        return 0.5 * (self.intrados_points + self.extrados_points)

    @cached_property
    def extrados_radius(self) -> float:
        """Largest distance of any block vertex from the origin, m (R + t/2 for a circular
        arch): the radius of the origin-centred circle that holds the arch."""
        return float(max(np.hypot(p[:, 0], p[:, 1]).max() for p in self.block_polygons))

    @cached_property
    def crown_point(self) -> np.ndarray:
        """The highest point of the extrados, m, shape (2,)."""
        pts = np.vstack(self.block_polygons)
        return pts[int(np.argmax(pts[:, 1]))].copy()

    @cached_property
    def symmetric(self) -> bool:
        """True if the chain is its own mirror image in the vertical axis x = 0."""
        ip, ep = self.intrados_points, self.extrados_points
        tol = 1e-9 * self.radius
        mirror = np.array([-1.0, 1.0])
        return bool(
            np.allclose(ip[::-1] * mirror, ip, atol=tol) and np.allclose(ep[::-1] * mirror, ep, atol=tol)
            and np.allclose(self.voussoir_masses[::-1], self.voussoir_masses, rtol=1e-9)
        )


def check_tiling(chain: VoussoirChain, rtol: float = 1e-9) -> None:
    """Check that the blocks tile the ring: consecutive blocks share their joint, no block
    overlaps another, and every block is a counter-clockwise polygon with positive area.

    Raises
    ------
    InvalidParameterError
        Naming the first offending block or joint.
    """
    ip, ep = chain.intrados_points, chain.extrados_points
    polys = chain.block_polygons
    scale = max(float(np.ptp(np.vstack(polys), axis=0).max()), 1e-300)
    tol = rtol * scale
    for k, p in enumerate(polys):
        if polygon_area(p) <= 0.0:
            raise InvalidParameterError(f"block {k} is not a counter-clockwise polygon of positive area")
        for j in (k, k + 1):
            for q in (ip[j], ep[j]):
                if np.min(np.hypot(*(p - q).T)) > tol:
                    raise InvalidParameterError(
                        f"block {k} does not reach joint {j} at ({q[0]:.6g}, {q[1]:.6g}) m: the "
                        "blocks leave a gap"
                    )
    for a in range(len(polys)):
        for b in range(a + 1, len(polys)):
            if _overlap(polys[a], polys[b], tol):
                raise InvalidParameterError(f"blocks {a} and {b} overlap")


def _overlap(p: np.ndarray, q: np.ndarray, tol: float) -> bool:
    """True if the interiors of two simple polygons intersect (edges crossing properly, or a
    vertex of one strictly inside the other by more than ``tol``)."""
    lo = np.maximum(p.min(axis=0), q.min(axis=0))
    hi = np.minimum(p.max(axis=0), q.max(axis=0))
    if np.any(hi - lo <= tol):
        return False
    for a, b in ((p, q), (q, p)):
        # a point farther than tol inside b lies farther than tol inside b's bounding box: only
        # those points are tested (the same answer, far less work for the thousands of vertices
        # of a sampled face)
        near = np.all((a > b.min(axis=0) + tol) & (a < b.max(axis=0) - tol), axis=1)
        inside = _points_inside(a[near], b, tol)
        if np.any(inside):
            return True
    # proper crossings of edges: a crossing point lies on both edges, so in the boxes' overlap;
    # only edges whose own box meets it (with a margin of tol for rounding) can cross
    a0, a1 = _edges_meeting(p, lo - tol, hi + tol)
    b0, b1 = _edges_meeting(q, lo - tol, hi + tol)
    da = (a1 - a0)[:, None, :]
    db = (b1 - b0)[None, :, :]
    w = b0[None, :, :] - a0[:, None, :]
    den = da[..., 0] * db[..., 1] - da[..., 1] * db[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * db[..., 1] - w[..., 1] * db[..., 0]) / den
        u = (w[..., 0] * da[..., 1] - w[..., 1] * da[..., 0]) / den
    eps = 1e-9
    return bool(np.any((np.abs(den) > 0) & (s > eps) & (s < 1 - eps) & (u > eps) & (u < 1 - eps)))


def _edges_meeting(poly: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The edges of ``poly`` (start points, end points) whose bounding boxes meet the box
    [lo, hi]."""
    end = np.roll(poly, -1, axis=0)
    meets = np.all((np.maximum(poly, end) >= lo) & (np.minimum(poly, end) <= hi), axis=1)
    return poly[meets], end[meets]


def _points_inside(points: np.ndarray, poly: np.ndarray, tol: float) -> np.ndarray:
    """Which ``points`` lie inside ``poly`` farther than ``tol`` from its boundary."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    x0, y0 = poly[:, 0][None, :], poly[:, 1][None, :]
    x1, y1 = np.roll(poly[:, 0], -1)[None, :], np.roll(poly[:, 1], -1)[None, :]
    cond = (y0 > y) != (y1 > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
    crossings = np.sum(cond & (x < xc), axis=1)
    inside = crossings % 2 == 1
    # distance to the boundary
    d = poly[None, :, :]
    e = np.roll(poly, -1, axis=0)[None, :, :] - d
    r = points[:, None, :] - d
    tt = np.clip(np.sum(r * e, axis=2) / np.maximum(np.sum(e * e, axis=2), 1e-300), 0.0, 1.0)
    dist = np.hypot(*(r - tt[..., None] * e).transpose(2, 0, 1)).min(axis=1)
    return inside & (dist > tol)


# ---------------------------------------------------------------------- explicit blocks
@dataclass(frozen=True)
class BlockChain(VoussoirChain):
    """A chain given by its blocks and joints explicitly (a surveyed arch, or any builder's
    output frozen as numbers).

    Parameters
    ----------
    blocks : tuple of tuple of (x, y)
        Each block's outline, m, counter-clockwise (reoriented if given clockwise).
    joints : tuple of ((x_i, y_i), (x_e, y_e))
        The n+1 joints' intrados and extrados ends, m (see the module docstring).
    depth : float
        Out-of-plane depth, m.
    density : float
        kg/m^3.
    name : str
        What the blocks are (for the JSON description).
    """

    blocks: tuple
    joints: tuple
    depth: float = 1.0
    density: float = 2000.0
    name: str = "blocks"

    def __post_init__(self) -> None:
        blocks = tuple(tuple((float(x), float(y)) for x, y in b) for b in self.blocks)
        joints = tuple(tuple((float(x), float(y)) for x, y in j) for j in self.joints)
        if len(blocks) < 3:
            raise InvalidParameterError(f"an arch needs at least 3 blocks, got {len(blocks)}")
        if len(joints) != len(blocks) + 1:
            raise InvalidParameterError(
                f"{len(blocks)} blocks need {len(blocks) + 1} joints, got {len(joints)}"
            )
        fixed = []
        for k, b in enumerate(blocks):
            if len(b) < 3:
                raise InvalidParameterError(f"block {k} has {len(b)} vertices; a block needs 3 or more")
            arr = np.array(b)
            if np.allclose(arr[0], arr[-1]):
                arr = arr[:-1]
            if polygon_area(arr) < 0:
                arr = arr[::-1]
            fixed.append(tuple(map(tuple, arr.tolist())))
        object.__setattr__(self, "blocks", tuple(fixed))
        object.__setattr__(self, "joints", joints)
        check_depth(self.depth)
        check_density(self.density)
        object.__setattr__(self, "depth", float(self.depth))
        object.__setattr__(self, "density", float(self.density))
        check_tiling(self)

    @property
    def voussoirs(self) -> int:  # type: ignore[override]
        return len(self.blocks)

    def _build_layout(self):
        return np.array(self.joints, dtype=float), tuple(np.array(b, dtype=float) for b in self.blocks)

    @property
    def springing_y(self) -> float:
        """Mean y of the two support joints' centres, m."""
        mid = self.joint_mid_points
        return float(0.5 * (mid[0, 1] + mid[-1, 1]))

    @property
    def span(self) -> float:
        """Distance between the centres of the two support joints, m."""
        mid = self.joint_mid_points
        return float(np.hypot(*(mid[-1] - mid[0])))

    @property
    def rise(self) -> float:
        """Height of the highest joint centre above the springings, m."""
        return float(self.joint_mid_points[:, 1].max() - self.springing_y)

    @property
    def embrace(self) -> float:
        """Angle between the two support joints, rad (the angle of embrace of a circular arch
        with radial joints; pi for arches whose springing joints are horizontal)."""
        d0 = self.extrados_points[0] - self.intrados_points[0]
        d1 = self.extrados_points[-1] - self.intrados_points[-1]
        c = float(np.dot(d0, d1) / (np.hypot(*d0) * np.hypot(*d1)))
        return math.acos(max(-1.0, min(1.0, c)))

    @property
    def thickness(self) -> float:  # type: ignore[override]
        """Mean joint length, m."""
        d = self.extrados_points - self.intrados_points
        return float(np.hypot(d[:, 0], d[:, 1]).mean())

    @cached_property
    def radius(self) -> float:
        """Radius of the circle through the support joints' centres and the highest joint
        centre, m (the characteristic length; the half-span if these are collinear)."""
        return three_point_radius(self.joint_mid_points)

    def describe(self) -> dict:
        return {
            "shape": self.name,
            "voussoirs": self.voussoirs,
            "span_m": self.span,
            "rise_m": self.rise,
            "thickness_m": self.thickness,
            "length_scale_m": self.radius,
            "depth_m": self.depth,
            "density_kg_m3": self.density,
        }

    def scaled(self, factor: float) -> BlockChain:
        require_positive("scale factor", factor)
        f = float(factor)
        return BlockChain(
            tuple(tuple((x * f, y * f) for x, y in b) for b in self.blocks),
            tuple(tuple((x * f, y * f) for x, y in j) for j in self.joints),
            self.depth * f,
            self.density,
            self.name,
        )


def three_point_radius(mid: np.ndarray) -> float:
    """Radius of the circle through the first, the highest and the last of ``mid`` (m)."""
    a, c = mid[0], mid[-1]
    b = mid[int(np.argmax(mid[:, 1]))]
    ab, bc, ca = np.hypot(*(b - a)), np.hypot(*(c - b)), np.hypot(*(a - c))
    area2 = abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    if area2 <= 1e-12 * ca * ca:
        return float(0.5 * ca)
    return float(ab * bc * ca / (2.0 * area2))


# ---------------------------------------------------------------------- piers
@dataclass(frozen=True)
class Piers:
    """Two equal piers (buttresses) under the springings, standing on a rigid base.

    Parameters
    ----------
    height : float
        From the base to the intrados springing point, m (> 0).
    width : float
        Horizontal width, m; the pier's inner face is flush with the intrados springing point
        and it reaches at least to the extrados springing point.
    courses : int
        Number of courses (blocks) between horizontal bed joints (>= 1).
    """

    height: float
    width: float
    courses: int = 1

    def __post_init__(self) -> None:
        check_pier_values(self.height, self.width, self.courses, _PIER_NAMES)
        object.__setattr__(self, "height", float(self.height))
        object.__setattr__(self, "width", float(self.width))
        object.__setattr__(self, "courses", int(self.courses))


@dataclass(frozen=True)
class OnPiers(VoussoirChain):
    """An arch standing on two piers on a rigid base: one chain of blocks, the left pier's
    courses bottom-up, the arch's voussoirs, the right pier's courses top-down.

    Joint 0 is the left pier's base, joint ``courses`` its top (the arch's left springing),
    and so on; four-hinge mechanisms may put hinges at any of them (the global arch-on-piers
    mechanisms). On a pier's bed joints the intrados end is the face towards the opening.

    Parameters
    ----------
    arch : VoussoirChain
        The arch (any shape), on supports at its joints 0 and n.
    piers : Piers

    Raises
    ------
    InvalidParameterError
        A pier narrower than its springing joint's horizontal extent, or a springing joint
        that faces away from the pier (the arch must spring on top of it).
    """

    arch: VoussoirChain
    piers: Piers

    def __post_init__(self) -> None:
        ip, ep = self.arch.intrados_points, self.arch.extrados_points
        for j, side in ((0, -1.0), (-1, 1.0)):
            reach = side * (ep[j, 0] - ip[j, 0])
            if reach > self.piers.width * (1 + 1e-12):
                raise InvalidParameterError(
                    f"--pier-width must be at least the springing joint's horizontal extent, "
                    f"{reach:.4g} m (the arch must spring on top of the pier), got "
                    f"{self.piers.width:g} m"
                )
            if reach < 0.0 or ep[j, 1] < ip[j, 1] - 1e-12 * self.arch.radius:
                raise InvalidParameterError(
                    "the arch's springing joints must face down onto the piers (intrados end "
                    "inner and lower)"
                )

    @property
    def voussoirs(self) -> int:  # type: ignore[override]
        return self.arch.voussoirs + 2 * self.piers.courses

    @property
    def thickness(self) -> float:  # type: ignore[override]
        return self.arch.thickness

    @property
    def depth(self) -> float:  # type: ignore[override]
        return self.arch.depth

    @property
    def density(self) -> float:  # type: ignore[override]
        return self.arch.density

    @property
    def radius(self) -> float:
        return self.arch.radius

    @property
    def embrace(self) -> float:
        return self.arch.embrace

    @property
    def span(self) -> float:
        return self.arch.span

    @property
    def rise(self) -> float:
        return self.arch.rise

    @property
    def springing_y(self) -> float:
        return self.arch.springing_y

    @property
    def base_y(self) -> float:
        """y of the rigid base, m."""
        return float(self.arch.intrados_points[0, 1] - self.piers.height)

    def _pier(self, side: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """Bed joints bottom-up (intrados = inner end) and courses bottom-up of one pier
        (side -1 left, +1 right), before orienting them along the chain."""
        arch, pier = self.arch, self.piers
        j = 0 if side < 0 else -1
        ip, ep = arch.intrados_points[j], arch.extrados_points[j]
        x_in = float(ip[0])
        x_out = x_in + side * pier.width
        y0 = self.base_y
        top = float(ip[1])
        levels = y0 + (top - y0) * np.arange(pier.courses) / pier.courses
        beds = [np.array([[x_in, y], [x_out, y]]) for y in levels]
        courses = []
        for c in range(pier.courses):
            yb = levels[c]
            if c < pier.courses - 1:
                yt = levels[c + 1]
                poly = [[x_in, yb], [x_out, yb], [x_out, yt], [x_in, yt]]
            else:
                # top course: its top is the springing joint, then level to the pier's outer face
                poly = [[x_in, yb], [x_out, yb], [x_out, ep[1]]]
                if abs(ep[0] - x_out) > 1e-12 * arch.radius:
                    poly.append([ep[0], ep[1]])
                poly.append([ip[0], ip[1]])
            p = np.array(poly, dtype=float)
            if polygon_area(p) < 0:
                p = p[::-1]
            courses.append(p)
        return beds, courses

    def _build_layout(self):
        lb, lc = self._pier(-1)
        rb, rc = self._pier(+1)
        arch_joints = np.stack([self.arch.intrados_points, self.arch.extrados_points], axis=1)
        # left pier bottom-up: intrados end is the inner (right) end; right pier top-down
        left = [b for b in lb]
        right = [b for b in rb[::-1]]
        joints = np.concatenate([np.array(left), arch_joints, np.array(right)], axis=0)
        blocks = tuple(lc) + tuple(self.arch.block_polygons) + tuple(rc[::-1])
        return joints, blocks

    @cached_property
    def _mass_properties(self):
        # the arch's own (exact, closed form for circular arches) plus the piers' polygons
        lb, lc = self._pier(-1)
        rb, rc = self._pier(+1)
        pm = [polygon_mass_properties(p, self.density, self.depth) for p in lc]
        qm = [polygon_mass_properties(p, self.density, self.depth) for p in rc[::-1]]
        a = self.arch
        return (
            np.concatenate([[m for m, _, _ in pm], a.voussoir_masses, [m for m, _, _ in qm]]),
            np.vstack([[c for _, c, _ in pm], a.voussoir_centroids, [c for _, c, _ in qm]]),
            np.concatenate([[i for _, _, i in pm], a.voussoir_inertias, [i for _, _, i in qm]]),
        )

    def describe(self) -> dict:
        return {
            **self.arch.describe(),
            "pier_height_m": self.piers.height,
            "pier_width_m": self.piers.width,
            "pier_courses": self.piers.courses,
            "voussoirs": self.arch.voussoirs,
            "blocks": self.voussoirs,
        }

    def scaled(self, factor: float) -> OnPiers:
        require_positive("scale factor", factor)
        p = self.piers
        return OnPiers(self.arch.scaled(factor), Piers(p.height * factor, p.width * factor, p.courses))

    def with_thickness(self, thickness: float) -> OnPiers:
        return replace(self, arch=self.arch.with_thickness(thickness))


__all__ = ["BlockChain", "OnPiers", "Piers", "VoussoirChain", "check_tiling", "three_point_radius"]
