"""Time histories under the impact laws (simulate(..., impact=...)).

Oracles: where the chain law selects the mirror (symmetric hinges) it is Eq. 4 (see
test_impact_chain), so the histories must coincide; every impact multiplies the rate by the law's
c_v <= 1 (energy); the default stays the paper's law (reproduce unchanged).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, simulate


def test_symmetric_hinges_chain_history_equals_paper():
    """t/R = 0.19 (hinges (0, 2, 5, 7)): same impacts, same rates. Tolerance: the two c_v agree
    to 1e-10, the integration is deterministic, so impact times agree to 1e-8 s."""
    arch = Arch(10.0, 1.9, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.2, 0.2)
    a = simulate(arch, motion)
    b = simulate(arch, motion, impact="chain")
    assert a.impact_law == "paper" and b.impact_law == "chain"
    assert b.impact_followed and b.impact_validity == "four_hinge"
    assert a.outcome == b.outcome
    assert a.impact_times.size >= 2
    assert np.allclose(a.impact_times, b.impact_times, atol=1e-8)
    assert np.allclose(a.impact_rates, b.impact_rates, rtol=1e-8)


def test_oppenheim_chain_history():
    """Oppenheim's arch: the chain law selects 0e 2i 5e 7i (not the mirror 0e 2i 4e 7i) and the
    history follows it (docs/notes/mechanism.md, the reachable set: 0i 3e 5i 7e -> 0e 2i 5e 7i ->
    0i 2e 5i 7e -> ...). Every impact keeps the law's c_T <= 1 of the kinetic energy."""
    prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7), "chain")
    r = simulate(prep, StepImpulse.from_g(1.0, 0.20))
    assert r.impact_followed
    assert r.impact_validity == "near_four_hinge"
    assert r.to_dict()["impact_law"] == "chain"
    hinges = [e.hinges for e in r.mechanisms[:4]]
    assert hinges == ["0i 3e 5i 7e", "0e 2i 5e 7i", "0i 2e 5i 7e", "0e 2i 5e 7i"]
    assert r.restitution_ct <= 1.0


def test_default_law_is_the_papers():
    prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    assert prep.impact.law == "paper"
    assert prep.restitution == pytest.approx(0.8754, abs=1e-4)
