"""The time-history route (C8.7.1.2.1.9) with the chain of rigid voussoirs.

Oracles: an arch of three voussoirs can only move as the four-hinge mechanism, so the chain's
equivalent displacement (its centre of mass through C8.7.1.4) must be the capacity curve's
d(phi) at the chain's own rotation of link AB: the four-link kinematics against the chain's
integration (tolerance 1e-6 relative: the chain's position correction holds its contacts to
round-off, the four-link solve is exact); and the code's rule (no record beyond d0, the mean of
the peaks below d_SLV), on pulses below the activation multiplier (no motion) and far above it
(collapse)."""

import math

import numpy as np
import pytest

from archquake.codecheck.kinematic import capacity_curve
from archquake.codecheck.timehistory import (
    chain_displacement,
    time_history_capacity,
    time_history_check,
)
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.rigid import simulate_rigid


@pytest.fixture(scope="module")
def three():
    arch = Arch(10.0, 1.5, math.radians(157.5), 3)
    return arch, capacity_curve(arch)


def test_chain_displacement_is_the_curve_displacement(three):
    arch, curve = three
    assert curve.mechanism.prepared.mechanism.joints == (0, 1, 2, 3)
    run = simulate_rigid(arch, StepImpulse.from_g(2 * curve.alpha0, 0.25), duration=0.6)
    res = run
    d = chain_displacement(curve, res)
    opening = (res.rotation > 1e-4) & (res.rotation < curve.phi0_rad)
    assert opening.sum() > 100 and d.max() > 0.1 * curve.d0_m
    expected = np.array([curve.displacement(float(p)) for p in res.rotation[opening]])
    np.testing.assert_allclose(d[opening], expected, rtol=1e-6)


def test_rule_no_motion_passes_collapse_fails(three):
    arch, curve = three
    weak = [StepImpulse.from_g(0.5 * curve.alpha0, 0.1 + 0.02 * i) for i in range(7)]
    res = time_history_check(curve, weak, "SLV")
    assert res.passes and res.mean_peak_m < 1e-9 and not res.exceeds_d0
    strong = [StepImpulse.from_g(3 * curve.alpha0, 1.0)] + weak[1:]
    res = time_history_check(curve, strong, "SLC")
    assert not res.passes and len(res.exceeds_d0) == 1 and math.isinf(res.mean_peak_m)
    assert res.d_limit_m == pytest.approx(0.6 * curve.d0_m)


def test_fewer_than_seven_records_refused(three):
    _, curve = three
    with pytest.raises(InvalidParameterError, match="at least 7 records"):
        time_history_check(curve, [StepImpulse.from_g(0.1, 0.1)] * 6)


def test_capacity_brackets_the_four_link_threshold(three):
    """Seven identical step pulses: the capacity a_g of the time-history route must bracket the
    amplitude at which the four-link model's largest half-cycle displacement (its own
    integration and impact law; on three voussoirs the chain moves as the four links) reaches
    d_SLV = 0.4 d0. Identical records give identical runs, so each level is run once."""
    from archquake.mechanism import PreparedMechanism, simulate
    from archquake.rigid.run import rigid_to_verdict

    arch, curve = three
    tp = 0.25
    prep = PreparedMechanism.build(arch)

    def four_link_peak_d(a_g):
        r = simulate(prep, StepImpulse.from_g(a_g, tp), t_end=6.0)
        return max((curve.displacement(min(p, curve.phi0_rad)) for p in r.peak_rotation),
                   default=0.0)

    lo, hi = 0.5, 1.5
    target = 0.4 * curve.d0_m
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if four_link_peak_d(mid) < target else (lo, mid)
    threshold = 0.5 * (lo + hi)

    runs = {}

    def run_once(a, motion):
        key = round(float(motion.magnitude), 12)
        if key not in runs:
            runs[key] = rigid_to_verdict(a, motion)
        return runs[key]

    cap = time_history_capacity(curve, [StepImpulse.from_g(1.0, tp)] * 7, 1.0, 0.8, "SLV",
                                bisections=2, run=run_once)
    assert cap.bracket_g[0] <= threshold <= cap.bracket_g[1]
    assert cap.bracket_g[1] - cap.bracket_g[0] <= 0.1 + 1e-12
