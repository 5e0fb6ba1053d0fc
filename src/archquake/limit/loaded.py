"""Limit analysis of an arch with what it carries: fill, backing, loads on the extrados, traffic.

One problem, two load sets on the blocks: the *dead* actions (self-weight, the fill columns,
the loads on the extrados) and the *live* actions that a multiplier mu scales. For the
equivalent static (earthquake) analysis the live actions are the horizontal inertia
``g`` of every mass that moves with the arch (voussoirs, fill columns, carried loads), each
at its own centroid, and mu is lambda in g; for the traffic capacity they are the traffic
load, and mu multiplies it. Joints the backing holds are no hinges and put no bound on the
line of thrust.

The two methods, as for the bare arch (`archquake.limit.analysis`):

- kinematic (upper bound): over every admissible four-hinge mechanism at the joints that are
  not held, mu = -P_dead / P_live, P being the virtual power of an action set in the opening
  motion, for the mechanisms the live load drives (P_live > 0); the least is the collapse
  multiplier. Each link's power is w (M_O - P x F) (plus v_B . F on the coupler), with prefix
  sums of the blocks' forces and moments about O, so each mechanism costs O(1);
- static (lower bound): the largest mu for which a line of thrust fits in every joint that is
  not held, a linear program over (H, V, M0, mu).

The multiplier reported is the one of the equilibrium through the four hinges (a 4 x 4 solve),
so it carries no linear-program tolerance; both bounds must agree with it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import ArchquakeError, InvalidParameterError, SolverError
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import Face, HingeMechanism
from archquake.geometry.loads import (
    BlockExtras,
    Loads,
    Traffic,
    block_extras,
    passive_resultants,
    traffic_actions,
)
from archquake.geometry.planar import cross, perp
from archquake.limit.static import MAX_MULTIPLIER, _solve, _thickness_bisection
from archquake.limit.thrust import JointForces, arch_joint_points, joint_forces, moments_about_origin


@dataclass(frozen=True)
class LoadCase:
    """The actions on the blocks of ``arch`` (n blocks): dead ones, and live ones scaled by mu.

    Attributes
    ----------
    arch : VoussoirChain
    dead_force, live_force : ndarray, shape (n, 2)
        N.
    dead_moment, live_moment : ndarray, shape (n,)
        About the origin, N m.
    held : ndarray of bool, shape (n+1,)
        Joints that cannot hinge (backing).
    passive_block, passive_point, passive_direction, passive_limit : ndarray
        The passive forces the fill may put on the blocks (s of them): block, point (m),
        direction (+1 towards +x) and largest value (N)
        (`passive_resultants`); each takes any value from 0
        to its limit.
    """

    arch: VoussoirChain
    dead_force: np.ndarray
    dead_moment: np.ndarray
    live_force: np.ndarray
    live_moment: np.ndarray
    held: np.ndarray
    passive_block: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    passive_point: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    passive_direction: np.ndarray = field(default_factory=lambda: np.zeros(0))
    passive_limit: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def weight(self) -> float:
        """Total dead vertical load, N."""
        return float(-self.dead_force[:, 1].sum())


def _dead(arch: VoussoirChain, extras: BlockExtras, g: float) -> tuple[np.ndarray, np.ndarray]:
    n = arch.voussoirs
    w_own = arch.voussoir_masses * g
    w_extra = extras.mass * g
    force = np.zeros((n, 2))
    force[:, 1] = -(w_own + w_extra)
    own = np.column_stack([np.zeros(n), -w_own])
    extra = np.column_stack([np.zeros(n), -w_extra])
    moment = (moments_about_origin(own, arch.voussoir_centroids)
              + moments_about_origin(extra, extras.centroid))
    return force + extras.weight_force, moment + extras.weight_moment


def seismic_case(arch: VoussoirChain, loads: Loads | None = None, *, direction: int = 1,
                 g: float = STANDARD_GRAVITY, vertical: float = 0.0) -> LoadCase:
    """Self-weight and the loads, with the horizontal inertia (towards ``direction`` x) of every
    mass that moves with the arch as the live load: mu is lambda, in g.

    ``vertical`` is a constant upward ground acceleration, in g (> -1): every mass that moves
    with the arch then weighs m g (1 + vertical), and so does the fill behind the passive
    pressure; loads whose mass does not move with the arch keep their weight."""
    loads = Loads() if loads is None else loads
    extras = block_extras(arch, loads, g=g)
    weigh = g * (1.0 + vertical) if vertical else g
    dead_f, dead_m = _dead(arch, extras, weigh)
    n = arch.voussoirs
    own = np.column_stack([direction * arch.voussoir_masses * g, np.zeros(n)])
    extra = np.column_stack([direction * extras.mass * g, np.zeros(n)])
    live_f = own + extra
    live_m = (moments_about_origin(own, arch.voussoir_centroids)
              + moments_about_origin(extra, extras.centroid))
    return _with_passive(LoadCase(arch, dead_f, dead_m, live_f, live_m, extras.held), loads,
                         weigh)


def _with_passive(case: LoadCase, loads: Loads, g: float) -> LoadCase:
    if loads.passive is None:
        return case
    blocks, points, dirs, limits = passive_resultants(case.arch, loads, g=g)
    keep = ~(case.held[blocks] & case.held[blocks + 1])  # blocks the backing holds need none
    return replace(case, passive_block=blocks[keep], passive_point=points[keep],
                   passive_direction=dirs[keep], passive_limit=limits[keep])


def traffic_case(arch: VoussoirChain, loads: Loads, traffic: Traffic | None = None, *,
                 g: float = STANDARD_GRAVITY) -> LoadCase:
    """Self-weight and the loads as dead actions, the traffic as the live one: mu is the
    multiplier on the traffic load."""
    traffic = traffic or loads.traffic
    if traffic is None:
        raise InvalidParameterError("the traffic capacity needs a traffic load")
    extras = block_extras(arch, loads, g=g)
    dead_f, dead_m = _dead(arch, extras, g)
    live_f, live_m, _ = traffic_actions(arch, loads, traffic)
    return _with_passive(LoadCase(arch, dead_f, dead_m, live_f, live_m, extras.held), loads, g)


# ---------------------------------------------------------------------------------------------
# Static (lower bound)
# ---------------------------------------------------------------------------------------------


def _unit_actions(case: LoadCase) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, float]:
    """N and M at every joint for the dead loads and each unit unknown (H, V, M0, mu), over
    the force scale W and the length scale R; rows as in `archquake.limit.static`."""
    arch = case.arch
    scale_l = arch.radius
    scale_f = case.weight if case.weight > 0 else float(np.abs(case.live_force).sum())
    pts = arch_joint_points(arch) / scale_l
    n = arch.voussoirs
    zero_f, zero_m = np.zeros((n, 2)), np.zeros(n)
    cases = [
        (case.dead_force / scale_f, case.dead_moment / (scale_f * scale_l), (0.0, 0.0), 0.0),
        (zero_f, zero_m, (1.0, 0.0), 0.0),
        (zero_f, zero_m, (0.0, 1.0), 0.0),
        (zero_f, zero_m, (0.0, 0.0), 1.0),
        (case.live_force / scale_f, case.live_moment / (scale_f * scale_l), (0.0, 0.0), 0.0),
    ]
    for b, pt, d in zip(case.passive_block, case.passive_point, case.passive_direction,
                        strict=True):  # one unit passive force each (force scale: 1 = W)
        f, m = zero_f.copy(), zero_m.copy()
        f[b, 0] = d
        m[b] = moments_about_origin(f[b], pt / scale_l)
        cases.append((f, m, (0.0, 0.0), 0.0))
    res = [joint_forces(pts, f, m, np.array(r), r_m) for f, m, r, r_m in cases]
    return (np.array([r.normal for r in res]), np.array([r.moment for r in res]),
            res[0].half_widths, scale_f, scale_l)


def _constraints(case: LoadCase) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    normal, moment, half, _, _ = _unit_actions(case)
    rows = np.empty((normal.shape[0], 2 * normal.shape[1]))
    rows[:, 0::2] = moment - half * normal
    rows[:, 1::2] = -moment - half * normal
    keep = np.repeat(~case.held, 2)
    index = np.flatnonzero(keep)
    return rows[1:, keep].T.copy(), -rows[0, keep], index


class _Tie(SolverError):
    """The linear program's optimum marks more than four hinges (a tie between mechanisms)."""

    def __init__(self, message: str, multiplier: float):
        super().__init__(message)
        self.multiplier = multiplier

    def __reduce__(self):
        return (type(self), (str(self), self.multiplier))


def static_multiplier(case: LoadCase, *, rtol: float = 1e-7) -> tuple[float, HingeMechanism]:
    """Largest mu for which a line of thrust fits in every joint not held (the linear
    program), and the hinges its duals mark.

    Raises
    ------
    UnstableArchError
        No line of thrust fits under the dead loads alone.
    ArchquakeError
        Any mu up to `MAX_MULTIPLIER` is carried, or the collapse
        is not a four-hinge mechanism.
    """
    res, index = _lp(case)
    mu = float(res.x[3])
    duals = np.abs(res.ineqlin.marginals)
    order = np.argsort(duals)[::-1]
    active = sorted(int(index[i]) for i in order if duals[i] > rtol * duals[order[0]])
    if len(active) != 4:
        raise _Tie(f"the collapse state has {len(active)} active hinges instead of 4 (a tie "
                   "between mechanisms); use the kinematic method", mu)
    joints = tuple(i // 2 for i in active)
    if len(set(joints)) < 4:
        raise ArchquakeError(
            f"at collapse ({mu:.4g}) a joint opens on both faces (the arch lifts off and turns "
            "as a rigid body): not a four-hinge mechanism")
    faces = tuple(Face.INTRADOS if i % 2 == 0 else Face.EXTRADOS for i in active)
    return mu, HingeMechanism(case.arch, joints, faces)  # type: ignore[arg-type]


def _passive_bounds(case: LoadCase) -> list[tuple[float, float]]:
    """0 <= p_s <= limit_s, over the force scale of `_unit_actions`."""
    scale_f = case.weight if case.weight > 0 else float(np.abs(case.live_force).sum())
    return [(0.0, float(lim) / scale_f) for lim in case.passive_limit]


def _unstable(case: LoadCase) -> ArchquakeError:
    from archquake.errors import UnstableArchError

    return UnstableArchError(
        "the arch is too thin to stand under its own weight and the loads it carries: no "
        "line of thrust fits inside it; lighten the loads or thicken the ring",
        min_thickness_ratio=None)


def stands(case: LoadCase) -> bool:
    """True if a line of thrust fits under the dead loads alone."""
    a_ub, b_ub, _ = _constraints(case)
    a_ub = np.delete(a_ub, 3, axis=1)  # no live load
    passive = _passive_bounds(case)
    return _solve(np.zeros(3 + len(passive)), a_ub, b_ub,
                  [(None, None)] * 3 + passive).status == 0


# ---------------------------------------------------------------------------------------------
# Kinematic (upper bound)
# ---------------------------------------------------------------------------------------------


def _powers(mechs, force: np.ndarray, moment: np.ndarray) -> np.ndarray:
    """Virtual power of the actions (force (n, 2), moment about O (n,)) in every mechanism's
    opening motion, per unit opening rate, shape (m,)."""
    cf = np.vstack([np.zeros((1, 2)), np.cumsum(force, axis=0)])
    cm = np.concatenate([[0.0], np.cumsum(moment)])
    a, b, c, d = mechs.joints.T
    pa, pb, pc, pd = (mechs.points[:, i] for i in range(4))
    w_ab, w_bc, w_cd = mechs.rates.T
    f_ab, f_bc, f_cd = cf[b] - cf[a], cf[c] - cf[b], cf[d] - cf[c]
    m_ab, m_bc, m_cd = cm[b] - cm[a], cm[c] - cm[b], cm[d] - cm[c]
    vb = w_ab[:, None] * perp(pb - pa)
    del pc
    return (w_ab * (m_ab - cross(pa, f_ab))
            + w_bc * (m_bc - cross(pb, f_bc)) + np.einsum("ij,ij->i", vb, f_bc)
            + w_cd * (m_cd - cross(pd, f_cd)))


def _passive_resistance(mechs, case: LoadCase, chunk: int = 200_000) -> np.ndarray:
    """The power the passive forces absorb in every mechanism's opening motion (>= 0): each
    at its limit where its point moves into the fill (d v_x < 0), else 0, shape (m,)."""
    out = np.zeros(len(mechs))
    if case.passive_limit.size == 0:
        return out
    blk, pts = case.passive_block, case.passive_point
    for start in range(0, len(mechs), chunk):
        sl = slice(start, start + chunk)
        j = mechs.joints[sl]
        p = mechs.points[sl]
        w = mechs.rates[sl]
        vb_x = -w[:, 0] * (p[:, 1, 1] - p[:, 0, 1])
        k = blk[None, :]
        y = pts[None, :, 1]
        on_ab = (k >= j[:, 0:1]) & (k < j[:, 1:2])
        on_bc = (k >= j[:, 1:2]) & (k < j[:, 2:3])
        on_cd = (k >= j[:, 2:3]) & (k < j[:, 3:4])
        vx = np.where(on_ab, -w[:, 0:1] * (y - p[:, 0, 1:2]), 0.0)
        vx = np.where(on_bc, vb_x[:, None] - w[:, 1:2] * (y - p[:, 1, 1:2]), vx)
        vx = np.where(on_cd, -w[:, 2:3] * (y - p[:, 3, 1:2]), vx)
        into = np.maximum(0.0, -case.passive_direction[None, :] * vx)
        out[sl] = into @ case.passive_limit
    return out


def _mechanism_passive_forces(case: LoadCase, mechanism: HingeMechanism) -> np.ndarray:
    """The passive forces of ``mechanism``'s collapse state: each at its limit where its point
    moves into the fill, else 0, N, shape (s,)."""
    if case.passive_limit.size == 0:
        return np.zeros(0)
    from archquake.limit.kinematic import MechanismSet

    one = MechanismSet(np.array([mechanism.joints]),
                       np.array([[1 if f is Face.EXTRADOS else 0 for f in mechanism.faces]]),
                       mechanism.points[None], mechanism.rates[None])
    absorbed = np.zeros(case.passive_limit.size)
    for s in range(case.passive_limit.size):
        unit = replace(case, passive_limit=np.where(np.arange(absorbed.size) == s, 1.0, 0.0))
        absorbed[s] = _passive_resistance(one, unit)[0]
    return np.where(absorbed > 0.0, case.passive_limit, 0.0)


def kinematic_multiplier(case: LoadCase) -> tuple[float, HingeMechanism]:
    """Least virtual-work multiplier over the four-hinge mechanisms at joints not held."""
    from archquake.limit.kinematic import admissible_mechanisms

    mechs = admissible_mechanisms(case.arch)
    allowed = ~case.held[mechs.joints].any(axis=1)
    mechs = mechs.subset(allowed)
    p_dead = _powers(mechs, case.dead_force, case.dead_moment) - _passive_resistance(mechs, case)
    p_live = _powers(mechs, case.live_force, case.live_moment)
    scale = float(np.max(np.abs(p_live), initial=0.0))
    ok = p_live > 1e-12 * scale
    if not np.any(ok):
        raise InvalidParameterError("no four-hinge mechanism at the free joints is driven by "
                                    "this load")
    mu = -p_dead[ok] / p_live[ok]
    i = int(np.argmin(mu))
    return float(mu[i]), mechs.subset(ok).mechanism(i, case.arch)


# ---------------------------------------------------------------------------------------------
# The collapse state through four hinges
# ---------------------------------------------------------------------------------------------


def collapse_forces(case: LoadCase, mechanism: HingeMechanism, *, scale: float = 1.0
                    ) -> tuple[float, JointForces]:
    """The multiplier and the joint resultants (N, N m) of the equilibrium whose line of thrust
    passes through the four hinges of ``mechanism``."""
    if case.passive_limit.size:  # the passive forces of this mechanism become dead loads
        forces = _mechanism_passive_forces(case, mechanism)
        f, m = case.dead_force.copy(), case.dead_moment.copy()
        for b, pt, d, p in zip(case.passive_block, case.passive_point, case.passive_direction,
                               forces, strict=True):
            push = np.array([d * p, 0.0])
            f[b] += push
            m[b] += moments_about_origin(push, pt)
        case = replace(case, dead_force=f, dead_moment=m, passive_block=case.passive_block[:0],
                       passive_point=case.passive_point[:0],
                       passive_direction=case.passive_direction[:0],
                       passive_limit=case.passive_limit[:0])
    normal, moment, half, scale_f, scale_l = _unit_actions(case)
    rows, rhs = [], []
    for j, face in zip(mechanism.joints, mechanism.faces, strict=True):
        e = half[j] if face is Face.EXTRADOS else -half[j]
        coeff = moment[:, j] + e * normal[:, j]
        rows.append(coeff[1:5])
        rhs.append(-coeff[0])
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    mu = float(x[3])
    jf = joint_forces(
        arch_joint_points(case.arch),
        case.dead_force + mu * case.live_force,
        case.dead_moment + mu * case.live_moment,
        np.array([x[0], x[1]]) * scale_f,
        float(x[2]) * scale_f * scale_l,
    )
    return mu, jf


@dataclass(frozen=True)
class LoadedCollapse:
    """The collapse of a `LoadCase`: multiplier, hinges, joint resultants, both bounds."""

    case: LoadCase
    multiplier: float
    mechanism: HingeMechanism
    joint_forces: JointForces
    static_multiplier: float | None
    kinematic_multiplier: float | None
    hinge_count: int = 4

    @property
    def four_hinges(self) -> bool:
        """False where the collapse needs more than four hinges (possible with passive
        pressure): ``mechanism`` is then the least four-hinge mechanism, an upper bound."""
        return self.hinge_count == 4


def _lp(case: LoadCase):
    """The line-of-thrust program's optimum (raises where the arch cannot stand or never
    collapses) and the constraint rows' joint-face indices."""
    a_ub, b_ub, index = _constraints(case)
    passive = _passive_bounds(case)
    res = _solve(np.concatenate([[0.0, 0.0, 0.0, -1.0], np.zeros(len(passive))]), a_ub, b_ub,
                 [(None, None)] * 3 + [(None, MAX_MULTIPLIER)] + passive)
    if res.status == 2:
        raise _unstable(case)
    mu = float(res.x[3])
    if res.status == 3 or mu >= MAX_MULTIPLIER * (1 - 1e-9):
        raise ArchquakeError(
            f"no collapse mechanism: a line of thrust fits for any multiplier up to "
            f"{MAX_MULTIPLIER:g}")
    return res, index


def _passive_collapse(case: LoadCase, method: str, rtol: float = 1e-7) -> LoadedCollapse:
    """With passive pressure the fill's resistance is a convex, piecewise linear function of
    the motion, so the collapse may combine two four-hinge mechanisms (five hinges or more).
    The line-of-thrust program is then the exact multiplier of the block model; the least
    four-hinge mechanism is an upper bound that equals it where the program marks four
    hinges."""
    if method == "kinematic":
        raise InvalidParameterError(
            "with passive fill pressure the collapse may need more than four hinges: use the "
            "static method (or both)")
    res, index = _lp(case)
    mu_s = float(res.x[3])
    duals = np.abs(res.ineqlin.marginals)
    top = float(np.max(duals))
    active = sorted(int(index[i]) for i in np.flatnonzero(duals > rtol * top))
    mech: HingeMechanism | None = None
    joints = tuple(i // 2 for i in active)
    if len(active) == 4 and len(set(joints)) == 4:
        faces = tuple(Face.INTRADOS if i % 2 == 0 else Face.EXTRADOS for i in active)
        mech = HingeMechanism(case.arch, joints, faces)  # type: ignore[arg-type]
    mu_k = None
    if method == "both":
        mu_k, mech_k = kinematic_multiplier(case)
        if mech is not None and abs(mu_k - mu_s) > 1e-6 * max(1.0, abs(mu_k)):
            raise SolverError(f"static ({mu_s:.9g}) and kinematic ({mu_k:.9g}) collapse "
                              "multipliers disagree")
        if mu_k < mu_s - 1e-6 * max(1.0, abs(mu_k)):
            raise SolverError(f"the upper bound ({mu_k:.9g}) is below the lower bound "
                              f"({mu_s:.9g})")
        mech = mech or mech_k
    if mech is None:
        from archquake.limit.kinematic import MAX_KINEMATIC_VOUSSOIRS

        if case.arch.voussoirs > MAX_KINEMATIC_VOUSSOIRS:
            raise ArchquakeError(
                f"the collapse ({mu_s:.4g}) needs {len(active)} hinges, and no four-hinge "
                f"mechanism can be enumerated beside it above {MAX_KINEMATIC_VOUSSOIRS} "
                "voussoirs to draw it")
        mu_k, mech = kinematic_multiplier(case)  # the least four-hinge mechanism, to draw
    # the joint resultants of the program's own equilibrium (its passive forces included)
    scale_f = case.weight if case.weight > 0 else float(np.abs(case.live_force).sum())
    push = res.x[4:] * scale_f * case.passive_direction
    f, m = case.dead_force.copy(), case.dead_moment.copy()
    for b, pt, p in zip(case.passive_block, case.passive_point, push, strict=True):
        f[b, 0] += p
        m[b] += moments_about_origin(np.array([p, 0.0]), pt)
    jf = joint_forces(arch_joint_points(case.arch), f + mu_s * case.live_force,
                      m + mu_s * case.live_moment, res.x[:2] * scale_f,
                      float(res.x[2]) * scale_f * case.arch.radius)
    return LoadedCollapse(case, mu_s, mech, jf, mu_s, mu_k, len(active))


def loaded_collapse(case: LoadCase, method: str = "both") -> LoadedCollapse:
    """Collapse of ``case`` by the static ("static"), kinematic ("kinematic") or both methods
    ("both": they must agree to 1e-6 relative). With passive pressure see
    `_passive_collapse`: the program's multiplier is reported."""
    if case.passive_limit.size:
        return _passive_collapse(case, method)
    mu_s = mu_k = None
    mech: HingeMechanism | None = None
    if method in ("static", "both"):
        try:
            mu_s, mech = static_multiplier(case)
        except _Tie as tie:  # the kinematic method names the mechanism
            if method == "static":
                raise
            mu_s = tie.multiplier
    if method in ("kinematic", "both"):
        if method == "kinematic" and not stands(case):
            raise _unstable(case)
        mu_k, mech_k = kinematic_multiplier(case)
        if mu_s is not None and abs(mu_k - mu_s) > 1e-6 * max(1.0, abs(mu_k)):
            raise SolverError(f"static ({mu_s:.9g}) and kinematic ({mu_k:.9g}) collapse "
                              "multipliers disagree")
        mech = mech_k
    assert mech is not None
    mu, jf = collapse_forces(case, mech)
    return LoadedCollapse(case, mu, mech, jf, mu_s, mu_k)


def min_thickness_loaded(arch: VoussoirChain, loads: Loads, *, rtol: float = 1e-7,
                         g: float = STANDARD_GRAVITY) -> float:
    """Least ring thickness, m, for which ``arch`` (its shape kept) stands under its own weight
    and the loads it carries (traffic left out), by bisection on the line-of-thrust program's
    feasibility. A fill keeps its depth over the crown of each thickness tried (or its
    level), a backing its height.

    Examples
    --------
    >>> import math
    >>> from archquake.geometry import Arch
    >>> from archquake.geometry.loads import Fill
    >>> arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
    >>> round(min_thickness_loaded(arch, Loads(fill=Fill(depth=1.0))) / 5.0, 4)
    0.0869
    """
    dead = loads.without_traffic()
    return _thickness_bisection(
        arch, lambda t: stands(seismic_case(arch.with_thickness(t), dead, g=g)), rtol)


__all__ = [
    "min_thickness_loaded",
    "LoadCase",
    "LoadedCollapse",
    "collapse_forces",
    "kinematic_multiplier",
    "loaded_collapse",
    "seismic_case",
    "stands",
    "static_multiplier",
    "traffic_case",
]
