"""Study files: a good file expands to the expected grid; each malformed variant is refused
through the command line with one line naming the bad key (exit 2)."""

from __future__ import annotations

from pathlib import Path

import pytest
from sweep_fake_model import SMALL_STUDY

from archquake.errors import StudyFileError
from archquake.sweeps import load_study


def test_good_study_gives_the_grid(small_study_file):
    study = load_study(small_study_file)
    assert study.name == "small"
    assert study.default_store == small_study_file.parent / "small.sqlite"
    assert len(study.cases) == 3 * 4 * 2
    radii = sorted({c.arch.radius for c in study.cases})
    assert radii == [1.0, 5.0, 10.0]
    # {start, stop, num} is an inclusive linspace: 0.3, 0.6, 0.9, 1.2 g
    mags = sorted({c.excitation.magnitude_g for c in study.cases})
    assert mags == pytest.approx([0.3, 0.6, 0.9, 1.2], abs=1e-15)
    assert {c.excitation.duration_s for c in study.cases} == {0.1, 0.4}
    assert all(c.arch.thickness_ratio == 0.15 and c.arch.voussoirs == 7 for c in study.cases)
    assert all(c.excitation.direction == -1 for c in study.cases)  # drives Figure 1's mechanism
    # grid order: arches outermost, then excitations
    assert [c.arch.radius for c in study.cases[:8]] == [1.0] * 8


def test_several_excitation_blocks_and_options(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text("""
[study]
name = "mixed"
[arches]
radius = 10
thickness_ratio = [0.1, 0.15]
embrace_deg = 157.5
voussoirs = 7
[[excitation]]
type = "step"
magnitude_g = 0.5
duration_s = 0.2
direction = [-1, 1]
[[excitation]]
type = "sine"
magnitude_g = [0.3, 0.6]
period_s = 1.0
[options]
restitution = [0.8, 1.0]
t_end_s = 12
""")
    study = load_study(path)
    assert len(study.cases) == 2 * (2 + 2) * 2
    assert {c.options.restitution for c in study.cases} == {0.8, 1.0}
    assert {c.excitation.kind.value for c in study.cases} == {"step", "sine"}
    assert all(c.options.t_end_s == 12.0 for c in study.cases)


def test_record_study_resolves_files_next_to_the_study(tmp_path):
    from test_cases import AT2

    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "q.AT2").write_text(AT2)
    path = tmp_path / "rec.toml"
    path.write_text(SMALL_STUDY.split("[excitation]")[0] + """
[excitation]
type = "record"
files = ["records/q.AT2"]
units = "g"
scale = [0.5, 1.0, 2.0]
""")
    study = load_study(path)
    assert len(study.cases) == 3 * 3
    motion = study.cases[0].excitation.build()
    # Oracle: the file's first nonzero sample, 0.1 g, scaled by 0.5 and kept in sign (+1)
    assert motion.acceleration(0.01) == pytest.approx(0.5 * 0.1 * 9.80665, rel=1e-12)


def _replace(old: str, new: str) -> str:
    assert old in SMALL_STUDY
    return SMALL_STUDY.replace(old, new)


MALFORMED = [
    ("name missing", _replace('name = "small"\n', ""), "study.name"),
    ("bad model", _replace('model = "fourlink"', 'model = "fem"'), "study.model"),
    ("unknown arch key", _replace("voussoirs = 7", "voussoirs = 7\nradiu = 3"), "arches.radiu"),
    ("missing arch key", _replace("voussoirs = 7\n", ""), "arches.voussoirs"),
    ("text radius", _replace("radius = [1, 5, 10]", 'radius = "ten"'), "arches.radius"),
    ("negative radius", _replace("radius = [1, 5, 10]", "radius = [1, -5]"), "arches.radius"),
    ("fractional voussoirs", _replace("voussoirs = 7", "voussoirs = 7.5"), "arches.voussoirs"),
    ("thick arch", _replace("thickness_ratio = 0.15", "thickness_ratio = 2.5"),
     "arches.thickness_ratio"),
    ("embrace over 240", _replace("embrace_deg = 157.5", "embrace_deg = 250"),
     "arches.embrace_deg"),
    ("range without num", _replace("num = 4}", "step = 4}"), "excitation.magnitude_g"),
    ("empty list", _replace("duration_s = [0.1, 0.4]", "duration_s = []"), "excitation.duration_s"),
    ("zero duration", _replace("duration_s = [0.1, 0.4]", "duration_s = 0"), "excitation.duration_s"),
    ("bad type", _replace('type = "step"', 'type = "earthquake"'), "excitation.type"),
    ("key of another type", _replace("duration_s = [0.1, 0.4]", "period_s = 1"),
     "excitation.period_s"),
    ("bad direction", _replace("duration_s = [0.1, 0.4]", "duration_s = 0.1\ndirection = 0"),
     "excitation.direction"),
    ("missing record", _replace('type = "step"\nmagnitude_g = {start = 0.3, stop = 1.2, num = 4}\n'
                                'duration_s = [0.1, 0.4]', 'type = "record"\nfiles = ["nope.AT2"]'),
     "excitation.files"),
    ("bad option", SMALL_STUDY + "[options]\nrestitution = 1.5\n", "options.restitution"),
    ("unknown option", SMALL_STUDY + "[options]\ndamping = 0.05\n", "options.damping"),
    ("unknown table", SMALL_STUDY + "[arch]\nradius = 1\n", "arch "),
    ("no excitation", SMALL_STUDY.split("[excitation]")[0], "excitation"),
    ("not TOML", SMALL_STUDY.replace("radius = [1, 5, 10]", "radius = [1, 5"), "not valid TOML"),
]


@pytest.mark.parametrize("text, key", [m[1:] for m in MALFORMED], ids=[m[0] for m in MALFORMED])
def test_malformed_study_is_one_line_naming_the_key(tmp_path, capsys, sweep_cli, text, key):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert sweep_cli(["sweep", str(path), "--workers", "1"]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("archquake: error: bad.toml: ")
    assert key in lines[0], lines[0]
    assert not (tmp_path / "small.sqlite").exists()  # nothing ran


def test_missing_study_file(capsys, sweep_cli, tmp_path):
    assert sweep_cli(["sweep", str(tmp_path / "none.toml")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_library_raises_study_file_error(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(SMALL_STUDY.replace("voussoirs = 7", "voussoirs = 2"))
    with pytest.raises(StudyFileError, match=r"arches\.voussoirs.*>= 3"):
        load_study(path)



def test_the_documented_example_parses(tmp_path):
    # docs/sweeps.md promises 4 arches x (25 + 4 + 8) excitations x 2 restitutions = 296 cases
    import re

    from test_cases import AT2

    doc = (Path(__file__).parents[2] / "docs" / "sweeps.md").read_text()
    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "RSN953_NORTHR_MUL009.AT2").write_text(AT2)
    (tmp_path / "s.toml").write_text(re.search(r"```toml\n(.*?)```", doc, re.S).group(1))
    assert len(load_study(tmp_path / "s.toml").cases) == 296
    example = Path(__file__).parents[2] / "examples" / "sweep_scale.toml"
    assert len(load_study(example).cases) == 400
