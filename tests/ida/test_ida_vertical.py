"""IDA of a record with its vertical component: every level scales both components together.

Oracles: each level's outcome against a run of the model itself on the two components scaled
by the level's factor (`simulate`, the four-link model: its compiled batch is simulate case
by case); a zero vertical gives the IDA of the horizontal alone, level for level; a suite's
``.list`` file naming a vertical after its record loads both, and ``--record-vertical`` pairs
with a suite of one record (one-line refusal otherwise).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from ida_inputs import OPPENHEIM, synthetic_record

from archquake.cli.main import main
from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch
from archquake.ground import Record, load_suite
from archquake.ground.vertical import WithVertical
from archquake.ida import incremental_dynamic_analysis
from archquake.mechanism import simulate
from archquake.parallel import SerialExecutor
from archquake.sweeps import ResultStore

ARCH = Arch(10.0, 1.5, np.radians(157.5), 7)


def _vertical(h: Record, ratio: float) -> Record:
    """A vertical of ``ratio`` times the horizontal's PGA: a 6 Hz burst (near-field verticals
    are of higher frequency than the horizontal)."""
    t = h.times
    v = np.sin(2 * np.pi * 6.0 * t) * np.exp(-((t - 2.5) / 0.8) ** 2)
    return Record(ratio * h.peak * v / np.max(np.abs(v)), h.dt, name=f"{h.name}-UP")


def _ida(motions, path):
    with ResultStore(path) as store:
        return incremental_dynamic_analysis(OPPENHEIM, motions, "pga", store, model="fourlink",
                                            ceiling=1.5, precision=0.05, fill=0.2,
                                            executor=SerialExecutor())


def test_every_level_scales_both_components(tmp_path):
    h = synthetic_record(3, duration=6.0)
    both = WithVertical(h, _vertical(h, 0.8))
    res = _ida([both], tmp_path / "v.sqlite")
    rec = res.records[0]
    assert rec.first_collapse is not None
    for factor, outcome in zip(rec.factors, rec.outcomes, strict=True):
        direct = simulate(ARCH, WithVertical(h.scaled(factor), both.vertical.scaled(factor)))
        assert direct.outcome.value == outcome
    # the vertical changes the runs: the same levels without it do not all agree
    plain = [simulate(ARCH, h.scaled(f)).outcome.value for f in rec.factors]
    peaks = [simulate(ARCH, WithVertical(h.scaled(f), both.vertical.scaled(f))).to_dict()[
        "max_rotation_rad"] for f in rec.factors[:3]]
    assert plain != list(rec.outcomes) or peaks != [
        simulate(ARCH, h.scaled(f)).to_dict()["max_rotation_rad"] for f in rec.factors[:3]]


def test_a_zero_vertical_gives_the_ida_of_the_horizontal(tmp_path):
    h = synthetic_record(3, duration=6.0)
    zero = _ida([WithVertical(h, Record(np.zeros(h.points), h.dt, name="up"))],
                tmp_path / "z.sqlite").records[0]
    plain = _ida([h], tmp_path / "p.sqlite").records[0]
    assert np.array_equal(zero.levels, plain.levels)
    assert zero.outcomes == plain.outcomes


def _write(path, record: Record) -> None:
    np.savetxt(path, np.column_stack([record.times, record.accelerations / G]), delimiter=",")


def test_suite_list_carries_verticals_and_cli(tmp_path, capsys):
    h1, h2 = synthetic_record(1, duration=4.0), synthetic_record(2, duration=4.0)
    for r in (h1, h2):
        _write(tmp_path / f"{r.name}.csv", r)
    _write(tmp_path / "up1.csv", _vertical(h1, 0.6))
    (tmp_path / "three.list").write_text("# horizontal  vertical\nsynthetic1.csv up1.csv\n"
                                         "synthetic2.csv\n")
    suite = load_suite(tmp_path / "three.list", units="g")
    assert isinstance(suite[0], WithVertical) and isinstance(suite[1], Record)
    assert np.allclose(suite[0].vertical.accelerations, _vertical(h1, 0.6).accelerations,
                       rtol=1e-7, atol=1e-9)
    (tmp_path / "bad.list").write_text("synthetic1.csv up1.csv synthetic2.csv\n")
    with pytest.raises(Exception, match="3 paths"):
        load_suite(tmp_path / "bad.list", units="g")
    base = ["ida", "--radius", "10", "--thickness", "1.5", "--embrace", "157.5", "--voussoirs",
            "7", "--model", "fourlink", "--units", "g", "--ceiling", "1", "--no-progress",
            "--store", str(tmp_path / "cli.sqlite")]
    assert main([*base, "--records", str(tmp_path / "synthetic1.csv"), "--record-vertical",
                 str(tmp_path / "up1.csv"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["records"][0]["record"] == "synthetic1 + up1 (vertical)"
    assert main([*base, "--records", str(tmp_path / "three.list"), "--record-vertical",
                 str(tmp_path / "up1.csv")]) == 2
    assert "--record-vertical pairs with one record" in capsys.readouterr().err


def test_levels_stop_where_the_vertical_lifts_the_arch_off(tmp_path):
    """Oracle: g + f min(a_v) = 0 at the lift-off factor f: no level reaches it, the record's
    ceiling sits just below it."""
    h = synthetic_record(3, duration=6.0)
    v = _vertical(h, 4.0)  # downward peak 4 PGA_h: lifts off at PGA_h = g / 4 (about 0.25 g)
    res = _ida([WithVertical(h, v)], tmp_path / "lift.sqlite")
    rec = res.records[0]
    lift_level = (h.peak / G) * G / -float(np.min(v.accelerations))
    assert rec.ceiling == pytest.approx(lift_level, rel=1e-8) and rec.ceiling < lift_level
    assert rec.levels.max() <= rec.ceiling


def test_records_lists_each_vertical_with_its_measures(tmp_path, capsys):
    """Oracle: the vertical's measures of `archquake record` (the same summary) and V/H."""
    h = synthetic_record(1, duration=4.0)
    _write(tmp_path / "h.csv", h)
    _write(tmp_path / "up.csv", _vertical(h, 0.6))
    (tmp_path / "s.list").write_text("h.csv up.csv\n")
    assert main(["records", str(tmp_path / "s.list"), "--units", "g", "--json"]) == 0
    row = json.loads(capsys.readouterr().out)["records"][0]
    assert row["vertical"]["v_over_h"]["pga"] == pytest.approx(0.6, rel=1e-6)
    assert main(["record", str(tmp_path / "h.csv"), "--units", "g", "--record-vertical",
                 str(tmp_path / "up.csv"), "--periods", "1", "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)["vertical"]
    assert row["vertical"]["intensity_measures"] == alone["intensity_measures"]
    assert main(["records", str(tmp_path / "s.list"), "--units", "g"]) == 0
    assert "V/H 0.60" in capsys.readouterr().out


def test_the_text_output_names_a_lowered_ceiling(tmp_path, capsys):
    h = synthetic_record(3, duration=6.0)
    _write(tmp_path / "h.csv", h)
    _write(tmp_path / "up.csv", _vertical(h, 4.0))
    assert main(["ida", "--radius", "10", "--thickness", "1.5", "--embrace", "157.5",
                 "--voussoirs", "7", "--model", "fourlink", "--units", "g", "--ceiling", "1",
                 "--no-progress", "--store", str(tmp_path / "s.sqlite"), "--records",
                 str(tmp_path / "h.csv"), "--record-vertical", str(tmp_path / "up.csv")]) == 0
    assert "reaches g downward" in capsys.readouterr().out
