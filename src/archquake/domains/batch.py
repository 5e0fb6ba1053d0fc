"""Outcomes of many pulses of one family on one arch: the fast path of the domain search.

`evaluate_pulses` runs every (magnitude, duration) pair through one call of the compiled
batch kernel (`archquake.domains._kernels`), which runs the same compiled time history as
`archquake.mechanism.simulate` for each case; `evaluate_pulses_scalar` is its plain
twin, a Python loop over `simulate`, which the tests hold it to.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from archquake._validate import require_gravity
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.ground.base import check_time_resolution
from archquake.ground.pulses import PulseFamily
from archquake.mechanism.impact import check_restitution
from archquake.mechanism.prepared import PreparedMechanism
from archquake.mechanism.simulate import SolverOptions, conclude_run, simulate
from archquake.outcome import Outcome, qualify

#: Integrator settings of `simulate`'s default.
DEFAULT_OPTIONS = SolverOptions()

@dataclass(frozen=True)
class PulseOutcomes:
    """Outcomes of a set of pulses, shape (n,) each: what any model plugged into the domain
    search returns (`failure_domain`'s ``evaluate``).

    Attributes
    ----------
    magnitude_g : ndarray, g
    duration : ndarray, s
    outcome : ndarray of Outcome (object)
        Built from `Outcome` values (or their strings); the verdict
        as it may be stated (``indeterminate`` where it depends on an impact the law does not
        describe, `archquake.outcome.qualify`).
    collapse_half_cycle : ndarray of int
        Half cycle of the computed collapse (1 = before any impact), 0 where none (also set
        where the verdict is indeterminate: the law as stated computed that collapse).
    runs : ndarray of int
        Model runs each case needed (the batch kernel's early decision, see `._kernels`).
    """

    magnitude_g: np.ndarray
    duration: np.ndarray
    outcome: np.ndarray
    collapse_half_cycle: np.ndarray
    runs: np.ndarray

    def __post_init__(self) -> None:
        codes = np.empty(len(self.outcome), dtype=object)
        for i, o in enumerate(self.outcome):
            codes[i] = Outcome(o)
        object.__setattr__(self, "outcome", codes)

    @property
    def collapses(self) -> np.ndarray:
        """(n,) bool: the model, with its impact law as stated, computes a collapse (a certain
        collapse, or an indeterminate verdict whose computation collapsed: the domain search
        brackets the law's boundary and marks what is not certain, see
        `collapse_verdict`)."""
        return np.array([o is Outcome.COLLAPSE or (o is Outcome.INDETERMINATE and h > 0)
                         for o, h in zip(self.outcome, self.collapse_half_cycle)], dtype=bool)

    @property
    def indeterminate(self) -> np.ndarray:
        """(n,) bool: the verdict depends on an impact the law does not describe."""
        return np.array([o is Outcome.INDETERMINATE for o in self.outcome], dtype=bool)

    @property
    def collapses_first(self) -> np.ndarray:
        """(n,) bool: the pulse collapses the arch in the first half cycle."""
        return self.collapses & (self.collapse_half_cycle == 1)


def _pairs(magnitudes_g, durations) -> tuple[np.ndarray, np.ndarray]:
    a = np.atleast_1d(np.asarray(magnitudes_g, dtype=float))
    d = np.atleast_1d(np.asarray(durations, dtype=float))
    a, d = np.broadcast_arrays(a, d)
    if a.ndim != 1:
        raise InvalidParameterError("magnitudes and durations must be 1-D (or scalars)")
    if np.any(~np.isfinite(a)) or np.any(a < 0):
        raise InvalidParameterError("magnitudes must be finite and >= 0 g")
    if np.any(~np.isfinite(d)) or np.any(d <= 0):
        raise InvalidParameterError("durations must be finite and > 0 s")
    return a.copy(), d.copy()


def check_durations(family: PulseFamily, durations: np.ndarray, arch_radius: float,
                    g: float) -> None:
    """Refuse durations below the integrators' time resolution
    (`archquake.ground.base.check_time_resolution`, one error naming t_p or T)."""
    tau = math.sqrt(arch_radius / g)
    for d in np.unique(np.asarray(durations, dtype=float)):
        check_time_resolution(family.kind, np.array([1.0, float(d), -1.0]), tau)


def evaluate_pulses(
    arch: Arch | PreparedMechanism,
    family: PulseFamily | str,
    magnitudes_g,
    durations,
    *,
    restitution: float | None = None,
    impact: str | None = None,
    options: SolverOptions = DEFAULT_OPTIONS,
    early: bool = True,
    g: float = STANDARD_GRAVITY,
) -> PulseOutcomes:
    """Outcome of each pulse ``(magnitudes_g[i], durations[i])`` (broadcast), in one compiled call.

    Parameters
    ----------
    arch : Arch or PreparedMechanism
    family : PulseFamily or {'step', 'sine'}
    magnitudes_g : array_like, (n,), g
    durations : array_like, (n,), s (t_p for the step impulse, T for the sine pulse)
    restitution : float, optional
        Prescribed c_v in [0, 1]; None: the impact law's.
    impact : {"paper", "chain", "mirror"}, optional
        Impact law; None: a PreparedMechanism's own, else "paper".
    options : SolverOptions
        Tolerances, rest rotation and impact cap, as for `simulate`.
    early : bool
        Stop a surviving case as soon as energy proves it can no longer collapse (see
        `archquake.domains._kernels`); False runs every case to rest as ``simulate`` does.
    g : float
        Gravity, m/s^2.

    Returns
    -------
    PulseOutcomes

    Examples
    --------
    The three pulses of the paper's Figure 4 (a = 1.0 g):

    >>> import math
    >>> from archquake import Arch
    >>> r = evaluate_pulses(Arch(10, 1.5, math.radians(157.5), 7), "step", 1.0, [0.44, 0.27, 0.20])
    >>> [int(h) for h in r.collapse_half_cycle], [o.value for o in r.outcome]
    ([1, 2, 0], ['collapse', 'collapse', 'survives'])
    """
    from archquake.domains._kernels import batch_kernel, decode
    from archquake.ranges import default_t_end

    prepared = PreparedMechanism.build(arch, impact)
    table = prepared.kernel_table(check_restitution(restitution))
    fam = PulseFamily.parse(family)
    require_gravity(g)
    a, d = _pairs(magnitudes_g, durations)
    check_durations(fam, d, prepared.mechanism.arch.radius, g)
    n = a.shape[0]
    params = np.empty((n, 3))
    params[:, 0] = a * g
    params[:, 1] = d
    params[:, 2] = -1.0
    t_exc = 3.0 * d if fam is PulseFamily.STEP else d
    t_end = default_t_end(t_exc, prepared.mechanism.arch.radius, g)
    decided = batch_kernel(table, fam.kind, params, options.kernel_settings(g), t_end,
                           bool(early))
    outcome, half, n_imp, runs, _peak, unseen, final, fraction = decided
    verdict = np.empty(n, dtype=object)
    for i, o in enumerate(decode(outcome)):
        # how the run ended (locked by max_impacts, cut by t_end): simulate's own rule
        settled, _reason = conclude_run(o, int(final[i]), impacts=int(n_imp[i]),
                                        max_impacts=int(options.max_impacts),
                                        t_end=float(t_end[i]), excitation_end=float(t_exc[i]),
                                        energy_fraction=float(fraction[i]))
        # per impact: the verdict depends on the impacts before it (all those recorded)
        verdict[i] = qualify(settled, collapse_half_cycle=int(half[i]),
                             impacts=min(int(n_imp[i]), int(options.max_impacts)),
                             impact_described=not bool(unseen[i]))
    return PulseOutcomes(a, d, verdict, half, runs)


def evaluate_pulses_scalar(
    arch: Arch | PreparedMechanism,
    family: PulseFamily | str,
    magnitudes_g,
    durations,
    *,
    restitution: float | None = None,
    impact: str | None = None,
    options: SolverOptions = DEFAULT_OPTIONS,
    g: float = STANDARD_GRAVITY,
) -> PulseOutcomes:
    """The plain twin of `evaluate_pulses`: a loop over `simulate`."""
    prepared = PreparedMechanism.build(arch, impact)
    fam = PulseFamily.parse(family)
    a, d = _pairs(magnitudes_g, durations)
    outcome = np.empty(a.shape[0], dtype=object)
    half = np.zeros(a.shape[0], dtype=np.int64)
    opts = SolverOptions(options.rtol, options.atol, options.rest_rotation, options.max_impacts, 0.0)
    for i, (ai, di) in enumerate(zip(a, d)):
        r = simulate(prepared, fam.motion(float(ai), float(di), g=g), restitution=restitution,
                     options=opts, g=g)
        outcome[i] = r.outcome
        half[i] = r.collapse_half_cycle or 0
    return PulseOutcomes(a, d, outcome, half, np.ones(a.shape[0], dtype=np.int64))


__all__ = ["PulseOutcomes", "evaluate_pulses", "evaluate_pulses_scalar"]
