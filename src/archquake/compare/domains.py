"""Failure domains of the block models, found by the four-link model's domain search
(`archquake.domains.failure_domain`) with a block model's evaluation plugged in: the
distinct-element model (``model='dem'``, paper Figures 6, 11) or the chain of rigid blocks
(``model='rigid'``, hinges moving: the DEM's rigid limit), on the same assemblies
with the same tail and the same search.

As in the paper, the DEM's first-half-cycle boundary comes from the arch cut at the four-link
model's hinges (``assembly='hinges'``, the three-voussoir arch: no impacts, the same mechanism), and its
governing boundary from the voussoir arch (``assembly='voussoirs'``, hinges free to move).

Each evaluation is one DEM time history, so the search runs at a coarser resolution than the
four-link model's (`DEM_DOMAIN_SETTINGS`: 8 coarse magnitudes, 4 fine, 0.01 g brackets) and the
runs of each search round are spread over a process pool (the round's (magnitude, duration)
pairs, i.e. parallel over durations and brackets).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from archquake import models
from archquake._deprecated import renamed
from archquake.compare.histories import HINGES, VOUSSOIRS, dem_assembly
from archquake.constants import STANDARD_GRAVITY
from archquake.domains import DomainSettings, FailureDomain, PulseFamily, failure_domain
from archquake.domains.blocks import (  # noqa: F401  (re-exported)
    BLOCK_MODELS,
    DOMAIN_TAIL,
    DemPulseEvaluator,
    block_pulse_outcome,
    rigid_pulse_outcomes,
)
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.parallel import process_pool, usable_cores

#: Search settings of the DEM domains: ceiling 2 g (Figures 6 and 11 stop at 1.2-2 g), 8 coarse
#: magnitudes (geometric from lambda), 4 fine ones between the boundaries, brackets of 0.01 g.
DEM_DOMAIN_SETTINGS = DomainSettings(max_magnitude_g=2.0, scan_reference_g=2.0, coarse_points=8,
                                     fine_points=4,
                                     precision_g=0.01, early=False)

@dataclass(frozen=True)
class DemDomain:
    """A block model's failure domain and how it was found.

    Attributes
    ----------
    domain : FailureDomain
        The search's result (its ``evaluations`` count lookups; ``runs`` the DEM runs).
    assembly : str
        ``'hinges'`` or ``'voussoirs'``.
    first_only : bool
        Only first-half-cycle collapses counted (then ``collapse_g`` = ``first_half_cycle_g``).
    runs : int
        Time histories run.
    seconds : float
        Wall time, s.
    workers : int
    model : str
        'dem' or 'rigid' (`BLOCK_MODELS`).
    """

    domain: FailureDomain = field(repr=False)
    assembly: str
    first_only: bool
    runs: int
    seconds: float
    workers: int
    dem_settings: dict = field(repr=False, default_factory=dict)
    governing_only: bool = False
    model: str = "dem"

    @property
    def boundary_g(self) -> np.ndarray:
        """The boundary this domain is for: first half cycle (hinges) or governing."""
        return self.domain.first_half_cycle_g if self.first_only else self.domain.collapse_g

    def to_dict(self) -> dict:
        return {"model": self.model, "assembly": self.assembly, "first_half_cycle_only": self.first_only,
                "governing_only": self.governing_only, "runs": self.runs, "seconds": self.seconds,
                "workers": self.workers,
                "search": self.domain.settings.to_dict(), "dem_settings": self.dem_settings,
                "points": self.domain.to_dict()}


def dem_failure_domain(
    arch: Arch,
    family: PulseFamily | str = PulseFamily.STEP,
    durations=(0.1, 0.2, 0.3, 0.5, 0.8),
    *,
    assembly: str = VOUSSOIRS,
    first_only: bool | None = None,
    settings: DomainSettings = DEM_DOMAIN_SETTINGS,
    dem_settings=None,
    tail: float = DOMAIN_TAIL,
    workers: int | None = None,
    executor: Executor | None = None,
    g: float = STANDARD_GRAVITY,
    governing_only: bool = False,
    model: str = "dem",
    solver: str = "direct",
    progress: Callable[[int], None] | None = None,
    loads=None,
) -> DemDomain:
    """The failure domain of the arch's blocks under the DEM (default) or the rigid chain,
    through the four-link model's domain search.

    Parameters
    ----------
    arch : Arch
    family : {'step', 'sine'}
    durations : array_like, s
        t_p or T.
    assembly : {'voussoirs', 'hinges'}
    first_only : bool, optional
        Default True for ``'hinges'`` (the three-voussoir arch gives the first-half-cycle
        boundary), False for ``'voussoirs'``.
    settings : DomainSettings
        The search (default `DEM_DOMAIN_SETTINGS`, 0.01 g).
    dem_settings : DemSettings, optional
        Default: the paper's stiffness and damping.
    tail : float
        Simulated time after each pulse, in sqrt(R/g).
    workers : int, optional
        Process-pool size (default: the usable cores, at most the number of durations x 2);
        1 runs serially. Ignored if ``executor`` is given. With ``model='rigid'`` and
        ``solver='direct'`` the runs are batches of verdicts threaded in this process
        (`archquake.rigid.verdict.rigid_verdicts`): ``workers`` is then the
        number of threads (default: the usable cores) and ``executor`` is not used.
    executor : Executor, optional
        An executor to use instead of a new process pool.
    g : float
    governing_only : bool
        Search only the governing boundary (``collapse_g``): collapses are not told apart by
        half cycle, so the runs that would bracket this assembly's own first-half-cycle boundary
        are saved (the paper takes that boundary from the three-voussoir arch). The domain's
        ``first_half_cycle_g`` is then NaN and ``collapse_half_cycle`` 0: not searched.
    solver : {'direct', 'events'}
        With ``model='rigid'``: how the chain is integrated (``simulate_rigid``'s ``solver``).
    progress : callable, optional
        Called with the number of runs so far as the search goes.
    loads : Loads, optional
        What the arch carries (``assembly='voussoirs'`` only): the blocks carry it
        (`build_arch_assembly`) and the search starts at the
        loaded arch's lambda.
    model : {'dem', 'rigid'}
        The block model: the DEM (``dem_settings`` its stiffness, damping and thresholds) or the
        chain of rigid blocks (`archquake.rigid.simulate_rigid`; only
        the thresholds of ``dem_settings`` are read), each run for the pulse plus ``tail``.

    Returns
    -------
    DemDomain
    """
    from archquake.dem import DemSettings

    if not isinstance(arch, VoussoirChain):
        raise InvalidParameterError(f"dem_failure_domain needs an Arch, got {type(arch).__name__}")
    if model not in BLOCK_MODELS:
        raise InvalidParameterError(f"model must be one of {', '.join(BLOCK_MODELS)}, got {model!r}")
    if solver not in ("direct", "events"):
        raise InvalidParameterError(f"solver must be 'direct' or 'events', got {solver!r}")
    fam = PulseFamily.parse(family)
    first_only = (assembly == HINGES) if first_only is None else bool(first_only)
    asm = dem_assembly(arch, assembly, loads=loads)
    dst = DemSettings() if dem_settings is None else dem_settings
    n_dur = int(np.atleast_1d(durations).size)
    t0 = time.perf_counter()
    own = None
    # the rigid chain's verdicts: threads in one process, no pool
    batched = models.spec(model).batched and solver == "direct"
    if batched:
        n = workers if workers is not None else usable_cores()
        if n < 1:
            raise InvalidParameterError(f"workers must be >= 1, got {n}")
    elif executor is None:
        n = workers if workers is not None else min(usable_cores(), max(1, 2 * n_dur))
        if n < 1:
            raise InvalidParameterError(f"workers must be >= 1, got {n}")
        if n > 1:
            own = executor = process_pool(n)
    else:
        n = getattr(executor, "_max_workers", 0) or 0
    try:
        tail_s = tail * math.sqrt(arch.radius / g)
        ev = DemPulseEvaluator(asm, fam, dst, tail_s, first_only, executor, g,
                               governing_only and not first_only, model, solver,
                               threads=n if batched else None, progress=progress)
        dom = failure_domain(arch, fam, durations, settings=settings, g=g, evaluate=ev,
                             loads=loads)
    finally:
        if own is not None:
            own.shutdown()
    return DemDomain(dom, assembly, first_only, ev.runs, time.perf_counter() - t0, max(n, 1),
                     dst.to_dict(), ev.governing_only, model)


@dataclass(frozen=True)
class DomainComparison:
    """Four-link and DEM failure domains of one arch and pulse family (Figure 6, 11).

    ``first`` (the three-voussoir arch) and ``governing`` (the voussoir arch) may be None when
    not computed. The former name of ``fourlink``, ``analytical``, is read for one more
    release, with a DeprecationWarning.
    """

    fourlink: FailureDomain = field(repr=False)
    first: DemDomain | None = field(repr=False, default=None)
    governing: DemDomain | None = field(repr=False, default=None)
    label: str = ""

    analytical = renamed("analytical", "fourlink", "DomainComparison")

    def rows(self) -> list[dict]:
        """One row per DEM duration: durations (s) and boundaries (g; None where none)."""
        an = self.fourlink
        rows = []
        for which, dd in (("first_half_cycle", self.first), ("collapse", self.governing)):
            if dd is None:
                continue
            for d, m in zip(dd.domain.durations, dd.boundary_g):
                i = int(np.argmin(np.abs(an.durations - d)))
                a = float(an.first_half_cycle_g[i] if which == "first_half_cycle" else an.collapse_g[i])
                if abs(an.durations[i] - d) > 1e-9:
                    a = math.nan
                rows.append({"boundary": which, "assembly": dd.assembly, "duration_s": float(d),
                             "fourlink_g": _num(a), "block_g": _num(float(m)),
                             "relative": _num((m - a) / a) if math.isfinite(a) and math.isfinite(m)
                             else None})
        return rows

    def to_dict(self) -> dict:
        block = next((d.model for d in (self.first, self.governing) if d is not None), None)
        return {"label": self.label, "arch": self.fourlink.arch.describe(),
                "block_model": block,  # the rows' and block_* entries' model: dem or rigid
                "pulse": self.fourlink.family.value, "rows": self.rows(),
                "fourlink": self.fourlink.to_dict(),
                "block_first_half_cycle": self.first.to_dict() if self.first else None,
                "block_governing": self.governing.to_dict() if self.governing else None}


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def compare_domains(
    arch: Arch,
    family: PulseFamily | str = PulseFamily.STEP,
    durations=(0.1, 0.2, 0.3, 0.5, 0.8),
    *,
    first: bool = True,
    governing: bool = True,
    dem_settings=None,
    settings: DomainSettings = DEM_DOMAIN_SETTINGS,
    workers: int | None = None,
    executor: Executor | None = None,
    label: str = "",
    g: float = STANDARD_GRAVITY,
    model: str = "dem",
    loads=None,
) -> DomainComparison:
    """The four-link domain at ``durations`` (default search, 0.001 g) beside the DEM's: the
    first-half-cycle boundary of the three-voussoir arch (``first``) and the governing boundary
    of the voussoir arch (``governing``), both at ``settings`` (0.01 g). ``model``: the block
    model, 'dem' (default) or 'rigid' (`dem_failure_domain`). With ``loads`` every model
    carries them (the four-link links and both assemblies, on the loaded arch's hinges)."""
    subject: Any = arch
    if loads is not None and not loads.empty:
        from archquake.mechanism import PreparedMechanism

        subject = PreparedMechanism.build(arch, loads=loads)
    an = failure_domain(subject, family, durations, g=g, model="fourlink")
    pool = executor
    own = None
    if pool is None and (workers is None or workers > 1):
        n = workers if workers is not None else min(usable_cores(), max(1, 2 * len(np.atleast_1d(durations))))
        if n > 1:
            own = pool = process_pool(n)
    try:
        kw = dict(settings=settings, dem_settings=dem_settings, g=g, executor=pool,
                  workers=1 if pool is None else None, model=model, loads=loads)
        f = dem_failure_domain(arch, family, durations, assembly=HINGES, **kw) if first else None
        gov = dem_failure_domain(arch, family, durations, assembly=VOUSSOIRS, **kw) if governing else None
    finally:
        if own is not None:
            own.shutdown()
    return DomainComparison(an, f, gov, label)


__all__ = [
    "BLOCK_MODELS",
    "DEM_DOMAIN_SETTINGS",
    "DOMAIN_TAIL",
    "DemDomain",
    "DemPulseEvaluator",
    "DomainComparison",
    "compare_domains",
    "dem_failure_domain",
]
