"""The rigid chain's verdict alone, fast: a step chosen for the verdict, a guard that proves it,
and many histories in one compiled, threaded call.

* **The step** (`verdict_time_step`): h = `STEP_FACTOR` sqrt(L / g), L the chain's
  reference length (the voussoirs' thickness): time scales as sqrt(L / g), so a lab arch and a
  nave get the same accuracy (1.0e-3 s on Oppenheim's arch, L = 1.5 m). Its measured error is
  in docs/notes/mechanism.md ("The rigid chain's step").
* **The guard**: a verdict that depends on an impact and may lie near its threshold (a half
  cycle after the first lasted more than `GUARD_LENGTHENING` times the first: the arch
  lingered near a crest) is run again at half the step; where the two verdicts differ the
  result is ``indeterminate``, with the reason. ``guard_ran`` says whether it ran. A collapse
  in the first half cycle (no impact) is not rerun: the first half cycle's threshold moves by
  at most 0.2 % between the default step and a quarter of it (docs/notes/mechanism.md). The
  rule was measured on pulses; on earthquake records it reruns about half of the verdicts and
  no single run foretells which verdicts change with the step, so incremental dynamic analysis
  runs its levels with ``guard=False`` and reruns at half the step only the levels that decide
  its result (`archquake.ida.analysis.deciding_levels`; docs/notes/mechanism.md, "The
  guard on earthquake records").
* **Fast** (`archquake.rigid._verdict_kernels`): the whole history is one compiled
  call; steps of the untouched chain under a ground acceleration inside the safe domain are
  skipped; the run stops at collapse or once rest is proven; no samples are recorded and no
  `BlockResult` is built.

`rigid_verdict` is one history; `rigid_verdicts` runs many over a thread pool (the
kernel releases the GIL), for failure domains, IDA and sweeps.
"""

from __future__ import annotations

import functools
import heapq
import itertools
import math
import threading
from collections.abc import Callable, Hashable, Iterable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass
from typing import Any

import numpy as np

import archquake.rigid._input_kernels as IK
import archquake.rigid._step_kernels as RK
import archquake.rigid._verdict_kernels as VK
from archquake.blocks.assembly import Assembly
from archquake.blocks.criteria import BlockCriteria, block_criteria
from archquake.blocks.criteria import default_window as block_window
from archquake.blocks.result import (
    REST_KINETIC,
    collapse_parameters,
    crown_height,
    excitation_end,
    mirror_link,
    rest_threshold,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import check_motion_lift_off
from archquake.ground.records import Record
from archquake.outcome import Outcome
from archquake.parallel import usable_cores
from archquake.ranges import RUN_TAIL
from archquake.rigid.model import (
    ACC_SAMPLES,
    GAP_TOLERANCE,
    HOLD_TOLERANCE,
    MAX_SWEEPS,
    SOLVER_TOLERANCE,
    RigidModel,
    check_work,
    mean_acceleration,
    mean_vertical,
)

#: The verdict's step, in sqrt(L / g) (L the reference length): 1.0e-3 s on Oppenheim's arch
#: (L = 1.5 m). Measured in docs/notes/mechanism.md, "The rigid chain's step".
STEP_FACTOR = 2.56e-3
#: The guard reruns a verdict reached after an impact when one of its half cycles after the
#: first (for a collapse: the collapsing one, up to the collapse) lasted more than this many
#: times the first half cycle (onset to first impact): near the crest of its mechanism the arch
#: slows down, and a half cycle's duration grows as log(1/delta) with the distance delta to the
#: threshold. Measured at the default step (docs/notes/mechanism.md, "The rigid chain's step"): 2.0
#: is passed from 7 % below to 4 % above the critical step duration on Oppenheim's arch, from 7 %
#: below to 10 % above at t/R = 0.11, and over the pointed arch's band where the step changes
#: the verdict (collapse in half cycle 3; 2.5 missed it).
GUARD_LENGTHENING = 2.0
#: After a motion, the chain settled near (not at) its undisplaced configuration is taken as
#: safe under the rest of the ground motion when it stays below this fraction of its onset
#: accelerations (the run then stops at proven rest).
REST_MARGIN = 0.98

_OUTCOMES = (Outcome.NO_HINGING, Outcome.SURVIVES, Outcome.COLLAPSE, Outcome.INDETERMINATE)


@functools.lru_cache(maxsize=64)
def _model_of_chain(arch: VoussoirChain) -> RigidModel:
    return RigidModel.build(arch)


def _onset_g(model: RigidModel) -> tuple[float, float]:
    """The chain's onset multipliers, g (`onset_g`), by the bisection seeded with the
    equivalent static analysis of the arch with what it carries, where the assembly records it
    (``collapse_multiplier``, `archquake.blocks.assembly.build_arch_assembly`:
    `onset_near`, the same numbers with fewer projections)."""
    from archquake.rigid.events import EventModel

    events = EventModel.of(model)
    hint = model.assembly.meta.get("collapse_multiplier")
    if hint is None:
        return events.onset_g
    return events.onset_near(float(hint))


#: Models built from assemblies (not hashable: keyed by identity, the assembly kept alive).
_ASSEMBLY_MODELS: dict[int, tuple[Assembly, RigidModel]] = {}


#: Held while a model, or its verdict arrays, are built: threads asking at once share one.
_BUILDING = threading.Lock()


def rigid_model(arch_or_model: VoussoirChain | Assembly | RigidModel) -> RigidModel:
    """The `RigidModel` of an arch or an assembly, built once (memoised: both are
    frozen; one model for threads that ask at once), or a model itself."""
    if isinstance(arch_or_model, RigidModel):
        return arch_or_model
    with _BUILDING:
        if isinstance(arch_or_model, VoussoirChain):
            return _model_of_chain(arch_or_model)
        hit = _ASSEMBLY_MODELS.get(id(arch_or_model))
        if hit is not None and hit[0] is arch_or_model:
            return hit[1]
        model = RigidModel.build(arch_or_model)
        if len(_ASSEMBLY_MODELS) > 64:
            _ASSEMBLY_MODELS.clear()
        _ASSEMBLY_MODELS[id(arch_or_model)] = (arch_or_model, model)
        return model


def verdict_time_step(arch_or_model, *, g: float = STANDARD_GRAVITY) -> float:
    """The verdict's default step, s: `STEP_FACTOR` sqrt(L / g), L the reference
    length, m.

    >>> import math
    >>> from archquake.geometry import Arch
    >>> round(verdict_time_step(Arch(10.0, 1.5, math.radians(157.5), 7)), 5)
    0.001
    """
    model = rigid_model(arch_or_model)
    return STEP_FACTOR * math.sqrt(model.assembly.reference_length / g)


@dataclass(frozen=True)
class _Packed:
    """A model's arrays for `verdict_run`."""

    chain: RK.Chain
    frame: VK.Frame
    safe_pos: float  # m/s^2 per g
    safe_neg: float


def _packed(model: RigidModel, settings: BlockCriteria) -> _Packed:
    """A model's arrays for `verdict_run` under ``settings``, built once for each (a model
    hashes by identity; threads asking at once wait for the one being built)."""
    with _BUILDING:
        return _packed_once(model, settings)


@functools.lru_cache(maxsize=64)
def _packed_once(model: RigidModel, settings: BlockCriteria) -> _Packed:
    return _pack(model, settings)


def _pack(model: RigidModel, settings: BlockCriteria) -> _Packed:
    asm = model.assembly
    nblocks = len(asm.base)
    base_state = np.zeros((nblocks, 3))
    base_state[:, :2] = np.asarray(asm.centroids, float)
    cpar = collapse_parameters(asm, settings, float(crown_height(asm, base_state[None])[0]))
    free_mask = (~np.asarray(asm.base, dtype=bool)).astype(np.int64)
    links = [asm.rotation_link, mirror_link(asm) or asm.rotation_link]
    cents = np.asarray(asm.centroids, float)
    lb = np.array([[ln.block_a, ln.block_b] for ln in links], np.int64)
    ll = np.array([[np.asarray(ln.point_a) - cents[ln.block_a],
                    np.asarray(ln.point_b) - cents[ln.block_b]] for ln in links], float)
    ls = np.array([float(ln.sign) for ln in links])
    lam_p, lam_n = _onset_g(model)
    frame = VK.Frame(base_state, model.free_blocks.astype(np.int64), free_mask, cpar, lb, ll, ls)
    return _Packed(model.chain, frame, lam_p, lam_n)


@dataclass(frozen=True)
class RigidVerdict:
    """The rigid chain's verdict on one history (`rigid_verdict`).

    Attributes
    ----------
    outcome : Outcome
    reason : str
        One sentence: why.
    collapse_half_cycle : int or None
        1 + the impacts before the collapse (the DEM's count, the rotation measure's sign
        changes); None without a collapse.
    collapse_time_s, onset_time_s : float or None
        s.
    end_time_s : float
        Where the run stopped, s (at collapse, at proven rest, or at the end of its window).
    time_step_s : float
        The step of the verdict, s.
    guard_ran : bool
        Whether the verdict was rerun at half the step (the guard).
    guard_outcome : Outcome or None
        The rerun's outcome.
    peak_crown_drop : float
        Largest fall of the crown before any collapse, a fraction of the collapse drop.
    max_rotation_rad : float
        The largest |rotation| of the chord of the rotation link (hinge A to hinge B, as
        ``BlockResult.rotation``) before the verdict, rad (at the collapse for a collapse).
    lengthening : float
        The longest half cycle after the first (a collapse's up to the collapse) over the
        first (0 without an impact): the guard's measure of nearness.
    impacts : int
        Impacts before the verdict.
    steps, skipped_steps : int
        Steps computed, and skipped at rest (of the first run).
    rest_proven : bool
        The run stopped at rest with the rest of the ground motion inside the safe domain.
    final_state : str
        How the run at the verdict's step ended: ``collapsed``, ``rest`` or ``moving``.
    """

    outcome: Outcome
    reason: str
    collapse_half_cycle: int | None
    collapse_time_s: float | None
    onset_time_s: float | None
    end_time_s: float
    time_step_s: float
    guard_ran: bool
    guard_outcome: Outcome | None
    peak_crown_drop: float
    max_rotation_rad: float
    lengthening: float
    impacts: int
    steps: int
    skipped_steps: int
    rest_proven: bool
    final_state: str
    #: Gravity, m/s^2.
    g: float = STANDARD_GRAVITY

    def to_dict(self) -> dict:
        """Summary for JSON (units in the keys): the keys of `archquake.outcome.RESULT_KEYS`
        first (``model`` ``"rigid"``, as ``--model`` names it; ``impact_times_s`` and
        ``peak_rotation_rad`` None: the verdict path records no history, only the count of
        impacts, ``impacts``), then the verdict path's own."""
        return {"model": "rigid", "outcome": self.outcome.value,
                "final_state": self.final_state,
                "collapse_half_cycle": self.collapse_half_cycle,
                "collapse_time_s": self.collapse_time_s, "onset_time_s": self.onset_time_s,
                "impact_times_s": None, "peak_rotation_rad": None,
                "max_rotation_rad": self.max_rotation_rad, "g_m_s2": self.g,
                "verdict_reason": self.reason,
                "end_time_s": self.end_time_s, "time_step_s": self.time_step_s,
                "guard_ran": self.guard_ran,
                "guard_outcome": None if self.guard_outcome is None else self.guard_outcome.value,
                "peak_crown_drop": self.peak_crown_drop, "lengthening": self.lengthening,
                "impacts": self.impacts,
                "steps": self.steps, "skipped_steps": self.skipped_steps,
                "rest_proven": self.rest_proven}


def _params(model: RigidModel, packed: _Packed, settings: BlockCriteria, h: float, g: float,
            exc_end: float, skip: bool, solver_tolerance: float) -> np.ndarray:
    lref = model.assembly.reference_length
    k_rest, window = rest_threshold(model.assembly, g)
    par = np.zeros(VK.N_PAR)
    par[VK.P_H] = h
    par[VK.P_G] = g
    par[VK.P_GAP_TOL] = GAP_TOLERANCE * lref
    par[VK.P_TOL] = solver_tolerance * math.sqrt(g * lref)
    par[VK.P_MAX_ITER] = MAX_SWEEPS
    par[VK.P_HOLD_TOL] = HOLD_TOLERANCE * lref
    # the bisection's bound moves; just below it the chain stays
    par[VK.P_SAFE_POS] = packed.safe_pos * g * (1.0 - 1e-9)
    par[VK.P_SAFE_NEG] = packed.safe_neg * g * (1.0 - 1e-9)
    par[VK.P_EXC_END] = exc_end
    par[VK.P_OPEN] = settings.hinge_opening * lref
    par[VK.P_REST_KIN] = k_rest
    par[VK.P_REST_WINDOW] = window
    par[VK.P_ROT_THR] = settings.hinge_opening
    par[VK.P_SKIP] = 1.0 if skip else 0.0
    par[VK.P_STOP_COLLAPSE] = 1.0 if settings.stop_at_collapse else 0.0
    par[VK.P_REST_MARGIN] = REST_MARGIN
    par[VK.P_SUB_SAMPLES] = ACC_SAMPLES
    return par


def _decode(out: np.ndarray, h: float, vg_of) -> dict:
    """The kernel's ``out`` as plain values; ``vg_of(step)``: the ground velocity after a step
    (for `mirror_opens_first`'s choice of the rotation link)."""
    code = int(out[VK.O_OUTCOME])
    onset = int(out[VK.O_ONSET_STEP])
    mirrored = False
    if onset >= 0:
        back = max(1, int(round(0.01 / h)))
        mirrored = vg_of(onset) - vg_of(onset - back) > 0.0
    impacts = int(out[VK.O_IMPACTS_1] if mirrored else out[VK.O_IMPACTS_0])
    first_impact = float(out[VK.O_FIRST_IMPACT_1] if mirrored else out[VK.O_FIRST_IMPACT_0])
    longest = float(out[VK.O_LONGEST_1] if mirrored else out[VK.O_LONGEST_0])
    peak_rot = float(out[VK.O_PEAK_ROT_1] if mirrored else out[VK.O_PEAK_ROT_0])
    t_onset = None if onset < 0 else (onset + 1) * h
    lengthening = (longest / (first_impact - t_onset)
                   if t_onset is not None and first_impact > t_onset else 0.0)
    return {"outcome": _OUTCOMES[code], "impacts": impacts,
            "half": 1 + impacts if code == VK.OUTCOME_COLLAPSE else None,
            "t_collapse": None if math.isnan(out[VK.O_T_COLLAPSE]) else float(out[VK.O_T_COLLAPSE]),
            "onset": t_onset, "t_end": float(out[VK.O_T_END]), "lengthening": lengthening,
            "steps": int(out[VK.O_STEPS]), "skipped": int(out[VK.O_SKIPPED]),
            "peak_drop": float(out[VK.O_PEAK_DROP]), "peak_rotation": peak_rot,
            "rest_proven": bool(out[VK.O_REST_PROVEN]),
            "final": int(out[VK.O_FINAL])}


def _near(d: dict) -> bool:
    """The guard's rule: the verdict depends on an impact (a survival or a collapse after
    one) and one of its half cycles after the first (a collapse's up to the collapse) lasted
    more than `GUARD_LENGTHENING` times the first: the arch lingered near a crest."""
    return (d["impacts"] >= 1 and d["outcome"] in (Outcome.SURVIVES, Outcome.COLLAPSE)
            and d["lengthening"] > GUARD_LENGTHENING)


def _reason(d: dict) -> str:
    o = d["outcome"]
    if o is Outcome.COLLAPSE:
        return "a collapse criterion was met (crown fallen, a block below the springings or turned)"
    if o is Outcome.NO_HINGING:
        return "no joint opened"
    if o is Outcome.SURVIVES:
        return ("at rest with the rest of the ground motion below the onset accelerations"
                if d["rest_proven"] else
                f"at rest: kinetic energy below {REST_KINETIC:g} W L over a rest window, after "
                "the excitation")
    return (f"still moving at the end of the run ({d['t_end']:.3g} s); run longer to decide")


class _Job:
    """One history for the kernel: its parameters, its steps' mean ground accelerations and
    the last steps reaching the safe domain's bounds, prepared by `run` in the thread that
    runs it (compiled for a record, and its means computed by the kernel as the run reaches
    them: without the GIL, beside the other threads' kernels)."""

    def __init__(self, model, packed, motion, h, duration, until_rest, settings, g, skip, tol):
        self.motion = motion
        self.h = h
        self.n = int(math.ceil(max(duration, until_rest or 0.0) / h - 1e-9))
        end = excitation_end(motion)
        self.par = _params(model, packed, settings, h, g,
                           float(self.n * h) if end is None else end, skip, tol)
        self.acc: np.ndarray | None = None
        self._vg: np.ndarray | None = None

    def expected_steps(self) -> float:
        """A guess of the steps the kernel will compute, to start the longest first: for a
        record (steps skipped at rest), those from its first sample outside the safe domain to
        its last (the steps before are skipped; after the last, the run ends at collapse or
        once the arch settles); otherwise all of them."""
        if not isinstance(self.motion, Record) or self.par[VK.P_SKIP] == 0.0:
            return float(self.n)
        x = self.motion.accelerations
        out = np.flatnonzero((x > self.par[VK.P_SAFE_POS]) | (-x > self.par[VK.P_SAFE_NEG]))
        if out.size == 0:
            return 0.0
        return min(float(self.n), (out[-1] - out[0] + 1) * self.motion.dt / self.h)

    def run(self, packed: _Packed) -> np.ndarray:
        """Prepare the steps and run the kernel: its ``out`` (`VK.N_OUT`). A sampled record
        without a vertical component has its steps' means computed by the kernel as the run
        reaches them (`VK.Histories`); any other motion's are computed here first."""
        g = self.par[VK.P_G]
        h = self.h
        check_motion_lift_off(self.motion, g)
        vacc = mean_vertical(self.motion, 0.0, h, self.n)
        safe_pos, safe_neg, margin = (self.par[VK.P_SAFE_POS], self.par[VK.P_SAFE_NEG],
                                      self.par[VK.P_REST_MARGIN])
        bounds = (safe_pos, safe_neg, margin * safe_pos, margin * safe_neg)
        rest_last = np.empty((1, VK.REST_LAST), np.int64)
        if isinstance(self.motion, Record) and vacc.size == 0:
            acc = np.empty(self.n)  # the kernel fills it
            record = self.motion.kernel_spec()[1]
            frac = IK.sub_fractions(ACC_SAMPLES)
            values = np.empty(ACC_SAMPLES)
            for j, lim in enumerate(bounds):
                rest_last[0, j] = IK.record_last_at_least(record, 0.0, h, frac, values, self.n,
                                                          lim, 1.0 if j % 2 == 0 else -1.0)
            skip_acc = acc
        else:
            acc = mean_acceleration(self.motion, 0.0, h, self.n)
            record = np.empty(0)
            skip_acc = acc * (g / (g + vacc)) if vacc.size else acc
            for j, lim in enumerate(bounds):
                rest_last[0, j] = IK.last_at_least(skip_acc, lim, 1.0 if j % 2 == 0 else -1.0)
        hist = VK.Histories(acc, rest_last, np.array([0, acc.size], np.int64),
                            self.par.reshape(1, -1), vacc, skip_acc, record,
                            np.array([0, record.size], np.int64))
        out = np.zeros((1, VK.N_OUT))
        batch: Any = VK.verdict_batch  # a numba dispatcher
        batch(packed.chain, packed.frame, hist, out, 0, 1)
        self.acc = acc[:int(out[0, VK.O_MEANS])]
        return out[0]

    def vg(self, step: int) -> float:
        """The ground velocity after a step, m/s (after `run`): the running sum of the
        steps' accelerations, up to the latest step asked for (a prefix of ``np.cumsum``,
        which sums one step after another: the same bits). A record's means past those its
        run reached are computed here (each step's mean is a function of its index alone)."""
        if step < 0:
            return 0.0
        if self._vg is None or self._vg.size <= step:
            assert self.acc is not None
            acc = (self.acc[:step + 1] if step < self.acc.size
                   else mean_acceleration(self.motion, 0.0, self.h, step + 1))
            self._vg = np.cumsum(acc) * self.h
        return float(self._vg[step])


def _drain(packed: _Packed, jobs: Iterable[tuple[float, Hashable, _Job]], threads: int,
           done: Callable[[Hashable, _Job, np.ndarray], list[tuple[float, Hashable, _Job]]]
           ) -> None:
    """Run ``(expected steps, key, job)`` jobs on ``threads`` threads, the longest expected
    first, one job a task (the histories' costs differ tenfold); ``done(key, job, out)``, in
    this thread as each ends, may return more jobs (the guard's), queued with the rest. Each
    job's numbers do not depend on the order."""
    queue: list[tuple[float, int, Hashable, _Job]] = []
    order = itertools.count()

    def push(items) -> None:
        for cost, key, job in items:
            heapq.heappush(queue, (-cost, next(order), key, job))

    push(jobs)
    if threads == 1:
        while queue:
            _, _, key, job = heapq.heappop(queue)
            push(done(key, job, job.run(packed)))
        return
    with ThreadPoolExecutor(threads) as pool:
        running: dict[Future, tuple[Hashable, _Job]] = {}
        while queue or running:
            while queue and len(running) < threads:
                _, _, key, job = heapq.heappop(queue)
                running[pool.submit(job.run, packed)] = (key, job)
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for future in finished:
                key, job = running.pop(future)
                push(done(key, job, future.result()))


def _threads(threads: int | None) -> int:
    if threads is None:
        return usable_cores()
    if int(threads) < 1:
        raise InvalidParameterError(f"threads must be >= 1, got {threads!r}")
    return int(threads)


def rigid_verdicts(arch_or_model: VoussoirChain | Assembly | RigidModel, motions: Sequence,
                   *, duration: float | Sequence[float] | None = None,
                   until_rest: float | Sequence[float] | None = None,
                   time_step: float | None = None, settings: BlockCriteria | None = None,
                   g: float = STANDARD_GRAVITY, guard: bool = True, skip_at_rest: bool = True,
                   solver_tolerance: float = SOLVER_TOLERANCE,
                   threads: int | None = None) -> list[RigidVerdict]:
    """The rigid chain's verdicts on many ground motions, in one compiled call per step size,
    threaded (the kernel releases the GIL).

    Parameters
    ----------
    arch_or_model : VoussoirChain, Assembly or RigidModel
    motions : sequence of GroundMotion
        Ground accelerations, m/s^2.
    duration : float or sequence, optional
        s, the run's window for each motion (default: the end of the excitation
        + `WINDOW_TAIL` sqrt(R/g), at most ``ranges.DEM_T_END_MAX_S``; required for an
        assembly). The run stops earlier at collapse or at proven rest, so a long window costs
        only while the arch keeps moving.
    until_rest : float or sequence, optional
        s: go on past ``duration`` while the arch moves, up to this time.
    time_step : float, optional
        s (default `verdict_time_step`).
    settings : BlockCriteria, optional
        Thresholds of the verdict (hinge opening, collapse criteria), as the DEM's (a
        `archquake.dem.DemSettings` is accepted for one release, with a
        `DeprecationWarning`).
    g : float
        m/s^2.
    guard : bool
        Rerun a verdict near its threshold at half the step (module docstring).
    skip_at_rest : bool
        Skip steps at rest and stop at proven rest (exact; False only to check that).
    solver_tolerance : float
        As `simulate_rigid`'s.
    threads : int, optional
        Threads (default: the cores this process may use).

    Returns
    -------
    list of RigidVerdict, in the order of ``motions``.
    """
    model = rigid_model(arch_or_model)
    settings = block_criteria(settings, caller="rigid_verdicts")
    h = verdict_time_step(model, g=g) if time_step is None else float(time_step)
    if not (h > 0 and math.isfinite(h)):
        raise InvalidParameterError(f"time_step must be > 0 s, got {time_step!r}")
    motions = list(motions)
    n = len(motions)
    durs = _per_motion(duration, n, "duration")
    rests = _per_motion(until_rest, n, "until_rest")
    for i, mo in enumerate(motions):
        if durs[i] is None:
            durs[i] = default_window(arch_or_model, mo, g)
    for i in range(n):
        check_work(model.n_bodies, max(durs[i], rests[i] or 0.0), h, runs=n)
    packed = _packed(model, settings)
    nthreads = _threads(threads)

    def job(step: float, i: int) -> _Job:
        return _Job(model, packed, motions[i], step, durs[i], rests[i], settings, g,
                    skip_at_rest, solver_tolerance)

    found: dict[int, dict] = {}
    second: dict[int, dict] = {}

    def done(key, ran: _Job, out: np.ndarray) -> list[tuple[float, Hashable, _Job]]:
        i, rerun = key
        d = _decode(out, ran.h, ran.vg)
        if rerun:
            second[i] = d
            return []
        found[i] = d
        if guard and _near(d):  # at half the step: twice the steps computed at the first
            return [(2.0 * d["steps"], (i, True), job(0.5 * h, i))]
        return []

    firsts = [job(h, i) for i in range(n)]
    _drain(packed, [(j.expected_steps(), (i, False), j) for i, j in enumerate(firsts)],
           nthreads, done)
    return [_verdict(found[i], second.get(i), h, g) for i in range(n)]


def _verdict(d: dict, d2: dict | None, h: float, g: float) -> RigidVerdict:
    outcome = d["outcome"]
    reason = _reason(d)
    if d2 is not None:
        if d2["outcome"] is not outcome:
            reason = (f"near the threshold: {outcome.value} at the step {h:.3g} s, "
                      f"{d2['outcome'].value} at {0.5 * h:.3g} s; a finer step "
                      "(time_step) or solver='events' decides")
            outcome = Outcome.INDETERMINATE
        else:
            reason += f" (confirmed at half the step, {0.5 * h:.3g} s)"
    return RigidVerdict(
        outcome=outcome, reason=reason,
        collapse_half_cycle=d["half"] if outcome is Outcome.COLLAPSE else None,
        collapse_time_s=d["t_collapse"] if outcome is Outcome.COLLAPSE else None,
        onset_time_s=d["onset"], end_time_s=d["t_end"], time_step_s=h,
        guard_ran=d2 is not None, guard_outcome=None if d2 is None else d2["outcome"],
        peak_crown_drop=d["peak_drop"], max_rotation_rad=d["peak_rotation"],
        lengthening=d["lengthening"], impacts=d["impacts"], steps=d["steps"],
        skipped_steps=d["skipped"], rest_proven=d["rest_proven"],
        final_state=("moving", "rest", "collapsed")[d["final"]], g=g)


def _per_motion(value, n: int, name: str) -> list:
    if value is None or np.ndim(value) == 0:
        return [None if value is None else float(value)] * n
    out = [None if x is None else float(x) for x in value]
    if len(out) != n:
        raise InvalidParameterError(f"{name} has {len(out)} entries for {n} ground motions")
    return out


#: The default window after the end of the excitation, in sqrt(R/g): the four-link model's
#: default end (`archquake.ranges.RUN_TAIL`), the longest window of
#: ``rigid_to_verdict``.
WINDOW_TAIL = RUN_TAIL


def default_window(arch_or_model, motion, g: float) -> float:
    """The default run window, s: the end of the excitation + `WINDOW_TAIL` sqrt(R/g),
    at most ``ranges.DEM_T_END_MAX_S`` (the block models' cap); the run stops earlier at
    collapse or proven rest."""
    from archquake.ranges import DEM_T_END_MAX_S

    end = excitation_end(motion)
    if end is None:
        raise InvalidParameterError("give duration: the ground motion does not say when it ends")
    radius = getattr(arch_or_model, "radius", None)
    if radius is None:
        raise InvalidParameterError("give duration: a block assembly has no radius to scale "
                                    "the default window by")
    return min(block_window(motion, radius, tail=WINDOW_TAIL, g=g), max(DEM_T_END_MAX_S, end))


def rigid_verdict(arch_or_model: VoussoirChain | Assembly | RigidModel, motion, *,
                  duration: float | None = None, until_rest: float | None = None,
                  time_step: float | None = None, settings: BlockCriteria | None = None,
                  g: float = STANDARD_GRAVITY, guard: bool = True,
                  skip_at_rest: bool = True,
                  solver_tolerance: float = SOLVER_TOLERANCE) -> RigidVerdict:
    """The rigid chain's verdict on one ground motion (`rigid_verdicts`, one thread)."""
    return rigid_verdicts(arch_or_model, [motion], duration=duration, until_rest=until_rest,
                          time_step=time_step, settings=settings, g=g, guard=guard,
                          skip_at_rest=skip_at_rest, solver_tolerance=solver_tolerance,
                          threads=1)[0]


__all__ = ["GUARD_LENGTHENING", "STEP_FACTOR", "RigidVerdict", "default_window", "rigid_model",
           "rigid_verdict", "rigid_verdicts", "verdict_time_step"]
