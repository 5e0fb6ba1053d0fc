"""The paper's numbers as :mod:`archquake.validation.paper` holds them: each with a tolerance and
a justification, and checks that say by how much a value misses."""

from __future__ import annotations

import math

import pytest

from archquake.validation import paper

VALUES = {k: v for k, v in vars(paper).items() if isinstance(v, paper.PaperValue)}
AGREEMENTS = {k: v for k, v in vars(paper).items() if isinstance(v, paper.Agreement)}


@pytest.mark.parametrize("name", sorted(VALUES))
def test_every_value_has_a_tolerance_a_reason_and_a_page(name):
    v = VALUES[name]
    assert v.tolerance > 0 and v.why and v.where and v.stated
    assert v.within(v.value) and v.within(v.value + 0.999 * v.tolerance)
    assert not v.within(v.value + 1.5 * v.tolerance) and not v.within(math.nan)
    assert not v.within(None)


def test_check_explains_a_miss():
    v = paper.FIGURE4C_FIRST_IMPACT
    assert v.check(0.87) is None
    msg = v.check(0.90, "first impact")
    assert msg == "first impact = 0.9 s, the paper 0.86 s +/- 0.02 s (p. 2126, Figure 4(c)): off by 0.04 s"
    assert "not computed" in v.check(None)


def test_agreement_relative_and_absolute():
    rel = paper.DEM_FIRST_IMPACT_AGREEMENT
    assert rel.within(0.94, 0.86) and not rel.within(0.95, 0.86) and not rel.within(None, 0.86)
    assert "reasonably good" in rel.check(1.0, 0.86)
    ab = paper.THREE_VOUSSOIR_AGREEMENT
    assert ab.within(4e-3, 0.0) and not ab.within(6e-3, 0.0)
    assert all(a.bound > 0 and a.why and a.stated for a in AGREEMENTS.values())


def test_oppenheim_arch_is_the_papers():
    arch = paper.oppenheim_arch()
    assert (arch.radius, arch.voussoirs) == (paper.OPPENHEIM_RADIUS_M, paper.OPPENHEIM_VOUSSOIRS)
    assert arch.thickness_ratio == pytest.approx(paper.OPPENHEIM_THICKNESS_RATIO, rel=1e-12)
    assert math.degrees(arch.embrace) == pytest.approx(paper.OPPENHEIM_EMBRACE_DEG, rel=1e-12)
