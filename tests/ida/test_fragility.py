"""Fragility fits recover known lognormal parameters.

Oracle: synthetic capacities drawn from a lognormal with known median and beta (fixed seeds).
Tolerances: for n = 200 samples the standard error of ln(median) is beta / sqrt(n) = 0.028 for
beta = 0.4 (so 5 % is ~1.8 standard errors) and that of beta is beta / sqrt(2n) = 5 % (10 % is
2 standard errors); the seeds are fixed, so the tests are deterministic, and the coverage check
over many seeds is the statistical statement.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from archquake.errors import InvalidParameterError
from archquake.ida.fragility import fit_collapse_fraction, fit_first_collapse

MEDIAN, BETA = 0.8, 0.4


def _capacities(seed, n=200):
    return MEDIAN * np.exp(BETA * np.random.default_rng(seed).standard_normal(n))


def test_first_collapse_fit_recovers_median_and_beta():
    fit = fit_first_collapse(_capacities(1), rng=np.random.default_rng(2), bootstrap=400)
    assert fit.median == pytest.approx(MEDIAN, rel=0.05)
    assert fit.beta == pytest.approx(BETA, rel=0.10)
    assert fit.median_ci[0] < MEDIAN < fit.median_ci[1]
    assert fit.beta_ci[0] < BETA < fit.beta_ci[1]


def test_first_collapse_closed_form_is_the_likelihood_maximum():
    """The uncensored estimate is mean/std of the logs; the numerical censored maximiser with
    nothing censored above the data must give the same (independent code path)."""
    x = _capacities(3, 50)
    closed = fit_first_collapse(x)
    assert closed.median == pytest.approx(math.exp(np.mean(np.log(x))), rel=1e-12)
    assert closed.beta == pytest.approx(np.std(np.log(x)), rel=1e-12)
    # a record known only to stand up to a level far below every capacity carries no
    # information (its survival probability is 1): the censored maximiser finds the same fit
    censored = fit_first_collapse(np.append(x, np.nan), ceiling=1e-3)
    assert censored.median == pytest.approx(closed.median, rel=1e-4)
    assert censored.beta == pytest.approx(closed.beta, rel=1e-3)


def test_censored_fit_recovers_parameters_where_dropping_the_censored_is_biased():
    x = _capacities(4, 400)
    ceiling = 1.0  # ~71 % of the records collapse below it
    seen = np.where(x <= ceiling, x, np.nan)
    fit = fit_first_collapse(seen, ceiling=ceiling)
    naive = fit_first_collapse(seen[np.isfinite(seen)])
    assert fit.censored == int(np.sum(x > ceiling)) > 50
    assert fit.median == pytest.approx(MEDIAN, rel=0.05)
    assert fit.beta == pytest.approx(BETA, rel=0.10)
    assert naive.median < 0.93 * MEDIAN  # the truncated sample alone is biased low


def test_collapse_fraction_fit_recovers_parameters():
    """Baker (2015): monotone records (collapse iff x >= capacity) observed at 15 stripes."""
    cap = _capacities(5)
    levels = np.geomspace(0.2, 3.0, 15)
    fit = fit_collapse_fraction(levels, cap[:, None] <= levels[None, :],
                                rng=np.random.default_rng(6), bootstrap=60)
    assert fit.median == pytest.approx(MEDIAN, rel=0.05)
    assert fit.beta == pytest.approx(BETA, rel=0.10)
    assert fit.median_ci[0] < fit.median < fit.median_ci[1]


def test_collapse_fraction_maximises_the_binomial_likelihood():
    cap = _capacities(7, 60)
    levels = np.geomspace(0.3, 2.5, 9)
    c = cap[:, None] <= levels[None, :]
    fit = fit_collapse_fraction(levels, c)
    z, n = c.sum(axis=0), c.shape[0]

    def loglik(m, b):
        p = stats.norm.cdf(np.log(levels / m) / b)
        return float(np.sum(stats.binom.logpmf(z, n, p)))

    best = loglik(fit.median, fit.beta)
    for dm, db in [(1.01, 1), (0.99, 1), (1, 1.02), (1, 0.98)]:
        assert loglik(fit.median * dm, fit.beta * db) < best


def test_bootstrap_interval_covers_the_truth_at_about_its_level():
    """Coverage of the 90 % percentile interval of the median over 200 independent samples of
    n = 40 (closed-form estimator, so cheap): binomial sd of the coverage is 2 %; accept
    0.82-0.97 (percentile intervals undercover slightly at small n)."""
    rng = np.random.default_rng(11)
    hits = 0
    for seed in range(200):
        fit = fit_first_collapse(_capacities(100 + seed, 40), rng=rng, bootstrap=300)
        hits += fit.median_ci[0] <= MEDIAN <= fit.median_ci[1]
    assert 0.82 <= hits / 200 <= 0.97


def test_degenerate_inputs_are_refused():
    with pytest.raises(InvalidParameterError, match="at least 2"):
        fit_first_collapse([1.0])
    with pytest.raises(InvalidParameterError, match="ceiling"):
        fit_first_collapse([1.0, 2.0, np.nan])
    with pytest.raises(InvalidParameterError, match="every level"):
        fit_collapse_fraction([1.0, 2.0], np.zeros((3, 2), dtype=bool))


def _mle_first_scipy(logs, log_ceilings):
    """The censored lognormal likelihood written with scipy.stats.norm's logpdf and logsf,
    maximised with the same Nelder-Mead settings: the plain path that `_mle_first` computes
    without scipy's generic wrapper and memoises."""
    from scipy import optimize

    n = logs.size
    if log_ceilings.size == 0:  # none censored: the closed form
        return float(np.mean(logs)), float(np.std(logs))
    mu0, beta0 = float(np.mean(logs)), max(float(np.std(logs)), 1e-3)

    def nll(p):
        mu, lb = p
        b = math.exp(lb)
        return -(np.sum(stats.norm.logpdf((logs - mu) / b)) - n * lb
                 + np.sum(stats.norm.logsf((log_ceilings - mu) / b)))

    res = optimize.minimize(nll, [mu0, math.log(beta0)], method="Nelder-Mead",
                            options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    return float(res.x[0]), float(math.exp(res.x[1]))


def test_censored_fit_is_bit_for_bit_the_scipy_likelihoods():
    """Oracle: the same maximisation with scipy.stats.norm (``_mle_first_scipy``): equal to
    the last bit, on resamples of censored capacities (the bootstrap's inputs)."""
    from archquake.ida.fragility import _mle_first

    rng = np.random.default_rng(5)
    caps = _capacities(3, n=28)
    caps[caps > 1.2] = np.nan  # right-censored at the ceiling
    for _ in range(40):
        x = caps[rng.integers(0, caps.size, caps.size)]
        cens = ~np.isfinite(x)
        logs, log_c = np.log(x[~cens]), np.full(int(cens.sum()), math.log(1.2))
        assert _mle_first(logs, log_c) == _mle_first_scipy(logs, log_c)


def test_probability_interval_refits_nothing_the_fragility_fitted(monkeypatch):
    """The assessment's interval of P(collapse | site PGA) resamples the records from the seed
    the fragility's bootstrap used: its fits are found again (kept by their input), none
    is made twice, and the interval is the one the plain refits give (oracle: each resample
    fitted anew with scipy.stats' likelihood)."""
    from archquake.assess.sections import _p_at_site_ci
    from archquake.ida import fragility

    first = _capacities(7, n=28)
    first[first > 1.1] = np.nan
    fragility._FIRST_FITS.clear()
    fit_first_collapse(first, ceiling=1.1, rng=np.random.default_rng(0), bootstrap=200)
    made = []
    searched = fragility._nelder_mead_many
    monkeypatch.setattr(fragility, "_nelder_mead_many",
                        lambda nll, x0: made.append(len(x0)) or searched(nll, x0))
    ci = _p_at_site_ci(first, 1.1, 0.6, 200)
    assert made == []  # every fit found again
    rng = np.random.default_rng(0)
    ps = []
    for _ in range(200):
        x = first[rng.integers(0, first.size, first.size)]
        cens = ~np.isfinite(x)
        if (~cens).sum() < 2:
            continue
        mu, beta = _mle_first_scipy(np.log(x[~cens]), np.full(int(cens.sum()), math.log(1.1)))
        ps.append(float(stats.norm.cdf(np.log(0.6 / math.exp(mu)) / beta)))
    q = [50 * (1 - 0.9), 50 * (1 + 0.9)]  # the 90 % interval, as the assessment writes it
    assert ci == tuple(float(v) for v in np.percentile(ps, q))


def _mle_fraction_scipy(levels, z, n):
    """The binomial likelihood of the collapse fraction with scipy.stats.norm's logcdf and
    logsf, maximised by ``scipy.optimize.minimize`` with the fits' Nelder-Mead settings, from
    the fits' start (`_fraction_start`)."""
    from scipy import optimize

    from archquake.ida.fragility import NELDER_MEAD, _fraction_start

    lx = np.log(levels)

    def nll(p):
        mu, lb = p
        s = (lx - mu) / math.exp(lb)
        return -float(np.sum(z * stats.norm.logcdf(s) + (n - z) * stats.norm.logsf(s)))

    res = optimize.minimize(nll, list(_fraction_start(lx, z, n)), method="Nelder-Mead",
                            options=NELDER_MEAD)
    return float(res.x[0]), float(math.exp(res.x[1]))


def test_bootstrap_fits_are_scipys_nelder_mead_resample_by_resample():
    """The bootstrap fits its resamples together (one Nelder-Mead run over all of them,
    `_nelder_mead_many`). Oracle: each resample maximised alone by
    ``scipy.optimize.minimize`` with scipy.stats' likelihoods. The intervals are equal to the
    last bit, for both fits, on samples with ties, censored records and non-monotone
    collapses."""
    from archquake.ida.fragility import _with_ci

    rng = np.random.default_rng(21)
    q = [50 * (1 - 0.9), 50 * (1 + 0.9)]
    for trial in range(2):
        caps = np.round(_capacities(30 + trial, n=28), 2 if trial % 2 else 6)
        levels = np.geomspace(0.3, 2.0, 12)
        collapses = (levels[None, :] >= caps[:, None]) ^ (rng.random((28, 12)) < 0.04)
        fit = fit_collapse_fraction(levels, collapses, rng=np.random.default_rng(trial),
                                    bootstrap=80)
        draw = np.random.default_rng(trial)
        n = np.full(levels.size, 28.0)
        fits = []
        for _ in range(80):
            z = collapses[draw.integers(0, 28, 28)].sum(axis=0).astype(float)
            if np.all(z == 0) or np.all(z == 28):
                continue
            fits.append(_mle_fraction_scipy(levels, z, n))
        meds = np.array([math.exp(m) for m, _ in fits])
        betas = np.array([b for _, b in fits])
        assert fit == _with_ci(fit, meds, betas, 0.9, len(fits))
        assert fit.median_ci == tuple(float(v) for v in np.percentile(meds, q))

        cens = np.where(caps > 1.2, np.nan, caps)
        fit = fit_first_collapse(cens, ceiling=1.2, rng=np.random.default_rng(trial),
                                 bootstrap=80)
        draw = np.random.default_rng(trial)
        fits = []
        for _ in range(80):
            x = cens[draw.integers(0, 28, 28)]
            cx = ~np.isfinite(x)
            if (~cx).sum() < 2:
                continue
            fits.append(_mle_first_scipy(np.log(x[~cx]), np.full(int(cx.sum()), math.log(1.2))))
        meds = np.array([math.exp(m) for m, _ in fits])
        betas = np.array([b for _, b in fits])
        assert fit.beta_ci == tuple(float(v) for v in np.percentile(betas, q))
        assert fit.median_ci == tuple(float(v) for v in np.percentile(meds, q))


def test_a_bootstrap_larger_than_the_kept_fits_is_the_same(monkeypatch):
    """The fits are kept by their input up to a bound (`_FIRST_FITS_KEPT`); a bootstrap with
    more resamples than that gives the interval it gives with room for all of them (oracle:
    the same call with the bound far above the resamples), and the bound holds."""
    from archquake.ida import fragility

    first = _capacities(9, n=28)
    first[first > 1.1] = np.nan
    fragility._FIRST_FITS.clear()
    whole = fit_first_collapse(first, ceiling=1.1, rng=np.random.default_rng(3), bootstrap=60)
    fragility._FIRST_FITS.clear()
    monkeypatch.setattr(fragility, "_FIRST_FITS_KEPT", 10)
    bounded = fit_first_collapse(first, ceiling=1.1, rng=np.random.default_rng(3), bootstrap=60)
    assert bounded == whole
    assert len(fragility._FIRST_FITS) <= 10
