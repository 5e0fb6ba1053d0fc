"""The sweep extensions incremental dynamic analysis uses: a record case holding its motion in
memory ("a record scaled by a factor"), the store's lookup by id, and batch case functions.

Oracles: the file-based record case (same samples, same scale -> same motion), the per-case
runner (a batch function must store exactly what the per-case function stores), and the
canonical-id rules of docs/sweeps.md.
"""

from __future__ import annotations

import numpy as np
import pytest

from archquake.errors import ArchquakeError, InvalidParameterError
from archquake.ground import Record, StepImpulse
from archquake.parallel import SerialExecutor
from archquake.sweeps import ArchSpec, Case, ExcitationSpec, ResultStore, run_sweep
from archquake.sweeps.store import TIMING_COLUMNS

ARCH = ArchSpec(10, 0.15, 157.5, 7)


def _record(seed=0, name="quake"):
    rng = np.random.default_rng(seed)
    return Record(rng.normal(0.0, 2.0, 400), 0.01, name=name)


def test_in_memory_record_builds_the_scaled_motion_and_ids_follow_the_samples():
    rec = _record()
    spec = ExcitationSpec("record", motion=rec, scale=2.5)
    built = spec.build()
    assert np.array_equal(built.accelerations, 2.5 * rec.accelerations)
    assert spec.units == "m/s2" and spec.record_name == "quake"
    same = Case(ARCH, ExcitationSpec("record", motion=Record(rec.accelerations.copy(), 0.01,
                                                             name="quake"), scale=2.5))
    assert Case(ARCH, spec).case_id == same.case_id
    # a different sample, a different scale or a different name change the id
    other = rec.accelerations.copy()
    other[7] += 1e-12
    for changed in (ExcitationSpec("record", motion=Record(other, 0.01, name="quake"), scale=2.5),
                    ExcitationSpec("record", motion=rec, scale=2.5000001),
                    ExcitationSpec("record", motion=Record(rec.accelerations, 0.01, name="b"),
                                   scale=2.5)):
        assert Case(ARCH, changed).case_id != Case(ARCH, spec).case_id
    assert Case(ARCH, spec).columns()["record"] == "quake"


def test_any_ground_motion_can_be_held_in_memory():
    pulse = StepImpulse.from_g(1.0, 0.27)
    spec = ExcitationSpec("record", motion=pulse, scale=0.5)
    assert spec.build().acceleration(0.1) == pytest.approx(pulse.acceleration(0.1) * 0.5)
    assert Case(ARCH, spec).columns()["record"] == getattr(pulse, "name", "StepImpulse")


@pytest.mark.parametrize("kwargs, needle", [
    ({"motion": 3.0}, "kernel_spec"),
    ({"motion": StepImpulse(1.0, 0.2), "file": "a.AT2"}, "not both"),
    ({"motion": StepImpulse(1.0, 0.2), "units": "g"}, "m/s2"),
    ({"motion": StepImpulse(1.0, 0.2), "scale": -1.0}, "scale"),
])
def test_bad_in_memory_cases_are_one_line(kwargs, needle):
    with pytest.raises(InvalidParameterError, match=needle):
        ExcitationSpec("record", **kwargs)
    with pytest.raises(InvalidParameterError, match="motion does not apply"):
        ExcitationSpec("step", magnitude_g=1.0, duration_s=0.2, motion=StepImpulse(1.0, 0.2))


def _cases():
    rec = _record()
    return [Case(ARCH, ExcitationSpec("record", motion=rec, scale=s)) for s in (0.5, 1.0, 2.0)]


def _per_case(case):
    return {"outcome": "survives" if case.excitation.scale < 1.5 else "collapse",
            "scale": case.excitation.scale}


def _batch(cases):
    return [_per_case(c) if c.excitation.scale != 1.0 else ArchquakeError("refused at 1.0")
            for c in cases]


def _per_case_refusing(case):
    if case.excitation.scale == 1.0:
        raise ArchquakeError("refused at 1.0")
    return _per_case(case)


def _rows(path):
    with ResultStore(path) as store:
        return {r["case_id"]: {k: v for k, v in r.items() if k not in TIMING_COLUMNS}
                for r in store.rows(flatten_outputs=False)}


def test_a_batch_function_stores_what_the_per_case_function_stores(tmp_path):
    cases = _cases()
    with ResultStore(tmp_path / "one.sqlite") as store:
        run_sweep(cases, store, evaluate=_per_case_refusing, executor=SerialExecutor())
    with ResultStore(tmp_path / "batch.sqlite") as store:
        report = run_sweep(cases, store, evaluate_batch=_batch, executor=SerialExecutor())
        assert report.computed == 3 and report.outcomes == {"collapse": 1, "error": 1,
                                                            "survives": 1}
        found = store.lookup([c.case_id for c in cases] + ["0" * 20])
    assert _rows(tmp_path / "one.sqlite") == _rows(tmp_path / "batch.sqlite")
    assert set(found) == {c.case_id for c in cases}
    assert found[cases[2].case_id].outputs == {"outcome": "collapse", "scale": 2.0}
    assert found[cases[1].case_id].status == "error"
    assert found[cases[1].case_id].error == "refused at 1.0"


def test_batch_and_per_case_functions_are_exclusive(tmp_path):
    with ResultStore(tmp_path / "x.sqlite") as store, pytest.raises(InvalidParameterError):
        run_sweep(_cases(), store, evaluate=_per_case, evaluate_batch=_batch)
