"""Response spectra of records and suites over a period range: each record's and their mean.

Each spectrum is `archquake.ground.measures.response_spectrum` (pseudo-spectral
acceleration of a linear oscillator integrated exactly for the piecewise-linear record,
5 % damping unless stated); this module tabulates it for many records on one period grid and
keeps what record selection needs beside it: the event of each record, the recording it
belongs to (the two horizontal components of one station share it) and the longest period at
which it is usable (1 / its lowest usable frequency, when the suite states one).

Examples
--------
>>> from archquake.ground import Record
>>> import numpy as np
>>> rec = Record(np.sin(np.linspace(0.0, 20 * np.pi, 1001)), 0.01, name="sine")
>>> spec = record_spectra([rec], [0.0, 0.5, 1.0])
>>> spec.periods_s.tolist(), spec.sa.shape
([0.0, 0.5, 1.0], (1, 3))
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

from archquake._validate import require_positive
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.measures import DEFAULT_DAMPING, response_spectrum


@dataclass(frozen=True)
class RecordSpectra:
    """Response spectra of several records on one period grid.

    Parameters
    ----------
    periods_s : numpy.ndarray, shape (m,)
        Periods, s (T = 0 gives each record's PGA).
    sa : numpy.ndarray, shape (n, m)
        Pseudo-spectral acceleration of each record (rows) at each period, m/s^2.
    names : tuple of str, length n
    events : tuple of str or None
        The earthquake each record comes from (None where the suite does not say).
    recordings : tuple of str
        The recording (station and event) each record is a component of.
    usable_period_s : numpy.ndarray, shape (n,)
        Longest usable period of each record, s (inf where the suite does not say).
    damping : float
        Damping ratio of the oscillators.
    g : float
        m/s^2, for values in g.
    """

    periods_s: np.ndarray
    sa: np.ndarray
    names: tuple[str, ...]
    events: tuple[str | None, ...]
    recordings: tuple[str, ...]
    usable_period_s: np.ndarray
    damping: float = DEFAULT_DAMPING
    g: float = STANDARD_GRAVITY
    metadata: dict = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self) -> None:
        periods = np.asarray(self.periods_s, dtype=float)
        sa = np.asarray(self.sa, dtype=float)
        n = len(self.names)
        if periods.ndim != 1 or sa.shape != (n, periods.size):
            raise InvalidParameterError(
                f"sa must have shape (records, periods) = ({n}, {periods.size}), got {sa.shape}")
        if len(self.events) != n or len(self.recordings) != n:
            raise InvalidParameterError("events and recordings must have one entry per record")
        usable = np.broadcast_to(np.asarray(self.usable_period_s, dtype=float), (n,)).copy()
        object.__setattr__(self, "periods_s", periods)
        object.__setattr__(self, "sa", sa)
        object.__setattr__(self, "usable_period_s", usable)
        object.__setattr__(self, "names", tuple(self.names))
        object.__setattr__(self, "events", tuple(self.events))
        object.__setattr__(self, "recordings", tuple(self.recordings))

    def __len__(self) -> int:
        return len(self.names)

    @property
    def mean(self) -> np.ndarray:
        """Arithmetic mean spectrum over the records, m/s^2, shape (m,)."""
        return self.sa.mean(axis=0)

    def subset(self, indices: Sequence[int], factors: Sequence[float] | None = None
               ) -> RecordSpectra:
        """The records at ``indices``, each multiplied by its factor (1 if None)."""
        idx = np.asarray(indices, dtype=int)
        f = np.ones(idx.size) if factors is None else np.asarray(factors, dtype=float)
        return RecordSpectra(self.periods_s, self.sa[idx] * f[:, None],
                             tuple(self.names[i] for i in idx),
                             tuple(self.events[i] for i in idx),
                             tuple(self.recordings[i] for i in idx),
                             self.usable_period_s[idx], self.damping, self.g, self.metadata)

    def to_dict(self) -> dict:
        """Plain values (units in the keys) for JSON."""
        return {
            "periods_s": self.periods_s,
            "damping_ratio": self.damping,
            "mean_sa_g": self.mean / self.g,
            "records": [
                {"name": name, "event": event, "recording": rec,
                 "usable_period_s": float(up) if math.isfinite(up) else None,
                 "sa_g": row / self.g}
                for name, event, rec, up, row in zip(self.names, self.events, self.recordings,
                                                     self.usable_period_s, self.sa)
            ],
            "g_m_s2": self.g,
        }


def record_spectra(records: Iterable, periods: Iterable[float] | np.ndarray, *,
                   damping: float = DEFAULT_DAMPING, g: float = STANDARD_GRAVITY
                   ) -> RecordSpectra:
    """Response spectra of ``records`` (a `Suite`, or any
    iterable of motions) at ``periods`` (s).

    Parameters
    ----------
    records : iterable of Record (or any GroundMotion)
        A record's ``metadata`` may carry ``event``, ``rsn`` or ``record_id`` (the recording its
        components share) and ``lowest_usable_frequency_hz``, as the FEMA P695 suites do.
    periods : array_like
        Periods, s (>= 0).
    damping : float
        Oscillator damping ratio (default 0.05).
    g : float
        m/s^2.

    Returns
    -------
    RecordSpectra
    """
    g = require_positive("g", g, "m/s^2")
    periods = np.asarray(list(periods) if not isinstance(periods, np.ndarray) else periods,
                         dtype=float)
    motions = list(records)
    if not motions:
        raise InvalidParameterError("record_spectra needs at least one record")
    names, events, recordings, usable, rows = [], [], [], [], []
    for i, motion in enumerate(motions):
        meta = dict(getattr(motion, "metadata", None) or {})
        name = str(getattr(motion, "name", None) or f"motion {i + 1}")
        names.append(name)
        events.append(meta.get("event"))
        recording = meta.get("rsn", meta.get("record_id"))
        recordings.append(f"{meta.get('suite_set', '')}:{recording}" if recording is not None
                          else name)
        f_low = meta.get("lowest_usable_frequency_hz")
        usable.append(1.0 / float(f_low) if f_low else math.inf)
        rows.append(response_spectrum(motion, periods, damping=damping))
    return RecordSpectra(periods, np.array(rows), tuple(names), tuple(events), tuple(recordings),
                         np.array(usable), damping, g)


__all__ = ["RecordSpectra", "record_spectra"]
