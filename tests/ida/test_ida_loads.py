"""Incremental dynamic analysis of an arch carrying its fill: every model carries it, and the
levels start at the loaded arch's lambda.

Oracles: lambda of the static analysis with the loads (:mod:`archquake.limit.loaded`, 0.0819 g
for the example bridge with 1 m of fill, 1e-12); the four-link failure domain of the same
loaded mechanism (a step pulse as a one-record suite, PGA = its magnitude: the IDA's first
collapse bracket, 1 % wide, holds the domain's collapse acceleration to its 0.001 g).
"""

from __future__ import annotations

import math

import pytest

from archquake.domains import failure_domain
from archquake.geometry.arch import Arch
from archquake.geometry.loads import Fill, Loads
from archquake.ground import StepImpulse
from archquake.ida import incremental_dynamic_analysis
from archquake.limit.loaded import loaded_collapse, seismic_case
from archquake.mechanism import PreparedMechanism
from archquake.parallel import SerialExecutor
from archquake.sweeps import ArchSpec, ResultStore

SPEC = ArchSpec(5.0, 0.12, 180.0, 15, 1.0, 1800.0)
ARCH = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
FILL = Loads(fill=Fill(depth=1.0, density=1800.0))
LAMBDA = loaded_collapse(seismic_case(ARCH, FILL)).multiplier


@pytest.mark.parametrize("model", ["rigid", "fourlink"])
def test_the_levels_start_at_the_loaded_lambda(tmp_path, model):
    with ResultStore(tmp_path / "s.sqlite") as store:
        res = incremental_dynamic_analysis(SPEC, [StepImpulse.from_g(1.0, 0.3)], "pga", store,
                                           model=model, ceiling=1.0, precision=0.05,
                                           executor=SerialExecutor(), loads=FILL)
    rec = res.records[0]
    assert res.collapse_acceleration_g == pytest.approx(LAMBDA, rel=1e-12)
    assert rec.start == pytest.approx(LAMBDA, rel=1e-12)
    assert rec.outcomes[0] == "no_hinging"
    assert res.to_dict()["loads"]["fill"]["depth_m"] == 1.0


def test_the_four_link_ida_finds_the_loaded_domains_collapse(tmp_path):
    tp = 0.3
    dom = failure_domain(PreparedMechanism.build(ARCH, loads=FILL), "step", [tp],
                         model="fourlink")
    with ResultStore(tmp_path / "s.sqlite") as store:
        res = incremental_dynamic_analysis(SPEC, [StepImpulse.from_g(1.0, tp)], "pga", store,
                                           model="fourlink", ceiling=2.0, precision=0.01,
                                           executor=SerialExecutor(), loads=FILL)
    first = res.records[0].collapse_intervals[0]
    assert first.below - 0.001 <= dom.collapse_g[0] <= first.low + 0.001


def test_the_rounds_share_one_loaded_body_and_give_the_fresh_bodys_verdicts():
    """Every round of the rigid IDA, and its guard's reruns, run the loaded arch's blocks built
    once (`rigid_body`: the same object for equal inputs, so its model and its onset
    accelerations, found by bisection, are too). Oracle: the verdicts of a body built afresh
    for the call (`build_arch_assembly`, the plain path), equal field by field."""
    from archquake.blocks.assembly import build_arch_assembly
    from archquake.ida.analysis import half_step_case
    from archquake.ida.batch import evaluate_rigid_cases, rigid_body
    from archquake.models import Model
    from archquake.rigid import rigid_verdicts
    from archquake.rigid.verdict import verdict_time_step
    from archquake.sweeps import CaseOptions
    from archquake.sweeps.cases import Case, ExcitationKind, ExcitationSpec
    from archquake.sweeps.evaluate import rigid_summary

    motions = [StepImpulse.from_g(a, 0.4) for a in (0.9 * LAMBDA, 1.6 * LAMBDA, 3.0 * LAMBDA)]
    assert rigid_body(SPEC.build(), FILL) is rigid_body(SPEC.build(), FILL)
    assert rigid_body(ARCH, None) == ARCH  # without loads, the arch (or an equal one)
    cases = [Case(SPEC, ExcitationSpec(ExcitationKind.RECORD, motion=m, scale=1.0),
                  Model.RIGID, CaseOptions(), FILL) for m in motions]
    first = evaluate_rigid_cases(cases)
    again = evaluate_rigid_cases(cases)  # the next round: the same body, no new bisection
    halves = evaluate_rigid_cases([half_step_case(c) for c in cases])
    fresh = build_arch_assembly(SPEC.build(), loads=FILL)
    assert fresh is not rigid_body(SPEC.build(), FILL)
    built = [c.excitation.build() for c in cases]
    plain = rigid_verdicts(fresh, built, guard=CaseOptions().guard)
    assert first == again
    assert [rigid_summary(v) for v in plain] == first
    plain_half = rigid_verdicts(fresh, built, time_step=0.5 * verdict_time_step(fresh),
                                guard=False)
    assert [rigid_summary(v) for v in plain_half] == halves
    assert {v.outcome.value for v in plain} >= {"collapse", "survives"}  # both kinds compared
