"""No silent mistake on the command line: a CSV record needs --units, a value far outside
practice (a unit slip: m/s^2 typed as g, ms as s, cm as m, radians as degrees) is warned about in
one line naming the option as typed, and a run made too long by its pulse names the pulse's
option and the step it would use.

Oracle: the unit slips themselves. 9.81 (m/s^2 typed as g) is above ranges.PLAUSIBLE_PGA_G; a
CSV in cm/s^2 read as g has a PGA of hundreds of g; 270 (ms typed as s) is above
ranges.PLAUSIBLE_PULSE_S; pi (radians typed as degrees) is below ranges.RADIANS_EMBRACE_DEG.
Values inside practice print nothing on stderr.
"""

from __future__ import annotations

import json
import math

import pytest

from archquake.cli import main as cli_main
from archquake.ranges import PLAUSIBLE_PGA_G, PLAUSIBLE_PULSE_S, PLAUSIBLE_RADIUS_M

FOURLINK = ["run", "--model", "fourlink", "--json"]


@pytest.fixture
def cms_csv(tmp_path):
    """A record in cm/s^2 (gal), peak 540 gal = 0.551 g: a CSV file does not say so."""
    path = tmp_path / "quake.csv"
    path.write_text("time,acc\n" + "\n".join(
        f"{0.01 * i:.2f},{540.0 * math.sin(math.pi * i / 20) if i < 20 else 0.0:.6g}"
        for i in range(60)) + "\n")
    return path


@pytest.fixture
def at2_file(tmp_path):
    path = tmp_path / "quake.AT2"
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, STATION, 000\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     4, DT=   .0100 SEC\n"
                    "  1.0000000E-01 -3.0000000E-01  2.0000000E-01  0.0000000E+00\n")
    return path


def _refused(capsys) -> str:
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err, captured.err
    assert lines[0].startswith("archquake: error: ")
    assert captured.out == ""
    return lines[0]


def _warnings(capsys) -> list[str]:
    captured = capsys.readouterr()
    return [line for line in captured.err.splitlines() if line.startswith("archquake: warning:")]


# ------------------------------------------------------------------------------ --units of a CSV
@pytest.mark.parametrize("argv", [
    ["record", "FILE"],
    ["records", "FILE"],
    ["run", "--model", "fourlink", "--record", "FILE"],
    ["ida", "--records", "FILE"],
])
def test_a_csv_without_units_is_refused_naming_units_and_its_choices(argv, cms_csv, capsys):
    assert cli_main.main([str(cms_csv) if a == "FILE" else a for a in argv]) == 2
    line = _refused(capsys)
    assert "--units" in line and "quake.csv" in line
    assert "{g,m/s2,cm/s2,gal}" in line


def test_the_units_given_are_used(cms_csv, capsys):
    # Oracle: 540 gal = 5.4 m/s^2 = 0.5506 g.
    assert cli_main.main(["record", str(cms_csv), "--units", "cm/s2", "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["pga_g"] == pytest.approx(5.4 / 9.80665, rel=1e-6)
    assert captured.err == ""


def test_an_at2_file_needs_no_units(at2_file, capsys):
    assert cli_main.main(["record", str(at2_file), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["pga_g"] == pytest.approx(0.3, rel=1e-12)


# --------------------------------------------------------------- peak ground accelerations, g
def test_cm_s2_typed_as_g_is_warned_naming_units(cms_csv, capsys):
    assert cli_main.main(["record", str(cms_csv), "--units", "g", "--json"]) == 0
    (line,) = _warnings(capsys)
    assert "--units g" in line and "540 g" in line and f"{PLAUSIBLE_PGA_G:g} g" in line


def test_a_scale_past_the_plausible_pga_is_warned_naming_scale(cms_csv, capsys):
    # 0.5506 g x 3 = 1.65 g > 1.5 g; x 2 = 1.10 g is within practice
    assert cli_main.main(["record", str(cms_csv), "--units", "cm/s2", "--scale", "2",
                          "--json"]) == 0
    assert _warnings(capsys) == []
    assert cli_main.main(["run", "--model", "fourlink", "--record", str(cms_csv), "--units",
                          "cm/s2", "--scale", "3", "--json"]) == 0
    (line,) = _warnings(capsys)
    assert line.startswith("archquake: warning: --scale 3 ") and "1.65 g" in line


def test_a_peer_file_past_the_plausible_pga_is_warned_naming_the_file(tmp_path, capsys):
    path = tmp_path / "strong.AT2"
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, STATION, 000\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     3, DT=   .0100 SEC\n"
                    "  1.0000000E-01 -2.0000000E+00  2.0000000E-01\n")
    assert cli_main.main(["record", str(path), "--json"]) == 0
    (line,) = _warnings(capsys)
    assert line.startswith("archquake: warning: strong.AT2 has a PGA of 2 g, above 1.5 g")


def test_magnitude_in_m_s2_is_warned_and_the_run_goes_on(capsys):
    assert cli_main.main([*FOURLINK, "--pulse", "step", "--magnitude", "9.81",
                          "--duration", "0.1"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["excitation"]["magnitude_g"] == 9.81
    (line,) = [x for x in captured.err.splitlines() if "warning" in x]
    assert line.startswith("archquake: warning: --magnitude 9.81 g is above 1.5 g")
    assert "m/s^2" in line


def test_values_within_practice_print_no_warning(capsys):
    assert cli_main.main([*FOURLINK, "--pulse", "sine", "--magnitude", f"{PLAUSIBLE_PGA_G:g}",
                          "--period", f"{PLAUSIBLE_PULSE_S:g}"]) == 0
    assert capsys.readouterr().err == ""
    assert cli_main.main(["static", "--radius", f"{PLAUSIBLE_RADIUS_M:g}", "--thickness", "0.03",
                          "--embrace", "7", "--voussoirs", "3", "--json"]) in (0, 2)
    err = capsys.readouterr().err  # 7 degrees is a strut (no mechanism), not radians
    assert "warning" not in err and "--embrace" not in err
    assert cli_main.main(["static", "--radius", f"{PLAUSIBLE_RADIUS_M:g}", "--thickness", "0.03",
                          "--json"]) == 0
    assert capsys.readouterr().err == ""


def test_site_ag_above_practice_is_warned(capsys):
    assert cli_main.main(["spectrum", "--code", "ec8", "--ag", "2.5", "--json"]) == 0
    (line,) = _warnings(capsys)
    assert line.startswith("archquake: warning: --ag 2.5 g is above 1.5 g")


def test_a_warning_never_joins_a_refusal(capsys):
    """The magnitude is warned about only once the command has run: a refusal met later on the
    same command line stays one line (exit 2)."""
    assert cli_main.main([*FOURLINK, "--pulse", "step", "--magnitude", "9.81",
                          "--duration", "0.1", "--friction", "0.5"]) == 2
    assert "--friction" in _refused(capsys)


# ---------------------------------------------------------------------------- pulse lengths, s
@pytest.mark.parametrize("pulse, option", [("step", "--duration"), ("sine", "--period")])
def test_a_pulse_longer_than_practice_is_warned(pulse, option, capsys):
    assert cli_main.main([*FOURLINK, "--pulse", pulse, "--magnitude", "0.5", option,
                          "12"]) == 0
    (line,) = _warnings(capsys)
    assert line.startswith(f"archquake: warning: {option} 12 s is longer than "
                           f"{PLAUSIBLE_PULSE_S:g} s")


def test_domain_durations_past_practice_are_warned(capsys):
    from archquake.cli.common import parse_durations
    from archquake.cli.input_warnings import take_input_warnings

    take_input_warnings()
    parse_durations("0.05:1.5:40")
    assert take_input_warnings() == []
    parse_durations("0.1:20:3")
    assert take_input_warnings() == [
        f"archquake: warning: --durations 0.1:20:3 reaches 20 s, longer than "
        f"{PLAUSIBLE_PULSE_S:g} s, beyond any recorded pulse: is it in s (not ms)?"]


@pytest.mark.parametrize("pulse, option", [("step", "--duration"), ("sine", "--period")])
def test_a_run_too_long_for_its_pulse_names_the_pulse_option_and_its_step(pulse, option, capsys):
    """270 (ms typed as s) with 150 voussoirs: the run to a verdict would be twice the pulse
    (3 x 270 s for the step, 270 s for the sine) and 60 sqrt(R/g) more at the verdict's step,
    beyond the work bound. The user gave no --t-end: the refusal names the
    option at fault and the step the run would take (the verdict path's)."""
    from archquake.geometry import Arch
    from archquake.rigid.verdict import verdict_time_step

    assert cli_main.main(["run", "--pulse", pulse, "--magnitude", "0.5", option, "270",
                          "--voussoirs", "150"]) == 2
    line = _refused(capsys)
    step = verdict_time_step(Arch(10.0, 1.5, math.radians(157.5), 150))
    assert f"a shorter {option}" in line and "--t-end" not in line
    assert f"time steps of {step:.3g} s" in line


def test_a_dem_run_too_long_for_its_pulse_names_the_pulse_option(capsys):
    """The DEM's default end is the excitation's (3 x 900 s) + 5 sqrt(R/g), above 120 s."""
    assert cli_main.main(["run", "--model", "dem", "--pulse", "step", "--magnitude", "0.5",
                          "--duration", "900"]) == 2
    assert "give a shorter --duration, or a --t-end" in _refused(capsys)


def test_a_given_t_end_is_still_the_option_named(capsys):
    assert cli_main.main(["run", "--pulse", "step", "--magnitude", "0.5", "--duration", "0.2",
                          "--voussoirs", "100", "--t-end", "900"]) == 2
    assert "a shorter --t-end" in _refused(capsys)


# ----------------------------------------------------------------------------------- geometry
def test_a_radius_below_practice_is_warned(capsys):
    assert cli_main.main(["static", "--radius", "0.1", "--thickness", "0.02", "--json"]) == 0
    (line,) = _warnings(capsys)
    assert line.startswith(f"archquake: warning: --radius 0.1 m is below "
                           f"{PLAUSIBLE_RADIUS_M:g} m")


@pytest.mark.parametrize("embrace", ["3.1416", "2.75", "6.28"])
def test_an_embrace_in_radians_is_refused_saying_degrees(embrace, capsys):
    assert cli_main.main(["static", "--embrace", embrace]) == 2
    line = _refused(capsys)
    assert f"--embrace {embrace} looks like radians" in line and "in degrees" in line
    degrees = math.degrees(float(embrace))
    assert f"({degrees:.4g} degrees)" in line
