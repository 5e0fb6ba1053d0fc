"""Impact when the hinges close (paper Eqs. 4a-4e) and the coefficient of restitution (Eqs. 5-7).

At closure the arch passes from a mechanism to its mirror image. Positions do not change during
the impact; velocities jump under impulsive forces. As in Housner's rocking block, the impulse at
each hinge section acts on the opposite face from the hinge that was open (the mechanism's
``impact_points``). Unknowns: the impulses J_A = F_A dt and J_D = F_D dt at the supports (x and y)
and the post-impact rate phi'_f of the mirrored mechanism. Equations (impulse-momentum):

* (4a, 4b) linear momentum of the whole arch in x and y;
* (4c) angular momentum of the whole arch about the centre O;
* (4d) angular momentum about the impact point at B of the part left of B's joint;
* (4e) angular momentum about the impact point at C of the part right of C's joint.

The internal impulses at B and C pass through the points the moments are taken about, and
self-weight is neglected during the impact. All five equations are linear and homogeneous in the
pre-impact rate, so the post-impact rate is ``c_v`` times the pre-impact rate's magnitude, with
``c_v`` a function of t/R, the embrace and the number of voussoirs only.

Impact laws
-----------
`solve_impact` holds every impact law behind one signature (``law=``):

``"paper"``
    Eqs. 4a-4e above, the post-impact mechanism the mirror image (the paper's assumption). Kept
    to reproduce the paper; it can create energy (c_T > 1) or give c_v < 0 for arches whose
    hinges are not symmetric.
``"chain"``
    The impact law of a chain of rigid voussoirs (`archquake.mechanism.impact_chain`):
    the post-impact mechanism is the four-hinge mechanism of maximum restitution (conservation of
    its generalised momentum), checked by the impulse line; never creates energy; reports its
    validity.
``"mirror"``
    The chain law with the post-impact mechanism forced to be the mirror image: equal to
    ``"paper"`` for mechanisms with symmetric hinges, c_T <= 1 always.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from archquake._validate import require_range
from archquake.errors import InvalidParameterError
from archquake.geometry.hinges import HingeMechanism
from archquake.geometry.planar import cross
from archquake.ranges import IMPACT_LAWS  # the laws' names (the command line reads them there)

if TYPE_CHECKING:
    from archquake.mechanism.impact_chain import ChainImpact


#: One line of meaning for each validity (what ``archquake run`` prints and the plots show).
VALIDITY_MEANING = {
    "assumed": "Eq. 4 with the paper's assumed mirror mechanism (not checked; c_T <= 1, c_v >= 0)",
    "four_hinge": "the impact response is exactly a four-hinge mechanism",
    "near_four_hinge": "the impact response is a four-hinge mechanism within 1 % of its energy",
    "at_rest": "the impact stops the arch (perfectly plastic)",
    "outside": "the impact law does not describe this arch's impacts",
    "not_four_hinge": "the impact response is not a four-hinge mechanism",
    "beyond_set": "the impact's post mechanism is beyond the mechanisms tabulated for the history",
}

#: The chain laws' validities under which the impact is described (`ImpactSolution.describes`).
DESCRIBED = ("four_hinge", "near_four_hinge", "at_rest")


def check_restitution(value: object, name: str = "restitution") -> float | None:
    """The one check of a prescribed coefficient of restitution c_v: None (the law's own) or a
    number in [0, 1] (0 = perfectly plastic: the arch stops at the impact; above 1 an impact
    would create energy). ``name`` is the option as the caller's user typed it
    (``--restitution`` on the command line)."""
    if value is None:
        return None
    shown = "[0, 1] (c_v, 0 = perfectly plastic)"
    try:
        return require_range(name, value, 0.0, 1.0, low_open=False, high_open=False, shown=shown)
    except InvalidParameterError:
        raise InvalidParameterError(f"{name} must be in {shown}, got {value!r}") from None


def check_impact_law(law: object, name: str = "impact") -> str:
    """The one check of an impact law's name (`IMPACT_LAWS`)."""
    if not isinstance(law, str) or law not in IMPACT_LAWS:
        raise InvalidParameterError(f"{name} must be one of {', '.join(IMPACT_LAWS)}, got {law!r}")
    return str(law)


@dataclass(frozen=True)
class ImpactSolution:
    """Solution of the impact problem for a unit pre-impact closing rate (phi'_i = -1 rad/s).

    Attributes
    ----------
    restitution_cv : float
        c_v = phi'_f / |phi'_i| (Eq. 5), dimensionless.
    restitution_ct : float
        c_T = T_f / T_i (Eq. 6), from the kinetic energies; equals c_v^2 (Eq. 7).
    impulse_a, impulse_d : ndarray, shape (2,)
        Impulses J_A and J_D acting on the arch, N s per (rad/s) of closing rate.
    energy_gain : bool
        True if c_T > 1: the five balances then create kinetic energy, which a real impact
        cannot; archquake reports it rather than hiding it.
    admissible : bool
        False if c_v < 0: the balances then start the mirror mechanism in its closing sense,
        which is not an admissible motion (seen for some thick, shallow arches);
        `archquake.mechanism.simulate` then treats the impact as perfectly plastic.
    residual : float
        Max |A x - b| of the 5x5 solve, relative to |b| (a check that the solve is sound); for
        the chain laws, the consistency of the impulse line's four hinge conditions.
    law : str
        The impact law (`IMPACT_LAWS`).
    post : HingeMechanism or None
        The post-impact mechanism (the mirror image for ``"paper"`` and ``"mirror"``; chosen for
        ``"chain"``; None if the arch stops or no four-hinge mechanism is the response).
    validity : str
        ``"four_hinge"``, ``"at_rest"``, ``"near_four_hinge"`` or ``"outside"`` for the chain laws
        (see `ChainImpact`); for ``"paper"``,
        ``"assumed"`` (not checked), or ``"outside"`` when it creates energy or is inadmissible.
    chain : ChainImpact or None
        The chain laws' full solution (impulse line, exact response, ...).
    """

    restitution_cv: float
    restitution_ct: float
    impulse_a: np.ndarray
    impulse_d: np.ndarray
    energy_gain: bool
    residual: float
    law: str = "paper"
    post: HingeMechanism | None = field(default=None, repr=False)
    validity: str = "assumed"
    chain: ChainImpact | None = field(default=None, repr=False)

    @property
    def admissible(self) -> bool:
        return self.restitution_cv >= 0.0

    def describes(self, prescribed: bool = False) -> bool:
        """True if this law describes the impact, so that a verdict reached after it stands.

        * ``"paper"``: the c_v of Eq. 4 is usable: no energy gain (c_T <= 1) and admissible
          (c_v >= 0). A prescribed c_v (``prescribed=True``, in [0, 1]) replaces that number
          and keeps the paper's assumed mirror mechanism, so it describes the impact.
        * ``"chain"``, ``"mirror"``: the response is a four-hinge mechanism (validity
          ``four_hinge``, ``near_four_hinge``) or rest (``at_rest``); ``outside`` and
          ``not_four_hinge`` do not describe it, whatever c_v is prescribed (a prescription
          replaces the number, not the mechanism).

        The rule that turns this into `archquake.outcome.Outcome.INDETERMINATE` is
        `archquake.outcome.qualify`.
        """
        if self.law == "paper":
            return bool(prescribed or (not self.energy_gain and self.restitution_cv >= 0.0))
        return self.validity in DESCRIBED

    def to_dict(self) -> dict:
        return {
            "restitution_cv": self.restitution_cv,
            "restitution_ct": self.restitution_ct,
            "energy_gain": self.energy_gain,
            "admissible": self.admissible,
            "law": self.law,
            "validity": self.validity,
            "post_hinges": None if self.post is None else [h.to_dict() for h in self.post.hinges],
        }


def _momenta(mech: HingeMechanism, rate: float):
    """Per-voussoir linear momentum (n, 2) and spin angular momentum (n,) for phi-dot = rate."""
    arch = mech.arch
    v, w = mech.voussoir_velocities()
    p = arch.voussoir_masses[:, None] * v * rate
    spin = arch.voussoir_inertias * w * rate
    return p, spin


def _angular(arch, p, spin, about, mask) -> float:
    r = arch.voussoir_centroids[mask] - about
    return float(cross(r, p[mask]).sum() + spin[mask].sum())


def _momenta_mirrored(mech: HingeMechanism, rate: float):
    """Momenta of the mirror-image motion: voussoir n-1-k moves as the mirror of voussoir k.

    The rate is that of the mirror image of link AB (the paper's theta'-dot, measured in the
    opposite sense), so the post-impact kinetic energy per unit rate equals the pre-impact one.
    """
    p, spin = _momenta(mech, rate)
    return (p * np.array([-1.0, 1.0]))[::-1], -spin[::-1]


def solve_impact(before: HingeMechanism, law: str = "paper") -> ImpactSolution:
    """The impact of the mechanism ``before`` closing, under the impact law ``law``.

    Parameters
    ----------
    before : HingeMechanism
        The mechanism whose hinges close (pre-impact rate -1 rad/s, i.e. closing).
    law : {"paper", "chain", "mirror"}
        See the module docstring. Default "paper" (Eqs. 4a-4e).

    Returns
    -------
    ImpactSolution
    """
    check_impact_law(law, "impact law")
    if law == "paper":
        return _solve_paper(before)
    if law in ("chain", "mirror"):
        from archquake.mechanism.impact_chain import chain_impact

        sol = chain_impact(before, post="mirror" if law == "mirror" else None)
        n = before.arch.voussoirs
        zero = np.zeros(2)
        imp = sol.impulses
        return ImpactSolution(
            restitution_cv=sol.restitution_cv,
            restitution_ct=sol.restitution_ct,
            impulse_a=zero if imp is None else imp.force[0].copy(),
            impulse_d=zero if imp is None else -imp.force[n].copy(),
            energy_gain=False,
            residual=0.0,
            law=law,
            post=sol.post,
            validity=sol.validity,
            chain=sol,
        )
    raise AssertionError(law)  # unreachable: check_impact_law above


def _solve_paper(before: HingeMechanism) -> ImpactSolution:
    """Solve Eqs. 4a-4e for the mechanism ``before`` closing and its mirror image opening.

    The post-impact mechanism is the mirror image of ``before`` (the paper's assumption of
    hinges symmetric to those before the impact), and its rate is that of the mirror image of
    link AB, measured in the opposite sense (the paper's primed quantities), so that
    c_T = c_v^2 (Eq. 7) holds exactly.

    Parameters
    ----------
    before : HingeMechanism
        The mechanism whose hinges close (pre-impact rate -1 rad/s, i.e. closing).

    Returns
    -------
    ImpactSolution
    """
    arch = before.arch
    n = arch.voussoirs
    pa, pb, pc, pd = before.impact_points
    p_i, s_i = _momenta(before, -1.0)  # closing
    k_p, k_s = _momenta_mirrored(before, 1.0)  # per unit post-impact opening rate
    everything = np.ones(n, dtype=bool)
    left_of_b = np.arange(n) < before.joints[1]
    right_of_c = np.arange(n) >= before.joints[2]
    origin = np.zeros(2)

    # unknowns x = [Jax, Jay, Jdx, Jdy, phidot_f];  sum(momentum after) - sum(before) = impulses
    mat = np.zeros((5, 5))
    rhs = np.zeros(5)
    # (4a, 4b) linear momentum
    mat[0] = [1.0, 0.0, 1.0, 0.0, -k_p[:, 0].sum()]
    mat[1] = [0.0, 1.0, 0.0, 1.0, -k_p[:, 1].sum()]
    rhs[0] = -p_i[:, 0].sum()
    rhs[1] = -p_i[:, 1].sum()
    # (4c) angular momentum about O of the whole arch
    mat[2] = [-pa[1], pa[0], -pd[1], pd[0], -_angular(arch, k_p, k_s, origin, everything)]
    rhs[2] = -_angular(arch, p_i, s_i, origin, everything)
    # (4d) about the impact point at B, the part left of B (impulse J_A only)
    ra = pa - pb
    mat[3] = [-ra[1], ra[0], 0.0, 0.0, -_angular(arch, k_p, k_s, pb, left_of_b)]
    rhs[3] = -_angular(arch, p_i, s_i, pb, left_of_b)
    # (4e) about the impact point at C, the part right of C (impulse J_D only)
    rd = pd - pc
    mat[4] = [0.0, 0.0, -rd[1], rd[0], -_angular(arch, k_p, k_s, pc, right_of_c)]
    rhs[4] = -_angular(arch, p_i, s_i, pc, right_of_c)

    x = np.linalg.solve(mat, rhs)
    residual = float(np.max(np.abs(mat @ x - rhs)) / max(np.max(np.abs(rhs)), 1e-300))
    cv = float(x[4])
    t_before = _kinetic(p_i, s_i, arch)
    t_after = _kinetic(k_p * cv, k_s * cv, arch)
    ct = t_after / t_before
    gain = bool(ct > 1.0 + 1e-12)
    return ImpactSolution(
        restitution_cv=cv,
        restitution_ct=float(ct),
        impulse_a=x[0:2].copy(),
        impulse_d=x[2:4].copy(),
        energy_gain=gain,
        residual=residual,
        law="paper",
        post=before.mirrored(),
        validity="outside" if (gain or cv < 0.0) else "assumed",
    )


def _kinetic(p: np.ndarray, spin: np.ndarray, arch) -> float:
    """Kinetic energy from per-voussoir momenta: sum |p|^2 / 2m + L^2 / 2I, J."""
    return 0.5 * float(
        ((p**2).sum(axis=1) / arch.voussoir_masses).sum() + (spin**2 / arch.voussoir_inertias).sum()
    )


__all__ = ["DESCRIBED", "IMPACT_LAWS", "VALIDITY_MEANING", "ImpactSolution", "check_impact_law",
           "check_restitution", "solve_impact"]
