"""``failure_domain`` searches the chain of rigid voussoirs by default (an Arch), the four-link
mechanism for a PreparedMechanism or ``model='fourlink'``.

Oracle: the recorded rigid stepper (:func:`archquake.rigid.simulate_rigid`, 1e-4 s, ten times
finer than the verdicts the search runs) on either side of the governing bracket, 3 % outside
it (the verdict step moves a threshold by well under 1 % away from its guard's band,
docs/mechanism.md), for the same pulse plus the search's tail; and the four-link domain,
whose governing boundary at this duration differs from the chain's by more than the brackets,
so a search that ran the wrong model fails."""

from __future__ import annotations

import math

import pytest

from archquake.domains import DomainSettings, PulseFamily, failure_domain
from archquake.domains.blocks import DOMAIN_TAIL
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.outcome import Outcome
from archquake.rigid import simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
#: A coarse search: brackets of 0.02 g under a 2 g ceiling.
COARSE = DomainSettings(max_magnitude_g=2.0, scan_reference_g=2.0, coarse_points=8,
                        fine_points=4, precision_g=0.02, early=False)


def test_the_default_model_is_the_rigid_chain():
    tp = 0.3
    d = failure_domain(OPPENHEIM, "step", [tp], settings=COARSE)
    assert d.impact_law == "contacts"  # another model's outcomes, not the four-link law's
    hi, lo = float(d.collapse_g[0]), float(d.collapse_below_g[0])
    assert lo < hi <= lo + 0.02 + 1e-9
    tail = DOMAIN_TAIL * math.sqrt(OPPENHEIM.radius / 9.80665)

    def outcome(a_g: float) -> Outcome:
        m = PulseFamily.STEP.motion(a_g, tp)
        return simulate_rigid(OPPENHEIM, m, duration=m.duration + tail).outcome

    assert outcome(1.03 * hi) is Outcome.COLLAPSE
    assert outcome(0.97 * lo) is not Outcome.COLLAPSE
    four = failure_domain(OPPENHEIM, "step", [tp], settings=COARSE, model="fourlink")
    assert four.impact_law == "paper"
    assert abs(float(four.collapse_g[0]) - hi) > 0.04


def test_impact_options_need_the_four_link_model():
    for kw, name in (({"restitution": 0.5}, "restitution"), ({"impact": "chain"}, "impact")):
        with pytest.raises(InvalidParameterError, match=f"^{name} applies to model fourlink"):
            failure_domain(OPPENHEIM, "step", [0.3], settings=COARSE, **kw)
    with pytest.raises(InvalidParameterError, match="model must be 'rigid' or 'fourlink'"):
        failure_domain(OPPENHEIM, "step", [0.3], model="dem")
