"""The friction coefficient the arch's joints need not to slide, over a whole time history
(paper, "Minimum coefficient of friction to avoid sliding", p. 2131).

At every instant the demand at a joint is |V| / N from the line of thrust of the moving arch
(`archquake.thrust.states`); the arch needs a friction coefficient at least equal to the
largest demand over joints and time. The paper finds, for Oppenheim's arch under the step
impulse, that this maximum is at the right springing (hinge D) at the onset t = 0+, so that it
depends on the magnitude only: 0.509 at 0.5 g and about 0.56 at 1.0 g (0.51 and 0.55 with
UDEC), against 0.50 from the equivalent static analysis.

Instants examined: every sample of the recorded history, the onset of hinging (t = 0+, at
rest, with the ground acceleration just after the onset), and both sides of every impact (the
closing mechanism at phi = 0 with the rate before impact, the opening one with the rate
after). While the arch is locked its forces are statically indeterminate and the least
friction an admissible line of thrust needs is used (`archquake.limit.locked_joint_forces`);
those states are cached by ground acceleration.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.ground.base import GroundMotion
from archquake.limit.analysis import limit_analysis
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import SimulationResult, simulate
from archquake.thrust.states import MotionState, state_at


@dataclass(frozen=True)
class FrictionDemand:
    """Friction needed by the joints over a time history.

    Attributes
    ----------
    max_friction_demand : float
        Largest |V| / N over all joints and instants.
    joint : int
        Joint where it occurs (0 = left springing .. n = right springing).
    time : float
        When it occurs, s.
    side : int
        Mechanism open at that instant (+1, -1; 0 locked).
    onset_demand : float or None
        The largest demand at the onset of hinging (t = 0+ for a pulse above the threshold),
        None if the arch never hinges.
    onset_joint : int or None
    static_friction_demand : float
        Demand of the equivalent static analysis at collapse (limit analysis).
    static_joint : int
        Its joint, for the load towards +x (the first mechanism's).
    times : ndarray, (N,)
        Instants examined, s (sorted; an impact appears twice, closing then opening).
    demand : ndarray, (N,)
        Largest demand over the joints at each instant.
    demand_joint : ndarray of int, (N,)
        Where it occurs.
    sides : ndarray of int, (N,)
    tension_time : float or None
        First instant at which a joint would have to carry tension (N <= 0), s: the assumed
        mechanism is no longer in contact there (typically late in a collapse, at large
        rotations). Instants from then on are left out of the maximum. None if never.
    tension_joint : int or None
    simulation : SimulationResult
    """

    max_friction_demand: float
    joint: int
    time: float
    side: int
    onset_demand: float | None
    onset_joint: int | None
    static_friction_demand: float
    static_joint: int
    times: np.ndarray = field(repr=False)
    demand: np.ndarray = field(repr=False)
    demand_joint: np.ndarray = field(repr=False)
    sides: np.ndarray = field(repr=False)
    tension_time: float | None
    tension_joint: int | None
    simulation: SimulationResult = field(repr=False)

    def to_dict(self, include_history: bool = False) -> dict:
        out: dict[str, object] = {
            "max_friction_demand": self.max_friction_demand,
            "joint": self.joint,
            "time": self.time,
            "side": self.side,
            "onset_friction_demand": self.onset_demand,
            "onset_joint": self.onset_joint,
            "static_friction_demand": self.static_friction_demand,
            "static_joint": self.static_joint,
            "tension_time": self.tension_time,
            "tension_joint": self.tension_joint,
            "instants": int(self.times.size),
            "outcome": self.simulation.outcome.value,
            "impact_law": self.simulation.impact_law,
            "impact_validity": self.simulation.impact_validity,
            "restitution_cv": self.simulation.restitution_cv,
        }
        if include_history:
            out["history"] = {"t": self.times, "demand": self.demand,
                              "joint": self.demand_joint, "side": self.sides}
        return out


def _instants(result: SimulationResult, motion: GroundMotion, tau: float):
    """(t, phi, phi_dot, side, ground) of every instant to examine."""
    h = result.history
    if h is None or h.t.size == 0:
        raise InvalidParameterError("the simulation result has no history (output_interval = 0)")
    rows = [(t, p, v, int(s), a) for t, p, v, s, a in
            zip(h.t, h.phi, h.phi_dot, h.side, h.ground_acceleration)
            if not (s == 0 and t == result.onset_time)]  # replaced by the onset+ state below
    if result.onset_time is not None:
        t0 = result.onset_time
        moving = np.flatnonzero(h.side != 0)
        side = int(h.side[moving[0]]) if moving.size else 1
        rows.append((t0, 0.0, 0.0, side, float(motion.acceleration(t0 + 1e-9 * tau))))
    # the closing mechanism just before each impact (the history holds the state after)
    for t_imp, v_before in zip(result.impact_times, result.impact_rates[:, 0]):
        k = int(np.searchsorted(h.t, t_imp, side="left")) - 1
        if k >= 0 and h.side[k] != 0:
            rows.append((t_imp, 0.0, float(v_before), int(h.side[k]),
                         float(motion.acceleration(max(t_imp - 1e-9 * tau, 0.0)))))
    rows.sort(key=lambda r: r[0])
    return rows


def friction_demand(
    arch: Arch | PreparedMechanism,
    motion: GroundMotion,
    *,
    result: SimulationResult | None = None,
    restitution: float | None = None,
    impact: str | None = None,
    g: float = STANDARD_GRAVITY,
    progress: Callable[[int, int], None] | None = None,
) -> FrictionDemand:
    """Largest friction demand |V| / N over the joints and the whole response to a motion.

    Parameters
    ----------
    arch : Arch or PreparedMechanism
    motion : GroundMotion
    result : SimulationResult, optional
        The time history, if already computed (must hold its history).
    restitution : float, optional
        Prescribed c_v in [0, 1] for the time history (as in
        `archquake.mechanism.simulate`); ignored with ``result``.
    impact : {"paper", "chain", "mirror"}, optional
        Impact law of the time history (as in `archquake.mechanism.simulate`).
    g : float
        Gravity, m/s^2.
    progress : callable, optional
        Called as ``progress(done, total)`` before each instant is examined (the CLI draws a
        progress bar with it; a long record has thousands of instants, and every locked one
        needs a few linear programs).

    Returns
    -------
    FrictionDemand

    Examples
    --------
    Oppenheim's arch, step impulse of 0.5 g (paper p. 2131: 0.509 at the right springing
    at t = 0+; static analysis 0.50):

    >>> import math
    >>> from archquake import Arch
    >>> from archquake.ground import StepImpulse
    >>> fd = friction_demand(Arch(10.0, 1.5, math.radians(157.5), 7), StepImpulse.from_g(0.5, 0.27))
    >>> round(fd.max_friction_demand, 3), fd.joint, fd.time, round(fd.static_friction_demand, 3)
    (0.509, 7, 0.0, 0.495)
    """
    prepared = PreparedMechanism.build(arch, impact)
    if result is None:
        result = simulate(prepared, motion, restitution=restitution, g=g)
    geometry = prepared.mechanism.arch
    tau = float(np.sqrt(geometry.radius / g))
    locked_cache: dict[float, MotionState] = {}
    last_locked: MotionState | None = None
    times, demand, where, sides = [], [], [], []
    onset = None
    tension = None
    instants = _instants(result, motion, tau)
    for count, (t, phi, v, side, xg) in enumerate(instants):
        if progress is not None:
            progress(count, len(instants))
        if side == 0:
            key = float(xg)
            if key not in locked_cache:
                # warm start from the previous locked instant (nearby loads)
                locked_cache[key] = last_locked = state_at(
                    prepared, t, 0.0, 0.0, 0, xg, g=g,
                    locked_start=None if last_locked is None else last_locked.forces)
            ratios = locked_cache[key].friction_demand
        else:
            ratios = state_at(prepared, t, max(phi, 0.0), v, side, xg, g=g).friction_demand
        j = int(np.argmax(ratios))
        if not np.isfinite(ratios[j]):
            tension = (float(t), j)
            break
        times.append(t)
        demand.append(float(ratios[j]))
        where.append(j)
        sides.append(side)
        if onset is None and result.onset_time is not None and side != 0 and t == result.onset_time:
            onset = (float(ratios[j]), j)
    if not demand:  # tension from the first instant: nothing to report (the fuzz found this)
        assert tension is not None  # the loop ends early only by finding tension
        t0, j0 = tension
        raise InvalidParameterError(
            f"the mechanism loses contact at once: joint {j0} would need tension from t = "
            f"{t0:g} s, so no friction demand can be computed; lower the excitation's magnitude")
    demand_a = np.array(demand)
    k = int(np.argmax(demand_a))
    static = limit_analysis(geometry, g=g)
    return FrictionDemand(
        max_friction_demand=float(demand_a[k]),
        joint=int(where[k]),
        time=float(times[k]),
        side=int(sides[k]),
        onset_demand=onset[0] if onset else None,
        onset_joint=onset[1] if onset else None,
        static_friction_demand=static.min_friction,
        static_joint=static.min_friction_joint,
        times=np.array(times),
        demand=demand_a,
        demand_joint=np.array(where, dtype=int),
        sides=np.array(sides, dtype=int),
        tension_time=tension[0] if tension else None,
        tension_joint=tension[1] if tension else None,
        simulation=result,
    )


__all__ = ["FrictionDemand", "friction_demand"]
