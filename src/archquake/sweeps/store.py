"""The sweep store: one SQLite row per case, written as results arrive, never twice.

Table ``results`` (primary key ``case_id``):

- ``case_id`` (TEXT): the case's stable id (`archquake.sweeps.Case.case_id`);
- the flat input columns of `archquake.sweeps.cases.INPUT_COLUMNS` (model, radius_m,
  thickness_ratio, thickness_m, embrace_deg, voussoirs, depth_m, density_kg_m3, excitation,
  magnitude_g, duration_s, period_s, direction, record, record_sha256, record_units, scale,
  restitution, t_end_s, g_m_s2), NULL where they do not apply;
- ``status`` (TEXT): ``"ok"``, or ``"error"`` when the model refused the case with an
  `ArchquakeError` (e.g. an arch too thin to stand), whose one-line
  message is in ``error``;
- ``outcome`` (TEXT): the model's outcome (``no_hinging``, ``survives``, ``collapse``) or NULL;
- ``elapsed_s`` (REAL): wall time of the evaluation, s (the only column that differs between
  two runs of the same case);
- ``inputs_json`` (TEXT): the case's canonical JSON (what its id hashes);
- ``outputs_json`` (TEXT): the model's summary (``result.to_dict(include_history=False)``).

The database runs in WAL mode with ``synchronous=FULL`` and each batch is one transaction
(``INSERT OR IGNORE``), so an interruption at any moment leaves whole batches behind and a
rerun skips them. A store is verified, not trusted: when opened, SQLite's quick_check and the
tables' columns are checked (a damaged or foreign file is refused in one line); a row whose
status or outputs do not decode counts as not stored, is skipped by the export and is replaced
when its case is computed again; and one sweep at a time holds the file (an exclusive lock).
"""

from __future__ import annotations

import csv
import fcntl
import json
import os
import sqlite3
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from archquake._json import to_jsonable
from archquake.errors import ArchquakeError, CorruptStoreError
from archquake.sweeps.cases import INPUT_COLUMNS, Case

STORE_SCHEMA = "1"
STATUS_OK = "ok"
STATUS_ERROR = "error"
#: How long opening a store waits for another process's write lock before it says the store is
#: locked, s (SQLite's busy timeout).
LOCK_WAIT_S = 5.0
#: Columns written for every case besides its inputs, in order.
RESULT_COLUMNS: dict[str, str] = {
    "status": "TEXT NOT NULL", "outcome": "TEXT", "error": "TEXT", "elapsed_s": "REAL",
    "inputs_json": "TEXT NOT NULL", "outputs_json": "TEXT NOT NULL",
}
#: Columns whose values legitimately differ between two evaluations of the same case.
TIMING_COLUMNS = ("elapsed_s",)


@dataclass(frozen=True)
class CaseRecord:
    """What evaluating one case produced (built in the worker, stored by the driver).

    Attributes
    ----------
    case_id : str
    status : str
        ``"ok"`` or ``"error"``.
    outputs : dict
        JSON-able summary of the result (empty on error).
    outcome : str or None
    error : str or None
        The one-line message of the ArchquakeError that refused the case.
    elapsed_s : float
        Wall time of the evaluation, s.
    """

    case_id: str
    status: str
    outputs: dict = field(default_factory=dict)
    outcome: str | None = None
    error: str | None = None
    elapsed_s: float = 0.0


def _unwritable(path: Path) -> str:
    """Why a store that exists cannot be written, as the end of a sentence (the file, or its
    folder, where SQLite writes its journal beside it)."""
    folder = path.resolve().parent
    if not os.access(path, os.W_OK):
        return ("is read-only: make it writable (the results in it are kept), or give another "
                "--store")
    if not os.access(folder, os.W_OK):
        return (f"is in a read-only folder ({str(folder)!r}; SQLite writes its journal beside "
                "the store): copy it to a writable folder and give that --store (the results "
                "in it are kept)")
    return "cannot be written: give another --store"


def _not_damaged(path: Path, exc: sqlite3.DatabaseError) -> str | None:
    """The true reason, as the end of a sentence, when SQLite's error ``exc`` on opening a store
    says nothing about its contents: another process holds a lock on the database, or the file
    or its folder is read-only. None: the file may be damaged or not a store."""
    text = str(exc).lower()
    if "locked" in text or "busy" in text:
        return ("is locked by another process (SQLite: database is locked): wait for it to "
                "finish, then rerun (the results in it are kept), or give another --store")
    if ("readonly" in text or "read-only" in text or "unable to open" in text
            or not os.access(path, os.W_OK) or not os.access(path.resolve().parent, os.W_OK)):
        return _unwritable(path)
    return None


class ResultStore:
    """A sweep's SQLite store. Use as a context manager; only the driving process writes.

    Parameters
    ----------
    path : str or Path
        Database file (created, with its folder, if missing).
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)
        #: Rows found damaged (by id) when read: not counted as stored, skipped by the export,
        #: and replaced when their case is computed again.
        self.damaged: set[str] = set()
        self._lock_fd: int | None = None
        where = repr(str(self.path))
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            existed = self.path.exists() and self.path.stat().st_size > 0
            if self.path.exists() and not self.path.is_file():
                raise CorruptStoreError(f"sweep store {where} is not a regular file")
            self._db = sqlite3.connect(self.path, timeout=LOCK_WAIT_S)
        except (OSError, sqlite3.DatabaseError) as exc:
            raise ArchquakeError(f"cannot open sweep store {where}: {exc}") from None
        try:
            self._lock()
            if existed:
                self._verify(where)
            self._db.execute("PRAGMA journal_mode=WAL")
            self._db.execute("PRAGMA synchronous=FULL")
            cols = ", ".join(f"{name} {kind}" for name, kind in
                             {**INPUT_COLUMNS, **RESULT_COLUMNS}.items())
            with self._db:
                self._db.execute(f"CREATE TABLE IF NOT EXISTS results "
                                 f"(case_id TEXT PRIMARY KEY, {cols})")
                self._db.execute("CREATE TABLE IF NOT EXISTS meta "
                                 "(key TEXT PRIMARY KEY, value TEXT)")
                self._db.execute("INSERT OR IGNORE INTO meta VALUES ('schema', ?)", (STORE_SCHEMA,))
            (schema,) = self._db.execute("SELECT value FROM meta WHERE key='schema'").fetchone()
        except sqlite3.DatabaseError as exc:
            self.close()
            reason = _not_damaged(self.path, exc)
            if reason is not None:
                raise ArchquakeError(f"sweep store {where} {reason}") from None
            raise CorruptStoreError(f"sweep store {where} cannot be read ({exc}); it is damaged "
                                    "or not a sweep store: use a new --store file") from None
        except ArchquakeError:
            self.close()
            raise
        if schema != STORE_SCHEMA:
            self.close()
            raise ArchquakeError(f"sweep store {where} has schema {schema}, this "
                                 f"archquake writes schema {STORE_SCHEMA}; use a new --store file")

    def _lock(self) -> None:
        """Hold an exclusive lock on the store file for as long as it is open, so that two
        sweeps never write one store at once (the second is refused, in one line)."""
        try:
            fd = os.open(self.path, os.O_RDWR)
        except PermissionError:
            raise ArchquakeError(f"sweep store {str(self.path)!r} "
                                 f"{_unwritable(self.path)}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise ArchquakeError(
                f"sweep store {str(self.path)!r} is in use by another sweep; wait for it to "
                "finish (then rerun to resume) or give another --store") from None
        self._lock_fd = fd

    def _verify(self, where: str) -> None:
        """Refuse a damaged file (SQLite's quick_check) or one whose tables are not a sweep
        store's, in one line."""
        report = [str(row[0]) for row in self._db.execute("PRAGMA quick_check")]
        if report != ["ok"]:
            problems = [line.strip() for text in report for line in text.splitlines()
                        if line.strip() and not line.startswith("***")]
            first = problems[0][:100] if problems else "failed"
            more = f"; {len(problems) - 1} more" if len(problems) > 1 else ""
            raise CorruptStoreError(
                f"sweep store {where} is damaged (SQLite's integrity check: {first}{more}); "
                "restore it from a copy or use a new --store file")
        kinds = dict(self._db.execute(
            "SELECT name, type FROM sqlite_master WHERE name IN ('results', 'meta')").fetchall())
        if not kinds:
            return  # an empty database: the tables are created
        expected = ["case_id", *INPUT_COLUMNS, *RESULT_COLUMNS]
        for table, cols in (("results", expected), ("meta", ["key", "value"])):
            if kinds.get(table) != "table":
                what = f"a {kinds[table]}" if table in kinds else "missing"
                raise CorruptStoreError(
                    f"sweep store {where} is not an archquake sweep store ({table!r} is {what}); "
                    "use a new --store file")
            found = [row[1] for row in self._db.execute(f"PRAGMA table_info({table})")]
            if found != cols:
                raise CorruptStoreError(
                    f"sweep store {where} is not an archquake sweep store (table {table!r} has "
                    f"columns {', '.join(found[:4])}{', ...' if len(found) > 4 else ''}); "
                    "use a new --store file")

    # ------------------------------------------------------------------ context
    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        db = getattr(self, "_db", None)
        if db is not None:
            db.close()
        if self._lock_fd is not None:
            os.close(self._lock_fd)  # releases the lock
            self._lock_fd = None

    # ------------------------------------------------------------------ reading
    def stored_ids(self) -> set[str]:
        """Ids of every stored case whose row is whole (a damaged row, `damaged`, is not
        stored: its case is computed again)."""
        ids: set[str] = set()
        for cid, status, outputs in self._db.execute(
                "SELECT case_id, status, outputs_json FROM results"):
            if _decode(status, outputs) is None:
                self.damaged.add(str(cid))
            else:
                ids.add(cid)
        return ids

    def lookup(self, case_ids: Iterable[str]) -> dict[str, CaseRecord]:
        """The stored records of ``case_ids`` (ids not stored are absent), outputs decoded."""
        wanted = list(dict.fromkeys(case_ids))
        out: dict[str, CaseRecord] = {}
        for start in range(0, len(wanted), 500):  # SQLite's bound-parameter limit
            part = wanted[start:start + 500]
            sql = ("SELECT case_id, status, outputs_json, outcome, error, elapsed_s FROM results "
                   f"WHERE case_id IN ({', '.join('?' * len(part))})")
            for cid, status, outputs, outcome, error, elapsed in self._db.execute(sql, part):
                decoded = _decode(status, outputs)
                if decoded is None:
                    self.damaged.add(str(cid))
                    continue
                out[cid] = CaseRecord(cid, status, decoded, outcome, error,
                                      elapsed if isinstance(elapsed, (int, float)) else 0.0)
        return out

    def count(self) -> int:
        return int(self._db.execute("SELECT COUNT(*) FROM results").fetchone()[0])

    def outcome_counts(self, case_ids: Iterable[str] | None = None) -> dict[str, int]:
        """Number of stored cases by outcome (``error`` for refused cases), optionally restricted
        to ``case_ids``."""
        wanted = None if case_ids is None else set(case_ids)
        counts: dict[str, int] = {}
        for cid, status, outcome in self._db.execute(
                "SELECT case_id, status, outcome FROM results"):
            if (wanted is not None and cid not in wanted) or cid in self.damaged:
                continue
            key = STATUS_ERROR if status == STATUS_ERROR else (outcome or "none")
            counts[key] = counts.get(key, 0) + 1
        return dict(sorted(counts.items()))

    def rows(self, *, flatten_outputs: bool = True) -> list[dict[str, Any]]:
        """Every stored case as a flat dict (ordered by case id): id, inputs, status columns and,
        with ``flatten_outputs``, one column per output (nested keys joined by '.', lists as
        JSON text) instead of ``outputs_json``. Damaged rows are skipped (their ids are added
        to `damaged`)."""
        return list(self._iter_rows(flatten_outputs))

    def _iter_rows(self, flatten_outputs: bool) -> Iterator[dict[str, Any]]:
        cur = self._db.execute("SELECT * FROM results ORDER BY case_id")
        names = [d[0] for d in cur.description]
        for values in cur:
            row = dict(zip(names, values, strict=True))
            outputs = _decode(row["status"], row["outputs_json"])
            if outputs is None:
                self.damaged.add(str(row["case_id"]))
                continue
            if flatten_outputs:
                row.pop("outputs_json")
                row.update(_flatten(outputs, "out."))
            yield row

    # ------------------------------------------------------------------ writing
    def write(self, cases: Mapping[str, Case], records: Iterable[CaseRecord]) -> int:
        """Store ``records`` (inputs from ``cases`` by id) in one transaction; a case already
        stored is left as it is. Returns the number of rows inserted."""
        names = ["case_id", *INPUT_COLUMNS, *RESULT_COLUMNS]
        values = f"({', '.join(names)}) VALUES ({', '.join('?' * len(names))})"
        sql = f"INSERT OR IGNORE INTO results {values}"
        replace = f"INSERT OR REPLACE INTO results {values}"  # damaged rows only
        repaired: list[tuple] = []
        rows: list[tuple] = []
        for rec in records:
            case = cases[rec.case_id]
            inputs = case.columns()
            row = (rec.case_id, *(inputs[c] for c in INPUT_COLUMNS), rec.status,
                   rec.outcome, rec.error, rec.elapsed_s, case.canonical_json,
                   json.dumps(rec.outputs, sort_keys=True, allow_nan=False))
            (repaired if rec.case_id in self.damaged else rows).append(row)
        with self._db:
            before = self._db.total_changes
            self._db.executemany(sql, rows)
            self._db.executemany(replace, repaired)
            self.damaged.difference_update(r[0] for r in repaired)
            return self._db.total_changes - before

    # ------------------------------------------------------------------ export
    def export(self, path: str | Path) -> Path:
        """Write every whole row (inputs and outputs as columns) to ``.csv`` or ``.parquet``;
        damaged rows are skipped and their ids added to `damaged`."""
        path = Path(path)
        rows = self.rows()
        columns = ["case_id", *INPUT_COLUMNS, *(c for c in RESULT_COLUMNS if c != "outputs_json")]
        extra = sorted({k for r in rows for k in r} - set(columns))
        columns += extra
        suffix = path.suffix.lower()
        if suffix == ".csv":
            with path.open("w", newline="") as fh:
                writer = csv.DictWriter(fh, fieldnames=columns, restval="")
                writer.writeheader()
                writer.writerows(rows)
        elif suffix == ".parquet":
            try:
                import pyarrow as pa
                import pyarrow.parquet as pq
            except ImportError:
                raise ArchquakeError("exporting .parquet needs pyarrow: "
                                     "pip install 'archquake[parquet]'") from None
            table = pa.table({c: [r.get(c) for r in rows] for c in columns})
            pq.write_table(table, path)
        else:
            raise ArchquakeError(f"export file must end in .csv or .parquet, got {path.name!r}")
        return path


def _decode(status: object, outputs: object) -> dict | None:
    """A row's outputs, or None if the row is damaged (unknown status, outputs that are not a
    JSON object)."""
    if status not in (STATUS_OK, STATUS_ERROR) or not isinstance(outputs, str):
        return None
    try:
        decoded = json.loads(outputs)
    except ValueError:
        return None
    return decoded if isinstance(decoded, dict) else None


def _flatten(obj: Mapping[str, Any], prefix: str) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in obj.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(_flatten(value, name + "."))
        elif isinstance(value, list):
            out[name] = json.dumps(value)
        else:
            out[name] = value
    return out


#: The shared converter (kept under its old name for the runner).
jsonable = to_jsonable


__all__ = ["CaseRecord", "ResultStore", "RESULT_COLUMNS", "TIMING_COLUMNS", "jsonable"]
