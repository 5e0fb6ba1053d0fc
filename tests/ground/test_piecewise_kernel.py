"""The piecewise evaluation the integrators use: inside a piece it equals the plain evaluator;
at a piece's right end it is the left limit (so a step ending on a jump never sees the next
value); the breakpoints it walks through are the motion's own."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.ground import SinePulse, StepImpulse
from archquake.ground._kernel import ground_acceleration, ground_in_piece, next_breakpoint
from archquake.ground.records import Record

motions = st.one_of(
    st.builds(StepImpulse, st.floats(0.0, 30.0), st.floats(0.01, 2.0), st.sampled_from([-1, 1])),
    st.builds(SinePulse, st.floats(0.0, 30.0), st.floats(0.05, 4.0), st.sampled_from([-1, 1])),
    st.builds(lambda v, dt: Record(np.asarray(v, dtype=float), dt),
              st.lists(st.floats(-20.0, 20.0), min_size=2, max_size=30), st.floats(0.002, 0.05)),
)


def _pieces(kind, params, end):
    pts = [0.0]
    while True:
        b = next_breakpoint(kind, params, pts[-1])
        if not np.isfinite(b) or b > end + 1e-12:
            break
        pts.append(b)
    return np.array(pts)


@given(motions, st.floats(0.0, 1.0))
@settings(max_examples=120, deadline=None)
def test_piece_evaluation_matches_plain_evaluation_inside_pieces(motion, frac):
    kind, params = motion.kernel_spec()
    pieces = _pieces(kind, params, motion.duration)
    own = np.asarray(motion.breakpoints(), dtype=float)
    assert set(np.round(own, 12)) <= set(np.round(pieces, 12)) | {0.0}
    scale = 1.0 + float(np.max(np.abs(params[2:])) if kind == 2 else abs(params[0]))
    for left, right in zip(pieces[:-1], pieces[1:]):
        t = left + frac * 0.999 * (right - left)
        inside = ground_in_piece(kind, params, t, left)
        assert abs(inside - ground_acceleration(kind, params, t)) <= 1e-9 * scale
        # at the right end: the left limit, continuous with the interior of the piece
        near = right - 1e-9 * (right - left)
        at_end = ground_in_piece(kind, params, right, left)
        assert abs(at_end - ground_acceleration(kind, params, near)) <= 1e-6 * scale


def test_step_impulse_left_limits_at_its_jumps():
    p = StepImpulse(9.8, 0.3)
    kind, params = p.kernel_spec()
    assert ground_in_piece(kind, params, 0.3, 0.0) == -9.8  # still the first lobe
    assert ground_in_piece(kind, params, 0.3, 0.3) == 4.9  # the return lobe from t_p on
    assert ground_in_piece(kind, params, 0.9, 0.3) == 4.9
    assert ground_in_piece(kind, params, 0.9, 0.9) == 0.0
