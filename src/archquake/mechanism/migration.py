"""A reference time integrator of the rocking arch whose hinges move.

Readable, not fast (scipy ``solve_ivp``, like :mod:`archquake.mechanism.reference`). Between
events the arch moves on one four-hinge mechanism by its own Eq. 2 (the packed mechanism's
:func:`~archquake.mechanism.kinematics.acceleration`; a mechanism opened by a load towards -x is
carried as the mirror of its packed form, ``side = -1``, exactly as the fixed-hinge model carries
its mirror). The state is (mechanism, its own phi, phi_dot). Events:

* **Onset** (from rest, when a ground acceleration exceeds the static collapse acceleration of
  the limit-analysis mechanism): the starting mechanism is chosen by Gauss's principle, the
  acceleration counterpart of the impact law: of the four-hinge mechanisms, the one whose
  generalised force squared over generalised mass ``Q_R^2 / m_R`` is largest *and* whose joint
  forces are admissible (:mod:`archquake.mechanism.admissibility`). At a ground acceleration
  just above lambda it is the limit-analysis mechanism; above it, it need not be.
* **Closing impact** (phi -> 0 while closing): the chain impact law
  (:func:`archquake.mechanism.impact_chain.chain_impact`) chooses the post-impact mechanism and
  its rate (its generalised momentum is conserved).
* **Migration**: a locked joint's line of thrust reaches an edge of its section (the thrust
  margin of :func:`~archquake.mechanism.admissibility.admissibility` crosses zero). A hinge opens
  there, on that face. The arch continues on a four-hinge mechanism Q that contains the new
  hinge, chosen by the impact law's principle: the velocity field v of the current mechanism is
  projected (kinetic-energy metric) on each candidate's field, its generalised momentum is
  conserved, ``s = <u_Q, v>_M / <u_Q, u_Q>_M``, and of the candidates whose new state is
  admissible the one that keeps most kinetic energy is taken. One of the old hinges is not in
  Q: its joint has to close, and the energy the projection removes,
  ``T (1 - <u_Q, v>^2 / (<u_Q,u_Q> <v,v>))``, is that closure's plastic impact.

**The approximation at a migration.** The mechanisms share the voussoirs' rigid motions only
at phi = 0. Away from it the current configuration (P at phi_P) is not a configuration of Q;
the exact continuation is a transient two-degree-of-freedom motion in which the dropped hinge
closes. Here the arch jumps to Q at the rotation phi_Q of *equal potential energy*
(``V_Q(phi_Q) = V_P(phi_P)``), so that the only energy change at a migration is the
projection's loss, and the velocity fields u_P(phi_P), u_Q(phi_Q) are those of the displaced
configurations (finite differences of :func:`~archquake.mechanism.configuration.displaced_arch`).
The jump of the voussoirs' positions is measured and returned with every migration
(:attr:`Switch.position_jump_m`).

Energy between events is conserved in free motion (the integrator's tolerance), mirror
symmetry and dynamic similarity hold (tests/mechanism/test_migration.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.arch import Arch
from archquake.geometry.hinges import Face, HingeMechanism
from archquake.mechanism.admissibility import DEFAULT_FRICTION, state_margins
from archquake.mechanism.configuration import displaced_arch
from archquake.mechanism.kinematics import acceleration, eom_terms, potential
from archquake.mechanism.prepared import PreparedMechanism, hinges_of

#: Candidates (ranked by the generalised momentum at phi = 0) examined in full at a migration.
CANDIDATES = 16
#: A new mechanism's state counts as admissible when its least thrust margin is above -this.
ADMISSIBLE_TOL = 1e-9
#: Finite-difference step of the displaced velocity fields, rad.
FIELD_STEP = 1e-6


def label(joints, faces) -> str:
    """'0i 3e 5i 7e' for hinges at joints with faces."""
    return " ".join(f"{int(j)}{('e' if (f is Face.EXTRADOS or f == 1 or f == 'extrados') else 'i')}"
                    for j, f in zip(joints, faces))


# ----------------------------------------------------------------------------- mechanisms
@dataclass(frozen=True)
class Mechanism:
    """One four-hinge mechanism of the arch, in its real orientation, with its packed form.

    ``prepared`` packs the mechanism or its mirror image (the packed one is always opened by a
    ground acceleration towards -x); ``side`` says which (+1 itself, -1 the mirror of the
    packed one), so that Eq. 2 is ``acceleration(packed, phi, phi_dot, side * x_g'')``.
    """

    hinges: HingeMechanism
    prepared: PreparedMechanism = field(repr=False)
    side: int

    @property
    def key(self) -> tuple:
        return (self.hinges.joints, self.hinges.faces)

    @property
    def label(self) -> str:
        return label(self.hinges.joints, self.hinges.faces)

    @property
    def packed(self) -> np.ndarray:
        return self.prepared.packed

    def energy(self, phi: float, phi_dot: float, g: float) -> float:
        """Kinetic + gravitational energy relative to phi = 0 (ground frame), J."""
        meff = eom_terms(self.packed, phi)[1]
        return 0.5 * meff * phi_dot**2 + g * potential(self.packed, phi)

    def positions(self, phi: float) -> np.ndarray:
        """Centroid displacements and rotations of every voussoir, (n, 3)."""
        return displaced_arch(self.prepared, max(phi, 0.0), self.side).positions

    def field(self, phi: float) -> np.ndarray:
        """Velocity field per unit phi-dot at phi: (n, 3) d(positions)/d phi."""
        h = FIELD_STEP
        if phi > h:
            return (self.positions(phi + h) - self.positions(phi - h)) / (2 * h)
        p0, p1, p2 = self.positions(phi), self.positions(phi + h), self.positions(phi + 2 * h)
        return (-3 * p0 + 4 * p1 - p2) / (2 * h)


class MechanismCache:
    """Every mechanism of one arch that a history visits, prepared once."""

    def __init__(self, arch: Arch):
        self.arch = arch
        self._cache: dict = {}
        m = arch.voussoir_masses
        self.metric = np.column_stack([m, m, arch.voussoir_inertias])  # (n, 3)

    def get(self, hinges: HingeMechanism) -> Mechanism:
        key = (hinges.joints, hinges.faces)
        if key not in self._cache:
            prep = PreparedMechanism.build(hinges)
            same = prep.mechanism.joints == hinges.joints and prep.mechanism.faces == hinges.faces
            self._cache[key] = Mechanism(hinges, prep, 1 if same else -1)
        return self._cache[key]

    def of(self, joints, faces) -> Mechanism:
        faces = tuple(Face.EXTRADOS if int(f) else Face.INTRADOS for f in faces) \
            if not isinstance(faces[0], Face) else tuple(faces)
        a, b, c, d = (int(j) for j in joints)
        return self.get(HingeMechanism(self.arch, (a, b, c, d), faces))

    def inner(self, a: np.ndarray, b: np.ndarray) -> float:
        """<a, b>_M over the voussoirs' (vx, vy, w)."""
        return float(np.sum(self.metric * a * b))


# ----------------------------------------------------------------------------- the result
@dataclass(frozen=True)
class Switch:
    """One event at which the mechanism changes (or stops).

    Attributes
    ----------
    t : float
        s.
    kind : str
        'onset', 'impact', 'migration' or 'rest'.
    before, after : str
        Hinges before and after ('-' locked).
    energy_before, energy_after : float
        Kinetic + potential energy relative to the undisplaced arch, J.
    position_jump_m : float
        Largest displacement of a voussoir centroid caused by re-expressing the configuration in
        the new mechanism's phi (0 at impacts and onsets, where phi = 0), m.
    joint : int or None
        The joint whose thrust reached an edge (migration).
    admissible : bool
        False if no candidate's state was admissible (the best one was taken anyway).
    kept : float
        Kinetic energy kept by the switch's projection (c_T), 1 for an onset.
    """

    t: float
    kind: str
    before: str
    after: str
    energy_before: float
    energy_after: float
    position_jump_m: float = 0.0
    joint: int | None = None
    admissible: bool = True
    kept: float = 1.0

    def to_dict(self) -> dict:
        return {"t_s": self.t, "kind": self.kind, "before": self.before, "after": self.after,
                "energy_before_J": self.energy_before, "energy_after_J": self.energy_after,
                "position_jump_m": self.position_jump_m, "joint": self.joint,
                "admissible": self.admissible, "kept": self.kept}


@dataclass(frozen=True)
class MigrationResult:
    """A time history of the migrating model.

    Attributes
    ----------
    outcome : str
        'no_hinging', 'survives', 'collapse'.
    collapse_time : float or None
    switches : tuple of Switch
        Every onset, impact, migration and rest, in order.
    segments : tuple of (t0, t1, E0, E1, label)
        Every stretch between events with the energy at its ends (J): conserved in free motion.
    t, energy : ndarray
        Sampled energy history (kinetic + potential, J, relative to the undisplaced arch).
    signed_phi : ndarray
        phi of the open mechanism times its ``side`` (0 while locked), for plots.
    outside : tuple of (t, hinges, joints)
        Instants where a locked joint's thrust left the section and no four-hinge mechanism
        containing the new hinge had an admissible state: the arch needs more hinges than four
        there (a two-degree-of-freedom motion); the model keeps the current mechanism and watches
        those joints until their thrust is back inside.
    """

    outcome: str
    collapse_time: float | None
    switches: tuple
    segments: tuple = field(repr=False)
    t: np.ndarray = field(repr=False)
    energy: np.ndarray = field(repr=False)
    signed_phi: np.ndarray = field(repr=False)
    outside: tuple = ()

    @property
    def impacts(self) -> list[Switch]:
        return [s for s in self.switches if s.kind == "impact"]

    @property
    def hinge_sequence(self) -> list[tuple[float, str, str]]:
        """(time s, event kind, hinges after)."""
        return [(s.t, s.kind, s.after) for s in self.switches]

    def energy_at(self, t: float) -> float:
        return float(np.interp(t, self.t, self.energy))

    def to_dict(self) -> dict:
        return {"outcome": self.outcome, "collapse_time_s": self.collapse_time,
                "switches": [s.to_dict() for s in self.switches]}


# ----------------------------------------------------------------------------- choices
def _generalised(arch: Arch, cache: MechanismCache, field_v: np.ndarray):
    """Generalised momentum (or force) of a field (n, 3), per unit rate of every mechanism of
    the arch, and their generalised masses (the impact law's prefix sums, at phi = 0)."""
    from archquake.mechanism.impact_chain import _mechanisms, generalised_momenta

    mechs, meff = _mechanisms(arch)
    p = generalised_momenta(arch, mechs, field_v[:, :2], field_v[:, 2])
    return mechs, p, meff


def choose_onset(cache: MechanismCache, ground: float, *, mu: float = DEFAULT_FRICTION,
                 g: float = STANDARD_GRAVITY) -> Mechanism:
    """The mechanism that starts from rest under the ground acceleration ``ground`` (m/s^2):
    Gauss's principle over the four-hinge mechanisms (largest Q^2 / m among those with Q > 0,
    Q the generalised force of gravity and the ground's inertia), the first whose state is
    admissible; the limit-analysis mechanism if none of the first :data:`CANDIDATES` is."""
    arch = cache.arch
    n = arch.voussoirs
    free = np.zeros((n, 3))
    free[:, 0], free[:, 1] = -ground, -g  # free acceleration of every voussoir
    mechs, q, meff = _generalised(arch, cache, free)
    score = np.where(q > 0, q * q / meff, -np.inf)
    for i in np.argsort(-score)[:CANDIDATES]:
        if not np.isfinite(score[i]):
            break
        mech = cache.get(mechs.mechanism(int(i), arch))
        adm = state_margins(mech.prepared, 0.0, 0.0, 0.0, mech.side, ground, mu=mu, g=g)
        if adm.thrust >= -ADMISSIBLE_TOL:
            return mech
    la = hinges_of(arch)
    return cache.get(la if ground < 0 else la.mirrored())


def _phi_of_potential(mech: Mechanism, target: float) -> tuple[float, bool]:
    """phi in [0, crest] with potential equal to ``target`` (kg m); (crest, False) if above it."""
    crit = mech.prepared.critical_rotation
    if target <= 0.0:
        return 0.0, True
    top = potential(mech.packed, crit)
    if target >= top:
        return crit, False
    return brentq(lambda p: potential(mech.packed, p) - target, 0.0, crit, xtol=1e-14), True


def _phi_of_position(mech: Mechanism, pos: np.ndarray, cache: MechanismCache) -> float:
    """phi of ``mech`` whose voussoir positions are nearest ``pos`` (kinetic metric)."""
    from scipy.optimize import minimize_scalar

    top = 0.9 * min(mech.prepared.toggle_rotation, math.pi / 2)

    def dist(p):
        d = mech.positions(p) - pos
        return cache.inner(d, d)

    res = minimize_scalar(dist, bounds=(0.0, top), method="bounded",
                          options={"xatol": 1e-10})
    return float(res.x) if dist(res.x) < dist(0.0) else 0.0


def choose_migration(cache: MechanismCache, current: Mechanism, phi: float, phi_dot: float,
                     joint: int, face: Face, ground: float, t: float, *,
                     mu: float = DEFAULT_FRICTION, g: float = STANDARD_GRAVITY,
                     reexpress: str = "potential"):
    """The mechanism after a hinge opens at ``joint`` on ``face`` (module docstring).

    Returns (mechanism, phi, phi_dot, kept, position jump m, admissible); when no candidate is
    reachable, the current state with ``admissible`` False."""
    arch = cache.arch
    u_p = current.field(phi)
    v = phi_dot * u_p
    vv = cache.inner(v, v)
    mechs, p, meff = _generalised(arch, cache, v)
    fcode = 1 if face is Face.EXTRADOS else 0
    has = np.any((mechs.joints == joint) & (mechs.faces == fcode), axis=1)
    rank = np.where(has, p * p / meff, -np.inf)
    pos_p = current.positions(phi)
    v_target = potential(current.packed, phi)
    best = None
    for i in np.argsort(-rank)[:CANDIDATES]:
        if not np.isfinite(rank[i]):
            break
        hm = mechs.mechanism(int(i), arch)
        if hm.joints == current.hinges.joints and hm.faces == current.hinges.faces:
            continue
        try:
            q = cache.get(hm)
        except (InvalidParameterError, SolverError):
            continue
        try:
            if reexpress == "potential":
                phi_q, reach = _phi_of_potential(q, v_target)
                if not reach:  # the configuration's potential is beyond Q's crest
                    continue
            else:
                phi_q = _phi_of_position(q, pos_p, cache)
            if phi_q + 2 * FIELD_STEP >= q.prepared.toggle_rotation:
                continue
            u_q = q.field(phi_q)
            uu = cache.inner(u_q, u_q)
            s = cache.inner(u_q, v) / uu
            if phi_q <= 0.0 and s <= 0.0:
                continue
            kept = s * s * uu / vv if vv > 0 else 0.0
            jump = float(np.max(np.hypot(*(q.positions(phi_q)[:, :2] - pos_p[:, :2]).T)))
            adm = state_margins(q.prepared, t, phi_q, s, q.side, ground, mu=mu, g=g)
        except SolverError:
            continue
        ok = adm.thrust >= -ADMISSIBLE_TOL
        cand = (ok, kept, q, phi_q, s, jump)
        if best is None or (cand[0], cand[1]) > (best[0], best[1]):
            best = cand
    if best is None:  # no candidate can be reached from here: keep the current mechanism
        return current, phi, phi_dot, 1.0, 0.0, False
    ok, kept, q, phi_q, s, jump = best
    return q, phi_q, s, kept, jump, ok


# ----------------------------------------------------------------------------- integrator
class Excitation(Protocol):
    """What the integrator reads of a ground motion (any :class:`GroundMotion` has it)."""

    @property
    def duration(self) -> float: ...

    def acceleration(self, t): ...

    def breakpoints(self) -> np.ndarray: ...


def _event(fn, direction: int) -> None:
    """Mark ``fn`` as a terminal solve_ivp event crossing zero in ``direction``."""
    setattr(fn, "terminal", True)  # noqa: B010 (solve_ivp reads these attributes)
    setattr(fn, "direction", direction)  # noqa: B010


def _pieces(motion: Excitation | None, t_end: float) -> list[float]:
    if motion is None:
        return [0.0, t_end]
    from archquake.mechanism.reference import _pieces as pieces

    return pieces(motion, t_end)  # type: ignore[arg-type]


def simulate_migrating(
    arch: Arch,
    motion: Excitation | None,
    *,
    t_end: float | None = None,
    stop_after_impacts: int | None = None,
    initial: tuple[HingeMechanism, float] | None = None,
    mu: float = DEFAULT_FRICTION,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_switches: int = 200,
    retry: float = 0.01,
    reexpress: str = "potential",
    samples_per_segment: int = 50,
    g: float = STANDARD_GRAVITY,
) -> MigrationResult:
    """Time history of the arch with migrating hinges (module docstring).

    Parameters
    ----------
    arch : Arch
    motion : GroundMotion (or any Excitation) or None
        None: no ground motion (free rocking from ``initial``).
    t_end : float, optional
        s (default: the excitation's end + 60 sqrt(R/g)).
    stop_after_impacts : int, optional
        Stop just after this many closing impacts.
    initial : (HingeMechanism, rate rad/s), optional
        Start at t = 0 on that mechanism at phi = 0 opening at that rate (instead of from rest).
    mu : float
        Friction coefficient of the admissibility margins (reported; not an event).
    rtol, atol : float
        solve_ivp (DOP853) tolerances.
    reexpress : {'potential', 'position'}
        How a migration away from phi = 0 re-expresses the configuration in the new mechanism's
        own phi: equal potential energy (no energy change but the projection's; a candidate
        whose crest lies below the configuration's potential is not reachable and is skipped)
        or the nearest voussoir positions in the kinetic metric (the potential energy then
        jumps, and the jump is in ``Switch.energy_after``).
    retry : float
        While a locked joint's thrust is outside and no four-hinge continuation is admissible,
        the choice is tried again every ``retry`` sqrt(R/g) (dimensionless, so that the model
        stays dynamically similar).

    Returns
    -------
    MigrationResult
    """
    cache = MechanismCache(arch)
    tau = math.sqrt(arch.radius / g)
    t_exc = 0.0 if motion is None else float(motion.duration)
    t_end = t_exc + 60.0 * tau if t_end is None else float(t_end)
    bounds = _pieces(motion, t_end)
    la = PreparedMechanism.build(hinges_of(arch))
    lam = la.collapse_acceleration_g * g

    def ground(tt: float, right: float) -> float:
        if motion is None:
            return 0.0
        return float(motion.acceleration(min(tt, np.nextafter(right, -np.inf))))

    def piece_end(tt: float) -> float:
        for b in bounds:
            if b > tt + 1e-12 * (1 + tt):
                return b
        return t_end

    switches: list[Switch] = []
    segments: list = []
    ts: list[np.ndarray] = []
    es: list[np.ndarray] = []
    ps: list[np.ndarray] = []
    outcome, collapse_time = "no_hinging", None

    def find_onset(t0: float) -> float:
        for left, right in zip(bounds[:-1], bounds[1:]):
            if right <= t0 or left >= min(t_exc, t_end):
                continue
            grid = np.linspace(max(left, t0), right, 129)
            prev = grid[0]
            for tj in grid:
                if abs(ground(tj, right)) > lam:
                    if tj == grid[0]:
                        return float(tj)
                    lo, hi = prev, tj
                    for _ in range(80):
                        mid = 0.5 * (lo + hi)
                        if abs(ground(mid, right)) > lam:
                            hi = mid
                        else:
                            lo = mid
                    return float(hi)
                prev = tj
        return math.inf

    t = 0.0
    mech: Mechanism | None = None
    phi = v = 0.0
    if initial is not None:
        mech, phi, v = cache.get(initial[0]), 0.0, float(initial[1])
        outcome = "survives"
        switches.append(Switch(0.0, "onset", "-", mech.label, 0.0, mech.energy(0.0, v, g)))
    impacts = 0
    suppressed: set = set()
    outside_log: list = []
    loops = 0
    while t < t_end and len(switches) < max_switches and loops < 50 * max_switches:
        loops += 1
        if mech is None:
            t_on = find_onset(t)
            if not math.isfinite(t_on):
                break
            right = piece_end(t_on)
            xg = ground(t_on + 1e-12 * tau, right)
            mech, phi, v, t = choose_onset(cache, xg, mu=mu, g=g), 0.0, 0.0, t_on
            suppressed = set()
            outcome = "survives"
            switches.append(Switch(t, "onset", "-", mech.label, 0.0, 0.0))
            continue
        right = piece_end(t)
        over = t >= t_exc - 1e-12 * (1 + t_exc)
        m = mech
        crit, toggle = m.prepared.critical_rotation, m.prepared.toggle_rotation
        if over and phi >= crit and v >= 0:
            outcome, collapse_time = "collapse", t
            break

        def rhs(tt, y, m=m, right=right):
            return [y[1], acceleration(m.packed, y[0], y[1], m.side * ground(tt, right), g)]

        def closure(tt, y):
            return y[0]

        _event(closure, -1)

        def margins(tt, y, m=m, right=right):
            return state_margins(m.prepared, tt, max(y[0], 0.0), y[1], m.side, ground(tt, right),
                                 mu=mu, g=g).thrust_margin

        def exit_(tt, y, sup=frozenset(suppressed)):
            if y[0] < 0:
                return 1.0
            mm = margins(tt, y)
            if sup:
                mm = mm.copy()
                mm[list(sup)] = np.nan
            return float(np.nanmin(mm)) if np.any(np.isfinite(mm)) else 1.0

        _event(exit_, -1)

        def recover(tt, y, sup=frozenset(suppressed)):
            if not sup or y[0] < 0:
                return -1.0
            return float(np.min(margins(tt, y)[list(sup)]))

        _event(recover, 1)

        def crest(tt, y, over=over, crit=crit):
            return y[0] - crit if over else 1.0

        _event(crest, 1)

        def tog(tt, y, toggle=toggle):
            return y[0] - toggle * (1 - 1e-9)

        _event(tog, 1)
        # joints already outside at the start of a stretch cannot trigger the exit event; they
        # are watched by ``recover`` instead (the four-hinge model is outside its validity there)
        start = margins(t, [phi, v])
        newly = {int(k) for k in np.flatnonzero(start < -ADMISSIBLE_TOL)} - suppressed
        if newly:
            suppressed |= newly
            outside_log.append((t, m.label, sorted(newly)))
            continue
        if True:
            seg_end = min(right, t + retry * tau) if suppressed else right
            sol = solve_ivp(rhs, (t, seg_end), [phi, v], method="DOP853", rtol=rtol,
                            atol=[atol, atol / tau], events=[closure, exit_, crest, tog, recover],
                            dense_output=True)
            fired = [(ev[0], i) for i, ev in enumerate(sol.t_events) if len(ev) and ev[0] > t]
            if sol.status == 1 and fired:
                t_ev, which = min(fired)
                y_ev = sol.sol(t_ev)
            else:
                t_ev, which, y_ev = float(sol.t[-1]), -1, sol.y[:, -1]
            tt = np.linspace(t, t_ev, samples_per_segment)
            yy = sol.sol(tt)
            ts.append(tt)
            es.append(np.array([m.energy(max(a, 0.0), b, g) for a, b in yy.T]))
            ps.append(m.side * np.maximum(yy[0], 0.0))
            segments.append((t, float(t_ev), m.energy(phi, v, g), m.energy(max(float(y_ev[0]), 0.0),
                                                                         float(y_ev[1]), g), m.label))
        t = float(t_ev)
        phi, v = max(float(y_ev[0]), 0.0), float(y_ev[1])
        if which == -1:
            if suppressed and phi > 0:  # retry: is there an admissible four-hinge mechanism now?
                xg = ground(t, right)
                adm = state_margins(m.prepared, t, phi, v, m.side, xg, mu=mu, g=g)
                j = min(suppressed, key=lambda k: adm.thrust_margin[k])
                face = Face.EXTRADOS if adm.relative_eccentricity[j] > 0 else Face.INTRADOS
                e_before = m.energy(phi, v, g)
                q, phi_q, s_q, kept, jump, ok = choose_migration(cache, m, phi, v, j, face, xg, t,
                                                                 mu=mu, g=g, reexpress=reexpress)
                if ok:
                    suppressed = set()
                    mech, phi, v = q, phi_q, s_q
                    switches.append(Switch(t, "migration", m.label, q.label, e_before,
                                           q.energy(phi_q, s_q, g), position_jump_m=jump, joint=j,
                                           admissible=True, kept=kept))
            continue
        if which == 4:  # a suppressed joint's thrust is back inside
            back = margins(t, [phi, v])
            left = {k for k in suppressed if back[k] < -1e-6}
            suppressed = left if left != suppressed else set()
            continue
        e_before = m.energy(phi, v, g)
        if which == 0:  # closing impact: the chain law
            from archquake.mechanism.impact_chain import chain_impact

            imp = chain_impact(m.hinges, exact=False)
            impacts += 1
            suppressed = set()
            if imp.post is None:
                switches.append(Switch(t, "rest", m.label, "-", e_before, 0.0, kept=0.0))
                mech, phi, v = None, 0.0, 0.0
            else:
                q = cache.get(imp.post)
                u_p, u_q = m.field(0.0), q.field(0.0)
                vel = v * u_p
                s = cache.inner(u_q, vel) / cache.inner(u_q, u_q)
                mech, phi, v = q, 0.0, s
                e_after = q.energy(0.0, s, g)
                switches.append(Switch(t, "impact", m.label, q.label, e_before, e_after,
                                       admissible=imp.validity != "outside",
                                       kept=e_after / e_before if e_before > 0 else 0.0))
                if e_after < 1e-12 * arch.mass * g * arch.radius:
                    mech, phi, v = None, 0.0, 0.0
            if stop_after_impacts is not None and impacts >= stop_after_impacts:
                break
            continue
        if which == 1:  # migration
            xg = ground(t, right)
            adm = state_margins(m.prepared, t, phi, v, m.side, xg, mu=mu, g=g)
            j = adm.worst_joint
            face = Face.EXTRADOS if adm.worst_face == "extrados" else Face.INTRADOS
            q, phi_q, s, kept, jump, ok = choose_migration(cache, m, phi, v, j, face, xg, t,
                                                           mu=mu, g=g, reexpress=reexpress)
            if not ok:  # no admissible four-hinge continuation: keep P, flag the joint
                suppressed.add(j)
                outside_log.append((t, m.label, [j]))
                continue
            suppressed = set()
            mech, phi, v = q, phi_q, s
            switches.append(Switch(t, "migration", m.label, q.label, e_before,
                                   q.energy(phi_q, s, g), position_jump_m=jump, joint=j,
                                   admissible=ok, kept=kept))
            continue
        outcome, collapse_time = "collapse", t
        break
    if ts:
        t_all, e_all, p_all = np.concatenate(ts), np.concatenate(es), np.concatenate(ps)
    else:
        t_all = e_all = p_all = np.zeros(0)
    return MigrationResult(outcome, collapse_time, tuple(switches), tuple(segments), t_all,
                           e_all, p_all, tuple(outside_log))


__all__ = [
    "CANDIDATES",
    "Mechanism",
    "MechanismCache",
    "MigrationResult",
    "Switch",
    "choose_migration",
    "choose_onset",
    "label",
    "simulate_migrating",
]
