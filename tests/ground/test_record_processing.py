"""One-column files, cm/s^2 (gal) units, baseline correction and resampling of records."""

from __future__ import annotations

import numpy as np
import pytest

from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.ground import Record, read_csv, read_record
from archquake.ground.records import baseline_corrected, resampled


# -------------------------------------------------------------------------------------
# one column with a stated dt; units
# -------------------------------------------------------------------------------------
def test_one_column_file_with_dt(tmp_path):
    path = tmp_path / "one.txt"
    path.write_text("# accelerations in g, dt = 0.01 s\nacc\n0.1\n-0.2\n0.3,\n0.05\n")
    rec = read_record(path, units="g", dt=0.01)
    assert rec == Record(np.array([0.1, -0.2, 0.3, 0.05]) * G, 0.01, name="one")
    assert rec.duration == pytest.approx(0.03)


@pytest.mark.parametrize(("units", "factor"), [("cm/s2", 0.01), ("gal", 0.01), ("cm/s^2", 0.01),
                                               ("m/s2", 1.0), ("g", G)])
def test_units(tmp_path, units, factor):
    path = tmp_path / "r.csv"
    path.write_text("0,981\n0.02,-490.5\n0.04,10\n")
    rec = read_csv(path, units=units)
    np.testing.assert_allclose(rec.accelerations, np.array([981, -490.5, 10]) * factor,
                               rtol=1e-15)


@pytest.mark.parametrize(
    ("content", "dt", "fragment"),
    [("0.1\n0.2\n", None, "line 1: expected 2 columns (time s, acceleration), found 1; for a "
                          "one-column file give its time step"),
     ("0,0.1\n0.01,0.2\n", 0.01, "line 1: expected 1 column (acceleration, dt = 0.01 s), found 2"),
     ("0.1\nx\n", 0.01, "line 2: 'x' is not a number"),
     ("0.1\n", 0.01, "has 1 data row(s); a record needs at least 2 rows of acceleration")],
)
def test_one_column_errors_name_file_and_line(tmp_path, content, dt, fragment):
    path = tmp_path / "q.txt"
    path.write_text(content)
    with pytest.raises(GroundMotionFormatError) as info:
        read_record(path, units="g", dt=dt)
    message = str(info.value)
    assert message.startswith(str(path)) and fragment in message and "\n" not in message


def test_dt_does_not_apply_to_at2(tmp_path):
    with pytest.raises(InvalidParameterError, match="states its own DT"):
        read_record(tmp_path / "x.AT2", dt=0.01)
    with pytest.raises(InvalidParameterError, match="time step dt must be > 0"):
        read_csv(tmp_path / "x.csv", units="g", dt=0.0)


# -------------------------------------------------------------------------------------
# baseline correction
# -------------------------------------------------------------------------------------
@pytest.mark.parametrize("order", [0, 1, 2, 3])
def test_baseline_removes_a_polynomial_of_its_order_exactly(order):
    """A baseline c_0 + ... + c_order t^order on a quiet record is in the fitted space: it is
    removed up to the difference between the velocity of the record's linear pieces and the
    polynomial's own, (dt^2/12) a'(t) by Euler-Maclaurin, which leaves a residual
    (dt^2/12) |a''| (< 1e-8 here; 0 for order <= 1). The correction is linear in the input, so
    correcting (record + baseline) gives the same as correcting the record."""
    dt = 0.01
    t = dt * np.arange(2001)
    rng = np.random.default_rng(order)
    coef = rng.normal(size=order + 1) * 0.1
    drift = sum(c * (t / 20.0) ** k for k, c in enumerate(coef))
    quiet = baseline_corrected(Record(drift, dt), order=order)
    second = np.max(np.abs(np.gradient(np.gradient(drift, dt), dt)))
    assert np.max(np.abs(quiet.accelerations)) < 1e-12 + 2 * dt**2 / 12 * second
    signal = np.sin(2 * np.pi * t) * np.exp(-((t - 8) ** 2) / 4)
    a = baseline_corrected(Record(signal, dt), order=order).accelerations
    b = baseline_corrected(Record(signal + drift, dt), order=order).accelerations
    np.testing.assert_allclose(a, b, atol=1e-12 + 2 * dt**2 / 12 * second)


def test_baseline_takes_out_the_velocity_drift():
    """An offset of 0.05 m/s^2 on a zero-mean record makes the velocity drift by 1 m/s over
    20 s; after the correction the final velocity is back to the record's own scale."""
    dt = 0.01
    t = dt * np.arange(2001)
    signal = np.sin(2 * np.pi * t) * np.exp(-((t - 8) ** 2) / 4)
    rec = Record(signal + 0.05, dt, metadata={"kept": 1})
    fixed = baseline_corrected(rec, order=0)

    def final_velocity(r):
        return float(np.sum(0.5 * r.dt * (r.accelerations[1:] + r.accelerations[:-1])))

    assert abs(final_velocity(rec)) == pytest.approx(1.0, rel=1e-3)
    assert abs(final_velocity(fixed)) < 0.02
    assert fixed.metadata == {"kept": 1, "baseline_order": 0} and fixed.name == rec.name


def test_baseline_order_range():
    with pytest.raises(InvalidParameterError, match="baseline order"):
        baseline_corrected(Record([0.0, 1.0], 0.1), order=6)


# -------------------------------------------------------------------------------------
# resampling
# -------------------------------------------------------------------------------------
def test_linear_refinement_keeps_the_motion():
    """The record is linear between samples, so refining by an integer factor with
    method='linear' keeps x_g''(t) everywhere (to rounding)."""
    rng = np.random.default_rng(3)
    rec = Record(rng.normal(size=200), 0.02)
    fine = resampled(rec, 0.005, method="linear")
    assert fine.points == 4 * 199 + 1 and fine.dt == 0.005
    t = np.linspace(0, rec.duration, 5003)
    np.testing.assert_allclose(fine.acceleration(t), rec.acceleration(t), atol=1e-12)
    assert fine.metadata["resampled_from_dt_s"] == 0.02


def test_polyphase_resampling_is_band_limited():
    """1 Hz + 40 Hz sampled at 200 Hz, resampled to 50 Hz (Nyquist 25 Hz): the anti-aliasing
    filter of resample_poly removes the 40 Hz part (what is left is the 1 Hz sine to
    < 1e-3 away from the ends, where the filter starts up), while linear sampling folds
    it onto 10 Hz at full amplitude. Upsampling reproduces a 1 Hz sine to < 1e-3."""
    dt = 0.005
    t = dt * np.arange(2001)
    rec = Record(np.sin(2 * np.pi * t) + np.sin(2 * np.pi * 40 * t), dt)
    coarse = resampled(rec, 0.02)
    inner = slice(20, -20)
    ref = np.sin(2 * np.pi * coarse.times)
    assert np.max(np.abs(coarse.accelerations - ref)[inner]) < 1e-3
    aliased = resampled(rec, 0.02, method="linear")
    assert np.max(np.abs(aliased.accelerations - ref)[inner]) > 0.9
    smooth = Record(np.sin(2 * np.pi * t), dt)
    for new_dt in (0.0025, 0.003):
        up = resampled(smooth, new_dt)
        assert up.points == int(np.floor(10.0 / new_dt + 1e-9)) + 1
        assert np.max(np.abs(up.accelerations - np.sin(2 * np.pi * up.times))[20:-20]) < 1e-3


def test_resampling_errors():
    rec = Record([0.0, 1.0, 0.0], 0.01)
    with pytest.raises(InvalidParameterError, match="longer than the record"):
        resampled(rec, 0.5)
    with pytest.raises(InvalidParameterError, match="p/q with p, q <= 1000"):
        resampled(rec, 0.01 * np.pi / 3.3)
    with pytest.raises(InvalidParameterError, match="'polyphase' or 'linear'"):
        resampled(rec, 0.005, method="cubic")


def test_component_and_metadata_travel_with_the_record():
    """Scaling and mirroring keep the provenance; == still compares name, dt and samples only."""
    rec = Record([0.0, 1.0, -1.0], 0.01, name="r", component="a", metadata={"event": "X"})
    for other in (rec.scaled(2.0), rec.mirrored()):
        assert other.component == "a" and other.metadata == {"event": "X"}
    assert rec == Record([0.0, 1.0, -1.0], 0.01, name="r")
    assert rec.to_dict()["component"] == "a" and rec.to_dict()["metadata"] == {"event": "X"}
