"""Run the registered studies into a folder, reusing what an earlier (interrupted) run finished.

Layout of the output folder ``out``::

    out/report.md, out/report.html      the report (HTML self-contained)
    out/figures/<study>_*.png           the figures
    out/cache/<study>-<version>-<quick|full>.json
                                        each finished study's result

A study's cache entry is written only after its figures, so an interrupted run leaves either a
complete entry or none. A rerun with the same archquake version and the same quick flag skips
every study whose entry exists and whose figures are all present; ``force`` recomputes.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from archquake import __version__
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.reproduce.core import Study, StudyResult
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


def _load_cached(out: Path, name: str, quick: bool) -> StudyResult | None:
    path = cache_path(out, name, quick)
    try:
        result = StudyResult.from_dict(json.loads(path.read_text()))
    except (OSError, ValueError, KeyError, TypeError):
        return None
    figures = Path(out) / "figures"
    if result.name != name or not all((figures / f.file).is_file() for f in result.figures):
        return None
    return result


def _store(out: Path, result: StudyResult, quick: bool) -> None:
    path = cache_path(out, result.name, quick)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(result.to_dict(), indent=1))
    os.replace(tmp, path)  # atomic: an interrupted write leaves no entry


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
        cached = None if force else _load_cached(out, study.name, quick)
        if cached is not None:
            runs.append(StudyRun(cached, True))
            if progress:
                progress(f"{head}: cached ({cached.seconds:.1f} s when computed)")
            continue
        t0 = time.perf_counter()
        result = study.function()(arch, quick, figures)
        result = replace(result, seconds=time.perf_counter() - t0)
        _store(out, result, quick)
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


__all__ = ["Reproduction", "StudyRun", "cache_path", "run_studies", "select"]
