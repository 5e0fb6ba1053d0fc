"""The rigid step's active-set solve on 15 voussoirs: the steps where the contacts change end
in an accepted active set (the exact projection), not in Gauss-Seidel run to its limit."""

from __future__ import annotations

import math

from archquake.geometry import Arch
from archquake.ground.measures import im_value
from archquake.ground.suites import load_suite
from archquake.outcome import Outcome
from archquake.rigid import simulate_rigid
from archquake.rigid._step_kernels import ACTIVE_SET_ITERATIONS
from archquake.rigid.model import MAX_SWEEPS
from archquake.rigid.verdict import verdict_time_step


def test_no_step_of_the_bridge_runs_gauss_seidel_to_its_limit():
    """Oracle: the solver's own count (factorised sets plus Gauss-Seidel sweeps of the worst
    step), a cost bound by counts. The bridge (R 5 m, t 0.6 m, 15 voussoirs) under
    IMPVALL-H-E06_233 scaled to 0.11 g, at the verdict's step, up to its collapse: with 6
    active sets allowed, 15 of its steps went to Gauss-Seidel and ran the 5000 sweeps allowed
    (worst count 5006); with :data:`ACTIVE_SET_ITERATIONS` they end in an accepted set, and the
    few left to Gauss-Seidel (stalled refinements) converge well within the limit (worst count
    2273 measured; docs/notes/measurements.md, "The rigid chain's step on 15 voussoirs")."""
    arch = Arch(5.0, 0.6, math.pi, 15)
    record = load_suite("near-field-pulse").records[0]
    assert record.name.startswith("IMPVALL-H-E06")
    motion = record.scaled(0.11 / im_value(record, "pga"))
    run = simulate_rigid(arch, motion, duration=8.5, time_step=verdict_time_step(arch))
    assert run.outcome is Outcome.COLLAPSE
    assert ACTIVE_SET_ITERATIONS < run.max_sweeps < MAX_SWEEPS
