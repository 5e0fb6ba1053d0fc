"""Frozen inputs of the distinct-element model: the joint contact law and the run settings.

Units are SI throughout. Joint stiffnesses are given per unit joint area (Pa/m, i.e. stress per
unit overlap, as UDEC's ``jkn``/``jks``); each contact point turns them into a spring in N/m by
multiplying with the block depth and its tributary contact length (see
`archquake.blocks.assembly`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from archquake._validate import require_finite, require_positive, require_range
from archquake.blocks.criteria import MAX_DURATION, BlockCriteria
from archquake.errors import InvalidParameterError

#: Friction coefficient used when none is given: large enough that nothing slides (the paper's
#: "very large friction angle").
NO_SLIDING = 1.0e6

#: Accepted ranges (SI), wide enough for every physical reading (the paper's "10^12 GPa/m"
#: taken literally is 1e21 Pa/m) and narrow enough that the stable time step, the contact
#: forces and the step count stay representable; beyond them a run would overflow or never end.
STIFFNESS_RANGE_PA_M = (1.0e3, 1.0e24)
MAX_FRICTION = 1.0e9
MAX_RAYLEIGH_ALPHA = 1.0e6  # 1/s
MAX_RAYLEIGH_BETA = 10.0  # s
TIME_STEP_RANGE = (1.0e-12, 1.0)  # s


@dataclass(frozen=True)
class ContactLaw:
    """Deformable, zero-tension, cohesionless Coulomb joints (no dilatancy).

    Parameters
    ----------
    normal_stiffness : float
        Joint normal stiffness k_n, Pa/m (> 0). Default 1e12 Pa/m = 1000 GPa/m, the plausible
        reading of the paper's "10^12 GPa/m" (see docs/models/dem.md).
    shear_stiffness : float
        Joint shear stiffness k_s, Pa/m (> 0). Default equal to ``normal_stiffness``.
    friction : float
        Coulomb friction coefficient mu = tan(friction angle) (> 0); very large by default.

    Examples
    --------
    >>> import math
    >>> law = ContactLaw.from_friction_angle(math.radians(30.0))
    >>> round(law.friction, 4), round(math.degrees(law.friction_angle), 1)
    (0.5774, 30.0)
    """

    normal_stiffness: float = 1.0e12
    shear_stiffness: float | None = None
    friction: float = NO_SLIDING

    def __post_init__(self) -> None:
        lo, hi = STIFFNESS_RANGE_PA_M
        kn = require_range("normal_stiffness", self.normal_stiffness, lo, hi, "Pa/m",
                           low_open=False, high_open=False)
        ks = kn if self.shear_stiffness is None else self.shear_stiffness
        ks = require_range("shear_stiffness", ks, lo, hi, "Pa/m", low_open=False,
                           high_open=False)
        mu = require_range("friction coefficient", self.friction, 0.0, MAX_FRICTION,
                           high_open=False)
        object.__setattr__(self, "normal_stiffness", kn)
        object.__setattr__(self, "shear_stiffness", ks)
        object.__setattr__(self, "friction", mu)

    @classmethod
    def from_friction_angle(cls, angle: float, **kwargs: float) -> ContactLaw:
        """Build from a friction angle in rad, 0 < angle < pi/2."""
        require_range("friction angle", angle, 0.0, 0.5 * math.pi, "rad")
        return cls(friction=math.tan(angle), **kwargs)

    @property
    def friction_angle(self) -> float:
        """atan(mu), rad."""
        return math.atan(self.friction)

    def to_dict(self) -> dict:
        return {
            "normal_stiffness_Pa_m": self.normal_stiffness,
            "shear_stiffness_Pa_m": self.shear_stiffness,
            "friction_coefficient": self.friction,
        }


@dataclass(frozen=True)
class DemSettings:
    """Everything a distinct-element run needs besides the blocks and the ground motion.

    Parameters
    ----------
    contact : ContactLaw
        Joint law (stiffnesses, friction).
    damping : tuple of two floats
        Rayleigh damping ``(alpha, beta)``: alpha in 1/s (mass-proportional), beta in s
        (stiffness-proportional). Default: the paper's (6.28e-5, 1.59e-4). Use
        `rayleigh_from_minimum` for UDEC's ``(f_min, xi_min)`` form.
    duration : float
        Simulated time after the pulse starts, s (> 0).
    output_interval : float
        Sampling interval of the recorded histories, s (> 0).
    safety : float
        Fraction (0, 1] of the stable time step actually used.
    time_step : float or None
        Fixed time step, s; ``None`` (default) derives it from the block masses, inertias,
        contact stiffnesses and damping (`archquake.dem.run.stable_time_step`).
    settle_time : float
        Time, s (>= 0), for which the assembly is brought to rest under gravity (kinetic
        damping) before the ground starts to move, so that the joints carry their static
        forces at t = 0 (UDEC practice: solve to equilibrium, then shake).
    collapse_drop, collapse_rotation, hinge_opening, stop_at_collapse
        The thresholds both block models read, held as a
        `archquake.blocks.criteria.BlockCriteria` (``criteria``; see it for their
        meaning and units).
    stop_at_rest : bool
        End the run once it is at rest after the excitation (`archquake.blocks.result.settled`
        on the samples so far: the rule by which a run's verdict is ``survives``), instead of
        at ``duration``. After the excitation the energy can only decrease, so the verdict is
        the one the whole run would give; ``duration`` is then the longest the run may take.
        Default False: the run covers ``duration`` (its histories to the end).
    """

    contact: ContactLaw = ContactLaw()
    damping: tuple[float, float] = (6.28e-5, 1.59e-4)
    duration: float = 3.0
    output_interval: float = 0.005
    safety: float = 0.8
    time_step: float | None = None
    settle_time: float = 0.02
    collapse_drop: float = 1.0
    collapse_rotation: float = 0.5 * math.pi
    hinge_opening: float = 1.0e-4
    stop_at_collapse: bool = True
    stop_at_rest: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.contact, ContactLaw):
            raise InvalidParameterError(
                f"contact must be a ContactLaw, got {type(self.contact).__name__}"
            )
        try:
            alpha, beta = self.damping
        except (TypeError, ValueError):
            raise InvalidParameterError(
                f"damping must be a pair (alpha [1/s], beta [s]), got {self.damping!r}"
            ) from None
        alpha = require_finite("Rayleigh alpha", alpha, "1/s")
        beta = require_finite("Rayleigh beta", beta, "s")
        if alpha < 0 or beta < 0:
            raise InvalidParameterError(
                f"Rayleigh damping (alpha, beta) must both be >= 0, got ({alpha:g}, {beta:g})"
            )
        require_range("Rayleigh alpha", alpha, 0.0, MAX_RAYLEIGH_ALPHA, "1/s", low_open=False,
                      high_open=False)
        require_range("Rayleigh beta", beta, 0.0, MAX_RAYLEIGH_BETA, "s", low_open=False,
                      high_open=False)
        object.__setattr__(self, "damping", (alpha, beta))
        object.__setattr__(self, "duration", require_range(
            "duration", self.duration, 0.0, MAX_DURATION, "s", high_open=False))
        object.__setattr__(
            self,
            "output_interval",
            require_positive("output_interval", self.output_interval, "s"),
        )
        object.__setattr__(
            self,
            "safety",
            require_range("safety", self.safety, 0.0, 1.0, high_open=False),
        )
        if self.time_step is not None:
            object.__setattr__(self, "time_step", require_range(
                "time_step", self.time_step, *TIME_STEP_RANGE, "s", low_open=False,
                high_open=False))
        settle = require_finite("settle_time", self.settle_time, "s")
        if not 0.0 <= settle <= MAX_DURATION:
            raise InvalidParameterError(
                f"settle_time must be in [0, {MAX_DURATION:g}] s, got {settle:g}")
        object.__setattr__(self, "settle_time", settle)
        criteria = BlockCriteria(hinge_opening=self.hinge_opening,
                                 collapse_rotation=self.collapse_rotation,
                                 collapse_drop=self.collapse_drop,
                                 stop_at_collapse=self.stop_at_collapse)
        object.__setattr__(self, "collapse_drop", criteria.collapse_drop)
        object.__setattr__(self, "collapse_rotation", criteria.collapse_rotation)
        object.__setattr__(self, "hinge_opening", criteria.hinge_opening)
        object.__setattr__(self, "stop_at_collapse", criteria.stop_at_collapse)
        object.__setattr__(self, "stop_at_rest", bool(self.stop_at_rest))

    @property
    def criteria(self) -> BlockCriteria:
        """The thresholds both block models read (`archquake.blocks.criteria.BlockCriteria`):
        ``hinge_opening``, ``collapse_rotation``, ``collapse_drop``, ``stop_at_collapse``."""
        return BlockCriteria(hinge_opening=self.hinge_opening,
                             collapse_rotation=self.collapse_rotation,
                             collapse_drop=self.collapse_drop,
                             stop_at_collapse=self.stop_at_collapse)

    @staticmethod
    def rayleigh_from_minimum(f_min: float, xi_min: float) -> tuple[float, float]:
        """UDEC's Rayleigh damping form: the (alpha, beta) whose damping ratio
        xi(omega) = alpha/(2 omega) + beta omega/2 has its minimum ``xi_min`` at ``f_min`` Hz.

        alpha = xi_min * omega_min, beta = xi_min / omega_min, omega_min = 2 pi f_min.

        Examples
        --------
        The paper's values (xi_min = 0.01 % at 0.1 Hz):

        >>> a, b = DemSettings.rayleigh_from_minimum(0.1, 1e-4)
        >>> f"{a:.3g} {b:.3g}"
        '6.28e-05 0.000159'
        """
        f = require_positive("f_min", f_min, "Hz")
        xi = require_finite("xi_min", xi_min)
        if xi < 0:
            raise InvalidParameterError(f"xi_min must be >= 0 (a fraction, not %), got {xi:g}")
        omega = 2.0 * math.pi * f
        return xi * omega, xi / omega

    def with_(self, **changes: Any) -> DemSettings:
        """A copy with some fields changed (validated again)."""
        from dataclasses import replace

        return replace(self, **changes)

    def to_dict(self) -> dict:
        return {
            "contact": self.contact.to_dict(),
            "rayleigh_alpha_1_s": self.damping[0],
            "rayleigh_beta_s": self.damping[1],
            "duration_s": self.duration,
            "output_interval_s": self.output_interval,
            "safety": self.safety,
            "time_step_s": self.time_step,
            "settle_time_s": self.settle_time,
            "collapse_drop": self.collapse_drop,
            "collapse_rotation_rad": self.collapse_rotation,
            "hinge_opening": self.hinge_opening,
        }


__all__ = ["ContactLaw", "DemSettings", "NO_SLIDING"]
