"""Collapse fragility: lognormal fits by maximum likelihood, with bootstrap confidence intervals.

A fragility curve is the probability of collapse at intensity x,
``P(C | x) = Phi(ln(x / theta) / beta)`` (median theta, dispersion beta). Two estimators:

(a) **first-collapse intensities** (`fit_first_collapse`): each record's first-collapse
    level x_i is a sample of the capacity, ln x_i ~ N(ln theta, beta^2). The maximum-likelihood
    estimate is ``ln theta = mean(ln x_i)``, ``beta = std(ln x_i)`` (population form, n in the
    denominator). A record that does not collapse the arch up to the ceiling c is right-censored:
    it contributes ``ln(1 - Phi(ln(c / theta) / beta))`` to the log-likelihood, which is then
    maximised numerically (Nelder-Mead on ln theta, ln beta from the uncensored estimate).
(b) **collapse fraction per level** (`fit_collapse_fraction`, Baker 2015, "Efficient
    analytical fragility function fitting using dynamic structural analysis", Earthquake Spectra
    31(1), Eq. 11): at levels x_j, z_j of n_j records collapse; the likelihood is the product of
    binomial probabilities ``C(n_j, z_j) p_j^z_j (1 - p_j)^(n_j - z_j)`` with
    ``p_j = Phi(ln(x_j / theta) / beta)``. Where collapse is not monotonic in the intensity (an
    arch can survive a larger scale of a record that collapsed it), (b) counts what happens at
    each level and (a) only the first collapse, so (b)'s curve lies at or below (a)'s.

Confidence intervals: percentile bootstrap over records (the records are the independent
samples; in (b) a record's outcomes at all levels travel together), with a
`numpy.random.Generator` passed in, so the intervals are reproducible.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import special, stats

from archquake._validate import require_int, require_range
from archquake.errors import InvalidParameterError

#: Bootstrap resamples unless stated.
DEFAULT_BOOTSTRAP = 1000
#: Two-sided confidence of the bootstrap intervals unless stated.
DEFAULT_CONFIDENCE = 0.90


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility ``P(C | x) = Phi(ln(x / median) / beta)``.

    Attributes
    ----------
    median : float
        theta, in the intensity's unit.
    beta : float
        Logarithmic standard deviation (dispersion), dimensionless.
    method : str
        ``"first_collapse"`` or ``"collapse_fraction"``.
    samples : int
        Records used.
    censored : int
        Records without a collapse up to the ceiling (method a).
    median_ci, beta_ci : tuple of float or None
        Percentile-bootstrap interval at ``confidence`` (None without bootstrap).
    confidence : float
    bootstrap : int
        Resamples used (0: none).
    """

    median: float
    beta: float
    method: str
    samples: int
    censored: int = 0
    median_ci: tuple[float, float] | None = None
    beta_ci: tuple[float, float] | None = None
    confidence: float = DEFAULT_CONFIDENCE
    bootstrap: int = 0

    def probability(self, x) -> np.ndarray:
        """P(collapse | intensity x)."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return stats.norm.cdf(np.log(x / self.median) / self.beta)

    def scaled(self, divisor: float) -> LognormalFit:
        """The same fit in the intensity divided by ``divisor`` (beta unchanged)."""
        ci = None if self.median_ci is None else (self.median_ci[0] / divisor,
                                                  self.median_ci[1] / divisor)
        return LognormalFit(self.median / divisor, self.beta, self.method, self.samples,
                            self.censored, ci, self.beta_ci, self.confidence, self.bootstrap)

    def to_dict(self, unit: str) -> dict:
        """JSON form; ``unit`` suffixes the keys of the median (e.g. ``g``, ``m_s``,
        ``dimensionless``)."""
        return {"method": self.method, f"median_{unit}": self.median, "beta": self.beta,
                f"median_ci_{unit}": None if self.median_ci is None else list(self.median_ci),
                "beta_ci": None if self.beta_ci is None else list(self.beta_ci),
                "confidence": self.confidence, "bootstrap": self.bootstrap,
                "records": self.samples, "censored": self.censored}


# ----------------------------------------------------------------------------- the fits
#: log sqrt(2 pi), as scipy.stats.norm's log density subtracts it.
_NORM_LOG_C = float(np.log(np.sqrt(2 * np.pi)))
#: Nelder-Mead's options for both fits (`scipy.optimize.minimize`'s).
NELDER_MEAD = {"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000}


def _nelder_mead_many(nll: Callable[[np.ndarray, np.ndarray], np.ndarray],
                      x0: np.ndarray) -> np.ndarray:
    """``scipy.optimize.minimize(f_i, x0[i], method="Nelder-Mead", options=NELDER_MEAD).x``
    for many problems of two parameters at once, to the bit.

    SciPy's algorithm step for step (its initial simplex, reflection, expansion, the two
    contractions and the shrink, its sort and its stopping test, with the same expressions),
    run on every problem in step: each iteration evaluates the objective of all the problems
    still iterating in one call, so NumPy's cost per call is paid once per iteration rather
    than once per problem (a bootstrap refits the same likelihood a thousand times).
    tests/ida/test_fragility.py holds it to ``scipy.optimize.minimize``.

    Parameters
    ----------
    nll : callable
        ``nll(points, rows)``: the objective of problem ``rows[k]`` at ``points[k]``, (m,)
        from (m, 2) and (m,).
    x0 : ndarray (P, 2)
        The starting points.

    Returns
    -------
    ndarray (P, 2)
        The best vertex of each problem's final simplex.
    """
    xatol, fatol, maxiter = NELDER_MEAD["xatol"], NELDER_MEAD["fatol"], NELDER_MEAD["maxiter"]
    rho, chi, psi, sigma = 1, 2, 0.5, 0.5  # scipy's, not adaptive
    nonzdelt, zdelt = 0.05, 0.00025
    x0 = np.asarray(x0, dtype=float)
    count = x0.shape[0]
    sim = np.empty((count, 3, 2))
    sim[:, 0] = x0
    for k in range(2):
        y = x0.copy()
        nonzero = y[:, k] != 0
        y[nonzero, k] = (1 + nonzdelt) * y[nonzero, k]
        y[~nonzero, k] = zdelt
        sim[:, k + 1] = y
    rows = np.arange(count)
    fsim = np.empty((count, 3))
    for k in range(3):
        fsim[:, k] = nll(sim[:, k], rows)
    _sort_simplices(sim, fsim, rows)
    iterations = 1
    while rows.size and iterations < maxiter:
        s, f = sim[rows], fsim[rows]
        done = ((np.max(np.abs(s[:, 1:] - s[:, :1]).reshape(rows.size, -1), axis=1) <= xatol)
                & (np.max(np.abs(f[:, :1] - f[:, 1:]), axis=1) <= fatol))
        rows, s, f = rows[~done], s[~done], f[~done]
        if not rows.size:
            break
        xbar = np.add.reduce(s[:, :-1], 1) / 2
        worst = s[:, -1]
        xr = (1 + rho) * xbar - rho * worst
        fxr = nll(xr, rows)
        new, fnew = xr.copy(), fxr.copy()
        expand = fxr < f[:, 0]
        if expand.any():
            xe = (1 + rho * chi) * xbar[expand] - rho * chi * worst[expand]
            fxe = nll(xe, rows[expand])
            take = fxe < fxr[expand]
            idx = np.flatnonzero(expand)[take]
            new[idx], fnew[idx] = xe[take], fxe[take]
        rest = ~expand & ~(fxr < f[:, -2])  # neither expanded nor reflected: contract
        shrink = np.zeros(rows.size, dtype=bool)
        outside = rest & (fxr < f[:, -1])
        if outside.any():
            xc = (1 + psi * rho) * xbar[outside] - psi * rho * worst[outside]
            fxc = nll(xc, rows[outside])
            take = fxc <= fxr[outside]
            idx = np.flatnonzero(outside)
            new[idx[take]], fnew[idx[take]] = xc[take], fxc[take]
            shrink[idx[~take]] = True
        inside = rest & ~(fxr < f[:, -1])
        if inside.any():
            xcc = (1 - psi) * xbar[inside] + psi * worst[inside]
            fxcc = nll(xcc, rows[inside])
            take = fxcc < f[inside, -1]
            idx = np.flatnonzero(inside)
            new[idx[take]], fnew[idx[take]] = xcc[take], fxcc[take]
            shrink[idx[~take]] = True
        keep = ~shrink
        s[keep, -1], f[keep, -1] = new[keep], fnew[keep]
        if shrink.any():
            for j in (1, 2):
                s[shrink, j] = s[shrink, 0] + sigma * (s[shrink, j] - s[shrink, 0])
                f[shrink, j] = nll(s[shrink, j], rows[shrink])
        sim[rows], fsim[rows] = s, f
        iterations += 1
        _sort_simplices(sim, fsim, rows)
    return sim[:, 0].copy()


def _sort_simplices(sim: np.ndarray, fsim: np.ndarray, rows: np.ndarray) -> None:
    """Each of the simplices ``rows`` in the order of its values, best first, as
    ``np.argsort`` orders one simplex (in place)."""
    ind = np.argsort(fsim[rows], axis=1)
    sim[rows] = np.take_along_axis(sim[rows], ind[:, :, None], 1)
    fsim[rows] = np.take_along_axis(fsim[rows], ind, 1)


# ----------------------------------------------------------------------------- (a)
#: The first-collapse fits made, by their input (the float64 bytes of the logs of the
#: collapsing levels and of the censoring levels): the same resample of the same records,
#: drawn again by another caller from the same seed (the probability of collapse at the site
#: PGA beside the fragility's own interval), is not fitted twice.
_FIRST_FITS: dict[tuple[bytes, bytes], tuple[float, float]] = {}
_FIRST_FITS_KEPT = 4096
_FIRST_FITS_LOCK = threading.Lock()


def _mle_first(logs: np.ndarray, log_ceilings: np.ndarray) -> tuple[float, float]:
    """(ln theta, beta) maximising the lognormal likelihood of ``logs`` with records censored
    at ``log_ceilings`` (no collapse up to there); each fit made once per input
    (`_mle_first_many`)."""
    return _mle_first_many([(np.asarray(logs, dtype=float), np.asarray(log_ceilings, dtype=float))])[0]


def _mle_first_many(samples: Sequence[tuple[np.ndarray, np.ndarray]]) -> list[tuple[float, float]]:
    """`_mle_first` of each (logs, log ceilings) in ``samples``: a censored sample's maximum
    by Nelder-Mead from the uncensored estimate, the samples of equal sizes in one run of
    `_nelder_mead_many`; each fit kept by its input (`_FIRST_FITS`)."""
    keys = [(lg.tobytes(), lc.tobytes()) for lg, lc in samples]
    fits: dict[tuple[bytes, bytes], tuple[float, float]] = {}
    groups: dict[tuple[int, int], list[int]] = {}
    for i, ((lg, lc), key) in enumerate(zip(samples, keys, strict=True)):
        if key in fits:
            continue
        kept = _FIRST_FITS.get(key)
        if kept is not None:
            fits[key] = kept
        elif lg.size < 2:
            raise InvalidParameterError(f"a lognormal fit needs at least 2 collapses, got {lg.size}")
        elif lc.size == 0:
            fits[key] = (float(np.mean(lg)), float(np.std(lg)))
        else:
            fits[key] = (math.nan, math.nan)  # fitted below, once for equal samples
            groups.setdefault((lg.size, lc.size), []).append(i)
    for (n, _), members in groups.items():
        logs = np.array([samples[i][0] for i in members])
        log_ceilings = np.array([samples[i][1] for i in members])
        x0 = np.array([[float(np.mean(lg)), math.log(max(float(np.std(lg)), 1e-3))]
                       for lg in logs])

        def nll(points: np.ndarray, rows: np.ndarray, logs=logs, log_ceilings=log_ceilings,
                n=n) -> np.ndarray:
            mu = points[:, :1]
            lb = points[:, 1]
            b = np.array([math.exp(v) for v in lb])[:, None]
            z = (logs[rows] - mu) / b
            # log phi(z) and log(1 - Phi(s)) as scipy.stats.norm's logpdf and logsf compute them
            # (the same expressions, the same bits), without their generic wrapper
            return -(np.sum(-z**2 / 2.0 - _NORM_LOG_C, axis=1) - n * lb
                     + np.sum(special.log_ndtr(-((log_ceilings[rows] - mu) / b)), axis=1))

        best = _nelder_mead_many(nll, x0)
        for i, (mu, lb) in zip(members, best, strict=True):
            fits[keys[i]] = (float(mu), float(math.exp(lb)))
    with _FIRST_FITS_LOCK:
        for key, fit in fits.items():
            if key not in _FIRST_FITS:
                if len(_FIRST_FITS) >= _FIRST_FITS_KEPT:
                    del _FIRST_FITS[next(iter(_FIRST_FITS))]  # the oldest
                _FIRST_FITS[key] = fit
    return [fits[key] for key in keys]


def fit_first_collapse(values: Sequence[float], *, ceiling=None,
                       rng: np.random.Generator | None = None,
                       bootstrap: int = DEFAULT_BOOTSTRAP,
                       confidence: float = DEFAULT_CONFIDENCE) -> LognormalFit:
    """Lognormal fit of first-collapse intensities by maximum likelihood (method a).

    Parameters
    ----------
    values : sequence of float
        First-collapse intensity of each record (> 0); NaN for a record that did not collapse
        the arch up to ``ceiling`` (right-censored).
    ceiling : float or array_like, optional
        Level up to which a censored record was run (one for all, or one per record); required
        when any value is NaN.
    rng : numpy.random.Generator, optional
        Source of the bootstrap resamples; None: no confidence intervals.
    bootstrap : int
        Resamples (records drawn with replacement).
    confidence : float
        Two-sided level of the percentile intervals.

    Examples
    --------
    >>> fit = fit_first_collapse([1.0, 2.0, 4.0])
    >>> round(fit.median, 12), round(fit.beta, 6)
    (2.0, 0.565952)
    """
    x = np.asarray(values, dtype=float)
    censored = ~np.isfinite(x)
    if np.any(x[~censored] <= 0):
        raise InvalidParameterError("first-collapse intensities must be > 0")
    if np.any(censored) and ceiling is None:
        raise InvalidParameterError("records without a collapse need the ceiling")
    log_c = np.log(np.broadcast_to(np.asarray(1.0 if ceiling is None else ceiling, dtype=float),
                                   x.shape))
    logs = np.log(x[~censored])
    mu, beta = _mle_first(logs, log_c[censored])
    fit = LognormalFit(math.exp(mu), beta, "first_collapse", int(x.size), int(censored.sum()),
                       confidence=confidence)
    if rng is None or bootstrap <= 0:
        return fit
    require_int("bootstrap", bootstrap, 1, 10**7)
    require_range("confidence", confidence, 0, 1)
    samples = []
    for _ in range(int(bootstrap)):
        pick = rng.integers(0, x.size, x.size)
        cx = censored[pick]
        lx = np.log(x[pick][~cx])
        if lx.size < 2:
            continue
        samples.append((lx, log_c[pick][cx]))
    fits = _mle_first_many(samples)
    meds = np.array([math.exp(m) for m, _ in fits])
    betas = np.array([b for _, b in fits])
    return _with_ci(fit, meds, betas, confidence, len(fits))


# ----------------------------------------------------------------------------- (b)
def _mle_fraction(levels: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple[float, float]:
    """(ln theta, beta) maximising the binomial likelihood of Baker (2015)."""
    return _mle_fraction_many(levels, np.asarray(z, dtype=float)[None, :], n)[0]


def _fraction_start(lx: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple[float, float]:
    """Nelder-Mead's start for the collapse fraction's fit: the level where the fraction
    crosses 1/2, and the spread of the transition (ln theta, ln beta)."""
    frac = z / n
    if np.all(frac == 0) or np.all(frac == 1):
        raise InvalidParameterError("the collapse fraction is 0 (or 1) at every level: no "
                                    "fragility can be fitted; widen the levels")
    mu0 = float(np.interp(0.5, np.maximum.accumulate(frac), lx))
    inside = (frac > 0) & (frac < 1)
    beta0 = float(np.std(lx[inside])) if inside.sum() >= 2 else 0.1 * max(1e-3, np.ptp(lx))
    return mu0, math.log(max(beta0, 1e-3))


def _mle_fraction_many(levels: np.ndarray, zs: np.ndarray, n: np.ndarray
                       ) -> list[tuple[float, float]]:
    """`_mle_fraction` of each row of ``zs`` (collapses at each level), in one run of
    `_nelder_mead_many`."""
    lx = np.log(levels)
    x0 = np.array([_fraction_start(lx, z, n) for z in zs])

    def nll(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
        s = (lx - points[:, :1]) / np.array([math.exp(v) for v in points[:, 1]])[:, None]
        z = zs[rows]
        # log Phi(s) and log(1 - Phi(s)): scipy.stats.norm's logcdf and logsf are these
        # ufuncs behind a generic wrapper that cost 10x more
        return -np.sum(z * special.log_ndtr(s) + (n - z) * special.log_ndtr(-s), axis=1)

    return [(float(mu), float(math.exp(lb))) for mu, lb in _nelder_mead_many(nll, x0)]


def fit_collapse_fraction(levels: Sequence[float], collapses, *,
                          rng: np.random.Generator | None = None,
                          bootstrap: int = DEFAULT_BOOTSTRAP,
                          confidence: float = DEFAULT_CONFIDENCE) -> LognormalFit:
    """Lognormal fit of the collapse fraction per level by binomial maximum likelihood (b).

    Parameters
    ----------
    levels : sequence of float
        Intensity levels x_j (> 0).
    collapses : array_like of bool, shape (records, levels)
        Whether record i collapses the arch at level j.
    rng, bootstrap, confidence
        As `fit_first_collapse`; records (rows) are resampled.
    """
    x = np.asarray(levels, dtype=float)
    c = np.asarray(collapses, dtype=bool)
    if c.ndim != 2 or c.shape[1] != x.size:
        raise InvalidParameterError("collapses must have shape (records, levels)")
    if np.any(x <= 0):
        raise InvalidParameterError("levels must be > 0")
    n_rec = c.shape[0]
    n = np.full(x.size, float(n_rec))
    mu, beta = _mle_fraction(x, c.sum(axis=0).astype(float), n)
    fit = LognormalFit(math.exp(mu), beta, "collapse_fraction", n_rec, confidence=confidence)
    if rng is None or bootstrap <= 0:
        return fit
    zs = []
    for _ in range(int(bootstrap)):
        pick = rng.integers(0, n_rec, n_rec)
        z = c[pick].sum(axis=0).astype(float)
        if np.all(z == 0) or np.all(z == n_rec):
            continue
        zs.append(z)
    if not zs:
        return fit
    fits = _mle_fraction_many(x, np.array(zs), n)
    meds = np.array([math.exp(m) for m, _ in fits])
    betas = np.array([b for _, b in fits])
    return _with_ci(fit, meds, betas, confidence, len(fits))


def _with_ci(fit: LognormalFit, meds: np.ndarray, betas: np.ndarray, confidence: float,
             used: int) -> LognormalFit:
    if used < 2:
        return fit
    q = [50 * (1 - confidence), 50 * (1 + confidence)]
    m_lo, m_hi = (float(v) for v in np.percentile(meds, q))
    b_lo, b_hi = (float(v) for v in np.percentile(betas, q))
    return LognormalFit(fit.median, fit.beta, fit.method, fit.samples, fit.censored, (m_lo, m_hi),
                        (b_lo, b_hi), confidence, used)


# ----------------------------------------------------------------------------- IDA results
def dimensionless_divisor(im, *, collapse_acceleration_g: float, radius: float,
                          g: float) -> tuple[float, str] | None:
    """The scale that makes an intensity transfer between arch sizes, and its label.

    PGA and Sa (in g) divided by lambda (the static collapse multiplier: PGA / (lambda g));
    PGV (m/s) divided by sqrt(g R) (a velocity of the arch's own scale: the dimensionless
    equation of motion in time units sqrt(R/g), docs/domains.md). None for other measures.
    """
    name = getattr(im, "name", im)
    if name in ("pga", "sa"):
        return collapse_acceleration_g, "/ lambda"
    if name == "pgv":
        return math.sqrt(g * radius), "/ sqrt(g R)"
    return None


def fragility_of(result, *, rng: np.random.Generator | None = None,
                 bootstrap: int = DEFAULT_BOOTSTRAP, confidence: float = DEFAULT_CONFIDENCE,
                 levels=None) -> dict:
    """Both fits of an `IdaResult` in its intensity measure.

    Returns
    -------
    dict
        ``{"first_collapse": LognormalFit or None, "collapse_fraction": LognormalFit or None,
        "levels": ndarray, "fraction": ndarray}`` (a fit is None when it cannot be made, e.g.
        fewer than two collapsing records).
    """
    levels = result.stripe_levels() if levels is None else np.asarray(levels, dtype=float)
    first = result.first_collapse_levels
    out: dict = {"levels": levels, "fraction": result.collapse_fraction(levels)}
    try:
        out["first_collapse"] = fit_first_collapse(first, ceiling=result.ceiling, rng=rng,
                                                   bootstrap=bootstrap, confidence=confidence)
    except InvalidParameterError:
        out["first_collapse"] = None
    matrix = np.array([[r.collapses_at(x) for x in levels] for r in result.records])
    try:
        out["collapse_fraction"] = fit_collapse_fraction(levels, matrix, rng=rng,
                                                         bootstrap=bootstrap,
                                                         confidence=confidence)
    except InvalidParameterError:
        out["collapse_fraction"] = None
    return out


def dispersion_by_im(result, ims: Sequence[str]) -> list[dict]:
    """Median and beta of the first-collapse intensities in each measure of ``ims`` (method a,
    no bootstrap): the measure with the smallest beta predicts this arch's collapse best.

    The first-collapse scale factor of each record does not depend on the measure the analysis
    was run in, so one analysis gives every measure (to the analysis's precision in its own
    measure: 2 % in PGA is 2 % in any linear measure, 4 % in Arias intensity).
    """
    from archquake.ground.measures import parse_im

    rows = []
    for text in ims:
        im = parse_im(text)
        values = result.first_collapse_in(im)
        # a record without collapse was run up to the ceiling's scale factor: its censoring
        # level in this measure
        ceilings = result.ceiling_in(im)
        try:
            fit = fit_first_collapse(values, ceiling=ceilings)
        except InvalidParameterError:
            fit = None
        unit = {"g": "g", "m/s": "m_s", "m": "m"}[im.unit]
        rows.append({"im": im.label, "unit": im.unit,
                     f"median_{unit}": None if fit is None else fit.median,
                     "beta": None if fit is None else fit.beta,
                     "records_collapsing": int(np.sum(np.isfinite(values)))})
    return rows


__all__ = ["DEFAULT_BOOTSTRAP", "DEFAULT_CONFIDENCE", "LognormalFit", "dimensionless_divisor",
           "dispersion_by_im", "fit_collapse_fraction", "fit_first_collapse", "fragility_of"]
