"""Physical constants. No other module writes a literal value of g."""

from __future__ import annotations

#: Standard gravity, m/s^2 (CGPM 1901). Functions that need gravity take ``g`` by keyword
#: with this default and record the value they used.
STANDARD_GRAVITY: float = 9.80665

__all__ = ["STANDARD_GRAVITY"]
