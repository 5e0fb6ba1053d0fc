"""Thrust states under the chain law followed (issue 10).

Oracle: the sequence of mechanisms of :func:`archquake.mechanism.simulate` (its
``mechanisms``): at each instant the displaced arch must open the hinges of the mechanism the
history is on, and the state must be the history's own (phi, phi_dot at that time).
"""

from __future__ import annotations

import math

import numpy as np

from archquake import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import simulate
from archquake.thrust import states


def test_states_open_the_mechanism_the_history_is_on():
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    r = simulate(arch, motion, impact="chain", t_eval=[0.3, 1.0, 1.6])
    hinges = {0.3: "0i 3e 5i 7e", 1.0: "0e 2i 5e 7i", 1.6: "0i 2e 5i 7e"}  # r.mechanisms
    assert [e.hinges for e in r.mechanisms[:3]] == list(hinges.values())
    got = states(arch, motion, list(hinges), impact="chain")
    assert r.evaluated is not None
    for s, t, phi in zip(got, hinges, r.evaluated.phi, strict=True):
        label = " ".join(f"{j}{f.value[0]}" for j, f in
                         zip(s.hinge_joints, s.configuration.hinge_faces, strict=True))
        assert label == hinges[t]
        assert np.isclose(s.phi, phi, rtol=1e-12, atol=0.0)
