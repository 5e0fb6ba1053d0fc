"""Failure domains: which pulse magnitudes and durations collapse the arch (paper Figures 5-7, 11).

For each duration (t_p of the step impulse, period T of the sine pulse) the search finds

* the no-hinging limit: the static collapse multiplier lambda (in g) of the mechanism. Both
  pulses reach their magnitude a in the direction that opens the first mechanism (the step's
  first lobe, the sine's first peak) and never exceed it, so the arch hinges exactly when
  a > lambda g, whatever the duration (a test checks this with single runs);
* ``first_half_cycle_g``: the smallest magnitude that collapses the arch in the first half cycle
  (Oppenheim's boundary);
* ``collapse_g``: the smallest magnitude that collapses it at all (the governing boundary; the
  paper finds it in the second half cycle for the step impulse).

Search
------
Collapse need not be monotonic in the magnitude, so nothing assumes it:

1. a coarse scan, geometric from lambda with the ratio ``(scan_reference_g / lambda) ** (1 /
   coarse_points)`` (``coarse_points`` magnitudes up to ``scan_reference_g``, 5 g by default),
   continued with the same ratio up to ``max_magnitude_g`` and closed by the ceiling itself, for
   every duration. The grid is anchored at lambda and its spacing does not depend on the ceiling,
   so a band below both of two ceilings is scanned at the same magnitudes, and found or missed
   alike, whatever the ceiling; doubling ``coarse_points`` only adds magnitudes between the
   previous ones;
2. a fine scan of ``fine_points`` magnitudes, uniform between the coarse brackets of the two
   boundaries (the second-half-cycle region, where the arch's response is least regular);
3. on the merged scan, each boundary is bracketed by its first collapsing magnitude and the
   magnitude below it, and every run of non-collapsing magnitudes above a collapsing one is a
   non-monotonic band; all brackets (boundaries and band edges, all durations) are then bisected
   together, one compiled batch call per round, to ``precision_g``.

Bands narrower than the scan's spacing can be missed (the coarse ratio is 1.044 by default for
Oppenheim's arch, lambda = 0.370 g: a band narrower than about 4 % of its magnitude may fall
between two scanned magnitudes), and a bracket hides any transition inside it: the result
states the scan it used. The fine scan spans the two boundaries' coarse brackets; when no
first-half-cycle collapse is found below the ceiling it reaches up to the ceiling, and only then
does the ceiling move its points.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from archquake import models
from archquake._validate import (
    require_array,
    require_gravity,
    require_instance,
    require_int,
    require_positive,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.ground.pulses import PulseFamily
from archquake.mechanism.impact import check_restitution
from archquake.mechanism.kinematics import G0, H0
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import SolverOptions
from archquake.outcome import Outcome

from .batch import PulseOutcomes, check_durations, evaluate_pulses

#: Figure 5's durations t_p, s.
FIGURE5_DURATIONS = tuple(np.linspace(0.05, 1.5, 40).tolist())

#: Finest bracket width relative to the scan's ceiling: a bracket [lo, hi] below the ceiling
#: can be halved while hi - lo exceeds a few ulps of hi (2.2e-16 hi); 1e-12 leaves a margin
#: of 4500 and the integrator's own tolerance (rtol 1e-9) is coarser still.
PRECISION_FLOOR = 1e-12

#: Bisection rounds at most: log2(ceiling / (PRECISION_FLOOR ceiling)) = 40, doubled.
_MAX_ROUNDS = 80

#: What a band or boundary refers to.
COLLAPSE = "collapse"
FIRST_HALF_CYCLE = "first_half_cycle"


@dataclass(frozen=True)
class DomainSettings:
    """How the domain is searched.

    Parameters
    ----------
    max_magnitude_g : float
        Ceiling of the scan, g; a boundary above it is reported as NaN.
    coarse_points : int
        Magnitudes of the coarse scan (geometric from lambda to the ceiling).
    fine_points : int
        Magnitudes of the fine scan between the two boundaries' coarse brackets.
    scan_reference_g : float
        Magnitude, g, reached by the ``coarse_points``-th magnitude of the coarse scan: it sets
        the scan's ratio (its spacing), independently of the ceiling (if it is not above
        lambda, twice lambda is used).
    precision_g : float
        Width of the final brackets, g; at least `PRECISION_FLOOR` times the ceiling
        (finer brackets cannot be halved in double precision).
    early : bool
        Let the batch stop surviving runs once energy proves they cannot collapse (see
        `archquake.domains._kernels`).
    options : SolverOptions
        Integrator settings of every run (history is never recorded).
    """

    max_magnitude_g: float = 5.0
    coarse_points: int = 60
    fine_points: int = 40
    precision_g: float = 1e-3
    early: bool = True
    options: SolverOptions = SolverOptions()
    scan_reference_g: float = 5.0

    def __post_init__(self) -> None:
        require_positive("max_magnitude_g", self.max_magnitude_g, "g")
        require_int("coarse_points", self.coarse_points, 2)
        require_int("fine_points", self.fine_points, 0)
        require_positive("precision_g", self.precision_g, "g")
        require_positive("scan_reference_g", self.scan_reference_g, "g")
        floor = PRECISION_FLOOR * self.max_magnitude_g
        if self.precision_g < floor:
            raise InvalidParameterError(
                f"precision_g must be >= {floor:.3g} g ({PRECISION_FLOOR:g} times the ceiling "
                f"max_magnitude_g = {self.max_magnitude_g:g} g: double precision cannot resolve "
                f"a finer bracket), got {self.precision_g:g}")

    def to_dict(self) -> dict:
        o = self.options
        return {"max_magnitude_g": self.max_magnitude_g, "coarse_points": self.coarse_points,
                "fine_points": self.fine_points, "precision_g": self.precision_g,
                "scan_reference_g": self.scan_reference_g,
                "early": self.early, "rtol": o.rtol, "atol": o.atol,
                "rest_rotation": o.rest_rotation, "max_impacts": o.max_impacts}


@dataclass(frozen=True)
class NonMonotonicBand:
    """Magnitudes in [lower_g, upper_g] at which the arch does NOT do what it does just below
    ``lower_g`` (``criterion``: ``collapse`` = collapse at all, ``first_half_cycle`` = collapse
    in the first half cycle), although a smaller magnitude does.

    ``lower_g`` and ``upper_g`` are the extreme magnitudes found without it (within the
    precision of the search); ``upper_open`` is True when the band reaches the scan's ceiling.
    """

    duration: float
    criterion: str
    lower_g: float
    upper_g: float
    upper_open: bool = False

    def to_dict(self) -> dict:
        return {"duration_s": self.duration, "criterion": self.criterion, "lower_g": self.lower_g,
                "upper_g": self.upper_g, "upper_open": self.upper_open}


@dataclass(frozen=True)
class FailureDomain:
    """The failure domain of an arch for a pulse family, shape (n,) arrays over ``durations``.

    Attributes
    ----------
    arch : Arch
    family : PulseFamily
    durations : ndarray, s
        t_p (step impulse) or T (sine pulse).
    no_hinging_g : ndarray, g
        Below it the arch moves rigidly with the ground.
    first_half_cycle_g : ndarray, g
        Smallest magnitude found to collapse the arch in the first half cycle (NaN if none up
        to the ceiling).
    collapse_g : ndarray, g
        Smallest magnitude found to collapse it at all (NaN if none): the governing boundary.
    first_half_cycle_below_g, collapse_below_g : ndarray, g
        The magnitude just below each boundary (within ``precision_g``) that was run and does
        not do so (lambda if the boundary's bracket starts there; NaN if no boundary).
    collapse_half_cycle : ndarray of int
        Half cycle in which ``collapse_g`` collapses the arch (0 where none).
    non_monotonic_bands : tuple of NonMonotonicBand
    restitution_cv : float
        c_v of the impact law, or the prescribed one (> 1 means the law creates energy: see
        ``energy_gain``).
    energy_gain : bool
    mechanism : dict
        The hinges (joints, faces, symmetric).
    settings : DomainSettings
    evaluations : int
        Time histories run by the search.
    g : float
        Gravity, m/s^2.
    impact_law : str
        The impact law (`archquake.mechanism.impact.IMPACT_LAWS`).
    impact_validity : str
        Its validity (`ImpactSolution`).
    impact_described : bool
        True if the law (with the prescribed c_v, if any) describes this arch's impacts (every
        row of its mechanism table, `PreparedMechanism.table`: a boundary may come from
        any of them). If False, every verdict reached after an impact is indeterminate
        (`archquake.outcome.qualify`): lambda and the first-half-cycle boundary stand, and
        ``collapse_g`` where it collapses after an impact is the law's computed boundary, not a
        certain one (`collapse_verdict`).
    restitution_prescribed : bool
        True if ``restitution_cv`` was prescribed.
    """

    arch: VoussoirChain
    family: PulseFamily
    durations: np.ndarray
    no_hinging_g: np.ndarray
    first_half_cycle_g: np.ndarray
    collapse_g: np.ndarray
    first_half_cycle_below_g: np.ndarray
    collapse_below_g: np.ndarray
    collapse_half_cycle: np.ndarray
    non_monotonic_bands: tuple[NonMonotonicBand, ...]
    restitution_cv: float
    energy_gain: bool
    mechanism: dict = field(repr=False)
    settings: DomainSettings = field(repr=False, default=DomainSettings())
    evaluations: int = 0
    g: float = STANDARD_GRAVITY
    impact_law: str = "paper"
    impact_validity: str = "assumed"
    impact_described: bool = True
    restitution_prescribed: bool = False

    @property
    def collapse_verdict(self) -> tuple[str | None, ...]:
        """Per duration: ``"collapse"`` where ``collapse_g`` is a certain collapse (in the first
        half cycle, or the law describes the impacts), ``"indeterminate"`` where it collapses
        only after an impact the law does not describe, None where no collapse was found."""
        out: list[str | None] = []
        for g_c, half in zip(self.collapse_g, self.collapse_half_cycle):
            if not math.isfinite(g_c):
                out.append(None)
            elif self.impact_described or int(half) == 1:
                out.append(Outcome.COLLAPSE.value)
            else:
                out.append(Outcome.INDETERMINATE.value)
        return tuple(out)

    def bands_at(self, duration: float) -> list[NonMonotonicBand]:
        return [b for b in self.non_monotonic_bands if b.duration == duration]

    def to_dict(self) -> list[dict]:
        """One object per duration: ``duration_s``, ``no_hinging_g``, ``first_half_cycle_g``,
        ``collapse_g`` (g, None where none) and ``non_monotonic_bands`` there."""
        out = []
        for i, d in enumerate(self.durations):
            out.append({
                "duration_s": float(d),
                "no_hinging_g": _num(self.no_hinging_g[i]),
                "first_half_cycle_g": _num(self.first_half_cycle_g[i]),
                "collapse_g": _num(self.collapse_g[i]),
                "collapse_half_cycle": int(self.collapse_half_cycle[i]) or None,
                "collapse_verdict": self.collapse_verdict[i],
                "impact_law": self.impact_law,
                "impact_validity": self.impact_validity,
                "non_monotonic_bands": [
                    {k: v for k, v in b.to_dict().items() if k != "duration_s"}
                    for b in self.bands_at(float(d))
                ],
            })
        return out

    def summary(self) -> dict:
        """What was analysed and how: arch, pulse family, mechanism, c_v, settings."""
        return {"arch": self.arch.describe(), "pulse": self.family.value,
                "duration_symbol": self.family.duration_symbol,
                "restitution_cv": self.restitution_cv,
                "restitution_prescribed": self.restitution_prescribed,
                "energy_gain": self.energy_gain, "impact_law": self.impact_law,
                "impact_validity": self.impact_validity,
                "impact_described": self.impact_described, "mechanism": self.mechanism,
                "settings": self.settings.to_dict(), "evaluations": self.evaluations,
                "g_m_s2": self.g}

    def write_csv(self, path: str | Path) -> Path:
        """Write one row per duration; bands as ``criterion:lower-upper`` separated by ``;``."""
        path = Path(path)
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["duration_s", "no_hinging_g", "first_half_cycle_g", "collapse_g",
                        "collapse_half_cycle", "non_monotonic_bands"])
            for row in self.to_dict():
                bands = ";".join(f"{b['criterion']}:{b['lower_g']:.4f}-{b['upper_g']:.4f}"
                                 for b in row["non_monotonic_bands"])
                w.writerow([f"{row['duration_s']:.6g}"] + [
                    "" if row[k] is None else f"{row[k]:.4f}"
                    for k in ("no_hinging_g", "first_half_cycle_g", "collapse_g")
                ] + [row["collapse_half_cycle"] or "", bands])
        return path


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


# ----------------------------------------------------------------------------- the search
@dataclass
class _Bracket:
    """A transition of ``criterion`` at ``duration`` between lo (value v_lo) and hi."""

    index: int  # duration index
    criterion: str
    lo: float
    hi: float
    v_lo: bool
    role: str  # "boundary", "band_lower", "band_upper"


#: Most magnitudes the coarse scan may hold (per duration).
MAX_SCAN_POINTS = 10_000


def coarse_scan(lam: float, ceiling: float, points: int, reference: float) -> np.ndarray:
    """The coarse scan's magnitudes, g: ``lam * (ref / lam) ** (k / points)`` for k = 1, 2, ...
    up to ``ceiling``, then ``ceiling`` itself if it is not on the grid (``ref`` = ``reference``,
    or 2 lam if ``reference`` is not above lambda). Anchored at lambda, with a ratio independent of
    the ceiling."""
    ref = reference if reference > lam else 2.0 * lam
    n = int(math.floor(points * math.log(ceiling / lam) / math.log(ref / lam) + 1e-9))
    if n > MAX_SCAN_POINTS:
        raise InvalidParameterError(
            f"max_magnitude_g = {ceiling:g} g would take {n} scanned magnitudes (more than "
            f"{MAX_SCAN_POINTS}) at the scan's spacing: lower it, or raise scan_reference_g")
    k = np.arange(1, n + 1)
    grid = lam * (ref / lam) ** (k / points)
    grid = grid[grid <= ceiling * (1.0 + 1e-12)]  # the reference itself, within rounding
    if grid.size == 0 or grid[-1] < ceiling * (1.0 - 1e-12):
        grid = np.append(grid, ceiling)
    return grid


def _predicate(res, criterion: str) -> np.ndarray:
    return res.collapses_first if criterion == FIRST_HALF_CYCLE else res.collapses


def _rigid_evaluator(arch, family, restitution, impact, g: float, threads: int | None):
    """The rigid chain's outcomes for `failure_domain` (``model='rigid'``)."""
    from archquake.blocks.assembly import VOUSSOIRS, dem_assembly
    from archquake.dem.settings import DemSettings
    from archquake.domains.blocks import DOMAIN_TAIL, DemPulseEvaluator

    for name, value in (("restitution", restitution), ("impact", impact)):
        if value is not None:
            raise InvalidParameterError(f"{name} applies to model fourlink only; the rigid "
                                        "chain's impacts follow from its contacts")
    if not isinstance(arch, VoussoirChain):
        raise InvalidParameterError("model 'rigid' needs an Arch; a PreparedMechanism is the "
                                    "four-link model's (model='fourlink')")
    require_positive("g", g, "m/s^2")
    return DemPulseEvaluator(dem_assembly(arch, VOUSSOIRS), PulseFamily.parse(family),
                             DemSettings(), DOMAIN_TAIL * math.sqrt(arch.radius / g), g=g,
                             model="rigid", threads=threads)


def failure_domain(
    arch: Arch | PreparedMechanism,
    family: PulseFamily | str = PulseFamily.STEP,
    durations=None,
    *,
    settings: DomainSettings | None = None,
    restitution: float | None = None,
    impact: str | None = None,
    g: float = STANDARD_GRAVITY,
    evaluate: Callable[[np.ndarray, np.ndarray], PulseOutcomes] | None = None,
    model: str | None = None,
    threads: int | None = None,
    loads=None,
) -> FailureDomain:
    """Failure domain of an arch for a pulse family (paper Figures 5, 6, 7, 11).

    Parameters
    ----------
    arch : Arch or PreparedMechanism
        The arch (hinges from the equivalent static analysis, as in the paper).
    family : PulseFamily or {'step', 'sine'}
    durations : array_like, (n,), s
        t_p for the step impulse, T for the sine pulse (default: 40 from 0.05 to 1.5 s, Figure 5).
    settings : DomainSettings
    restitution : float, optional
        Prescribed c_v in [0, 1] (0: perfectly plastic); None: the impact law's.
    impact : {"paper", "chain", "mirror"}, optional
        Impact law (`archquake.mechanism.impact`); None: a PreparedMechanism's own, else
        "paper".
    g : float
        Gravity, m/s^2.
    evaluate : callable, optional
        ``evaluate(magnitudes_g, durations) -> PulseOutcomes`` for 1-D arrays of equal length:
        another model's outcomes plugged into the same search (e.g. the distinct-element model,
        `archquake.compare.dem_failure_domain`). Default: the compiled four-link batch
        `evaluate_pulses` (``settings.options``, ``settings.early``).
        lambda (the scan's start) is always the four-link mechanism's.
    model : {'rigid', 'fourlink'}, optional
        The model whose outcomes are searched when ``evaluate`` is not given. ``'rigid'`` (the
        default for an Arch): the chain of rigid voussoirs, every voussoir a block, each pulse
        run for itself plus `DOMAIN_TAIL` sqrt(R/g) as
        threaded batches of guarded verdicts (`archquake.rigid.rigid_verdicts`; its
        impacts follow from the contacts: no ``restitution`` or ``impact``). ``'fourlink'``
        (the default for a PreparedMechanism): the paper's four-link mechanism, the compiled
        batch `evaluate_pulses`.
    threads : int, optional
        With ``model='rigid'``: threads of each batch (default: the usable cores).
    loads : Loads, optional
        What the arch carries, for another model's ``evaluate`` whose blocks carry them
        (`archquake.compare.dem_failure_domain`): lambda, the scan's start, is then the
        static analysis's with the loads (`archquake.limit.loaded`).

    Returns
    -------
    FailureDomain

    Examples
    --------
    Oppenheim's arch, step impulse of t_p = 0.44 s (paper Figure 4b: 1.0 g collapses it in the
    first half cycle):

    >>> import math
    >>> from archquake import Arch
    >>> d = failure_domain(Arch(10, 1.5, math.radians(157.5), 7), "step", [0.44],
    ...                    settings=DomainSettings(coarse_points=30, fine_points=10),
    ...                    model="fourlink")
    >>> lam, first, governing = d.no_hinging_g[0], d.first_half_cycle_g[0], d.collapse_g[0]
    >>> bool(lam < governing < first < 1.0), int(d.collapse_half_cycle[0])
    (True, 2)
    """
    settings = DomainSettings() if settings is None else settings
    require_instance("settings", settings, DomainSettings, "a DomainSettings (or None)")
    if model is None:
        model = "fourlink" if isinstance(arch, PreparedMechanism) else "rigid"
    word = str(getattr(model, "value", model))
    try:
        spec = models.spec(word)
    except InvalidParameterError:
        spec = None
    if spec is None or not spec.batched:  # the models whose domains run in compiled batches
        raise InvalidParameterError(f"model must be 'rigid' or 'fourlink', got {word!r}")
    model = spec.model.value
    loaded = loads is not None and not loads.empty
    if loaded and (evaluate is None or not isinstance(arch, VoussoirChain)):
        raise InvalidParameterError("a domain with loads needs the block models' evaluation of "
                                    "the loaded arch (archquake.compare.dem_failure_domain)")
    if evaluate is None and spec.blocks:
        evaluate = _rigid_evaluator(arch, family, restitution, impact, g, threads)
    if evaluate is not None and isinstance(arch, VoussoirChain):
        # another model's outcomes carry their own impacts: only the hinges and lambda of the
        # equivalent static analysis are read (an asymmetric arch has no four-link impact law)
        from archquake.limit import hinges_of
        from archquake.mechanism.prepared import pack_mechanism

        mech0 = hinges_of(arch)
        packed = pack_mechanism(mech0)
        prepared = None
        cv = math.nan
        lam = float(packed[G0] / abs(packed[H0]))  # PreparedMechanism's lambda
        if loaded:
            from archquake.limit.loaded import loaded_collapse, seismic_case

            collapse = loaded_collapse(seismic_case(arch, loads, g=g))
            lam, mech0 = collapse.multiplier, collapse.mechanism
        radius = mech0.arch.radius
    else:
        prepared = PreparedMechanism.build(arch, impact)
        cv = prepared.restitution_for(restitution)
        lam = prepared.collapse_acceleration_g
        mech0 = prepared.mechanism
        radius = mech0.arch.radius
    fam = PulseFamily.parse(family)
    require_gravity(g)
    if durations is None:
        durations = FIGURE5_DURATIONS
    dur = require_array("durations", durations, "s", minimum=0.0, exclusive=True)
    check_durations(fam, dur, radius, g)
    ceiling = settings.max_magnitude_g
    if ceiling <= lam:
        raise InvalidParameterError(
            f"max_magnitude_g must exceed the no-hinging limit lambda = {lam:.4f} g, got {ceiling:g}")
    nd = dur.size
    evaluations = 0

    def run(mags: np.ndarray, idx: np.ndarray):
        nonlocal evaluations
        evaluations += mags.size
        if evaluate is not None:
            return evaluate(mags, dur[idx])
        assert prepared is not None  # built whenever no other model evaluates
        return evaluate_pulses(prepared, fam, mags, dur[idx], restitution=restitution,
                               options=settings.options, early=settings.early, g=g)

    # 1. coarse scan ------------------------------------------------------------------------
    coarse = coarse_scan(lam, ceiling, settings.coarse_points, settings.scan_reference_g)
    grid = [coarse.copy() for _ in range(nd)]
    idx = np.repeat(np.arange(nd), coarse.size)
    res = run(np.tile(coarse, nd), idx)
    col = res.collapses.reshape(nd, -1)
    first = res.collapses_first.reshape(nd, -1)
    values = {COLLAPSE: [col[i].copy() for i in range(nd)],
              FIRST_HALF_CYCLE: [first[i].copy() for i in range(nd)]}

    # 2. fine scan between the boundaries' coarse brackets -----------------------------------
    if settings.fine_points > 0:
        fine_m, fine_i = [], []
        for i in range(nd):
            jc = np.flatnonzero(col[i])
            if jc.size == 0:
                continue
            lo = coarse[jc[0] - 1] if jc[0] > 0 else lam
            jf = np.flatnonzero(first[i])
            hi = coarse[jf[0]] if jf.size else ceiling
            pts = np.linspace(lo, hi, settings.fine_points + 2)[1:-1]
            fine_m.append(pts)
            fine_i.append(np.full(pts.size, i))
        if fine_m:
            fm, fi = np.concatenate(fine_m), np.concatenate(fine_i)
            fres = run(fm, fi)
            for i in np.unique(fi):
                sel = fi == i
                mags = np.concatenate([grid[i], fm[sel]])
                order = np.argsort(mags, kind="stable")
                grid[i] = mags[order]
                for crit in (COLLAPSE, FIRST_HALF_CYCLE):
                    v = np.concatenate([values[crit][i], _predicate(fres, crit)[sel]])
                    values[crit][i] = v[order]

    # 3. brackets on the merged scans, bisected together --------------------------------------
    brackets: list[_Bracket] = []
    for i in range(nd):
        mags = grid[i]
        for crit in (COLLAPSE, FIRST_HALF_CYCLE):
            v = values[crit][i]
            hits = np.flatnonzero(v)
            if hits.size == 0:
                continue
            j0 = hits[0]
            brackets.append(_Bracket(i, crit, mags[j0 - 1] if j0 > 0 else lam, mags[j0], False,
                                     "boundary"))
            for j in range(j0 + 1, mags.size):
                if v[j - 1] and not v[j]:
                    brackets.append(_Bracket(i, crit, mags[j - 1], mags[j], True, "band_lower"))
                if not v[j - 1] and v[j]:
                    brackets.append(_Bracket(i, crit, mags[j - 1], mags[j], False, "band_upper"))
            if not v[-1]:
                # the band reaches the ceiling: a degenerate bracket marks its open top
                brackets.append(_Bracket(i, crit, mags[-1], math.inf, False, "band_upper"))
    for _ in range(_MAX_ROUNDS):
        live = [b for b in brackets if math.isfinite(b.hi) and b.hi - b.lo > settings.precision_g
                and b.lo < 0.5 * (b.lo + b.hi) < b.hi]
        if not live:
            break
        mids = np.array([0.5 * (b.lo + b.hi) for b in live])
        r = run(mids, np.array([b.index for b in live]))
        for n, b in enumerate(live):
            hit = bool(_predicate(r, b.criterion)[n])
            if hit == b.v_lo:
                b.lo = mids[n]
            else:
                b.hi = mids[n]

    # 4. pack the result ---------------------------------------------------------------------
    nan = np.full(nd, np.nan)
    out = {COLLAPSE: (nan.copy(), nan.copy()), FIRST_HALF_CYCLE: (nan.copy(), nan.copy())}
    bands: list[NonMonotonicBand] = []
    for crit in (COLLAPSE, FIRST_HALF_CYCLE):
        for i in range(nd):
            mine = [b for b in brackets if b.index == i and b.criterion == crit]
            for b in mine:
                if b.role == "boundary":
                    out[crit][0][i] = b.hi
                    out[crit][1][i] = b.lo
            lowers = [b for b in mine if b.role == "band_lower"]
            uppers = [b for b in mine if b.role == "band_upper"]
            for lower, upper in zip(lowers, uppers):
                open_top = not math.isfinite(upper.hi)
                bands.append(NonMonotonicBand(float(dur[i]), crit, float(lower.hi),
                                              float(upper.lo), open_top))
    collapse_g, collapse_below = out[COLLAPSE]
    first_g, first_below = out[FIRST_HALF_CYCLE]
    half = np.zeros(nd, dtype=int)
    ok = np.isfinite(collapse_g)
    if ok.any():
        half[ok] = run(collapse_g[ok], np.flatnonzero(ok)).collapse_half_cycle
    bands.sort(key=lambda b: (b.criterion, b.duration, b.lower_g))
    mech = mech0
    if prepared is None:  # another model's impacts: no restitution, no law
        return FailureDomain(
            arch=mech.arch, family=fam, durations=dur.copy(), no_hinging_g=np.full(nd, lam),
            first_half_cycle_g=first_g, collapse_g=collapse_g,
            first_half_cycle_below_g=first_below, collapse_below_g=collapse_below,
            collapse_half_cycle=half, non_monotonic_bands=tuple(bands), restitution_cv=math.nan,
            energy_gain=False,
            mechanism={"joints": list(mech.joints), "faces": [f.value for f in mech.faces],
                       "symmetric": bool(mech.symmetric)},
            settings=settings, evaluations=evaluations, g=g, impact_law="contacts",
            impact_validity="not applicable", impact_described=True,
            restitution_prescribed=False)
    return FailureDomain(
        arch=mech.arch,
        family=fam,
        durations=dur.copy(),
        no_hinging_g=np.full(nd, lam),
        first_half_cycle_g=first_g,
        collapse_g=collapse_g,
        first_half_cycle_below_g=first_below,
        collapse_below_g=collapse_below,
        collapse_half_cycle=half,
        non_monotonic_bands=tuple(bands),
        restitution_cv=float(prepared.impact.restitution_cv if restitution is None else cv),
        energy_gain=bool(prepared.impact.energy_gain and restitution is None),
        mechanism={"joints": list(mech.joints), "faces": [f.value for f in mech.faces],
                   "symmetric": bool(mech.symmetric)},
        settings=settings,
        evaluations=evaluations,
        g=g,
        impact_law=prepared.impact.law,
        impact_validity=prepared.impact.validity,
        # another model's outcomes (the DEM) carry their own impacts; the law's: every impact
        # the arch can have (each row of its table) is described
        impact_described=evaluate is not None or bool(np.all(prepared.table.described(
            prepared.impact.law, check_restitution(restitution)))),
        restitution_prescribed=restitution is not None,
    )


__all__ = ["COLLAPSE", "FIRST_HALF_CYCLE", "DomainSettings", "coarse_scan", "FailureDomain",
           "NonMonotonicBand",
           "failure_domain"]
