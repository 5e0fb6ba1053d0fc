"""Case ids are stable (a pinned value, int/float and key order do not matter) and distinct;
record cases are identified by their bytes, not their folder."""

from __future__ import annotations

import shutil

import pytest

from archquake.errors import InvalidParameterError
from archquake.sweeps import ArchSpec, Case, CaseOptions, ExcitationSpec, parse_study
from archquake.sweeps.cases import canonical_json

OPPENHEIM = ArchSpec(radius=10, thickness_ratio=0.15, embrace_deg=157.5, voussoirs=7)
STEP = ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25)

AT2 = """PEER NGA STRONG MOTION DATABASE RECORD
TEST, 1/1/2000, STATION, 000
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=    6, DT=   .0100 SEC
  .0000000E+00  .1000000E+00  .2000000E+00 -.1000000E+00  .0500000E+00
  .0000000E+00
"""


def test_case_id_is_pinned():
    # Oracle: the id is SHA-256 of the canonical JSON. A store written by one version must be
    # resumable by the next, so this exact value may only change with CASE_SCHEMA (the four-link
    # model keeps hashing under its earlier word, "analytical").
    case = Case(OPPENHEIM, STEP, "fourlink")
    assert case.canonical_json == (
        '{"arch":{"density_kg_m3":2000.0,"depth_m":1.0,"embrace_deg":157.5,"radius_m":10.0,'
        '"thickness_ratio":0.15,"voussoirs":7},"excitation":{"direction":-1,"duration_s":0.25,'
        '"magnitude_g":0.5,"type":"step"},"model":"analytical","options":{"g_m_s2":9.80665,'
        '"restitution":null,"t_end_s":null},"schema":1}'
    )
    assert case.case_id == "aec2e12de1ef622838a5"


def test_case_id_ignores_int_versus_float_and_defaults():
    a = Case(OPPENHEIM, STEP)
    b = Case(ArchSpec(10.0, 0.15, 157.5, 7.0, depth=1, density=2000),
             ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25, direction=-1),
             "rigid", CaseOptions())
    assert a.case_id == b.case_id
    assert a == b


@pytest.mark.parametrize("change", [
    dict(arch=ArchSpec(10, 0.15, 157.5, 9)),
    dict(excitation=ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25, direction=1)),
    dict(excitation=ExcitationSpec("sine", magnitude_g=0.5, period_s=0.25)),
    dict(options=CaseOptions(restitution=0.9)),
    dict(model="dem"),
])
def test_every_input_changes_the_id(change):
    base = dict(arch=OPPENHEIM, excitation=STEP)
    assert Case(**{**base, **change}).case_id != Case(**base).case_id


def test_ids_survive_reordering_a_study():
    one = parse_study({
        "study": {"name": "s"},
        "arches": {"radius": [1, 5], "thickness_ratio": 0.15, "embrace_deg": 157.5,
                   "voussoirs": [7, 9]},
        "excitation": {"type": "sine", "magnitude_g": [0.4, 0.8], "period_s": 1},
    })
    two = parse_study({
        "excitation": {"period_s": 1.0, "magnitude_g": [0.8, 0.4], "type": "sine"},
        "arches": {"voussoirs": [9, 7], "embrace_deg": 157.5, "thickness_ratio": 0.15,
                   "radius": [5.0, 1.0]},
        "study": {"name": "s"},
    })
    ids = [c.case_id for c in one.cases]
    assert len(ids) == len(set(ids)) == 8
    assert set(ids) == {c.case_id for c in two.cases}


def test_record_id_depends_on_bytes_not_folder(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    first = tmp_path / "a" / "quake.AT2"
    first.write_text(AT2)
    moved = tmp_path / "b" / "quake.AT2"
    shutil.copy(first, moved)
    spec = dict(kind="record", units="g", scale=2.0)
    id_a = Case(OPPENHEIM, ExcitationSpec(file=str(first), **spec)).case_id
    id_b = Case(OPPENHEIM, ExcitationSpec(file=str(moved), **spec)).case_id
    assert id_a == id_b
    moved.write_text(AT2.replace(".2000000E+00", ".2500000E+00"))
    assert Case(OPPENHEIM, ExcitationSpec(file=str(moved), **spec)).case_id != id_a


def test_record_case_builds_a_scaled_signed_motion(tmp_path):
    # Oracle: the file's peak, 0.2 g, times scale 2 and direction -1.
    path = tmp_path / "quake.AT2"
    path.write_text(AT2)
    spec = ExcitationSpec("record", file=str(path), scale=2.0, direction=-1)
    motion = spec.build()
    assert motion.acceleration(0.02) == pytest.approx(-2.0 * 0.2 * 9.80665, rel=1e-12)


@pytest.mark.parametrize("make, name", [
    (lambda: ArchSpec(-1, 0.15, 157.5, 7), "radius"),
    (lambda: ArchSpec(1, 0.15, 300, 7), "embrace_deg"),
    (lambda: ArchSpec(1, 0.15, 157.5, 2), "voussoirs"),
    (lambda: ExcitationSpec("step", magnitude_g=-0.1, duration_s=0.2), "magnitude_g"),
    (lambda: ExcitationSpec("sine", magnitude_g=0.1, duration_s=0.2), "duration_s"),
    (lambda: CaseOptions(restitution=1.5), "restitution"),
])
def test_bad_inputs_name_the_parameter(make, name):
    with pytest.raises(InvalidParameterError, match=name):
        make()


def test_canonical_json_treats_negative_zero_as_zero():
    assert canonical_json({"x": -0.0}) == canonical_json({"x": 0.0})
