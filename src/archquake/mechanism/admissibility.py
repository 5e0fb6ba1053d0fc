"""Is the assumed mechanism admissible at this instant of the motion?

A four-hinge mechanism moving as Eq. 2 says is a statically admissible state of the real arch
only if the joint forces it needs can be carried by unilateral, frictional contact:

* at every **locked joint** (a joint that is not one of the four hinges) the line of thrust lies
  within the section and the joint is compressed: ``|M| <= h N`` (``h`` the half-width). The
  margin used is ``(h N - |M|) / (h W)`` (W the arch's weight): continuous in time, also
  through ``N = 0``, and negative exactly when the thrust is outside or the joint in tension;
* at every **hinge** the reaction is compressive: margin ``N / W``;
* at every joint in compression friction is within the cone: margin ``(mu N - |V|) / W``.

The joint forces are those of :func:`archquake.thrust.states.state_at` (the one computation of
the moving arch's joint forces, :class:`~archquake.thrust.states.MotionState`); nothing is
recomputed here.

When a locked joint's margin reaches zero the thrust touches an edge of that joint: a hinge
opens there, on the face the thrust touches (eccentricity > 0: the extrados), and the assumed
mechanism stops being the arch's motion. :func:`first_exit` finds the first such instant of a
time history by a scan of the compiled integrator's exact states
(:func:`archquake.mechanism.simulate` with ``t_eval``) and a bisection to a stated tolerance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.ground.base import GroundMotion

#: Default friction coefficient of the cone (the DEM comparisons' mu).
DEFAULT_FRICTION = 0.8


@dataclass(frozen=True)
class Admissibility:
    """Margins of one mechanism state (all dimensionless, >= 0 where admissible).

    Attributes
    ----------
    t : float
        Time, s.
    thrust_margin : ndarray (n+1,)
        ``(h N - |M|) / (h W)`` at the locked joints; nan at the four hinges (and for a locked
        arch's unknown line of thrust there is no hinge).
    hinge_margin : ndarray (n+1,)
        ``N / W`` at the hinges, nan elsewhere.
    friction_margin : ndarray (n+1,)
        ``(mu N - |V|) / W`` at every joint.
    relative_eccentricity : ndarray (n+1,)
        e / h (the line of thrust, :attr:`JointForces.relative_eccentricity`).
    mu : float
    """

    t: float
    thrust_margin: np.ndarray = field(repr=False)
    hinge_margin: np.ndarray = field(repr=False)
    friction_margin: np.ndarray = field(repr=False)
    relative_eccentricity: np.ndarray = field(repr=False)
    mu: float = DEFAULT_FRICTION

    @property
    def thrust(self) -> float:
        """Least thrust margin over the locked joints."""
        return float(np.nanmin(self.thrust_margin))

    @property
    def worst_joint(self) -> int:
        """The locked joint of least thrust margin."""
        return int(np.nanargmin(self.thrust_margin))

    @property
    def worst_face(self) -> str:
        """'extrados' or 'intrados': the edge the thrust of :attr:`worst_joint` is nearest."""
        return "extrados" if self.relative_eccentricity[self.worst_joint] > 0 else "intrados"

    @property
    def hinges_compressed(self) -> float:
        return float(np.nanmin(self.hinge_margin)) if np.any(np.isfinite(self.hinge_margin)) else math.inf

    @property
    def friction(self) -> float:
        return float(np.min(self.friction_margin))

    @property
    def admissible(self) -> bool:
        """Thrust inside at every locked joint, hinges compressed, friction within the cone."""
        return self.thrust >= 0.0 and self.hinges_compressed >= 0.0 and self.friction >= 0.0

    def to_dict(self) -> dict:
        return {"t_s": self.t, "thrust_margin": self.thrust, "worst_joint": self.worst_joint,
                "worst_face": self.worst_face, "hinge_margin": self.hinges_compressed,
                "friction_margin": self.friction, "mu": self.mu, "admissible": self.admissible}


def admissibility(state, mu: float = DEFAULT_FRICTION) -> Admissibility:
    """The margins of a :class:`~archquake.thrust.states.MotionState` (an open mechanism).

    Parameters
    ----------
    state : MotionState
        From :func:`archquake.thrust.states.state_at` or :func:`~archquake.thrust.states.states`.
    mu : float
        Friction coefficient of the cone.

    Returns
    -------
    Admissibility
    """
    jf = state.forces
    arch = state.configuration.arch
    w = arch.mass * state.g
    n = jf.normal.size
    hinge = np.zeros(n, dtype=bool)
    if state.hinge_joints is not None:
        hinge[list(state.hinge_joints)] = True
    thrust = (jf.half_widths * jf.normal - np.abs(jf.moment)) / (jf.half_widths * w)
    return Admissibility(
        t=state.t,
        thrust_margin=np.where(hinge, np.nan, thrust),
        hinge_margin=np.where(hinge, jf.normal / w, np.nan),
        friction_margin=(mu * jf.normal - np.abs(jf.shear)) / w,
        relative_eccentricity=jf.relative_eccentricity,
        mu=float(mu),
    )


def state_margins(prepared, t: float, phi: float, phi_dot: float, side: int, ground: float, *,
                  mu: float = DEFAULT_FRICTION, g: float = STANDARD_GRAVITY) -> Admissibility:
    """:func:`admissibility` of the mechanism state (``prepared``, ``side``, phi, phi_dot) under
    the ground acceleration ``ground`` (m/s^2); phi_ddot is Eq. 2's
    (:func:`archquake.thrust.states.state_at`)."""
    from archquake.thrust.states import state_at

    return admissibility(state_at(prepared, t, max(phi, 0.0), phi_dot, side, ground, g=g), mu)


@dataclass(frozen=True)
class ExitEvent:
    """The first instant at which the assumed mechanism is no longer admissible.

    Attributes
    ----------
    time : float or None
        s (None: admissible over the whole scan).
    joint : int or None
        The locked joint whose thrust reaches the section's edge.
    face : str or None
        'intrados' or 'extrados': where a hinge opens.
    tolerance : float
        The bisection's bracket on ``time``, s.
    side : int
        The mechanism open at that instant (+1 first, -1 mirror).
    times : ndarray
        The scan's instants, s.
    margins : ndarray (len(times), n+1)
        Thrust margins (nan at the hinges and while locked) at those instants: the margin history.
    hinge_margins, friction_margins : ndarray (len(times),)
        Least hinge and friction margins at each instant (nan while locked).
    """

    time: float | None
    joint: int | None
    face: str | None
    tolerance: float
    side: int
    times: np.ndarray = field(repr=False)
    margins: np.ndarray = field(repr=False)
    hinge_margins: np.ndarray = field(repr=False)
    friction_margins: np.ndarray = field(repr=False)

    def to_dict(self) -> dict:
        return {"time_s": self.time, "joint": self.joint, "face": self.face,
                "tolerance_s": self.tolerance, "side": self.side}


def first_exit(arch, motion: GroundMotion, t_end: float, *, dt: float | None = None,
               tol: float = 1e-6, mu: float = DEFAULT_FRICTION, impact: str = "paper",
               g: float = STANDARD_GRAVITY) -> ExitEvent:
    """The first instant where a locked joint's thrust leaves its section, in a time history of
    the fixed-hinge model (:func:`archquake.mechanism.simulate`).

    The states come from ``simulate(..., t_eval=grid)`` (the compiled integrator's exact
    states); the first grid instant with a negative thrust margin is bracketed with the one
    before, and the crossing located by bisection on the least thrust margin, each evaluation a
    ``simulate(..., t_eval=[t])``, to ``tol`` seconds.

    Parameters
    ----------
    arch : Arch, HingeMechanism or PreparedMechanism
    motion : GroundMotion
    t_end : float
        End of the scan, s (before any collapse).
    dt : float, optional
        Scan step, s (default sqrt(R/g)/400).
    tol : float
        Bisection tolerance on the time, s.
    mu : float
        Friction coefficient (reported margins only; the exit is the thrust's).
    impact : str
        The impact law of the history.

    Returns
    -------
    ExitEvent
    """
    from archquake.mechanism.prepared import PreparedMechanism
    from archquake.mechanism.simulate import SolverOptions, simulate
    from archquake.thrust.states import state_at

    prep = PreparedMechanism.build(arch, impact)
    from archquake.mechanism.kinematics import LENGTH

    a = prep.mechanism.arch
    tau = math.sqrt(float(prep.packed[LENGTH]) / g)
    dt = tau / 400.0 if dt is None else float(dt)
    grid = np.arange(0.0, float(t_end) + 0.5 * dt, dt)
    opts = SolverOptions(output_interval=0.0)

    def run(times):
        res = simulate(prep, motion, options=opts, g=g, t_end=float(np.max(times)) * 1.0001 + 1e-6,
                       t_eval=np.asarray(times))
        return res.evaluated

    def margins_at(t, phi, phi_dot, side):
        if side == 0:
            return None
        # the ground acceleration just before t (a snapshot at a jump shows the pulse still acting)
        xg = float(motion.acceleration(t - 1e-9 * tau if t > 1e-9 * tau else t))
        return admissibility(state_at(prep, t, max(phi, 0.0), phi_dot, side, xg, g=g), mu)

    ev = run(grid)
    times = np.asarray(ev.t)
    ecc: dict[int, np.ndarray] = {}

    def _ecc(k):
        return ecc[k][int(np.nanargmin(margins[k]))]

    n1 = a.voussoirs + 1
    margins = np.full((times.size, n1), np.nan)
    hinge_m = np.full(times.size, np.nan)
    fric_m = np.full(times.size, np.nan)
    first = None
    for k in range(times.size):
        adm = margins_at(float(times[k]), float(ev.phi[k]), float(ev.phi_dot[k]), int(ev.side[k]))
        if adm is None:
            continue
        margins[k] = adm.thrust_margin
        ecc[k] = adm.relative_eccentricity
        hinge_m[k] = adm.hinges_compressed
        fric_m[k] = adm.friction
        if first is None and adm.thrust < 0.0:
            first = k
    if first is None:
        return ExitEvent(None, None, None, tol, 0, times, margins, hinge_m, fric_m)
    if first == 0 or int(ev.side[first - 1]) == 0:
        # inadmissible from the onset of hinging itself: no bracket to bisect
        k = first
        return ExitEvent(float(times[k]), int(np.nanargmin(margins[k])),
                         "extrados" if _ecc(k) > 0 else "intrados", 0.0, int(ev.side[k]), times,
                         margins, hinge_m, fric_m)
    lo, hi = float(times[first - 1]), float(times[first])
    for _ in range(200):
        if hi - lo <= tol:
            break
        mid = 0.5 * (lo + hi)
        e = run([mid])
        adm = margins_at(mid, float(e.phi[0]), float(e.phi_dot[0]), int(e.side[0]))
        if adm is not None and adm.thrust < 0.0:
            hi = mid
        else:
            lo = mid
    e = run([hi])
    adm = margins_at(hi, float(e.phi[0]), float(e.phi_dot[0]), int(e.side[0]))
    assert adm is not None
    return ExitEvent(hi, adm.worst_joint, adm.worst_face, hi - lo, int(e.side[0]), times, margins,
                     hinge_m, fric_m)


__all__ = ["DEFAULT_FRICTION", "Admissibility", "ExitEvent", "admissibility", "first_exit",
           "state_margins"]
