"""The ground-motion contract shared by the analytical model and the distinct-element model.

Sign convention: ``acceleration(t)`` is the horizontal ground acceleration x_g'' in m/s^2,
positive towards +x (to the right). A ground acceleration towards -x loads the arch with an
inertia force towards +x and drives the paper's first mechanism (its Figure 1; the paper
quotes the onset as "-0.37 g" for this reason). The pulses here therefore start towards -x
by default (``direction=-1``); ``mirrored()`` flips any motion.

Every motion also describes itself to the compiled kernels as ``(kind, params)``:

==========  =================================  ==========================================
kind        params (float64)                   x_g''(t)
==========  =================================  ==========================================
0 step      [a, t_p, direction]                direction*a on [0, t_p), -direction*a/2 on
                                               [t_p, 3 t_p), 0 after (Oppenheim's impulse)
1 sine      [a, T, direction]                  direction*a*sin(2 pi t/T) on [0, T), 0 after
2 sampled   [t0, dt, x_0, x_1, ..., x_{N-1}]   linear between samples, 0 outside
==========  =================================  ==========================================
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

KIND_STEP = 0
KIND_SINE = 1
KIND_SAMPLED = 2


@runtime_checkable
class GroundMotion(Protocol):
    """A horizontal ground acceleration history."""

    @property
    def name(self) -> str:
        """Label of the motion (read-only: the motions are frozen dataclasses)."""
        ...

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Ground acceleration x_g'' at times ``t`` (s), m/s^2, positive towards +x."""
        ...

    @property
    def duration(self) -> float:
        """Time (s) after which the acceleration is identically zero."""
        ...

    def breakpoints(self) -> np.ndarray:
        """Times (s) in [0, duration] where x_g'' or its slope jumps; integrators stop there."""
        ...

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        """``(kind, params)`` for the compiled evaluator (see the module docstring)."""
        ...

    def mirrored(self) -> GroundMotion:
        """The same motion towards the other side."""
        ...

    def scaled(self, factor: float) -> GroundMotion:
        """The motion with every acceleration multiplied by ``factor``."""
        ...

    def to_dict(self) -> dict:
        """Plain description for JSON (accelerations in m/s^2 and in g)."""
        ...


__all__ = ["GroundMotion", "KIND_STEP", "KIND_SINE", "KIND_SAMPLED"]
