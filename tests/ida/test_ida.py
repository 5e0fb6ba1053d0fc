"""Incremental dynamic analysis: hunt-and-fill finds what the failure domain finds, the batch
evaluator is simulate, the store makes it resumable, the command line speaks one-line errors.

Oracles: the failure domain (archquake.domains, an independent search with its own scan and
bisection to 0.001 g) for a step pulse used as a one-record suite; archquake.mechanism.simulate
case by case for the compiled batch; an uninterrupted run for the resumed one; a made-up
outcome function with known bands for the pure hunt-and-fill logic.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from ida_inputs import OPPENHEIM

from archquake.domains import failure_domain, oppenheim_arch
from archquake.ground import StepImpulse
from archquake.ground.measures import im_value
from archquake.ida import HuntFill, incremental_dynamic_analysis, intervals, propose_levels
from archquake.ida.batch import evaluate_cases
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.parallel import SerialExecutor
from archquake.sweeps import Case, ExcitationSpec, ResultStore


# ----------------------------------------------------------------------------- pure logic
def _trace(outcome, settings):
    levels, collapsed, rounds = [], [], 0
    while True:
        new = propose_levels(levels, collapsed, settings)
        if not new:
            return levels, collapsed, rounds
        rounds += 1
        assert not set(new) & set(levels)
        levels += new
        collapsed += [outcome(x) for x in new]


def test_hunt_and_fill_finds_every_band_of_a_known_outcome_function():
    """Collapse from 0.6 except for survival on [1.0, 1.3) (a 30 % band) and [2.0, 2.1) (5 %,
    narrower than the 10 % fill, so it may be missed, as documented): the edges of the wide band
    and of the first collapse must be bracketed to 2 %."""
    def outcome(x):
        return x >= 0.6 and not (1.0 <= x < 1.3) and not (2.0 <= x < 2.1)

    s = HuntFill(start=0.37, ceiling=5.0, precision=0.02, fill=0.10)
    levels, collapsed, _ = _trace(outcome, s)
    runs = intervals(levels, collapsed, True)
    assert runs[0].below < 0.6 <= runs[0].low and runs[0].low / runs[0].below - 1 <= 0.02
    assert runs[0].high < 1.0 <= runs[0].above and runs[0].above / runs[0].high - 1 <= 0.02
    assert runs[1].below < 1.3 <= runs[1].low and runs[1].low / runs[1].below - 1 <= 0.02
    # the hunt went up with growing steps before the first collapse
    hunt = sorted(levels)[:4]
    steps = np.diff(hunt)
    assert np.all(steps[1:] > steps[:-1])
    # every gap is at most the fill, every transition at most the precision
    obs = sorted(zip(levels, collapsed, strict=True))
    for (a, ca), (b, cb) in zip(obs, obs[1:], strict=False):
        assert b / a - 1 <= (0.02 if ca != cb else 0.10) + 1e-12


def test_the_trace_does_not_depend_on_the_order_results_arrive():
    """Replaying with results delivered one level at a time (an interrupted round) converges to
    the same set of levels as whole rounds."""
    def outcome(x):
        return 0.8 <= x < 1.5 or x >= 1.9

    s = HuntFill(start=0.4, ceiling=4.0)
    whole, _, _ = _trace(outcome, s)
    levels, collapsed = [], []
    while True:
        new = propose_levels(levels, collapsed, s)
        if not new:
            break
        levels.append(new[-1])  # only one of each round's proposals "arrives"
        collapsed.append(outcome(new[-1]))
    assert sorted(levels) == sorted(whole)


# ----------------------------------------------------------------------------- the step pulse
@pytest.mark.parametrize("tp", [0.273, 0.385])
def test_step_pulse_ida_reproduces_the_failure_domain(tmp_path, tp):
    """docs/domains.md: at t_p = 0.273 s Oppenheim's arch collapses from 0.678 g (2nd half
    cycle), survives again for 1.688-1.834 g, and collapses in the 1st half cycle from 1.835 g.
    The IDA of the pulse as a one-record suite (PGA = a) must find the same three transitions.
    Tolerance: each IDA bracket is 0.2 % wide (precision 0.002) and each domain bracket 0.001 g,
    so the domain's collapsing level must lie within the IDA bracket widened by 0.001 g."""
    dom = failure_domain(oppenheim_arch(), "step", [tp], model="fourlink")
    (band,) = dom.non_monotonic_bands
    with ResultStore(tmp_path / "s.sqlite") as store:
        res = incremental_dynamic_analysis(OPPENHEIM, [StepImpulse.from_g(1.0, tp)], "pga", store,
                                           model="fourlink", ceiling=5.0, precision=0.002, fill=0.05,
                                           executor=SerialExecutor())
    rec = res.records[0]
    first, second = rec.collapse_intervals
    tol = 0.001

    def inside(value, lo, hi):
        return lo - tol <= value <= hi + tol

    assert inside(dom.collapse_g[0], first.below, first.low)
    assert inside(band.lower_g, first.high, first.above)         # last collapse / first survival
    (resurrection,) = rec.resurrections
    assert inside(band.upper_g, resurrection.high, resurrection.above)
    assert inside(dom.first_half_cycle_g[0], second.below, second.low)
    assert second.above is None                                   # collapses up to the ceiling
    halves = dict(zip(rec.levels, rec.collapse_half_cycles, strict=True))
    assert {halves[x] for x in rec.levels if first.low <= x <= first.high} == {2}
    assert {halves[x] for x in rec.levels if x >= second.low} == {1}
    assert rec.start == pytest.approx(res.collapse_acceleration_g, rel=1e-12)
    assert rec.outcomes[0] == "no_hinging"


# ----------------------------------------------------------------------------- the batch
def test_batch_evaluator_is_simulate_case_by_case(records):
    prepared = PreparedMechanism.build(OPPENHEIM.build())
    cases = [Case(OPPENHEIM, ExcitationSpec("record", motion=r, scale=s), model="fourlink")
             for r in records for s in (0.9, 1.3, 2.0, 3.0, 4.5, 6.0)]
    batch = evaluate_cases(cases)
    outcomes = set()
    for case, got in zip(cases, batch, strict=True):
        ref = simulate(prepared, case.excitation.build(), options=SolverOptions(output_interval=0))
        assert got["outcome"] == ref.outcome.value
        assert got["collapse_half_cycle"] == ref.collapse_half_cycle
        outcomes.add(got["outcome"])
        if ref.outcome.value == "survives":
            # the largest peak: recorded before the early decision, or the free half cycle's
            # (bisection of the energy balance to round-off vs the kernel's event location)
            assert got["peak_rotation_max_rad"] == pytest.approx(ref.peak_rotation.max(),
                                                                  rel=1e-7, abs=1e-12)
    assert outcomes == {"no_hinging", "survives", "collapse"}


def test_batch_evaluator_is_simulate_under_the_followed_chain_law(records):
    """The chain law's two mechanisms on Oppenheim's arch: outcome, collapse half cycle and the
    largest peak (free rocking over the table after the early decision) as simulate's."""
    from archquake.sweeps import CaseOptions

    prepared = PreparedMechanism.build(OPPENHEIM.build(), "chain")
    assert prepared.table.size == 2
    opts = CaseOptions(impact="chain")
    cases = [Case(OPPENHEIM, ExcitationSpec("record", motion=r, scale=s), "fourlink", opts)
             for r in records for s in (1.3, 2.0, 3.0, 4.5)]
    batch = evaluate_cases(cases)
    early = 0
    for case, got in zip(cases, batch, strict=True):
        ref = simulate(prepared, case.excitation.build(), options=SolverOptions(output_interval=0))
        assert got["outcome"] == ref.outcome.value
        assert got["collapse_half_cycle"] == ref.collapse_half_cycle
        if ref.outcome.value == "survives":
            early += got["kernel_runs"] == 1
            assert got["peak_rotation_max_rad"] == pytest.approx(ref.peak_rotation.max(),
                                                                  rel=1e-7, abs=1e-12)
    assert early >= 1  # the early decision was taken (and its peak checked)


@pytest.mark.parametrize("early", [True, False])
def test_batch_evaluator_states_a_cut_run_as_simulate_does(early):
    """Runs cut by the case's t_end (Oppenheim's arch, Eq. 4, step impulses; the excitation
    ends at 3 t_p). Oracle: evaluate_case (simulate) case by case, whose rule (outcome.conclude)
    is pinned here: cut before the excitation ends (t_end 0.3 s), nothing is shown
    (indeterminate, also for 0.3 g, which has not yet hinged); 1.0 g, t_p = 0.27 s cut at 1.5 s
    rocks with more energy than the crest barrier (its full run collapses in half cycle 2,
    paper Figure 4c): indeterminate, not a survival; 1.0 g, t_p = 0.20 s to the default end
    survives."""
    from archquake.sweeps import CaseOptions
    from archquake.sweeps.evaluate import evaluate_case

    specs = [(0.3, 1.0, 0.20), (0.3, 0.3, 0.20), (1.5, 1.0, 0.27), (None, 1.0, 0.27),
             (None, 1.0, 0.20)]
    cases = [Case(OPPENHEIM, ExcitationSpec("step", magnitude_g=a, duration_s=d), "fourlink",
                  options=CaseOptions(t_end_s=t)) for t, a, d in specs]
    got = [r["outcome"] for r in evaluate_cases(cases, early=early)]
    ref = [evaluate_case(c)["outcome"] for c in cases]
    assert got == ref == ["indeterminate", "indeterminate", "indeterminate", "collapse",
                          "survives"]


def test_cases_are_dealt_to_the_threads_in_turn():
    # Oracle: numba's static schedule, one contiguous block per thread, the first blocks one
    # longer (n = 7 on 2 threads: 4 + 3); each block must then hold every T-th case.
    from archquake.ida.batch import thread_order

    assert thread_order(7, 2) == [0, 2, 4, 6, 1, 3, 5]
    for n, t in ((28, 2), (29, 4), (3, 8), (1, 1), (0, 2)):
        order = thread_order(n, t)
        assert sorted(order) == list(range(n))
        size = -(-n // t) if n else 0
        if n >= t:
            assert order[:size] == list(range(0, n, t))


def test_a_round_is_one_task_per_worker():
    from concurrent.futures import ThreadPoolExecutor

    from archquake.ida.analysis import round_chunk_size

    assert round_chunk_size(262, SerialExecutor(), None) == 262
    with ThreadPoolExecutor(3) as pool:
        assert round_chunk_size(262, pool, None) == 88
    assert round_chunk_size(262, None, 2) == 131
    assert round_chunk_size(1, None, 4) == 1


def test_the_fourlink_ida_runs_in_process_by_default(tmp_path, monkeypatch):
    # the compiled batch spreads a round over the cores itself: no process pool unless asked
    # (executor or workers); each round is one task for the in-process executor
    import archquake.sweeps.runner as runner

    seen = []
    real = runner.run_sweep

    def spy(cases, store, **kwargs):
        seen.append((type(kwargs["executor"]).__name__, kwargs["chunk_size"], len(cases)))
        return real(cases, store, **kwargs)

    monkeypatch.setattr(runner, "run_sweep", spy)
    with ResultStore(tmp_path / "d.sqlite") as store:
        incremental_dynamic_analysis(OPPENHEIM, [StepImpulse.from_g(1.0, 0.3)], "pga", store,
                                     model="fourlink", ceiling=1.0, precision=0.2, fill=0.5)
    assert seen and all(kind == "SerialExecutor" and chunk == n for kind, chunk, n in seen)


def test_prescribed_restitution_reaches_the_batch(records):
    prepared = PreparedMechanism.build(OPPENHEIM.build())
    from archquake.sweeps import CaseOptions

    case = Case(OPPENHEIM, ExcitationSpec("record", motion=records[0], scale=3.0), "fourlink",
                options=CaseOptions(restitution=0.6))
    (got,) = evaluate_cases([case])
    ref = simulate(prepared, case.excitation.build(), restitution=0.6,
                   options=SolverOptions(output_interval=0))
    assert got["restitution_cv"] == 0.6 and got["outcome"] == ref.outcome.value


# ----------------------------------------------------------------------------- the store
def test_interrupted_ida_resumes_to_the_same_result(tmp_path, records):
    kwargs = dict(ceiling=3.0, precision=0.05, fill=0.2, executor=SerialExecutor(),
                  chunk_size=4)
    with ResultStore(tmp_path / "full.sqlite") as store:
        full = incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", **kwargs)

    class Stop(KeyboardInterrupt):
        pass

    calls = []

    def progress(done, total, rounds):
        calls.append(rounds)
        if rounds == 4 and len(calls) > 6:
            raise Stop

    path = tmp_path / "cut.sqlite"
    with ResultStore(path) as store, pytest.raises(Stop):
        incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", progress=progress,
                                     **kwargs)
    with ResultStore(path) as store:
        partial = store.count()
        again = incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", **kwargs)
    assert 0 < partial < full.total
    assert again.computed == full.total - partial
    assert again.to_dict()["records"] == full.to_dict()["records"]
    with ResultStore(path) as store:
        rerun = incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", **kwargs)
    assert rerun.computed == 0 and rerun.total == full.total


def test_levels_are_the_intensity_measure_of_the_scaled_record(tmp_path, records):
    with ResultStore(tmp_path / "pgv.sqlite") as store:
        res = incremental_dynamic_analysis(OPPENHEIM, records[:1], "pgv", store,
                                           model="fourlink", ceiling=2.0,
                                           precision=0.1, fill=0.5, executor=SerialExecutor())
    rec = res.records[0]
    for level, factor in zip(rec.levels, rec.factors, strict=True):
        assert im_value(records[0].scaled(factor), "pgv") == pytest.approx(level, rel=1e-12)
    # the first level is where the scaled record's PGA is lambda g
    assert im_value(records[0].scaled(rec.factors[0]), "pga") == pytest.approx(
        res.collapse_acceleration_g, rel=1e-12)
    # the first collapse in PGA terms is the same scale factor seen through PGA
    first_pga = res.first_collapse_in("pga")[0]
    assert first_pga == pytest.approx(
        im_value(records[0].scaled(rec.factor_at(rec.first_collapse_level, 1)), "pga"), rel=1e-12)


def test_dem_model_goes_through_the_same_rounds(tmp_path):
    """A DEM IDA of the step pulse t_p = 0.3 s (one-record suite, 10 % precision): its first
    collapse bracket must overlap the DEM failure domain's governing boundary at that duration,
    0.672 g with a 0.01 g bracket (docs/models/dem.md, an independent bisection on the DEM), and lie
    above the four-link 0.610 g (the DEM is the stronger model there). All runs are DEM cases."""
    pulse = [StepImpulse.from_g(1.0, 0.3)]
    with ResultStore(tmp_path / "dem.sqlite") as store:
        res = incremental_dynamic_analysis(OPPENHEIM, pulse, "pga", store, ceiling=1.0,
                                           precision=0.1, fill=1.0, model="dem",
                                           executor=SerialExecutor())
        rows = store.rows()
    assert {r["model"] for r in rows} == {"dem"}
    first = res.records[0].first_collapse
    assert first.below < 0.672 and first.low > 0.662
    assert first.below > 0.610


# ----------------------------------------------------------------------------- command line
def test_cli_ida_json_and_csv(tmp_path, capsys, records):
    from archquake.cli.main import main

    folder = tmp_path / "suite"
    folder.mkdir()
    for r in records:
        t = np.arange(r.points) * r.dt
        np.savetxt(folder / f"{r.name}.csv", np.column_stack([t, r.accelerations]),
                   delimiter=",", header="time_s,acc_m_s2", comments="")
    argv = ["ida", "--model", "fourlink", "--records", str(folder), "--units", "m/s2",
            "--ceiling", "2.5",
            "--precision", "0.05", "--fill", "0.2", "--workers", "1", "--no-progress",
            "--store", str(tmp_path / "i.sqlite"), "--csv", str(tmp_path / "runs.csv"),
            "--bootstrap", "50", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "fourlink"
    assert out["im"] == "pga" and out["records_total"] == 3
    assert out["computed_now"] == out["cases_total"] > 0
    assert {"first_collapse", "collapse_fraction"} <= set(out["fragility"])
    dim = out["fragility_dimensionless"]
    assert dim["divisor"] == "/ lambda"
    assert dim["first_collapse"]["median_dimensionless"] == pytest.approx(
        out["fragility"]["first_collapse"]["median_g"] / out["collapse_acceleration_g"], rel=1e-12)
    # the dispersion row of the analysis's own IM is fit (a) without bootstrap
    (pga,) = [r for r in out["dispersion_by_im"] if r["im"] == "pga"]
    assert pga["median_g"] == pytest.approx(out["fragility"]["first_collapse"]["median_g"],
                                            rel=1e-9)
    assert pga["beta"] == pytest.approx(out["fragility"]["first_collapse"]["beta"], rel=1e-9)
    assert {"pgv", "sa:1", "arias"} <= {r["im"] for r in out["dispersion_by_im"]}
    lines = (tmp_path / "runs.csv").read_text().splitlines()
    assert len(lines) == out["cases_total"] + 1
    assert main(argv) == 0  # resumed entirely from the store
    again = json.loads(capsys.readouterr().out)
    assert again["computed_now"] == 0 and again["records"] == out["records"]


@pytest.mark.parametrize("extra, pool", [(["--model", "fourlink"], False),
                                         (["--model", "fourlink", "--workers", "2"], True),
                                         (["--model", "dem"], True), ([], False)])
def test_cli_executor_follows_the_library_default(tmp_path, monkeypatch, extra, pool):
    """The four-link model and the rigid chain (the default) with no --workers/--scheduler
    run as the library's default (in this process: no executor passed, no pool opened);
    --workers and the DEM open the pool.
    Oracle: the executor the analysis receives (a spy stops before any run)."""
    import archquake.ida
    import archquake.parallel
    from archquake.cli.main import main

    seen = []

    def spy(*args, executor=None, workers=None, **kwargs):
        seen.append((executor, workers))
        raise KeyboardInterrupt  # stop here: the CLI reports it as an interruption

    opened = []
    real = archquake.parallel.open_executor

    def open_spy(**kwargs):
        opened.append(kwargs)
        return real(**kwargs)

    monkeypatch.setattr(archquake.ida, "incremental_dynamic_analysis", spy)
    monkeypatch.setattr(archquake.parallel, "open_executor", open_spy)
    assert main(["ida", "--records", "near-field-pulse", "--no-progress", *extra,
                 "--store", str(tmp_path / "s.sqlite")]) == 130
    ((executor, workers),) = seen
    assert bool(opened) == pool and (executor is not None) == pool
    if not pool:
        assert workers is None


@pytest.mark.parametrize("extra, needle", [
    (["--im", "sa"], "--im"),
    (["--precision", "0"], "--precision"),
    (["--fill", "0.001"], "--fill"),
    (["--restitution", "1.5"], "--restitution"),
    (["--model", "dem", "--restitution", "0.5"], "--restitution"),
    (["--plot", "x.txt"], "--plot"),
    (["--records", "no-such-suite"], "--records"),
])
def test_cli_bad_options_are_one_line(tmp_path, capsys, extra, needle):
    from archquake.cli.main import main

    assert main(["ida", "--records", "near-field-pulse", *extra,
                 "--store", str(tmp_path / "never.sqlite")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0]
    assert not (tmp_path / "never.sqlite").exists()


def test_ceiling_default_is_the_median_record_at_5_g(tmp_path, records):
    with ResultStore(tmp_path / "c.sqlite") as store:
        res = incremental_dynamic_analysis(OPPENHEIM, records[:1], "pga", store,
                                           model="fourlink", precision=0.2,
                                           fill=2.0, executor=SerialExecutor())
    assert res.ceiling == pytest.approx(5.0, rel=1e-12)
    assert math.isfinite(res.records[0].first_collapse_level)


def test_worker_processes_after_a_threaded_kernel_in_this_process(tmp_path):
    """Regression: an IDA in this process runs numba's threaded batch (OpenMP), after which an
    IDA on 2 worker processes used to die ("fork() called from a process already using GNU
    OpenMP", BrokenProcessPool): forked workers cannot run a threaded kernel. The pool's workers
    are no longer forked from this process. Oracle: the same analysis run in this process."""
    import numba

    def ida(name, **kwargs):
        with ResultStore(tmp_path / f"{name}.sqlite") as store:
            res = incremental_dynamic_analysis(OPPENHEIM, [StepImpulse.from_g(1.0, 0.3)], "pga",
                                               store, model="fourlink", ceiling=2.0,
                                               precision=0.05, fill=0.2, **kwargs)
        return [(i.lower_edge, i.upper_edge) for i in res.records[0].collapse_intervals]

    here = ida("here", executor=SerialExecutor())
    assert numba.threading_layer()  # raises ValueError if no threaded kernel has run
    assert ida("pool", workers=2) == here


def test_rigid_model_ida_brackets_its_own_threshold(tmp_path):
    """An IDA with the rigid chain (hinges moving) of the step pulse t_p = 0.3 s (one-record
    suite, 10 % precision) against the rigid chain's own collapse threshold found by bisection
    with ``simulate_rigid`` (0.04 g; the window of ``run --hinges moving``: the end of the pulse
    + 5 sqrt(R/g), on until rest up to + 60 sqrt(R/g); ``indeterminate`` counted with collapse,
    as the IDA counts it): the two brackets overlap. All runs are rigid cases."""
    from archquake.dem.run import default_dem_duration
    from archquake.ida.analysis import COUNTED_AS_COLLAPSE
    from archquake.rigid import simulate_rigid

    arch = OPPENHEIM.build()

    def collapses(a_g: float) -> bool:
        m = StepImpulse.from_g(a_g, 0.3)
        cap = m.duration + 60 * math.sqrt(arch.radius / 9.80665)
        run = simulate_rigid(arch, m, duration=default_dem_duration(arch, m), until_rest=cap)
        return run.outcome in COUNTED_AS_COLLAPSE

    lo, hi = 0.5, 1.0
    assert not collapses(lo) and collapses(hi)
    while hi - lo > 0.04:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if collapses(mid) else (mid, hi)
    with ResultStore(tmp_path / "rigid.sqlite") as store:
        res = incremental_dynamic_analysis(OPPENHEIM, [StepImpulse.from_g(1.0, 0.3)], "pga",
                                           store, ceiling=1.0, precision=0.1, fill=1.0,
                                           model="rigid", executor=SerialExecutor())
        rows = store.rows()
    assert {r["model"] for r in rows} == {"rigid"}
    first = res.records[0].first_collapse
    assert first.below < hi and first.low > lo


def test_first_collapses_first_give_the_same_analysis(tmp_path):
    """With a ``first_collapses`` callback the analysis runs the levels below each record's
    lowest collapse first (and the guard's reruns that bracket it), hands over the analysis so
    far, then fills the levels above. Oracle: the same analysis without the callback, which
    fills every gap at once. Four near-field records on Oppenheim's arch up to 2 g, chosen for
    what could tell the two schedules apart: each has levels above its first collapse, three a
    resurrection (survival above a collapse) and all some verdicts the half-step guard turned
    indeterminate. The same levels, outcomes and guard reruns; the callback's first collapses
    are the result's, from fewer levels."""
    from archquake.ground.suites import load_suite

    records = load_suite("near-field-pulse").records
    motions = [records[i] for i in (11, 17, 23, 27)]
    kwargs = dict(ceiling=2.0, precision=0.05, fill=0.2, model="rigid")
    with ResultStore(tmp_path / "whole.sqlite") as store:
        whole = incremental_dynamic_analysis(OPPENHEIM, motions, "pga", store, **kwargs)
    partial = []
    with ResultStore(tmp_path / "first.sqlite") as store:
        first = incremental_dynamic_analysis(OPPENHEIM, motions, "pga", store,
                                             first_collapses=partial.append, **kwargs)
    assert sum(len(r.resurrections) > 0 for r in whole.records) == 3
    assert all(np.any(r.indeterminate) for r in whole.records)
    for a, b in zip(whole.records, first.records, strict=True):
        assert list(a.levels) == list(b.levels) and a.outcomes == b.outcomes
    assert (first.total, first.guarded) == (whole.total, whole.guarded)
    (early,) = partial
    np.testing.assert_array_equal(early.first_collapse_levels, whole.first_collapse_levels)
    for a, p in zip(whole.records, early.records, strict=True):
        assert (p.first_collapse.low, p.first_collapse.below) == (a.first_collapse.low,
                                                                  a.first_collapse.below)
        assert set(p.levels) < set(a.levels)  # the levels above were still to run


def test_a_resumed_rigid_ida_reads_its_guards_reruns_from_the_store(tmp_path):
    """The half-step guard's reruns are cases of their own in the store: the same analysis run
    again on its store computes nothing, the guard included, and gives the same trace.
    Oracle: the first call (its levels, outcomes and reasons), and the store's rows (the
    reruns at half the levels' step)."""
    args = (OPPENHEIM, [StepImpulse.from_g(1.0, 0.3)], "pga")
    kwargs = dict(ceiling=1.0, precision=0.1, fill=1.0, model="rigid",
                  executor=SerialExecutor())
    with ResultStore(tmp_path / "rigid.sqlite") as store:
        first = incremental_dynamic_analysis(*args, store, **kwargs)
        again = incremental_dynamic_analysis(*args, store, **kwargs)
        rows = store.rows()
    assert first.guarded > 0 and again.guarded == first.guarded
    assert first.computed == first.total and again.computed == 0
    assert first.total == len(rows)  # the levels and the guard's reruns, each stored once
    halves = [r for r in rows if json.loads(r["inputs_json"])["options"].get("step_fraction")
              == 0.5]
    assert len(halves) == first.guarded
    steps = sorted({r["out.time_step_s"] for r in rows})
    assert len(steps) == 2 and steps[1] == 2 * steps[0]
    assert {r["out.time_step_s"] for r in halves} == {steps[0]}
    (a,), (b,) = first.records, again.records
    assert list(a.levels) == list(b.levels) and a.outcomes == b.outcomes
