"""Time histories of the rocking arch (paper Eqs. 2-7): driver and result.

`simulate` takes an arch (or a hinge mechanism) and any ground motion and returns a
`SimulationResult`. The hinges default to those of the equivalent static analysis
(the paper's assumption); after each impact the arch continues on the mechanism the impact law
selects (the mirror image for Eq. 4 and "mirror"; the chain law's choice, from the reachable set
tabulated in `table`) with the law's rate
or a prescribed coefficient of restitution.

Outcomes
--------
``no_hinging``
    The ground acceleration never exceeded the static collapse acceleration in the direction of
    either mechanism: the arch moved rigidly with the ground.
``collapse``
    After the excitation had ended, the mechanism was opening at or beyond the crest of its
    potential energy (``phi >= phi_crit``, where gravity alone can no longer bring it back;
    past the crest the potential decreases up to the toggle, so energy conservation forbids a
    return), or, at any time, the linkage reached its toggle position. The collapse time is the
    first such instant; the half cycle counts the mechanisms opened so far (1 = before any impact).
``survives``
    Hinges opened, no collapse, and the run shows that none can come
    (`archquake.outcome.conclude`): the arch came to rest after the excitation (an impact
    left a rate whose next half cycle would peak below ``rest_rotation``; ``final_state``
    ``rest``), or it was still rocking at ``t_end`` (``moving``) or stopped by ``max_impacts``
    (``stalled``) but its last impact, after the excitation, left a kinetic energy
    ``1/2 m_eff(0) phi'^2`` below the least crest barrier ``g [V(phi_crit) - V(0)]`` over the
    rows of the mechanism table, with every row's c_T <= 1 (free rocking then never reaches a
    crest: the proof of the domain and IDA batches, with their
    `table_energies`).
``indeterminate``
    The run ended before the survival (or the absence of hinging) could be shown: ``t_end``
    before the end of the excitation, or still rocking (stalled) without that proof; or a
    verdict was computed only through an impact the impact law does not describe
    (`archquake.outcome.qualify`, with the validity of each impact before the verdict).
    ``computed_outcome`` keeps what was computed, ``verdict_reason`` (JSON ``verdict``) says why.
    With the default ``t_end`` (the end of the excitation plus 60 sqrt(R/g)) a described run
    nearly always ends at rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import Enum
from functools import cached_property, lru_cache
from pathlib import Path

import numpy as np

import archquake.mechanism._kernels as K
from archquake._validate import (
    require_array,
    require_finite,
    require_gravity,
    require_instance,
    require_int,
    require_positive,
    require_range,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.hinges import HingeMechanism
from archquake.ground.base import (
    GroundMotion,
    check_lift_off,
    check_motion,
    check_time_resolution,
)
from archquake.mechanism.impact import check_restitution
from archquake.mechanism.prepared import PreparedMechanism
from archquake.outcome import Outcome, conclude, qualify
from archquake.ranges import RUN_TAIL, default_t_end  # noqa: F401  (re-exported)
from archquake.result import shared_columns, shared_keys, write_csv


class FinalState(str, Enum):
    """How the integration ended."""

    REST = "rest"
    MOVING = "moving"  # still rocking below the crest at t_end
    COLLAPSED = "collapsed"
    STALLED = "stalled"  # max_impacts reached after the excitation (impacts accumulating)
    UNRESOLVED = "unresolved"  # an impact's post mechanism is beyond the tabulated set


#: Most impacts a run may record (SolverOptions.max_impacts).
MAX_IMPACTS = 1_000_000

#: Samples the history buffer starts with (2.6 MB); a run that needs more is rerun once.
INITIAL_HISTORY_SAMPLES = 1 << 16

#: Most history samples one run may record (40 bytes each: 0.8 GB).
MAX_HISTORY_SAMPLES = 20_000_000

#: Most samples of a locked stretch during the excitation (its interval is at least the
#: excitation's duration over this; after the excitation a locked arch records no samples).
LOCKED_SAMPLES = 100_000

_OUTCOMES = {K.OUTCOME_NO_HINGING: Outcome.NO_HINGING, K.OUTCOME_SURVIVES: Outcome.SURVIVES,
             K.OUTCOME_COLLAPSE: Outcome.COLLAPSE}
_FINALS = {K.FINAL_REST: FinalState.REST, K.FINAL_MOVING: FinalState.MOVING,
           K.FINAL_COLLAPSED: FinalState.COLLAPSED, K.FINAL_STALLED: FinalState.STALLED,
           K.FINAL_UNRESOLVED: FinalState.UNRESOLVED}


@dataclass(frozen=True)
class SolverOptions:
    """Integrator settings.

    Parameters
    ----------
    rtol : float
        Relative tolerance of the Dormand-Prince 5(4) error estimate, in [1e-13, 1e-2] (below,
        the error estimate is rounding noise and the steps collapse to the floor; above, the
        events are located too coarsely to mean anything).
    atol : float
        Absolute tolerance on phi, rad (on the rate: atol * sqrt(g/R), rad/s), in [1e-20, 1e-3].
    rest_rotation : float
        The arch is taken to be at rest when an impact leaves it a rate whose next half cycle
        would peak below this rotation, rad, in (0, 1e-2].
    max_impacts : int
        Impacts recorded at most (1 to 1,000,000: 32 bytes each); beyond it the arch is locked
        (reported as ``stalled`` if the excitation is over).
    output_interval : float or None
        History sampling interval, s, by cubic Hermite interpolation of the steps (relative
        error of order 1e-5 at the default tolerances, ample for plots); None picks
        sqrt(R/g)/200; 0 records no history; a negative value records the integrator's own
        accepted steps and the events instead (exact to the tolerances).
    """

    rtol: float = 1e-9
    atol: float = 1e-12
    rest_rotation: float = 1e-9
    max_impacts: int = 2000
    output_interval: float | None = None

    def __post_init__(self) -> None:
        require_range("rtol", self.rtol, 1e-13, 1e-2, low_open=False, high_open=False)
        require_range("atol", self.atol, 1e-20, 1e-3, "rad", low_open=False, high_open=False)
        require_range("rest_rotation", self.rest_rotation, 0.0, 1e-2, "rad", high_open=False)
        require_int("max_impacts", self.max_impacts, 1, MAX_IMPACTS)
        if self.output_interval is not None:
            object.__setattr__(self, "output_interval",
                               require_finite("output_interval", self.output_interval, "s"))

    def kernel_settings(self, g: float, t_end: float = math.nan, *, dt_out: float = 0.0,
                        dt_lock: float | None = None, hist_limit: int = 1,
                        initial_rate: float = 0.0) -> np.ndarray:
        """These tolerances, rest rotation and cap on impacts as the compiled kernels' settings
        array (`archquake.mechanism._kernels.settings`, which gives the other arguments),
        with gravity ``g`` (m/s^2) and the end of the analysis ``t_end`` (s; the batches set
        each case's). The output interval is ``dt_out`` (s; default none), not
        ``output_interval``, which `simulate` resolves first."""
        return K.settings(float(g), float(t_end), self.rtol, self.atol, self.rest_rotation,
                          int(self.max_impacts), dt_out=dt_out, dt_lock=dt_lock,
                          hist_limit=hist_limit, initial_rate=initial_rate)


@dataclass(frozen=True)
class History:
    """Sampled time history (shape (N,) each): t (s), phi (rad), phi_dot (rad/s), side
    (0 locked, +1 the row mechanism, -1 its mirror image), ground acceleration (m/s^2), and the
    row of `table` that is open
    (``mechanism_row``; always 0 under Eq. 4 and "mirror").

    ``phi`` is the rotation of the open mechanism's first link (the paper's theta0 - theta,
    or theta'0 - theta' on the mirror image); ``signed_rotation`` = side * phi
    tells a mechanism from its mirror on a plot. ``phi_ddot`` (rad/s^2, Eq. 2) is given for the
    states at requested times (`SimulationResult.evaluated`), None for the sampled history.
    """

    t: np.ndarray
    phi: np.ndarray
    phi_dot: np.ndarray
    side: np.ndarray
    ground_acceleration: np.ndarray
    phi_ddot: np.ndarray | None = None
    mechanism_row: np.ndarray | None = None

    @property
    def signed_rotation(self) -> np.ndarray:
        return self.side * self.phi

    def to_dict(self) -> dict:
        """The columns, keyed with their units (as ``archquake run --history`` writes them)."""
        out = {"t_s": self.t, "phi_rad": self.phi, "phi_dot_rad_s": self.phi_dot,
               "side": self.side, "ground_acceleration_m_s2": self.ground_acceleration}
        if self.phi_ddot is not None:
            out["phi_ddot_rad_s2"] = self.phi_ddot
        if self.mechanism_row is not None:
            out["mechanism_row"] = self.mechanism_row
        return out


@dataclass(frozen=True)
class MechanismEvent:
    """One change of the open mechanism in a time history.

    Attributes
    ----------
    time_s : float
    hinges : str
        The mechanism that opens (``"0i 3e 5i 7e"``: joint and face of A, B, C, D), or, for a
        ``rest`` and an unresolved impact, the one the law selected.
    kind : str
        ``onset`` (hinging starts from rest), ``impact`` (the arch continues on ``hinges``),
        ``rest`` (the impact left too little motion: the arch locks) or ``unresolved`` (the law's
        post-impact mechanism is beyond the tabulated set: the history stops).
    validity : str
        The impact's validity under the law (onsets: ``""``).
    described : bool
        The law describes this impact (onsets: True).
    row : int
        Row of the mechanism table (-1 beyond it); ``side`` +1 the row, -1 its mirror image.
    """

    time_s: float
    hinges: str
    kind: str
    validity: str
    described: bool
    row: int
    side: int

    def to_dict(self) -> dict:
        return {"time_s": self.time_s, "hinges": self.hinges, "kind": self.kind,
                "validity": self.validity, "described": self.described, "row": self.row,
                "side": self.side}


@dataclass(frozen=True)
class SimulationResult:
    """A time history of the arch and what became of it.

    Attributes
    ----------
    outcome : Outcome
        The verdict as it may be stated: ``computed_outcome``, or ``indeterminate`` where the
        run ended before the survival could be shown (`archquake.outcome.conclude`) or the
        verdict depends on an impact the law does not describe
        (`archquake.outcome.qualify`); ``verdict_reason`` says why.
    final_state : FinalState
    collapse_half_cycle : int or None
        1 = collapse before any impact, 2 = after the first impact, ... (the computed collapse,
        also when the verdict is indeterminate).
    collapse_time : float or None, s
    onset_time : float or None
        When hinging started, s.
    impact_times : ndarray, (k,), s
    impact_rates : ndarray, (k, 2)
        phi-dot just before (negative, closing) and just after (opening) each impact, rad/s.
    peak_rotation : ndarray, (half cycles,), rad
        Largest phi in each half cycle (the open mechanism's own phi: under the chain law
        successive half cycles may be different mechanisms, ``mechanisms``).
    restitution_cv : float
        c_v used at the impacts (from Eq. 4, or prescribed); under the chain law, that of the
        first mechanism's impact (sqrt of its c_T; each row's is in ``PreparedMechanism.table``).
    restitution_ct : float
        c_T = c_v^2.
    energy_gain : bool
        True if the c_v used gives c_T > 1 (see `.impact`).
    impact_model_cv : float
        c_v from the impact model (Eq. 4) for this geometry, whether or not it was used.
    impact_admissible : bool
        False if the impact model's c_v is negative (inadmissible: it would start the mirror
        mechanism closing); the impacts are then computed as perfectly plastic (c_v = 0) unless
        a restitution is prescribed.
    impact_law : str
        The impact law (``"paper"``: Eq. 4; ``"chain"``, ``"mirror"``: see
        `archquake.mechanism.impact`).
    impact_validity : str
        The law's validity (`ImpactSolution`).
    impact_followed : bool
        True if the time history moves on the mechanism the law selects after every impact (the
        law's reachable set is tabulated whole, `PreparedMechanism.table`); False if an
        impact could leave the tabulated set (such an impact stops the history, ``unresolved``).
    mechanisms : tuple of MechanismEvent
        The sequence of mechanisms: every onset and impact with the hinges that open, its kind
        and the impact's validity.
    computed_outcome : Outcome
        What the model computed with the impact law as stated (no_hinging, survives, collapse).
    verdict_reason : str
        Why ``outcome`` is what it is, in one sentence (`archquake.outcome.conclude`,
        then `qualify`); the JSON key ``verdict``, as the block models'.
    restitution_prescribed : bool
        True if ``restitution_cv`` was prescribed (``simulate(..., restitution=...)``).
    impact_described : bool
        True if the impact law describes every impact of this history (per impact: the validity
        of its row's impact, `describes`; with
        no impact, whether it describes the first mechanism's).
    mechanism : HingeMechanism
        The first mechanism (opened by a ground acceleration towards -x).
    collapse_acceleration_g : float
        lambda, g: the equivalent static collapse acceleration of the mechanism, the onset
        threshold.
    critical_rotation, toggle_rotation : float, rad
        Crest of the potential and the linkage's toggle.
    history : History or None
    stats : dict
        Integrator counters (steps, rejected steps, right-hand-side evaluations; and
        ``history_reruns`` when the history outgrew its first buffer and the run was repeated
        with one of the exact size).
    evaluated : History or None
        The states at the times requested with ``simulate(..., t_eval=...)`` (with
        ``phi_ddot``), each reached by an integrator step landing on it; only the times reached
        (none after a collapse). None without ``t_eval``.
    """

    outcome: Outcome
    final_state: FinalState
    collapse_half_cycle: int | None
    collapse_time: float | None
    onset_time: float | None
    impact_times: np.ndarray
    impact_rates: np.ndarray
    peak_rotation: np.ndarray
    restitution_cv: float
    restitution_ct: float
    energy_gain: bool
    impact_model_cv: float
    impact_admissible: bool
    mechanism: HingeMechanism
    collapse_acceleration_g: float
    critical_rotation: float
    toggle_rotation: float
    g: float
    history: History | None = field(repr=False, default=None)
    stats: dict = field(default_factory=dict, repr=False)
    evaluated: History | None = field(repr=False, default=None)
    impact_law: str = "paper"
    impact_validity: str = "assumed"
    impact_followed: bool = True
    computed_outcome: Outcome | None = None
    impact_described: bool = True
    restitution_prescribed: bool = False
    mechanisms: tuple = ()
    verdict_reason: str = ""

    @property
    def half_cycles(self) -> int:
        return int(self.peak_rotation.shape[0])

    @property
    def times(self) -> np.ndarray:
        """The history's sample times, s (empty without a history: ``output_interval=0``)."""
        return self.history.t if self.history is not None else np.zeros(0)

    @property
    def rotation(self) -> np.ndarray:
        """phi signed by the side, rad (> 0 in the first mechanism, < 0 in its mirror image),
        at `times`: `History.signed_rotation`."""
        return self.history.signed_rotation if self.history is not None else np.zeros(0)

    @cached_property
    def _motion(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        from archquake.mechanism.configuration import crown_and_energies

        h = self.history
        if h is None:
            return np.zeros((0, 2)), np.zeros(0), np.zeros(0)
        prepared = PreparedMechanism.build(self.mechanism, self.impact_law)
        return crown_and_energies(prepared, h.phi, h.phi_dot, h.side, h.mechanism_row, g=self.g)

    @property
    def crown_displacement(self) -> np.ndarray:
        """(nt, 2): the crown point's displacement dx, dy relative to the ground at
        `times`, m (`archquake.mechanism.configuration.crown_and_energies`;
        computed on first use)."""
        return self._motion[0]

    @property
    def kinetic(self) -> np.ndarray:
        """Kinetic energy relative to the ground, ``1/2 m_eff phi'^2``, at `times`, J."""
        return self._motion[1]

    @property
    def potential(self) -> np.ndarray:
        """Gravitational potential energy from the undisplaced arch at `times`, J."""
        return self._motion[2]

    @property
    def hinge_events(self) -> tuple[MechanismEvent, ...]:
        """The sequence of mechanisms (`mechanisms`), as
        `archquake.result.ModelResult.hinge_events`."""
        return tuple(self.mechanisms)

    def to_table(self) -> dict[str, np.ndarray]:
        """Columns for a tabular export (``pandas.DataFrame(result.to_table())``):
        `archquake.result.TABLE_COLUMNS`, then phi' (rad/s), the side, the ground
        acceleration (m/s^2) and the mechanism's row. Empty columns without a history."""
        out = shared_columns(self)
        h = self.history
        if h is None:
            out.update(phi_dot_rad_s=np.zeros(0), side=np.zeros(0, dtype=int),
                       ground_acceleration_m_s2=np.zeros(0))
            return out
        out.update(phi_dot_rad_s=h.phi_dot, side=np.asarray(h.side).astype(int),
                   ground_acceleration_m_s2=h.ground_acceleration)
        if h.mechanism_row is not None:
            out["mechanism_row"] = h.mechanism_row
        return out

    def to_csv(self, path: str | Path) -> Path:
        """Write `to_table` as CSV (`archquake.result.write_csv`)."""
        return write_csv(self.to_table(), path)

    def to_dict(self, include_history: bool = False) -> dict:
        """Plain dict for JSON (the CLI's ``--json``, a sweep's stored row): the keys of
        `archquake.outcome.RESULT_KEYS`, shared with the distinct-element result, then
        the four-link model's own."""
        out = {
            **shared_keys(self, "fourlink", self.final_state.value),
            "restitution_cv": self.restitution_cv,
            "restitution_ct": self.restitution_ct,
            "energy_gain": self.energy_gain,
            "impact_model_cv": self.impact_model_cv,
            "impact_admissible": self.impact_admissible,
            "impact_law": self.impact_law,
            "impact_validity": self.impact_validity,
            "impact_followed": self.impact_followed,
            "impact_described": self.impact_described,
            "restitution_prescribed": self.restitution_prescribed,
            "computed_outcome": (self.outcome if self.computed_outcome is None
                                 else self.computed_outcome).value,
            "verdict": self.verdict_reason,
            "collapse_acceleration_g": self.collapse_acceleration_g,
            "critical_rotation_rad": self.critical_rotation,
            "toggle_rotation_rad": self.toggle_rotation,
            "hinges": [h.to_dict() for h in self.mechanism.hinges],
            "mechanisms": [e.to_dict() for e in self.mechanisms],
            "solver": {("t_end_s" if k == "t_end" else k): v for k, v in self.stats.items()},
        }
        if include_history and self.history is not None:
            out["history"] = self.history.to_dict()
        return out


def _record_tail(prepared: PreparedMechanism, kind: int,
                 params: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For a sampled record: ``int_{t_i}^{end} |x_g''| dt`` from each sample (m/s, exact for
    the linear interpolation, sign changes included) and, per row of the mechanism table, the
    potential/g at the toggle, for the no-return collapse criterion
    (`archquake.mechanism._kernels.no_return`). The tail is empty (the criterion off) for
    the pulses; a row's toggle value is nan (the criterion off on that row) if the potential
    does not decrease from its crest to its toggle (sampled at 257 points), which the
    criterion's bound assumes.

    A record with its vertical component: the vertical's power on the mechanism,
    -a_v V'(phi) phi', obeys the horizontal's bound (|V'| <= sqrt(M m_eff) by the same
    Cauchy-Schwarz step, V the moving links' potential/g), so the criterion holds with the
    tail of |x_g''| + |a_v|: on the horizontal's grid, continued to the vertical's end, the
    vertical's part taken from its last sample at or before each time (an upper bound)."""
    from archquake.ground.base import KIND_SAMPLED, KIND_SAMPLED_VERTICAL

    rows = prepared.table.packed
    v_toggle = np.full(rows.shape[0], np.nan)
    if kind not in (KIND_SAMPLED, KIND_SAMPLED_VERTICAL):
        return np.empty(0), v_toggle
    for r, packed in enumerate(rows):
        value = _toggle_potential(np.ascontiguousarray(packed).tobytes())
        if value is not None:
            v_toggle[r] = value
    if not np.any(np.isfinite(v_toggle)):
        return np.empty(0), v_toggle
    if kind == KIND_SAMPLED:
        return _abs_tail(params[2:], float(params[1])), v_toggle
    n = int(params[0])
    t0, dt = float(params[1]), float(params[2])
    t0v, dtv, v = float(params[3 + n]), float(params[4 + n]), params[5 + n:]
    end_v = t0v + dtv * (v.size - 1)
    points = max(n, int(math.ceil((end_v - t0) / dt)) + 1)
    tail = np.zeros(points)
    tail[:n] = _abs_tail(params[3:3 + n], dt)
    j = np.floor((t0 + dt * np.arange(points) - t0v) / dtv + 1e-9).astype(np.intp)
    tail += _abs_tail(v, dtv)[np.clip(j, 0, v.size - 1)]
    return np.ascontiguousarray(tail), v_toggle


def _abs_tail(signed: np.ndarray, dt: float) -> np.ndarray:
    """``int_{t_i}^{end} |x| dt`` from each sample of a record linear between its samples
    ``signed`` (time step ``dt``), exact, sign changes included; (n,)."""
    x = np.abs(signed)
    lo, hi = signed[:-1], signed[1:]
    same = lo * hi >= 0.0
    den = np.where(same, 1.0, x[:-1] + x[1:])
    piece = np.where(same, 0.5 * dt * (x[:-1] + x[1:]),
                     0.5 * dt * (lo * lo + hi * hi) / den)
    tail = np.zeros(x.size)
    tail[:-1] = np.cumsum(piece[::-1])[::-1]
    return np.ascontiguousarray(tail)


@lru_cache(maxsize=64)
def _toggle_potential(packed: bytes) -> float | None:
    """Potential/g at the toggle (lowered, see below) of the packed mechanism given by its
    bytes, or None if the potential does not decrease from the crest to the toggle (sampled at
    257 points) or the two are not finite and ordered: the no-return criterion is then off.

    It depends on the mechanism only, so it is computed once per mechanism (the 257 potentials
    are plain Python, 2 ms: a plain loop of ``simulate`` over a suite paid it on every call)."""
    from archquake.mechanism.kinematics import PHI_CRIT, PHI_TOGGLE, potential

    mech = np.frombuffer(packed, dtype=np.float64)
    crest, toggle = float(mech[PHI_CRIT]), float(mech[PHI_TOGGLE])
    if not (math.isfinite(crest) and math.isfinite(toggle) and toggle > crest):
        return None
    phis = np.linspace(crest, crest + (toggle - crest) * (1.0 - 1e-9), 257)
    pot = np.array([potential(mech, float(p)) for p in phis])
    if not (np.all(np.isfinite(pot)) and np.all(np.diff(pot) <= 0.0)):
        return None
    # the last sample sits 1e-9 of the range short of the toggle: lower it by far more than
    # the potential can still drop there (the bound needs a lower bound of the potential)
    return float(pot[-1] - 1e-6 * (pot[0] - pot[-1]))


def mechanism_events(prepared: PreparedMechanism, impacts: np.ndarray, onsets: np.ndarray,
                     restitution: float | None = None) -> tuple[MechanismEvent, ...]:
    """The sequence of mechanisms of a run from the kernel's impacts (the
    `IMPACT_COLUMNS`) and onsets (time, side), in time
    order."""
    table = prepared.table
    described = table.described(prepared.impact.law, restitution)
    events = []
    for t, side in onsets:
        events.append((float(t), 0, MechanismEvent(float(t), table.hinges_label(0, int(side)),
                                                    "onset", "", True, 0, int(side))))
    for row in impacts:
        t, pre, post, side, locked = float(row[0]), int(row[3]), int(row[4]), int(row[5]), row[6]
        if post < 0:
            kind, hinges = "unresolved", ""
        else:
            kind = "rest" if locked else "impact"
            hinges = table.hinges_label(post, side)
        events.append((t, 1, MechanismEvent(t, hinges, kind, table.validity[pre],
                                            bool(described[pre]), post, side)))
    events.sort(key=lambda e: (e[0], e[1]))
    return tuple(e[2] for e in events)


def last_impact_fraction(table: K.Table, impacts: np.ndarray, n_all: int, excitation: float,
                         g: float) -> float:
    """The kinetic energy the run's last impact left, as a fraction of the least crest barrier,
    where the free-rocking proof applies to it (NaN where not): the batches' proof,
    `archquake.mechanism._kernels.last_impact_energy`, with the energies, c_T and described
    rows of the packed impact table ``table``
    (`archquake.mechanism.prepared.PreparedMechanism.kernel_table`)."""
    meff0, barrier = K.table_energies(table.mechs, g)
    return float(K.last_impact_energy(impacts, int(n_all), float(excitation), table, meff0,
                                      float(barrier)))


def conclude_run(computed: Outcome, final: FinalState | int, *, impacts: int, max_impacts: int,
                 t_end: float, excitation_end: float, energy_fraction: float
                 ) -> tuple[Outcome, str]:
    """The verdict of a compiled run, with its reason, from how it ended: the one rule of
    `simulate` and of the batches (`archquake.domains.evaluate_pulses`).

    A run that ended at rest with ``impacts >= max_impacts`` was locked by the cap, not by the
    rest criterion, and counts as ``stalled``; the last impact's ``energy_fraction`` (of the
    least crest barrier, NaN where the proof does not apply: `last_impact_fraction`)
    proves survival when below ``1 - ENERGY_MARGIN``; then
    `archquake.outcome.conclude`. Apply `qualify` to the result.

    Parameters
    ----------
    computed : Outcome
        The kernel's outcome (no_hinging, survives, collapse).
    final : FinalState or int
        How the run ended (or the kernel's ``FINAL_*`` code).
    impacts : int
        Impacts the run had (counted past the cap), and ``max_impacts`` its cap.
    t_end, excitation_end : float
        End of the run and of the excitation, s.
    energy_fraction : float
        As above (NaN: no proof).

    Examples
    --------
    >>> conclude_run(Outcome.SURVIVES, FinalState.REST, impacts=3, max_impacts=3, t_end=9.0,
    ...              excitation_end=0.6, energy_fraction=math.nan)[0].value
    'indeterminate'
    >>> conclude_run(Outcome.SURVIVES, FinalState.REST, impacts=2, max_impacts=3, t_end=9.0,
    ...              excitation_end=0.6, energy_fraction=math.nan)[0].value
    'survives'
    """
    state = final if isinstance(final, FinalState) else _FINALS[int(final)]
    if state is FinalState.REST and impacts >= max_impacts:
        state = FinalState.STALLED  # locked by max_impacts, not by the rest criterion
    proof = math.isfinite(energy_fraction)
    return conclude(Outcome(computed), final_state=state.value, t_end_s=float(t_end),
                    excitation_end_s=float(excitation_end),
                    below_barrier=proof and energy_fraction < 1.0 - K.ENERGY_MARGIN,
                    energy_fraction=float(energy_fraction) if proof else None)


def simulate(
    arch: Arch | HingeMechanism | PreparedMechanism,
    motion: GroundMotion,
    *,
    restitution: float | None = None,
    impact: str | None = None,
    t_end: float | None = None,
    initial_rate: float = 0.0,
    options: SolverOptions = SolverOptions(),
    t_eval=None,
    g: float = STANDARD_GRAVITY,
) -> SimulationResult:
    """Time history of the arch under a ground motion (paper Eqs. 2-7).

    Parameters
    ----------
    arch : Arch, HingeMechanism or PreparedMechanism
        The arch (hinges from the equivalent static analysis) or a given mechanism.
    motion : GroundMotion
        Any archquake ground motion (step impulse, sine pulse, record).
    restitution : float, optional
        Prescribed c_v in [0, 1] instead of the impact law's (the paper allows either; 0 is
        perfectly plastic); outside it is refused. It replaces the energy, not the mechanism:
        the post-impact mechanism is still the law's, with c_v^2 of the kinetic energy before
        the impact (for the mirror image, the rate is c_v times the closing rate).
    impact : {"paper", "chain", "mirror"}, optional
        Impact law (`archquake.mechanism.impact`): "paper" (Eq. 4), "chain" (the chain
        law, `archquake.mechanism.impact_chain`, followed over its reachable set of
        mechanisms; see ``SimulationResult.mechanisms``) or "mirror". None: a
        PreparedMechanism's own law, else `DEFAULT_IMPACT_LAW`.
    t_end : float, optional
        End of the analysis, s. Default: the end of the excitation plus 60 sqrt(R/g).
    initial_rate : float, optional
        If > 0, the first mechanism starts open at t = 0 with this opening rate phi-dot, rad/s
        (free rocking; with a zero ground motion this is the paper's free vibration).
    options : SolverOptions
    t_eval : sequence of float, optional
        Times, s (>= 0, non-decreasing), at which to report the exact state in
        `SimulationResult.evaluated`: each is reached by one Dormand-Prince step of the
        integrator landing on it from its last accepted step (as accurate as the steps
        themselves, unlike the interpolated ``history``); the steps, events and outcome are
        those of the run without ``t_eval``. At an impact the state is the closing one; at the
        onset of hinging the opening one. Times after a collapse or beyond ``t_end`` are left
        out.
    g : float
        Gravity, m/s^2.

    Returns
    -------
    SimulationResult

    Examples
    --------
    Oppenheim's arch under the paper's step impulse a = 1.0 g, t_p = 0.27 s (Figure 4c):

    >>> import math
    >>> from archquake import Arch
    >>> from archquake.ground import StepImpulse
    >>> arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    >>> r = simulate(arch, StepImpulse.from_g(1.0, 0.27))
    >>> r.outcome.value, r.collapse_half_cycle, round(float(r.impact_times[0]), 2)
    ('collapse', 2, 0.86)
    """
    prepared = PreparedMechanism.build(arch, impact)
    require_gravity(g)
    require_instance("options", options, SolverOptions, "a SolverOptions")
    model_cv = prepared.impact.restitution_cv
    cv = prepared.restitution_for(restitution)
    table = prepared.kernel_table(check_restitution(restitution))
    initial_rate = require_finite("initial_rate", initial_rate, "rad/s")
    if initial_rate < 0:
        raise InvalidParameterError(f"initial_rate must be >= 0 rad/s, got {initial_rate:g}")
    if t_eval is None:
        requested = np.empty(0)
    else:
        requested = np.ascontiguousarray(require_array("t_eval", t_eval, "s", minimum=0.0))
        if np.any(np.diff(requested) < 0):
            raise InvalidParameterError("t_eval must be sorted (non-decreasing times, s)")
    check_motion(motion)
    kind, params = motion.kernel_spec()
    params = np.ascontiguousarray(params, dtype=np.float64)
    mech = prepared.mechanism
    tau = math.sqrt(mech.arch.radius / g)
    check_time_resolution(kind, params, tau)
    check_lift_off(kind, params, g)
    excitation = float(K.excitation_end(kind, params))
    if t_end is None:
        t_end = float(default_t_end(excitation, mech.arch.radius, g))
    require_positive("t_end", t_end, "s")
    dt_out = options.output_interval if options.output_interval is not None else tau / 200.0
    n_imp_cap = int(options.max_impacts)
    # history: sized by what happens, not by t_end. While locked during the
    # excitation at most LOCKED_SAMPLES samples (then each stretch's end), none after it; while
    # moving one per dt_out. The buffer starts small; a run that wants more samples is rerun
    # with the exact size (deterministic: the same steps), up to MAX_HISTORY_SAMPLES.
    dt_lock = max(dt_out, excitation / LOCKED_SAMPLES) if dt_out > 0 else dt_out
    if dt_out > 0:
        cap = min(int(min(t_end / dt_out, 1e18)) + 2 * n_imp_cap + 16,
                  INITIAL_HISTORY_SAMPLES + int(min(excitation / dt_lock, 1e18)) + 2)
    elif dt_out < 0:
        cap = INITIAL_HISTORY_SAMPLES
    else:
        cap = 1
    tail, v_toggle = _record_tail(prepared, kind, params)
    table = table._replace(v_toggle=v_toggle)
    exc = K.excitation(kind, params, tail)
    run = options.kernel_settings(g, float(t_end), dt_out=float(dt_out), dt_lock=float(dt_lock),
                                  hist_limit=MAX_HISTORY_SAMPLES,
                                  initial_rate=float(initial_rate))
    reruns = 0
    while True:
        hist = np.zeros((cap, K.HIST_COLUMNS))
        impacts = np.zeros((n_imp_cap, K.IMPACT_COLUMNS))
        peaks = np.zeros(n_imp_cap + 1)
        counters = np.zeros(10)
        onsets = np.zeros((n_imp_cap + 1, 2))
        eval_out = np.zeros((requested.size, K.HIST_COLUMNS))
        outcome, final, collapse_half, n_eval = K.simulate_kernel_eval(
            table, exc, run, K.Output(hist, impacts, peaks, counters, onsets),
            K.Requested(requested, eval_out))
        if counters[8]:
            raise InvalidParameterError(
                f"the history would hold more than {MAX_HISTORY_SAMPLES:,} samples "
                f"({MAX_HISTORY_SAMPLES * 40 / 1e9:.1f} GB): the arch moves for longer than "
                f"{MAX_HISTORY_SAMPLES:,} output intervals; raise output_interval "
                f"(now {dt_out:g} s), shorten t_end (now {t_end:g} s), or set "
                f"output_interval=0 for no history")
        if int(counters[0]) <= cap:
            break
        cap = int(counters[0])
        reruns += 1
    n_hist, n_imp, n_half = int(counters[0]), int(counters[1]), int(counters[2])
    n_imp = min(n_imp, n_imp_cap)
    history = None
    if dt_out != 0:
        h = hist[:n_hist]
        history = History(h[:, 0].copy(), h[:, 1].copy(), h[:, 2].copy(), h[:, 3].copy(),
                          h[:, 4].copy(), mechanism_row=h[:, 5].astype(int))
    evaluated = None
    if t_eval is not None:
        e = eval_out[:int(n_eval)]
        evaluated = History(requested[:int(n_eval)].copy(), e[:, 0].copy(), e[:, 1].copy(),
                            e[:, 3].astype(int), e[:, 4].copy(), phi_ddot=e[:, 2].copy(),
                            mechanism_row=e[:, 5].astype(int))
    onset = counters[6]
    ctime = counters[7]
    computed = _OUTCOMES[int(outcome)]
    n_on = min(int(counters[9]), onsets.shape[0])
    events = mechanism_events(prepared, impacts[:n_imp], onsets[:n_on],
                              check_restitution(restitution))
    # every recorded impact precedes the verdict (a collapse ends the run)
    impact_events = [e for e in events if e.kind != "onset"]
    described = (all(e.described for e in impact_events) if impact_events
                 else prepared.describes_impact(restitution))
    final_state = _FINALS[int(final)]
    n_all = int(counters[1])
    fraction = last_impact_fraction(table, impacts, n_all, excitation, g)
    settled, reason = conclude_run(computed, final_state, impacts=n_all, max_impacts=n_imp_cap,
                                   t_end=float(t_end), excitation_end=excitation,
                                   energy_fraction=fraction)
    verdict = qualify(settled, collapse_half_cycle=int(collapse_half), impacts=n_imp,
                      impact_described=described)
    if verdict is not settled:
        reason = ("the verdict depends on an impact its law does not describe "
                  f"(see impact, restitution); as computed: {reason}")
    return SimulationResult(
        outcome=verdict,
        verdict_reason=reason,
        mechanisms=events,
        computed_outcome=computed,
        impact_described=described,
        restitution_prescribed=restitution is not None,
        final_state=final_state,
        collapse_half_cycle=int(collapse_half) if computed is Outcome.COLLAPSE else None,
        collapse_time=float(ctime) if math.isfinite(ctime) else None,
        onset_time=float(onset) if math.isfinite(onset) else None,
        impact_times=impacts[:n_imp, 0].copy(),
        impact_rates=impacts[:n_imp, 1:3].copy(),
        peak_rotation=peaks[:n_half].copy(),
        restitution_cv=float(cv),
        restitution_ct=float(cv) ** 2,
        energy_gain=bool(float(cv) ** 2 > 1.0),
        impact_model_cv=float(model_cv),
        impact_admissible=bool(model_cv >= 0.0),
        impact_law=prepared.impact.law,
        impact_validity=prepared.impact.validity,
        impact_followed=prepared.follows_law,
        mechanism=mech,
        collapse_acceleration_g=prepared.collapse_acceleration_g,
        critical_rotation=prepared.critical_rotation,
        toggle_rotation=prepared.toggle_rotation,
        g=g,
        history=history,
        stats={"steps": int(counters[3]), "rejected": int(counters[4]),
               "rhs_evaluations": int(counters[5]), "t_end": float(t_end),
               # the history outgrew its first buffer and the run was repeated at its size
               **({"history_reruns": reruns} if reruns else {})},
        evaluated=evaluated,
    )


__all__ = ["RUN_TAIL", "FinalState", "History", "MechanismEvent", "Outcome", "SimulationResult",
           "SolverOptions", "conclude_run", "default_t_end", "last_impact_fraction",
           "mechanism_events", "simulate"]
