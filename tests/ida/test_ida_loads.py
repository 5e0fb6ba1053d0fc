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
