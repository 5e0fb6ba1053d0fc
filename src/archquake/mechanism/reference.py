"""A plain reference driver: ``scipy.integrate.solve_ivp`` with a Python right-hand side.

Same model and outcome semantics as `archquake.mechanism.simulate`, written the
straightforward way: solve_ivp (DOP853) between the excitation's breakpoints, with terminal
events for closure, collapse and the toggle, and a plain scan for the onset of hinging. It is
slow by design and serves as the oracle the compiled path is held to in the tests, and as the
baseline the benchmarks measure against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch
from archquake.geometry.hinges import HingeMechanism
from archquake.ground.base import GroundMotion
from archquake.mechanism.kinematics import G0, H0, LENGTH, acceleration, eom_terms
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import Outcome


@dataclass(frozen=True)
class ReferenceResult:
    """Outcome, collapse half cycle and time, impact times and peak rotations (as in
    `SimulationResult`), plus the number of right-hand-side calls."""

    outcome: Outcome
    collapse_half_cycle: int | None
    collapse_time: float | None
    impact_times: np.ndarray
    peak_rotation: np.ndarray
    rhs_evaluations: int


def _pieces(motion: GroundMotion, t_end: float) -> list[float]:
    pts = sorted({0.0, *[float(b) for b in motion.breakpoints() if 0.0 < b < t_end], t_end})
    return pts


def simulate_reference(
    arch: Arch | HingeMechanism | PreparedMechanism,
    motion: GroundMotion,
    *,
    restitution: float | None = None,
    t_end: float | None = None,
    initial_rate: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    rest_rotation: float = 1e-9,
    max_impacts: int = 2000,
    g: float = STANDARD_GRAVITY,
) -> ReferenceResult:
    """Time history with solve_ivp; see `archquake.mechanism.simulate` for the arguments."""
    prep = PreparedMechanism.build(arch)
    mech = prep.packed
    cv = prep.restitution_for(restitution)
    tau = math.sqrt(mech[LENGTH] / g)
    t_exc = float(motion.duration)
    t_end = t_exc + 60.0 * tau if t_end is None else float(t_end)
    phi_crit, phi_toggle = prep.critical_rotation, prep.toggle_rotation
    meff0 = eom_terms(mech, 0.0)[1]
    bounds = _pieces(motion, t_end)
    nfev = 0

    def ground(t: float, right: float) -> float:
        # left limit at the end of a piece, as the compiled path does
        return float(motion.acceleration(min(t, np.nextafter(right, -np.inf))))

    def opening_force(side: int, a: float) -> float:
        return -g * mech[G0] - side * a * mech[H0]

    def find_onset(t0: float) -> tuple[float, int]:
        for left, right in zip(bounds[:-1], bounds[1:]):
            if right <= t0 or left >= min(t_exc, t_end):
                continue
            ts = np.linspace(max(left, t0), right, 129)
            prev = ts[0]
            for tj in ts:
                for side in (1, -1):
                    if opening_force(side, ground(tj, right)) > 0.0:
                        if tj == ts[0]:
                            return float(tj), side
                        lo, hi = prev, tj
                        for _ in range(80):
                            mid = 0.5 * (lo + hi)
                            if opening_force(side, ground(mid, right)) > 0.0:
                                hi = mid
                            else:
                                lo = mid
                        return float(hi), side
                prev = tj
        return math.inf, 0

    t, side, phi, v = 0.0, 0, 0.0, 0.0
    outcome = Outcome.NO_HINGING
    impacts: list[float] = []
    peaks: list[float] = []
    collapse_half = None
    collapse_time = None
    if initial_rate > 0:
        side, v, outcome = 1, float(initial_rate), Outcome.SURVIVES
        peaks.append(0.0)
    while t < t_end:
        if side == 0:
            t_on, s_on = find_onset(t)
            if s_on == 0:
                break
            t, side, phi, v = t_on, s_on, 0.0, 0.0
            peaks.append(0.0)
            if outcome is Outcome.NO_HINGING:
                outcome = Outcome.SURVIVES
            continue
        right = next(b for b in bounds if b > t + 1e-12 * (1 + t)) if t < bounds[-1] else t_end
        over = t >= t_exc - 1e-12 * (1 + t_exc)
        if over and phi >= phi_crit and v >= 0:
            outcome, collapse_half, collapse_time = Outcome.COLLAPSE, len(peaks), t
            break
        s = side

        def rhs(tt, y, s=s, right=right):
            nonlocal nfev
            nfev += 1
            return [y[1], acceleration(mech, y[0], y[1], s * ground(tt, right), g)]

        def closure(tt, y):
            return y[0]

        closure.terminal, closure.direction = True, -1  # type: ignore[attr-defined]  # solve_ivp event attributes

        def crest(tt, y, over=over):
            return y[0] - phi_crit if over else 1.0

        crest.terminal, crest.direction = True, 1  # type: ignore[attr-defined]  # solve_ivp event attributes

        def turn(tt, y, over=over):  # beyond the crest, closing, turning open again
            return y[1] if over else 1.0

        turn.terminal, turn.direction = True, 1  # type: ignore[attr-defined]  # solve_ivp event attributes

        def toggle(tt, y):
            return y[0] - phi_toggle * (1 - 1e-9)

        toggle.terminal, toggle.direction = True, 1  # type: ignore[attr-defined]  # solve_ivp event attributes
        sol = solve_ivp(rhs, (t, right), [phi, v], method="DOP853", rtol=rtol,
                        atol=[atol, atol * math.sqrt(g / mech[LENGTH])],
                        events=[closure, crest, toggle, turn], dense_output=True)
        # peak of this stretch, up to the event if one fired
        t_last = min([sol.t[-1], *[ev[0] for ev in sol.t_events if len(ev)]])
        ts = np.linspace(t, t_last, 400)
        peaks[-1] = max(peaks[-1], float(np.max(sol.sol(ts)[0])))
        if sol.status == 1:
            fired = [(ev[0], i) for i, ev in enumerate(sol.t_events) if len(ev)]
            t_ev, which = min(fired)
            y_ev = sol.sol(t_ev)
            if which == 0 and y_ev[1] < 0:
                impacts.append(float(t_ev))
                v_after = cv * abs(float(y_ev[1]))
                t = float(t_ev)
                if 0.5 * meff0 * v_after**2 / (g * mech[G0]) < rest_rotation or len(impacts) >= max_impacts:
                    side, phi, v = 0, 0.0, 0.0
                else:
                    side, phi, v = -side, 0.0, v_after
                    peaks.append(0.0)
                continue
            if which == 3 and y_ev[0] < phi_crit:  # a turn below the crest: carry on
                t, phi, v = float(t_ev), float(y_ev[0]), max(float(y_ev[1]), 0.0)
                continue
            outcome, collapse_half, collapse_time = Outcome.COLLAPSE, len(peaks), float(t_ev)
            break
        t, phi, v = float(sol.t[-1]), float(sol.y[0, -1]), float(sol.y[1, -1])
        if t >= t_end:
            break
    return ReferenceResult(
        outcome=outcome,
        collapse_half_cycle=collapse_half,
        collapse_time=collapse_time,
        impact_times=np.array(impacts),
        peak_rotation=np.array(peaks),
        rhs_evaluations=nfev,
    )


__all__ = ["ReferenceResult", "simulate_reference"]
