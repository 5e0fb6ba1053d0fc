"""The pieces of a reproduction: a checked row, a study's result, the registry entry.

A study is a pure function ``study(arch, quick, figures) -> StudyResult``: it computes one part
of the paper for ``arch`` (Oppenheim's arch by default), writes its figures into the folder
``figures`` and returns the rows that set each number the paper states beside archquake's.
The report (`archquake.reproduce.report`) is assembled from the results alone, so a
cached result (`archquake.reproduce.runner`) reproduces the same report.
"""

from __future__ import annotations

import hashlib
import math
import os
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from archquake._json import to_jsonable
from archquake.geometry.arch import Arch
from archquake.validation.paper import PaperValue


@dataclass(frozen=True)
class Row:
    """One number (or statement) of the paper beside archquake's.

    Parameters
    ----------
    quantity : str
        What is compared.
    source : str
        Where the paper states it (page, figure).
    paper : str
        The paper's value, as the paper states it.
    archquake : str
        archquake's value, formatted.
    tolerance : str
        The accepted difference (or the criterion).
    justification : str
        Why that tolerance: how many digits the paper gives, what it reads off a figure, what
        the criterion means.
    passed : bool or None
        True/False; None when the comparison does not apply (``note`` says why).
    note : str
        Why a row is not applicable, or where archquake departs from the paper and why.
    departure : bool
        A not-applicable row (``passed`` None) that states a deliberate departure from the
        paper (e.g. a claim the exact analysis contradicts), explained in ``note``.
    """

    quantity: str
    source: str
    paper: str
    archquake: str
    tolerance: str
    justification: str
    passed: bool | None
    note: str = ""
    departure: bool = False

    def __post_init__(self) -> None:
        if self.passed is None and not self.note:
            raise ValueError(f"row {self.quantity!r}: a not-applicable row must say why (note)")
        if self.passed is not None:
            object.__setattr__(self, "passed", bool(self.passed))
            if self.departure:
                raise ValueError(f"row {self.quantity!r}: a departure is not a pass or a fail")

    @property
    def status(self) -> str:
        """'pass', 'fail', 'departure' or 'n/a'."""
        if self.passed is None:
            return "departure" if self.departure else "n/a"
        return "pass" if self.passed else "fail"

    @property
    def mark(self) -> str:
        """What the report shows: 'pass', 'FAIL', 'departs' or 'n/a'."""
        return {"pass": "pass", "fail": "FAIL", "departure": "departs", "n/a": "n/a"}[self.status]

    def to_dict(self) -> dict:
        return {
            "quantity": self.quantity,
            "source": self.source,
            "paper": self.paper,
            "archquake": self.archquake,
            "tolerance": self.tolerance,
            "justification": self.justification,
            "pass": self.passed,
            "note": self.note,
            "departure": self.departure,
            "status": self.status,
        }

    @classmethod
    def from_dict(cls, d: dict) -> Row:
        return cls(
            d["quantity"],
            d["source"],
            d["paper"],
            d["archquake"],
            d["tolerance"],
            d["justification"],
            d["pass"],
            d.get("note", ""),
            d.get("departure", False),
        )


def within(value: float, target: float, tolerance: float) -> bool:
    """|value - target| <= tolerance (False for NaN)."""
    return bool(math.isfinite(value) and abs(value - target) <= tolerance)


def paper_row(
    quantity: str,
    value: PaperValue,
    archquake: str,
    x: float | None,
    *,
    source: str | None = None,
    paper: str | None = None,
    justification: str | None = None,
) -> Row:
    """The row of a number the paper states (`PaperValue`):
    its page, value, tolerance and why come from `archquake.validation.paper`; ``x`` is
    archquake's value (None when not computed), ``archquake`` its formatted text. ``source``,
    ``paper`` and ``justification`` only add context (a figure panel, "(same arch)")."""
    return Row(
        quantity,
        value.where if source is None else source,
        value.stated if paper is None else paper,
        archquake,
        value.tolerance_text,
        value.why if justification is None else justification,
        value.within(x),
    )


def domain_settings(quick: bool):
    """The four-link domain search of the reproduction: coarse in quick mode."""
    from archquake.domains import DomainSettings

    return (
        DomainSettings(coarse_points=20, fine_points=8, precision_g=5e-3) if quick else DomainSettings()
    )


def fmt(x: float | None, digits: int = 3) -> str:
    """``x`` to ``digits`` decimals, "none" for None or NaN."""
    return "none" if x is None or not math.isfinite(x) else f"{x:.{digits}f}"


def at_least(upper: np.ndarray, lower: np.ndarray, slack: float) -> bool:
    """``upper`` >= ``lower`` - slack at every duration; NaN (no collapse up to the scan's
    ceiling) counts as above everything."""
    u = np.where(np.isfinite(upper), upper, np.inf)
    lo = np.where(np.isfinite(lower), lower, np.inf)
    return bool(np.all(u >= lo - slack))


def nondecreasing(a: np.ndarray, slack: float) -> bool:
    """The finite entries of ``a`` never fall by more than ``slack``."""
    a = a[np.isfinite(a)]
    return bool(np.all(np.diff(a) >= -slack))


@dataclass(frozen=True)
class Figure:
    """A figure written by a study: file name (inside the figures folder) and caption."""

    file: str
    caption: str

    def to_dict(self) -> dict:
        return {"file": self.file, "caption": self.caption}


@dataclass(frozen=True)
class StudyResult:
    """What one study found.

    Attributes
    ----------
    name : str
        Registry key (also the cache key's first part).
    title : str
    rows : tuple of Row
    figures : tuple of Figure
        Files inside the figures folder.
    departures : tuple of str
        Where archquake departs from the paper, and why (plain sentences).
    data : dict
        Numbers behind the rows (JSON-able), for ``--json`` and the cache.
    seconds : float
        Wall time of the computation, s.
    """

    name: str
    title: str
    rows: tuple[Row, ...]
    figures: tuple[Figure, ...] = ()
    departures: tuple[str, ...] = ()
    data: dict = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def counts(self) -> dict[str, int]:
        """Rows passed, failed, departing from the paper, and not applicable."""
        out = {"pass": 0, "fail": 0, "departure": 0, "n/a": 0}
        for r in self.rows:
            out[r.status] += 1
        return out

    def to_dict(self) -> dict:
        return to_jsonable(
            {
                "name": self.name,
                "title": self.title,
                "rows": [r.to_dict() for r in self.rows],
                "figures": [f.to_dict() for f in self.figures],
                "departures": list(self.departures),
                "data": self.data,
                "seconds": self.seconds,
            }
        )

    @classmethod
    def from_dict(cls, d: dict) -> StudyResult:
        return cls(
            d["name"],
            d["title"],
            tuple(Row.from_dict(r) for r in d["rows"]),
            tuple(Figure(f["file"], f["caption"]) for f in d["figures"]),
            tuple(d["departures"]),
            d.get("data", {}),
            float(d.get("seconds", 0.0)),
        )


StudyFunction = Callable[[Arch, bool, Path], StudyResult]


@dataclass(frozen=True)
class Study:
    """A registry entry: the study's key, its title, what of the paper it covers, and the
    function (imported lazily from ``target`` = ``"module:function"``)."""

    name: str
    title: str
    covers: str
    target: str

    def function(self) -> StudyFunction:
        import importlib

        module, func = self.target.split(":")
        return getattr(importlib.import_module(module), func)


# ----------------------------------------------------------------------- trustworthy files
def _fsync_dir(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:  # a platform without directory descriptors
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def commit_file(source: str | Path, target: str | Path) -> Path:
    """Move a finished file into place atomically: fsync its bytes, rename it over ``target``
    (same folder, so the rename is atomic), fsync the folder. A reader (or a run after a
    ``kill -9``) sees the old file or the new one, never a part of it."""
    source, target = Path(source), Path(target)
    with open(source, "rb") as fh:
        os.fsync(fh.fileno())
    os.replace(source, target)
    _fsync_dir(target.parent)
    return target


def atomic_write_bytes(path: str | Path, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same folder, fsync and
    rename (`commit_file`): an interrupted write leaves the old file or none."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    _fsync_dir(path.parent)
    return path


def atomic_write_text(path: str | Path, text: str) -> Path:
    """`atomic_write_bytes` of UTF-8 text."""
    return atomic_write_bytes(path, text.encode("utf-8"))


def file_seal(path: str | Path) -> dict:
    """What a cache entry records of a file it relies on: ``{"size_bytes", "sha256"}``."""
    h = hashlib.sha256()
    size = 0
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
            size += len(block)
    return {"size_bytes": size, "sha256": h.hexdigest()}


def seal_intact(path: str | Path, seal: object) -> bool:
    """True if ``path`` exists with the size and SHA-256 of ``seal`` (`file_seal`); a
    missing seal, a 0-byte, truncated or altered file is not intact."""
    if not isinstance(seal, dict) or "size_bytes" not in seal or "sha256" not in seal:
        return False
    path = Path(path)
    try:
        if path.stat().st_size != seal["size_bytes"]:
            return False
        return file_seal(path)["sha256"] == seal["sha256"]
    except OSError:
        return False


__all__ = [
    "atomic_write_bytes",
    "atomic_write_text",
    "commit_file",
    "file_seal",
    "seal_intact",
    "Figure",
    "Row",
    "Study",
    "StudyFunction",
    "StudyResult",
    "at_least",
    "domain_settings",
    "fmt",
    "nondecreasing",
    "paper_row",
    "within",
]
