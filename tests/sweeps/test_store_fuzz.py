"""The sweep store is verified, not trusted: damaged files (random pages, truncation), foreign
schemas and bad rows, and two writers at once.

Oracles: SQLite's own integrity check (a page of random bytes breaks a b-tree page's header,
which ``PRAGMA quick_check`` reports), the rows written (a store either is refused in one line
naming the file, or every row it reports is byte for byte one that was written: nothing
damaged is passed on as a result), and the lock (a second writer is refused while the first
holds the store).
"""

from __future__ import annotations

import json
import os
import sqlite3
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from archquake.errors import ArchquakeError, CorruptStoreError
from archquake.sweeps import ResultStore
from archquake.sweeps.cases import ArchSpec, Case, ExcitationSpec
from archquake.sweeps.store import CaseRecord

QUICK = settings(max_examples=25, deadline=None, derandomize=True, database=None,
                 phases=[Phase.explicit, Phase.generate],
                 suppress_health_check=[HealthCheck.function_scoped_fixture])
THOROUGH = settings(QUICK, max_examples=300, derandomize=False)

#: Rows of the healthy store: enough for several b-tree pages (a row is ~0.5 kB, a page 4 kB).
N_ROWS = 200


def _cases(n: int) -> dict[str, Case]:
    cases = [Case(ArchSpec(10.0, 0.15, 157.5, 5),
                  ExcitationSpec("step", magnitude_g=0.01 * (k + 1), duration_s=0.1))
             for k in range(n)]
    return {c.case_id: c for c in cases}


@pytest.fixture(scope="module")
def healthy(tmp_path_factory) -> tuple[bytes, dict[str, dict]]:
    """The bytes of a closed, healthy store of N_ROWS rows, and its rows by id."""
    path = tmp_path_factory.mktemp("store") / "healthy.sqlite"
    cases = _cases(N_ROWS)
    records = [CaseRecord(cid, "ok", {"collapse_g": 0.1 * k, "note": "x" * 200}, "survives",
                          None, 0.5) for k, cid in enumerate(cases)]
    with ResultStore(path) as store:
        store.write(cases, records)
    with ResultStore(path) as store:
        rows = {r["case_id"]: r for r in store.rows(flatten_outputs=False)}
    assert len(rows) == N_ROWS
    return path.read_bytes(), rows


def _one_line(exc: BaseException, path: Path) -> None:
    message = str(exc)
    assert "\n" not in message and str(path) in message, message


def _check_opens_whole_or_refuses(path: Path, rows: dict[str, dict]) -> str:
    """Open ``path``: either an archquake error in one line naming it, or every row it reports
    (stored ids, rows, export) is a row that was written, unchanged."""
    try:
        store = ResultStore(path)
    except ArchquakeError as exc:
        _one_line(exc, path)
        return "refused"
    with store:
        ids = store.stored_ids()
        assert ids <= rows.keys()
        for row in store.rows(flatten_outputs=False):
            assert row == rows[row["case_id"]]
        store.export(path.with_suffix(".csv"))
    return "opened"


def test_a_healthy_store_reopens_with_every_row(tmp_path, healthy) -> None:
    """The baseline of the fuzz below: no row of a healthy store is lost by reopening it,
    exporting it, or writing its cases again."""
    data, rows = healthy
    path = tmp_path / "s.sqlite"
    path.write_bytes(data)
    cases = _cases(N_ROWS)
    with ResultStore(path) as store:
        assert store.stored_ids() == rows.keys()
        assert store.write(cases, [CaseRecord(cid, "ok", {}, None) for cid in cases]) == 0
        store.export(tmp_path / "s.csv")
        assert not store.damaged
    with ResultStore(path) as store:
        assert {r["case_id"]: r for r in store.rows(flatten_outputs=False)} == rows
    assert len((tmp_path / "s.csv").read_text().splitlines()) == N_ROWS + 1


def _damage_pages(data: bytes, pages: list[int], seed: int) -> bytes:
    import random

    page_size = int.from_bytes(data[16:18], "big")
    rng = random.Random(seed)
    out = bytearray(data)
    n_pages = len(data) // page_size
    for p in pages:
        p %= n_pages
        out[p * page_size:(p + 1) * page_size] = rng.randbytes(page_size)
    return bytes(out)


@QUICK
@given(pages=st.lists(st.integers(0, 10**6), min_size=1, max_size=3), seed=st.integers(0, 2**32))
def test_random_pages_are_refused_or_read_whole(tmp_path, healthy, pages, seed) -> None:
    data, rows = healthy
    path = tmp_path / f"pages-{seed}.sqlite"
    path.write_bytes(_damage_pages(data, pages, seed))
    _check_opens_whole_or_refuses(path, rows)


@pytest.mark.slow
@THOROUGH
@given(pages=st.lists(st.integers(0, 10**6), min_size=1, max_size=5), seed=st.integers(0, 2**32))
def test_random_pages_thorough(tmp_path, healthy, pages, seed) -> None:
    data, rows = healthy
    path = tmp_path / f"pages-{seed}.sqlite"
    path.write_bytes(_damage_pages(data, pages, seed))
    _check_opens_whole_or_refuses(path, rows)


def test_two_damaged_pages_of_rows_are_refused(tmp_path, healthy) -> None:
    """The campaign's case: two pages holding rows overwritten. It was opened and reported as
    holding every case; SQLite's integrity check fails, so it is refused."""
    data, rows = healthy
    path = tmp_path / "two.sqlite"
    path.write_bytes(_damage_pages(data, [3, 5], seed=1))
    with pytest.raises(CorruptStoreError, match="damaged") as info:
        ResultStore(path)
    _one_line(info.value, path)


@QUICK
@given(fraction=st.floats(0.0, 0.999))
def test_a_truncated_store_is_refused_or_read_whole(tmp_path, healthy, fraction) -> None:
    data, rows = healthy
    path = tmp_path / f"cut-{fraction}.sqlite"
    path.write_bytes(data[: int(len(data) * fraction)])
    _check_opens_whole_or_refuses(path, rows)


FOREIGN = [
    ("CREATE TABLE results (a INTEGER, b TEXT)", "not an archquake sweep store"),
    ("CREATE TABLE other (x); CREATE VIEW results AS SELECT x FROM other",
     "'results' is a view"),
    ("CREATE TABLE results (case_id TEXT PRIMARY KEY, status TEXT); "
     "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)", "not an archquake sweep store"),
]


@pytest.mark.parametrize("sql, words", FOREIGN)
def test_a_foreign_schema_is_refused_in_one_line(tmp_path, sql, words) -> None:
    path = tmp_path / "foreign.sqlite"
    with sqlite3.connect(path) as db:
        db.executescript(sql)
    db.close()
    with pytest.raises(CorruptStoreError, match=words) as info:
        ResultStore(path)
    _one_line(info.value, path)


def test_a_file_that_is_not_a_database_is_refused(tmp_path) -> None:
    path = tmp_path / "text.sqlite"
    path.write_text("not a database at all\n" * 100)
    with pytest.raises(ArchquakeError) as info:
        ResultStore(path)
    _one_line(info.value, path)


def test_bad_rows_are_not_stored_skipped_by_the_export_and_recomputed(tmp_path, healthy) -> None:
    """Rows with undecodable outputs or an unknown status: the export writes the others and
    names how many it skipped (store.damaged); a rerun's write replaces exactly those."""
    data, rows = healthy
    path = tmp_path / "bad.sqlite"
    path.write_bytes(data)
    ids = sorted(rows)
    with sqlite3.connect(path) as db:
        db.execute("UPDATE results SET outputs_json = '{not json' WHERE case_id = ?", (ids[0],))
        db.execute("UPDATE results SET outputs_json = '[1, 2]' WHERE case_id = ?", (ids[1],))
        db.execute("UPDATE results SET status = 'what' WHERE case_id = ?", (ids[2],))
    db.close()
    cases = _cases(N_ROWS)
    with ResultStore(path) as store:
        assert store.stored_ids() == set(ids[3:])
        assert store.damaged == set(ids[:3])
        store.export(tmp_path / "bad.csv")
        assert len((tmp_path / "bad.csv").read_text().splitlines()) == N_ROWS - 3 + 1
        new = [CaseRecord(cid, "ok", {"collapse_g": 1.0}, "collapse") for cid in cases]
        assert store.write(cases, new) == 3  # the three damaged rows, nothing else
        assert store.stored_ids() == rows.keys() and not store.damaged
    with ResultStore(path) as store:
        got = {r["case_id"]: r for r in store.rows(flatten_outputs=False)}
    for cid in ids[3:]:
        assert got[cid] == rows[cid]
    for cid in ids[:3]:
        assert json.loads(got[cid]["outputs_json"]) == {"collapse_g": 1.0}


def test_a_second_writer_is_refused_while_the_first_holds_the_store(tmp_path) -> None:
    """Two sweeps on one store once each reported 0 computed, 0 stored: now the second is
    refused in one line and the first is unaffected; once the first closes, the store opens."""
    path = tmp_path / "shared.sqlite"
    cases = _cases(3)
    with ResultStore(path) as first:
        with pytest.raises(ArchquakeError, match="in use by another sweep") as info:
            ResultStore(path)
        _one_line(info.value, path)
        assert first.write(cases, [CaseRecord(cid, "ok", {}, None) for cid in cases]) == 3
    with ResultStore(path) as again:
        assert again.count() == 3


def test_a_second_process_is_refused_too(tmp_path) -> None:
    """The lock holds across processes (flock on the store file), as two sweeps are."""
    import subprocess
    import sys

    path = tmp_path / "shared.sqlite"
    with ResultStore(path):
        code = ("import sys\nfrom archquake.sweeps import ResultStore\n"
                "try:\n    ResultStore(sys.argv[1])\nexcept Exception as e:\n"
                "    print(type(e).__name__, e)\n")
        out = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True,
                             text=True, timeout=120, env={**os.environ, "PYTHONWARNINGS": "ignore"})
    assert "in use by another sweep" in out.stdout, out.stdout + out.stderr
