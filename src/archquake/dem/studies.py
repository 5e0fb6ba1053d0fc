"""Small studies on top of `simulate_dem`: restitution of a free-rocking block, the
rocking-onset and overturning thresholds of a block, and the friction needed by an arch.

Each returns plain numbers so that tests and docs/models/dem.md can quote them.
"""

from __future__ import annotations

import math

import numpy as np

from archquake.blocks.assembly import Assembly, block_on_base
from archquake.constants import STANDARD_GRAVITY
from archquake.dem.run import simulate_dem
from archquake.dem.settings import DemSettings
from archquake.ground.records import Record
from archquake.validation.housner import restitution


def tilted_block(width: float, height: float, tilt: float, **kwargs) -> Assembly:
    """`block_on_base` with the block turned clockwise by ``tilt`` rad about its
    bottom-right corner, i.e. standing on that corner (its left corner lifted)."""
    base = block_on_base(width, height, **kwargs)
    c, s = math.cos(-tilt), math.sin(-tilt)
    pivot = np.array([0.5 * width, 0.0])
    rot = np.array([[c, -s], [s, c]])
    poly = (base.polygons[1] - pivot) @ rot.T + pivot
    cent = (base.centroids[1] - pivot) @ rot.T + pivot
    from dataclasses import replace

    return replace(
        base,
        polygons=(base.polygons[0], poly),
        centroids=np.array([base.centroids[0], cent]),
        outlines=(),
    )


def free_rocking_restitution(
    width: float,
    height: float,
    settings: DemSettings,
    *,
    release: float = 0.5,
    g: float = STANDARD_GRAVITY,
) -> float:
    """Measured restitution of the first impact of a block released from rest at a tilt of
    ``release`` * alpha.

    The ratio of angular velocities just after and just before the impact is taken from the
    energies (the same rigid-body argument as Housner's): r^2 = (cos(alpha - theta1) - cos
    alpha) / (cos(alpha - theta0) - cos alpha), with theta0 the release tilt and theta1 the
    largest tilt to the other side after the impact. Free flight is not damped in practice
    (the mass-proportional term is ~1e-4 /s), so the loss is the impact's.
    """
    alpha = math.atan2(width, height)
    theta0 = release * alpha
    asm = tilted_block(width, height, theta0)
    settings = settings.with_(settle_time=0.0, stop_at_collapse=False,
                              output_interval=min(settings.output_interval, 1e-3))
    # time for a quarter cycle plus the rebound, from the rigid-body period (generous)
    p = math.sqrt(3 * g / (4 * 0.5 * math.hypot(width, height)))
    duration = 6.0 * math.acosh(1.0 / (1.0 - release)) / p + 0.05
    res = simulate_dem(asm, Record(np.array([0.0, 0.0]), 1.0), settings.with_(duration=duration), g=g)
    tilt = theta0 - res.positions[:, 1, 2]
    cross = np.flatnonzero(tilt <= 0.0)
    if cross.size == 0:
        raise RuntimeError("the block did not reach its first impact in the simulated time")
    after = tilt[cross[0]:]
    back = np.flatnonzero(after > 0.0)
    swing = after[: back[0]] if back.size else after
    theta1 = float(-swing.min())
    ratio = (math.cos(alpha - theta1) - math.cos(alpha)) / (math.cos(alpha - theta0) - math.cos(alpha))
    return math.sqrt(max(ratio, 0.0))


def restitution_table(
    cases: list[tuple[float, float, DemSettings]], *, g: float = STANDARD_GRAVITY
) -> list[dict]:
    """Rows (b, h, alpha, stiffness, alpha_R, beta_R, measured r, Housner r) for docs/models/dem.md."""
    rows = []
    for b, h, st in cases:
        rows.append(
            {
                "width_m": b,
                "height_m": h,
                "alpha_rad": math.atan2(b, h),
                "stiffness_Pa_m": st.contact.normal_stiffness,
                "rayleigh_alpha": st.damping[0],
                "rayleigh_beta": st.damping[1],
                "measured": free_rocking_restitution(b, h, st, g=g),
                "housner": restitution(b, h),
            }
        )
    return rows


def bisect(predicate, low: float, high: float, *, rtol: float = 1e-3, max_iter: int = 40) -> float:
    """Threshold x with predicate(low) False and predicate(high) True, to relative ``rtol``."""
    if predicate(low) or not predicate(high):
        raise ValueError(f"bisection bracket [{low}, {high}] does not bracket the threshold")
    for _ in range(max_iter):
        mid = 0.5 * (low + high)
        if predicate(mid):
            high = mid
        else:
            low = mid
        if high - low <= rtol * abs(high):
            break
    return 0.5 * (low + high)


def ramp_and_hold(acceleration: float, ramp: float, hold: float) -> Record:
    """Ground acceleration rising linearly to ``acceleration`` (m/s^2) over ``ramp`` s, then
    constant for ``hold`` s (a quasi-static constant acceleration)."""
    n_hold = max(2, int(math.ceil(hold / ramp)))
    return Record(np.array([0.0] + [acceleration] * (n_hold + 1)), ramp, name="ramp and hold")


def rectangular_pulse(acceleration: float, duration: float, *, samples: int = 2000) -> Record:
    """A rectangular acceleration pulse (m/s^2, s), sampled finely (the fall to zero takes
    duration / samples): `archquake.ground.pulses.RectangularPulse.sampled`."""
    from archquake.ground.pulses import RectangularPulse

    return RectangularPulse(acceleration, duration).sampled(samples)


__all__ = [
    "bisect",
    "friction_threshold",
    "slides",
    "free_rocking_restitution",
    "ramp_and_hold",
    "rectangular_pulse",
    "restitution_table",
    "tilted_block",
]


def slides(arch_or_assembly, friction: float, a_g: float, *, window: float = 0.2,
           slip_limit: float = 1e-3, settings: DemSettings | None = None,
           g: float = STANDARD_GRAVITY) -> bool:
    """True if some joint slides by more than ``slip_limit`` (m) within ``window`` s of the
    start of a step impulse of ``a_g`` g (the pulse is longer than the window)."""
    from archquake.dem.settings import ContactLaw
    from archquake.ground.pulses import StepImpulse

    base = settings or DemSettings()
    law = ContactLaw(base.contact.normal_stiffness, base.contact.shear_stiffness, friction)
    st = base.with_(contact=law, duration=window, output_interval=0.002)
    res = simulate_dem(arch_or_assembly, StepImpulse.from_g(a_g, 1.0, g=g), st, g=g)
    return bool(np.max(np.abs(res.joint_slip)) > slip_limit)


def friction_threshold(arch_or_assembly, a_g: float, *, low: float = 0.3, high: float = 1.0,
                       rtol: float = 5e-3, **kwargs) -> float:
    """The friction coefficient below which joints slide at the start of an ``a_g`` g
    impulse (bisection on the coefficient; see `slides`)."""
    return bisect(lambda mu: not slides(arch_or_assembly, mu, a_g, **kwargs), low, high, rtol=rtol)
