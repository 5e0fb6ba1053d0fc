"""Run an assessment into a folder, resuming what an interrupted run finished.

Layout of ``out`` (the reproduction's, :mod:`archquake.reproduce.runner`)::

    out/report.md, out/report.html, out/results.json
    out/figures/*.png
    out/cache/assess-<section>-<digest>-<version>-<quick|full>.json   each finished section
    out/cache/ida-<digest>-<quick|full>.sqlite                        the IDA's runs

``digest`` hashes the validated input (:meth:`AssessConfig.digest`), so a changed file never
reuses a stale section.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from archquake import __version__
from archquake._json import to_jsonable
from archquake.assess.config import AssessConfig
from archquake.assess.sections import SECTIONS, Context, Mode, dynamics_refusal, verdict
from archquake.reproduce.core import StudyResult
from archquake.reproduce.runner import _load_cached, _store


@dataclass(frozen=True)
class Assessment:
    """Every section's result (by name), the verdict, and where the report went."""

    config: AssessConfig
    sections: dict
    cached: dict
    verdict: dict
    quick: bool
    out: Path
    seconds: float

    def data(self, name: str) -> dict:
        return self.sections[name].data

    def to_dict(self) -> dict:
        return to_jsonable({
            "archquake_version": __version__,
            "model": self.config.model,
            "input": self.config.canonical(),
            "source": self.config.source,
            "quick": self.quick,
            "seconds": self.seconds,
            "sections": {k: dict(v.data, seconds=v.seconds, cached=self.cached[k],
                                 figures=[f.file for f in v.figures])
                         for k, v in self.sections.items()},
            "verdict": self.verdict,
            "report_html": str(self.out / "report.html"),
            "report_md": str(self.out / "report.md"),
        })


def section_names(config: AssessConfig, arch=None) -> list[str]:
    """The sections this input calls for (records only with a suite, the DEM only if asked; no
    pulses, records or DEM for an ``arch`` the four-link model cannot take:
    :func:`~archquake.assess.sections.dynamics_refusal`, reported in the validity section)."""
    names = [n for n, _ in SECTIONS]
    if config.suite is None:
        names.remove("records")
    if not config.dem:
        names.remove("dem")
    if config.site is None:
        names.remove("codecheck")
    if arch is not None and dynamics_refusal(arch, config.model) is not None:
        names = [n for n in names if n not in ("pulses", "records", "dem")]
    return names


def run_assessment(config: AssessConfig, out: str | Path, *, quick: bool = False,
                   force: bool = False, progress: Callable[[str], None] | None = None,
                   report: bool = True) -> Assessment:
    """Assess ``config``'s arch into ``out`` (see the module docstring).

    Parameters
    ----------
    config : AssessConfig
    out : path
        Output folder (created).
    quick : bool
        Coarse domains, four records of the suite, one DEM run per governing case.
    force : bool
        Recompute every section even if cached.
    progress : callable, optional
        Called with one line per step.
    report : bool
        Write report.md, report.html and results.json.
    """
    t0 = time.perf_counter()
    out = Path(out)
    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    arch = config.build_arch()
    funcs = dict(SECTIONS)
    names = section_names(config, arch)
    results: dict[str, StudyResult] = {}
    cached: dict[str, bool] = {}
    for k, name in enumerate(names, 1):
        key = f"assess-{name}-{config.digest}"
        hit = None if force else _load_cached(out, key, quick)
        head = f"[{k}/{len(names)}] {name}"
        if hit is not None:
            results[name], cached[name] = hit, True
            if progress:
                progress(f"{head}: cached ({hit.seconds:.1f} s when computed)")
            continue
        if progress:
            progress(f"{head} ...")
        ctx = Context(config, arch, Mode(quick), figures, out,
                      {n: r.data for n, r in results.items()}, progress)
        s0 = time.perf_counter()
        res = funcs[name](ctx)
        res = replace(res, name=key, seconds=time.perf_counter() - s0)
        _store(out, res, quick)
        # what the cache gives back (JSON types), so a fresh and a resumed run report alike
        results[name], cached[name] = StudyResult.from_dict(json.loads(json.dumps(
            res.to_dict()))), False
        if progress:
            progress(f"{head}: {res.seconds:.1f} s")
    v = verdict(config, {n: r.data for n, r in results.items()})
    rep = Assessment(config, results, cached, v, quick, out, time.perf_counter() - t0)
    if report:
        from archquake.assess.report import write_html, write_markdown

        write_markdown(rep, out / "report.md")
        write_html(rep, out / "report.html")
        (out / "results.json").write_text(json.dumps(rep.to_dict(), indent=1) + "\n")
    return rep


__all__ = ["Assessment", "run_assessment", "section_names"]
