"""The runner and the store: executors agree, interruptions resume without repeating a case,
refused cases are stored as errors, rows are never stored twice, exports carry every column.

Oracle throughout: an uninterrupted serial run of the same deterministic case function
(sweep_fake_model.fake_evaluate). Stored values must agree exactly (JSON round-trips floats
exactly), except the wall-time column ``elapsed_s``.
"""

from __future__ import annotations

import csv
import json
from concurrent.futures import ProcessPoolExecutor

import pytest
from sweep_fake_model import CountingEvaluate, fake_evaluate, picky_evaluate

from archquake.parallel import SerialExecutor
from archquake.sweeps import ModelUnavailableError, ResultStore, run_sweep
from archquake.sweeps.runner import evaluate_chunk
from archquake.sweeps.store import TIMING_COLUMNS


def stored(path) -> dict[str, dict]:
    """Every row of a store by case id, without the wall-time columns."""
    with ResultStore(path) as store:
        rows = store.rows(flatten_outputs=False)
    return {r["case_id"]: {k: v for k, v in r.items() if k not in TIMING_COLUMNS} for r in rows}


@pytest.fixture
def reference(tmp_path, small_cases):
    """The uninterrupted serial run."""
    path = tmp_path / "reference.sqlite"
    with ResultStore(path) as store:
        report = run_sweep(small_cases, store, evaluate=fake_evaluate, executor=SerialExecutor())
    assert report.computed == report.total == len(small_cases) == 24
    return stored(path)


def test_serial_run_stores_every_case_with_inputs_and_outputs(reference, small_cases):
    assert set(reference) == {c.case_id for c in small_cases}
    case = small_cases[5]
    row = reference[case.case_id]
    assert row["radius_m"] == case.arch.radius and row["magnitude_g"] == case.excitation.magnitude_g
    assert row["thickness_m"] == pytest.approx(0.15 * case.arch.radius, rel=1e-15)
    assert row["status"] == "ok"
    assert json.loads(row["outputs_json"]) == fake_evaluate(case)
    assert row["outcome"] == fake_evaluate(case)["outcome"]
    assert json.loads(row["inputs_json"]) == case.canonical()


def test_process_pool_and_chunking_give_identical_stores(tmp_path, reference, small_cases):
    path = tmp_path / "pool.sqlite"
    with ProcessPoolExecutor(max_workers=2) as pool, ResultStore(path) as store:
        report = run_sweep(small_cases, store, evaluate=fake_evaluate, executor=pool,
                           chunk_size=5)
    assert report.computed == 24
    assert stored(path) == reference
    path = tmp_path / "chunk1.sqlite"
    with ResultStore(path) as store:
        run_sweep(small_cases, store, evaluate=fake_evaluate, executor=SerialExecutor(),
                  chunk_size=1)
    assert stored(path) == reference


def test_default_executor_is_a_local_process_pool(tmp_path, reference, small_cases):
    path = tmp_path / "default.sqlite"
    with ResultStore(path) as store:
        run_sweep(small_cases, store, evaluate=fake_evaluate, workers=2)
    assert stored(path) == reference


@pytest.mark.parametrize("k", [0, 1, 10, 23])
def test_interrupted_sweep_resumes_without_repeating_a_case(tmp_path, reference, small_cases, k):
    path = tmp_path / "resume.sqlite"
    first = CountingEvaluate(stop_at=k + 1)  # Ctrl-C arrives during case k+1
    with ResultStore(path) as store, pytest.raises(KeyboardInterrupt):
        run_sweep(small_cases, store, evaluate=first, executor=SerialExecutor(), chunk_size=1)
    assert first.calls == k + 1
    partial = stored(path)
    assert len(partial) == k  # every completed case, nothing else
    assert set(partial) == set(first.evaluated)

    second = CountingEvaluate()
    with ResultStore(path) as store:
        report = run_sweep(small_cases, store, evaluate=second, executor=SerialExecutor(),
                           chunk_size=1)
    assert second.calls == 24 - k  # only what was missing
    assert not set(second.evaluated) & set(first.evaluated)
    assert (report.already_stored, report.computed) == (k, 24 - k)
    assert stored(path) == reference


def test_a_progress_callback_can_stop_the_sweep_after_whole_batches(tmp_path, reference,
                                                                    small_cases):
    path = tmp_path / "stop.sqlite"
    seen = []

    def progress(done, total):
        seen.append((done, total))
        if done >= 6:
            raise KeyboardInterrupt

    with ResultStore(path) as store, pytest.raises(KeyboardInterrupt):
        run_sweep(small_cases, store, evaluate=fake_evaluate, executor=SerialExecutor(),
                  chunk_size=3, progress=progress)
    assert seen == [(0, 24), (3, 24), (6, 24)]
    assert len(stored(path)) == 6  # two whole batches
    counter = CountingEvaluate()
    with ResultStore(path) as store:
        run_sweep(small_cases, store, evaluate=counter, executor=SerialExecutor(), chunk_size=3)
    assert counter.calls == 18
    assert stored(path) == reference


def test_refused_cases_are_stored_as_errors_and_not_retried(tmp_path, small_cases):
    path = tmp_path / "errors.sqlite"
    with ResultStore(path) as store:
        report = run_sweep(small_cases, store, evaluate=picky_evaluate, executor=SerialExecutor())
    rows = stored(path)
    errors = [r for r in rows.values() if r["status"] == "error"]
    assert len(errors) == 8  # radius 10 m: 4 magnitudes x 2 durations
    assert all("radius 10 m is refused" in r["error"] and r["outcome"] is None for r in errors)
    assert report.outcomes["error"] == 8
    counter = CountingEvaluate()
    with ResultStore(path) as store:
        assert run_sweep(small_cases, store, evaluate=counter).computed == 0
    assert counter.calls == 0


def test_bugs_and_missing_models_are_not_stored(tmp_path, small_cases):
    def buggy(case):
        raise ZeroDivisionError("a bug")

    def missing(case):
        raise ModelUnavailableError("model 'dem' needs archquake.dem.simulate_dem")

    for fn, exc in ((buggy, ZeroDivisionError), (missing, ModelUnavailableError)):
        with ResultStore(tmp_path / "bug.sqlite") as store:
            with pytest.raises(exc):
                run_sweep(small_cases, store, evaluate=fn, executor=SerialExecutor())
            assert store.count() == 0


def test_a_case_is_never_stored_twice(tmp_path, small_cases):
    by_id = {c.case_id: c for c in small_cases}
    records = evaluate_chunk(fake_evaluate, small_cases[:4])
    with ResultStore(tmp_path / "twice.sqlite") as store:
        assert store.write(by_id, records) == 4
        assert store.write(by_id, records + evaluate_chunk(fake_evaluate, small_cases[3:6])) == 2
        assert store.count() == 6


def test_duplicate_cases_are_evaluated_once(tmp_path, small_cases):
    counter = CountingEvaluate()
    with ResultStore(tmp_path / "dup.sqlite") as store:
        report = run_sweep(list(small_cases) * 2, store, evaluate=counter,
                           executor=SerialExecutor())
    assert counter.calls == report.total == 24


def test_export_csv_and_parquet(tmp_path, reference, small_cases):
    path = tmp_path / "x.sqlite"
    with ResultStore(path) as store:
        run_sweep(small_cases, store, evaluate=fake_evaluate, executor=SerialExecutor())
        store.export(tmp_path / "x.csv")
        store.export(tmp_path / "x.parquet")
    with (tmp_path / "x.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 24
    for col in ("case_id", "radius_m", "magnitude_g", "duration_s", "outcome", "elapsed_s",
                "out.collapse_acceleration_g", "out.summary.span_m", "out.impact_times"):
        assert col in rows[0], col
    case = next(c for c in small_cases if c.case_id == rows[0]["case_id"])
    expected = fake_evaluate(case)
    assert float(rows[0]["out.collapse_acceleration_g"]) == expected["collapse_acceleration_g"]
    assert json.loads(rows[0]["out.impact_times"]) == expected["impact_times"]

    import pyarrow.parquet as pq

    table = pq.read_table(tmp_path / "x.parquet").to_pylist()
    assert [r["case_id"] for r in table] == [r["case_id"] for r in rows]
    assert table[0]["out.mass_kg"] == expected["mass_kg"]
