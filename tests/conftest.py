"""Shared fixtures: the paper's arches."""

from __future__ import annotations

import math

import pytest

from archquake.geometry import Arch


@pytest.fixture
def oppenheim() -> Arch:
    """Oppenheim's arch: t/R = 0.15, embrace 157.5 deg, R = 10 m, 7 voussoirs (paper, p. 2126)."""
    return Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
