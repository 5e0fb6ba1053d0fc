"""Joint forces of the rocking arch at any instant of its motion: the line of thrust during
motion (paper, Figure 8) and the friction the joints need (p. 2131).

At an instant of a time history the mechanism's state (``phi``, ``phi_dot``, which mechanism
is open) fixes the displaced arch (`archquake.mechanism.configuration.displaced_arch`),
and the equation of motion (Eq. 2, or Eq. 3 for the mirror mechanism) gives ``phi_ddot``.
Each voussoir then carries, in the frame moving with the ground:

- its weight ``-m g`` (vertical),
- the ground's inertia force ``-m x_g''`` (horizontal),
- its own d'Alembert force ``-m a_c`` and couple ``-I alpha``.

The four hinges carry forces through the hinge points and no moment. The three links give
nine equilibrium equations for the eight force components at A, B, C and D; they are
consistent (rank eight) exactly because ``phi_ddot`` satisfies the equation of motion, which
is their virtual-work combination, and the residual of the least-squares solution is kept as
a check (`MotionState.equilibrium_residual`). With the reaction at A known, the
resultant at every joint follows from `archquake.limit.thrust.joint_forces` (the one
statics routine of the package) applied to the displaced voussoirs; voussoirs outside the
mechanism stay on the ground and are loaded by weight and ground inertia only. At an open
hinge the friction demand is measured against the bisector of the two faces (see
`archquake.mechanism.configuration`).

While the arch is locked (before hinging starts, and after it comes to rest) it moves rigidly
with the ground and its internal forces are statically indeterminate. The state reported is
then the admissible line of thrust that needs the least friction
(`archquake.limit.locked_joint_forces`); by the lower-bound theorem of limit analysis
such a line exists whenever the arch stands.

The time history itself is the one compiled integrator's: `states` asks
`archquake.mechanism.simulate` for the exact states at the requested times
(``t_eval``); nothing here integrates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from archquake._validate import require_finite
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.planar import perp
from archquake.ground.base import GroundMotion, has_vertical
from archquake.limit.locked import locked_joint_forces
from archquake.limit.thrust import JointForces, joint_forces, moments_about_origin
from archquake.mechanism.configuration import DisplacedArch, displaced_arch
from archquake.mechanism.kinematics import acceleration
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import SolverOptions, simulate


@dataclass(frozen=True)
class MotionState:
    """The arch at one instant: displaced voussoirs and the forces at every joint.

    Attributes
    ----------
    t : float
        Time, s.
    configuration : DisplacedArch
        The displaced arch (`archquake.mechanism.configuration.displaced_arch`): phi,
        phi_dot, phi_ddot (Eq. 2), side, joint lines, centroids, rigid motions and hinges, each
        also readable here under its own name (``state.phi``, ``state.joint_points``, ...).
    ground_acceleration : float
        x_g'' used for the forces, m/s^2 (towards +x positive).
    loads : ndarray, (n, 2)
        Resultant external force on each voussoir (weight, ground inertia, own inertia), N.
    load_moments : ndarray, (n,)
        Their moment about the origin O, N m.
    hinge_forces : ndarray, (4, 2), or None
        Force transmitted at A, B, C, D from the part on the left to the part on the right, N.
    forces : JointForces
        Resultants at every joint (`archquake.limit.thrust` conventions).
    equilibrium_residual : float
        Largest violation of the links' nine equilibrium equations, relative to the total
        weight (forces) and weight x R (moments): ~1e-15 when phi_ddot obeys Eq. 2.
    g : float
        Gravity, m/s^2.
    """

    t: float
    configuration: DisplacedArch
    ground_acceleration: float
    loads: np.ndarray = field(repr=False)
    load_moments: np.ndarray = field(repr=False)
    hinge_forces: np.ndarray | None = field(repr=False)
    forces: JointForces = field(repr=False)
    equilibrium_residual: float
    g: float

    # the displaced arch, read from its one home
    phi = property(lambda self: self.configuration.phi, doc="rad")
    phi_dot = property(lambda self: self.configuration.phi_dot, doc="rad/s")
    phi_ddot = property(lambda self: self.configuration.phi_ddot, doc="rad/s^2 (Eq. 2)")
    side = property(lambda self: self.configuration.side, doc="+1, -1; 0 locked")
    joint_points = property(lambda self: self.configuration.joint_points, doc="m, (n+1, 2, 2)")
    centroids = property(lambda self: self.configuration.centroids, doc="m, (n, 2)")
    rotations = property(lambda self: self.configuration.rotations, doc="rad, (n,)")
    translations = property(lambda self: self.configuration.translations, doc="m, (n, 2)")
    positions = property(lambda self: self.configuration.positions, doc="dx, dy (m), rotation (rad), (n, 3)")
    hinge_joints = property(lambda self: self.configuration.hinge_joints, doc="A, B, C, D or None")
    hinge_points = property(lambda self: self.configuration.hinge_points, doc="m, (4, 2) or None")

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


def _voussoir_loads(arch: VoussoirChain, centroids: np.ndarray, acc: np.ndarray, alpha: np.ndarray,
                    ground: float, g: float) -> tuple[np.ndarray, np.ndarray]:
    """Weight, ground inertia and own inertia of each voussoir (N, (n, 2)) and their moments
    about O (N m, (n,))."""
    m = arch.voussoir_masses
    f = -m[:, None] * (acc + np.array([ground, g]))
    return f, moments_about_origin(f, centroids, -arch.voussoir_inertias * alpha)


def _hinge_forces(config: DisplacedArch, loads: np.ndarray, moments: np.ndarray,
                  scale_f: float, scale_m: float) -> tuple[np.ndarray, float]:
    """Forces at A, B, C, D (left part on right part) from the three links' equilibrium, and
    the largest residual of the nine equations (relative to ``scale_f``, ``scale_m``)."""
    j = config.hinge_joints
    p = config.hinge_points
    assert j is not None and p is not None  # an open mechanism
    a = np.zeros((9, 8))
    rhs = np.zeros(9)
    for link in range(3):
        sl = slice(j[link], j[link + 1])
        r = 3 * link
        # F_in + L - F_out = 0 ; p_in x F_in + M - p_out x F_out = 0
        a[r:r + 2, 2 * link:2 * link + 2] = np.eye(2)
        a[r:r + 2, 2 * link + 2:2 * link + 4] = -np.eye(2)
        a[r + 2, 2 * link:2 * link + 2] = perp(p[link])
        a[r + 2, 2 * link + 2:2 * link + 4] = -perp(p[link + 1])
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
    locked_start: JointForces | None = None,
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
    locked_start : JointForces, optional
        For a locked state: a line of thrust to start the least-friction search from (the
        ``forces`` of a nearby locked state; see `archquake.limit.locked_joint_forces`).

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
        return _locked_state(prepared, t, xg, g, locked_start)
    if phi < 0:
        raise InvalidParameterError(f"phi must be >= 0 rad while a mechanism is open, got {phi:g}")
    # Eq. 2 for side +1; the mirror mechanism is the packed one under -x_g'' (Eq. 3)
    phi_ddot = float(acceleration(prepared.packed, phi, phi_dot, side * xg, g))
    config = displaced_arch(prepared, phi, side, phi_dot=phi_dot, phi_ddot=phi_ddot)
    assert config.hinge_joints is not None and config.hinge_points is not None
    loads, moments = _voussoir_loads(arch, config.centroids, config.accelerations,
                                     config.angular_accelerations, xg, g)
    weight = arch.mass * g
    hinge_f, residual = _hinge_forces(config, loads, moments, weight, weight * arch.radius)
    a_joint = config.hinge_joints[0]
    reaction = hinge_f[0] - loads[:a_joint].sum(axis=0)
    reaction_moment = float(perp(config.hinge_points[0]) @ hinge_f[0] - moments[:a_joint].sum())
    jf = joint_forces(config.joint_points, loads, moments, reaction, reaction_moment)
    return MotionState(t=float(t), configuration=config, ground_acceleration=xg, loads=loads,
                       load_moments=moments, hinge_forces=hinge_f, forces=jf,
                       equilibrium_residual=residual, g=float(g))


def _locked_state(prepared: PreparedMechanism, t: float, xg: float, g: float,
                  start: JointForces | None = None) -> MotionState:
    config = displaced_arch(prepared, 0.0, 0)
    arch = config.arch
    loads, moments = _voussoir_loads(arch, config.centroids, config.accelerations,
                                     config.angular_accelerations, xg, g)
    jf = locked_joint_forces(arch, loads, moments, start=start)
    residual_f = np.abs(jf.force[0] + loads.sum(axis=0) - jf.force[-1]).max() / (arch.mass * g)
    return MotionState(t=float(t), configuration=config, ground_acceleration=xg, loads=loads,
                       load_moments=moments, hinge_forces=None, forces=jf,
                       equilibrium_residual=float(residual_f), g=float(g))


# --------------------------------------------------------------------------- time histories
def states(
    arch: Arch | PreparedMechanism,
    motion: GroundMotion,
    times,
    *,
    restitution: float | None = None,
    impact: str | None = None,
    options: SolverOptions | None = None,
    g: float = STANDARD_GRAVITY,
) -> list[MotionState]:
    """The arch at given instants of its response to a ground motion (Figure 8).

    The states come from `archquake.mechanism.simulate` with ``t_eval=times``: each
    requested time is reached by a step of the integrator landing on it. At a jump of the
    ground acceleration the snapshot shows the value just before the jump (the paper's Figure
    8(a) at t = t_p: "the first pulse is still acting"); at t = 0, and at the onset of hinging,
    the value just after (t = 0+, onset+). A vertical ground acceleration a_v(t) (upward: a
    pulse's vertical part, a record's vertical component) weighs on every voussoir as gravity
    g + a_v at the same instant, as it does in the integration; the states' ``g`` stays the
    nominal gravity (their accelerations in g are read against it).

    Parameters
    ----------
    arch : Arch or PreparedMechanism
    motion : GroundMotion
    times : sequence of float
        Instants, s (>= 0, before any collapse; any order, repeats allowed).
    restitution : float, optional
        Prescribed c_v in [0, 1], as in `archquake.mechanism.simulate`.
    impact : {"paper", "chain", "mirror"}, optional
        Impact law, as in `archquake.mechanism.simulate`.
    options : SolverOptions, optional
        Integrator settings (default: simulate's; no history is recorded).
    g : float
        Gravity, m/s^2.

    Returns
    -------
    list of MotionState
        In the order of ``times``.
    """
    prepared = PreparedMechanism.build(arch, impact)
    times = [require_finite("time", float(t), "s") for t in np.atleast_1d(times)]
    if any(t < 0 for t in times):
        raise InvalidParameterError(f"times must be >= 0 s, got {min(times):g}")
    order = np.argsort(times, kind="stable")
    requested = np.asarray(times)[order]
    base = SolverOptions() if options is None else options
    opts = SolverOptions(rtol=base.rtol, atol=base.atol, rest_rotation=base.rest_rotation,
                         max_impacts=base.max_impacts, output_interval=0.0)
    result = simulate(prepared, motion, restitution=restitution, options=opts, g=g,
                      t_end=max(float(requested[-1]), 1e-9) * 1.001 + 1e-6, t_eval=requested)
    ev = result.evaluated
    assert ev is not None
    if ev.t.size < requested.size:
        t = float(requested[ev.t.size])
        if result.collapse_time is not None:
            raise InvalidParameterError(
                f"time {t:g} s is after the collapse at {result.collapse_time:.4g} s; choose "
                "earlier times"
            )
        raise InvalidParameterError(f"time {t:g} s is beyond the simulated history")
    tau = math.sqrt(prepared.mechanism.arch.radius / g)
    onset = result.onset_time
    # the motion's upward ground acceleration, m/s^2 (None: it has none)
    vertical = getattr(motion, "vertical_acceleration", None) if has_vertical(motion) else None
    out: list[MotionState | None] = [None] * len(times)
    for k, i in enumerate(order):
        t, side = float(ev.t[k]), int(ev.side[k])
        # the instant whose ground acceleration the snapshot shows: onset+ (the acceleration
        # that opens the mechanism), else just before t (at t = 0: just after)
        eps = 1e-9 * tau
        shown = t + eps if (side != 0 and t == onset) or t <= eps else t - eps
        xg = float(motion.acceleration(shown))
        phi = max(float(ev.phi[k]), 0.0) if side != 0 else 0.0
        # the mechanism open at t: a row of the impact law's table (row 0 under Eq. 4)
        row = int(ev.mechanism_row[k]) if ev.mechanism_row is not None and side != 0 else 0
        # a vertical ground acceleration a_v (upward) weighs as gravity g + a_v at that instant
        g_t = g if vertical is None else g + float(vertical(shown))
        state = state_at(prepared.member(row), t, phi, float(ev.phi_dot[k]), side, xg, g=g_t)
        out[i] = state if g_t == g else replace(state, g=float(g))
    return out  # type: ignore[return-value]


__all__ = ["MotionState", "state_at", "states"]
