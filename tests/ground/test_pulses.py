"""The analytical pulses against their definitions, the compiled evaluator and the paper's
sign convention."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground import GroundMotion, SinePulse, StepImpulse
from archquake.ground._kernel import evaluate, ground_acceleration, ground_duration
from archquake.ground.base import KIND_SINE, KIND_STEP

magnitudes = st.floats(0.0, 30.0)
durations = st.floats(1e-3, 5.0)
directions = st.sampled_from([-1, 1])


def _pieces_integral(motion, power: int = 0) -> float:
    """Integral of t^power x_g''(t) over [0, duration] for a piecewise-constant motion, summed
    piece by piece (value at each piece's midpoint times its length: exact for constants)."""
    b = motion.breakpoints()
    mid = 0.5 * (b[:-1] + b[1:])
    values = motion.acceleration(mid)
    return float(sum(v * (hi ** (power + 1) - lo ** (power + 1)) / (power + 1)
                     for v, lo, hi in zip(values, b[:-1], b[1:], strict=True)))


def test_step_impulse_leaves_the_ground_at_rest_exactly():
    # Oracle: Oppenheim's impulse a t_p - (a/2)(2 t_p) = 0. In exact rational arithmetic on
    # the values the class produces (t_p dyadic, so every product is exact in binary too).
    p = StepImpulse(3.0, 0.25)
    b = [Fraction(x) for x in p.breakpoints()]
    pieces = list(zip(b[:-1], b[1:], strict=True))
    v = [Fraction(float(p.acceleration(float((lo + hi) / 2)))) for lo, hi in pieces]
    assert sum(vi * (hi - lo) for vi, (lo, hi) in zip(v, pieces, strict=True)) == 0
    assert _pieces_integral(p) == 0.0


@given(magnitudes, durations, directions)
@settings(max_examples=60, deadline=None)
def test_step_impulse_final_ground_velocity_is_zero(a, t_p, direction):
    # Oracle: the closed form above; in floating point 3 t_p - t_p differs from 2 t_p by an
    # ulp, so the sum vanishes to a few ulp of a t_p. quad over the breakpoints agrees.
    p = StepImpulse(a, t_p, direction)
    assert abs(_pieces_integral(p)) <= 8 * np.finfo(float).eps * max(a * t_p, 1e-300)
    integral, _ = quad(lambda t: float(p.acceleration(t)), 0.0, p.duration,
                       points=p.breakpoints()[1:-1], epsabs=1e-12 * max(a * t_p, 1e-12))
    assert abs(integral) <= 1e-10 * max(a * t_p, 1e-12)


def test_step_impulse_shape_and_paper_sign():
    # Oracle: the definition; first lobe towards -x drives the paper's first mechanism.
    p = StepImpulse.from_g(0.5, 0.2)
    a = 0.5 * STANDARD_GRAVITY
    end = p.duration  # 3 t_p as the class computes it (3 * 0.2 is 0.6000000000000001)
    t = np.array([-1e-9, 0.0, 0.1, 0.2 - 1e-12, 0.2, 0.4, end - 1e-12, end, 1.0])
    np.testing.assert_array_equal(p.acceleration(t),
                                  [0, -a, -a, -a, a / 2, a / 2, a / 2, 0, 0])
    assert p.duration == pytest.approx(0.6)
    np.testing.assert_allclose(p.breakpoints(), [0.0, 0.2, 0.6])
    assert isinstance(p, GroundMotion)


def test_sine_pulse_shape_and_rest_after_one_cycle():
    p = SinePulse.from_g(0.3, 0.4)
    a = 0.3 * STANDARD_GRAVITY
    assert float(p.acceleration(0.1)) == pytest.approx(-a, rel=1e-15)    # first half towards -x
    assert float(p.acceleration(0.3)) == pytest.approx(a, rel=1e-15)
    assert float(p.acceleration(0.4)) == 0.0 and float(p.acceleration(-0.01)) == 0.0
    integral, _ = quad(lambda t: float(p.acceleration(t)), 0.0, 0.4, points=[0.2])
    assert integral == pytest.approx(0.0, abs=1e-12 * a)   # one cycle: zero final velocity
    assert isinstance(p, GroundMotion)


@given(magnitudes, durations, directions, st.lists(st.floats(-0.5, 4.0), min_size=1,
                                                   max_size=20))
@settings(max_examples=60, deadline=None)
def test_kernels_equal_python_accelerations(a, duration, direction, fractions):
    # Oracle: the Python definitions. The step is a comparison and a product, so equality is
    # exact; the sine uses math.sin vs numpy.sin (an ulp apart at most).
    for motion, kind, exact in ((StepImpulse(a, duration, direction), KIND_STEP, True),
                                (SinePulse(a, duration, direction), KIND_SINE, False)):
        k, params = motion.kernel_spec()
        assert k == kind
        t = np.concatenate([np.asarray(fractions) * motion.duration, motion.breakpoints()])
        compiled, python = evaluate(k, params, t), motion.acceleration(t)
        if exact:
            np.testing.assert_array_equal(compiled, python)
        else:
            np.testing.assert_allclose(compiled, python, rtol=0, atol=4e-16 * max(a, 1e-300))
        assert ground_duration(k, params) == motion.duration


@pytest.mark.parametrize("cls", [StepImpulse, SinePulse])
def test_mirrored_flips_the_sign_and_scaled_scales(cls):
    p = cls.from_g(0.4, 0.3)
    t = np.linspace(-0.1, 1.0, 221)
    np.testing.assert_array_equal(p.mirrored().acceleration(t), -p.acceleration(t))
    assert p.mirrored().direction == +1 and p.direction == -1
    assert p.mirrored().mirrored() == p
    assert p.scaled(-1.0) == p.mirrored()
    np.testing.assert_allclose(p.scaled(2.5).acceleration(t), 2.5 * p.acceleration(t),
                               rtol=1e-15, atol=0)
    k, params = p.mirrored().kernel_spec()
    assert float(ground_acceleration(k, params, 0.05)) == -float(p.acceleration(0.05))


def test_from_g_uses_standard_gravity_or_the_given_g():
    assert StepImpulse.from_g(0.37, 0.1).magnitude == 0.37 * STANDARD_GRAVITY
    assert SinePulse.from_g(0.37, 0.1, g=9.81).magnitude == 0.37 * 9.81
    d = StepImpulse.from_g(0.37, 0.1).to_dict()
    assert d["magnitude_g"] == pytest.approx(0.37, rel=1e-15)
    assert d["magnitude_m_s2"] == 0.37 * STANDARD_GRAVITY


@pytest.mark.parametrize(
    ("build", "fragment"),
    [
        (lambda: StepImpulse(-1.0, 0.1), "magnitude must be >= 0 m/s^2"),
        (lambda: StepImpulse.from_g(-0.2, 0.1), "magnitude must be >= 0 g, got -0.2"),
        (lambda: SinePulse.from_g(-0.2, 0.1), "magnitude must be >= 0 g"),
        (lambda: StepImpulse(math.nan, 0.1), "magnitude must be a finite number"),
        (lambda: StepImpulse.from_g(math.inf, 0.1), "magnitude must be a finite number (g)"),
        (lambda: StepImpulse(1.0, 0.0), "pulse duration t_p must be > 0 (s)"),
        (lambda: StepImpulse(1.0, -0.1), "pulse duration t_p must be > 0"),
        (lambda: StepImpulse(1.0, "0.1"), "pulse duration t_p must be a number"),
        (lambda: SinePulse(1.0, 0.0), "period must be > 0 (s)"),
        (lambda: SinePulse(1.0, math.nan), "period must be a finite number"),
        (lambda: StepImpulse(1.0, 0.1, 0), "direction must be -1"),
        (lambda: SinePulse(1.0, 0.1, True), "direction must be -1"),
        (lambda: StepImpulse(1.0, 0.1).scaled(math.nan), "scale factor"),
        (lambda: StepImpulse.from_g(0.2, 0.1, g=0.0), "g must be in [0.01, 1000]"),
    ],
)
def test_bad_pulse_parameters_give_one_line(build, fragment):
    with pytest.raises(InvalidParameterError) as info:
        build()
    assert fragment in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("motion, want", [
    (StepImpulse.from_g(0.5, 0.25), "step a = 0.5 g, t_p = 0.25 s"),
    (StepImpulse.from_g(0.5, 0.25).mirrored(),
     "step a = 0.5 g, t_p = 0.25 s, first towards +x (mirrored)"),
    (SinePulse.from_g(0.41, 1.3), "sine a = 0.41 g, T = 1.3 s"),
    (SinePulse.from_g(0.41, 1.3).mirrored(), "sine a = 0.41 g, T = 1.3 s, first towards +x (mirrored)"),
])
def test_motion_label_reads_the_motion_and_its_description_alike(motion, want):
    """Oracle: the text output's words for each kind (magnitude in g to 3 digits, the first
    lobe's side only when mirrored); the motion and its ``to_dict()`` give the same line."""
    from archquake.ground.base import motion_label

    assert motion_label(motion) == motion_label(motion.to_dict()) == want


def test_motion_label_of_a_record_is_its_name():
    from archquake.ground import Record
    from archquake.ground.base import motion_label

    record = Record([0.0, 2.0, -1.0], 0.01, name="RSN6_IMPVALL.I_I-ELC180")
    assert motion_label(record) == motion_label(record.to_dict()) == "RSN6_IMPVALL.I_I-ELC180"
