"""Intensity measures (archquake.ground.measures) against closed forms, scaling laws and eqsig.

Oracles:
- closed forms of the one-cycle sine pulse and Oppenheim's step impulse (PGV, PGD, Arias, CAV,
  D5-95), integrated by hand;
- the response of a linear oscillator to a sine at its own period: undamped, N cycles give
  Sa = pi N A exactly; damped, the closed-form solution (particular + homogeneous, then free
  vibration) evaluated on a dense grid;
- dimensional scaling (IM(s x) = s^k IM(x)) on random records;
- eqsig (an independent implementation: Nigam & Jennings coefficients, trapezoid integrals) on
  a real record, pyslammer's Northridge 1994 Pacoima Dam 175.
"""

from __future__ import annotations

import importlib.resources
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import InvalidParameterError
from archquake.ground import Record, SinePulse, StepImpulse, read_record
from archquake.ground.measures import (
    IntensityMeasure,
    im_value,
    intensity_measures,
    parse_im,
    response_spectrum,
    scale_to,
    significant_duration,
)
from archquake.ground.records import resampled

# A pulse is sampled with 8192 linear pieces: the interpolation error of a sine is
# (2 pi/8192)^2/12 ~ 5e-8 relative, so 1e-6 is a safe tolerance for its integrals.
PULSE_RTOL = 1e-6


# -------------------------------------------------------------------------------------
# closed forms of the pulses
# -------------------------------------------------------------------------------------
@pytest.mark.parametrize("direction", [-1, 1])
def test_sine_pulse_closed_forms(direction):
    """a = A sin(2 pi t/T) on [0, T): v = A T/(2 pi) (1 - cos), PGV = A T/pi at T/2;
    d(T) = A T^2/(2 pi); int a^2 = A^2 T/2; int |a| = 2 A T/pi."""
    amp, period = 3.0, 0.8
    m = intensity_measures(SinePulse(amp, period, direction))
    assert m.pga_g == pytest.approx(amp / G, rel=1e-12)
    assert m.pgv_m_s == pytest.approx(amp * period / math.pi, rel=PULSE_RTOL)
    assert m.pgd_m == pytest.approx(amp * period**2 / (2 * math.pi), rel=PULSE_RTOL)
    assert m.arias_m_s == pytest.approx(math.pi / (2 * G) * amp**2 * period / 2, rel=PULSE_RTOL)
    assert m.cav_m_s == pytest.approx(2 * amp * period / math.pi, rel=PULSE_RTOL)


def test_step_impulse_closed_forms():
    """a on [0, t_p), -a/2 on [t_p, 3 t_p): PGV = a t_p, PGD = d(3 t_p) = 3/2 a t_p^2,
    int a^2 = 3/2 a^2 t_p, CAV = 2 a t_p; 5 % of the energy at 0.075 t_p, 95 % at
    t_p + (0.95 - 2/3) 6 t_p = 2.7 t_p, so D5-95 = 2.625 t_p. The pulse is piecewise
    constant, so the linear pieces represent it exactly: rounding-level agreement."""
    a, tp = 2.5, 0.3
    m = intensity_measures(StepImpulse(a, tp))
    assert m.pga_g == pytest.approx(a / G, rel=1e-14)
    assert m.pgv_m_s == pytest.approx(a * tp, rel=1e-12)
    assert m.pgd_m == pytest.approx(1.5 * a * tp**2, rel=1e-12)
    assert m.arias_m_s == pytest.approx(math.pi / (2 * G) * 1.5 * a**2 * tp, rel=1e-12)
    assert m.cav_m_s == pytest.approx(2 * a * tp, rel=1e-12)
    assert m.d5_95_s == pytest.approx(2.625 * tp, rel=1e-9)


def test_pgv_between_samples():
    """A record 0, +1, -1, 0 (dt = 1): v peaks where a crosses zero inside the second interval,
    at v = 1/2 + 1/4 = 3/4 (the sample values of v are 0, 1/2, 1/2, 0)."""
    m = intensity_measures(Record([0.0, 1.0, -1.0, 0.0], 1.0))
    assert m.pgv_m_s == pytest.approx(0.75, rel=1e-14)
    # |a| integral with the sign change: 1/2 + 2 x 1/4 + 1/2 = 3/2
    assert m.cav_m_s == pytest.approx(1.5, rel=1e-14)


# -------------------------------------------------------------------------------------
# Sa at resonance
# -------------------------------------------------------------------------------------
def _sine_record(amp, period, cycles, per_period=2000):
    dt = period / per_period
    t = dt * np.arange(cycles * per_period + 1)
    return Record(amp * np.sin(2 * np.pi * t / period), dt, name="sine")


@pytest.mark.parametrize("cycles", [1, 5])
def test_undamped_resonance_sa_is_pi_n_a(cycles):
    """u'' + w^2 u = -A sin(w t) from rest: u = -A/(2 w^2) (sin wt - wt cos wt); its extremes
    at t = k T/2 grow as pi k A/(2 w^2), the last (k = 2N, at the end of the motion, with
    u' = 0) is the largest and the free vibration keeps it: Sa = w^2 max|u| = pi N A.
    Linear pieces of T/2000 (one-cycle pulse: T/8192) represent the sine to ~1e-6."""
    amp, period = 1.7, 0.4
    motion = SinePulse(amp, period, 1) if cycles == 1 else _sine_record(amp, period, cycles)
    sa = response_spectrum(motion, [period], damping=0.0)[0]
    assert sa == pytest.approx(math.pi * cycles * amp, rel=1e-5)
    # Sa(0) is the PGA
    assert response_spectrum(motion, [0.0])[0] == pytest.approx(amp, rel=1e-6)


def _damped_resonance_peak(amp, period, zeta, cycles):
    """max |u| of u'' + 2 zeta w u' + w^2 u = -A sin(w t), t in [0, N T], then free, from rest."""
    w = 2 * np.pi / period
    wd = w * np.sqrt(1 - zeta**2)
    x = amp / (2 * zeta * w**2)            # particular solution X cos(w t)
    c1, c2 = -x, -zeta * w * x / wd        # u(0) = 0, u'(0) = 0
    t = np.linspace(0.0, cycles * period, 400_001)
    e = np.exp(-zeta * w * t)
    u = x * np.cos(w * t) + e * (c1 * np.cos(wd * t) + c2 * np.sin(wd * t))
    te = t[-1]
    ee = np.exp(-zeta * w * te)
    ue = x * np.cos(w * te) + ee * (c1 * np.cos(wd * te) + c2 * np.sin(wd * te))
    ve = (-x * w * np.sin(w * te)
          + ee * ((-zeta * w * c1 + wd * c2) * np.cos(wd * te)
                  + (-zeta * w * c2 - wd * c1) * np.sin(wd * te)))
    tau = np.linspace(0.0, period, 100_001)
    uf = np.exp(-zeta * w * tau) * (ue * np.cos(wd * tau)
                                    + (ve + zeta * w * ue) / wd * np.sin(wd * tau))
    return max(np.max(np.abs(u)), np.max(np.abs(uf)))


@pytest.mark.parametrize(("zeta", "cycles"), [(0.05, 1), (0.05, 4), (0.2, 3)])
def test_damped_resonance_matches_closed_form(zeta, cycles):
    """Sa = w^2 max|u| of the closed-form solution. archquake reads the peak at sub-steps of at
    most T/100, so it may miss the true peak by at most a factor cos(pi/100) (a peak within
    half a sub-step of a node): the tolerance is that one-sided band plus 1e-5 for the
    linear pieces."""
    amp, period = 2.0, 0.5
    motion = SinePulse(amp, period, 1) if cycles == 1 else _sine_record(amp, period, cycles)
    exact = (2 * np.pi / period) ** 2 * _damped_resonance_peak(amp, period, zeta, cycles)
    sa = response_spectrum(motion, [period], damping=zeta)[0]
    assert exact * math.cos(math.pi / 100) * (1 - 1e-5) <= sa <= exact * (1 + 1e-5)


# -------------------------------------------------------------------------------------
# scaling laws, scale_to and parse_im
# -------------------------------------------------------------------------------------
@settings(max_examples=25, deadline=None)
@given(
    st.lists(st.floats(-5.0, 5.0, allow_nan=False), min_size=3, max_size=60),
    st.sampled_from([0.005, 0.01, 0.02]),
    st.floats(0.1, 10.0),
)
def test_scaling_laws(values, dt, factor):
    """IM(s x) = s IM(x) for the linear measures, s^2 for Arias; D5-95 and Tm do not change."""
    if max(abs(v) for v in values) < 1e-3:
        return
    rec = Record(values, dt)
    a = intensity_measures(rec, periods=(0.3,))
    b = intensity_measures(rec.scaled(factor), periods=(0.3,))
    for key in ("pga_g", "pgv_m_s", "pgd_m", "cav_m_s"):
        assert getattr(b, key) == pytest.approx(factor * getattr(a, key), rel=1e-9, abs=1e-300)
    assert b.sa_g[0.3] == pytest.approx(factor * a.sa_g[0.3], rel=1e-9)
    assert b.arias_m_s == pytest.approx(factor**2 * a.arias_m_s, rel=1e-9)
    assert b.d5_95_s == pytest.approx(a.d5_95_s, rel=1e-9, abs=1e-12)
    if math.isfinite(a.mean_period_s):
        assert b.mean_period_s == pytest.approx(a.mean_period_s, rel=1e-9)


@pytest.mark.parametrize("im", ["pga", "pgv", "pgd", "arias", "cav", "sa:0.5", "sa:1.2"])
def test_scale_to_reaches_the_target(im):
    motion = _sine_record(1.0, 0.7, 3, per_period=200)
    target = 0.37
    scaled, factor = scale_to(motion, im, target)
    assert im_value(scaled, im) == pytest.approx(target, rel=1e-10)
    exponent = parse_im(im).exponent
    assert factor == pytest.approx((target / im_value(motion, im)) ** (1 / exponent), rel=1e-12)


def test_scale_to_rejects_a_zero_motion_and_bad_target():
    quiet = Record([0.0, 0.0, 0.0], 0.01, name="quiet")
    with pytest.raises(InvalidParameterError, match="its pga is 0"):
        scale_to(quiet, "pga", 0.3)
    with pytest.raises(InvalidParameterError, match="target pga"):
        scale_to(StepImpulse(1.0, 0.1), "pga", -1.0)


def test_parse_im():
    assert parse_im(" PGA ") == IntensityMeasure("pga")
    assert parse_im("sa:0.5") == IntensityMeasure("sa", 0.5)
    assert parse_im("Sa(1.0)") == IntensityMeasure("sa", 1.0)
    assert parse_im("arias").exponent == 2 and parse_im("pgv").unit == "m/s"
    assert parse_im("sa:0.25").key == "sa_0.25s_g" and parse_im("pgd").key == "pgd_m"
    assert parse_im(parse_im("cav")).label == "cav"


@pytest.mark.parametrize(
    ("text", "fragment"),
    [("pgx", "is not one of pga (g), pgv (m/s)"), ("sa", "is not one of"),
     ("sa:-1", "period of sa:T must be a number of seconds > 0"),
     ("sa:abc", "period of sa:T"), ("sa:inf", "period of sa:T"), (3.0, "must be text")],
)
def test_parse_im_errors_are_one_line(text, fragment):
    with pytest.raises(InvalidParameterError, match=None) as info:
        parse_im(text)
    assert fragment in str(info.value) and "\n" not in str(info.value)


# -------------------------------------------------------------------------------------
# durations and the mean period
# -------------------------------------------------------------------------------------
def test_steady_sine_durations_and_mean_period():
    """A sine of constant amplitude deposits energy at a constant rate on average, so D5-95 is
    0.9 of its length (to within a quarter period of ripple); its Fourier amplitude is
    concentrated at f0 = 2 Hz, inside Rathje's 0.25-20 Hz band, so Tm = 1/f0 to within the
    leakage of a 40 s window (1 %)."""
    rec = _sine_record(1.0, 0.5, 80, per_period=100)  # 40 s
    m = intensity_measures(rec)
    assert m.d5_95_s == pytest.approx(0.9 * 40.0, abs=0.5 / 4)
    assert m.mean_period_s == pytest.approx(0.5, rel=0.01)
    assert significant_duration(rec, 0.05, 0.95) == pytest.approx(m.d5_95_s, rel=1e-12)


# -------------------------------------------------------------------------------------
# eqsig on a real record
# -------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def northridge():
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource / "Northridge_1994_PAC-175.csv") as path:
        return read_record(path, units="g")


def test_agreement_with_eqsig_on_northridge(northridge):
    """eqsig integrates with node-based rules (trapezoid of a^2 and |a|, Nigam-Jennings at the
    samples, peaks read at the samples, no free vibration after the record). Fed the same
    piecewise-linear motion refined 20 times (linear resampling leaves it unchanged) and
    padded with 5 s of zeros, its rules converge to archquake's exact integrals: the
    residuals are O((dt/20)^2) for the integrals (< 0.1 %) and the half-step peak reading
    1 - cos(pi dt/(20 T)) < 0.05 % at T >= 0.2 s. D5-95 is read on eqsig's sample grid:
    within two fine steps."""
    import eqsig  # a test dependency (pyproject's test extra): CI runs this, never skips it
    import eqsig.im
    import eqsig.sdof

    periods = np.array([0.2, 0.3, 0.5, 1.0, 2.0, 4.0])
    m = intensity_measures(northridge, periods=periods)
    fine = resampled(northridge, northridge.dt / 20, method="linear")
    values = np.concatenate([fine.accelerations, np.zeros(int(round(5.0 / fine.dt)))])
    sig = eqsig.AccSignal(values, fine.dt)
    assert sig.pga == pytest.approx(m.pga_g * G, rel=1e-12)
    assert sig.pgv == pytest.approx(m.pgv_m_s, rel=1e-4)
    assert sig.pgd == pytest.approx(m.pgd_m, rel=2e-3)  # trapezoid twice: O(h) on d
    assert eqsig.im.calc_arias_intensity(sig)[-1] * 9.81 / G == pytest.approx(m.arias_m_s,
                                                                              rel=1e-3)
    assert eqsig.im.calc_cav(sig)[-1] == pytest.approx(m.cav_m_s, rel=1e-3)
    assert eqsig.im.calc_sig_dur_vals(fine.accelerations, fine.dt) == pytest.approx(
        m.d5_95_s, abs=2 * fine.dt)
    _, _, sa = eqsig.sdof.pseudo_response_spectra(values, fine.dt, periods, 0.05)
    np.testing.assert_allclose(sa / G, [m.sa_g[p] for p in periods], rtol=1e-3)


def test_northridge_measures_are_stable(northridge):
    """Regression of the numbers quoted in docs/earthquakes.md (computed by this module,
    cross-checked above with eqsig): PGA is the file's 0.415325 g exactly."""
    m = intensity_measures(northridge, periods=(1.0,))
    assert m.pga_g == pytest.approx(0.415325, rel=1e-12)
    assert m.pgv_m_s == pytest.approx(0.4527, rel=1e-3)
    assert m.arias_m_s == pytest.approx(0.8895, rel=1e-3)


def test_records_on_one_time_step_share_their_oscillator_coefficients(monkeypatch):
    """The spectrum's cost bounded by a count, as solve_ivp's by nfev: the state-transition
    matrices (one matrix exponential per period and time step) of a record serve every other
    record sampled at the same step, and the spectra stay bit-for-bit those computed afresh.
    Oracle: calls of scipy.linalg.expm counted; the spectra compared with np.array_equal."""
    import scipy.linalg

    from archquake.ground import Record
    from archquake.ground.measures import _transition, response_spectrum

    calls = []
    expm = scipy.linalg.expm
    monkeypatch.setattr(scipy.linalg, "expm", lambda m: calls.append(1) or expm(m))
    rng = np.random.default_rng(7)
    first, second = (Record(rng.normal(0.0, 1.0, 400), 0.01, name=n) for n in ("a", "b"))
    periods = (0.2, 0.5, 1.0)
    _transition.cache_clear()
    sa_first = response_spectrum(first, periods)
    computed = len(calls)
    sa_second = response_spectrum(second, periods)
    assert computed >= len(periods) and len(calls) == computed  # none computed again
    _transition.cache_clear()
    assert np.array_equal(response_spectrum(second, periods), sa_second)
    assert np.array_equal(response_spectrum(first, periods), sa_first)
