"""The excitation options: each combination builds the motion it names (in SI, with the
paper's sign), and every option that would be ignored is an error instead."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from archquake.cli.common import add_ground_motion_arguments, ground_motion_from_args
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.ground import Record, SinePulse, StepImpulse

G = STANDARD_GRAVITY


def parse(*argv: str, g: float = G):
    parser = argparse.ArgumentParser(prog="t")
    add_ground_motion_arguments(parser)
    return ground_motion_from_args(parser.parse_args(list(argv)), g=g)


@pytest.fixture
def csv_file(tmp_path):
    path = tmp_path / "quake.csv"
    path.write_text("# Time (s),Acceleration (g's)\n0.0,0.1\n0.01,-0.3\n0.02,0.2\n")
    return path


@pytest.fixture
def at2_file(tmp_path):
    path = tmp_path / "quake.AT2"
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, STATION, 000\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     3, DT=   .0100 SEC\n"
                    "  1.0000000E-01 -3.0000000E-01  2.0000000E-01\n")
    return path


def test_step_pulse_in_g_towards_minus_x():
    # Oracle: the CLI takes g, the library m/s^2; the first lobe is towards -x (paper Fig. 1).
    motion = parse("--pulse", "step", "--magnitude", "0.37", "--duration", "0.25")
    assert motion == StepImpulse(0.37 * G, 0.25, -1)
    assert float(motion.acceleration(0.1)) == pytest.approx(-0.37 * G, rel=1e-15)


def test_sine_pulse_and_mirror():
    motion = parse("--pulse", "sine", "--magnitude", "0.2", "--period", "0.5", "--mirror")
    assert motion == SinePulse(0.2 * G, 0.5, +1)
    assert float(motion.acceleration(0.125)) == pytest.approx(0.2 * G, rel=1e-15)


def test_given_gravity_is_used():
    assert parse("--pulse", "step", "--magnitude", "1", "--duration", "0.1", g=9.81).magnitude \
        == 9.81


def test_csv_record_needs_units_and_honours_units_scale_mirror(csv_file):
    # A CSV file does not say its units: none is assumed (cm/s^2 read as g is 981 times too much)
    with pytest.raises(InvalidParameterError, match=r"quake.csv needs --units \{g,m/s2,cm/s2"):
        parse("--record", str(csv_file))
    base = parse("--record", str(csv_file), "--units", "g")
    assert isinstance(base, Record)
    np.testing.assert_allclose(base.accelerations, np.array([0.1, -0.3, 0.2]) * G, rtol=1e-15)
    si = parse("--record", str(csv_file), "--units", "m/s2")
    np.testing.assert_allclose(si.accelerations, [0.1, -0.3, 0.2], rtol=1e-15)
    scaled = parse("--record", str(csv_file), "--units", "g", "--scale", "2", "--mirror")
    np.testing.assert_allclose(scaled.accelerations, -2 * base.accelerations, rtol=1e-15)
    assert scaled.scale == -2.0


def test_at2_record_is_in_g(at2_file, csv_file):
    # Oracle: the same values written as CSV in g.
    assert parse("--record", str(at2_file)) == parse("--record", str(csv_file), "--units", "g")
    with pytest.raises(InvalidParameterError, match="--units m/s2 does not apply to quake.AT2"):
        parse("--record", str(at2_file), "--units", "m/s2")


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        ((), "no excitation: give --pulse"),
        (("--pulse", "step", "--magnitude", "0.3", "--duration", "0.1", "--record", "x.csv"),
         "--record excludes --pulse"),
        (("--pulse", "step", "--magnitude", "0.3"), "--pulse step needs --duration"),
        (("--pulse", "step", "--duration", "0.1"), "--pulse step needs --magnitude"),
        (("--pulse", "step", "--magnitude", "0.3", "--duration", "0.1", "--period", "1"),
         "--period applies to --pulse sine"),
        (("--pulse", "sine", "--magnitude", "0.3"), "--pulse sine needs --period"),
        (("--pulse", "sine", "--magnitude", "0.3", "--period", "1", "--duration", "0.1"),
         "--duration applies to --pulse step"),
        (("--pulse", "step", "--magnitude", "-0.3", "--duration", "0.1"),
         "--magnitude must be in [0, 1000] g"),
        (("--pulse", "sine", "--magnitude", "0.3", "--period", "0"), "--period must be in [1e-06, 1000] s"),
        (("--pulse", "step", "--magnitude", "0.3", "--duration", "-1"),
         "--duration must be in [1e-06, 1000] s"),
        (("--pulse", "step", "--magnitude", "0.3", "--duration", "0.1", "--scale", "2"),
         "--scale applies to --record"),
        (("--pulse", "step", "--magnitude", "0.3", "--duration", "0.1", "--units", "g"),
         "--units applies to --record"),
        (("--record", "RECORD", "--magnitude", "0.3"), "--magnitude applies to --pulse"),
        (("--record", "RECORD", "--period", "1"), "--period applies to --pulse"),
        (("--record", "RECORD", "--scale", "0"), "--scale must be in (0, 1000]"),
        (("--record", "RECORD", "--scale", "-1"), "use --mirror"),
    ],
)
def test_bad_combinations_give_one_line(argv, fragment, csv_file):
    argv = tuple(str(csv_file) if a == "RECORD" else a for a in argv)
    with pytest.raises(InvalidParameterError) as info:
        parse(*argv)
    assert fragment in str(info.value)
    assert "\n" not in str(info.value)


def test_malformed_record_is_a_format_error(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("0,1\n0.01,2\n0.03,3\n")
    with pytest.raises(GroundMotionFormatError, match="bad.csv: line 3"):
        parse("--record", str(bad), "--units", "g")


def test_help_states_units_and_direction():
    parser = argparse.ArgumentParser(prog="t")
    add_ground_motion_arguments(parser)
    text = " ".join(parser.format_help().split())
    for phrase in ("in g", "towards -x", "required with a CSV", "TP", "s (1e-06 to 1000)", ".AT2",
                   "towards +x"):
        assert phrase in text, phrase
