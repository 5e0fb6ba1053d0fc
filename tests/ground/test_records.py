"""Recorded accelerograms: the readers against a real record, the AT2 format against the same
data written as CSV, every malformed file against its one-line message, and the Record
motion against the compiled evaluator."""

from __future__ import annotations

import dataclasses
import importlib.resources
import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.ground import GroundMotion, Record, read_at2, read_csv, read_record
from archquake.ground._kernel import evaluate, ground_acceleration, ground_duration
from archquake.ground.base import KIND_SAMPLED

G = STANDARD_GRAVITY


# -- the real record (pyslammer, GPL: used in place at test time, never copied) ----------
@pytest.fixture(scope="module")
def northridge_csv():
    """pyslammer's Northridge 1994 PAC-175: 1000 points, dt = 0.02 s, PGA 0.415 g."""
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource / "Northridge_1994_PAC-175.csv") as path:
        yield Path(path)


@pytest.fixture(scope="module")
def northridge(northridge_csv) -> Record:
    return read_csv(northridge_csv, units="g")


def test_northridge_pac175_matches_its_published_description(northridge, northridge_csv):
    # Oracle: the record's stated properties (1000 points, dt 0.02 s, PGA 0.415 g; the PGA is
    # quoted to 3 digits, hence 0.5 %) and an independent parse with numpy.loadtxt.
    assert northridge.points == 1000
    assert northridge.dt == 0.02
    assert northridge.duration == pytest.approx(19.98, rel=1e-12)
    assert northridge.peak / G == pytest.approx(0.415, rel=5e-3)
    reference = np.loadtxt(northridge_csv, delimiter=",", comments="#")
    np.testing.assert_array_equal(northridge.accelerations, reference[:, 1] * G)
    assert northridge.name == "Northridge_1994_PAC-175"
    assert northridge.source == str(northridge_csv)
    assert isinstance(northridge, GroundMotion)


def test_csv_with_a_byte_order_mark_reads():
    # pyslammer's VSP-360 file starts with a UTF-8 BOM (and CRLF line ends).
    resource = importlib.resources.files("pyslammer") / "sample_ground_motions"
    with importlib.resources.as_file(resource / "Northridge_1994_VSP-360.csv") as path:
        assert Path(path).read_bytes().startswith(b"\xef\xbb\xbf")
        record = read_csv(path, units="g")
        reference = np.loadtxt(path, delimiter=",", comments="#", encoding="utf-8-sig")
    assert record.points == reference.shape[0]
    assert record.dt == 0.005
    np.testing.assert_array_equal(record.accelerations, reference[:, 1] * G)


# -- AT2 written from the same data must give the identical Record -----------------------
def write_at2(path: Path, values_g: np.ndarray, dt: float, *, style: str, per_line: int = 5,
              trailing_comma: bool = False, units_line: str | None = None) -> Path:
    """Write a PEER .AT2 file: 'west2' (NPTS=, DT=) or 'old' (NPTS, DT after the numbers)."""
    header = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        "NORTHRIDGE 01/17/94 1231, PACOIMA DAM (DOWNSTR), 175",
        units_line or "ACCELERATION TIME SERIES IN UNITS OF G",
    ]
    if style == "west2":
        header.append(f"NPTS= {len(values_g):6d}, DT= {f'{dt:.4f}'.lstrip('0')} SEC")
    else:
        header.append(f"  {len(values_g)}   {dt:.5f}   NPTS, DT")
    rows = []
    for i in range(0, len(values_g), per_line):
        row = "".join(f"{v:15.7E}" for v in values_g[i:i + per_line])
        rows.append(row + ("," if trailing_comma else ""))
    path.write_text("\n".join(header + rows) + "\n")
    return path


@pytest.mark.parametrize(
    ("style", "per_line", "trailing_comma"),
    [("west2", 5, False), ("old", 5, False), ("west2", 3, True), ("old", 7, False)],
    ids=["west2", "old", "west2-short-last-line-trailing-comma", "old-short-last-line"],
)
def test_at2_of_the_same_data_gives_the_identical_record(
    tmp_path, northridge, style, per_line, trailing_comma
):
    # Oracle: the CSV reading of the same record. %15.7E keeps every digit the CSV holds
    # (at most 6 significant), so the values, dt and name must be bit-identical.
    values_g = northridge.accelerations / G
    text_values = np.loadtxt(northridge.source, delimiter=",", comments="#")[:, 1]
    np.testing.assert_array_equal(np.array([float(f"{v:15.7E}") for v in text_values]),
                                  text_values)
    path = write_at2(tmp_path / "Northridge_1994_PAC-175.AT2", text_values, 0.02,
                     style=style, per_line=per_line, trailing_comma=trailing_comma)
    assert style != "west2" or ".0200" in path.read_text().splitlines()[3]  # leading-dot decimal
    record = read_at2(path)
    assert record == northridge
    assert record.dt == northridge.dt
    np.testing.assert_array_equal(record.accelerations, northridge.accelerations)
    assert record.source == str(path)
    assert read_record(path) == northridge  # dispatch on the (upper-case) extension
    np.testing.assert_allclose(values_g, text_values, rtol=1e-15)


def test_scale_and_gravity_are_applied_once(tmp_path):
    # Oracle: the definition x_g'' = scale * value * g, in both readers.
    path = write_at2(tmp_path / "r.at2", np.array([0.1, -0.2, 0.3]), 0.01, style="west2")
    record = read_at2(path, scale=2.0, g=10.0)
    np.testing.assert_allclose(record.accelerations, [2.0, -4.0, 6.0], rtol=1e-15)
    assert record.scale == 2.0
    csv = tmp_path / "r.csv"
    csv.write_text("0,0.1\n0.01,-0.2\n0.02,0.3\n")
    np.testing.assert_allclose(read_csv(csv, units="m/s2", scale=3.0).accelerations,
                               [0.3, -0.6, 0.9], rtol=1e-15)
    np.testing.assert_allclose(read_csv(csv, units="g").accelerations,
                               np.array([0.1, -0.2, 0.3]) * G, rtol=1e-15)


# -- CSV rules -------------------------------------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "# comment\n0.0,1.0\n0.5,2.0\n1.0,-1.0\n",
        "time (s),acc (g)\n0.0,1.0\n0.5,2.0\n1.0,-1.0\n",
        "0.0 1.0\n0.5\t2.0\n\n1.0   -1.0\n",
        "0.0,1.0,\n0.5,2.0,\n1.0,-1.0,\n",
        "\ufeff# Time (s),Acceleration (g's)\r\n0.0,1.0\r\n0.5,2.0\r\n1.0,-1.0\r\n",
        "5.0,1.0\n5.5,2.0\n6.0,-1.0\n",  # starts at 5 s: shifted to t = 0
    ],
    ids=["comment", "header-row", "whitespace", "trailing-comma", "bom-crlf", "shifted-start"],
)
def test_csv_variants_give_the_same_record(tmp_path, text):
    path = tmp_path / "r.csv"
    path.write_text(text, encoding="utf-8")
    record = read_csv(path, units="m/s2")
    assert record == Record([1.0, 2.0, -1.0], 0.5, name="r")
    assert record.t0 == 0.0


def test_spacing_tolerance_is_relative_to_dt(tmp_path):
    # Written times carry rounding (1e-12 of dt here): accepted. A 1e-4 dt jitter is not an
    # even grid (the limit is 1e-6 dt): rejected at the row that jumps.
    t = 0.01 * np.arange(50)
    ok = t + 1e-14 * np.sin(np.arange(50))
    (tmp_path / "ok.csv").write_text("".join(f"{float(x)!r},{i}\n" for i, x in enumerate(ok)))
    assert read_csv(tmp_path / "ok.csv", units="g").dt == 0.01
    bad = t.copy()
    bad[20] += 1e-6
    (tmp_path / "bad.csv").write_text("".join(f"{float(x)!r},{i}\n" for i, x in enumerate(bad)))
    with pytest.raises(GroundMotionFormatError, match=r"line 21: .*even|line 21: .*time step"):
        read_csv(tmp_path / "bad.csv", units="g")


# -- malformed files: one line naming the file, the line, the problem and the fix ---------
HEADER = ("PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, DATE, STATION, 000\n"
          "ACCELERATION TIME SERIES IN UNITS OF G\n")
MALFORMED = [
    # (file name, content, line, fragment of the message)
    ("uneven.csv", "0,1\n0.01,2\n0.02,3\n0.04,4\n0.05,5\n", 4, "resample"),
    ("repeated.csv", "0,1\n0.01,2\n0.01,3\n", 3, "does not increase"),
    ("backwards.csv", "0,1\n-0.01,2\n", 2, "dt must be > 0"),
    ("nan.csv", "0,1\n0.01,nan\n0.02,3\n", 2, "not finite"),
    ("text.csv", "0,1\n0.01,abc\n0.02,3\n", 2, "'abc' is not a number"),
    ("columns.csv", "0,1,5\n0.01,2,5\n", 1, "expected 2 columns"),
    ("one.csv", "# t, a\n0,1\n", None, "at least 2"),
    ("empty.csv", "", None, "empty"),
    ("blank.at2", "\n  \n", None, "empty"),
    ("noheader.at2", "1.0E-02 2.0E-02\n3.0E-02\n", 1, "four header lines"),
    ("short.at2", "PEER\nEVENT\n", None, "four header lines"),
    ("garbled.at2", HEADER + "THE TIME STEP IS SMALL\n 1.0 2.0\n", 4, "expected NPTS and DT"),
    ("truncated.at2", HEADER + "NPTS=     5, DT=   .0100 SEC\n 1.0 2.0 3.0 4.0\n", 4,
     "NPTS = 5 but the file holds 4"),
    ("extra.at2", HEADER + "  3   0.01000   NPTS, DT\n 1.0 2.0 3.0 4.0\n", 4,
     "NPTS = 3 but the file holds 4"),
    ("nan.at2", HEADER + "NPTS=     3, DT=   .0100 SEC\n 1.0\n NaN 3.0\n", 6, "not finite"),
    ("text.at2", HEADER + "NPTS=     3, DT=   .0100 SEC\n 1.0 x2 3.0\n", 5, "'x2' is not"),
    ("zero-dt.at2", HEADER + "NPTS=     3, DT=   .0000 SEC\n 1.0 2.0 3.0\n", 4, "DT must be"),
    ("one.at2", HEADER + "NPTS=     1, DT=   .0100 SEC\n 1.0\n", 4, "at least 2"),
    ("velocity.at2",
     HEADER.replace("ACCELERATION", "VELOCITY").replace("UNITS OF G", "UNITS OF CM/S")
     + "NPTS=     2, DT=   .0100 SEC\n 1.0 2.0\n", 3, "velocity"),
    ("cgs.at2", HEADER.replace("UNITS OF G", "UNITS OF CM/S/S")
     + "NPTS=     2, DT=   .0100 SEC\n 1.0 2.0\n", 3, "'CM/S/S'"),
    ("record.vt2", HEADER + "NPTS=     2, DT=   .0100 SEC\n 1.0 2.0\n", None, "velocity file"),
    ("record.dat", "0,1\n0.01,2\n", None, "unknown extension"),
]


@pytest.mark.parametrize(("name", "content", "line", "fragment"), MALFORMED,
                         ids=[m[0] for m in MALFORMED])
def test_malformed_file_gives_one_line(tmp_path, name, content, line, fragment):
    path = tmp_path / name
    path.write_text(content)
    with pytest.raises(GroundMotionFormatError) as info:
        read_record(path, units="g")
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path))
    assert fragment in message
    if line is not None:
        assert f": line {line}: " in message
    else:
        assert ": line " not in message


def test_missing_file_and_directory(tmp_path):
    for path in (tmp_path / "nowhere.AT2", tmp_path / "nowhere.csv"):
        with pytest.raises(GroundMotionFormatError, match="no such file; check the path"):
            read_record(path, units="g")
    (tmp_path / "dir.csv").mkdir()
    with pytest.raises(GroundMotionFormatError, match="is a directory"):
        read_record(tmp_path / "dir.csv", units="g")


def test_csv_units_must_be_stated(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text("0,1\n0.01,2\n")
    with pytest.raises(InvalidParameterError, match="units of r.csv must be given"):
        read_record(path)
    with pytest.raises(InvalidParameterError, match="units must be 'g', 'm/s2' or 'cm/s2'"):
        read_csv(path, units="mm/s2")
    with pytest.raises(TypeError):
        read_csv(path)  # type: ignore[call-arg]  # no silent default in the library
    at2 = write_at2(tmp_path / "r.at2", np.array([1.0, 2.0]), 0.01, style="old")
    with pytest.raises(InvalidParameterError, match="in g by definition"):
        read_record(at2, units="m/s2")


# -- the Record motion -----------------------------------------------------------------
samples = st.lists(st.floats(-20.0, 20.0, allow_nan=False), min_size=2, max_size=40)
steps = st.floats(1e-3, 0.5)


@given(samples, steps, st.lists(st.floats(-0.2, 1.2), min_size=1, max_size=20))
@settings(max_examples=60, deadline=None)
# found by hypothesis: (n-1) dt / dt rounds above n-1, which once dropped the last sample
@example([0.0, 0.0, 0.0, 0.0, 0.0, 1.0], 0.21333258726368454, [1.0])
def test_kernel_equals_python_acceleration_everywhere(values, dt, fractions):
    # Oracles: the compiled evaluator (same arithmetic, so agreement to rounding: 1e-13 of
    # the peak) and numpy.interp (independent linear interpolation, zero outside).
    record = Record(values, dt)
    kind, params = record.kernel_spec()
    assert kind == KIND_SAMPLED
    times = np.concatenate([
        np.asarray(fractions) * record.duration,           # arbitrary, inside and outside
        record.times, record.times[:-1] + 0.5 * dt,        # on samples and between them
        [-dt, -1e-9, record.duration, record.duration * (1 + 1e-12) + 1e-12, 2 * record.duration],
    ])
    python = record.acceleration(times)
    compiled = evaluate(kind, params, times)
    scale = max(record.peak, 1.0)
    np.testing.assert_allclose(compiled, python, rtol=0, atol=1e-13 * scale)
    inside = (times >= 0) & (times <= record.duration)
    reference = np.where(inside, np.interp(times, record.times, record.accelerations), 0.0)
    np.testing.assert_allclose(python, reference, rtol=0, atol=1e-9 * scale)
    assert ground_duration(kind, params) == pytest.approx(record.duration, rel=1e-15)
    assert float(ground_acceleration(kind, params, record.duration + dt)) == 0.0


def test_acceleration_on_samples_between_and_outside():
    record = Record([0.0, 2.0, -4.0], 0.1)
    np.testing.assert_array_equal(record.acceleration([-0.01, 0.0, 0.1, 0.2, 0.2001]),
                                  [0.0, 0.0, 2.0, -4.0, 0.0])
    # 0.15 / 0.1 is 1.4999999999999998 in binary: agreement to a few ulp of the values
    assert float(record.acceleration(0.15)) == pytest.approx(-1.0, abs=1e-14)
    np.testing.assert_array_equal(record.breakpoints(), record.times)
    assert record.breakpoints()[-1] == pytest.approx(record.duration)


def test_mirrored_and_scaled(northridge):
    # Oracles: the definitions, and their group structure (mirror twice = identity,
    # scaled(-1) = mirrored, scaled(a).scaled(b) = scaled(a b), PGA scales with |factor|).
    m = northridge.mirrored()
    np.testing.assert_array_equal(m.accelerations, -northridge.accelerations)
    assert m.mirrored() == northridge
    assert northridge.scaled(-1.0) == m
    assert northridge.scaled(2.0).scaled(0.5) == northridge  # powers of two: exact
    assert northridge.scaled(-3.0).peak == pytest.approx(3.0 * northridge.peak, rel=1e-15)
    assert (m.scale, northridge.scaled(2.0).scale) == (-1.0, 2.0)
    t = np.linspace(-1.0, 21.0, 501)
    np.testing.assert_array_equal(m.acceleration(t), -northridge.acceleration(t))
    with pytest.raises(InvalidParameterError, match="scale factor"):
        northridge.scaled(float("nan"))


def test_record_is_an_immutable_value(northridge):
    with pytest.raises(dataclasses.FrozenInstanceError):
        northridge.dt = 0.01  # type: ignore[misc]
    with pytest.raises(ValueError):
        northridge.accelerations[0] = 1.0
    assert hash(northridge) == hash(read_csv(northridge.source, units="g"))
    d = json.loads(json.dumps(northridge.to_dict()))
    assert d["points"] == 1000 and d["dt_s"] == 0.02
    assert d["pga_g"] == pytest.approx(0.415325, rel=1e-12)
    assert d["pga_m_s2"] == pytest.approx(0.415325 * G, rel=1e-12)
    assert d["time_of_pga_s"] == pytest.approx(
        0.02 * int(np.argmax(np.abs(northridge.accelerations))))


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"accelerations": [1.0], "dt": 0.01}, "at least 2 samples"),
        ({"accelerations": [[1.0, 2.0]], "dt": 0.01}, "1-D"),
        ({"accelerations": [1.0, math.nan], "dt": 0.01}, "finite"),
        ({"accelerations": [1.0, 2.0], "dt": 0.0}, r"dt must be in \(0, 1\]"),
        ({"accelerations": [1.0, 2.0], "dt": -0.01}, r"dt must be in \(0, 1\]"),
        ({"accelerations": ["a", "b"], "dt": 0.01}, "sequence of real numbers"),
    ],
)
def test_record_validates_its_inputs(kwargs, fragment):
    with pytest.raises(InvalidParameterError, match=fragment) as info:
        Record(**kwargs)
    assert "\n" not in str(info.value)
