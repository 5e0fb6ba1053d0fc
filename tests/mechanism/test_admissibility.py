"""Admissibility of the moving mechanism (issue 16): the line of thrust at the locked joints.

Oracles: the paper's Figure 8 (the thrust leaves the section at joint 2 at t = 0.20 s; archquake's
existing number: by 0.96 m), the existing ``MotionState.outside`` (an independent reading of the
same joint forces), mirror symmetry, and the bisection's own bracket.
"""

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.ground import StepImpulse
from archquake.mechanism.admissibility import admissibility, first_exit
from archquake.thrust import states

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def test_figure8_thrust_outside_at_joint2():
    s = states(OPPENHEIM, StepImpulse.from_g(1.0, 0.20), [0.20])[0]
    adm = admissibility(s)
    assert not adm.admissible
    assert adm.worst_joint == 2 and adm.worst_face == "extrados"
    # the existing reading of the same forces: 0.96 m outside (docs, reproduce figure8)
    assert s.outside[2] == pytest.approx(0.959, abs=0.005)
    # margin < 0 exactly at the locked joints where MotionState says the thrust is outside
    locked = np.isfinite(adm.thrust_margin)
    assert np.array_equal(adm.thrust_margin[locked] < 0, s.outside[locked] > 0)


def test_figure8_first_exit_is_at_the_onset():
    """Under 1.0 g the assumed mechanism (0i 3e 5i 7e) is inadmissible from the onset: the
    thrust is already outside at joint 2 (extrados) at t = 0+, long before the 0.20 s snapshot."""
    ev = first_exit(OPPENHEIM, StepImpulse.from_g(1.0, 0.20), 0.2)
    assert ev.time == 0.0 and ev.joint == 2 and ev.face == "extrados" and ev.side == 1


def test_exit_located_by_bisection_and_mirror_symmetric():
    """0.4 g (just above lambda = 0.37 g): admissible during the pulse, the thrust leaves at
    joint 1 (intrados) when the ground acceleration drops at t_p = 0.20 s; the bracket is within
    the tolerance, and the mirrored pulse gives the mirrored joint at the same instant."""
    tol = 1e-6
    m = StepImpulse.from_g(0.4, 0.20)
    ev = first_exit(OPPENHEIM, m, 0.6, tol=tol)
    assert ev.joint == 1 and ev.face == "intrados"
    assert 0.20 <= ev.time <= 0.20 + 2 * tol and ev.tolerance <= tol
    before = ev.times < ev.time - tol
    assert np.all(np.nan_to_num(ev.margins[before], nan=1.0) >= 0.0)
    mir = first_exit(OPPENHEIM, m.mirrored(), 0.6, tol=tol)
    assert mir.joint == 7 - ev.joint and mir.face == ev.face and mir.side == -ev.side
    assert mir.time == pytest.approx(ev.time, abs=1e-12)
    # the margin histories are mirror images (joint j <-> n - j), to round-off
    assert np.allclose(np.nan_to_num(mir.margins[:, ::-1], nan=9.0),
                       np.nan_to_num(ev.margins, nan=9.0), atol=1e-9)
