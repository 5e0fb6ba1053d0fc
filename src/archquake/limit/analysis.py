"""Equivalent static analysis: the horizontal acceleration that turns the arch into a mechanism.

Self-weight plus a uniform horizontal acceleration ``lambda g`` on every voussoir, towards +x
(the mirror case follows by symmetry: `HingeMechanism.mirrored`); rigid voussoirs, no
tension, infinite compressive strength, no sliding (Heyman's assumptions, paper p. 2120).
``lambda`` is the minimum constant ground acceleration, in g, that starts the motion: the
paper's 0.37 g for Oppenheim's arch (p. 2126; the paper writes -0.37 g because its ground
acceleration points the other way, towards -x, which loads the arch towards +x).

Two independent methods that must agree:

- kinematic (upper bound, `archquake.limit.kinematic`): least virtual-work multiplier
  over every admissible four-hinge mechanism at the joints (up to 60 voussoirs);
- static (lower bound, `archquake.limit.static`): largest lambda for which a line of
  thrust fits in the section, a linear program (any number of voussoirs).

Scope: the four-hinge mechanism is the collapse mode of arches of moderate to large embrace
(the paper's range). Thick arches of small embrace (seen below about 135 degrees of
embrace, t/R > 0.15) can instead fail by lifting off a springing (a rigid rotation, shear without
normal force at the joint), or carry any horizontal acceleration as a strut; both are
reported as `ArchquakeError` rather than forced into four hinges.

Figure 7 of the paper (R = 10 m, 7 voussoirs, the number of Oppenheim's arch; the paper does
not state another), computed here with `limit_analysis`:

=====  =====  ==========  ====================  ==========  ===============
t/R    beta   lambda (g)  hinges A, B, C, D     locations   friction demand
=====  =====  ==========  ====================  ==========  ===============
0.11   157.5  0.2327      0i, 3e, 5i, 7e        asymmetric  0.413 (joint 7)
0.15   157.5  0.3700      0i, 3e, 5i, 7e        asymmetric  0.495 (joint 7)
0.17   157.5  0.4367      0i, 2e, 5i, 7e        symmetric   0.535 (joint 7)
0.19   157.5  0.4938      0i, 2e, 5i, 7e        symmetric   0.573 (joint 7)
0.15   142.5  0.5237      0i, 2e, 5i, 7e        symmetric   0.491 (joint 7)
0.15   150.0  0.4442      0i, 2e, 5i, 7e        symmetric   0.493 (joint 7)
0.15   165.0  0.2962      0i, 3e, 5i, 7e        asymmetric  0.497 (joint 7)
=====  =====  ==========  ====================  ==========  ===============

(joint index, i = intrados, e = extrados; checked by tests/limit/test_paper.py). All these arches
stand under self-weight: with 7 voussoirs a 157.5 degree arch needs only t/R >= 0.0592.
"Symmetric" is the paper's sense: the hinge *locations* are mirror images about the vertical
axis (joints 2 and 5 of 7). The faces of a mechanism driven by a horizontal load are never
mirror symmetric (the mirror faces give the mirror mechanism, driven by the opposite load),
so `HingeMechanism.symmetric` compares the joints only.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from archquake._validate import (
    require_choice,
    require_gravity,
    require_instance,
    require_range,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.arch import Arch  # noqa: F401  (doctests)
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import Face, HingeMechanism
from archquake.geometry.loads import BlockExtras, Loads
from archquake.limit.kinematic import MAX_KINEMATIC_VOUSSOIRS, kinematic_collapse
from archquake.limit.static import (
    MAX_MULTIPLIER,
    _constraints,
    collapse_state,
    min_thickness_ratio,
    stands,
    static_collapse,
    unstable_error,
)
from archquake.limit.thrust import (
    JointForces,
    arch_joint_points,
    joint_forces,
    moments_about_origin,
)


class Method(StrEnum):
    """How the collapse multiplier was found."""

    STATIC = "static"
    KINEMATIC = "kinematic"
    BOTH = "both"

#: The largest constant vertical ground acceleration the statics take, g (upward).
MAX_VERTICAL_G = 5.0


@dataclass(frozen=True)
class LimitAnalysis:
    """Result of the equivalent static analysis of an arch (load towards +x).

    Attributes
    ----------
    arch : VoussoirChain
        Any arch of `archquake.geometry` (a chain of blocks between two supports).
    collapse_acceleration_g : float
        lambda, the equivalent static collapse acceleration: the horizontal acceleration, in g,
        at which the arch becomes a mechanism (from the line of thrust through the four
        hinges). The one name of lambda in the package (``PreparedMechanism``,
        ``HingeMechanism`` and ``SimulationResult`` use it too).
    mechanism : HingeMechanism
        Hinges A, B, C, D at collapse (``mechanism.load_direction == +1``).
    joint_forces : JointForces
        Resultants at every joint at collapse, N and N m (forces of the left part on the
        right part); ``joint_forces.thrust_points`` is the line of thrust, shape (n+1, 2).
    static_collapse_acceleration_g : float or None
        lambda by the static method (lower bound): the linear program's optimum, g (None if
        not computed).
    kinematic_collapse_acceleration_g : float or None
        lambda by the kinematic method (upper bound): the least virtual-work value over the
        four-hinge mechanisms, g (None if not computed).
    method : Method
    g : float
        Gravity used for the forces, m/s^2.
    loads : Loads or None
        What the arch carries (None: the bare arch). With loads, lambda, the hinges and the
        joint forces are those of the arch with its fill and carried loads
        (`archquake.limit.loaded`); traffic is not part of the earthquake load.
    carried : BlockExtras or None
        The loads as each block carries them (masses, centroids, held joints).
    opposite_collapse_acceleration_g : float or None
        With loads, lambda for a load towards -x (loads need not be symmetric), g.
    hinge_count : int or None
        With loads, the hinges of the collapse: 4, or more where passive pressure makes the
        collapse combine two mechanisms (then ``mechanism`` is the least four-hinge one, an
        upper bound, and lambda is the line-of-thrust program's).
    vertical_g : float
        The constant vertical ground acceleration of the analysis, g, upward positive (0: none).
    """

    arch: VoussoirChain
    collapse_acceleration_g: float
    mechanism: HingeMechanism
    joint_forces: JointForces
    static_collapse_acceleration_g: float | None
    kinematic_collapse_acceleration_g: float | None
    method: Method
    g: float
    loads: Loads | None = None
    carried: BlockExtras | None = None
    opposite_collapse_acceleration_g: float | None = None
    hinge_count: int | None = None
    vertical_g: float = 0.0

    @property
    def symmetric(self) -> bool:
        """True if the hinge locations (joints) are mirror images about the vertical axis,
        the paper's "symmetric mechanism" (Figure 7); see the module docstring for why the
        faces are not compared."""
        return self.mechanism.symmetric

    @property
    def thrust_line(self) -> np.ndarray:
        """Where the line of thrust at collapse crosses each joint, m, shape (n+1, 2)."""
        return self.joint_forces.thrust_points

    @property
    def friction_ratios(self) -> np.ndarray:
        """|V| / N at every joint at collapse, shape (n+1,); nan at joints a backing holds
        (inside the backing, they do not slide)."""
        ratios = self.joint_forces.friction_ratio
        if self.carried is not None and np.any(self.carried.held):
            return np.where(self.carried.held, np.nan, ratios)
        return ratios

    @property
    def min_friction(self) -> float:
        """Static friction demand: the largest |V| / N over the joints at the onset of motion
        (the friction coefficient needed to exclude sliding; paper p. 2131: 0.50)."""
        return float(np.nanmax(self.friction_ratios))

    @property
    def min_friction_joint(self) -> int:
        """The joint where the friction demand is largest."""
        return int(np.nanargmax(self.friction_ratios))

    def to_dict(self) -> dict:
        jf = self.joint_forces
        return {
            "arch": self.arch.describe(),
            "collapse_acceleration_g": self.collapse_acceleration_g,
            "hinges": [h.to_dict() for h in self.mechanism.hinges],
            "symmetric": self.symmetric,
            "load_direction": "+x",
            "min_friction": self.min_friction,
            "min_friction_joint": self.min_friction_joint,
            "static_collapse_acceleration_g": self.static_collapse_acceleration_g,
            "kinematic_collapse_acceleration_g": self.kinematic_collapse_acceleration_g,
            "method": self.method.value,
            "g": self.g,
            "joints": {
                "thrust_x": jf.thrust_points[:, 0],
                "thrust_y": jf.thrust_points[:, 1],
                "normal_N": jf.normal,
                "shear_N": jf.shear,
                "eccentricity_m": jf.eccentricity,
                "friction_ratio": self.friction_ratios,
            },
        } | self._loads_dict() | ({"vertical_g": self.vertical_g} if self.vertical_g else {})

    def _loads_dict(self) -> dict:
        if self.loads is None:
            return {}
        assert self.carried is not None
        return {"loads": self.loads.to_dict(), "carried": self.carried.to_dict(),
                "collapse_hinge_count": self.hinge_count,
                "collapse_acceleration_towards_minus_x_g": self.opposite_collapse_acceleration_g}


def collapse_joint_forces(
    mechanism: HingeMechanism, *, g: float = STANDARD_GRAVITY
) -> tuple[float, JointForces]:
    """Multiplier and joint resultants (N, N m) of the equilibrium through the four hinges."""
    arch = mechanism.arch
    lam, (h, v, m0) = collapse_state(mechanism)
    weight = arch.voussoir_masses * g
    total = float(weight.sum())
    loads = np.column_stack([lam * weight, -weight])
    jf = joint_forces(
        arch_joint_points(arch),
        loads,
        moments_about_origin(loads, arch.voussoir_centroids),
        np.array([h, v]) * total,
        m0 * total * arch.radius,
    )
    return lam, jf


def limit_analysis(
    arch: VoussoirChain, *, method: Method | str = Method.STATIC, g: float = STANDARD_GRAVITY,
    loads: Loads | None = None, vertical: float = 0.0,
) -> LimitAnalysis:
    """Equivalent static analysis of ``arch`` under a horizontal acceleration towards +x.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch of `archquake.geometry` (a chain of blocks between two supports).
    method : {"static", "kinematic", "both"}
        "static" (any n), "kinematic" (n <= 60), or "both" (checks that they agree).
    g : float, optional
        Gravity, m/s^2 (only scales the joint forces; lambda is in g).
    loads : Loads, optional
        What the arch carries (`archquake.geometry.loads`): the fill's and the carried
        loads' weight and horizontal inertia act at their centroids, the backing holds the
        joints below its top. Its traffic, if any, is left out (see
        `traffic_capacity`).
    vertical : float, optional
        A constant vertical ground acceleration, in g, upward positive (> -1): every mass that
        moves with the arch weighs m g (1 + vertical), the horizontal inertia stays m a. The
        bare arch then collapses at (1 + vertical) times its lambda at 0 (only the direction
        of the body force matters); loads whose mass does not move keep their weight.

    Returns
    -------
    LimitAnalysis

    Raises
    ------
    UnstableArchError
        The arch cannot stand under its own weight (message names the minimum t/R).

    Examples
    --------
    Oppenheim's arch (paper p. 2126: 0.37 g):

    >>> import math
    >>> res = limit_analysis(Arch(10.0, 1.5, math.radians(157.5), 7), method="both")
    >>> round(res.collapse_acceleration_g, 3), res.mechanism.joints, res.symmetric
    (0.37, (0, 3, 5, 7), False)
    """
    require_instance("arch", arch, VoussoirChain, "an arch of archquake.geometry (e.g. Arch)")
    method = require_choice("method", method, Method)
    g = require_gravity(g)
    if method is not Method.STATIC and arch.voussoirs > MAX_KINEMATIC_VOUSSOIRS:
        raise InvalidParameterError(
            f"the kinematic method enumerates mechanisms and needs voussoirs <= "
            f"{MAX_KINEMATIC_VOUSSOIRS}, got {arch.voussoirs}; use method='static'"
        )
    if vertical:
        vertical = require_range("vertical", vertical, -1.0, MAX_VERTICAL_G, "g",
                                 high_open=False)
    if loads is not None or vertical:
        return _loaded_analysis(arch, method, g, loads, vertical)
    lam_static = lam_kin = None
    if method is not Method.KINEMATIC:
        lam_static, mech = static_collapse(arch)  # raises UnstableArchError
    if method is not Method.STATIC:
        if method is Method.KINEMATIC:
            if not stands(arch):
                raise unstable_error(arch)
        lam_kin, mech_kin = kinematic_collapse(arch)
        if method is Method.KINEMATIC:
            mech = mech_kin
        elif lam_static is not None and abs(lam_kin - lam_static) > 1e-6 * max(1.0, abs(lam_kin)):
            raise SolverError(
                f"static ({lam_static:.9g} g) and kinematic ({lam_kin:.9g} g) collapse "
                "multipliers disagree"
            )
    lam, jf = collapse_joint_forces(mech, g=g)
    return LimitAnalysis(
        arch=arch,
        collapse_acceleration_g=lam,
        mechanism=mech,
        joint_forces=jf,
        static_collapse_acceleration_g=lam_static,
        kinematic_collapse_acceleration_g=lam_kin,
        method=method,
        g=float(g),
    )


def _loaded_analysis(arch: VoussoirChain, method: Method, g: float, loads: Loads | None,
                     vertical: float = 0.0) -> LimitAnalysis:
    from archquake.geometry.loads import block_extras
    from archquake.limit.loaded import loaded_collapse, seismic_case

    if loads is None:  # the bare arch under a vertical: the same linear program, no loads
        res = loaded_collapse(seismic_case(arch, None, g=g, vertical=vertical), method.value)
        return LimitAnalysis(
            arch=arch, collapse_acceleration_g=res.multiplier, mechanism=res.mechanism,
            joint_forces=res.joint_forces, static_collapse_acceleration_g=res.static_multiplier,
            kinematic_collapse_acceleration_g=res.kinematic_multiplier, method=method,
            g=float(g), vertical_g=vertical)
    require_instance("loads", loads, Loads, "a Loads (archquake.geometry.loads)")
    dead = loads.without_traffic()
    res = loaded_collapse(seismic_case(arch, dead, g=g, vertical=vertical), method.value)
    opposite = loaded_collapse(seismic_case(arch, dead, direction=-1, g=g, vertical=vertical),
                               method.value)
    return LimitAnalysis(
        arch=arch,
        collapse_acceleration_g=res.multiplier,
        mechanism=res.mechanism,
        joint_forces=res.joint_forces,
        static_collapse_acceleration_g=res.static_multiplier,
        kinematic_collapse_acceleration_g=res.kinematic_multiplier,
        method=method,
        g=float(g),
        loads=loads,
        carried=block_extras(arch, dead, g=g),
        opposite_collapse_acceleration_g=opposite.multiplier,
        hinge_count=res.hinge_count,
        vertical_g=vertical,
    )


def coupled_vertical_analysis(
    arch: VoussoirChain, ratio: float, *, method: Method | str = Method.STATIC,
    g: float = STANDARD_GRAVITY, loads: Loads | None = None, xtol: float = 1e-10,
) -> LimitAnalysis:
    """The collapse under a horizontal acceleration lambda g with a concurrent downward
    vertical ratio * lambda g (EN 1998-5's pseudo-static k_v = 0.5 k_h or 0.33 k_h, taken
    with the sign that lightens the arch).

    Solves lambda = lambda(vertical = -ratio * lambda) by Brent's method on [0, lambda(0)]; for
    an arch whose loads are all body forces this is lambda(0) / (1 + ratio lambda(0)).

    Parameters
    ----------
    ratio : float
        k_v / k_h, in [0, 1].
    method, g, loads
        As in `limit_analysis`.

    Returns
    -------
    LimitAnalysis
        With ``vertical_g`` = -ratio * lambda.
    """
    from scipy.optimize import brentq

    ratio = require_range("vertical ratio", ratio, 0.0, 1.0, low_open=False, high_open=False)
    base = limit_analysis(arch, method=method, g=g, loads=loads)
    lam0 = base.collapse_acceleration_g
    if ratio == 0.0:
        return base

    def gap(lam: float) -> float:
        return limit_analysis(arch, method=method, g=g, loads=loads,
                              vertical=-ratio * lam).collapse_acceleration_g - lam

    lam = brentq(gap, 0.0, lam0, xtol=xtol)
    return limit_analysis(arch, method=method, g=g, loads=loads, vertical=-ratio * lam)


def hinges_of(arch: VoussoirChain) -> HingeMechanism:
    """The hinges of ``arch``: those of the equivalent static analysis, oriented so that a ground
    acceleration towards -x opens them (the paper's Figure 1).

    Goes through `archquake.limit.limit_analysis` (the line-of-thrust method), so arches of
    any number of voussoirs are handled, hinges may sit anywhere (a hinge above a springing
    leaves the voussoirs below it on the ground), and an arch too thin to stand raises
    `UnstableArchError` naming its minimum thickness.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch of `archquake.geometry` (a chain of blocks between two supports).

    Returns
    -------
    HingeMechanism
        ``load_direction == +1``.

    Examples
    --------
    >>> import math
    >>> m = hinges_of(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> m.joints, m.load_direction
    ((0, 3, 5, 7), 1)
    """
    try:
        hash(arch)
    except TypeError:  # a chain that cannot be a key: not memoised
        return _hinges(arch)
    return _memoised_hinges(arch)


def _hinges(arch: VoussoirChain) -> HingeMechanism:
    mech = certified_mechanism(arch)
    if mech is None:
        mech = limit_analysis(arch).mechanism
    return mech if mech.load_direction > 0 else mech.mirrored()


#: `hinges_of` once per arch (arches are frozen; the DEM's and the rigid chain's
#: assemblies of one arch, and the verdict's onset, all ask for its hinges).
_memoised_hinges = functools.lru_cache(maxsize=128)(_hinges)


#: Largest arch whose hinges `certified_mechanism` looks for (it enumerates 16 C(n+1, 4)
#: mechanisms: 1 120 at n = 7, 95 760 at n = 20, a few ms); above it the linear program does.
CERTIFIED_VOUSSOIRS = 20
#: Margins of the certificate, relative to the largest of their kind: a joint that is not a
#: hinge keeps the line of thrust inside its section by more than this (of the largest
#: half-depth times normal force), and each hinge's dual (its rotation in the virtual-work
#: equation) exceeds this of the largest. Both far above the linear program's tolerances
#: (1e-7 relative on the duals, HiGHS's 1e-7 on feasibility is absolute in these units).
CERTIFICATE_MARGIN = 1e-5


def certified_mechanism(arch: VoussoirChain) -> HingeMechanism | None:
    """The collapse mechanism of the static linear program, found without solving it, where
    its optimum can be proven; None where it cannot (then call `limit_analysis`).

    The least-multiplier four-hinge mechanism of the enumeration
    (`kinematic_collapse`) proposes a vertex of the static
    program: the equilibrium with the line of thrust through its four hinges
    (`collapse_state`). That vertex is the program's optimum,
    and its only one, when it is primal feasible with every other constraint strictly slack
    (the line of thrust inside every other joint) and dual feasible with every dual strictly
    positive (the objective's gradient a positive combination of the four hinge constraints'):
    the optimality conditions of linear programming, checked with the margin
    `CERTIFICATE_MARGIN`. The program's duals are then these four, so
    `static_collapse` reads the same hinges from them. Arches of
    more than `CERTIFIED_VOUSSOIRS` voussoirs, ties between mechanisms, a line of thrust
    that grazes a fifth joint, a multiplier at `MAX_MULTIPLIER`
    and arches that cannot stand are left to the program (which reports them).

    Examples
    --------
    >>> import math
    >>> certified_mechanism(Arch(10.0, 1.5, math.radians(157.5), 7)).joints
    (0, 3, 5, 7)
    """
    if arch.voussoirs > CERTIFIED_VOUSSOIRS:
        return None
    try:
        _, mech = kinematic_collapse(arch)
    except InvalidParameterError:
        return None
    if len(set(mech.joints)) < 4:
        return None
    a_ub, b_ub = _constraints(arch)  # A x <= b over x = (H, V, M0, lambda)
    rows = [2 * j + (1 if face is Face.EXTRADOS else 0)
            for j, face in zip(mech.joints, mech.faces, strict=True)]
    a_act = a_ub[rows]
    try:
        x = np.linalg.solve(a_act, b_ub[rows])
        duals = np.linalg.solve(a_act.T, np.array([0.0, 0.0, 0.0, 1.0]))  # max lambda
    except np.linalg.LinAlgError:
        return None
    lam = float(x[3])
    if not (0.0 < lam < MAX_MULTIPLIER * (1 - 1e-9)) or not np.all(np.isfinite(x)):
        return None
    slack = b_ub - a_ub @ x
    others = np.ones(slack.size, dtype=bool)
    others[rows] = False
    # the section's size at each constraint: half-depth times normal force (b - A x at a
    # constraint's partner face is 2 h N)
    size = float(np.max(np.abs(slack)))
    if size <= 0.0 or np.any(slack[others] <= CERTIFICATE_MARGIN * size):
        return None
    if np.any(duals <= CERTIFICATE_MARGIN * float(np.max(np.abs(duals)))):
        return None
    return mech


__all__ = [
    "CERTIFICATE_MARGIN",
    "CERTIFIED_VOUSSOIRS",
    "LimitAnalysis",
    "certified_mechanism",
    "coupled_vertical_analysis",
    "hinges_of",
    "Method",
    "collapse_joint_forces",
    "limit_analysis",
    "min_thickness_ratio",
]
