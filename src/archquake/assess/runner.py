"""Run an assessment into a folder, resuming what an interrupted run finished.

Layout of ``out`` (the reproduction's, `archquake.reproduce.runner`)::

    out/report.md, out/report.html, out/results.json
    out/figures/*.png
    out/cache/assess-<section>-<digest>-<version>-<quick|full>.json   each finished section
    out/cache/ida-<digest>-<quick|full>.sqlite                        the IDA's runs

``digest`` hashes the validated input (`AssessConfig.digest`), so a changed file never
reuses a stale section.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path

from archquake import __version__, models
from archquake._json import to_jsonable
from archquake.assess.config import AssessConfig
from archquake.assess.sections import (
    SECTIONS,
    Context,
    Mode,
    dynamics_refusal,
    verdict,
    with_dem_warnings,
)
from archquake.reproduce.core import StudyResult
from archquake.reproduce.runner import load_cached, store_result


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
            "site_pga_source": self.config.site_pga_source,
            "input_warnings": list(self.config.notes),
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
    `dynamics_refusal`, reported in the validity section)."""
    names = [n for n, _ in SECTIONS]
    if config.suite is None:
        names.remove("records")
    if not config.dem:
        names.remove("dem")
    if config.site is None:
        names.remove("codecheck")
    if config.loads is None or config.loads.traffic is None:
        names.remove("traffic")
    if not (config.vertical_ratio or (config.suite_vertical and "records" in names)):
        names.remove("vertical")
    if arch is not None and dynamics_refusal(arch, config.model) is not None:
        names = [n for n in names if n not in ("pulses", "records", "dem", "vertical")]
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
    side_by_side = models.takes(config.model, "guard")  # the verdict batches' threads
    if progress is not None and side_by_side:
        progress = _one_at_a_time(progress)

    shared = _Shared()

    def run(k: int, name: str, prior: dict) -> None:
        key = f"assess-{name}-{config.digest}"
        hit = None if force else load_cached(out, key, quick)
        head = f"[{k}/{len(names)}] {name}"
        if hit is not None:
            results[name], cached[name] = hit, True
            if progress:
                progress(f"{head}: cached ({hit.seconds:.1f} s when computed)")
            return
        if progress:
            progress(f"{head} ...")
        ctx = Context(config, arch, Mode(quick), figures, out, prior,
                      _tagged(progress, name) if side_by_side else progress,
                      lambda key, value: shared.put(name, key, value))
        s0 = time.perf_counter()
        res = funcs[name](ctx)
        res = replace(res, name=key, seconds=time.perf_counter() - s0)
        store_result(out, res, quick)
        # what the cache gives back (JSON types), so a fresh and a resumed run report alike
        results[name], cached[name] = StudyResult.from_dict(json.loads(json.dumps(
            res.to_dict()))), False
        if progress:
            progress(f"{head}: {res.seconds:.1f} s")

    _run_sections(names, run, results, side_by_side, shared)
    results = {n: results[n] for n in names}  # the report's order
    if "validity" in results:
        va = results["validity"]
        results["validity"] = replace(va, data=with_dem_warnings(
            va.data, results["dem"].data if "dem" in results else None, config.model))
    v = verdict(config, {n: r.data for n, r in results.items()}, quick=quick)
    rep = Assessment(config, results, cached, v, quick, out, time.perf_counter() - t0)
    if report:
        from archquake.assess.report import write_html, write_markdown

        write_markdown(rep, out / "report.md")
        write_html(rep, out / "report.html")
        (out / "results.json").write_text(json.dumps(rep.to_dict(), indent=1) + "\n")
    return rep


def _one_at_a_time(progress: Callable[[str], None]) -> Callable[[str], None]:
    """``progress`` called by one thread at a time (whole lines from sections side by side)."""
    lock = threading.Lock()

    def say(line: str) -> None:
        with lock:
            progress(line)

    return say


def _tagged(progress: Callable[[str], None] | None, name: str
            ) -> Callable[[str], None] | None:
    """``progress`` with each line tagged by its section (sections running side by side)."""
    if progress is None:
        return None
    return lambda line: progress(f"  [{name}] {line.strip()}")


#: The sections whose data each section reads (``Context.prior``). The validity section does not
#: wait for the DEM check; the DEM check's warnings are added to it afterwards
#: (`with_dem_warnings`).
NEEDS: dict[str, tuple[str, ...]] = {
    "arch": (), "static": (), "traffic": (), "codecheck": (), "pulses": (), "records": (),
    "dem": ("static", "pulses", "records"), "validity": ("static", "pulses", "records"),
    "vertical": ("records",)}
#: Of `NEEDS`, the sections a section reads only once it has started the work that does not
#: depend on them: side by side, it starts once the others are done, and its reading of one of
#: these waits until that one is done (the DEM check's and the validity section's pulse runs
#: need only the pulses; only their governing record's runs wait for the records' IDA, until it
#: has settled every record's first collapse).
LATER: dict[str, tuple[str, ...]] = {"dem": ("records",), "validity": ("records",)}


class _Shared:
    """Values of sections' data handed out before their sections are done
    (`archquake.assess.sections.Context.share`), and the waits for them."""

    def __init__(self) -> None:
        self._values: dict[str, dict] = {}
        self._changed = threading.Condition()

    def put(self, name: str, key: str, value) -> None:
        with self._changed:
            self._values.setdefault(name, {})[key] = value
            self._changed.notify_all()

    def wait(self, name: str, key: str, done: threading.Event) -> tuple[bool, object]:
        """(True, the value) once section ``name`` has shared ``key``, or (False, None) once
        it is done without sharing it."""
        with self._changed:
            while True:
                if key in self._values.get(name, {}):
                    return True, self._values[name][key]
                if done.is_set():
                    return False, None
                self._changed.wait(0.2)


class _Prior(Mapping):
    """The data of the sections ``names`` (`NEEDS`) in ``results``, each read waiting until its
    section is done (`LATER`), or, with `early`, until it shares the value read; a section
    that failed or was not run reads as absent (the failure itself reaches the caller from its
    own section)."""

    def __init__(self, names, results: dict, done: dict, failed: dict,
                 shared: _Shared | None = None):
        self._names = tuple(n for n in names if n in done or n in results)
        self._results, self._done, self._failed = results, done, failed
        self._shared = _Shared() if shared is None else shared

    def early(self, name: str, key: str, default=None):
        """``key`` of section ``name``'s data as soon as it is shared, else once the section is
        done; ``default`` if the section does not run."""
        if name not in self._names:
            return default
        if name in self._done:
            found, value = self._shared.wait(name, key, self._done[name])
            if found:
                return value
        return self[name].get(key, default)

    def __getitem__(self, name: str) -> dict:
        if name not in self._names:
            raise KeyError(name)
        if name in self._done:
            self._done[name].wait()
        if name in self._failed or name not in self._results:
            raise _Lost(name)
        return self._results[name].data

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)


class _Lost(Exception):
    """A section read the data of one that failed (that failure is the one raised)."""


#: What the sections import as they run, imported here before they start side by side. Two
#: threads importing one package at once can each take the other's module lock; Python then
#: hands one of them the package half initialised, and an import inside it fails
#: ("cannot import name 'rigid' from 'archquake'": the pulses' verdicts importing
#: `archquake.rigid.verdict` while the records' IDA imported `archquake.rigid`). Every
#: package module the sections can reach, as a test reads them from the code.
SECTION_MODULES = (
    "archquake.assess.report", "archquake.blocks", "archquake.blocks.result", "archquake.codecheck",
    "archquake.codecheck.timehistory", "archquake.codes", "archquake.compare", "archquake.compare.domains",
    "archquake.compare.histories", "archquake.compare.snapshots", "archquake.dem", "archquake.dem.run",
    "archquake.domains", "archquake.domains.batch", "archquake.domains.blocks", "archquake.domains.studies",
    "archquake.geometry", "archquake.geometry.carrying", "archquake.geometry.survey", "archquake.ground",
    "archquake.ground.response_spectra", "archquake.ground.selection", "archquake.ground.suites",
    "archquake.ground.vertical", "archquake.ida", "archquake.ida._kernels", "archquake.ida.batch",
    "archquake.ida.fragility", "archquake.limit", "archquake.limit.capacity", "archquake.limit.loaded",
    "archquake.mechanism", "archquake.mechanism.impact_chain", "archquake.models", "archquake.plotting",
    "archquake.plotting.arch", "archquake.plotting.codecheck", "archquake.plotting.compare",
    "archquake.plotting.dem", "archquake.plotting.domains", "archquake.plotting.figures",
    "archquake.plotting.history", "archquake.plotting.ida", "archquake.plotting.loads",
    "archquake.plotting.spectra", "archquake.plotting.thrust", "archquake.reproduce",
    "archquake.reproduce.registry", "archquake.reproduce.report", "archquake.rigid",
    "archquake.rigid._force_kernels", "archquake.rigid.events", "archquake.rigid.forces",
    "archquake.rigid.run", "archquake.rigid.verdict", "archquake.sweeps", "archquake.sweeps.evaluate",
    "archquake.sweeps.runner", "archquake.sweeps.study", "archquake.thrust", "archquake.validation",
    "archquake.validation.paper",
)


def import_section_modules() -> None:
    """Import `SECTION_MODULES` (before the sections start in threads)."""
    import importlib

    for name in SECTION_MODULES:
        importlib.import_module(name)


def _run_sections(names: list[str], run, results: dict, side_by_side: bool,
                  shared: _Shared | None = None) -> None:
    """Call ``run(k, name, prior)`` for every section, ``prior`` the data of the sections it
    needs (`NEEDS`): one after another, or with ``side_by_side`` each in its own thread
    as soon as those are done (the chain of rigid voussoirs' sections spend their time in
    compiled kernels that release the GIL, and in worker processes; the four-link model's
    threaded kernels cannot be entered from two threads at once).

    The threads are daemons: on Ctrl-C this thread stops waiting at once, the command ends,
    and what each section finished is in the cache (its IDA's runs in their store)."""

    def prior_of(name: str) -> dict:
        return {n: results[n].data for n in NEEDS[name] if n in results}

    if not side_by_side:
        for k, name in enumerate(names, 1):
            run(k, name, prior_of(name))
        return
    import_section_modules()
    done = {name: threading.Event() for name in names}
    failed: dict[str, BaseException] = {}

    def task(k: int, name: str) -> None:
        try:
            first = [dep for dep in NEEDS[name] if dep not in LATER.get(name, ())]
            for dep in first:
                if dep in done:
                    done[dep].wait()
            lost = [dep for dep in first if dep in failed]
            if not lost:
                run(k, name, _Prior(NEEDS[name], results, done, failed, shared))
        except BaseException as exc:  # handed to the waiting thread, which raises it
            failed[name] = exc
        finally:
            done[name].set()

    for k, name in enumerate(names, 1):
        threading.Thread(target=task, args=(k, name), name=f"assess-{name}", daemon=True).start()
    for name in names:
        while not done[name].wait(0.2):  # short waits: Ctrl-C reaches this thread at once
            pass
        if name in failed:
            raise failed[name]


__all__ = ["LATER", "NEEDS", "SECTION_MODULES", "Assessment", "import_section_modules",
           "run_assessment", "section_names"]
