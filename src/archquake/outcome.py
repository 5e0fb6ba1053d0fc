"""What became of the arch: the one outcome vocabulary of every model.

Both the four-link model (`archquake.mechanism.simulate`) and the
distinct-element model (`archquake.dem.simulate_dem`) classify a run as one of these
outcomes, and the failure-domain search (`archquake.domains`) brackets their
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
        Hinges opened, and the arch did not collapse, and it is shown that it will not (the
        four-link model, `conclude`: it came to rest after the excitation, or after the
        excitation its energy fell below every crest barrier; the block models, the DEM and
        the rigid chain: it came to rest after the excitation,
        `archquake.blocks.result.settled`).
    ``collapse``
        The arch collapsed (each model states its criterion: the four-link model when the
        mechanism passes the crest of its potential energy after the excitation or reaches
        its toggle; the distinct-element model when the crown has fallen, a block has gone
        below the springings or turned too far).
    ``indeterminate``
        The four-link model reached a verdict only through an impact its impact law cannot
        describe (`qualify` states the rule), or its run ended before the survival could be
        shown (`conclude`: ``t_end`` before the end of the excitation, or the arch still
        rocking with energy enough to reach a crest): neither collapse nor survival is claimed.
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

    The rule (docs/notes/mechanism.md, "An honest verdict"): a verdict *depends on an impact* when an
    impact happened before it was reached:

    * ``collapse`` in half cycle 2 or later (an impact preceded it; half cycle 1 does not
      depend on any impact);
    * ``survives`` after at least one impact (the arch's later half cycles, and so the absence
      of collapse, follow from the impacts; survival with no impact does not);
    * ``no_hinging`` never (no mechanism opened, no impact).

    If the verdict depends on an impact and the law does not describe the impacts
    (`archquake.mechanism.impact.ImpactSolution.describes`: Eq. 4 creating energy or
    giving c_v < 0; the chain law's response outside the four-hinge model), the verdict is
    ``indeterminate``; otherwise it stands. Describedness is per impact: the caller passes
    whether *every impact before the verdict* is described (each impact has the validity of
    the mechanism that closed, `archquake.mechanism.prepared.PreparedMechanism.table`).

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


def conclude(outcome: Outcome, *, final_state: str, t_end_s: float, excitation_end_s: float,
             below_barrier: bool, energy_fraction: float | None = None) -> tuple[Outcome, str]:
    """The four-link model's verdict as it may be stated, given how its run ended, with the
    reason in one sentence.

    The rule (docs/notes/mechanism.md, "Time history: events, collapse, rest"): ``collapse`` stands
    (the mechanism passed its crest after the excitation, or reached its toggle). Otherwise the
    arch is only shown to be safe if nothing can still happen:

    * the run ended before the excitation did (``t_end_s < excitation_end_s``): the rest of it
      may still open hinges or bring collapse, so ``no_hinging`` and ``survives`` are
      ``indeterminate``;
    * ``no_hinging`` over the whole excitation stands;
    * ``survives`` stands when the arch came to rest after the excitation (``final_state``
      ``rest``: an impact left too little motion for another half cycle), or, still rocking at
      ``t_end`` (``moving``) or locked by ``max_impacts`` (``stalled``), when it is provably
      unable to reach a crest again (``below_barrier``: an impact after the excitation left
      ``1/2 m_eff(0) phi'^2`` below the least crest barrier ``g [V(phi_crit) - V(0)]`` of the
      mechanism table and no row's impact gains energy,
      `archquake.mechanism._kernels.table_energies`); else it is ``indeterminate``.
      ``unresolved`` (an impact left the tabulated mechanisms) is never shown safe here
      (`qualify` makes it indeterminate through the impact's validity as well).

    Apply `qualify` to the result for the impacts the law does not describe.

    Parameters
    ----------
    outcome : Outcome
        What the model computed (no_hinging, survives, collapse).
    final_state : str
        How the run ended: ``rest``, ``moving``, ``stalled``, ``collapsed``, ``unresolved``
        (a rest reached only because ``max_impacts`` locked the arch is ``stalled``).
    t_end_s, excitation_end_s : float
        End of the run and of the excitation, s.
    below_barrier : bool
        The barrier proof above holds.
    energy_fraction : float, optional
        The kinetic energy the last impact after the excitation left, as a fraction of the
        least crest barrier (for the reason; None: no such impact or the proof does not apply).

    Returns
    -------
    (Outcome, str)
        The verdict and its reason.

    Examples
    --------
    >>> conclude(Outcome.SURVIVES, final_state="moving", t_end_s=2.0, excitation_end_s=0.8,
    ...          below_barrier=False)[0].value
    'indeterminate'
    >>> conclude(Outcome.SURVIVES, final_state="rest", t_end_s=9.0, excitation_end_s=0.8,
    ...          below_barrier=False)[0].value
    'survives'
    """
    outcome = Outcome(outcome)
    if outcome is Outcome.COLLAPSE:
        return outcome, ("the mechanism passed the crest of its potential energy after the "
                         "excitation (or could no longer be brought back), or reached its toggle")
    if outcome is Outcome.INDETERMINATE:
        return outcome, "indeterminate as computed"
    if t_end_s < excitation_end_s:
        return Outcome.INDETERMINATE, (
            f"the run ended at t_end = {t_end_s:.4g} s, before the excitation ended at "
            f"{excitation_end_s:.4g} s: the rest of it may still open hinges or bring collapse; "
            "run to the end of the excitation or beyond (the default t_end) to decide")
    if outcome is Outcome.NO_HINGING:
        return outcome, "no hinge opened: the ground acceleration never exceeded lambda g"
    if final_state == "rest":
        return outcome, ("at rest after the excitation: an impact left too little motion for "
                         "another half cycle")
    if final_state in ("moving", "stalled") and below_barrier:
        share = "" if energy_fraction is None else f" ({energy_fraction:.3g} of it)"
        return outcome, (
            f"{'still rocking at t_end' if final_state == 'moving' else 'stopped by max_impacts'}"
            f", but the last impact, after the excitation, left a kinetic energy below the least "
            f"crest barrier g [V(phi_crit) - V(0)] of the mechanisms{share}, and no impact "
            "gains energy: the arch cannot reach a crest again")
    if final_state == "moving":
        return Outcome.INDETERMINATE, (
            f"still rocking at t_end = {t_end_s:.4g} s, and no impact after the excitation has "
            "shown its energy below every crest barrier: run longer (a larger t_end) to decide")
    if final_state == "stalled":
        return Outcome.INDETERMINATE, (
            "stopped by max_impacts, and no impact after the excitation has shown its energy "
            "below every crest barrier: raise max_impacts to decide")
    return Outcome.INDETERMINATE, (
        "an impact left the tabulated mechanisms and the history stopped there")


#: The keys that every model's ``result.to_dict()`` carries, with the same meaning and units
#: (what ``archquake run --json`` prints and a sweep stores as ``out.<key>``); each model adds
#: its own after them.
#:
#: ``model``: ``'rigid'``, ``'fourlink'`` or ``'dem'`` (as ``--model`` names them);
#: ``outcome``: an `Outcome` value; ``final_state``: how the run ended (fourlink:
#: rest, moving, collapsed, stalled; the block models: collapsed, rest or moving);
#: ``collapse_half_cycle``: 1 = before the first impact, 2 = after it, ... (None: no collapse);
#: ``collapse_time_s``, ``onset_time_s`` (hinging starts): s or None; ``impact_times_s``: s,
#: before the collapse; ``peak_rotation_rad``: the largest rotation of each half cycle, rad;
#: ``max_rotation_rad``: the largest of them, rad; ``g_m_s2``: gravity, m/s^2.
RESULT_KEYS = ("model", "outcome", "final_state", "collapse_half_cycle", "collapse_time_s",
               "onset_time_s", "impact_times_s", "peak_rotation_rad", "max_rotation_rad",
               "g_m_s2")


__all__ = ["Outcome", "RESULT_KEYS", "conclude", "qualify"]
