"""The assessment's vertical section: the runs with and without the vertical, side by side.

Oracles: the rigid chain's verdicts themselves at the reported levels (the pulses' least
collapsing magnitude collapses there and survives one grid step below, with the vertical part
R and without); a record whose vertical is zero gives the same first collapsing PGA with and
without it (exactly: the same runs); the file's key is refused outside [-2, 2] in one line, and
a file without it keeps its digest.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from archquake.assess.config import parse_config
from archquake.assess.report import _vertical
from archquake.assess.runner import section_names
from archquake.assess.sections import Context, Mode, section_vertical
from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import StudyFileError
from archquake.ground import Record, StepImpulse
from archquake.ground.vertical import WithVertical
from archquake.rigid import rigid_verdict

ARCH = {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180, "voussoirs": 15,
        "density": 1800, "friction": 0.6}


def _config(tmp_path: Path, **seismic):
    return parse_config({"arch": ARCH, "seismic": {"site_pga_g": 0.18, **seismic}},
                        source="v.toml", base_dir=tmp_path)


def test_the_key_and_the_digest(tmp_path):
    plain = _config(tmp_path)
    assert "vertical_ratio" not in plain.canonical() and "vertical" not in section_names(plain)
    up = _config(tmp_path, vertical_ratio=0.5)
    assert up.vertical_ratio == 0.5 and up.digest != plain.digest
    assert "vertical" in section_names(up)
    with pytest.raises(StudyFileError, match=r"\[seismic\] vertical_ratio.*\[-2, 2\]"):
        _config(tmp_path, vertical_ratio=3.0)


def test_pulses_with_and_without_the_vertical(tmp_path):
    cfg = _config(tmp_path, vertical_ratio=0.5)
    ctx = Context(cfg, cfg.build_arch(), Mode(quick=True), tmp_path, tmp_path)
    data = section_vertical(ctx).data
    rows = data["pulses"]["rows"]
    assert len(rows) == 3
    step = 1.0 + data["pulses"]["grid_step"]
    arch = cfg.build_arch()
    lam = ctx.collapse_acceleration_g()
    for row in rows:
        for key, ratio in (("first_collapse_g", 0.0), ("first_collapse_vertical_g", 0.5)):
            a = row[key]
            assert a is not None
            at = rigid_verdict(arch, StepImpulse.from_g(a, row["duration_s"], vertical=ratio))
            assert at.outcome.value == "collapse"
            if a > lam * step * (1 + 1e-9):  # the grid point below survives
                below = rigid_verdict(arch, StepImpulse.from_g(a / step, row["duration_s"],
                                                               vertical=ratio))
                assert below.outcome.value != "collapse"
    el: list = []
    _vertical(el, data)
    assert any(e[0] == "table" and "R = 0.5 (g)" in e[1] for e in el)


def test_a_zero_vertical_record_changes_nothing(tmp_path):
    from archquake.ida import incremental_dynamic_analysis
    from archquake.sweeps import ResultStore

    dt = 0.01
    t = np.arange(0.0, 6.0, dt)
    h = 0.3 * np.sin(2 * np.pi * 1.2 * t) * np.exp(-((t - 2.0) / 0.8) ** 2)
    np.savetxt(tmp_path / "h.csv", np.column_stack([t, h]), delimiter=",")
    np.savetxt(tmp_path / "v.csv", np.column_stack([t, 0.0 * t]), delimiter=",")
    (tmp_path / "s.list").write_text("h.csv v.csv\n")
    cfg = _config(tmp_path, suite=str(tmp_path / "s.list"), units="g")
    assert cfg.suite_vertical and "vertical" in section_names(cfg)
    both = WithVertical(Record(h * G, dt, name="h"), Record(0.0 * t, dt, name="v"))
    with ResultStore(tmp_path / "r.sqlite") as store:
        res = incremental_dynamic_analysis(cfg.arch, [both], "pga", store, ceiling=0.5,
                                           precision=0.05, fill=0.25)
    first = [None if not np.isfinite(x) else float(x) for x in res.first_collapse_levels]
    prior = {"records": {"records_used": [both.name], "first_collapse_g": first,
                         "ceiling_g": 0.5}}
    ctx = Context(cfg, cfg.build_arch(), Mode(quick=True), tmp_path, tmp_path, prior)
    row = section_vertical(ctx).data["records"][0]
    assert row["first_collapse_g"] is not None
    assert row["first_collapse_horizontal_only_g"] == row["first_collapse_g"]
