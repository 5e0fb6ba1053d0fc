"""Snapshots of both models: where the hinges are (paper Figures 8 and 9) and the inter-stone
displacements under reduced damping (Figure 10).

A DEM hinge is a joint whose wider end is open by more than a tenth of the widest joint opening
at that instant (`dem_hinges`); its face is the other end. The four-link model's hinges are
those of the open mechanism (`archquake.thrust.MotionState.hinge_joints`).
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from archquake._deprecated import renamed
from archquake.compare.histories import VOUSSOIRS, dem_assembly
from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch
from archquake.validation.paper import FIGURE9_TIMES, FIGURE10_DAMPING, FIGURE10_PULSE, FIGURE10_TIME

if TYPE_CHECKING:
    from archquake.blocks.result import BlockResult


def dem_hinges(result, time: float, *, relative: float = 0.1) -> list[tuple[int, str]]:
    """(joint, face) of the DEM hinges at the recorded sample nearest ``time`` (s): the block
    models' one rule, `archquake.blocks.result.open_hinges` (a tenth of the widest
    opening)."""
    from archquake.blocks.result import open_hinges

    return open_hinges(result, time, relative=relative)


def joint_displacements(result, time: float) -> dict[str, np.ndarray]:
    """Relative displacements of neighbouring blocks at the sample nearest ``time`` (s).

    Returns
    -------
    dict
        ``slip_m`` (nj,): tangential offset at the more closed end of each joint, m (the
        inter-stone displacement that looks like sliding); ``opening_m`` (nj, 2): gap at the
        intrados and extrados ends, m; ``max_opening_m`` (nj,); ``time_s``.
    """
    k = int(np.argmin(np.abs(result.times - time)))
    opening = result.joint_opening[k]
    return {"time_s": float(result.times[k]), "slip_m": result.joint_slip[k].copy(),
            "opening_m": opening.copy(), "max_opening_m": opening.max(axis=1)}


@dataclass(frozen=True)
class HingeComparison:
    """Four-link (Figure 8) and DEM (Figure 9) hinges at the same instants.

    Attributes
    ----------
    times : tuple of float, s
    fourlink : tuple
        Per time, the four-link model's open mechanism's hinge joints (4 ints) or None while
        locked (read for one more release under its former name ``analytical``, with a
        DeprecationWarning).
    dem : tuple
        Per time, the DEM's hinges as (joint, face) pairs.
    states : tuple of MotionState
    dem_result : BlockResult
    """

    times: tuple
    fourlink: tuple
    dem: tuple
    states: tuple = field(repr=False)
    dem_result: BlockResult = field(repr=False)
    seconds: float = 0.0

    analytical = renamed("analytical", "fourlink", "HingeComparison")

    def rows(self) -> list[dict]:
        out = []
        for t, a, d in zip(self.times, self.fourlink, self.dem):
            dj = sorted({j for j, _ in d})
            out.append({"time_s": t, "fourlink_joints": list(a) if a else None,
                        "dem_joints": dj, "dem_hinges": [f"{j} {f}" for j, f in d],
                        "same": a is not None and set(a) == set(dj)})
        return out

    def to_dict(self) -> dict:
        return {"rows": self.rows(), "seconds": self.seconds}


def compare_hinges(arch: Arch, times=FIGURE9_TIMES, *, magnitude_g: float = 1.0,
                   duration: float = 0.20, settings=None, g: float = STANDARD_GRAVITY
                   ) -> HingeComparison:
    """Figures 8 and 9: the four-link mechanism's hinges (`archquake.thrust.states`) and
    the DEM's (every voussoir a block) at ``times`` for the step impulse ``magnitude_g``,
    ``duration`` (s)."""
    from archquake.dem import DemSettings, simulate_dem
    from archquake.ground.pulses import StepImpulse
    from archquake.mechanism import PreparedMechanism
    from archquake.thrust import states

    t0 = _time.perf_counter()
    motion = StepImpulse.from_g(magnitude_g, duration, g=g)
    snaps = states(PreparedMechanism.build(arch), motion, list(times), g=g)
    st = (DemSettings() if settings is None else settings).with_(
        duration=max(times) + 0.05, output_interval=0.005)
    res = simulate_dem(dem_assembly(arch, VOUSSOIRS), motion, st, g=g)
    return HingeComparison(tuple(float(t) for t in times),
                           tuple(s.hinge_joints for s in snaps),
                           tuple(dem_hinges(res, t) for t in times), tuple(snaps), res,
                           _time.perf_counter() - t0)


@dataclass(frozen=True)
class ReducedDampingSnapshot:
    """Figure 10: the voussoir arch under reduced and under the paper's damping at one instant.

    Attributes
    ----------
    reduced, paper : BlockResult
    time : float, s
    reduced_displacements, paper_displacements : dict
        `joint_displacements` at ``time``.
    """

    reduced: BlockResult = field(repr=False)
    paper: BlockResult = field(repr=False)
    time: float
    reduced_displacements: dict = field(repr=False)
    paper_displacements: dict = field(repr=False)
    seconds: float = 0.0

    def to_dict(self) -> dict:
        def summary(res, jd):
            return {"outcome": res.outcome.value, "rayleigh": list(res.settings.damping),
                    "max_slip_mm": float(1e3 * np.max(np.abs(jd["slip_m"]))),
                    "slip_mm": (1e3 * jd["slip_m"]).tolist(),
                    "max_opening_mm": (1e3 * jd["max_opening_m"]).tolist(),
                    "max_slip_over_run_mm": float(1e3 * np.max(np.abs(res.joint_slip))),
                    "energy_error": res.energy_error}
        return {"time_s": self.time, "reduced": summary(self.reduced, self.reduced_displacements),
                "paper": summary(self.paper, self.paper_displacements), "seconds": self.seconds}


def reduced_damping_snapshot(arch: Arch, *, magnitude_g: float = FIGURE10_PULSE[0],
                             duration: float = FIGURE10_PULSE[1], time: float = FIGURE10_TIME,
                             damping=FIGURE10_DAMPING, g: float = STANDARD_GRAVITY,
                             end_time: float | None = None) -> ReducedDampingSnapshot:
    """Figure 10: run the voussoir arch to ``time`` (s) with reduced damping
    ``damping = (f_min Hz, xi_min fraction)`` and with the paper's, and measure the joints.

    ``end_time`` (s, default ``time`` + 0.02 s) runs both longer than the snapshot, e.g. to see
    their outcomes (the runs never stop at a collapse)."""
    from archquake.dem import DemSettings, simulate_dem
    from archquake.ground.pulses import StepImpulse

    t0 = _time.perf_counter()
    motion = StepImpulse.from_g(magnitude_g, duration, g=g)
    asm = dem_assembly(arch, VOUSSOIRS)
    end = time + 0.02 if end_time is None else max(float(end_time), time + 0.02)
    base = DemSettings(duration=end, output_interval=0.005, stop_at_collapse=False)
    reduced = simulate_dem(asm, motion, base.with_(
        damping=DemSettings.rayleigh_from_minimum(*damping)), g=g)
    paper = simulate_dem(asm, motion, base, g=g)
    return ReducedDampingSnapshot(reduced, paper, time, joint_displacements(reduced, time),
                                  joint_displacements(paper, time), _time.perf_counter() - t0)


__all__ = [
    "FIGURE10_DAMPING",
    "FIGURE10_PULSE",
    "FIGURE10_TIME",
    "FIGURE9_TIMES",
    "HingeComparison",
    "ReducedDampingSnapshot",
    "compare_hinges",
    "dem_hinges",
    "joint_displacements",
    "reduced_damping_snapshot",
]
