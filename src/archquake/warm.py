"""Compile every numba kernel once, ahead of the first real command.

Every kernel of the package is compiled with ``cache=True``: the first call of each compiles it
(10-40 s per model) and writes the machine code to numba's cache, from which every later process
loads it in milliseconds. `warm` makes that first call on purpose, for each model on a
tiny problem (an arch of 7 voussoirs, a fraction of a second of motion), so that a user's first
``archquake run`` loads its kernels instead of compiling them. ``make demo`` runs it right after
the install (``archquake warm``).

The workloads go through the same public functions as the commands, with the same argument
types (a sampled record is a read-only array, as the readers make it), so each kernel is
compiled for the signature the commands call it with.

Where the cache goes is numba's choice, see `archquake._kernel_cache`: ``NUMBA_CACHE_DIR``
if set; else ``__pycache__`` beside the kernels' sources if the install is writable; else the
user's cache directory (``~/.cache/numba``). numba uses a cache directory only where it can
write, so a read-only install warmed by its owner is compiled again by each other user (into
that user's cache): each user runs ``archquake warm`` once.
"""

from __future__ import annotations

import importlib
import math
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from archquake._kernel_cache import KERNEL_MODULES


def _arch():
    from archquake.geometry import Arch

    # Oppenheim's arch (paper p. 2126): the commands' default
    return Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)


def _record():
    import numpy as np

    from archquake.constants import STANDARD_GRAVITY
    from archquake.ground import Record

    # one cycle of a 1 s sine at 0.5 g, sampled at 0.01 s: a record as the readers build it
    t = 0.01 * np.arange(101)
    return Record(0.5 * STANDARD_GRAVITY * np.sin(2.0 * math.pi * t), 0.01, name="warm-up")


def _step():
    from archquake.ground import StepImpulse

    return StepImpulse.from_g(1.0, 0.27)  # the paper's Figure 4(c) pulse


def _four_link() -> None:
    """The four-link mechanism (``--model fourlink``)."""
    from archquake.mechanism import PreparedMechanism
    from archquake.mechanism.simulate import (
        simulate,  # the function (the module of its name can shadow it on the package)
    )

    prepared = PreparedMechanism.build(_arch(), None)
    simulate(prepared, _step(), restitution=None, t_end=None)
    simulate(prepared, _record(), restitution=None, t_end=None)


def _domains() -> None:
    """The batched pulses of ``archquake domain`` (a parallel loop over the four-link kernel)."""
    from archquake.domains.batch import evaluate_pulses

    evaluate_pulses(_arch(), "step", [0.5, 1.0], [0.27, 0.27])


def _ida() -> None:
    """The batched records of ``archquake ida`` and sweeps (a parallel loop)."""
    from archquake.ida.batch import evaluate_cases
    from archquake.models import Model
    from archquake.sweeps.cases import ArchSpec, Case, ExcitationKind, ExcitationSpec

    spec = ExcitationSpec(ExcitationKind.RECORD, motion=_record(), scale=2.0)
    # the batched kernel is the four-link model's (the rigid chain's batches are "verdicts")
    evaluate_cases([Case(ArchSpec(10.0, 0.15, 157.5, 7), spec, model=Model.FOURLINK)])


def _measures() -> None:
    """Intensity measures and response spectra (``archquake record``, ``records``, ``spectrum``,
    ``ida``): of a record (its read-only samples) and of a pulse (samples made for it)."""
    from archquake.ground.measures import intensity_measures

    intensity_measures(_record(), periods=(0.5, 1.0))
    intensity_measures(_step(), periods=(0.5, 1.0))


def _rigid_steps() -> None:
    """The chain of rigid blocks, time-stepped (``archquake run``, the default model)."""
    from archquake.rigid import simulate_rigid

    simulate_rigid(_arch(), _step(), duration=0.05).to_dict()  # with the joint forces
    simulate_rigid(_arch(), _step(), duration=0.02, friction=0.6)
    simulate_rigid(_arch(), _record(), duration=0.02)  # a record's step means


def _rigid_events() -> None:
    """The chain of rigid blocks, event-driven (``run --integrator events``)."""
    from archquake.ground import StepImpulse
    from archquake.rigid import simulate_rigid

    # a pulse below the onset first: it compiles the contact projection and the joint forces'
    # probe, which the time-stepped chain and the verdicts share, ahead of the event
    # integrator's own kernels (a warm-up split over two processes then loads them in the
    # other process instead of compiling them twice)
    simulate_rigid(_arch(), StepImpulse.from_g(0.05, 0.27), solver="events").to_dict()
    simulate_rigid(_arch(), _step(), duration=0.05, solver="events").to_dict()


def _rigid_verdicts() -> None:
    """The rigid chain's verdicts in batches (``domain``, sweeps, the IDA)."""
    from archquake.rigid import rigid_verdicts

    # one thread: the batch kernel is the same for any number of threads (a threaded run
    # afterwards loads it from the cache), and two threads compiling it side by side took
    # 152 s on a fresh cache where one takes 68 s
    rigid_verdicts(_arch(), [_step(), _record()], duration=0.05, threads=1)


def _dem() -> None:
    """The distinct-element model (``archquake run --model dem``)."""
    from archquake.dem import DemSettings, simulate_dem

    simulate_dem(_arch(), _step(), DemSettings(duration=0.01))


#: Each model's workload, by the name ``archquake warm --only`` takes, in the order they run.
WORKLOADS: dict[str, Callable[[], None]] = {
    "four-link": _four_link,
    "domains": _domains,
    "ida": _ida,
    "measures": _measures,
    "rigid": _rigid_steps,
    "events": _rigid_events,
    "verdicts": _rigid_verdicts,
    "dem": _dem,
}


@dataclass(frozen=True)
class WarmStep:
    """One workload of `warm`.

    Attributes
    ----------
    name : str
        Its key in `WORKLOADS`.
    seconds : float
        Wall time, s (compilation, or loading from the cache when already warm).
    compiled : int
        Kernel signatures compiled by it (not found in the cache).
    loaded : int
        Kernel signatures loaded from the cache.
    cpu_seconds : float
        CPU time of this process, s (user + system): on shared cores the steadier measure of
        what compiling costs.
    """

    name: str
    seconds: float
    compiled: int
    loaded: int
    cpu_seconds: float


@dataclass(frozen=True)
class WarmReport:
    """What `warm` did.

    Attributes
    ----------
    steps : tuple of WarmStep
    cache_dirs : tuple of str
        Where numba keeps the kernels (one directory per kernel package).
    """

    steps: tuple[WarmStep, ...]
    cache_dirs: tuple[str, ...]

    @property
    def seconds(self) -> float:
        """Total wall time, s."""
        return sum(step.seconds for step in self.steps)

    @property
    def cpu_seconds(self) -> float:
        """Total CPU time, s."""
        return sum(step.cpu_seconds for step in self.steps)

    @property
    def compiled(self) -> int:
        """Kernel signatures compiled in all."""
        return sum(step.compiled for step in self.steps)

    def to_dict(self) -> dict:
        return {
            "seconds_s": self.seconds,
            "cpu_s": self.cpu_seconds,
            "compiled": self.compiled,
            "steps": [{"name": s.name, "seconds_s": s.seconds, "cpu_s": s.cpu_seconds,
                       "compiled": s.compiled, "loaded": s.loaded} for s in self.steps],
            "cache_dirs": list(self.cache_dirs),
        }


def dispatchers() -> list:
    """Every numba dispatcher the package defines, by importing `KERNEL_MODULES`.

    Returns
    -------
    list of numba.core.dispatcher.Dispatcher
        In module order; each once.
    """
    from numba.core.dispatcher import Dispatcher

    found: dict[int, Dispatcher] = {}
    for name in KERNEL_MODULES:
        module = importlib.import_module(name)
        for value in vars(module).values():  # a kernel imported by another module counts once
            if isinstance(value, Dispatcher) and value.py_func.__module__.startswith("archquake."):
                found.setdefault(id(value), value)
    return list(found.values())


def cache_counts(kernels: Iterable) -> tuple[int, int]:
    """``(compiled, loaded)``: signatures the dispatchers compiled (cache misses) and loaded
    (cache hits) in this process so far."""
    compiled = loaded = 0
    for kernel in kernels:
        compiled += sum(kernel.stats.cache_misses.values())
        loaded += sum(kernel.stats.cache_hits.values())
    return compiled, loaded


def cache_dirs(kernels: Iterable) -> tuple[str, ...]:
    """The directories numba caches ``kernels`` in (sorted, each once)."""
    dirs = set()
    for kernel in kernels:
        path = getattr(getattr(kernel, "_cache", None), "cache_path", None)
        if path:
            dirs.add(path)
    return tuple(sorted(dirs))


def warm(only: Iterable[str] | None = None,
         progress: Callable[[WarmStep], None] | None = None) -> WarmReport:
    """Compile (or load from the cache) every kernel the commands use.

    Parameters
    ----------
    only : iterable of str, optional
        Names of `WORKLOADS` to run (default all).
    progress : callable, optional
        Called with each `WarmStep` as it finishes.

    Returns
    -------
    WarmReport

    Raises
    ------
    InvalidParameterError
        An unknown name in ``only``.
    """
    from archquake.errors import InvalidParameterError

    names = list(WORKLOADS) if only is None else list(only)
    unknown = [n for n in names if n not in WORKLOADS]
    if unknown:
        raise InvalidParameterError(
            f"unknown warm-up {unknown[0]!r}: choose from {', '.join(WORKLOADS)}")
    kernels = dispatchers()
    steps = []
    for name in names:
        before = cache_counts(kernels)
        t0, c0 = time.perf_counter(), time.process_time()
        WORKLOADS[name]()
        seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
        after = cache_counts(kernels)
        step = WarmStep(name, seconds, after[0] - before[0], after[1] - before[1], cpu)
        steps.append(step)
        if progress is not None:
            progress(step)
    return WarmReport(tuple(steps), cache_dirs(kernels))


__all__ = ["KERNEL_MODULES", "WORKLOADS", "WarmReport", "WarmStep", "cache_counts", "dispatchers",
           "warm"]
