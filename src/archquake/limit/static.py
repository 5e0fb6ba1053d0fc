"""Static (lower-bound) limit analysis: the largest load for which a line of thrust fits.

Unknowns (dimensionless: forces over the arch's weight W, lengths over R): the left support
reaction (H, V), its moment M0 about the origin O, and the load factor lambda (horizontal body
force lambda g on every voussoir, towards +x). Every joint's normal force N_j and moment M_j
about the joint's centre are affine in those four unknowns (`archquake.limit.thrust.
joint_forces` evaluated for each unit unknown and superposed), and the line of thrust lies
inside the section at joint j when

    -N_j t/2 <= M_j <= N_j t/2        (which implies N_j >= 0).

Maximising lambda under these 2(n+1) constraints is a linear program (HiGHS). By the
lower-bound theorem its optimum is the collapse multiplier; the constraints with non-zero
duals are the hinges of the collapse mechanism (the duals are the hinge rotations of the
virtual-work equation), and where the line of thrust touches the intrados or the extrados.

By the mirror symmetry of the arch, the set of admissible lambda is an interval [-l, l]:
it contains 0 whenever it is not empty, so the arch stands under its own weight exactly when
the program is feasible. `min_thickness_ratio` bisects on that feasibility.
"""

from __future__ import annotations

import math

import numpy as np

from archquake._validate import require_instance, require_range
from archquake.errors import ArchquakeError, SolverError, UnstableArchError
from archquake.geometry.arch import MAX_VOUSSOIRS, Arch
from archquake.geometry.chain import MIN_THICKNESS_RATIO, VoussoirChain
from archquake.geometry.hinges import Face, HingeMechanism
from archquake.limit.thrust import arch_joint_points, joint_forces, moments_about_origin

#: Below this t/R an arch that still stands is reported as standing at any thickness: twice the
#: least t/R an Arch accepts, so that the bisection's next midpoint is still an Arch.
_THINNEST = 2.0 * MIN_THICKNESS_RATIO

#: Smallest relative bracket width `min_thickness_ratio` accepts: a few units of double
#: precision (2.2e-16) above which the bisection's midpoint still differs from its ends.
MIN_RTOL = 1e-14

#: Bisections at most: log2(0.5 / _THINNEST) + log2(1 / MIN_RTOL) < 100.
_MAX_BISECTIONS = 100

#: Largest load factor the program searches (g); beyond it the arch is treated as not
#: collapsing under any horizontal acceleration (thick, shallow arches can carry any).
MAX_MULTIPLIER = 100.0


def _unit_joint_actions(arch: VoussoirChain) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """N and M (moment about the joint centre) at every joint for each unit unknown.

    Returns
    -------
    normal : ndarray, shape (5, n+1)
        Rows: the constant part (self-weight), then per unit H, V, M0, lambda.
    moment : ndarray, shape (5, n+1)
        Same rows, moments about the joint centres (lengths over R, forces over W).
    half_widths : ndarray, shape (n+1,)
        t / (2R) at every joint.
    """
    scale = arch.radius
    pts = arch_joint_points(arch) / scale
    centroids = arch.voussoir_centroids / scale
    w = arch.voussoir_masses / arch.voussoir_masses.sum()
    n = arch.voussoirs
    zero_f, zero_m = np.zeros((n, 2)), np.zeros(n)
    weight = np.column_stack([np.zeros(n), -w])
    push = np.column_stack([w, np.zeros(n)])
    cases = [
        (weight, moments_about_origin(weight, centroids), (0.0, 0.0), 0.0),
        (zero_f, zero_m, (1.0, 0.0), 0.0),
        (zero_f, zero_m, (0.0, 1.0), 0.0),
        (zero_f, zero_m, (0.0, 0.0), 1.0),
        (push, moments_about_origin(push, centroids), (0.0, 0.0), 0.0),
    ]
    results = [joint_forces(pts, f, m, np.array(r), r_m) for f, m, r, r_m in cases]
    return (
        np.array([r.normal for r in results]),
        np.array([r.moment for r in results]),
        results[0].half_widths,
    )


def _constraints(arch: VoussoirChain) -> tuple[np.ndarray, np.ndarray]:
    """A_ub x <= b_ub over x = (H, V, M0, lambda): rows 2j (intrados: M_j - h N_j <= 0) and
    2j+1 (extrados: -M_j - h N_j <= 0)."""
    normal, moment, half = _unit_joint_actions(arch)
    intrados = moment - half * normal  # (5, n+1)
    extrados = -moment - half * normal
    rows = np.empty((5, 2 * normal.shape[1]))
    rows[:, 0::2], rows[:, 1::2] = intrados, extrados
    return rows[1:].T.copy(), -rows[0]


def _solve(c, a_ub, b_ub, bounds):
    from scipy.optimize import linprog  # (lazy: scipy is slow to import)

    res = linprog(c, A_ub=a_ub, b_ub=b_ub, bounds=bounds, method="highs")
    if res.status not in (0, 2, 3):
        raise SolverError(f"the limit-analysis linear program failed: {res.message}")
    return res


def stands(arch: VoussoirChain) -> bool:
    """True if a line of thrust fits inside the arch under self-weight alone.

    Examples
    --------
    >>> stands(Arch.from_ratio(0.12, math.pi, 200)), stands(Arch.from_ratio(0.10, math.pi, 200))
    (True, False)
    """
    a_ub, b_ub = _constraints(arch)
    res = _solve(np.zeros(3), a_ub[:, :3], b_ub, [(None, None)] * 3)
    return res.status == 0


def min_thickness_ratio(embrace: float, voussoirs: int, *, rtol: float = 1e-7) -> float:
    """Least t/R for which a part-circular arch stands under its own weight.

    Bisection on the feasibility of the static program with lambda = 0 (each step is one
    small linear program; about 25 steps).

    Parameters
    ----------
    embrace : float
        Angle of embrace, rad (0, 240 degrees].
    voussoirs : int
        Number of voussoirs (3 .. MAX_VOUSSOIRS).
    rtol : float
        Relative width of the final bracket, in [`MIN_RTOL`, 0.5] (below the floor the
        bracket's ends cannot be told apart in double precision).

    Returns
    -------
    float
        Minimum t/R; 0.0 when the arch stands at any thickness (three voussoirs: a line of
        thrust can pass through all four joint centres). Tends to Milankovitch's 0.1075 for
        a semicircle as n grows (Heyman's 0.106 comes from an approximate statics).

    Examples
    --------
    >>> round(min_thickness_ratio(math.pi, 200), 3)
    0.107
    """
    require_range("rtol", rtol, MIN_RTOL, 0.5, low_open=False, high_open=False)
    low, high = 0.0, 0.5
    while not stands(Arch.from_ratio(high, embrace, voussoirs)):
        low, high = high, min(2.0 * high, 1.999)
        if low >= 1.999:
            raise ArchquakeError(
                f"no thickness below 2R lets this arch stand (embrace {math.degrees(embrace):g} "
                f"degrees, {voussoirs} voussoirs)"
            )
    # each halving takes the bracket's relative width down by 2: log2(1/rtol) + the halvings
    # from 0.5 down to _THINNEST bound the count (the cap is a guard, never reached)
    for _ in range(_MAX_BISECTIONS):
        if high - low <= rtol * high:
            break
        if high < _THINNEST:
            return 0.0
        mid = 0.5 * (low + high)
        if stands(Arch.from_ratio(mid, embrace, voussoirs)):
            high = mid
        else:
            low = mid
    return high


def min_thickness(arch: VoussoirChain, *, rtol: float = 1e-7) -> float:
    """Least ring thickness, m, for which ``arch`` (its shape, joints, voussoirs and piers
    kept; `with_thickness`) stands under its own weight.

    Bisection on the feasibility of the static program with lambda = 0, as
    `min_thickness_ratio` (which it equals times R for a circular `Arch`).

    With loads: `archquake.limit.loaded.min_thickness_loaded`.

    Raises
    ------
    InvalidParameterError
        The arch has no thickness parameter (blocks read from a file).
    ArchquakeError
        No thickness the shape admits lets it stand.

    Examples
    --------
    >>> round(min_thickness(Arch(2.0, 0.5, math.pi, 200)) / 2.0, 3)
    0.107
    """
    require_instance("arch", arch, VoussoirChain, "an arch of archquake.geometry (e.g. Arch)")
    if isinstance(arch, Arch):
        return min_thickness_ratio(arch.embrace, arch.voussoirs, rtol=rtol) * arch.radius
    return _thickness_bisection(arch, lambda t: stands(arch.with_thickness(t)), rtol)


def _thickness_bisection(arch: VoussoirChain, ok, rtol: float) -> float:
    """Least ring thickness of ``arch``'s shape for which ``ok(t)`` holds, m (bisection)."""
    require_range("rtol", rtol, MIN_RTOL, 0.5, low_open=False, high_open=False)
    t0 = arch.thickness

    low, high = 0.0, t0
    while not ok(high):
        low, high = high, 2.0 * high
        try:
            arch.with_thickness(high)
        except ArchquakeError:
            raise ArchquakeError(
                f"no ring thickness this shape admits lets it stand under its own weight "
                f"(tried up to {low:.4g} m)"
            ) from None
    for _ in range(_MAX_BISECTIONS):
        if high - low <= rtol * high:
            break
        if high < _THINNEST * arch.radius:
            return 0.0
        mid = 0.5 * (low + high)
        try:
            good = ok(mid)
        except ArchquakeError:  # a thickness some joint pattern cannot take
            good = False
        if good:
            high = mid
        else:
            low = mid
    return high


def geometric_safety_factor(arch: VoussoirChain) -> float:
    """The geometric factor of safety t / t_min (Heyman): how many times thicker than the
    thinnest arch of the same shape that stands, dimensionless."""
    t_min = min_thickness(arch)
    return math.inf if t_min == 0.0 else arch.thickness / t_min


def min_pier_width(arch: VoussoirChain, *, rtol: float = 1e-4) -> float | None:
    """Least width of an arch's piers (m) at which it stands under its own weight, its height,
    courses and arch held; None if the arch has no piers, or none up to 64 times the given
    width (or twice the pier height, if larger) stand.

    Bisection on `stands` between a width that does not stand and one that does (a
    wider pier is heavier and its base longer: the line of thrust fits more easily).

    Examples
    --------
    >>> from archquake.geometry import Arch, OnPiers, Piers
    >>> arch = OnPiers(Arch.from_ratio(0.15, math.pi, 9), Piers(6.0, 0.3, 3))
    >>> stands(arch), round(min_pier_width(arch), 3)
    (False, 0.367)
    """
    from archquake.geometry.chain import OnPiers, Piers

    piers = getattr(arch, "piers", None)
    if piers is None:
        return None
    inner = arch.arch  # type: ignore[attr-defined]

    def ok(width: float) -> bool:
        try:
            return stands(OnPiers(inner, Piers(piers.height, width, piers.courses)))
        except ArchquakeError:  # narrower than the springing joint
            return False

    if ok(piers.width):
        return float(piers.width)
    lo, hi = piers.width, piers.width
    top = max(64.0 * piers.width, 2.0 * piers.height)
    while not ok(hi):
        lo, hi = hi, 2.0 * hi
        if hi > top:
            return None
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return float(hi)


def unstable_error(arch: VoussoirChain) -> UnstableArchError:
    """The one-line error for an arch too thin to stand, naming its minimum thickness."""
    piers = getattr(arch, "piers", None)
    if piers is not None and stands(arch.arch):  # type: ignore[attr-defined]
        wide = min_pier_width(arch)
        would = ("" if wide is None else
                 f"; piers {math.ceil(wide * 1000.0) / 1000.0:.3f} m wide would stand")
        return UnstableArchError(
            f"the piers are too slender to stand under the arch's thrust ({piers.height:g} m "
            f"high, {piers.width:g} m wide): no line of thrust fits inside them{would}; "
            "increase --pier-width or lower --pier-height",
            min_thickness_ratio=None,
        )
    if not isinstance(arch, Arch):
        try:
            t_min = min_thickness(arch)
        except ArchquakeError:
            return UnstableArchError(
                "the arch is too thin to stand under its own weight: no line of thrust fits "
                "inside its blocks", min_thickness_ratio=math.nan)
        return UnstableArchError(
            f"the arch is too thin to stand under its own weight: its minimum thickness is "
            f"{t_min:.4g} m, got {arch.thickness:.4g} m; increase --thickness",
            min_thickness_ratio=t_min / arch.radius,
        )
    ratio = min_thickness_ratio(arch.embrace, arch.voussoirs)
    return UnstableArchError(
        f"the arch is too thin to stand under its own weight: t/R = {arch.thickness_ratio:.4g} "
        f"but an arch of {math.degrees(arch.embrace):g} degrees embrace and {arch.voussoirs} "
        f"voussoirs needs t/R >= {ratio:.4f} (t >= {ratio * arch.radius:.4g} m for R = "
        f"{arch.radius:g} m); increase the thickness",
        min_thickness_ratio=ratio,
    )


def static_collapse(arch: VoussoirChain, *, rtol: float = 1e-7) -> tuple[float, HingeMechanism]:
    """Largest horizontal load factor (towards +x) for which a line of thrust fits.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch of `archquake.geometry` (a chain of blocks between two supports).
    rtol : float
        Relative threshold on the duals (against the largest) that marks a hinge.

    Returns
    -------
    multiplier : float
        Collapse acceleration in g, as the program's optimum.
    mechanism : HingeMechanism
        Hinges where the optimum's duals are non-zero.

    Raises
    ------
    UnstableArchError
        No line of thrust fits even without horizontal load.
    ArchquakeError
        The arch carries any horizontal acceleration up to `MAX_MULTIPLIER` g.

    Examples
    --------
    >>> lam, mech = static_collapse(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> round(lam, 4), mech.joints, [f.value[0] for f in mech.faces]
    (0.37, (0, 3, 5, 7), ['i', 'e', 'i', 'e'])
    """
    if arch.voussoirs > MAX_VOUSSOIRS:  # pragma: no cover - Arch already forbids it
        raise ArchquakeError(f"at most {MAX_VOUSSOIRS} voussoirs")
    a_ub, b_ub = _constraints(arch)
    bounds = [(None, None)] * 3 + [(None, MAX_MULTIPLIER)]
    res = _solve(np.array([0.0, 0.0, 0.0, -1.0]), a_ub, b_ub, bounds)
    if res.status == 2:
        raise unstable_error(arch)
    lam = float(res.x[3])
    if res.status == 3 or lam >= MAX_MULTIPLIER * (1 - 1e-9):
        raise ArchquakeError(
            f"no collapse mechanism: a line of thrust fits for any horizontal acceleration up to "
            f"{MAX_MULTIPLIER:g} g (the arch is thick and shallow enough to act as a strut)"
        )
    duals = np.abs(res.ineqlin.marginals)
    order = np.argsort(duals)[::-1]
    active = [int(i) for i in order if duals[i] > rtol * duals[order[0]]]
    if len(active) != 4:
        raise SolverError(
            f"the collapse state has {len(active)} active hinges instead of 4 (a degenerate "
            "tie between mechanisms); use the kinematic method"
        )
    active.sort()
    joints = tuple(i // 2 for i in active)
    if len(set(joints)) < 4:
        j = next(x for x in joints if joints.count(x) == 2)
        raise ArchquakeError(
            f"at collapse ({lam:.4g} g) joint {j} opens on both faces (the arch lifts off there "
            "and turns as a rigid body): not a four-hinge mechanism, which is the only collapse "
            "mode archquake models (typical of thick arches of small embrace)"
        )
    faces = tuple(Face.INTRADOS if i % 2 == 0 else Face.EXTRADOS for i in active)
    return lam, HingeMechanism(arch, joints, faces)  # type: ignore[arg-type]


def collapse_state(mechanism: HingeMechanism) -> tuple[float, np.ndarray]:
    """The unique equilibrium with the line of thrust through the four hinges.

    Solves the 4 x 4 linear system M_j = -e_j N_j at the hinges (e_j = -t/2 on the intrados,
    +t/2 on the extrados) for (H, V, M0, lambda).

    Returns
    -------
    multiplier : float
        Load factor in g (equal, by virtual work, to ``mechanism.collapse_acceleration_g``).
    unknowns : ndarray, shape (3,)
        (H, V, M0) of the left reaction over the weight W (M0 about O, over W R).
    """
    arch = mechanism.arch
    normal, moment, half = _unit_joint_actions(arch)
    rows, rhs = [], []
    for j, face in zip(mechanism.joints, mechanism.faces, strict=True):
        e = half[j] if face is Face.EXTRADOS else -half[j]
        coeff = moment[:, j] + e * normal[:, j]  # (5,): constant, H, V, M0, lambda
        rows.append(coeff[1:])
        rhs.append(-coeff[0])
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return float(x[3]), x[:3]


__all__ = [
    "MAX_MULTIPLIER",
    "collapse_state",
    "geometric_safety_factor",
    "min_thickness",
    "min_thickness_ratio",
    "min_pier_width",
    "stands",
    "static_collapse",
    "unstable_error",
]
