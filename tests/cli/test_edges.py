"""The command line's edges (issue 15): ranges named as typed in user units, output paths checked
before any computation, options that do not apply refused, one error prefix."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from archquake.cli.main import main

PULSE = ["--pulse", "step", "--magnitude", "0.5", "--duration", "0.1"]


def one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("archquake: error: "), err
    assert err.count("archquake: error") == 1 and "error: archquake" not in err, err
    return err


@pytest.mark.parametrize("argv, names", [
    # overflow and underflow the computation cannot represent (the 40 tracebacks)
    (["run", *PULSE, "--t-end", "1e308"], ("--t-end", "[0.01, 10000] s")),
    (["run", *PULSE, "--t-end", "1e150"], ("--t-end",)),
    (["run", "--model", "fourlink", *PULSE, "--restitution", "1e308"],
     ("--restitution", "[0, 1]")),
    (["run", *PULSE, "--depth", "1e-300"], ("--depth", "[0.001, 10000] m")),
    (["run", *PULSE, "--density", "1e-300"], ("--density", "kg/m^3")),
    (["static", "--thickness", "1e-300"], ("--thickness",)),
    (["run", "--pulse", "step", "--magnitude", "1e150", "--duration", "0.1"],
     ("--magnitude", "[0, 1000] g")),
    (["friction", "--pulse", "step", "--magnitude", "1", "--duration", "1e150"],
     ("--duration", "1000] s")),
    (["thrust", *PULSE, "--times", "1e308"], ("--times", "s")),
    (["domain", "--precision", "1e-300"], ("--precision", "g")),
    (["domain", "--max-magnitude", "1e150"], ("--max-magnitude", "g")),
    (["domain", "--scan", "1000000"], ("--scan",)),
    (["run", *PULSE, "--model", "dem", "--stiffness", "1e308"], ("--stiffness", "Pa/m")),
    (["run", *PULSE, "--model", "dem", "--stiffness", "1e-300"], ("--stiffness",)),
    (["run", *PULSE, "--model", "dem", "--t-end", "1e-300"], ("--t-end",)),
    (["run", *PULSE, "--model", "dem", "--damping", "1e-9,50"], ("--damping",)),
    (["run", *PULSE, "--model", "dem", "--rayleigh", "0,1"], ("--rayleigh BETA", "s")),
    (["run", *PULSE, "--model", "dem", "--friction", "nan"], ("--friction",)),
    (["sweep", "x.toml", "--workers", "0"], ("--workers",)),
    (["run", *PULSE, "--model", "dem", "--t-end", "500"], ("--t-end", "<= 120 s")),
    (["run", "--pulse", "step", "--magnitude", "0.5", "--duration", "900", "--model", "dem"],
     ("default --t-end", "<= 120 s")),
    (["static", "--method", "kinematic", "--voussoirs", "200"],
     ("--method kinematic", "--voussoirs <= 60", "--method static")),
])
def test_out_of_range_values_are_one_line_naming_the_option(capsys, argv, names):
    assert main(argv) == 2
    err = one_line(capsys)
    for name in names:
        assert name in err, (name, err)
    for internal in ("t_end", "max_magnitude_g", "normal_stiffness", "precision_g", "method="):
        assert internal not in err, err


@pytest.mark.parametrize("argv, names", [
    (["run", *PULSE, "--stiffness", "1e9"], ("--stiffness", "--model dem")),
    (["run", *PULSE, "--friction", "0.5", "--damping", "0.1,0.01"],
     ("--friction", "--damping", "--model dem")),
    (["run", *PULSE, "--dem-assembly", "hinges"], ("--dem-assembly",)),
    (["run", *PULSE, "--rayleigh", "0,0"], ("--rayleigh",)),
    (["domain", "--model", "fourlink", "--workers", "2"], ("--workers", "--model rigid or dem")),
    (["run", *PULSE, "--restitution", "0.5"], ("--restitution", "--model fourlink")),
])
def test_options_that_do_not_apply_are_refused(capsys, argv, names):
    assert main(argv) == 2
    err = one_line(capsys)
    for name in names:
        assert name in err, (name, err)


def test_thrust_times_refuses_an_empty_item(capsys):
    assert main(["thrust", *PULSE, "--times=1,,2"]) == 2
    err = one_line(capsys)
    assert "--times" in err and "empty item" in err


def test_a_usage_error_has_one_prefix_and_names_the_command(capsys):
    assert main(["static", "--radius", "abc"]) == 2
    err = one_line(capsys)
    assert err.startswith("archquake: error: static: argument --radius:")


@pytest.fixture
def in_tmp(tmp_path):
    old = os.getcwd()
    os.chdir(tmp_path)
    yield tmp_path
    os.chdir(old)


@pytest.mark.parametrize("argv, option", [
    (["static", "--plot", "{tmp}"], "--plot"),  # a directory: never {tmp}.png
    (["static", "--plot", "fig"], "--plot"),  # no suffix: refused, nothing added to it
    (["static", "--plot", "fig.zzz"], "--plot"),
    (["static", "--plot", "missing/fig.png"], "--plot"),
    (["static", "--plot", "/proc/fig.png"], "--plot"),  # not writable, even for root
    (["run", *PULSE, "--history", "{tmp}"], "--history"),
    (["run", *PULSE, "--history", "h.txt"], "--history"),
    (["run", *PULSE, "--animate", "a.png"], "--animate"),
    (["domain", "--csv", "missing/d.csv"], "--csv"),
    (["sweep", "x.toml", "--export", "rows.xlsx"], "--export"),
    (["sweep", "x.toml", "--store", "{tmp}"], "--store"),
    (["reproduce", "--out", "{tmp}/file.txt"], "--out"),
])
def test_output_paths_are_refused_before_any_computation(capsys, in_tmp, monkeypatch, argv, option):
    # the checks run first: reaching a computation (or the study file) fails the test
    import archquake.domains
    import archquake.mechanism
    import archquake.reproduce
    from archquake.cli import cmd_static, cmd_sweep

    def computed(*args, **kwargs):
        raise AssertionError("the computation ran before the output path was checked")

    for module, name in ((cmd_static, "limit_analysis"), (archquake.mechanism, "simulate"),
                         (archquake.domains, "failure_domain"), (cmd_sweep, "load_study"),
                         (archquake.reproduce, "run_studies")):
        monkeypatch.setattr(module, name, computed)
    (in_tmp / "file.txt").write_text("x")
    argv = [a.replace("{tmp}", str(in_tmp)) for a in argv]
    assert main(argv) == 2
    err = one_line(capsys)
    assert option in err, err
    assert not Path(f"{in_tmp}.png").exists()
    assert sorted(p.name for p in in_tmp.iterdir()) == ["file.txt"]


def test_plot_is_written_at_exactly_the_path_given(capsys, in_tmp):
    assert main(["static", "--voussoirs", "5", "--plot", "fig.svg"]) == 0
    assert (in_tmp / "fig.svg").stat().st_size > 1000
    assert sorted(p.name for p in in_tmp.iterdir()) == ["fig.svg"]
    assert "fig.svg" in capsys.readouterr().out


def test_record_units_on_an_at2_file_name_the_option(capsys, tmp_path):
    at2 = tmp_path / "q.AT2"
    at2.write_text("PEER\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     3, DT=   .0100 SEC\n"
                   "  1.0000000E-01 -3.0000000E-01  2.0000000E-01\n")
    assert main(["record", str(at2), "--units", "m/s2"]) == 2
    assert "--units" in one_line(capsys)


def test_record_time_step_outside_its_range_is_one_line(capsys, tmp_path):
    csv = tmp_path / "q.csv"
    csv.write_text("0,0.1\n1000000,0.2\n2000000,0.1\n")
    assert main(["run", "--record", str(csv), "--units", "g", "--t-end", "1"]) == 2
    err = one_line(capsys)
    assert "q.csv" in err and "time step" in err and "(0, 1]" in err


def test_friction_under_a_pulse_that_opens_every_joint_at_once_is_one_line(capsys):
    """3 g on a 5-voussoir arch: the four-link mechanism would need tension from t = 0, so there
    is no instant to take a friction demand from (was: argmax of an empty sequence)."""
    assert main(["friction", "--model", "fourlink", "--pulse", "step", "--magnitude", "3",
                 "--duration", "0.1", "--voussoirs", "5"]) == 2
    assert "loses contact" in one_line(capsys)
