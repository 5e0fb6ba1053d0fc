"""Line of thrust of the rocking arch at any instant of its motion (paper, "Line of thrust
during motion", Figure 8).

At an instant of a time history the mechanism's state (``phi``, ``phi_dot``, which mechanism
is open) fixes the displaced position of every voussoir, and the equation of motion (Eq. 2 or
Eq. 3) gives ``phi_ddot``. Each voussoir then carries, in the frame moving with the ground:

- its weight ``-m g`` (vertical),
- the ground's inertia force ``-m x_g''`` (horizontal),
- its own d'Alembert force ``-m a_c`` and couple ``-I alpha``, with the centroid
  acceleration ``a_c = r' phi'' + r'' phi'^2`` and angular acceleration
  ``alpha = psi' phi'' + psi'' phi'^2`` (primes on ``r``, ``psi`` are d/dphi).

The four hinges carry forces through the hinge points and no moment. The three links give
nine equilibrium equations for the eight force components at A, B, C and D; they are
consistent (rank eight) exactly because ``phi_ddot`` satisfies the equation of motion, which
is their virtual-work combination, and the residual of the least-squares solution is kept as
a check (:attr:`MotionState.equilibrium_residual`). With the reaction at A known, the
resultant at every joint follows from :func:`archquake.limit.thrust.joint_forces` (the one
statics routine of the package) applied to the displaced voussoirs; voussoirs outside the
mechanism stay on the ground and are loaded by weight and ground inertia only.

Joint geometry in the displaced arch: a joint inside a link keeps its two faces together;
at a hinge the faces open by the links' relative rotation and touch only at the hinge point.
The joint line used there is the bisector of the two faces, drawn from the hinge point over
the full thickness; the friction demand at an open hinge is measured against that line
(at ``phi = 0``, e.g. at t = 0+, both faces coincide and the choice does not matter).

While the arch is locked (before hinging starts, and after it comes to rest) it moves rigidly
with the ground and its internal forces are statically indeterminate. The state reported is
then the admissible line of thrust (inside the section, in compression) that needs the least
friction, found by bisection on the friction coefficient with a linear feasibility program
(:func:`locked_joint_forces`); by the lower-bound theorem of limit analysis such a line exists
whenever the arch stands.

Side convention: side +1 is the packed (first) mechanism; side -1 is its mirror image, whose
dynamics are the packed mechanism's under ``-x_g''`` (Eq. 3): the kinematics are computed for
the packed mechanism and mirrored (x -> -x, joint order reversed), and the statics are then
solved in the physical frame with the actual ground acceleration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import linprog

from archquake._validate import require_finite
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.arch import Arch
from archquake.geometry.hinges import Face
from archquake.ground.base import GroundMotion
from archquake.limit.thrust import JointForces, arch_joint_points, joint_forces, moments_about_origin
from archquake.mechanism.kinematics import acceleration, fourbar, link_states
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import SimulationResult, simulate

#: Relative tolerance (on the thickness) below which two faces of a joint count as closed.
_CLOSED = 1e-12


# --------------------------------------------------------------------------- kinematics
@dataclass(frozen=True)
class _Kinematics:
    """Displaced voussoirs in the physical frame (see :class:`MotionState` for shapes)."""

    left_faces: np.ndarray  # (n, 2, 2): joint k of voussoir k, [intrados, extrados]
    right_faces: np.ndarray  # (n, 2, 2): joint k+1 of voussoir k
    centroids: np.ndarray  # (n, 2)
    rotations: np.ndarray  # (n,)
    translations: np.ndarray  # (n, 2): x_new = Rot(rotation) x_old + translation
    accelerations: np.ndarray  # (n, 2), relative to the ground
    angular_accelerations: np.ndarray  # (n,)
    hinge_joints: tuple[int, int, int, int]
    hinge_faces: tuple[Face, Face, Face, Face]
    hinge_points: np.ndarray  # (4, 2)


def _rot(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def _packed_kinematics(prepared: PreparedMechanism, phi: float, phi_dot: float,
                       phi_ddot: float) -> _Kinematics:
    """Kinematics of the packed (side +1) mechanism at phi, in its own frame."""
    mech = prepared.mechanism
    arch = mech.arch
    packed = prepared.packed
    n = arch.voussoirs
    fb = fourbar(packed, phi)
    ls = link_states(packed, phi)
    if not (fb[0] and ls[0]):
        raise SolverError(f"the mechanism cannot be assembled at phi = {phi:.6g} rad (beyond its toggle)")
    b = np.array([fb[1], fb[2]])
    b1, b2 = np.array([fb[3], fb[4]]), np.array([fb[5], fb[6]])
    c_pt = np.array([fb[7], fb[8]])
    a0, b0, c0, d0 = mech.points
    zero = np.zeros(2)
    # per link: pivot now, pivot undisplaced, pivot' and pivot'', psi, psi', psi''
    links = (
        (a0, a0, zero, zero, ls[1], ls[2], ls[3]),
        (b, b0, b1, b2, ls[4], ls[5], ls[6]),
        (d0, d0, zero, zero, ls[7], ls[8], ls[9]),
    )
    pts = arch_joint_points(arch)
    cen0 = arch.voussoir_centroids
    left = pts[:-1].copy()
    right = pts[1:].copy()
    cen = cen0.copy()
    rotation = np.zeros(n)
    translation = np.zeros((n, 2))
    acc = np.zeros((n, 2))
    alpha = np.zeros(n)
    for rng, (p, p0, p1, p2, psi, w, a) in zip(mech.link_voussoirs, links, strict=True):
        rot = _rot(psi)
        shift = p - rot @ p0
        omega = w * phi_dot
        alph = w * phi_ddot + a * phi_dot**2
        pivot_acc = p1 * phi_ddot + p2 * phi_dot**2
        for k in rng:
            left[k] = pts[k] @ rot.T + shift
            right[k] = pts[k + 1] @ rot.T + shift
            cen[k] = rot @ cen0[k] + shift
            r = cen[k] - p
            acc[k] = pivot_acc + alph * np.array([-r[1], r[0]]) - omega**2 * r
            alpha[k] = alph
            rotation[k] = psi
            translation[k] = shift
    hinge_points = np.array([a0, b, c_pt, d0])
    return _Kinematics(left, right, cen, rotation, translation, acc, alpha,
                       mech.joints, mech.faces, hinge_points)


def _mirror(kin: _Kinematics, n: int) -> _Kinematics:
    """The mirror image in the vertical axis: x -> -x, voussoir k -> n-1-k, joint j -> n-j."""
    flip = np.array([-1.0, 1.0])
    idx = np.arange(n)[::-1]
    return _Kinematics(
        left_faces=kin.right_faces[idx] * flip,
        right_faces=kin.left_faces[idx] * flip,
        centroids=kin.centroids[idx] * flip,
        rotations=-kin.rotations[idx],
        translations=kin.translations[idx] * flip,
        accelerations=kin.accelerations[idx] * flip,
        angular_accelerations=-kin.angular_accelerations[idx],
        hinge_joints=tuple(n - j for j in reversed(kin.hinge_joints)),  # type: ignore[arg-type]
        hinge_faces=tuple(reversed(kin.hinge_faces)),  # type: ignore[arg-type]
        hinge_points=kin.hinge_points[::-1] * flip,
    )


def _joint_lines(arch: Arch, kin: _Kinematics) -> np.ndarray:
    """Joint end points (n+1, 2, 2) of the displaced arch: the common face where the two sides
    touch, the bisector from the hinge point where a hinge has opened."""
    pts = arch_joint_points(arch)
    n = arch.voussoirs
    out = np.empty_like(pts)
    tol = _CLOSED * arch.thickness + 1e-15 * arch.radius
    hinge_of = dict(zip(kin.hinge_joints, zip(kin.hinge_faces, kin.hinge_points, strict=True),
                        strict=True))
    for j in range(n + 1):
        lf = pts[0] if j == 0 else kin.right_faces[j - 1]
        rf = pts[n] if j == n else kin.left_faces[j]
        if np.max(np.abs(lf - rf)) <= tol or j not in hinge_of:
            out[j] = 0.5 * (lf + rf)
            continue
        face, point = hinge_of[j]
        u = (lf[1] - lf[0]) / np.linalg.norm(lf[1] - lf[0]) + (rf[1] - rf[0]) / np.linalg.norm(rf[1] - rf[0])
        u *= arch.thickness / np.linalg.norm(u)
        out[j] = (point, point + u) if face is Face.INTRADOS else (point - u, point)
    return out


# --------------------------------------------------------------------------- state
@dataclass(frozen=True)
class MotionState:
    """The arch at one instant: displaced voussoirs and the forces at every joint.

    Attributes
    ----------
    t : float
        Time, s.
    phi, phi_dot, phi_ddot : float
        Rotation of the open mechanism (rad), its rate (rad/s) and acceleration (rad/s^2).
    side : int
        +1 the first mechanism, -1 its mirror image, 0 locked (moving rigidly with the ground).
    ground_acceleration : float
        x_g'' used for the forces, m/s^2 (towards +x positive).
    joint_points : ndarray, (n+1, 2, 2)
        Intrados and extrados ends of every joint in the displaced arch, m.
    centroids : ndarray, (n, 2)
        Displaced voussoir centroids, m.
    rotations : ndarray, (n,)
        Rotation of each voussoir, rad (counter-clockwise); ``translations`` (n, 2), m, complete
        the rigid motion x -> Rot(rotation) x + translation of its undisplaced points.
    loads : ndarray, (n, 2)
        Resultant external force on each voussoir (weight, ground inertia, own inertia), N.
    load_moments : ndarray, (n,)
        Their moment about the origin O, N m.
    hinge_joints : tuple of 4 int, or None
        Joints of the open mechanism's hinges (None while locked).
    hinge_points : ndarray, (4, 2), or None
        Hinge points in the displaced arch, m.
    hinge_forces : ndarray, (4, 2), or None
        Force transmitted at A, B, C, D from the part on the left to the part on the right, N.
    forces : JointForces
        Resultants at every joint (:mod:`archquake.limit.thrust` conventions).
    equilibrium_residual : float
        Largest violation of the links' nine equilibrium equations, relative to the total
        weight (forces) and weight x R (moments): ~1e-15 when phi_ddot obeys Eq. 2.
    g : float
        Gravity, m/s^2.
    """

    t: float
    phi: float
    phi_dot: float
    phi_ddot: float
    side: int
    ground_acceleration: float
    joint_points: np.ndarray = field(repr=False)
    centroids: np.ndarray = field(repr=False)
    rotations: np.ndarray = field(repr=False)
    translations: np.ndarray = field(repr=False)
    loads: np.ndarray = field(repr=False)
    load_moments: np.ndarray = field(repr=False)
    hinge_joints: tuple[int, int, int, int] | None
    hinge_points: np.ndarray | None = field(repr=False)
    hinge_forces: np.ndarray | None = field(repr=False)
    forces: JointForces = field(repr=False)
    equilibrium_residual: float
    g: float

    @property
    def locked(self) -> bool:
        return self.side == 0

    @property
    def left_reaction(self) -> np.ndarray:
        """Force of the left support on the arch, N, (2,)."""
        return self.forces.force[0]

    @property
    def right_reaction(self) -> np.ndarray:
        """Force of the right support on the arch, N, (2,)."""
        return -self.forces.force[-1]

    @property
    def thrust_points(self) -> np.ndarray:
        """The line of thrust: where each joint's resultant crosses the joint line, m, (n+1, 2)."""
        return self.forces.thrust_points

    @property
    def relative_eccentricity(self) -> np.ndarray:
        """Eccentricity over the joint's half-width, (n+1,): |.| > 1 outside the section."""
        return self.forces.relative_eccentricity

    @property
    def friction_demand(self) -> np.ndarray:
        """|V| / N at every joint, (n+1,) (inf where a joint is in tension)."""
        return self.forces.friction_ratio

    @property
    def outside(self) -> np.ndarray:
        """How far the line of thrust lies outside the section at each joint, m, (n+1,):
        ``max(|e| - h, 0)`` (0 inside; inf for a joint in tension)."""
        n = self.forces.normal
        excess = np.abs(self.forces.eccentricity) - self.forces.half_widths
        tol = 1e-9 * self.forces.half_widths
        return np.where(n > 0, np.where(excess > tol, excess, 0.0), np.inf)

    @property
    def exit_joint(self) -> int | None:
        """The joint where the line of thrust lies farthest outside the section (where a hinge
        would form instead of an assumed one), or None if it stays inside."""
        out = self.outside
        return int(np.argmax(out)) if np.any(out > 0) else None

    def to_dict(self) -> dict:
        jf = self.forces
        exit_joint = self.exit_joint
        return {
            "t": self.t,
            "phi_rad": self.phi,
            "phi_dot_rad_s": self.phi_dot,
            "phi_ddot_rad_s2": self.phi_ddot,
            "side": self.side,
            "ground_acceleration_g": self.ground_acceleration / self.g,
            "hinge_joints": list(self.hinge_joints) if self.hinge_joints else None,
            "exit_joint": exit_joint,
            "max_outside_m": float(self.outside[exit_joint]) if exit_joint is not None else 0.0,
            "left_reaction_N": self.left_reaction,
            "right_reaction_N": self.right_reaction,
            "equilibrium_residual": self.equilibrium_residual,
            "joints": {
                "thrust_x": jf.thrust_points[:, 0],
                "thrust_y": jf.thrust_points[:, 1],
                "normal_N": jf.normal,
                "shear_N": jf.shear,
                "eccentricity_m": jf.eccentricity,
                "relative_eccentricity": jf.relative_eccentricity,
                "outside_m": self.outside,
                "friction_demand": self.friction_demand,
            },
        }


def _voussoir_loads(arch: Arch, centroids: np.ndarray, acc: np.ndarray, alpha: np.ndarray,
                    ground: float, g: float) -> tuple[np.ndarray, np.ndarray]:
    m = arch.voussoir_masses
    f = -m[:, None] * (acc + np.array([ground, g]))
    return f, moments_about_origin(f, centroids, -arch.voussoir_inertias * alpha)


def _cross(p: np.ndarray) -> np.ndarray:
    """Row giving p x F (z-component) for F = (Fx, Fy)."""
    return np.array([-p[1], p[0]])


def _hinge_forces(kin: _Kinematics, loads: np.ndarray, moments: np.ndarray,
                  scale_f: float, scale_m: float) -> tuple[np.ndarray, float]:
    """Forces at A, B, C, D (left part on right part) from the three links' equilibrium."""
    j = kin.hinge_joints
    p = kin.hinge_points
    a = np.zeros((9, 8))
    rhs = np.zeros(9)
    for link in range(3):
        sl = slice(j[link], j[link + 1])
        r = 3 * link
        # F_in + L - F_out = 0 ; p_in x F_in + M - p_out x F_out = 0
        a[r:r + 2, 2 * link:2 * link + 2] = np.eye(2)
        a[r:r + 2, 2 * link + 2:2 * link + 4] = -np.eye(2)
        a[r + 2, 2 * link:2 * link + 2] = _cross(p[link])
        a[r + 2, 2 * link + 2:2 * link + 4] = -_cross(p[link + 1])
        rhs[r:r + 2] = -loads[sl].sum(axis=0)
        rhs[r + 2] = -moments[sl].sum()
    weights = np.tile([1.0 / scale_f, 1.0 / scale_f, 1.0 / scale_m], 3)
    x, *_ = np.linalg.lstsq(a * weights[:, None], rhs * weights, rcond=None)
    residual = float(np.max(np.abs((a @ x - rhs) * weights)))
    return x.reshape(4, 2), residual


def state_at(
    prepared: PreparedMechanism,
    t: float,
    phi: float,
    phi_dot: float,
    side: int,
    ground_acceleration: float,
    *,
    g: float = STANDARD_GRAVITY,
) -> MotionState:
    """Displaced arch and joint forces for a given mechanism state.

    Parameters
    ----------
    prepared : PreparedMechanism
        The first mechanism (side +1).
    t : float
        Time, s (recorded only).
    phi, phi_dot : float
        Rotation (rad, >= 0) and rate (rad/s) of the open mechanism.
    side : {+1, -1, 0}
        Which mechanism is open; 0 = locked (phi and phi_dot ignored).
    ground_acceleration : float
        x_g'', m/s^2, towards +x positive.
    g : float
        Gravity, m/s^2.

    Returns
    -------
    MotionState

    Examples
    --------
    Oppenheim's arch at the onset of a 1.0 g step impulse (paper p. 2131: the friction
    demand is largest at the right springing, about 0.56):

    >>> import math
    >>> from archquake import Arch
    >>> prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> s = state_at(prep, 0.0, 0.0, 0.0, 1, -STANDARD_GRAVITY)
    >>> int(s.friction_demand.argmax()), round(float(s.friction_demand.max()), 3)
    (7, 0.55)
    """
    arch = prepared.mechanism.arch
    side = int(side)
    xg = require_finite("ground_acceleration", ground_acceleration)
    if side not in (-1, 0, 1):
        raise InvalidParameterError(f"side must be -1, 0 or +1, got {side}")
    if side == 0:
        return _locked_state(arch, t, xg, g)
    if phi < 0:
        raise InvalidParameterError(f"phi must be >= 0 rad while a mechanism is open, got {phi:g}")
    phi_ddot = float(acceleration(prepared.packed, phi, phi_dot, side * xg, g))
    kin = _packed_kinematics(prepared, phi, phi_dot, phi_ddot)
    if side < 0:
        kin = _mirror(kin, arch.voussoirs)
    loads, moments = _voussoir_loads(arch, kin.centroids, kin.accelerations,
                                     kin.angular_accelerations, xg, g)
    weight = arch.mass * g
    hinge_f, residual = _hinge_forces(kin, loads, moments, weight, weight * arch.radius)
    a_joint = kin.hinge_joints[0]
    reaction = hinge_f[0] - loads[:a_joint].sum(axis=0)
    reaction_moment = float(_cross(kin.hinge_points[0]) @ hinge_f[0] - moments[:a_joint].sum())
    jp = _joint_lines(arch, kin)
    jf = joint_forces(jp, loads, moments, reaction, reaction_moment)
    return MotionState(
        t=float(t), phi=float(phi), phi_dot=float(phi_dot), phi_ddot=phi_ddot, side=side,
        ground_acceleration=xg, joint_points=jp, centroids=kin.centroids,
        rotations=kin.rotations, translations=kin.translations, loads=loads,
        load_moments=moments, hinge_joints=kin.hinge_joints, hinge_points=kin.hinge_points,
        hinge_forces=hinge_f, forces=jf, equilibrium_residual=residual, g=float(g),
    )


# --------------------------------------------------------------------------- locked arch
def _locked_state(arch: Arch, t: float, xg: float, g: float) -> MotionState:
    n = arch.voussoirs
    zero = np.zeros((n, 2))
    loads, moments = _voussoir_loads(arch, arch.voussoir_centroids, zero, np.zeros(n), xg, g)
    jf = locked_joint_forces(arch, loads, moments)
    residual_f = np.abs(jf.force[0] + loads.sum(axis=0) - jf.force[-1]).max() / (arch.mass * g)
    return MotionState(
        t=float(t), phi=0.0, phi_dot=0.0, phi_ddot=0.0, side=0, ground_acceleration=xg,
        joint_points=arch_joint_points(arch), centroids=arch.voussoir_centroids.copy(),
        rotations=np.zeros(n), translations=np.zeros((n, 2)), loads=loads, load_moments=moments,
        hinge_joints=None, hinge_points=None, hinge_forces=None, forces=jf,
        equilibrium_residual=float(residual_f), g=float(g),
    )


def locked_joint_forces(arch: Arch, loads: np.ndarray, moments: np.ndarray, *,
                        tol: float = 1e-6) -> JointForces:
    """The admissible line of thrust of the undisplaced arch that needs the least friction.

    Unknowns: the left reaction (H, V) and its moment M0 about O. Every joint's N, V and M are
    affine in them; the program asks |M_j| <= h_j N_j (inside the section) and
    |V_j| <= mu N_j, and the least feasible mu is found by bisection.

    Parameters
    ----------
    arch : Arch
    loads : ndarray, (n, 2)
        Force on each voussoir, N.
    moments : ndarray, (n,)
        Their moments about O, N m.
    tol : float
        Absolute tolerance on the friction coefficient.

    Returns
    -------
    JointForces

    Raises
    ------
    SolverError
        No admissible line of thrust exists (the arch could not stand under these loads).
    """
    pts = arch_joint_points(arch)
    w = float(np.abs(loads).sum())
    scale_m = w * arch.radius
    base = joint_forces(pts, loads, moments, np.zeros(2), 0.0)
    units = [joint_forces(pts, np.zeros_like(loads), np.zeros_like(moments), r, rm)
             for r, rm in ((np.array([w, 0.0]), 0.0), (np.array([0.0, w]), 0.0), (np.zeros(2), scale_m))]
    half = base.half_widths

    def affine(attr):
        return getattr(base, attr), np.array([getattr(u, attr) for u in units]).T  # (n+1,), (n+1, 3)

    (n0, n1), (v0, v1), (m0, m1) = affine("normal"), affine("shear"), affine("moment")

    def solve(mu: float):
        # rows: M - hN <= 0, -M - hN <= 0, V - mu N <= 0, -V - mu N <= 0
        a = np.vstack([m1 - half[:, None] * n1, -m1 - half[:, None] * n1,
                       v1 - mu * n1, -v1 - mu * n1])
        b = -np.concatenate([m0 - half * n0, -m0 - half * n0, v0 - mu * n0, -v0 - mu * n0])
        scale = np.concatenate([np.full(2 * len(half), scale_m), np.full(2 * len(half), w)])
        res = linprog(np.zeros(3), A_ub=a / scale[:, None], b_ub=b / scale,
                      bounds=[(None, None)] * 3, method="highs")
        return res.x if res.status == 0 else None

    lo, hi = 0.0, 1.0
    x = solve(hi)
    while x is None:
        lo, hi = hi, 2.0 * hi
        if hi > 1e3:
            raise SolverError("no admissible line of thrust fits in the locked arch under these loads")
        x = solve(hi)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        xm = solve(mid)
        if xm is None:
            lo = mid
        else:
            hi, x = mid, xm
    return joint_forces(pts, loads, moments, np.array([x[0] * w, x[1] * w]), x[2] * scale_m)


# --------------------------------------------------------------------------- time histories
def _ground_before(motion: GroundMotion, t: float, tau: float) -> float:
    """x_g'' just before t (at t = 0: just after): the side of a jump a snapshot shows."""
    eps = 1e-9 * tau
    return float(motion.acceleration(t - eps if t > eps else t + eps))


def _integrate(prepared: PreparedMechanism, motion: GroundMotion, side: int, t0: float,
               phi0: float, v0: float, t1: float, g: float) -> tuple[float, float]:
    """Carry (phi, phi_dot) from t0 to t1 with the Python equation of motion, split at the
    ground motion's breakpoints."""
    if t1 <= t0:
        return phi0, v0
    packed = prepared.packed
    cuts = [t0, *[b for b in np.asarray(motion.breakpoints()) if t0 < b < t1], t1]
    y = np.array([phi0, v0])

    def rhs(t, yy):
        xg = float(motion.acceleration(t))
        return [yy[1], acceleration(packed, yy[0], yy[1], side * xg, g)]

    for a, b in zip(cuts[:-1], cuts[1:]):
        sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-11, atol=1e-13)
        y = sol.y[:, -1]
    return float(y[0]), float(y[1])


def states(
    arch: Arch | PreparedMechanism,
    motion: GroundMotion,
    times,
    *,
    result: SimulationResult | None = None,
    g: float = STANDARD_GRAVITY,
) -> list[MotionState]:
    """The arch at given instants of its response to a ground motion (Figure 8).

    The time history comes from :func:`archquake.mechanism.simulate`; each requested time is
    reached exactly by integrating from the last recorded sample (or impact) before it. At a
    jump of the ground acceleration the snapshot shows the value just before the jump (the
    paper's Figure 8(a) at t = t_p: "the first pulse is still acting"); at t = 0 it shows the
    value just after (t = 0+).

    Parameters
    ----------
    arch : Arch or PreparedMechanism
    motion : GroundMotion
    times : sequence of float
        Instants, s (>= 0, before any collapse).
    result : SimulationResult, optional
        A history already computed for this arch and motion (with its history recorded).
    g : float

    Returns
    -------
    list of MotionState
    """
    prepared = PreparedMechanism.build(arch)
    times = [require_finite("time", float(t)) for t in np.atleast_1d(times)]
    if any(t < 0 for t in times):
        raise InvalidParameterError(f"times must be >= 0 s, got {min(times):g}")
    if result is None:
        result = simulate(prepared, motion, t_end=max(max(times), 1e-9) * 1.001 + 1e-6, g=g)
    h = result.history
    if h is None or h.t.size == 0:
        raise InvalidParameterError("the simulation result has no history (output_interval = 0)")
    tau = math.sqrt(prepared.mechanism.arch.radius / g)
    out = []
    for t in times:
        if result.collapse_time is not None and t > result.collapse_time:
            raise InvalidParameterError(
                f"time {t:g} s is after the collapse at {result.collapse_time:.4g} s; choose "
                "earlier times"
            )
        t_end = float(result.stats.get("t_end", h.t[-1]))
        if t > t_end and result.final_state.value == "moving":
            raise InvalidParameterError(f"time {t:g} s is beyond the simulated history "
                                        f"(ends at {t_end:.4g} s)")
        xg = _ground_before(motion, t, tau)
        i = int(np.searchsorted(h.t, t, side="right")) - 1
        i = max(i, 0)
        t0, phi0, v0, side = float(h.t[i]), float(h.phi[i]), float(h.phi_dot[i]), int(h.side[i])
        onset = result.onset_time
        if side == 0 and onset is not None and t0 <= onset <= t and i + 1 < h.t.size:
            # hinging starts between the sample and t (or at t: show t = onset+)
            nxt = np.flatnonzero(h.side[i + 1:] != 0)
            if nxt.size:
                side = int(h.side[i + 1 + nxt[0]])
                t0, phi0, v0 = onset, 0.0, 0.0
                if t == onset:
                    xg = float(motion.acceleration(t + 1e-9 * tau))
        if side == 0:
            out.append(state_at(prepared, t, 0.0, 0.0, 0, xg, g=g))
            continue
        phi, v = _integrate(prepared, motion, side, t0, phi0, v0, t, g)
        out.append(state_at(prepared, t, max(phi, 0.0), v, side, xg, g=g))
    return out


__all__ = ["MotionState", "locked_joint_forces", "state_at", "states"]
