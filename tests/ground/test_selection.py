"""Record selection (archquake.ground.selection): the chosen set meets the code's band.

Oracle: the band of NTC 2018 §3.2.3.6 (0.9 <= mean / target <= 1.3 at every period) and of
EN 1998-1 §3.2.3.1.2 (mean >= 0.9 target, mean PGA >= target PGA), checked here from the
candidates' unscaled spectra, the returned indices and factors, and the target: nothing the
selection computed about itself is trusted. The candidates are synthetic spectra of realistic
shape (code-like plateau and decay with random corner periods, amplification and smooth
log-normal noise), so the tests run in milliseconds; the limits (scale range, records per event
and per recording) are checked the same way. A case no set can meet must say so.
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from archquake.codes import ec8_spectrum, ntc2018_spectrum
from archquake.errors import InvalidParameterError
from archquake.ground.periods import period_grid
from archquake.ground.response_spectra import RecordSpectra
from archquake.ground.selection import ec8_band, ntc_band, select_records

G = 9.80665


def _candidates(periods: np.ndarray, n: int = 40, seed: int = 1) -> RecordSpectra:
    rng = np.random.default_rng(seed)
    rows = []
    for _ in range(n):
        pga = rng.uniform(0.1, 0.6) * G
        amp, tc, td = rng.uniform(2.0, 3.2), rng.uniform(0.2, 0.9), rng.uniform(1.5, 3.0)
        tb = tc / 3
        t = periods
        shape = np.where(t < tb, 1 + t / tb * (amp - 1), amp)
        shape = np.where(t >= tc, amp * tc / np.maximum(t, 1e-9), shape)
        shape = np.where(t >= td, amp * tc * td / np.maximum(t, 1e-9) ** 2, shape)
        noise = sum(rng.normal(0, 0.15) * np.sin(k * np.log1p(t / 0.05) + rng.uniform(0, 6))
                    for k in (1, 2, 3))
        rows.append(pga * shape * np.exp(noise - noise[0] * (t == 0)))
    names = tuple(f"r{i:02d}" for i in range(n))
    events = tuple(f"event {i // 2}" for i in range(n))         # two records per event
    recordings = tuple(f"rec {i}" for i in range(n))
    return RecordSpectra(periods, np.array(rows), names, events, recordings,
                         np.full(n, np.inf))


TARGETS = {
    "ntc B 0.25 g": (ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B"), ntc_band),
    "ntc D 0.10 g": (ntc2018_spectrum(ag_g=0.10, f0=2.6, tc_star_s=0.45, soil="D"), ntc_band),
    "ec8 1 C 0.30 g": (ec8_spectrum(ag_g=0.30, spectrum_type=1, ground="C"), ec8_band),
}


@pytest.mark.parametrize("which", list(TARGETS))
def test_chosen_mean_lies_in_the_band_at_every_period(which):
    spec, band = TARGETS[which]
    periods = period_grid(0.1, 2.0, 0.05)
    if band is ec8_band:
        periods = np.concatenate([[0.0], periods])     # the mean-PGA condition
    cands = _candidates(periods)
    sel = select_records(cands, spec.sa, band=band, count=7, scale_range=(0.5, 2.0),
                         max_per_event=1, seed=3)
    assert sel.compatible, sel.describe_failure()
    idx, f = np.array(sel.indices), sel.scale_factors
    assert len(set(idx)) == 7
    mean = (cands.sa[idx] * f[:, None]).mean(axis=0)
    ratio = mean / spec.sa(periods)
    lower, upper = band(periods)
    assert np.all(ratio >= lower * (1 - 1e-9)) and np.all(ratio <= upper * (1 + 1e-9))
    if band is ec8_band:
        assert ratio[0] >= 1.0 - 1e-9
    assert np.all((f >= 0.5 - 1e-12) & (f <= 2.0 + 1e-12))
    assert max(Counter(cands.events[i] for i in idx).values()) == 1
    assert sel.failures() == [] and sel.describe_failure() == ""


def test_common_scale_and_limits_per_recording():
    spec, _ = TARGETS["ntc B 0.25 g"]
    periods = period_grid(0.1, 1.5, 0.1)
    cands = _candidates(periods, seed=7)
    # pairs of components: records 2k and 2k+1 share a recording
    cands = RecordSpectra(cands.periods_s, cands.sa, cands.names, cands.events,
                          tuple(f"rec {i // 2}" for i in range(len(cands))),
                          cands.usable_period_s)
    sel = select_records(cands, spec.sa, count=7, common_scale=True, max_per_event=None,
                         max_per_recording=1, scale_range=(0.25, 4.0))
    assert sel.compatible, sel.describe_failure()
    assert np.ptp(sel.scale_factors) == 0.0
    assert max(Counter(cands.recordings[i] for i in sel.indices).values()) == 1


def test_deterministic_for_a_seed():
    spec, _ = TARGETS["ntc D 0.10 g"]
    cands = _candidates(period_grid(0.1, 2.0, 0.1), seed=11)
    a = select_records(cands, spec.sa, seed=5)
    b = select_records(cands, spec.sa, seed=5)
    assert a.indices == b.indices
    np.testing.assert_array_equal(a.scale_factors, b.scale_factors)


def test_no_set_can_match_says_where_and_by_how_much():
    """Records held at scale 1 against a target four times stronger: the mean is below the band
    everywhere, and the line says so with the worst ratio."""
    spec = ntc2018_spectrum(ag_g=2.0, f0=2.4, tc_star_s=0.3)
    periods = period_grid(0.2, 1.0, 0.2)
    cands = _candidates(periods, seed=2)
    sel = select_records(cands, spec.sa, scale_range=(1.0, 1.0), restarts=2)
    assert not sel.compatible and sel.violation > 0
    line = sel.describe_failure()
    assert line.startswith("no set of 7 records meets the band: the best mean is below the band")
    assert "T = 0.2-1 s" in line and "\n" not in line
    worst = min(f[1] for f in sel.failures())
    assert f"worst {worst:.2f} x target" in line


def test_callable_target_and_bad_input():
    spec, _ = TARGETS["ntc B 0.25 g"]
    periods = period_grid(0.1, 1.0, 0.1)
    cands = _candidates(periods, n=10)
    sel = select_records(cands, spec.sa, count=3, max_per_event=None)
    assert len(sel.indices) == 3
    with pytest.raises(InvalidParameterError, match="fewer than count = 11"):
        select_records(cands, spec.sa, count=11)
    with pytest.raises(InvalidParameterError, match="target must be 10 positive"):
        select_records(cands, np.ones(3))
    with pytest.raises(InvalidParameterError, match="scale_range must satisfy"):
        select_records(cands, spec.sa, scale_range=(1.2, 2.0))
    with pytest.raises(InvalidParameterError, match="no 7 records satisfy the limits"):
        select_records(cands, spec.sa, max_per_event=1, count=7)   # 5 events only
    short = RecordSpectra(cands.periods_s, cands.sa, cands.names, cands.events,
                          cands.recordings, np.r_[np.full(5, 0.5), np.full(5, np.inf)])
    with pytest.raises(InvalidParameterError, match="only 5 of 10 records are usable"):
        select_records(short, spec.sa, count=7)


def test_selected_suite_holds_the_scaled_records(tmp_path):
    """The suite of the chosen records: each one the candidate times its factor (its spectrum
    scales linearly: checked on the records' values)."""
    from archquake.ground import Record
    from archquake.ground.response_spectra import record_spectra
    from archquake.ground.selection import selected_suite
    from archquake.ground.suites import Suite

    t = np.arange(0.0, 4.0, 0.01)
    rng = np.random.default_rng(0)
    records = tuple(Record(np.sin(2 * np.pi * t / rng.uniform(0.2, 1.0)) * rng.uniform(1, 4), 0.01,
                           name=f"s{i}") for i in range(8))
    suite = Suite("sines", records)
    spectra = record_spectra(suite, [0.2, 0.5, 1.0])
    spec, _ = TARGETS["ntc B 0.25 g"]
    sel = select_records(spectra, spec.sa, count=3, scale_range=(0.1, 10.0), restarts=2)
    chosen = selected_suite(suite, sel)
    assert len(chosen) == 3
    for rec, i, f in zip(chosen, sel.indices, sel.scale_factors):
        np.testing.assert_allclose(rec.accelerations, f * suite[i].accelerations, rtol=1e-15)
    with pytest.raises(InvalidParameterError, match="was not made from suite"):
        selected_suite(Suite("other", records[::-1]), sel)
