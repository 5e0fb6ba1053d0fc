"""A bad assessment file: one line naming the key, exit status 2, and nothing computed (the
assessment itself is replaced by a function that fails the test if it is ever called)."""

from __future__ import annotations

import math

import pytest

from archquake.cli.main import main

GOOD = """
[arch]
radius = 5.0
thickness_ratio = 0.12
embrace_deg = 180
voussoirs = 15
friction = 0.6
[seismic]
site_pga_g = 0.15
"""

BAD = {
    "unknown key": (GOOD.replace("voussoirs = 15", "voussoirs = 15\nspan_m = 3"), "[arch] span_m"),
    "unknown table": (GOOD + "\n[extras]\nx = 1\n", "[extras]"),
    "missing arch": ("[seismic]\nsite_pga_g = 0.15\n", "[arch]"),
    "missing friction": (GOOD.replace("friction = 0.6", ""), "[arch] friction"),
    "record file missing": (GOOD + 'suite = ["no/such/record.AT2"]\n', "[seismic] suite"),
    "record folder missing": (GOOD + 'suite = "no_such_folder"\n', "[seismic] suite"),
    "bad restitution": (GOOD + '[options]\nmodel = "fourlink"\nrestitution = 1.5\n',
                        "[options] restitution must be in (0, 1]"),
    "bad impact": (GOOD + '[options]\nmodel = "fourlink"\nimpact = "elastic"\n',
                   "[options] impact"),
    "restitution with the rigid chain": (GOOD + "[options]\nrestitution = 0.8\n",
                                         '[options] restitution applies to model = "fourlink"'),
    "impact with the rigid chain": (GOOD + '[options]\nmodel = "rigid"\nimpact = "chain"\n',
                                    '[options] impact applies to model = "fourlink"'),
    "dem as the model": (GOOD + '[options]\nmodel = "dem"\n',
                         "[options] model must be one of ['rigid', 'fourlink']"),
    "arch mixture": (GOOD.replace("voussoirs = 15", "voussoirs = 15\nspan = 10"), "[arch]"),
    "arch too thin": (GOOD.replace("0.12", "0.05"), "[arch]"),
    "not toml": ("[arch\nradius = 1", "not valid TOML"),
    "embrace in radians": (GOOD.replace("embrace_deg = 180", "embrace_deg = 3.1416"),
                           "[arch] embrace_deg = 3.1416 looks like radians (180 degrees)"),
    "piers too slender": (GOOD.replace("voussoirs = 15", "voussoirs = 15\npier_height = 6.0\n"
                                       "pier_width = 0.6\npier_courses = 3"),
                          "[arch] pier_width = 0.6 m is too narrow"),
    "site without soil": (GOOD.replace("site_pga_g = 0.15", "") + "[site]\nhazard = [[50, 0.05, "
                          "2.5, 0.26], [475, 0.15, 2.45, 0.3]]\n", "[site] soil is missing"),
    "site PGA against the site table": (GOOD + "[site]\nsoil = \"B\"\nhazard = [[50, 0.05, 2.5, "
                                        "0.26], [475, 0.15, 2.45, 0.3]]\n",
                                        "[seismic] site_pga_g = 0.15 g differs from the [site]"),
}


@pytest.fixture
def no_computation(monkeypatch):
    import archquake.assess as assess

    def fail(*args, **kwargs):
        raise AssertionError("the assessment started although the file is invalid")

    monkeypatch.setattr(assess, "run_assessment", fail)


@pytest.mark.parametrize("case", list(BAD))
def test_bad_file_is_one_line_exit_2_before_any_computation(case, tmp_path, capsys,
                                                            no_computation):
    text, key = BAD[case]
    path = tmp_path / "arch.toml"
    path.write_text(text)
    out = tmp_path / "out"
    assert main(["assess", str(path), "--out", str(out), "--quick"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert key in err and "arch.toml" in err, err
    assert not out.exists()  # nothing written: validation came first


@pytest.mark.parametrize("text, model, message", [
    (GOOD, "dem", "--model must be rigid or fourlink for assess"),
    (GOOD + '[options]\nmodel = "fourlink"\nrestitution = 0.8\n', "rigid",
     "--model rigid: the file prescribes [options] restitution"),
])
def test_bad_model_option_is_one_line_exit_2(text, model, message, tmp_path, capsys,
                                            no_computation):
    path = tmp_path / "arch.toml"
    path.write_text(text)
    assert main(["assess", str(path), "--out", str(tmp_path / "o"), "--model", model]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_good_file_reaches_the_assessment(tmp_path, no_computation):
    """The same file without the defect passes validation (so the cases above fail for the
    reason they name): the replaced assessment is then called."""
    path = tmp_path / "arch.toml"
    path.write_text(GOOD)
    with pytest.raises(AssertionError, match="the assessment started"):
        main(["assess", str(path), "--out", str(tmp_path / "out")])


def test_the_arch_is_built_by_the_study_files_builder(tmp_path):
    """[arch] takes the study files' keys and builds through ArchSpec: the same arch."""
    from archquake.assess import load_config
    from archquake.sweeps import ArchSpec

    path = tmp_path / "arch.toml"
    path.write_text(GOOD)
    cfg = load_config(path)
    assert cfg.arch == ArchSpec(radius=5.0, thickness_ratio=0.12, embrace_deg=180, voussoirs=15)
    assert cfg.friction == 0.6 and cfg.site_pga_g == 0.15 and cfg.suite is None


def test_examples_validate():
    from archquake.assess import load_config
    from archquake.ground.suites import fema_available

    from .conftest import EXAMPLES

    nave = load_config(EXAMPLES / "nave.toml")
    assert nave.arch.shape == "pointed" and nave.arch.pier_height == 6.0
    if fema_available():
        assert load_config(EXAMPLES / "bridge.toml").suite == "fema-p695-near-field-pulse"


def test_piers_refusal_names_the_width_that_stands(tmp_path):
    """The width the refusal names stands (the static program finds a line of thrust), and
    one 2 % narrower does not: the bisection's answer, rounded up to the millimetre."""
    import re

    from archquake.assess import load_config
    from archquake.errors import StudyFileError
    from archquake.geometry import Arch, OnPiers, Piers
    from archquake.limit import stands

    path = tmp_path / "arch.toml"
    path.write_text(GOOD.replace("voussoirs = 15", "voussoirs = 15\npier_height = 6.0\n"
                                 "pier_width = 0.6\npier_courses = 3"))
    with pytest.raises(StudyFileError) as exc:
        load_config(path)
    width = float(re.search(r"piers (\d+\.\d+) m wide would stand", str(exc.value))[1])
    arch = Arch.from_ratio(0.12, math.pi, 15, radius=5.0)
    assert stands(OnPiers(arch, Piers(6.0, width, 3)))
    assert not stands(OnPiers(arch, Piers(6.0, 0.98 * width, 3)))


def _records(tmp_path):
    good = tmp_path / "good.csv"
    good.write_text("".join(f"{0.01 * k:.2f},{0.1 * math.sin(k / 5):.5f}\n" for k in range(400)))
    bad = tmp_path / "broken.AT2"
    bad.write_text("PEER\nx\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 10, DT= 0.01 SEC\n"
                   "0.1 0.2 oops\n")
    return good, bad



@pytest.mark.parametrize("suite, units, key, words", [
    ('["good.csv"]', None, "[seismic] units", "good.csv"),
    ('["good.csv", "broken.AT2"]', "m/s2", "[seismic] suite", "broken.AT2"),
])
def test_records_are_read_before_any_computation(suite, units, key, words, tmp_path, capsys,
                                                 no_computation):
    """Every record of the suite is read when the file is validated: a CSV without units or a
    malformed .AT2 stops the run in one line naming the key and the file as the assessment
    file names it (no absolute path), before anything is computed."""
    _records(tmp_path)
    path = tmp_path / "arch.toml"
    path.write_text(GOOD + f"suite = {suite}\n" + (f'units = "{units}"\n' if units else ""))
    out = tmp_path / "out"
    assert main(["assess", str(path), "--out", str(out), "--quick"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert key in err and words in err and str(tmp_path) not in err, err
    assert not out.exists()


@pytest.mark.parametrize("text, words", [
    (GOOD.replace("site_pga_g = 0.15", "site_pga_g = 2.55"),
     "[seismic] site_pga_g = 2.55 g is above 1.5 g"),
    (GOOD.replace("radius = 5.0", "radius = 0.15"), "[arch] radius = 0.15 m is below 0.2 m"),
])
def test_implausible_values_are_warned_before_the_run(text, words, tmp_path, capsys,
                                                      no_computation):
    path = tmp_path / "arch.toml"
    path.write_text(text)
    with pytest.raises(AssertionError, match="the assessment started"):
        main(["assess", str(path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert words in err


def test_the_last_release_word_for_the_four_link_model_warns_and_maps(tmp_path):
    """``model = "analytical"`` (the four-link model's earlier name) still reads as
    ``fourlink`` for one release, with a DeprecationWarning naming the key as typed. Oracle:
    the same file with ``model = "fourlink"``."""
    from archquake.assess.config import load_config

    old, now = tmp_path / "old.toml", tmp_path / "now.toml"
    old.write_text(GOOD + '[options]\nmodel = "analytical"\n')
    now.write_text(GOOD + '[options]\nmodel = "fourlink"\n')
    with pytest.warns(DeprecationWarning, match=r"^\[options\] model analytical is deprecated"):
        config = load_config(old)
    assert config.model == "fourlink" == load_config(now).model
