"""Inputs of the IDA tests: Oppenheim's arch and synthetic records."""

from __future__ import annotations

import numpy as np

from archquake.ground import Record
from archquake.sweeps import ArchSpec

OPPENHEIM = ArchSpec(10, 0.15, 157.5, 7)


def synthetic_record(seed: int, *, duration: float = 8.0, dt: float = 0.01,
                     name: str | None = None) -> Record:
    """Band-limited noise under a rise-and-decay envelope plus one velocity pulse (m/s^2,
    PGA ~ 0.3 g): rich enough to rock the arch through several impacts."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, dt)
    noise = np.convolve(rng.standard_normal(t.size), np.ones(8) / 8, mode="same")
    envelope = (t / 1.5) ** 2 * np.exp(2.0 * (1.0 - t / 1.5))
    pulse_period = 0.5 + rng.random()
    pulse = np.where((t > 2.0) & (t < 2.0 + pulse_period),
                     np.sin(2 * np.pi * (t - 2.0) / pulse_period), 0.0)
    acc = noise * envelope + 1.5 * pulse
    acc *= 0.3 * 9.80665 / np.max(np.abs(acc))
    return Record(acc, dt, name=name or f"synthetic{seed}")
