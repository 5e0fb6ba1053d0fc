"""Full-resolution studies (``pytest -m slow``): Figure 5 at 40 durations and the scale effect."""

from __future__ import annotations

import numpy as np
import pytest

from archquake.domains import compare_scaling, failure_domain, oppenheim_arch, similar_boundary
from archquake.mechanism import Outcome, simulate

pytestmark = pytest.mark.slow


def test_figure5_full_resolution():
    d = failure_domain(oppenheim_arch(), "step", np.linspace(0.05, 1.5, 40), model="fourlink")
    ok = np.isfinite(d.collapse_g) & np.isfinite(d.first_half_cycle_g)
    assert ok.sum() >= 35  # only the shortest pulses need more than 5 g
    assert np.all(d.first_half_cycle_g[ok] > d.collapse_g[ok])
    assert np.all(np.diff(d.collapse_g[ok]) < 1e-3)  # non-increasing to the bracket width
    assert set(d.collapse_half_cycle[ok].tolist()) == {2}
    for i in np.flatnonzero(ok)[::6]:  # scalar runs either side of the governing boundary
        motion = d.family.motion
        assert simulate(oppenheim_arch(), motion(d.collapse_g[i], d.durations[i])).outcome is Outcome.COLLAPSE
        assert simulate(oppenheim_arch(), motion(d.collapse_below_g[i], d.durations[i])).outcome \
            is not Outcome.COLLAPSE


def test_scale_full_resolution():
    base_d = np.linspace(0.1, 1.5, 15)
    ref = failure_domain(oppenheim_arch(10.0), "step", base_d, model="fourlink")
    for r in (1.0, 5.0, 20.0):
        k = r / 10.0
        exact = failure_domain(oppenheim_arch(r), "step", similar_boundary(base_d, base_d, k)[0],
                               model="fourlink")
        np.testing.assert_allclose(exact.collapse_g, ref.collapse_g, atol=1e-3)
        same_t = failure_domain(oppenheim_arch(r), "step", base_d, model="fourlink")
        assert np.isfinite(compare_scaling(ref, same_t).collapse_error).any()
