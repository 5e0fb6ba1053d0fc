"""Failure domains of Oppenheim's arch (paper Figures 5 and 11) against single time histories.

Oracles: the scalar path :func:`archquake.mechanism.simulate` run at the magnitudes that bracket
each boundary (the domain claims each bracket, 0.001 g wide, straddles the transition); the
paper's Figure 4 pulses (1.0 g at t_p = 0.44, 0.27, 0.20 s) and its description of Figure 5.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from archquake.domains import COLLAPSE, FIRST_HALF_CYCLE, DomainSettings, failure_domain
from archquake.mechanism import Outcome, SolverOptions, simulate

NO_HISTORY = SolverOptions(output_interval=0)
PRECISION = 1e-3


def _run(prepared, domain, magnitude_g, duration):
    return simulate(prepared, domain.family.motion(float(magnitude_g), float(duration)),
                    options=NO_HISTORY)


def _first(r):
    return r.outcome is Outcome.COLLAPSE and r.collapse_half_cycle == 1


@pytest.mark.parametrize("which", ["step_domain", "sine_domain"])
def test_boundaries_bracket_single_runs(request, oppenheim_prepared, which):
    dom = request.getfixturevalue(which)
    assert np.all(np.isfinite(dom.collapse_g)) and np.all(np.isfinite(dom.first_half_cycle_g))
    for i, d in enumerate(dom.durations):
        lo, hi = dom.first_half_cycle_below_g[i], dom.first_half_cycle_g[i]
        assert 0 < hi - lo <= PRECISION + 1e-12
        assert not _first(_run(oppenheim_prepared, dom, lo, d))
        assert _first(_run(oppenheim_prepared, dom, hi, d))
        lo, hi = dom.collapse_below_g[i], dom.collapse_g[i]
        assert 0 < hi - lo <= PRECISION + 1e-12
        assert _run(oppenheim_prepared, dom, lo, d).outcome is not Outcome.COLLAPSE
        r = _run(oppenheim_prepared, dom, hi, d)
        assert r.outcome is Outcome.COLLAPSE and r.collapse_half_cycle == dom.collapse_half_cycle[i]


@pytest.mark.parametrize("family", ["step", "sine"])
def test_no_hinging_limit_is_lambda(oppenheim_prepared, step_domain, family):
    # hinging starts at lambda of the equivalent static analysis (paper p. 2126), whatever the
    # duration (the paper's 0.37 g: tests/paper)
    lam = step_domain.no_hinging_g[0]
    assert lam == pytest.approx(oppenheim_prepared.mechanism.collapse_acceleration_g, abs=5e-4)
    for d in (0.1, 0.5, 2.0):
        below = simulate(oppenheim_prepared, step_domain.family.motion(lam * (1 - 1e-6), d)
                         if family == "step" else _sine(lam * (1 - 1e-6), d), options=NO_HISTORY)
        above = simulate(oppenheim_prepared, step_domain.family.motion(lam * (1 + 1e-4), d)
                         if family == "step" else _sine(lam * (1 + 1e-4), d), options=NO_HISTORY)
        assert below.outcome is Outcome.NO_HINGING
        assert above.outcome is not Outcome.NO_HINGING


def _sine(a, period):
    from archquake.domains import PulseFamily

    return PulseFamily.SINE.motion(a, period)


def test_figure5_shape(step_domain):
    """Paper p. 2127-2128: both boundaries above 0.37 g, the 2nd-half-cycle one the lowest, both
    falling towards 0.37 g as t_p grows, no collapse after the 2nd half cycle."""
    d = step_domain
    lam = d.no_hinging_g
    assert np.all(d.collapse_g > lam) and np.all(d.first_half_cycle_g > d.collapse_g)
    assert np.all(np.diff(d.collapse_g) < 0) and np.all(np.diff(d.first_half_cycle_g) < 0)
    # approach to lambda: the excess over lambda shrinks by an order of magnitude over the range
    excess = d.collapse_g - lam
    assert excess[-1] < 0.1 * excess[0]
    assert d.first_half_cycle_g[-1] - lam[-1] < 0.1 * (d.first_half_cycle_g[0] - lam[0])
    # the governing collapse happens in the 2nd half cycle (1st or 2nd allowed by the paper)
    assert set(d.collapse_half_cycle.tolist()) <= {1, 2}
    assert set(d.collapse_half_cycle.tolist()) == {2}


def test_figure4_pulses_sit_in_the_right_regions(step_domain):
    """a = 1.0 g: t_p = 0.44 s above the 1st-half-cycle boundary, 0.27 s between the two, 0.20 s
    below the governing one (paper Figure 4b-d)."""
    d = step_domain
    at = {round(float(t), 2): i for i, t in enumerate(d.durations)}
    assert d.first_half_cycle_g[at[0.44]] < 1.0
    assert d.collapse_g[at[0.27]] < 1.0 < d.first_half_cycle_g[at[0.27]]
    assert d.collapse_g[at[0.2]] > 1.0


def test_bands_are_real(oppenheim_prepared, step_domain, sine_domain):
    """Each reported non-monotonic band: single runs at both its edges do not collapse (for the
    band's criterion), while the governing boundary below it does."""
    for dom in (step_domain, sine_domain):
        for b in dom.non_monotonic_bands:
            i = int(np.flatnonzero(dom.durations == b.duration)[0])
            for mag in (b.lower_g, b.upper_g):
                r = _run(oppenheim_prepared, dom, mag, b.duration)
                if b.criterion == COLLAPSE:
                    assert r.outcome is not Outcome.COLLAPSE
                    assert mag > dom.collapse_g[i]
                else:
                    assert b.criterion == FIRST_HALF_CYCLE and not _first(r)
                    assert mag > dom.first_half_cycle_g[i]


def test_step_recovery_band_below_first_half_cycle_boundary(step_domain):
    """The non-monotonic band found for the step impulse (see docs/domains.md): just below the
    1st-half-cycle boundary the arch creeps to near the crest after the pulse has ended, returns
    with nearly the barrier energy, loses (1 - c_v^2) of it at impact and recovers."""
    band_durations = {b.duration for b in step_domain.non_monotonic_bands if b.criterion == COLLAPSE}
    assert 0.27 in {round(x, 2) for x in band_durations}
    for b in step_domain.non_monotonic_bands:
        i = int(np.flatnonzero(step_domain.durations == b.duration)[0])
        assert b.upper_g <= step_domain.first_half_cycle_g[i]


def test_result_serialises(step_domain, tmp_path):
    rows = step_domain.to_dict()
    assert [r["duration_s"] for r in rows] == step_domain.durations.tolist()
    assert set(rows[0]) >= {"duration_s", "no_hinging_g", "first_half_cycle_g", "collapse_g",
                            "non_monotonic_bands"}
    json.dumps(rows, allow_nan=False)
    json.dumps(step_domain.summary(), allow_nan=False)
    path = step_domain.write_csv(tmp_path / "d.csv")
    lines = path.read_text().splitlines()
    assert lines[0].startswith("duration_s,no_hinging_g,first_half_cycle_g,collapse_g")
    assert len(lines) == 1 + step_domain.durations.size


def test_ceiling_gives_nan(oppenheim_prepared):
    # t_p = 0.05 s: nothing collapses below 2 g (the boundary is far above)
    d = failure_domain(oppenheim_prepared, "step", [0.05],
                       settings=DomainSettings(max_magnitude_g=2.0, coarse_points=10, fine_points=4))
    assert math.isnan(d.collapse_g[0]) and math.isnan(d.first_half_cycle_g[0])
    assert d.to_dict()[0]["collapse_g"] is None


def test_bad_settings_are_one_line(oppenheim_prepared):
    with pytest.raises(ValueError, match="max_magnitude_g must exceed the no-hinging limit"):
        failure_domain(oppenheim_prepared, "step", [0.3], settings=DomainSettings(max_magnitude_g=0.2))
    with pytest.raises(ValueError, match="durations must be"):
        failure_domain(oppenheim_prepared, "step", [])
