"""The one place that prepares a mechanism from an arch.

"Which hinges does this arch have" has one answer, :func:`hinges_of`: those of the equivalent
static analysis (:func:`archquake.limit.limit_analysis`, the paper's assumption), oriented so that
a ground acceleration towards -x opens them (the paper's Figure 1). :class:`PreparedMechanism`
packs that mechanism for the compiled kernels (:func:`pack_mechanism`) with its impact solution
(Eq. 4), once, and is what the time histories (:func:`archquake.mechanism.simulate`), the domain
search (:mod:`archquake.domains`), the thrust line in motion (:mod:`archquake.thrust`) and the
distinct-element assemblies (:mod:`archquake.dem.assembly`) all start from.

Its properties are the mechanism's scalar characteristics, so that no code outside
:mod:`archquake.mechanism` reads the packed layout:

* :attr:`PreparedMechanism.collapse_acceleration_g`: lambda, the equivalent static collapse
  acceleration in g (the onset threshold of hinging);
* :attr:`PreparedMechanism.critical_rotation`: the crest of the potential, rad;
* :attr:`PreparedMechanism.toggle_rotation`: the toggle of the linkage, rad;
* :attr:`PreparedMechanism.restitution`: the c_v the time histories use.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch  # noqa: F401  (doctests)
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import HingeMechanism
from archquake.mechanism._kernels import linkage_limits_compiled
from archquake.mechanism.impact import (
    ImpactSolution,
    check_impact_law,
    check_restitution,
    solve_impact,
)
from archquake.mechanism.kinematics import (
    AX,
    AY,
    B0X,
    B0Y,
    BRANCH,
    C0X,
    C0Y,
    DX,
    DY,
    G0,
    H0,
    LBC,
    LCD,
    LENGTH,
    LINK0,
    MASS,
    PACKED_SIZE,
    PHI_CRIT,
    PHI_TOGGLE,
    SIGMA,
    eom_terms,
)

#: Samples of the crest/toggle search (:func:`archquake.mechanism.kinematics.linkage_limits`).
_LIMIT_SAMPLES = 4000


def hinges_of(arch: VoussoirChain) -> HingeMechanism:
    """The hinges of ``arch``: those of the equivalent static analysis, oriented so that a ground
    acceleration towards -x opens them (the paper's Figure 1).

    Goes through :func:`archquake.limit.limit_analysis` (the line-of-thrust method), so arches of
    any number of voussoirs are handled, hinges may sit anywhere (a hinge above a springing
    leaves the voussoirs below it on the ground), and an arch too thin to stand raises
    :class:`~archquake.errors.UnstableArchError` naming its minimum thickness.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch of :mod:`archquake.geometry` (a chain of blocks between two supports).

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
    from archquake.limit import limit_analysis

    mech = limit_analysis(arch).mechanism
    return mech if mech.load_direction > 0 else mech.mirrored()


def pack_mechanism(mech: HingeMechanism) -> np.ndarray:
    """Pack a :class:`HingeMechanism` into the float64 array the kernels read, shape (30,).

    The layout is that of :mod:`archquake.mechanism.kinematics`. Link masses and inertias are
    sums over the links' voussoirs (parallel-axis theorem); G0, H0 are the gravity and ground
    terms of the equation of motion at phi = 0; the critical and toggle rotations come from
    :func:`~archquake.mechanism.kinematics.linkage_limits`.
    """
    arch = mech.arch
    a, b, c, d = mech.points
    out = np.zeros(PACKED_SIZE)
    out[AX:AY + 1], out[B0X:B0Y + 1], out[C0X:C0Y + 1], out[DX:DY + 1] = a, b, c, d
    out[SIGMA] = float(mech.opening_sign)
    u0, dv0 = c - b, d - b
    out[BRANCH] = 1.0 if (dv0[0] * u0[1] - dv0[1] * u0[0]) >= 0.0 else -1.0
    out[LBC] = math.hypot(*(c - b))
    out[LCD] = math.hypot(*(c - d))
    pivots = (a, b, d)
    for k, (rng, pivot) in enumerate(zip(mech.link_voussoirs, pivots)):
        idx = np.fromiter(rng, dtype=int)
        m = arch.voussoir_masses[idx]
        r = arch.voussoir_centroids[idx]
        mass = float(m.sum())
        centroid = (m[:, None] * r).sum(axis=0) / mass
        inertia = float(arch.voussoir_inertias[idx].sum() + (m * ((r - centroid) ** 2).sum(axis=1)).sum())
        base = LINK0 + 4 * k
        out[base] = mass
        out[base + 1:base + 3] = centroid - pivot
        out[base + 3] = inertia
    out[MASS] = arch.mass
    out[LENGTH] = arch.radius
    _, _, _, gg, hh = eom_terms(out, 0.0)
    out[G0], out[H0] = gg, hh
    crit, toggle = linkage_limits_compiled(out, _LIMIT_SAMPLES)
    out[PHI_CRIT], out[PHI_TOGGLE] = crit, toggle
    return out


@dataclass(frozen=True)
class PreparedMechanism:
    """A mechanism packed for the kernels, with its impact solution (reusable across runs).

    Build it with :meth:`build` (from an arch, a mechanism or a prepared mechanism).

    Attributes
    ----------
    mechanism : HingeMechanism
        The first mechanism, opened by a ground acceleration towards -x.
    packed : ndarray, shape (30,)
        :func:`pack_mechanism` of it (the kernels' input; read it through the properties).
    impact : ImpactSolution
        Eq. 4 solved for this mechanism closing.

    Examples
    --------
    >>> import math
    >>> p = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> round(p.collapse_acceleration_g, 4), round(p.critical_rotation, 3) < round(p.toggle_rotation, 3)
    (0.37, True)
    """

    mechanism: HingeMechanism
    packed: np.ndarray
    impact: ImpactSolution

    @property
    def collapse_acceleration_g(self) -> float:
        """lambda: the equivalent static collapse acceleration of the mechanism, in g.

        The onset threshold the kernels use, G0 / |H0| (the gravity and ground terms of Eq. 2 at
        phi = 0): equal, by virtual work, to ``LimitAnalysis.collapse_acceleration_g`` for the
        hinges of the equivalent static analysis.
        """
        return float(self.packed[G0] / abs(self.packed[H0]))

    @property
    def critical_rotation(self) -> float:
        """Crest of the potential, rad: beyond it gravity can no longer close the mechanism."""
        return float(self.packed[PHI_CRIT])

    @property
    def toggle_rotation(self) -> float:
        """Rotation at which the linkage toggles (B, C, D collinear), rad (pi if it never does)."""
        return float(self.packed[PHI_TOGGLE])

    @property
    def restitution(self) -> float:
        """The c_v the time histories use: the impact model's, or 0 (perfectly plastic) where
        the model's is negative (inadmissible; see :class:`~archquake.mechanism.ImpactSolution`)."""
        return max(self.impact.restitution_cv, 0.0)

    def restitution_for(self, restitution: float | None = None) -> float:
        """The c_v a time history uses: ``restitution`` if prescribed (checked once, here:
        :func:`~archquake.mechanism.impact.check_restitution`, [0, 1]), else :attr:`restitution`
        (the impact law's own)."""
        cv = check_restitution(restitution)
        return self.restitution if cv is None else cv

    def describes_impact(self, restitution: float | None = None) -> bool:
        """True if the impact law (with ``restitution`` prescribed or not) describes this arch's
        impacts (:meth:`~archquake.mechanism.impact.ImpactSolution.describes`)."""
        return self.impact.describes(prescribed=restitution is not None)

    @classmethod
    def build(cls, arch_or_mechanism: VoussoirChain | HingeMechanism | PreparedMechanism,
              impact: str | None = None) -> PreparedMechanism:
        """Prepare an arch (its hinges: :func:`hinges_of`), a given mechanism (mirrored if a load
        towards -x opens it, so that the first mechanism is always the one a ground acceleration
        towards -x opens), or take a prepared mechanism. ``impact`` is the impact law
        (:data:`archquake.mechanism.impact.IMPACT_LAWS`); None: a prepared mechanism's own, or
        "paper" (Eq. 4). A prepared mechanism under another law is re-solved for that law only
        (the packed mechanism is kept)."""
        if impact is not None:
            check_impact_law(impact)
        if isinstance(arch_or_mechanism, PreparedMechanism):
            prep = arch_or_mechanism
            if impact is None or impact == prep.impact.law:
                return prep
            return replace(prep, impact=solve_impact(prep.mechanism, impact))
        impact = "paper" if impact is None else impact
        if isinstance(arch_or_mechanism, HingeMechanism):
            mech = arch_or_mechanism
            if mech.load_direction < 0:
                mech = mech.mirrored()
        elif isinstance(arch_or_mechanism, VoussoirChain):
            mech = hinges_of(arch_or_mechanism)
        else:
            raise InvalidParameterError(
                f"expected an Arch or a HingeMechanism, got {type(arch_or_mechanism).__name__}"
            )
        return cls(mech, pack_mechanism(mech), solve_impact(mech, impact))


__all__ = ["PreparedMechanism", "hinges_of", "pack_mechanism"]
