"""One result interface for the three models.

`archquake.simulate` (the paper's four-link model) returns a
`SimulationResult`, `archquake.simulate_rigid` (the chain of
rigid voussoirs) a `RigidRun` and `archquake.simulate_dem` (the
distinct-element model) a `BlockResult`. Each has its own extras, and all
three satisfy `ModelResult`: the same attributes, with the same meaning and units, so
that a notebook comparing the models reads them alike. The attributes are views of what the
result holds (or computed from it on first use), not copies.

Examples
--------
>>> import math
>>> from archquake import Arch, StepImpulse, simulate
>>> arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
>>> run = simulate(arch, StepImpulse.from_g(1.0, 0.27))
>>> isinstance(run, ModelResult), run.outcome.value
(True, 'collapse')
>>> table = run.to_table()
>>> list(table)[:6] == list(TABLE_COLUMNS)
True
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Protocol, runtime_checkable

import numpy as np

from archquake.outcome import Outcome

#: The columns that every model's ``to_table()`` starts with (each model adds its own after
#: them): time (s), the crown's horizontal and vertical displacement relative to the ground
#: (m), the mechanism's rotation (rad), and the kinetic and gravitational potential energy
#: relative to the ground (J, the potential from the undisplaced arch at rest).
TABLE_COLUMNS = ("time_s", "crown_dx_m", "crown_dy_m", "rotation_rad", "kinetic_J",
                 "potential_J")


@runtime_checkable
class HingeEvent(Protocol):
    """One change of the open hinges in a time history: the four-link model's
    `MechanismEvent`, the block models'
    `HingeSet`."""

    @property
    def time_s(self) -> float:
        """When the hinges changed, s."""

    @property
    def hinges(self) -> str:
        """The hinges open from then on (joint and face, ``"0i 3e 5i 7e"``; "" none)."""

    @property
    def kind(self) -> str:
        """``onset``, ``impact``, ``change``, ``rest`` or ``unresolved`` (each model's own)."""

    def to_dict(self) -> dict:
        """The event for JSON."""


@runtime_checkable
class ModelResult(Protocol):
    """What every model's result has: the verdict, the histories and their export.

    Attributes
    ----------
    outcome : Outcome
        The verdict (`Outcome`).
    verdict_reason : str
        Why the verdict is what it is, in one sentence (the JSON key ``verdict``).
    times : ndarray (nt,)
        s, the recorded samples (the four-link model: empty if run with
        ``output_interval=0``).
    crown_displacement : ndarray (nt, 2)
        The crown point's displacement dx, dy relative to the ground, m (NaN for a DEM
        assembly with no crown block).
    rotation : ndarray (nt,)
        The mechanism's rotation, rad: > 0 while the first mechanism (the one a ground
        acceleration towards -x opens) is open, < 0 in its mirror image. The four-link
        model's phi; the block models' chord rotation (`archquake.blocks.result`).
    kinetic, potential : ndarray (nt,)
        Kinetic energy relative to the ground and gravitational potential energy from the
        undisplaced arch, J.
    impact_times : ndarray (k,)
        s, before the collapse.
    hinge_events : tuple of HingeEvent
        Every change of the open hinges, in time order.
    onset_time, collapse_time : float or None
        s: hinging starts; the collapse (each model's criterion: compare outcomes, not
        collapse times).
    peak_rotation : ndarray (half cycles,)
        The largest rotation of each half cycle, rad.
    collapse_half_cycle : int or None
        1 = collapse before any impact, 2 = after the first, ...
    g : float
        Gravity, m/s^2.
    """

    @property
    def outcome(self) -> Outcome: ...

    @property
    def verdict_reason(self) -> str: ...

    @property
    def times(self) -> np.ndarray: ...

    @property
    def crown_displacement(self) -> np.ndarray: ...

    @property
    def rotation(self) -> np.ndarray: ...

    @property
    def kinetic(self) -> np.ndarray: ...

    @property
    def potential(self) -> np.ndarray: ...

    @property
    def impact_times(self) -> np.ndarray: ...

    @property
    def hinge_events(self) -> tuple[HingeEvent, ...]: ...

    @property
    def onset_time(self) -> float | None: ...

    @property
    def collapse_time(self) -> float | None: ...

    @property
    def peak_rotation(self) -> np.ndarray: ...

    @property
    def collapse_half_cycle(self) -> int | None: ...

    @property
    def g(self) -> float: ...

    def to_dict(self) -> dict:
        """The summary for JSON: the keys of `archquake.outcome.RESULT_KEYS` first."""

    def to_table(self) -> dict[str, np.ndarray]:
        """Equal-length columns (`TABLE_COLUMNS` first), for ``pandas.DataFrame``."""

    def to_csv(self, path: str | Path) -> Path:
        """Write `to_table` as CSV (a header of column names, one row per sample)."""


def shared_columns(result: ModelResult) -> dict[str, np.ndarray]:
    """The `TABLE_COLUMNS` of a result (its ``to_table()`` adds its own after them)."""
    crown = result.crown_displacement
    return {"time_s": result.times, "crown_dx_m": crown[:, 0], "crown_dy_m": crown[:, 1],
            "rotation_rad": result.rotation, "kinetic_J": result.kinetic,
            "potential_J": result.potential}


def shared_keys(result: ModelResult, model: str, final_state: str) -> dict:
    """The keys of `archquake.outcome.RESULT_KEYS`, in that order, for a result's
    ``to_dict()`` (each model adds its own after them).

    Parameters
    ----------
    result : ModelResult
    model : str
        ``'fourlink'``, ``'rigid'`` or ``'dem'`` (as ``--model`` names them).
    final_state : str
        How the run ended, in the model's words.
    """
    peaks = result.peak_rotation
    return {
        "model": model,
        "outcome": result.outcome.value,
        "final_state": final_state,
        "collapse_half_cycle": result.collapse_half_cycle,
        "collapse_time_s": result.collapse_time,
        "onset_time_s": result.onset_time,
        "impact_times_s": result.impact_times.tolist(),
        "peak_rotation_rad": peaks.tolist(),
        "max_rotation_rad": float(peaks.max()) if peaks.size else 0.0,
        "g_m_s2": result.g,
    }


def write_csv(table: dict[str, np.ndarray], path: str | Path) -> Path:
    """Write equal-length columns as CSV: a header of the column names, then one row per
    sample, each number with ten significant digits (integer columns as integers).

    Parameters
    ----------
    table : dict of str to ndarray (n,)
    path : str or Path

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    names = list(table)
    columns = [np.asarray(table[n]) for n in names]
    lengths = {c.shape[0] for c in columns}
    if len(lengths) > 1:
        raise ValueError(f"columns of unequal length: {dict(zip(names, map(len, columns)))}")
    formats = ["{:d}" if np.issubdtype(c.dtype, np.integer) else "{:.9e}" for c in columns]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for row in zip(*columns):
            w.writerow([f.format(x) for f, x in zip(formats, row)])
    return path


__all__ = ["TABLE_COLUMNS", "HingeEvent", "ModelResult", "shared_columns", "shared_keys",
           "write_csv"]
