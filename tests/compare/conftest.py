"""Shared fixtures for the four-link-vs-DEM comparison tests."""

from __future__ import annotations

import math

import pytest

from archquake.geometry import Arch


@pytest.fixture(scope="session")
def oppenheim() -> Arch:
    """Oppenheim's arch: R = 10 m, t/R = 0.15, embrace 157.5 deg, 7 voussoirs (paper p. 2126)."""
    return Arch(10.0, 1.5, math.radians(157.5), 7)
