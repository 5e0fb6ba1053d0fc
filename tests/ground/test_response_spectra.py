"""Spectra of several records (archquake.ground.response_spectra) against independent oracles.

Oracles:
- eqsig's response spectrum (an independent implementation: Nigam & Jennings coefficients at
  the samples) of each record, and so of the mean; the records are refined 20 times and padded
  with zeros as in tests/ground/test_measures.py, which bounds the difference by 0.1 %;
- the closed-form steady state of a damped oscillator under a harmonic ground acceleration
  A sin(w t) switched on and off slowly: Sa = A / sqrt((1 - r^2)^2 + (2 zeta r)^2),
  r = T / T_input;
- the grid's arithmetic: period_grid against numpy's arange.
"""

from __future__ import annotations

import importlib.resources
import math

import numpy as np
import pytest

from archquake.errors import InvalidParameterError
from archquake.ground import Record, read_record
from archquake.ground.periods import period_grid
from archquake.ground.records import resampled
from archquake.ground.response_spectra import record_spectra


@pytest.fixture(scope="module")
def northridge():
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource / "Northridge_1994_PAC-175.csv") as path:
        return read_record(path, units="g")


def test_suite_mean_agrees_with_eqsig(northridge):
    import eqsig.sdof  # a test dependency (pyproject's test extra)

    records = [northridge, northridge.scaled(0.5).mirrored()]
    periods = np.array([0.2, 0.5, 1.0, 2.0])
    spec = record_spectra(records, periods)
    rows = []
    for r in records:
        fine = resampled(r, r.dt / 20, method="linear")
        values = np.concatenate([fine.accelerations, np.zeros(int(round(5.0 / fine.dt)))])
        rows.append(eqsig.sdof.pseudo_response_spectra(values, fine.dt, periods, 0.05)[2])
    np.testing.assert_allclose(spec.sa, rows, rtol=1e-3)
    np.testing.assert_allclose(spec.mean, np.mean(rows, axis=0), rtol=1e-3)
    # the mirrored record at half scale: exactly half the spectrum (linearity, sign symmetry)
    np.testing.assert_allclose(spec.sa[1], 0.5 * spec.sa[0], rtol=1e-12)


@pytest.mark.parametrize("ratio", [0.5, 0.9, 1.0, 1.6])
def test_harmonic_steady_state(ratio):
    """A 2 Hz sine of amplitude 1 m/s^2, switched on and off by 20 s cosine ramps, 60 s long;
    the oscillator's period is ratio * 0.5 s. Away from the ramps it holds the steady amplitude.
    The ramps excite a small free vibration on top, which shrinks as they lengthen (for r = 0.9:
    13 % with 3 s ramps, 1.3 % with 10 s, 0.3 % with 20 s): tolerance 0.5 %."""
    dt, f, ramp = 0.005, 2.0, 20.0
    t = np.arange(0.0, 60.0, dt)
    up = np.where(t < ramp, 0.5 * (1 - np.cos(np.pi * t / ramp)), 1.0)
    rec = Record(up * up[::-1] * np.sin(2 * np.pi * f * t), dt, name="harmonic")
    zeta = 0.05
    spec = record_spectra([rec], [ratio / f], damping=zeta)
    r = ratio   # T / T_input = omega_input / omega_n
    expected = 1.0 / math.sqrt((1 - r**2) ** 2 + (2 * zeta * r) ** 2)
    assert spec.sa[0, 0] == pytest.approx(expected, rel=5e-3)


def test_metadata_carried_and_subset_scales(northridge):
    a = Record(northridge.accelerations, northridge.dt, name="a",
               metadata={"event": "E1", "rsn": 5, "lowest_usable_frequency_hz": 0.25})
    b = Record(northridge.accelerations, northridge.dt, name="b", metadata={"event": "E1",
                                                                          "rsn": 5})
    spec = record_spectra([a, b], [0.0, 1.0])
    assert spec.events == ("E1", "E1")
    assert spec.recordings[0] == spec.recordings[1]
    assert spec.usable_period_s[0] == 4.0 and math.isinf(spec.usable_period_s[1])
    sub = spec.subset([1], [2.0])
    np.testing.assert_allclose(sub.sa[0], 2 * spec.sa[1], rtol=1e-15)
    d = spec.to_dict()
    assert set(d) >= {"periods_s", "mean_sa_g", "records"}
    assert d["records"][1]["usable_period_s"] is None


def test_period_grid():
    np.testing.assert_allclose(period_grid(0.0, 2.0, 0.05), np.arange(41) * 0.05, atol=1e-12)
    assert period_grid(0.3, 0.3, 0.1).tolist() == [0.3]
    assert period_grid(0.1, 1.0, 0.4)[-1] == 1.0     # the stop is kept
    with pytest.raises(InvalidParameterError, match="START <= STOP"):
        period_grid(2.0, 1.0, 0.1)
    with pytest.raises(InvalidParameterError, match="period step must be > 0"):
        period_grid(0.0, 1.0, 0.0)
    with pytest.raises(InvalidParameterError, match="at most"):
        period_grid(0.0, 20.0, 1e-4)
