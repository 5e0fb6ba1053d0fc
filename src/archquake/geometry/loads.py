"""What an arch carries: fill, backing, loads on the extrados and traffic (one description that
every analysis reads), and its translation into per-block extras.

Conventions (SI; forces per metre of barrel width are multiplied by the arch's ``depth``):

- **Positions** along the span are measured horizontally from the left springing of the
  intrados, m: 0 is the left intrados springing, the clear span (the right intrados
  springing's x minus the left one's) the right one.
- **Fill** (the column model, the dead load of LimitState:RING and of the Italian seismic
  practice). A horizontal fill surface at ``depth`` above the crown's extrados (or at an
  absolute ``level`` for a surveyed arch). The fill above block k is the column between the
  verticals through the extrados ends of joints k and k+1, from the extrados up to the fill
  surface. The column rides on block k: its weight and, in an earthquake, its horizontal
  inertia act at the column's centroid. No arching, no shear between columns, no passive
  pressure (see below).
- **Backing**: solid masonry up to a height above each springing (the intrados springing's
  y). A joint whose extrados end is at or below the backing's top is held: no hinge forms
  there, and the blocks below it belong to the support. The backing's own weight goes to
  the support, not onto the arch; the fill above the held blocks is carried with them.
- **Point and distributed loads** act vertically on the extrados (a wall, a truss, a vault's
  springing). A point load at x sits on the block whose fill column holds x (the right one
  at a column boundary), at the extrados point above x. With ``moves_with_arch`` its mass,
  load/g, moves with that block (its horizontal inertia acts at that extrados point);
  otherwise it is a weight only.
- **Traffic**: an axle (``length`` 0) or a patch of ``length`` m, ``load`` N per metre of
  barrel width in all, at ``position``. With a ``dispersion`` angle delta from the vertical
  it spreads uniformly through the fill, depth h under its centre, to l = length + 2 h tan
  delta on the extrados (the 2:1 slope is 26.57 degrees); parts spread beyond the extrados's
  ends go into the abutments. Traffic is a statics load only (its multiplier is the
  capacity) and never carries mass.
- **Passive fill pressure** (`Passive`) is off unless given, and every result that
  reads the loads says which: a mobilised fraction of Rankine's K_p on the extrados, per
  block and face one resultant that the fill may mobilise from 0 to its limit, towards the
  ring (so it resists only where the arch moves into the fill).

Examples
--------
>>> import math
>>> from archquake.geometry.arch import Arch
>>> arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
>>> extras = block_extras(arch, Loads(fill=Fill(depth=1.0, density=1800.0)))
>>> area = float(extras.mass.sum()) / 1800.0   # m^2 between the extrados and the surface
>>> round(area, 4), round(2 * 5.3 * 6.3 - math.pi * 5.3**2 / 2, 4)
(22.6563, 22.6563)
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from archquake._validate import require_finite, require_instance, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.chain import MAX_DENSITY, OnPiers, VoussoirChain
from archquake.geometry.polygon import polygon_area, polygon_mass_properties

#: Largest fill depth over the crown, backing height and load extent, m.
MAX_LOAD_LENGTH_M = 1000.0
#: Largest load per metre of barrel width, N/m (100 MN/m).
MAX_LOAD_N_M = 1e8
#: Largest dispersion angle from the vertical, degrees.
MAX_DISPERSION_DEG = 60.0


@dataclass(frozen=True)
class Fill:
    """A horizontal fill surface and the fill's density.

    Parameters
    ----------
    depth : float, optional
        Depth of the fill surface above the crown's extrados (its highest point), m, >= 0.
    density : float
        Fill density, kg/m^3 (0 to the masonry's largest).
    level : float, optional
        The fill surface's absolute y, m, instead of ``depth`` (surveyed arches); at or above
        the highest point of the extrados.
    """

    depth: float | None = None
    density: float = 1800.0
    level: float | None = None

    def __post_init__(self) -> None:
        if (self.depth is None) == (self.level is None):
            raise InvalidParameterError("a fill needs its depth over the crown or its surface "
                                        "level, not both")
        if self.depth is not None:
            object.__setattr__(self, "depth", require_range(
                "fill depth", self.depth, 0.0, MAX_LOAD_LENGTH_M, "m", low_open=False,
                high_open=False))
        else:
            object.__setattr__(self, "level", require_finite("fill level", self.level, "m"))
        object.__setattr__(self, "density", require_range(
            "fill density", self.density, 0.0, MAX_DENSITY, "kg/m^3", low_open=False,
            high_open=False))

    def surface(self, arch: VoussoirChain) -> float:
        """The fill surface's y for ``arch``, m."""
        top = float(np.max(arch.extrados_points[:, 1]))
        top = max(top, float(arch.crown_point[1]))
        if self.depth is not None:
            return top + self.depth
        assert self.level is not None
        if self.level < top - 1e-9 * max(1.0, abs(top)):
            raise InvalidParameterError(
                f"fill level must be at or above the extrados's highest point, y = {top:.4g} m; "
                f"got {self.level:.4g} m")
        return float(self.level)

    def to_dict(self) -> dict:
        return {"depth_m": self.depth, "level_m": self.level, "density_kg_m3": self.density}


@dataclass(frozen=True)
class Backing:
    """Solid masonry up to ``left`` (and ``right``, default the same) m above each springing."""

    left: float
    right: float | None = None

    def __post_init__(self) -> None:
        left = require_range("backing height", self.left, 0.0, MAX_LOAD_LENGTH_M, "m",
                             low_open=False, high_open=False)
        right = left if self.right is None else require_range(
            "backing height (right)", self.right, 0.0, MAX_LOAD_LENGTH_M, "m", low_open=False,
            high_open=False)
        object.__setattr__(self, "left", left)
        object.__setattr__(self, "right", right)

    def to_dict(self) -> dict:
        return {"left_m": self.left, "right_m": self.right}


def _load(name: str, value: object) -> float:
    return require_range(name, value, -MAX_LOAD_N_M, MAX_LOAD_N_M, "N/m", low_open=False,
                         high_open=False)


def _position(name: str, value: object) -> float:
    return require_range(name, value, 0.0, MAX_LOAD_LENGTH_M, "m", low_open=False,
                         high_open=False)


@dataclass(frozen=True)
class PointLoad:
    """A vertical load on the extrados: ``load`` N per metre of barrel width (downwards
    positive) at ``position`` m along the span; ``moves_with_arch``: its mass (load / g)
    follows its block in an earthquake."""

    position: float
    load: float
    moves_with_arch: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _position("point load position", self.position))
        object.__setattr__(self, "load", _load("point load", self.load))
        object.__setattr__(self, "moves_with_arch", bool(self.moves_with_arch))

    def to_dict(self) -> dict:
        return {"position_m": self.position, "load_N_m": self.load,
                "moves_with_arch": self.moves_with_arch}


@dataclass(frozen=True)
class DistributedLoad:
    """A uniform vertical load on the extrados: ``pressure`` N/m per metre of barrel width
    (Pa, downwards positive) from ``start`` to ``end`` m along the span."""

    start: float
    end: float
    pressure: float
    moves_with_arch: bool = True

    def __post_init__(self) -> None:
        start = _position("distributed load start", self.start)
        end = _position("distributed load end", self.end)
        if not end > start:
            raise InvalidParameterError(
                f"distributed load end must exceed its start ({start:g} m), got {end:g} m")
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "end", end)
        object.__setattr__(self, "pressure", _load("distributed load", self.pressure))
        object.__setattr__(self, "moves_with_arch", bool(self.moves_with_arch))

    def to_dict(self) -> dict:
        return {"start_m": self.start, "end_m": self.end, "pressure_Pa": self.pressure,
                "moves_with_arch": self.moves_with_arch}


@dataclass(frozen=True)
class Traffic:
    """An axle (``length`` 0) or a patch: ``load`` N per metre of barrel width in all, centred
    at ``position`` m along the span, spread through the fill at ``dispersion`` degrees from
    the vertical (None: not spread), or with ``boussinesq`` by Flamant's 2-D elastic stress
    (see `traffic_actions`)."""

    load: float
    position: float = 0.0
    length: float = 0.0
    dispersion: float | None = None
    boussinesq: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "boussinesq", bool(self.boussinesq))
        if self.boussinesq and self.dispersion is not None:
            raise InvalidParameterError("traffic dispersion: give an angle or Boussinesq, not "
                                        "both")
        load = require_range("traffic load", self.load, 0.0, MAX_LOAD_N_M, "N/m",
                             low_open=True, high_open=False)
        object.__setattr__(self, "load", load)
        object.__setattr__(self, "position", _position("traffic position", self.position))
        object.__setattr__(self, "length", require_range(
            "traffic patch length", self.length, 0.0, MAX_LOAD_LENGTH_M, "m", low_open=False,
            high_open=False))
        if self.dispersion is not None:
            object.__setattr__(self, "dispersion", require_range(
                "traffic dispersion", self.dispersion, 0.0, MAX_DISPERSION_DEG, "degrees",
                low_open=False, high_open=False))

    def at(self, position: float) -> Traffic:
        """The same load at another position, m."""
        return Traffic(self.load, position, self.length, self.dispersion, self.boussinesq)

    def to_dict(self) -> dict:
        return {"load_N_m": self.load, "position_m": self.position, "length_m": self.length,
                "dispersion_deg": self.dispersion, "boussinesq": self.boussinesq}


@dataclass(frozen=True)
class Passive:
    """Passive fill pressure where the arch sways into the fill (off unless given).

    A mobilised fraction of Rankine's passive pressure, sigma_h(z) = fraction K_p gamma z,
    K_p = tan^2(45 deg + phi/2), z the depth below the fill surface, on the extrados as RING and
    Grandjean (2010) take it. Per block, the extrados facing left and the extrados facing
    right each have one resultant (the pressure integrated over the face's height, at its
    centre of pressure); the fill pushes on the block with any horizontal force from 0 up to
    that resultant, towards the ring: so it resists only where the arch moves into the fill.

    Parameters
    ----------
    fraction : float
        Mobilised fraction m_p of K_p, in (0, 1] (Grandjean: 0.33; Gilbert et al.: realistic
        loads need the mobilised, not the peak, strength).
    friction : float
        The fill's friction angle phi, degrees, in [0, 60) (default 30).
    """

    fraction: float
    friction: float = 30.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "fraction", require_range(
            "passive fraction", self.fraction, 0.0, 1.0, low_open=True, high_open=False))
        object.__setattr__(self, "friction", require_range(
            "fill friction angle", self.friction, 0.0, 60.0, "degrees", low_open=False,
            high_open=True))

    @property
    def kp(self) -> float:
        """Rankine's passive coefficient tan^2(45 deg + phi/2)."""
        return math.tan(math.radians(45.0 + 0.5 * self.friction)) ** 2

    def to_dict(self) -> dict:
        return {"fraction_of_kp": self.fraction, "friction_deg": self.friction, "kp": self.kp}


@dataclass(frozen=True)
class Loads:
    """Everything an arch carries (each part optional). Passive fill pressure is not modelled."""

    fill: Fill | None = None
    backing: Backing | None = None
    point_loads: tuple[PointLoad, ...] = field(default_factory=tuple)
    distributed_loads: tuple[DistributedLoad, ...] = field(default_factory=tuple)
    traffic: Traffic | None = None
    passive: Passive | None = None

    def __post_init__(self) -> None:
        if self.passive is not None:
            require_instance("passive", self.passive, Passive, "a Passive")
            if self.fill is None or self.fill.density == 0.0:
                raise InvalidParameterError("passive fill pressure needs a fill with a density")
        if self.fill is not None:
            require_instance("fill", self.fill, Fill, "a Fill")
        if self.backing is not None:
            require_instance("backing", self.backing, Backing, "a Backing")
        if self.traffic is not None:
            require_instance("traffic", self.traffic, Traffic, "a Traffic")
        object.__setattr__(self, "point_loads", tuple(
            require_instance("point load", p, PointLoad, "a PointLoad") for p in self.point_loads))
        object.__setattr__(self, "distributed_loads", tuple(
            require_instance("distributed load", d, DistributedLoad, "a DistributedLoad")
            for d in self.distributed_loads))

    @property
    def empty(self) -> bool:
        """True if the arch carries nothing."""
        return (self.fill is None and self.backing is None and not self.point_loads
                and not self.distributed_loads and self.traffic is None and self.passive is None)

    def without_traffic(self) -> Loads:
        return Loads(self.fill, self.backing, self.point_loads, self.distributed_loads, None,
                     self.passive)

    def with_traffic(self, traffic: Traffic) -> Loads:
        return Loads(self.fill, self.backing, self.point_loads, self.distributed_loads, traffic,
                     self.passive)

    def to_dict(self) -> dict:
        return {
            "fill": None if self.fill is None else self.fill.to_dict(),
            "backing": None if self.backing is None else self.backing.to_dict(),
            "point_loads": [p.to_dict() for p in self.point_loads],
            "distributed_loads": [d.to_dict() for d in self.distributed_loads],
            "traffic": None if self.traffic is None else self.traffic.to_dict(),
            "passive_pressure": ("off (not modelled)" if self.passive is None
                                 else self.passive.to_dict()),
        }


# ---------------------------------------------------------------------------------------------
# The extrados as a curve y_e(x)
# ---------------------------------------------------------------------------------------------


def _extrados_path(arch: VoussoirChain, k: int, outline: np.ndarray) -> np.ndarray:
    """The extrados edge of block k (``outline``), from the extrados end of joint k to that of
    joint k+1 (the outline's vertices between them), m, shape (m, 2)."""
    poly = np.asarray(outline, dtype=float)
    if polygon_area(poly) < 0:
        poly = poly[::-1]
    ep = arch.extrados_points
    i_right = int(np.argmin(np.hypot(*(poly - ep[k + 1]).T)))
    i_left = int(np.argmin(np.hypot(*(poly - ep[k]).T)))
    # counter-clockwise, the extrados runs from the right joint's end to the left one's
    idx = [(i_right + s) % len(poly) for s in range((i_left - i_right) % len(poly) + 1)]
    path = poly[idx][::-1].copy()
    path[0], path[-1] = ep[k], ep[k + 1]
    return path


@dataclass(frozen=True)
class Extrados:
    """The extrados of an arch as a curve y_e(x) and the blocks' column boundaries.

    Attributes
    ----------
    paths : tuple of ndarray
        Extrados edge of each block, left to right, m.
    edges : ndarray, shape (n+1,)
        x of the joints' extrados ends (the fill columns' verticals), m, increasing.
    x0 : float
        x of the left springing of the intrados (positions are measured from it), m.
    clear_span : float
        Between the intrados springings, m.
    """

    paths: tuple[np.ndarray, ...]
    edges: np.ndarray
    x0: float
    clear_span: float

    @classmethod
    def of(cls, arch: VoussoirChain) -> Extrados:
        """The extrados of ``arch`` (built once per arch: arches are frozen)."""
        try:
            hash(arch)
        except TypeError:
            return cls._build(arch)
        return _memoised_extrados(arch)

    @classmethod
    def _build(cls, arch: VoussoirChain) -> Extrados:
        if isinstance(arch, OnPiers):
            raise InvalidParameterError("loads on an arch standing on piers are not modelled; "
                                        "leave the piers out")
        outlines = arch.block_polygons
        paths = tuple(_extrados_path(arch, k, outlines[k]) for k in range(arch.voussoirs))
        x = np.concatenate([p[:, 0] for p in paths])
        if np.any(np.diff(x) < -1e-9 * max(1.0, float(np.ptp(x)))):
            raise InvalidParameterError(
                "loads need an extrados that runs left to right over its whole length "
                "(an embrace of at most 180 degrees)")
        ip = arch.intrados_points
        return cls(paths, arch.extrados_points[:, 0].copy(), float(ip[0, 0]),
                   float(ip[-1, 0] - ip[0, 0]))

    def x_at(self, position: float, what: str = "position") -> float:
        """x of a position along the span, m (checked to lie on the clear span)."""
        if not 0.0 <= position <= self.clear_span * (1 + 1e-12):
            raise InvalidParameterError(
                f"{what} must be from 0 to the clear span, {self.clear_span:.4g} m, got "
                f"{position:g} m")
        return self.x0 + position

    def y_at(self, x: float | np.ndarray) -> np.ndarray:
        """y_e(x) of the extrados, m."""
        pts = np.vstack(self.paths)
        return np.interp(x, pts[:, 0], pts[:, 1])

    def block_at(self, x: float) -> int:
        """The block whose column holds x (the right one at a boundary)."""
        n = self.edges.size - 1
        k = int(np.searchsorted(self.edges, x, side="right")) - 1
        return min(max(k, 0), n - 1)

    def split(self, a: float, b: float) -> list[tuple[int, float, float]]:
        """[a, b] cut at the column boundaries: (block, start, end) of each non-empty piece."""
        out = []
        e = self.edges
        for k in range(e.size - 1):
            lo, hi = max(a, e[k]), min(b, e[k + 1])
            if hi > lo:
                out.append((k, float(lo), float(hi)))
        return out

    def mean_y(self, a: float, b: float) -> float:
        """The mean of y_e over [a, b] (exact on the piecewise linear path), m."""
        pts = np.vstack(self.paths)
        xs = np.unique(np.concatenate([[a, b], pts[(pts[:, 0] > a) & (pts[:, 0] < b), 0]]))
        ys = np.interp(xs, pts[:, 0], pts[:, 1])
        return float(np.trapezoid(ys, xs) / (b - a))


def _extrados_of(arch: VoussoirChain) -> Extrados:
    return Extrados._build(arch)


_memoised_extrados = functools.lru_cache(maxsize=32)(_extrados_of)


# ---------------------------------------------------------------------------------------------
# Per-block extras
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class BlockExtras:
    """What each block carries, as packed arrays (n blocks).

    Attributes
    ----------
    mass : ndarray, shape (n,)
        Mass that moves with each block (fill column, loads that move with the arch), kg.
    centroid : ndarray, shape (n, 2)
        Centroid of that mass, m (the block's own centroid where the mass is 0).
    inertia : ndarray, shape (n,)
        Its rotational inertia about that centroid, kg m^2 (point masses add none).
    weight_force : ndarray, shape (n, 2)
        Weights that do not move with the arch (loads whose mass stays put), N.
    weight_moment : ndarray, shape (n,)
        Their moment about the origin, N m.
    held : ndarray of bool, shape (n+1,)
        Joints the backing holds (no hinge, no constraint on the line of thrust).
    fill_columns : tuple of ndarray
        Each block's fill column outline, m (empty arrays where there is none), for drawing.
    surface : float or None
        The fill surface's y, m.
    """

    mass: np.ndarray
    centroid: np.ndarray
    inertia: np.ndarray
    weight_force: np.ndarray
    weight_moment: np.ndarray
    held: np.ndarray
    fill_columns: tuple[np.ndarray, ...]
    surface: float | None

    def to_dict(self) -> dict:
        return {"carried_mass_kg": self.mass, "carried_centroid_x_m": self.centroid[:, 0],
                "carried_centroid_y_m": self.centroid[:, 1],
                "carried_inertia_kg_m2": self.inertia,
                "held_joints": [int(j) for j in np.flatnonzero(self.held)],
                "fill_surface_m": self.surface}


class _Lumps:
    """Masses with centroids and inertias, summed per block by the parallel-axis theorem."""

    def __init__(self, n: int):
        self.items: list[list[tuple[float, np.ndarray, float]]] = [[] for _ in range(n)]

    def add(self, k: int, mass: float, centroid: np.ndarray, inertia: float = 0.0) -> None:
        if mass != 0.0:
            self.items[k].append((mass, np.asarray(centroid, dtype=float), inertia))

    def pack(self, fallback: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        n = len(self.items)
        mass, cen, inertia = np.zeros(n), fallback.copy(), np.zeros(n)
        for k, items in enumerate(self.items):
            if not items:
                continue
            m = sum(i[0] for i in items)
            if m == 0.0:
                continue
            c = sum(i[0] * i[1] for i in items) / m
            inertia[k] = sum(i[2] + i[0] * float(np.sum((i[1] - c) ** 2)) for i in items)
            mass[k], cen[k] = m, c
        return mass, cen, inertia


def held_joints(arch: VoussoirChain, backing: Backing | None) -> np.ndarray:
    """Joints whose extrados end is at or below the backing's top, on each side (contiguous
    from each springing), shape (n+1,) of bool."""
    n = arch.voussoirs
    held = np.zeros(n + 1, dtype=bool)
    if backing is None:
        return held
    ip, ep = arch.intrados_points, arch.extrados_points
    top_left = ip[0, 1] + backing.left
    top_right = ip[-1, 1] + float(backing.right if backing.right is not None else backing.left)
    if backing.left > 0:
        j = 0
        while j <= n and ep[j, 1] <= top_left:
            held[j] = True
            j += 1
    if (backing.right or 0.0) > 0:
        j = n
        while j >= 0 and ep[j, 1] <= top_right:
            held[j] = True
            j -= 1
    return held


def fill_columns(arch: VoussoirChain, surface: float, extrados: Extrados | None = None
                 ) -> tuple[np.ndarray, ...]:
    """Each block's fill column, counter-clockwise outline, m (see the module docstring)."""
    ex = extrados or Extrados.of(arch)
    out = []
    for path in ex.paths:
        top = np.array([[path[-1, 0], surface], [path[0, 0], surface]])
        poly = np.vstack([path, top])
        if path[-1, 0] - path[0, 0] <= 0.0 or polygon_area(poly) <= 0.0:
            out.append(np.zeros((0, 2)))
            continue
        out.append(poly)
    return tuple(out)


def block_extras(arch: VoussoirChain, loads: Loads, *, g: float = STANDARD_GRAVITY
                 ) -> BlockExtras:
    """Turn ``loads`` into what each block of ``arch`` carries (traffic excluded: see
    `traffic_actions`).

    Parameters
    ----------
    arch : VoussoirChain
    loads : Loads
    g : float
        Gravity, m/s^2 (a load's mass is load / g).

    Returns
    -------
    BlockExtras
    """
    require_instance("loads", loads, Loads, "a Loads")
    n = arch.voussoirs
    lumps = _Lumps(n)
    wf, wm = np.zeros((n, 2)), np.zeros(n)
    columns: tuple[np.ndarray, ...] = tuple(np.zeros((0, 2)) for _ in range(n))
    surface = None
    need = loads.fill is not None or loads.point_loads or loads.distributed_loads
    ex = Extrados.of(arch) if need else None
    if loads.fill is not None and ex is not None:
        surface = loads.fill.surface(arch)
        columns = fill_columns(arch, surface, ex)
        if loads.fill.density > 0.0:
            for k, col in enumerate(columns):
                if col.size:
                    m, c, i = polygon_mass_properties(col, loads.fill.density, arch.depth)
                    lumps.add(k, m, c, i)
    for p in loads.point_loads:
        assert ex is not None
        x = ex.x_at(p.position, "point load position")
        k = ex.block_at(x)
        point = np.array([x, float(ex.y_at(x))])
        force = p.load * arch.depth
        if p.moves_with_arch:
            lumps.add(k, force / g, point)
        else:
            wf[k, 1] -= force
            wm[k] += x * -force
    for d in loads.distributed_loads:
        assert ex is not None
        a = ex.x_at(d.start, "distributed load start")
        b = ex.x_at(d.end, "distributed load end")
        for k, lo, hi in ex.split(a, b):
            force = d.pressure * (hi - lo) * arch.depth
            xm = 0.5 * (lo + hi)
            if d.moves_with_arch:
                lumps.add(k, force / g, np.array([xm, ex.mean_y(lo, hi)]))
            else:
                wf[k, 1] -= force
                wm[k] += xm * -force
    mass, cen, inertia = lumps.pack(np.asarray(arch.voussoir_centroids, dtype=float))
    return BlockExtras(mass, cen, inertia, wf, wm, held_joints(arch, loads.backing), columns,
                       surface)


def passive_resultants(arch: VoussoirChain, loads: Loads, *, g: float = STANDARD_GRAVITY
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The largest passive forces the fill can put on each block (`Passive`).

    Returns
    -------
    blocks : ndarray of int, shape (s,)
    points : ndarray, shape (s, 2)
        Centres of pressure, m.
    directions : ndarray, shape (s,)
        +1 where the fill pushes the block towards +x (its extrados faces left), else -1.
    limits : ndarray, shape (s,)
        The mobilised passive resultant, N (over the arch's depth).
    """
    empty = (np.zeros(0, dtype=np.int64), np.zeros((0, 2)), np.zeros(0), np.zeros(0))
    if loads.passive is None or loads.fill is None:
        return empty
    ex = Extrados.of(arch)
    ys = loads.fill.surface(arch)
    k = loads.passive.fraction * loads.passive.kp * loads.fill.density * g * arch.depth
    blocks, points, dirs, limits = [], [], [], []
    for b, path in enumerate(ex.paths):
        y1, y2 = path[:-1, 1], path[1:, 1]
        x1, x2 = path[:-1, 0], path[1:, 0]
        for sign in (1.0, -1.0):  # faces left (rising, dy > 0), faces right (falling)
            take = sign * (y2 - y1) > 0
            if not np.any(take):
                continue
            lo, hi = np.minimum(y1, y2)[take], np.maximum(y1, y2)[take]
            # int (ys - y) dy and int y (ys - y) dy over each segment's height
            f = ys * (hi - lo) - 0.5 * (hi**2 - lo**2)
            fy = 0.5 * ys * (hi**2 - lo**2) - (hi**3 - lo**3) / 3.0
            force = float(f.sum())
            if force <= 0.0:
                continue
            yc = float(fy.sum()) / force
            # x of the centre of pressure on the face (where the face is at height yc)
            xs, yv = np.concatenate([x1[take], x2[take][-1:]]), np.concatenate(
                [y1[take], y2[take][-1:]])
            order = np.argsort(yv)
            xc = float(np.interp(yc, yv[order], xs[order]))
            blocks.append(b)
            points.append((xc, yc))
            dirs.append(sign)
            limits.append(k * force)
    if not blocks:
        return empty
    return (np.array(blocks, dtype=np.int64), np.array(points), np.array(dirs),
            np.array(limits))


#: Sample points per block column, and line loads per patch, of the Flamant integration.
_FLAMANT_POINTS = 400
_FLAMANT_LINES = 21


def _flamant(ex: Extrados, surface: float, x0: float, length: float, total: float, n: int
             ) -> tuple[np.ndarray, np.ndarray, list[tuple[float, float]]]:
    """Flamant's vertical stress of a line load P on an elastic half-space, at depth z,
    sigma_z = 2 P z^3 / (pi ((x - x0)^2 + z^2)^2), taken at the extrados's own depth below
    the fill surface, z(x) = surface - y_e(x); a patch as uniform line loads across its length.
    The stress over each block's column gives its force and line of action; all is scaled so
    that the whole load reaches the extrados (what the half-space would carry past its ends
    is put back on the arch: on the safe side)."""
    force, moment = np.zeros((n, 2)), np.zeros(n)
    sources = (np.array([x0]) if length <= 0.0 else
               x0 + length * (np.arange(_FLAMANT_LINES) + 0.5) / _FLAMANT_LINES - 0.5 * length)
    per_block = []
    for k in range(n):
        xs = np.linspace(ex.edges[k], ex.edges[k + 1], _FLAMANT_POINTS)
        z = np.maximum(surface - ex.y_at(xs), 1e-12)
        d = xs[:, None] - sources[None, :]
        sigma = (2.0 / np.pi) * (z[:, None] ** 3 / (d * d + z[:, None] ** 2) ** 2).mean(axis=1)
        f = float(np.trapezoid(sigma, xs))
        fx = float(np.trapezoid(sigma * xs, xs))
        per_block.append((f, fx))
    whole = sum(f for f, _ in per_block)
    for k, (f, fx) in enumerate(per_block):
        share = total * f / whole
        force[k, 1] = -share
        moment[k] = -share * (fx / f if f > 0 else 0.0)
    return force, moment, [(float(ex.edges[0]), float(ex.edges[-1]))]


def traffic_actions(arch: VoussoirChain, loads: Loads, traffic: Traffic
                    ) -> tuple[np.ndarray, np.ndarray, list[tuple[float, float]]]:
    """The traffic load on each block: forces (n, 2) N, moments about the origin (n,) N m,
    and the extent [x_a, x_b] (m) it covers on the extrados (a point: x_a = x_b).

    The load, spread through the fill when ``traffic.dispersion`` is given (module
    docstring) or by Flamant's elastic stress with ``traffic.boussinesq``
    (`_flamant`; undispersed where there is no fill over the load), acts downwards on
    the extrados.
    """
    n = arch.voussoirs
    ex = Extrados.of(arch)
    x = ex.x_at(traffic.position, "traffic position")
    total = traffic.load * arch.depth
    h = 0.0
    if loads.fill is not None:
        h = max(0.0, loads.fill.surface(arch) - float(ex.y_at(x)))
    spread = traffic.length
    if traffic.dispersion is not None:
        spread += 2.0 * h * math.tan(math.radians(traffic.dispersion))
    force, moment = np.zeros((n, 2)), np.zeros(n)
    if traffic.boussinesq and h > 0.0 and loads.fill is not None:
        return _flamant(ex, loads.fill.surface(arch), x, traffic.length, total, n)
    if spread <= 0.0:
        k = ex.block_at(x)
        force[k, 1] = -total
        moment[k] = -total * x
        return force, moment, [(x, x)]
    a, b = x - 0.5 * spread, x + 0.5 * spread
    q = total / spread
    for k, lo, hi in ex.split(a, b):
        f = q * (hi - lo)
        force[k, 1] -= f
        moment[k] -= f * 0.5 * (lo + hi)
    return force, moment, [(a, b)]


# ---------------------------------------------------------------------------------------------
# A study file's [loads] table
# ---------------------------------------------------------------------------------------------

#: The keys of a study file's ``[loads]`` table (units as on the command line).
LOADS_KEYS = ("fill_depth", "fill_level", "fill_density", "backing", "backing_right",
              "point_loads", "distributed_loads", "traffic", "passive", "fill_friction_deg")
#: Keys of ``[loads] traffic``.
TRAFFIC_KEYS = ("axle_kN", "patch_kN", "patch_length", "position", "dispersion_deg",
                "boussinesq")


def loads_from_table(table: object, *, source: str = "study file") -> Loads:
    """The loads of a study file's ``[loads]`` table, in the command line's units::

        [loads]
        fill_depth = 1.0          # m over the crown's extrados (or fill_level = y, m)
        fill_density = 1800       # kg/m^3 (default 1800)
        backing = 1.2             # m above each springing (backing_right = m if it differs)
        point_loads = [{position = 7.0, load_kN = 30.0, moves_with_arch = false}]
        distributed_loads = [{start = 1.0, end = 3.0, load_kN_m = 10.0}]
        traffic = {axle_kN = 100.0, position = 2.5, dispersion_deg = 26.57}
        passive = 0.33            # mobilised fraction of K_p (default: off)
        fill_friction_deg = 30    # the fill's friction angle for passive

    Loads are per metre of barrel width. Every problem is one
    `StudyFileError` naming the key as the file spells it.

    Examples
    --------
    >>> loads_from_table({"fill_depth": 1.0, "traffic": {"axle_kN": 100.0}}).traffic.load
    100000.0
    """
    from archquake.errors import ArchquakeError, StudyFileError

    def fail(key: str, what: str) -> StudyFileError:
        return StudyFileError(f"{source}: [loads] {key}: {what}")

    if not isinstance(table, dict):
        raise StudyFileError(f"{source}: [loads] must be a table")
    unknown = sorted(set(table) - set(LOADS_KEYS))
    if unknown:
        raise fail(unknown[0], f"unknown key; the keys are {', '.join(LOADS_KEYS)}")

    def num(key: str, value: object) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise fail(key, f"expected a number, got {value!r}")
        return float(value)

    def entries(key: str, keys: tuple[str, ...], required: tuple[str, ...]) -> list[dict]:
        items = table.get(key, [])
        if not isinstance(items, list) or not all(isinstance(i, dict) for i in items):
            raise fail(key, "expected a list of tables")
        for i, item in enumerate(items):
            extra = sorted(set(item) - set(keys))
            missing = [k for k in required if k not in item]
            if extra or missing:
                raise fail(f"{key}[{i}]", f"expected the keys {', '.join(keys)}"
                           + (f"; {missing[0]} is missing" if missing else ""))
        return items

    try:
        fill = None
        density = num("fill_density", table.get("fill_density", 1800.0))
        if "fill_depth" in table and "fill_level" in table:
            raise fail("fill_depth", "give fill_depth or fill_level, not both")
        if "fill_depth" in table:
            fill = Fill(depth=num("fill_depth", table["fill_depth"]), density=density)
        elif "fill_level" in table:
            fill = Fill(level=num("fill_level", table["fill_level"]), density=density)
        elif "fill_density" in table:
            raise fail("fill_density", "applies to a fill: add fill_depth")
        backing = None
        if "backing" in table:
            right = table.get("backing_right")
            backing = Backing(num("backing", table["backing"]),
                              None if right is None else num("backing_right", right))
        elif "backing_right" in table:
            raise fail("backing_right", "needs backing (the left one's height)")
        points = tuple(
            PointLoad(num("point_loads position", p["position"]),
                      1e3 * num("point_loads load_kN", p["load_kN"]),
                      bool(p.get("moves_with_arch", True)))
            for p in entries("point_loads", ("position", "load_kN", "moves_with_arch"),
                             ("position", "load_kN")))
        spread = tuple(
            DistributedLoad(num("distributed_loads start", d["start"]),
                            num("distributed_loads end", d["end"]),
                            1e3 * num("distributed_loads load_kN_m", d["load_kN_m"]),
                            bool(d.get("moves_with_arch", True)))
            for d in entries("distributed_loads", ("start", "end", "load_kN_m",
                                                   "moves_with_arch"),
                             ("start", "end", "load_kN_m")))
        traffic = None
        if "traffic" in table:
            t = table["traffic"]
            if not isinstance(t, dict) or set(t) - set(TRAFFIC_KEYS):
                raise fail("traffic", f"expected a table of {', '.join(TRAFFIC_KEYS)}")
            if ("axle_kN" in t) == ("patch_kN" in t):
                raise fail("traffic", "give axle_kN or patch_kN (with patch_length)")
            if "patch_kN" in t and "patch_length" not in t:
                raise fail("traffic", "patch_kN needs patch_length (m)")
            load = num("traffic", t.get("axle_kN", t.get("patch_kN")))
            disp = t.get("dispersion_deg")
            traffic = Traffic(1e3 * load, num("traffic position", t.get("position", 0.0)),
                              num("traffic patch_length", t.get("patch_length", 0.0)),
                              None if disp is None else num("traffic dispersion_deg", disp),
                              bool(t.get("boussinesq", False)))
        passive = None
        if "passive" in table:
            passive = Passive(num("passive", table["passive"]),
                              num("fill_friction_deg", table.get("fill_friction_deg", 30.0)))
        elif "fill_friction_deg" in table:
            raise fail("fill_friction_deg", "applies to passive")
        return Loads(fill, backing, points, spread, traffic, passive)
    except StudyFileError:
        raise
    except ArchquakeError as exc:
        raise StudyFileError(f"{source}: [loads] {exc}") from None


__all__ = [
    "Passive",
    "passive_resultants",
    "LOADS_KEYS",
    "TRAFFIC_KEYS",
    "loads_from_table",
    "Backing",
    "BlockExtras",
    "DistributedLoad",
    "Extrados",
    "Fill",
    "Loads",
    "PointLoad",
    "Traffic",
    "block_extras",
    "fill_columns",
    "held_joints",
    "traffic_actions",
]
