"""The kinematic analysis of a local mechanism (NTC 2018 §8.7.1, Circolare 2019 C8.7.1.2.1).

What the Italian code builds its local-mechanism check from, for a one-degree-of-freedom
mechanism of rigid blocks (no tension, no sliding, infinite compressive strength):

- the activation multiplier ``alpha0`` (C8.7.1.1): the horizontal force, as a fraction of the
  weight, at which the blocks start to move. For an arch it is the collapse multiplier of the
  equivalent static analysis (`archquake.limit.limit_analysis`, the minimum over the
  admissible four-hinge mechanisms), the ``Q_k = 0``, ``F_k = 0`` case of the code;
- the equivalent single-degree-of-freedom system (C8.7.1.2.1.3): from the horizontal virtual
  displacements ``delta_x,k`` of the blocks' centroids at the undisplaced configuration,

      e* = (sum m_k delta_x,k)^2 / (M sum m_k delta_x,k^2)                 (C8.7.1.5)
      M* = e* M                      (participating mass, kg; M = moving mass)
      d  = d_C sum m_k delta_x,k^2 / (delta_C,x sum m_k delta_x,k)        (C8.7.1.4)

  with C the control point and d_C its actual horizontal displacement;
- the capacity curve at large displacements (C8.7.1.2.1.2): the multiplier ``alpha`` that holds
  the mechanism in equilibrium in its displaced configuration, by virtual work there,

      alpha(phi) = sum m_k v_y,k(phi) / sum m_k v_x,k(phi)

  (``v`` the centroid velocities per unit rate of the mechanism's coordinate ``phi``), followed
  from ``alpha0`` down to zero at ``phi0``, mapped to ``d`` by (C8.7.1.4); ``d0 = d(phi0)``;
  the spectral acceleration is ``a = alpha g / (e* FC)`` (C8.7.1.3).

Rotational inertia of the blocks is not part of (C8.7.1.4-5): the code's equivalent system
counts translational masses at the centroids only, and so does this module.

Two mechanisms are provided, both following `LocalMechanism`:

- `FourHingeMechanism`: the arch's four-link mechanism (the hinges of the equivalent
  static analysis, `PreparedMechanism`), whose large
  displacements are `displaced_arch`'s;
- `RockingBlock`: a rigid block rocking on its toe (``block_on_base``), the case with
  closed forms: ``alpha0 = b/h``, ``e* = 1``, ``alpha(d) = tan(asin(sin beta - d/R))``,
  ``d0 = b/2`` with the centroid as control point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Protocol

import numpy as np
from scipy.optimize import brentq

from archquake._validate import require_int
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.chain import VoussoirChain
from archquake.mechanism.kinematics import fourbar, link_states
from archquake.mechanism.prepared import PreparedMechanism

#: Samples of the capacity curve kept for tables and plots (the curve itself is evaluated
#: exactly at any displacement by `CapacityCurve.alpha_at`).
CURVE_SAMPLES = 101
#: Samples of the search for the first zero of alpha(phi) (then refined by Brent's method).
_ROOT_SAMPLES = 400


@dataclass(frozen=True)
class BlockMotion:
    """The blocks of a mechanism at one configuration.

    Attributes
    ----------
    centroids : ndarray, shape (N, 2)
        Centroid positions, m.
    rotations : ndarray, shape (N,)
        Rotations from the undisplaced configuration, rad (counter-clockwise).
    centroid_rates : ndarray, shape (N, 2)
        d centroid / d phi, m/rad.
    rotation_rates : ndarray, shape (N,)
        d rotation / d phi, rad/rad.
    """

    centroids: np.ndarray
    rotations: np.ndarray
    centroid_rates: np.ndarray
    rotation_rates: np.ndarray


class LocalMechanism(Protocol):
    """A one-degree-of-freedom mechanism of N rigid blocks, coordinate ``phi`` (rad, > 0 open)
    opened by a horizontal load towards +x."""

    @property
    def masses(self) -> np.ndarray:
        """Masses of the moving blocks, kg, shape (N,)."""
        ...

    @property
    def rotation_limit(self) -> float:
        """Largest phi at which the mechanism can be assembled, rad."""
        ...

    def motion(self, phi: float) -> BlockMotion:
        """The blocks at ``phi``."""
        ...

    def describe(self) -> dict:
        """What the mechanism is, for reports and JSON."""
        ...


@dataclass(frozen=True)
class FourHingeMechanism:
    """The arch's four-hinge mechanism as a `LocalMechanism` (the moving voussoirs).

    Build it with `of` (the hinges of the equivalent static analysis).

    Attributes
    ----------
    prepared : PreparedMechanism
        The mechanism packed for the four-link kinematics; phi is its link AB's rotation.
    """

    prepared: PreparedMechanism = field(repr=False)

    @classmethod
    def of(cls, arch: VoussoirChain) -> FourHingeMechanism:
        """The mechanism of ``arch`` opened by a load towards +x
        (`hinges_of`)."""
        return cls(PreparedMechanism.build(arch))

    @cached_property
    def _moving(self) -> np.ndarray:
        a, _, _, d = self.prepared.mechanism.joints
        return np.arange(a, d)

    @property
    def masses(self) -> np.ndarray:
        return self.prepared.mechanism.arch.voussoir_masses[self._moving]

    @property
    def rotation_limit(self) -> float:
        return self.prepared.toggle_rotation

    @property
    def critical_rotation(self) -> float:
        """The four-link model's crest of the potential, rad (where alpha reaches zero)."""
        return self.prepared.critical_rotation

    @property
    def voussoirs(self) -> np.ndarray:
        """The arch's indices of the moving voussoirs, shape (N,)."""
        return self._moving.copy()

    @cached_property
    def _links(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        # per moving voussoir: its link (0 AB, 1 BC, 2 CD) and its centroid relative to the
        # link's undisplaced pivot (A, B, D)
        mech = self.prepared.mechanism
        cen0 = mech.arch.voussoir_centroids
        pivots = mech.points[[0, 1, 3]]
        link = np.concatenate([np.full(len(r), i) for i, r in enumerate(mech.link_voussoirs)])
        return link, cen0[self._moving] - pivots[link], pivots

    def motion(self, phi: float) -> BlockMotion:
        """The moving voussoirs at ``phi``: each turns with its link about the link's pivot
        (`fourbar` and ``link_states``, the four-link
        model's own kinematics; `displaced_arch` is
        the same motion with the joint geometry, and a test holds the two together)."""
        fb = fourbar(self.prepared.packed, float(phi))
        ls = link_states(self.prepared.packed, float(phi))
        if not (fb[0] and ls[0]):
            raise SolverError(f"the mechanism cannot be assembled at phi = {phi:.6g} rad")
        link, rho0, pivots0 = self._links
        if phi == 0.0:
            psi = np.zeros(3)
            pivot = pivots0.copy()
        else:
            psi = np.array([ls[1], ls[4], ls[7]])
            pivot = np.array([pivots0[0], [fb[1], fb[2]], pivots0[2]])
        rate = np.array([ls[2], ls[5], ls[8]])
        pivot_rate = np.array([[0.0, 0.0], [fb[3], fb[4]], [0.0, 0.0]])
        c, s = np.cos(psi)[link], np.sin(psi)[link]
        r = np.column_stack([c * rho0[:, 0] - s * rho0[:, 1], s * rho0[:, 0] + c * rho0[:, 1]])
        w = rate[link]
        v = pivot_rate[link] + w[:, None] * np.column_stack([-r[:, 1], r[:, 0]])
        return BlockMotion(pivot[link] + r, psi[link], v, w)

    def describe(self) -> dict:
        mech = self.prepared.mechanism
        return {"kind": "four-hinge", "hinges": [h.to_dict() for h in mech.hinges],
                "voussoirs": [int(k) for k in self._moving]}


@dataclass(frozen=True)
class RockingBlock:
    """A rigid block rocking about a corner of its base (its toe), opened by a load towards +x.

    Attributes
    ----------
    mass : float
        kg.
    centroid : ndarray, shape (2,)
        Undisplaced centroid, m.
    pivot : ndarray, shape (2,)
        The toe it turns about (clockwise, phi > 0), m.
    """

    mass: float
    centroid: np.ndarray
    pivot: np.ndarray

    @classmethod
    def on_base(cls, width: float, height: float, *, density: float = 2000.0,
                depth: float = 1.0) -> RockingBlock:
        """The block of `archquake.blocks.assembly.block_on_base` (``width`` b x ``height``
        h, m) on its right toe (b/2, 0)."""
        from archquake.blocks.assembly import block_on_base

        asm = block_on_base(width, height, density=density, depth=depth)
        return cls(float(asm.masses[1]), asm.centroids[1].copy(), np.array([0.5 * width, 0.0]))

    @property
    def masses(self) -> np.ndarray:
        return np.array([self.mass])

    @property
    def rotation_limit(self) -> float:
        return math.pi / 2

    def motion(self, phi: float) -> BlockMotion:
        c, s = math.cos(phi), math.sin(phi)
        r0 = self.centroid - self.pivot
        r = np.array([c * r0[0] + s * r0[1], -s * r0[0] + c * r0[1]])  # turned by -phi
        return BlockMotion((self.pivot + r)[None, :], np.array([-phi]),
                           np.array([[r[1], -r[0]]]), np.array([-1.0]))

    def describe(self) -> dict:
        return {"kind": "rocking block", "mass_kg": self.mass,
                "centroid_m": [float(v) for v in self.centroid],
                "pivot_m": [float(v) for v in self.pivot]}


@dataclass(frozen=True)
class ControlPoint:
    """The control point C of (C8.7.1.4): a point fixed to one moving block.

    Attributes
    ----------
    block : int
        Index among the mechanism's moving blocks (0..N-1).
    point : ndarray, shape (2,)
        Its undisplaced position, m.
    """

    block: int
    point: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "block", require_int("control block", self.block, 0))
        object.__setattr__(self, "point", np.asarray(self.point, dtype=float).reshape(2))


def _alpha(motion: BlockMotion, masses: np.ndarray, weights: np.ndarray | None = None) -> float:
    """sum W v_y / sum m g v_x (``weights`` W / g in kg; default the masses themselves)."""
    v = masses @ motion.centroid_rates
    if weights is None:
        return float(v[1] / v[0])
    return float((weights @ motion.centroid_rates[:, 1]) / v[0])


@dataclass(frozen=True)
class CapacityCurve:
    """The equivalent single-degree-of-freedom system of a local mechanism and its capacity curve
    (C8.7.1.2.1.2-3). Build it with `capacity_curve`.

    Attributes
    ----------
    mechanism : LocalMechanism
    control : ControlPoint or None
        None: the centre of mass of the moving blocks.
    alpha0 : float
        Activation multiplier (C8.7.1.1), horizontal force / weight.
    e_star : float
        Fraction of participating mass (C8.7.1.5).
    mass_kg : float
        M, the moving mass, kg.
    m_star_kg : float
        Participating mass M* = e* M, kg.
    virtual_dx : ndarray, shape (N,)
        delta_x,k per unit phi at phi = 0, m/rad.
    control_dx : float
        delta_C,x per unit phi, m/rad.
    phi0_rad : float
        Rotation at which alpha reaches zero, rad.
    d0_m : float
        Spectral displacement at which alpha reaches zero, m.
    rotations_rad, alphas, displacements_m : ndarray, shape (CURVE_SAMPLES,)
        The curve sampled from phi = 0 to phi0 (alpha from alpha0 to 0; d from 0 to d0).
    g : float
        m/s^2.
    """

    mechanism: LocalMechanism = field(repr=False)
    control: ControlPoint | None
    alpha0: float
    e_star: float
    mass_kg: float
    m_star_kg: float
    virtual_dx: np.ndarray = field(repr=False)
    control_dx: float
    phi0_rad: float
    d0_m: float
    rotations_rad: np.ndarray = field(repr=False)
    alphas: np.ndarray = field(repr=False)
    displacements_m: np.ndarray = field(repr=False)
    g: float

    # ------------------------------------------------------------------ along the mechanism
    def control_displacement(self, phi: float) -> float:
        """d_C,x: the control point's horizontal displacement at ``phi``, m."""
        return _control_displacement(self.mechanism, self.control, phi)

    def displacement(self, phi: float) -> float:
        """d at ``phi`` by (C8.7.1.4), m."""
        s1 = float(self.mechanism.masses @ self.virtual_dx)
        s2 = float(self.mechanism.masses @ self.virtual_dx**2)
        return self.control_displacement(phi) * s2 / (self.control_dx * s1)

    def alpha(self, phi: float) -> float:
        """The multiplier holding the mechanism in equilibrium at ``phi``."""
        return _alpha(self.mechanism.motion(phi), self.mechanism.masses)

    def rotation_at(self, d: float) -> float:
        """phi at which the spectral displacement is ``d`` (0 <= d <= d0), rad."""
        if not 0.0 <= d <= self.d0_m * (1.0 + 1e-12):
            raise InvalidParameterError(
                f"spectral displacement must be in [0, d0 = {self.d0_m:.6g}] m, got {d:.6g}")
        if d == 0.0:
            return 0.0
        if d >= self.d0_m:
            return self.phi0_rad
        return float(brentq(lambda p: self.displacement(p) - d, 0.0, self.phi0_rad,
                            xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))

    def alpha_at(self, d: float) -> float:
        """alpha at the spectral displacement ``d``, m (exact: the equilibrium at that phi)."""
        return self.alpha(self.rotation_at(d))

    def acceleration_at(self, d: float, confidence_factor: float) -> float:
        """a = alpha(d) g / (e* FC), m/s^2 (C8.7.1.3)."""
        return self.alpha_at(d) * self.g / (self.e_star * confidence_factor)

    def a0_star(self, confidence_factor: float) -> float:
        """a0* = alpha0 g / (e* FC), m/s^2: the spectral acceleration of activation."""
        return self.alpha0 * self.g / (self.e_star * confidence_factor)

    def block_table(self) -> list[dict]:
        """The moving blocks behind alpha0, e* and M*: per block its mass m_k (kg) and the
        horizontal and vertical virtual displacements of its centroid per unit rotation of the
        mechanism at the onset, delta_x,k and delta_y,k (m/rad), with m_k delta_x,k,
        m_k delta_y,k (kg m/rad) and m_k delta_x,k^2 (kg m^2/rad^2). Their sums give
        alpha0 = sum m delta_y / sum m delta_x (virtual work of weight against the horizontal
        load, C8.7.1.1) and e* = (sum m delta_x)^2 / (M sum m delta_x^2) (C8.7.1.5).

        ``block`` is the block's number in the arch, counted from 1 at the left (its index in
        the chain plus one), where the mechanism says which blocks move; else from 1.

        Examples
        --------
        >>> rows = capacity_curve(RockingBlock.on_base(0.5, 5.0)).block_table()
        >>> len(rows), round(rows[0]["m_dy_kg_m"] / rows[0]["m_dx_kg_m"], 12)
        (1, 0.1)
        """
        masses = np.asarray(self.mechanism.masses, dtype=float)
        rates = self.mechanism.motion(0.0).centroid_rates
        numbers = getattr(self.mechanism, "voussoirs", None)
        numbers = np.arange(masses.size) if numbers is None else np.asarray(numbers)
        return [{"block": int(n) + 1, "mass_kg": float(m), "dx_m_rad": float(v[0]),
                 "dy_m_rad": float(v[1]), "m_dx_kg_m": float(m * v[0]),
                 "m_dy_kg_m": float(m * v[1]), "m_dx2_kg_m2": float(m * v[0] ** 2)}
                for n, m, v in zip(numbers, masses, rates, strict=True)]

    def to_dict(self) -> dict:
        return {
            "mechanism": self.mechanism.describe(),
            "control_point": (None if self.control is None else
                              {"block": self.control.block,
                               "point_m": [float(v) for v in self.control.point]}),
            "alpha0": self.alpha0,
            "e_star": self.e_star,
            "mass_kg": self.mass_kg,
            "m_star_kg": self.m_star_kg,
            "phi0_rad": self.phi0_rad,
            "d0_m": self.d0_m,
            "curve": {"phi_rad": self.rotations_rad, "alpha": self.alphas,
                      "d_m": self.displacements_m},
            "g": self.g,
        }


def _control_displacement(mech: LocalMechanism, control: ControlPoint | None, phi: float) -> float:
    motion = mech.motion(phi)
    start = mech.motion(0.0)
    if control is None:
        m = mech.masses
        return float(m @ (motion.centroids[:, 0] - start.centroids[:, 0]) / m.sum())
    k = control.block
    r0 = control.point - start.centroids[k]
    th = float(motion.rotations[k] - start.rotations[k])
    c, s = math.cos(th), math.sin(th)
    x = motion.centroids[k, 0] + c * r0[0] - s * r0[1]
    return float(x - control.point[0])


def _control_rate(mech: LocalMechanism, control: ControlPoint | None, start: BlockMotion) -> float:
    if control is None:
        m = mech.masses
        return float(m @ start.centroid_rates[:, 0] / m.sum())
    k = control.block
    r0 = control.point - start.centroids[k]
    return float(start.centroid_rates[k, 0] + start.rotation_rates[k] * -r0[1])  # x of w J r0


def participation(masses: np.ndarray, virtual_dx: np.ndarray) -> tuple[float, float]:
    """e* (C8.7.1.5) and M* = e* sum m (kg) from the masses (kg) and their horizontal virtual
    displacements (any scale: both are invariant under scaling the field).

    Examples
    --------
    One block: e* = 1.

    >>> import numpy as np
    >>> participation(np.array([5.0]), np.array([0.3]))
    (1.0, 5.0)
    """
    m = np.asarray(masses, dtype=float)
    dx = np.asarray(virtual_dx, dtype=float)
    s1, s2, total = float(m @ dx), float(m @ dx**2), float(m.sum())
    if s2 <= 0.0 or total <= 0.0:
        raise InvalidParameterError("the virtual displacement field has no horizontal component")
    e_star = s1 * s1 / (total * s2)
    return e_star, e_star * total


def capacity_curve(mechanism: LocalMechanism | VoussoirChain, *,
                   control: ControlPoint | None = None,
                   g: float = STANDARD_GRAVITY) -> CapacityCurve:
    """The equivalent SDOF system and capacity curve of a local mechanism (C8.7.1.2.1.2-3).

    Parameters
    ----------
    mechanism : LocalMechanism or VoussoirChain
        An arch is taken through `FourHingeMechanism.of` (the collapse mechanism of the
        equivalent static analysis).
    control : ControlPoint, optional
        The control point C of (C8.7.1.4); None: the moving blocks' centre of mass. e* and M*
        do not depend on it; d does to second order in phi (so d0 does, slightly).
    g : float, optional
        Gravity, m/s^2.

    Returns
    -------
    CapacityCurve

    Raises
    ------
    SolverError
        alpha does not reach zero before the mechanism's limit, or d does not grow with phi.

    Examples
    --------
    A block 0.5 m x 5 m: alpha0 = b/h, e* = 1, d0 = b/2.

    >>> c = capacity_curve(RockingBlock.on_base(0.5, 5.0))
    >>> round(c.alpha0, 12), round(c.e_star, 12), round(c.d0_m, 12)
    (0.1, 1.0, 0.25)
    """
    if isinstance(mechanism, VoussoirChain):
        mechanism = FourHingeMechanism.of(mechanism)
    masses = mechanism.masses
    # gravity's share of each block, kg (loads that weigh but do not move with the arch are
    # blocks of weight without mass: LoadedFourHingeMechanism.weights)
    weights = getattr(mechanism, "weights", None)
    start = mechanism.motion(0.0)
    virtual_dx = start.centroid_rates[:, 0].copy()
    e_star, m_star = participation(masses, virtual_dx)
    if control is not None and not 0 <= control.block < masses.size:
        raise InvalidParameterError(
            f"control block must be in [0, {masses.size - 1}], got {control.block}")
    control_dx = _control_rate(mechanism, control, start)
    if abs(control_dx) <= 1e-12 * float(np.max(np.abs(virtual_dx))):
        raise InvalidParameterError(
            "the control point does not move horizontally at the onset; choose another")
    alpha0 = _alpha(start, masses, weights)
    # first zero of alpha(phi): scan, then Brent
    limit = mechanism.rotation_limit * (1.0 - 1e-9)
    phis = np.linspace(0.0, limit, _ROOT_SAMPLES + 1)
    prev = alpha0
    phi0 = math.nan
    for lo, hi in zip(phis[:-1], phis[1:], strict=True):
        val = _alpha(mechanism.motion(hi), masses, weights)
        if prev > 0.0 >= val:
            phi0 = float(brentq(lambda p: _alpha(mechanism.motion(p), masses, weights), lo, hi,
                                xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))
            break
        prev = val
    if not math.isfinite(phi0):
        raise SolverError("the multiplier does not reach zero before the mechanism locks")
    s1, s2 = float(masses @ virtual_dx), float(masses @ virtual_dx**2)
    grid = np.linspace(0.0, phi0, CURVE_SAMPLES)
    d = np.array([_control_displacement(mechanism, control, p) for p in grid]) * s2 / (
        control_dx * s1)
    alphas = np.array([_alpha(mechanism.motion(p), masses, weights) for p in grid])
    alphas[-1] = 0.0
    if np.any(np.diff(d) <= 0.0):
        raise SolverError(
            "the spectral displacement does not grow along the mechanism with this control point")
    return CapacityCurve(
        mechanism=mechanism, control=control, alpha0=alpha0, e_star=e_star,
        mass_kg=float(masses.sum()), m_star_kg=m_star, virtual_dx=virtual_dx,
        control_dx=control_dx, phi0_rad=phi0, d0_m=float(d[-1]), rotations_rad=grid,
        alphas=alphas, displacements_m=d, g=float(g))


@dataclass(frozen=True)
class LoadedFourHingeMechanism:
    """The four-hinge mechanism of an arch with what it carries, as a `LocalMechanism`.

    The hinges are those of the equivalent static analysis with the loads
    (`archquake.limit.limit_analysis` with ``loads``). Each moving voussoir is two
    blocks of one link: the voussoir, and what it carries that moves with it (its fill
    column and the loads whose mass moves, lumped at their centroid,
    `archquake.geometry.loads.block_extras`); loads that weigh but do not move are
    blocks of weight without mass. So alpha0, M*, e* and the capacity curve count every
    carried mass (C8.7.1), and alpha0 equals the loaded collapse multiplier. Traffic is not
    part of the seismic combination here.

    Attributes
    ----------
    base : FourHingeMechanism
        The four-link kinematics of the ring with the loaded hinges.
    extras_mass : ndarray, shape (N,)
        Carried mass of each moving voussoir, kg.
    extras_centroid : ndarray, shape (N, 2)
        Its centroid, m.
    still_weight : ndarray, shape (N,)
        Weight that does not move with each moving voussoir, over g (kg), at
    still_point : ndarray, shape (N, 2)
        the x of its resultant (and the voussoir's centroid's y), m.
    """

    base: FourHingeMechanism = field(repr=False)
    extras_mass: np.ndarray
    extras_centroid: np.ndarray
    still_weight: np.ndarray
    still_point: np.ndarray

    @classmethod
    def of(cls, arch: VoussoirChain, loads, *, g: float = STANDARD_GRAVITY
           ) -> LoadedFourHingeMechanism:
        """The mechanism of ``arch`` carrying ``loads`` (a
        `Loads`; its traffic is left out) opened by a load
        towards +x."""
        from archquake.geometry.loads import block_extras
        from archquake.limit import limit_analysis

        dead = loads.without_traffic()
        if dead.passive is not None:
            raise InvalidParameterError(
                "the code check does not model passive fill pressure (C8.7.1 counts the "
                "masses, not the fill's resistance); leave the passive pressure out")
        mech = limit_analysis(arch, method="static", loads=dead, g=g).mechanism
        if mech.load_direction < 0:
            raise InvalidParameterError(
                "the ring alone would be opened by the opposite load in this mechanism: the "
                "code check of this loaded arch is not supported")
        base = FourHingeMechanism(PreparedMechanism.build(mech))
        extras = block_extras(arch, dead, g=g)
        moving = base.voussoirs
        still = -extras.weight_force[moving, 1] / g
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(still != 0.0, -extras.weight_moment[moving] / (still * g), 0.0)
        still_point = np.column_stack([np.where(still != 0.0, x, arch.voussoir_centroids[moving, 0]),
                                       arch.voussoir_centroids[moving, 1]])
        return cls(base, extras.mass[moving].copy(), extras.centroid[moving].copy(), still,
                   still_point)

    @property
    def masses(self) -> np.ndarray:
        """Voussoirs, then their carried masses, then the still loads (mass 0), kg, (3N,)."""
        return np.concatenate([self.base.masses, self.extras_mass,
                               np.zeros_like(self.still_weight)])

    @property
    def weights(self) -> np.ndarray:
        """Gravity's share of each block of `masses`, over g, kg, (3N,)."""
        return np.concatenate([self.base.masses, self.extras_mass, self.still_weight])

    @property
    def rotation_limit(self) -> float:
        return self.base.rotation_limit

    def motion(self, phi: float) -> BlockMotion:
        """The voussoirs (`FourHingeMechanism.motion`), and the points of their carried
        masses and still loads fixed to them."""
        m0 = self.base.motion(0.0)
        m = m0 if phi == 0.0 else self.base.motion(phi)
        parts = [m]
        for points in (self.extras_centroid, self.still_point):
            r0 = points - m0.centroids
            c, s = np.cos(m.rotations), np.sin(m.rotations)
            r = np.column_stack([c * r0[:, 0] - s * r0[:, 1], s * r0[:, 0] + c * r0[:, 1]])
            w = m.rotation_rates
            v = m.centroid_rates + w[:, None] * np.column_stack([-r[:, 1], r[:, 0]])
            parts.append(BlockMotion(m.centroids + r, m.rotations, v, w))
        return BlockMotion(np.vstack([p.centroids for p in parts]),
                           np.concatenate([p.rotations for p in parts]),
                           np.vstack([p.centroid_rates for p in parts]),
                           np.concatenate([p.rotation_rates for p in parts]))

    def describe(self) -> dict:
        out = self.base.describe()
        out["kind"] = "four-hinge, with the loads the arch carries"
        out["carried_mass_kg"] = float(self.extras_mass.sum())
        out["still_load_kN"] = float(self.still_weight.sum() * STANDARD_GRAVITY / 1e3)
        return out


__all__ = [
    "LoadedFourHingeMechanism",
    "CURVE_SAMPLES",
    "BlockMotion",
    "CapacityCurve",
    "ControlPoint",
    "FourHingeMechanism",
    "LocalMechanism",
    "RockingBlock",
    "capacity_curve",
    "participation",
]
