"""The block models' outcomes of pulses, for the failure-domain search
(`archquake.domains.failure_domain`'s ``evaluate``): the distinct-element model
(``model='dem'``) or the chain of rigid blocks (``model='rigid'``, hinges moving: the DEM's
rigid limit), each run for the pulse plus a tail. The chain's runs of one search round are one
threaded batch of verdicts (`archquake.rigid.rigid_verdicts`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from archquake import models
from archquake.constants import STANDARD_GRAVITY
from archquake.domains.batch import PulseFamily, PulseOutcomes
from archquake.outcome import Outcome

if TYPE_CHECKING:
    pass

#: The block models a domain may be searched with: the DEM and the rigid chain.
BLOCK_MODELS = ("dem", "rigid")

#: Seconds simulated after the end of the pulse, in sqrt(R/g), in a domain run. The DEM declares
#: collapse when the crown has fallen by t, which comes ~1 s (Oppenheim's arch) after the
#: four-link model's crest; near a boundary the arch lingers at the crest, so the tail is generous.
DOMAIN_TAIL = 6.0


def block_pulse_outcome(assembly, family: str, magnitude_g: float, duration: float, settings, tail_s: float,
             first_only: bool, g: float, governing_only: bool = False,
             model: str = "dem", solver: str = "direct") -> tuple[Outcome, int]:
    """One run of the block model ``model`` ('dem' or 'rigid', the latter integrated by
    ``solver``, `simulate_rigid`'s): (outcome, collapse
    half cycle or 0). Module-level: picklable. Both run the pulse plus ``tail_s``; the rigid chain reads
    only the DEM settings' thresholds (hinge opening, collapse criteria), as it always does.

    With ``first_only`` a collapse after the first impact counts as a survival; with
    ``governing_only`` a collapse is reported with half cycle 0 (not counted), so the search
    brackets no first-half-cycle boundary."""
    motion = PulseFamily(family).motion(magnitude_g, duration, g=g)
    options = models.RunOptions(t_end=motion.duration + tail_s, g=g, dem=settings,
                                integrator="events" if solver == "events" else None)
    res = models.run(model, assembly, motion, options=options)
    if res.outcome is Outcome.COLLAPSE:
        half = int(res.collapse_half_cycle or 0)
        if first_only and half != 1:
            return Outcome.SURVIVES, 0
        return Outcome.COLLAPSE, 0 if governing_only else half
    return res.outcome, 0


def rigid_pulse_outcomes(assembly, family: PulseFamily, points, settings, tail_s: float,
                    first_only: bool, g: float, governing_only: bool,
                    threads: int | None) -> list[tuple[Outcome, int]]:
    """`block_pulse_outcome` of the rigid chain for every (magnitude g, duration s) of ``points``,
    as one batch of verdicts (`rigid_verdicts`: the
    verdict's step with its guard, skips at rest, stops at collapse or proven rest)."""
    from archquake.rigid.verdict import rigid_verdicts

    motions = [family.motion(a, d, g=g) for a, d in points]
    verdicts = rigid_verdicts(assembly, motions, duration=[m.duration + tail_s for m in motions],
                              settings=settings.criteria, g=g, threads=threads)
    out = []
    for v in verdicts:
        if v.outcome is Outcome.COLLAPSE:
            half = int(v.collapse_half_cycle or 0)
            if first_only and half != 1:
                out.append((Outcome.SURVIVES, 0))
            else:
                out.append((Outcome.COLLAPSE, 0 if governing_only else half))
        else:
            out.append((v.outcome, 0))
    return out


@dataclass
class DemPulseEvaluator:
    """``evaluate(magnitudes_g, durations) -> PulseOutcomes`` of a block assembly under the DEM
    or the rigid chain, for `failure_domain`'s ``evaluate``.

    Parameters
    ----------
    assembly : Assembly
    family : PulseFamily
    settings : DemSettings
        Its duration is replaced per run (the pulse, then ``tail_s``).
    tail_s : float
        Simulated time after the pulse, s.
    first_only : bool
        Count only collapses in the first half cycle (before the first DEM impact) as collapses:
        the three-voussoir arch's boundary.
    executor : Executor, optional
        Where the runs of one call go (``map``); None runs them here.
    g : float
    governing_only : bool
        Report collapses without their half cycle (0), so that the domain search brackets
        only the governing boundary (see `dem_failure_domain`).
    model : {'dem', 'rigid'}
        The block model run (`BLOCK_MODELS`).
    solver : {'direct', 'events'}
        How the rigid chain is integrated (``simulate_rigid``'s ``solver``). With 'direct'
        the runs of a call are one batch of verdicts
        (`archquake.rigid.verdict.rigid_verdicts`, at the verdict's step,
        threaded), not time histories through ``executor``.
    threads : int, optional
        Threads of that batch (default: the usable cores).
    progress : callable, optional
        Called with the number of runs so far after each call that ran some.

    Notes
    -----
    Results are memoised per (magnitude, duration): the search's two criteria often bisect the
    same bracket.
    """

    assembly: object
    family: PulseFamily
    settings: object
    tail_s: float
    first_only: bool = False
    executor: Executor | None = None
    g: float = STANDARD_GRAVITY
    governing_only: bool = False
    model: str = "dem"
    solver: str = "direct"
    threads: int | None = None
    progress: Callable[[int], None] | None = None
    runs: int = 0
    seconds: float = 0.0
    _memo: dict = field(default_factory=dict, repr=False)

    def __call__(self, magnitudes_g, durations) -> PulseOutcomes:
        mags = np.atleast_1d(np.asarray(magnitudes_g, float))
        durs = np.broadcast_to(np.asarray(durations, float), mags.shape)
        keys = [(round(float(a), 12), round(float(d), 12)) for a, d in zip(mags, durs)]
        todo = sorted({k for k in keys if k not in self._memo})
        t0 = time.perf_counter()
        if todo:
            args = [(self.assembly, self.family.value, a, d, self.settings, self.tail_s,
                     self.first_only, self.g, self.governing_only, self.model, self.solver)
                    for a, d in todo]
            # the rigid chain's verdicts: one threaded batch in this process
            if models.spec(self.model).batched and self.solver == "direct":
                results = rigid_pulse_outcomes(self.assembly, self.family, todo, self.settings,
                                          self.tail_s, self.first_only, self.g,
                                          self.governing_only, self.threads)
            elif self.executor is None:
                results = [block_pulse_outcome(*a) for a in args]
            else:
                results = list(self.executor.map(block_pulse_outcome, *zip(*args)))
            self._memo.update(zip(todo, results))
            self.runs += len(todo)
            if self.progress is not None:
                self.progress(self.runs)
        self.seconds += time.perf_counter() - t0
        out = np.array([self._memo[k][0] for k in keys], dtype=object)
        half = np.array([self._memo[k][1] for k in keys], dtype=np.int64)
        return PulseOutcomes(mags.copy(), np.array(durs, float), out, half, np.ones(mags.size, np.int64))


__all__ = ["BLOCK_MODELS", "DOMAIN_TAIL", "DemPulseEvaluator", "block_pulse_outcome", "rigid_pulse_outcomes"]
