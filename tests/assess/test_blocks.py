"""Assessing a surveyed arch: ``[arch] blocks = "file.json"`` (ArchSpec's block file).

Oracles: the static section against the library's limit analysis of the same blocks read by the
one reader (:func:`archquake.geometry.survey.read_blocks`), equal to the last bit (the same
function on the same input); the circular arch the blocks were exported from (equal to 1e-6:
the JSON holds the vertices to 17 digits, the reader rebuilds the joints from them); the case id
against the file's bytes, not its folder."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

from archquake.errors import InvalidParameterError, StudyFileError
from archquake.sweeps.cases import ArchSpec, Case, ExcitationSpec


def _semicircle():
    from archquake.geometry import Arch

    return Arch.from_ratio(0.15, math.pi, 15, radius=5.0, density=2000.0)


def _write_blocks(path, warp: float = 0.0):
    """The blocks of a semicircle (R = 5 m, t/R = 0.15, 15 voussoirs) in the JSON format of
    docs/geometry.md; ``warp`` > 0 raises the right half (y -> y (1 + warp x / R)): the joints
    stay shared and the springings flat, the arch is no longer symmetric."""
    polys = [np.asarray(p, dtype=float) for p in _semicircle().block_polygons]
    polys = [np.c_[p[:, 0], p[:, 1] * (1 + warp * p[:, 0] / 5.0)] for p in polys]
    path.write_text(json.dumps({"blocks": [p.tolist() for p in polys]}))
    return path


def _toml(folder, blocks: str, extra: str = "", site: float = 0.2):
    """An assessment file of the four-link model (c_v 0.8) on a block file, no DEM."""
    path = folder / "survey.toml"
    path.write_text(f'[arch]\nblocks = "{blocks}"\ndensity = 2000\nfriction = 0.6\n{extra}'
                    f'[seismic]\nsite_pga_g = {site}\n[options]\nmodel = "fourlink"\n'
                    'restitution = 0.8\ndem = false\n')
    return path


def test_block_spec_id_depends_on_the_bytes_not_the_folder(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    _write_blocks(a / "arch.json")
    shutil.copy(a / "arch.json", b / "arch.json")
    step = ExcitationSpec("step", magnitude_g=0.5, duration_s=0.25)
    ida, idb = (Case(ArchSpec(blocks=str(d / "arch.json")), step).case_id for d in (a, b))
    assert ida == idb
    canon = ArchSpec(blocks=str(a / "arch.json")).canonical()
    assert canon["blocks"] == "arch.json" and str(tmp_path) not in json.dumps(canon)
    _write_blocks(b / "arch.json", warp=0.01)
    assert Case(ArchSpec(blocks=str(b / "arch.json")), step).case_id != ida


def test_blocks_with_shape_keys_is_refused_in_one_line(tmp_path):
    f = _write_blocks(tmp_path / "arch.json")
    with pytest.raises(InvalidParameterError, match="blocks .* does not go with the shape keys "
                                                    "radius, voussoirs"):
        ArchSpec(radius=5.0, voussoirs=15, blocks=str(f))
    toml = _toml(tmp_path, "arch.json", extra="voussoirs = 15\n")
    from archquake.assess import load_config

    with pytest.raises(StudyFileError) as err:
        load_config(toml)
    assert "[arch] blocks is invalid" in str(err.value) and "\n" not in str(err.value)
    out = subprocess.run([sys.executable, "-m", "archquake.cli.main", "assess", str(toml), "--out",
                          str(tmp_path / "o")], capture_output=True, text=True)
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
    missing = _toml(tmp_path, "nope.json")
    with pytest.raises(StudyFileError, match=r"\[arch\] blocks names 'nope.json', which does "
                                             "not exist"):
        load_config(missing)


def test_block_file_is_assessed_and_its_statics_equal_the_api(tmp_path):
    from archquake.assess import load_config, run_assessment
    from archquake.geometry.survey import read_blocks
    from archquake.limit import limit_analysis

    f = _write_blocks(tmp_path / "arch.json")
    cfg = load_config(_toml(tmp_path, "arch.json"))
    rep = run_assessment(cfg, tmp_path / "out", quick=True)
    res = json.loads((tmp_path / "out" / "results.json").read_text())
    assert list(res["sections"]) == ["arch", "static", "pulses", "validity"]
    la = limit_analysis(read_blocks(f, density=2000.0))
    st = res["sections"]["static"]
    assert st["collapse_acceleration_g"] == la.collapse_acceleration_g
    assert st["static_friction_demand"] == la.min_friction
    assert [h["joint"] for h in st["hinges"]] == list(la.mechanism.joints)
    # the arch the blocks came from (an independent construction of the same geometry)
    assert st["collapse_acceleration_g"] == pytest.approx(
        limit_analysis(_semicircle()).collapse_acceleration_g, rel=1e-6)
    # no ring thickness to vary: t_min is not defined, and the report says why
    assert st["min_thickness_m"] is None and "no ring thickness" in st["min_thickness_note"]
    assert res["input"]["arch"]["blocks"] == "arch.json"
    assert "minimum thickness t_min (same shape) | not defined" in (
        tmp_path / "out" / "report.md").read_text()
    assert rep.sections["pulses"].data["step"]["collapse_g"]  # the symmetric file's dynamics run


def test_asymmetric_block_file_under_fourlink_gets_one_line_not_a_traceback(tmp_path):
    _write_blocks(tmp_path / "arch.json", warp=0.05)
    toml = _toml(tmp_path, "arch.json")
    out = subprocess.run([sys.executable, "-m", "archquake.cli.main", "assess", str(toml), "--out",
                          str(tmp_path / "o"), "--quick"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr + out.stdout
    res = json.loads((tmp_path / "o" / "results.json").read_text())
    assert list(res["sections"]) == ["arch", "static", "validity"]
    warns = [w for w in res["sections"]["validity"]["warnings"] if w["key"] == "asymmetric"]
    assert len(warns) == 1 and warns[0]["serious"]
    assert "not symmetric" in warns[0]["meaning"] and "\n" not in warns[0]["meaning"]
    assert not res["verdict"]["certain"] and "not assessed" in res["verdict"]["text"]
    md = (tmp_path / "o" / "report.md").read_text()
    assert "## 3. Pulses" in md and "Not run: the arch is not symmetric" in md
    # below lambda the arch does not rock: the statics decide, the refusal is only a note
    from archquake.assess import load_config, run_assessment

    low = tmp_path / "low"
    low.mkdir()
    _write_blocks(low / "arch.json", warp=0.05)
    rep = run_assessment(load_config(_toml(low, "arch.json", site=0.05)), low / "o", quick=True)
    assert rep.sections["static"].data["collapse_acceleration_g"] > 0.05
    assert rep.verdict["level"] == "stands" and rep.verdict["certain"]
    assert [w["serious"] for w in rep.sections["validity"].data["warnings"]
            if w["key"] == "asymmetric"] == [False]


def test_study_file_takes_a_block_file_and_stores_its_cases(tmp_path):
    """A study file's [arches] blocks (relative to the study file) builds the same ArchSpec as
    the assessment's, and its cases go through the sweep into the store (whose input columns
    have no radius for a block file: None, not a KeyError)."""
    from archquake.parallel import SerialExecutor
    from archquake.sweeps import ResultStore, load_study, run_sweep

    _write_blocks(tmp_path / "arch.json")
    study = tmp_path / "s.toml"
    study.write_text('[study]\nname = "s"\nmodel = "fourlink"\n[arches]\nblocks = "arch.json"\n'
                     '[excitation]\ntype = "step"\nmagnitude_g = 0.3\nduration_s = 0.3\n'
                     '[options]\nrestitution = 0.8\n')
    st = load_study(study)
    (case,) = st.cases
    assert case.arch == ArchSpec(blocks=str(tmp_path / "arch.json"))
    assert case.columns()["radius_m"] is None and case.columns()["density_kg_m3"] == 2000.0
    with ResultStore(tmp_path / "s.sqlite") as store:
        run_sweep(st.cases, store, executor=SerialExecutor())
        rows = store.rows()
    assert len(rows) == 1 and rows[0]["status"] == "ok"
    study.write_text(study.read_text().replace('blocks = "arch.json"',
                                               'blocks = "arch.json"\nvoussoirs = 15'))
    with pytest.raises(StudyFileError, match="arches.blocks is invalid: blocks .* does not go "
                                             "with the shape keys voussoirs"):
        load_study(study)
    study.write_text(study.read_text().replace('blocks = "arch.json"\nvoussoirs = 15',
                                               'blocks = "gone.json"'))
    with pytest.raises(StudyFileError, match="arches.blocks names 'gone.json', which does not"):
        load_study(study)
