"""Run the registered studies into a folder, reusing what an earlier (interrupted) run finished.

Layout of the output folder ``out``::

    out/report.md, out/report.html      the report (HTML self-contained)
    out/figures/<study>_*.png           the figures
    out/cache/<study>-<version>-<quick|full>.json
                                        each finished study's result

A study draws its figures into a staging folder inside ``figures``; each finished figure is then
fsynced and renamed into place, and the cache entry, which records each figure's size and
SHA-256, is written last (to a temporary file, fsynced, renamed). An interrupted run (``kill -9``
included) therefore leaves complete files and either a complete entry or none. A rerun with the
same archquake version and the same quick flag skips every study whose entry exists and whose
figures all match their recorded size and hash (a 0-byte or truncated figure is recomputed, never
embedded); ``force`` recomputes.
"""

from __future__ import annotations

import json
import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from archquake import __version__
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.reproduce.core import (
    Study,
    StudyResult,
    atomic_write_text,
    commit_file,
    file_seal,
    seal_intact,
)
from archquake.reproduce.registry import STUDIES
from archquake.validation.paper import oppenheim_arch


@dataclass(frozen=True)
class StudyRun:
    """A study's result and whether it came from the cache."""

    result: StudyResult
    cached: bool


@dataclass(frozen=True)
class Reproduction:
    """Every study's result, and where the report was written."""

    runs: tuple[StudyRun, ...]
    out: Path
    quick: bool
    report_md: Path | None = None
    report_html: Path | None = None

    @property
    def results(self) -> tuple[StudyResult, ...]:
        return tuple(r.result for r in self.runs)

    @property
    def computed(self) -> int:
        """Studies computed in this run (the others came from the cache)."""
        return sum(not r.cached for r in self.runs)

    @property
    def counts(self) -> dict[str, int]:
        out = {"pass": 0, "fail": 0, "departure": 0, "n/a": 0}
        for res in self.results:
            for k, v in res.counts.items():
                out[k] += v
        return out

    def to_dict(self) -> dict:
        return {
            "archquake_version": __version__,
            "quick": self.quick,
            "out": str(self.out),
            "report_md": None if self.report_md is None else str(self.report_md),
            "report_html": None if self.report_html is None else str(self.report_html),
            "summary": self.counts,
            "computed": self.computed,
            "studies": [dict(r.result.to_dict(), cached=r.cached) for r in self.runs],
        }


def cache_path(out: Path, name: str, quick: bool, version: str = __version__) -> Path:
    """The cache entry of study ``name`` for this version and mode."""
    return Path(out) / "cache" / f"{name}-{version}-{'quick' if quick else 'full'}.json"


def load_cached(out: Path, name: str, quick: bool) -> StudyResult | None:
    """The cached result of study ``name`` under ``out`` (`store_result`), or None if
    there is none, it cannot be read, or a figure it drew is missing or altered."""
    path = cache_path(out, name, quick)
    try:
        entry = json.loads(path.read_text())
        result = StudyResult.from_dict(entry)
        seals = entry.get("figure_seals", {})
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    figures = Path(out) / "figures"
    if result.name != name or not isinstance(seals, dict):
        return None
    if not all(seal_intact(figures / f.file, seals.get(f.file)) for f in result.figures):
        return None  # a figure missing, empty, truncated or altered: recompute the study
    return result


def store_result(out: Path, result: StudyResult, quick: bool) -> None:
    """Write the cache entry (atomically) with each figure's size and SHA-256."""
    figures = Path(out) / "figures"
    entry = result.to_dict()
    entry["figure_seals"] = {f.file: file_seal(figures / f.file) for f in result.figures}
    atomic_write_text(cache_path(out, result.name, quick), json.dumps(entry, indent=1))


def _compute(study: Study, arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """Run ``study`` with its figures drawn into a staging folder, then commit each figure
    into ``figures`` (fsync, atomic rename)."""
    staging = Path(tempfile.mkdtemp(dir=figures, prefix=f".{study.name}-"))
    try:
        result = study.function()(arch, quick, staging)
        for item in sorted(staging.rglob("*")):
            if item.is_file():
                target = figures / item.relative_to(staging)
                target.parent.mkdir(parents=True, exist_ok=True)
                commit_file(item, target)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return result


def select(names: Sequence[str] | None) -> tuple[Study, ...]:
    """The registered studies named (all by default), in registry order."""
    if not names:
        return STUDIES
    known = {s.name for s in STUDIES}
    unknown = [n for n in names if n not in known]
    if unknown:
        raise InvalidParameterError(
            f"unknown study {', '.join(unknown)}: choose from {', '.join(sorted(known))}"
        )
    return tuple(s for s in STUDIES if s.name in set(names))


def run_studies(
    out: str | Path,
    *,
    quick: bool = False,
    force: bool = False,
    only: Sequence[str] | None = None,
    arch: Arch | None = None,
    progress: Callable[[str], None] | None = None,
    report: bool = True,
) -> Reproduction:
    """Run the studies into ``out`` and write the report.

    Parameters
    ----------
    out : path
        Output folder (created).
    quick : bool
        Coarse domains and fewer distinct-element runs (minutes instead of the full run's time).
    force : bool
        Recompute every study even if a cached result exists.
    only : sequence of str, optional
        Run only these studies (the report then covers only them).
    arch : Arch, optional
        The arch studied (default Oppenheim's: the paper's numbers refer to it).
    progress : callable, optional
        Called with one line per study (name, time, cached or not).
    report : bool
        Write report.md and report.html.
    """
    out = Path(out)
    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    arch = oppenheim_arch() if arch is None else arch
    runs = []
    studies = select(only)
    for k, study in enumerate(studies, 1):
        head = f"[{k}/{len(studies)}] {study.name:<10s} {study.title}"
        cached = None if force else load_cached(out, study.name, quick)
        if cached is not None:
            runs.append(StudyRun(cached, True))
            if progress:
                progress(f"{head}: cached ({cached.seconds:.1f} s when computed)")
            continue
        t0 = time.perf_counter()
        result = _compute(study, arch, quick, figures)
        result = replace(result, seconds=time.perf_counter() - t0)
        store_result(out, result, quick)
        runs.append(StudyRun(result, False))
        if progress:
            c = result.counts
            progress(
                f"{head}: {result.seconds:.1f} s ({c['pass']} pass, {c['fail']} fail, "
                f"{c['departure']} departures, {c['n/a']} n/a)"
            )
    rep = Reproduction(tuple(runs), out, quick)
    if report:
        from archquake.reproduce.report import write_html, write_markdown

        md = write_markdown(rep, out / "report.md")
        html = write_html(rep, out / "report.html")
        rep = replace(rep, report_md=md, report_html=html)
    return rep


__all__ = ["Reproduction", "StudyRun", "cache_path", "load_cached", "run_studies", "select",
           "store_result"]
