"""Warnings about the command line's values: a value accepted although it lies far outside
practice (the usual slip is a unit: m/s^2 typed as g, ms as s), one line on stderr naming the
option as typed.

The options' checks call :func:`warn_input`; :func:`archquake.cli.main.main` prints the lines
once the command has run, and drops them when it refuses the command line (a refusal stays one
line, exit status 2).
"""

from __future__ import annotations

import sys

_PENDING: list[str] = []


def warn_input(option: str, text: str) -> None:
    """Note ``archquake: warning: {option} {text}`` to print when the command ends (once)."""
    line = f"archquake: warning: {option} {text}"
    if line not in _PENDING:
        _PENDING.append(line)


def warn_pga(option: str, value_g: float | None) -> None:
    """Note a peak ground acceleration typed as ``option`` (g) above
    :data:`~archquake.ranges.PLAUSIBLE_PGA_G`, beyond design practice (m/s^2 typed as g?)."""
    text = pga_note(value_g)
    if text is not None:
        warn_input(option, text)


def pga_note(value_g: float | None) -> str | None:
    """What :func:`warn_pga` says after the option's name, or None for a plausible value."""
    from archquake.ranges import PLAUSIBLE_PGA_G

    if value_g is None or not value_g > PLAUSIBLE_PGA_G:
        return None
    return (f"{value_g:g} g is above {PLAUSIBLE_PGA_G:g} g, beyond design practice: is it in g "
            "(not m/s^2)?")


def take_input_warnings() -> list[str]:
    """The lines noted since the last call, which forgets them."""
    lines = list(_PENDING)
    _PENDING.clear()
    return lines


def print_input_warnings() -> None:
    """Print the noted lines on stderr (and forget them)."""
    for line in take_input_warnings():
        print(line, file=sys.stderr, flush=True)


__all__ = ["pga_note", "print_input_warnings", "take_input_warnings", "warn_input", "warn_pga"]
