"""What became of the arch: the one outcome vocabulary of every model.

Both the analytical rocking model (:func:`archquake.mechanism.simulate`) and the
distinct-element model (:func:`archquake.dem.simulate_dem`) classify a run as one of these
outcomes, and the failure-domain search (:mod:`archquake.domains`) brackets their
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
        Hinges opened, and the arch did not collapse (the analytical model: it came to rest, or
        was still rocking at the end of the run, ``final_state`` says which; the block models,
        the DEM and the rigid chain: it came to rest after the excitation,
        :func:`archquake.dem.result.settled`).
    ``collapse``
        The arch collapsed (each model states its criterion: the analytical model when the
        mechanism passes the crest of its potential energy after the excitation or reaches
        its toggle; the distinct-element model when the crown has fallen, a block has gone
        below the springings or turned too far).
    ``indeterminate``
        The analytical model reached a verdict only through an impact its impact law cannot
        describe (:func:`qualify` states the rule): neither collapse nor survival is claimed.
        A block model (DEM, rigid chain) returns it when hinges opened and the run ended with
        the arch still moving (``final_state`` ``moving``): run longer to decide.
    """

    NO_HINGING = "no_hinging"
    SURVIVES = "survives"
    COLLAPSE = "collapse"
    INDETERMINATE = "indeterminate"


def qualify(outcome: Outcome, *, collapse_half_cycle: int | None, impacts: int,
            impact_described: bool) -> Outcome:
    """The verdict as it may be stated, given whether the impact law describes the impacts.

    The rule (docs/mechanism.md, "An honest verdict"): a verdict *depends on an impact* when an
    impact happened before it was reached:

    * ``collapse`` in half cycle 2 or later (an impact preceded it; half cycle 1 does not
      depend on any impact);
    * ``survives`` after at least one impact (the arch's later half cycles, and so the absence
      of collapse, follow from the impacts; survival with no impact does not);
    * ``no_hinging`` never (no mechanism opened, no impact).

    If the verdict depends on an impact and the law does not describe the impacts
    (:meth:`archquake.mechanism.impact.ImpactSolution.describes`: Eq. 4 creating energy or
    giving c_v < 0; the chain law's response outside the four-hinge model), the verdict is
    ``indeterminate``; otherwise it stands. Describedness is per impact: the caller passes
    whether *every impact before the verdict* is described (each impact has the validity of
    the mechanism that closed, :attr:`archquake.mechanism.prepared.PreparedMechanism.table`).

    Parameters
    ----------
    outcome : Outcome
        What the model computed with the law as stated.
    collapse_half_cycle : int or None
        1 = collapse before any impact (ignored unless ``outcome`` is collapse).
    impacts : int
        Impacts computed before the verdict (before the collapse, or in the whole run).
    impact_described : bool
        Every impact before the verdict is described by the law.

    Examples
    --------
    >>> qualify(Outcome.COLLAPSE, collapse_half_cycle=2, impacts=1, impact_described=False).value
    'indeterminate'
    >>> qualify(Outcome.COLLAPSE, collapse_half_cycle=1, impacts=0, impact_described=False).value
    'collapse'
    """
    outcome = Outcome(outcome)
    if impact_described or outcome in (Outcome.NO_HINGING, Outcome.INDETERMINATE):
        return outcome
    if outcome is Outcome.COLLAPSE:
        return Outcome.INDETERMINATE if (collapse_half_cycle or 1) >= 2 else outcome
    return Outcome.INDETERMINATE if impacts > 0 else outcome


#: The keys that every model's ``result.to_dict()`` carries, with the same meaning and units
#: (what ``archquake run --json`` prints and a sweep stores as ``out.<key>``); each model adds
#: its own after them.
#:
#: ``model``: ``'analytical'``, ``'dem'`` or ``'rigid_chain'``; ``outcome``: an :class:`Outcome` value;
#: ``final_state``: how the run ended (analytical: rest, moving, collapsed, stalled; the
#: block models: collapsed, rest or moving);
#: ``collapse_half_cycle``: 1 = before the first impact, 2 = after it, ... (None: no collapse);
#: ``collapse_time_s``, ``onset_time_s`` (hinging starts): s or None; ``impact_times_s``: s,
#: before the collapse; ``peak_rotation_rad``: the largest rotation of each half cycle, rad;
#: ``max_rotation_rad``: the largest of them, rad; ``g_m_s2``: gravity, m/s^2.
RESULT_KEYS = ("model", "outcome", "final_state", "collapse_half_cycle", "collapse_time_s",
               "onset_time_s", "impact_times_s", "peak_rotation_rad", "max_rotation_rad",
               "g_m_s2")


__all__ = ["Outcome", "RESULT_KEYS", "qualify"]
