"""What became of the arch: the one outcome vocabulary of every model.

Both the analytical rocking model (:func:`archquake.mechanism.simulate`) and the
distinct-element model (:func:`archquake.dem.simulate_dem`) classify a run as one of these
three outcomes, and the failure-domain search (:mod:`archquake.domains`) brackets their
boundaries whichever model is plugged in.

Examples
--------
>>> Outcome("collapse") is Outcome.COLLAPSE, Outcome.SURVIVES.value
(True, 'survives')
"""

from __future__ import annotations

from enum import Enum


class Outcome(str, Enum):
    """What happened to the arch.

    ``no_hinging``
        No joint opened: the arch moved rigidly with the ground (the ground acceleration never
        exceeded the static collapse acceleration in either direction).
    ``survives``
        Hinges opened, and the arch did not collapse (it came to rest, or was still rocking
        at the end of the run).
    ``collapse``
        The arch collapsed (each model states its criterion: the analytical model when the
        mechanism passes the crest of its potential energy after the excitation or reaches
        its toggle; the distinct-element model when the crown has fallen, a block has gone
        below the springings or turned too far).
    """

    NO_HINGING = "no_hinging"
    SURVIVES = "survives"
    COLLAPSE = "collapse"


#: The keys that every model's ``result.to_dict()`` carries, with the same meaning and units
#: (what ``archquake run --json`` prints and a sweep stores as ``out.<key>``); each model adds
#: its own after them.
#:
#: ``model``: ``'analytical'`` or ``'dem'``; ``outcome``: an :class:`Outcome` value;
#: ``final_state``: how the run ended (analytical: rest, moving, collapsed, stalled; the
#: distinct-element model runs for a fixed time and reports ``collapsed`` or None);
#: ``collapse_half_cycle``: 1 = before the first impact, 2 = after it, ... (None: no collapse);
#: ``collapse_time_s``, ``onset_time_s`` (hinging starts): s or None; ``impact_times_s``: s,
#: before the collapse; ``peak_rotation_rad``: the largest rotation of each half cycle, rad;
#: ``max_rotation_rad``: the largest of them, rad; ``g_m_s2``: gravity, m/s^2.
RESULT_KEYS = ("model", "outcome", "final_state", "collapse_half_cycle", "collapse_time_s",
               "onset_time_s", "impact_times_s", "peak_rotation_rad", "max_rotation_rad",
               "g_m_s2")


__all__ = ["Outcome", "RESULT_KEYS"]
