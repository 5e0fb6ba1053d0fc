"""The time-history route of the local-mechanism check (Circolare 2019 C8.7.1.2.1.9).

The code allows the check by nonlinear dynamic analysis of the mechanism under natural records
compatible with the site's spectrum, more of them than for a global analysis: the mechanism
passes a limit state if **no record takes it beyond d0** (the displacement at which the capacity
curve reaches zero, the static instability) **and the mean of the peak displacements stays
below d_SLV (d_SLC)**, the capacity of the static route (0.4 d0, 0.6 d0).

Here the dynamics are archquake's own chain of rigid voussoirs (hinges open anywhere, impacts
dissipate energy through the contacts, no assumed restitution or viscous damping), run to a
verdict by `archquake.rigid.run.rigid_to_verdict`. Its motion is read as the equivalent
SDOF system's displacement through (C8.7.1.4): the horizontal displacement, relative to the
ground, of the curve's control point (by default the centre of mass of the mechanism's moving
voussoirs), times sum m delta^2 / (delta_C sum m delta). A record whose run collapses the arch
counts as exceeding d0.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from archquake.codecheck.check import NONLINEAR
from archquake.codecheck.kinematic import CapacityCurve, FourHingeMechanism
from archquake.errors import InvalidParameterError

#: The fewest records whose mean response the code lets one use (NTC 2018 §7.3.5).
MIN_RECORDS = 7
#: First of the rigid chain's blocks that is a voussoir (blocks 0 and 1 are the abutments:
#: `archquake.blocks.assembly.build_arch_assembly`).
_FIRST_VOUSSOIR = 2


@dataclass(frozen=True)
class RecordResponse:
    """One record's run.

    Attributes
    ----------
    name : str
    peak_displacement_m : float
        Largest |d| of the run, m (inf if the arch collapsed).
    outcome : str
        The run's verdict (``collapse``, ``survives``, ``no_hinging``, ``indeterminate``).
    """

    name: str
    peak_displacement_m: float
    outcome: str

    def to_dict(self) -> dict:
        return {"name": self.name, "peak_displacement_m": self.peak_displacement_m,
                "outcome": self.outcome}


@dataclass(frozen=True)
class TimeHistoryCheck:
    """The time-history check of one limit state (C8.7.1.2.1.9).

    Attributes
    ----------
    limit_state : {'SLV', 'SLC'}
    d_limit_m : float
        d_SLV = 0.4 d0 or d_SLC = 0.6 d0, m.
    d0_m : float
        m.
    responses : tuple of RecordResponse
    """

    limit_state: str
    d_limit_m: float
    d0_m: float
    responses: tuple[RecordResponse, ...]

    @property
    def mean_peak_m(self) -> float:
        """Mean of the records' peak displacements, m (inf if any record collapsed the arch)."""
        return float(np.mean([r.peak_displacement_m for r in self.responses]))

    @property
    def exceeds_d0(self) -> tuple[str, ...]:
        """The records that took the mechanism beyond d0."""
        return tuple(r.name for r in self.responses if r.peak_displacement_m > self.d0_m)

    @property
    def passes(self) -> bool:
        return not self.exceeds_d0 and self.mean_peak_m <= self.d_limit_m

    def verdict(self) -> str:
        word = "passes" if self.passes else "FAILS"
        beyond = (f"; {len(self.exceeds_d0)} of {len(self.responses)} records beyond d0"
                  if self.exceeds_d0 else "")
        mean = "inf" if math.isinf(self.mean_peak_m) else f"{self.mean_peak_m:.4f} m"
        return (f"{self.limit_state} (time histories, {len(self.responses)} records): mean peak d "
                f"{mean} against d_{self.limit_state} {self.d_limit_m:.4f} m{beyond}: {word}")

    def to_dict(self) -> dict:
        return {"limit_state": self.limit_state, "d_limit_m": self.d_limit_m, "d0_m": self.d0_m,
                "mean_peak_displacement_m": self.mean_peak_m, "passes": self.passes,
                "records_beyond_d0": list(self.exceeds_d0),
                "records": [r.to_dict() for r in self.responses]}


def chain_displacement(curve: CapacityCurve, result) -> np.ndarray:
    """The equivalent SDOF displacement d(t) of a rigid-chain run by (C8.7.1.4), m.

    Parameters
    ----------
    curve : CapacityCurve
        Of the arch's four-hinge mechanism (its moving voussoirs, control point and virtual
        field define d).
    result : BlockResult
        The run's samples (a `RigidRun`): absolute positions, the ground's displacement.

    Returns
    -------
    ndarray, shape (nt,)
        d at each sample, m (positive in the first mechanism's sense).
    """
    mech = curve.mechanism
    if not isinstance(mech, FourHingeMechanism):
        raise InvalidParameterError("the time-history route reads an arch's four-hinge mechanism")
    arch = mech.prepared.mechanism.arch
    idx = _FIRST_VOUSSOIR + mech.voussoirs
    pos = result.positions[:, idx, :]  # (nt, N, 3): x, y, rotation (absolute)
    ground = result.base_displacement[:, None]
    x0 = arch.voussoir_centroids[mech.voussoirs, 0][None, :]
    masses = mech.masses
    if curve.control is None:
        dc = (pos[:, :, 0] - ground - x0) @ masses / masses.sum()
    else:
        k = curve.control.block
        r0 = curve.control.point - arch.voussoir_centroids[mech.voussoirs[k]]
        th = pos[:, k, 2]
        x = pos[:, k, 0] + np.cos(th) * r0[0] - np.sin(th) * r0[1]
        dc = x - result.base_displacement - curve.control.point[0]
    s1 = float(masses @ curve.virtual_dx)
    s2 = float(masses @ curve.virtual_dx**2)
    return dc * s2 / (curve.control_dx * s1)


def _default_run(arch, motion):
    """The rigid chain run to a verdict at its recorded step (`archquake.models.run`, the
    stepper's default 1e-4 s: the route reads the voussoirs' positions)."""
    from archquake import models
    from archquake.rigid.model import DEFAULT_TIME_STEP

    options = models.RunOptions(time_step=DEFAULT_TIME_STEP)
    return models.run(models.Model.RIGID, arch, motion, options=options)


def time_history_check(curve: CapacityCurve, records: Sequence, limit_state: str = "SLV", *,
                       run: Callable | None = None) -> TimeHistoryCheck:
    """Check a limit state by time histories of the rigid chain (C8.7.1.2.1.9).

    Parameters
    ----------
    curve : CapacityCurve
        The arch's four-hinge mechanism's (`capacity_curve`).
    records : sequence of GroundMotion
        At least `MIN_RECORDS` ground motions (m/s^2), already selected and scaled to be
        compatible with the site's spectrum at ``limit_state``.
    limit_state : {'SLV', 'SLC'}
    run : callable, optional
        ``run(arch, motion) -> BlockResult``; default the rigid chain to a verdict.

    Returns
    -------
    TimeHistoryCheck
    """
    if limit_state not in NONLINEAR:
        raise InvalidParameterError(f"limit state must be SLV or SLC, got {limit_state!r}")
    if len(records) < MIN_RECORDS:
        raise InvalidParameterError(
            f"the time-history route needs at least {MIN_RECORDS} records, got {len(records)}")
    mech = curve.mechanism
    if not isinstance(mech, FourHingeMechanism):
        raise InvalidParameterError("the time-history route reads an arch's four-hinge mechanism")
    arch = mech.prepared.mechanism.arch
    run = _default_run if run is None else run
    responses = []
    for i, motion in enumerate(records):
        result = run(arch, motion)
        outcome = str(getattr(result.outcome, "value", result.outcome))
        peak = math.inf if outcome == "collapse" else float(
            np.max(np.abs(chain_displacement(curve, result))))
        name = getattr(motion, "name", None) or f"record {i + 1}"
        responses.append(RecordResponse(str(name), peak, outcome))
    d_limit = NONLINEAR[limit_state].fraction_of_d0 * curve.d0_m
    return TimeHistoryCheck(limit_state, d_limit, curve.d0_m, tuple(responses))


@dataclass(frozen=True)
class TimeHistoryCapacity:
    """The capacity a_g of the time-history route: the least a_g (records scaled with it) at
    which the check of C8.7.1.2.1.9 fails, found by bracketing and bisection.

    Attributes
    ----------
    limit_state : {'SLV', 'SLC'}
    capacity_ag_g : float
        g (the midpoint of the last bracket).
    bracket_g : (float, float)
        The last a_g that passed and the first that failed, g.
    levels : tuple of TimeHistoryCheck
        Every level run, with its a_g in ``ag_g``.
    ag_g : tuple of float
        The a_g of each level, g.
    """

    limit_state: str
    capacity_ag_g: float
    bracket_g: tuple[float, float]
    levels: tuple[TimeHistoryCheck, ...]
    ag_g: tuple[float, ...]

    def to_dict(self) -> dict:
        return {"limit_state": self.limit_state, "capacity_ag_g": self.capacity_ag_g,
                "bracket_g": list(self.bracket_g),
                "levels": [dict(c.to_dict(), ag_g=a) for c, a in zip(self.levels, self.ag_g)]}


def time_history_capacity(curve: CapacityCurve, records: Sequence, site_ag_g: float,
                          start_ag_g: float, limit_state: str = "SLV", *,
                          bisections: int = 3, growth: float = 1.5, max_ag_g: float = 5.0,
                          run: Callable | None = None,
                          progress: Callable[[str], None] | None = None) -> TimeHistoryCapacity:
    """The least a_g at which the time-history check fails, the records scaled in proportion.

    Parameters
    ----------
    curve : CapacityCurve
    records : sequence of GroundMotion
        Selected and scaled to the site's spectrum at ``site_ag_g``.
    site_ag_g : float
        The a_g the records are scaled to, g.
    start_ag_g : float
        First a_g tried (e.g. the static route's capacity), g.
    limit_state : {'SLV', 'SLC'}
    bisections : int
        Halvings of the bracket once found (the capacity is then known to within
        (growth - 1) / 2^bisections of itself).
    growth : float
        Factor between the levels while bracketing.
    max_ag_g : float
        Highest a_g tried, g (the capacity is reported as inf beyond it).
    run, progress : callable, optional
        As in `time_history_check`; ``progress`` is told each level's verdict.
    """
    levels: list[TimeHistoryCheck] = []
    ags: list[float] = []

    def check(ag: float) -> bool:
        scaled = [m.scaled(ag / site_ag_g) for m in records]
        res = time_history_check(curve, scaled, limit_state, run=run)
        levels.append(res)
        ags.append(ag)
        if progress:
            progress(f"a_g {ag:.4f} g: {res.verdict()}")
        return res.passes

    lo, hi = 0.0, float(start_ag_g)
    if check(hi):
        lo = hi
        hi = lo * growth
        while hi <= max_ag_g and check(hi):
            lo, hi = hi, hi * growth
        if hi > max_ag_g:
            return TimeHistoryCapacity(limit_state, math.inf, (lo, math.inf), tuple(levels),
                                       tuple(ags))
    else:
        hi_fail = hi
        lo = hi / growth
        while not check(lo):
            hi_fail, lo = lo, lo / growth
            if lo < 1e-3 * start_ag_g:
                return TimeHistoryCapacity(limit_state, 0.0, (0.0, hi_fail), tuple(levels),
                                           tuple(ags))
        hi = hi_fail
    for _ in range(bisections):
        mid = 0.5 * (lo + hi)
        if check(mid):
            lo = mid
        else:
            hi = mid
    return TimeHistoryCapacity(limit_state, 0.5 * (lo + hi), (lo, hi), tuple(levels), tuple(ags))


@dataclass(frozen=True)
class TimeHistoryRoute:
    """The time-history route of one limit state beside the static one: the records chosen
    from a suite to match the site's spectrum, their scale factors, and the capacity a_g they
    give (`time_history_route`).

    Attributes
    ----------
    limit_state : {'SLV', 'SLC'}
    records : tuple of str
        The chosen records' names.
    scale_factors : tuple of float
        Each record's factor to the site's spectrum at ``site_ag_g``.
    compatible : bool
        Whether the set's mean spectrum meets the code's band (NTC 2018 §3.2.3.6: -10 % / +30 %
        of the target over the periods checked).
    periods_s : (float, float)
        The band's periods, s.
    site_ag_g : float
        The site's a_g at the limit state, g.
    static_capacity_ag_g : float
        The static route's capacity a_g, g (where the bracketing starts).
    capacity : TimeHistoryCapacity
    """

    limit_state: str
    records: tuple[str, ...]
    scale_factors: tuple[float, ...]
    compatible: bool
    periods_s: tuple[float, float]
    site_ag_g: float
    static_capacity_ag_g: float
    capacity: TimeHistoryCapacity

    @property
    def ratio(self) -> float:
        """capacity a_g / site a_g (>= 1 passes)."""
        return self.capacity.capacity_ag_g / self.site_ag_g

    @property
    def passes(self) -> bool:
        return self.ratio >= 1.0

    def verdict(self) -> str:
        lo, hi = self.capacity.bracket_g
        return (f"{self.limit_state} (time histories, {len(self.records)} records): capacity a_g "
                f"{self.capacity.capacity_ag_g:.4f} g (between {lo:.4f} and {hi:.4f} g), site "
                f"{self.site_ag_g:.4f} g, ratio {self.ratio:.3f}: "
                f"{'passes' if self.passes else 'FAILS'} (static route "
                f"{self.static_capacity_ag_g:.4f} g)")

    def to_dict(self) -> dict:
        return {"limit_state": self.limit_state, "records": list(self.records),
                "scale_factors": list(self.scale_factors), "compatible": self.compatible,
                "periods_s": list(self.periods_s), "site_ag_g": self.site_ag_g,
                "static_capacity_ag_g": self.static_capacity_ag_g,
                "capacity_ag_g": self.capacity.capacity_ag_g, "ratio": self.ratio,
                "passes": self.passes, "capacity": self.capacity.to_dict()}


def time_history_route(curve: CapacityCurve, spectrum, suite: Sequence, limit_state: str,
                       static_capacity_ag_g: float, period_s: float, *,
                       count: int = MIN_RECORDS, bisections: int = 2,
                       trim: Callable | None = None, run: Callable | None = None,
                       progress: Callable[[str], None] | None = None) -> TimeHistoryRoute:
    """The time-history route of C8.7.1.2.1.9 for one limit state, from a suite of records.

    ``count`` records of ``suite`` are chosen and scaled so that their mean spectrum meets the
    NTC band around ``spectrum`` (`archquake.ground.selection.select_records`, over
    0.1 s to 1.2 ``period_s``, the limit state's period T_SLV or T_SLC of the static route),
    then scaled together with a_g until the check of `time_history_check` fails
    (`time_history_capacity`, starting at the static route's capacity).

    Parameters
    ----------
    curve : CapacityCurve
    spectrum : ElasticSpectrum
        The site's spectrum at ``limit_state``.
    suite : sequence of Record
        The candidates (e.g. a FEMA P695 set).
    limit_state : {'SLV', 'SLC'}
    static_capacity_ag_g : float
        The static route's capacity a_g, g.
    period_s : float
        The static route's period of the limit state, s.
    count : int
        Records in the set (at least `MIN_RECORDS`).
    bisections : int
        As `time_history_capacity`.
    trim : callable, optional
        ``trim(record) -> record`` applied to each chosen record before it is scaled (e.g. its
        strong part, to save time).
    run, progress : callable, optional
        As `time_history_capacity`.

    Returns
    -------
    TimeHistoryRoute
    """
    from archquake.ground.response_spectra import record_spectra
    from archquake.ground.selection import select_records

    if limit_state not in NONLINEAR:
        raise InvalidParameterError(f"limit state must be SLV or SLC, got {limit_state!r}")
    records = list(suite)
    if len(records) < count:
        raise InvalidParameterError(
            f"the time-history route chooses {count} records, the suite has {len(records)}")
    band = (0.1, 1.2 * float(period_s))
    periods = np.geomspace(band[0], max(band[1], 2.0 * band[0]), 25)
    sel = select_records(record_spectra(records, periods), lambda t: spectrum.sa(t),
                         count=count)
    chosen = []
    for i, f in zip(sel.indices, sel.scale_factors, strict=True):
        rec = records[int(i)] if trim is None else trim(records[int(i)])
        chosen.append(rec.scaled(float(f)))
    site_ag = spectrum.ag / spectrum.g
    cap = time_history_capacity(curve, chosen, site_ag, static_capacity_ag_g, limit_state,
                                bisections=bisections, run=run, progress=progress)
    return TimeHistoryRoute(limit_state, tuple(records[int(i)].name for i in sel.indices),
                            tuple(float(f) for f in sel.scale_factors), bool(sel.compatible),
                            band, float(site_ag), float(static_capacity_ag_g), cap)


__all__ = ["MIN_RECORDS", "RecordResponse", "TimeHistoryCapacity", "TimeHistoryCheck",
           "TimeHistoryRoute", "chain_displacement", "time_history_capacity",
           "time_history_check", "time_history_route"]
