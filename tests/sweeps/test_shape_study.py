"""Shapes in study files (issue 12): the same keys as the CLI in [arches].

Oracle: the library builders; the case ids of circular studies are pinned elsewhere
(tests/sweeps/test_cases.py) and must not move, so a circular arch by radius keeps exactly the
paper's canonical keys.
"""

from __future__ import annotations

import pytest

from archquake.errors import StudyFileError
from archquake.geometry import OnPiers, ShapedArch
from archquake.sweeps import ArchSpec, load_study

STUDY = """
[study]
name = "shapes"

[arches]
shape = ["pointed", "elliptical"]
span = 10.0
rise = [6.0, 7.0]
thickness = 0.8
voussoirs = 15
joints = ["radial", "vertical"]

[excitation]
type = "step"
magnitude_g = 0.3
duration_s = 0.2
"""


def test_study_grid_over_shapes_and_joints(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(STUDY)
    study = load_study(path)
    assert len(study.cases) == 2 * 2 * 2
    arches = {(c.arch.shape, c.arch.rise, c.arch.joints) for c in study.cases}
    assert ("pointed", 7.0, "vertical") in arches
    built = study.cases[0].arch.build()
    assert isinstance(built, ShapedArch)
    assert "shape" in study.cases[0].arch.canonical()


def test_circular_spec_keeps_the_paper_keys():
    spec = ArchSpec(10, 0.15, 157.5, 7)
    assert set(spec.canonical()) == {"radius_m", "thickness_ratio", "embrace_deg", "voussoirs",
                                     "depth_m", "density_kg_m3"}


def test_piers_in_a_spec():
    spec = ArchSpec(5, 0.15, 180, 15, pier_height=4.0, pier_width=1.5, pier_courses=3)
    assert isinstance(spec.build(), OnPiers)
    assert spec.canonical()["pier_courses"] == 3


@pytest.mark.parametrize("edit, key", [
    ('shape = ["pointed", "elliptical"]', "arches.shape"),
    ("rise = [6.0, 7.0]", "arches"),
])
def test_bad_shape_keys_are_one_line(tmp_path, edit, key):
    bad = STUDY.replace(edit, {"arches.shape": "shape = [1, 2]", "arches": "radius = 5.0"}[key])
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    with pytest.raises(StudyFileError, match=key.replace(".", r"\.")):
        load_study(path)
