"""Hunt-and-fill incremental dynamic analysis of one record: which intensity levels to run next.

Vamvatsikos & Cornell (2002, "Incremental dynamic analysis", Earthquake Engng Struct. Dyn. 31,
491-514, Section 5) trace each record's IDA curve with a *hunt* (intensity raised with a growing
step until the first collapse) followed by a *fill* (levels put back into the largest gaps).
An arch's collapse is not monotonic in the intensity (a record can collapse it at one scale and
leave it standing at a larger one, a "resurrection"), so here the fill covers the whole range up
to the ceiling and every transition between surviving and collapsing levels is then bisected to
the stated precision:

1. **hunt** (while no collapse is seen and the ceiling is not reached): the levels
   ``x_0 = start``, ``x_{k+1} = min(ceiling, x_k + s_0 gamma^k)`` with ``s_0 = hunt_step * start``;
2. **fill** (after the hunt): the ceiling itself, then the geometric midpoint of every pair of
   neighbouring levels further apart than ``fill`` (relative: ``b / a - 1 > fill``);
3. **refine**: the geometric midpoint of every neighbouring pair whose outcomes differ (survive vs
   collapse) while ``b / a - 1 > precision``.

Steps 2 and 3 propose every gap at once, so a round of the analysis runs many levels in one
batch. `propose_levels` is a pure function of the levels already run and their outcomes,
so an interrupted analysis resumes from its store by replaying the rounds; the set of levels it
converges to does not depend on the order in which results arrive (each proposal depends on one
gap only, and the hunt proposes one level at a time).

``start`` is the level at which the record's peak ground acceleration equals the arch's static
collapse multiplier lambda g: the arch opens only where |x_g''| > lambda g (symmetric arch, both
directions), so nothing happens below it. Collapses narrower than ``fill`` between two surviving
levels, and transitions inside a bracket narrower than ``precision``, can be missed: the result
records its settings.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence
from dataclasses import dataclass

from archquake._validate import require_positive, require_range
from archquake.errors import InvalidParameterError


@dataclass(frozen=True)
class HuntFill:
    """Settings of the hunt-and-fill trace of one record (intensities in the IM's units).

    Parameters
    ----------
    start : float
        First level (> 0): the level at which the record's PGA is lambda g.
    ceiling : float
        Largest level run (>= start).
    precision : float
        Relative width to which every survive/collapse transition is bracketed (0.02: the
        collapsing level is within 2 % of the surviving one below or above it).
    fill : float
        Largest relative gap left anywhere between start and ceiling (>= precision).
    hunt_step : float
        First hunt step as a fraction of ``start``.
    hunt_growth : float
        Factor by which each hunt step exceeds the previous one (>= 1).
    """

    start: float
    ceiling: float
    precision: float = 0.02
    fill: float = 0.10
    hunt_step: float = 0.25
    hunt_growth: float = 1.5

    def __post_init__(self) -> None:
        require_positive("start", self.start)
        require_positive("ceiling", self.ceiling)
        if self.ceiling < self.start:
            raise InvalidParameterError(f"ceiling ({self.ceiling:g}) must be >= the first level "
                                        f"({self.start:g})")
        require_range("precision", self.precision, 0, 1)
        require_range("fill", self.fill, 0, 10)
        if self.fill < self.precision:
            raise InvalidParameterError(f"fill ({self.fill:g}) must be >= precision "
                                        f"({self.precision:g})")
        require_positive("hunt_step", self.hunt_step)
        if not self.hunt_growth >= 1.0:
            raise InvalidParameterError(f"hunt_growth must be >= 1, got {self.hunt_growth:g}")


def _sorted(levels: Collection[float], collapsed: Collection[bool]) -> list[tuple[float, bool]]:
    if len(levels) != len(collapsed):
        raise InvalidParameterError("levels and collapsed must have the same length")
    return sorted(zip((float(x) for x in levels), (bool(c) for c in collapsed), strict=True))


def hunting(levels: Sequence[float], collapsed: Sequence[bool], settings: HuntFill) -> bool:
    """True while the hunt is on: no collapse seen and the ceiling not reached."""
    return not any(collapsed) and not any(x >= settings.ceiling for x in levels)


def propose_levels(levels: Sequence[float], collapsed: Sequence[bool],
                   settings: HuntFill) -> list[float]:
    """The levels to run next for one record (empty: its trace is complete).

    Parameters
    ----------
    levels : sequence of float
        Levels already run (IM units).
    collapsed : sequence of bool
        Whether each collapsed the arch.
    settings : HuntFill

    Returns
    -------
    list of float
        New levels, ascending, none already in ``levels``.

    Examples
    --------
    >>> s = HuntFill(start=1.0, ceiling=4.0, precision=0.02, fill=0.5)
    >>> propose_levels([], [], s)
    [1.0]
    >>> propose_levels([1.0], [False], s)
    [1.25]
    >>> [round(x, 4) for x in propose_levels([1.0, 1.25, 1.625], [False, False, True], s)]
    [1.4252, 4.0]
    """
    obs = _sorted(levels, collapsed)
    if not obs:
        return [settings.start]
    if hunting(levels, collapsed, settings):
        k = len(obs) - 1
        step = settings.hunt_step * settings.start * settings.hunt_growth ** k
        return [min(settings.ceiling, obs[-1][0] + step)]
    new: set[float] = set()
    if obs[-1][0] < settings.ceiling:
        new.add(settings.ceiling)
    for (a, ca), (b, cb) in zip(obs, obs[1:], strict=False):
        gap = b / a - 1.0
        if gap > settings.fill or (ca != cb and gap > settings.precision):
            mid = math.sqrt(a * b)
            if a < mid < b:
                new.add(mid)
    return sorted(new)


@dataclass(frozen=True)
class Interval:
    """A run of neighbouring levels with the same outcome, with its brackets.

    Attributes
    ----------
    low, high : float
        The lowest and highest level of the run (IM units).
    below : float or None
        The level run just below ``low`` (other outcome), None if ``low`` is the first level.
    above : float or None
        The level run just above ``high`` (other outcome), None if ``high`` is the last level
        (the interval is open up to the ceiling).
    """

    low: float
    high: float
    below: float | None
    above: float | None

    @property
    def lower_edge(self) -> float:
        """Estimate of where the run starts: the geometric midpoint of its lower bracket."""
        return self.low if self.below is None else math.sqrt(self.low * self.below)

    @property
    def upper_edge(self) -> float:
        """Estimate of where the run ends (``high`` if open to the ceiling)."""
        return self.high if self.above is None else math.sqrt(self.high * self.above)

    def to_dict(self, unit: str) -> dict:
        return {f"low_{unit}": self.low, f"high_{unit}": self.high, f"below_{unit}": self.below,
                f"above_{unit}": self.above, "open_to_ceiling": self.above is None}


def intervals(levels: Collection[float], collapsed: Collection[bool],
              outcome: bool) -> list[Interval]:
    """Maximal runs of neighbouring levels whose ``collapsed`` equals ``outcome``."""
    obs = _sorted(levels, collapsed)
    out: list[Interval] = []
    i = 0
    while i < len(obs):
        if obs[i][1] != outcome:
            i += 1
            continue
        j = i
        while j + 1 < len(obs) and obs[j + 1][1] == outcome:
            j += 1
        out.append(Interval(obs[i][0], obs[j][0], obs[i - 1][0] if i > 0 else None,
                            obs[j + 1][0] if j + 1 < len(obs) else None))
        i = j + 1
    return out


def collapsed_at(levels: Collection[float], collapsed: Collection[bool], x: float) -> bool:
    """Whether the trace says the arch collapses at level ``x``: the outcome of the highest level
    run at or below ``x`` (False below the first level, where nothing happens). Exact at the
    levels run; between them, right to within the bracket of a transition."""
    state = False
    for level, c in _sorted(levels, collapsed):
        if level > x:
            break
        state = c
    return state


__all__ = ["HuntFill", "Interval", "collapsed_at", "hunting", "intervals", "propose_levels"]
