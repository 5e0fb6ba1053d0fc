"""Kinematic (upper-bound) limit analysis: virtual work over every four-hinge mechanism.

For every admissible four-hinge mechanism with hinges at voussoir joints (quadruples of joints
``a < b < c < d`` in [0, n], each hinge on the intrados or the extrados, with a sense of
motion that opens all four hinges on their free faces), the horizontal load factor at which
it is in limit equilibrium follows from virtual work at the undisplaced configuration:

    lambda = sum(m_k v_ky) / sum(m_k v_kx),

v_k being the centroid velocities of the opening motion (gravity does ``-g sum m v_y``, the
load ``lambda g`` towards +x does ``lambda g sum m v_x``). By the upper-bound theorem the
collapse multiplier is the least such lambda over mechanisms that the load drives
(``sum m v_x > 0``). `HingeMechanism.collapse_acceleration_g` is the scalar reference; here
the enumeration is vectorised with prefix sums of the voussoirs' masses and first moments, so
each mechanism costs O(1).

The enumeration grows as 16 C(n+1, 4) ~ (2/3) n^4 mechanisms: about 8 million for n = 60,
which is the largest ``n`` accepted (`MAX_KINEMATIC_VOUSSOIRS`, about a second). Larger
arches use the static method (`archquake.limit.static`), which is exact for any ``n``.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch  # noqa: F401  (doctests)
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import Face, HingeMechanism
from archquake.geometry.planar import perp

#: Largest number of voussoirs the exhaustive mechanism enumeration accepts.
MAX_KINEMATIC_VOUSSOIRS = 60


@dataclass(frozen=True)
class MechanismSet:
    """Every admissible four-hinge mechanism of an arch, as packed arrays (m mechanisms).

    A mechanism opens with link AB turning at ``rates[:, 0]`` (rad per unit phi-dot, +1 or -1:
    the sense that opens all four hinges on their free faces, counter-clockwise positive), the
    coupler BC at ``rates[:, 1]`` and CD at ``rates[:, 2]``, at the undisplaced configuration;
    these are `HingeMechanism.rates` for every mechanism at once.

    Attributes
    ----------
    joints : ndarray of int, shape (m, 4)
        Hinge joints A, B, C, D.
    faces : ndarray of int, shape (m, 4)
        0 for intrados, 1 for extrados.
    points : ndarray, shape (m, 4, 2)
        Hinge points A, B, C, D, m.
    rates : ndarray, shape (m, 3)
        Link angular velocities (AB, BC, CD) per unit opening rate, rad/rad.
    """

    joints: np.ndarray
    faces: np.ndarray
    points: np.ndarray
    rates: np.ndarray

    def __len__(self) -> int:
        return int(self.joints.shape[0])

    def mechanism(self, i: int, arch: VoussoirChain) -> HingeMechanism:
        """Mechanism ``i`` as a `HingeMechanism` of ``arch``."""
        return HingeMechanism(
            arch,
            tuple(int(j) for j in self.joints[i]),  # type: ignore[arg-type]
            tuple(Face.EXTRADOS if f else Face.INTRADOS for f in self.faces[i]),  # type: ignore[arg-type]
        )

    def subset(self, mask: np.ndarray) -> MechanismSet:
        return MechanismSet(self.joints[mask], self.faces[mask], self.points[mask], self.rates[mask])


def _check_size(arch: VoussoirChain) -> None:
    n = arch.voussoirs
    if n > MAX_KINEMATIC_VOUSSOIRS:
        raise InvalidParameterError(
            f"the kinematic enumeration of four-hinge mechanisms needs voussoirs <= "
            f"{MAX_KINEMATIC_VOUSSOIRS} (it grows as n^4), got {n}; use the static method"
        )


def admissible_mechanisms(arch: VoussoirChain) -> MechanismSet:
    """Every four-hinge mechanism of ``arch`` with hinges at joints that can open.

    Quadruples of joints ``a < b < c < d`` in [0, n], each hinge on the intrados or the
    extrados, kept when one sense of motion opens all four hinges on their free faces (the
    sense is returned in ``rates[:, 0]``). Mechanisms driven by a load towards +x and towards
    -x are both included, and so are those a horizontal load does not drive at all (symmetric
    ones).

    Parameters
    ----------
    arch : VoussoirChain
        Any arch of `archquake.geometry` (a chain of blocks between two supports).
        With at most `MAX_KINEMATIC_VOUSSOIRS` voussoirs.

    Returns
    -------
    MechanismSet
    """
    _check_size(arch)
    n = arch.voussoirs
    quads = np.array(list(combinations(range(n + 1), 4)), dtype=np.int64)  # (q, 4)
    ends = np.stack([arch.intrados_points, arch.extrados_points])  # (2, n+1, 2)
    out_j, out_f, out_p, out_r = [], [], [], []
    for code in range(16):
        bits = np.array([(code >> i) & 1 for i in range(4)])
        pa, pb, pc, pd = (ends[bits[i]][quads[:, i]] for i in range(4))
        # four-bar rates for omega_AB = 1 (same algebra as geometry.fourbar.link_rates)
        jcb, jcd, jba = perp(pc - pb), perp(pc - pd), perp(pb - pa)
        det = -jcb[:, 0] * jcd[:, 1] + jcd[:, 0] * jcb[:, 1]
        scale = np.hypot(*(pc - pb).T) * np.hypot(*(pc - pd).T)
        ok = np.abs(det) > 1e-12 * scale
        det = np.where(ok, det, 1.0)
        w_bc = (jba[:, 0] * jcd[:, 1] - jcd[:, 0] * jba[:, 1]) / det
        w_cd = (-jcb[:, 0] * jba[:, 1] + jba[:, 0] * jcb[:, 1]) / det
        # relative rotations at A, B, C, D must all open the hinges on their free faces
        rel = np.column_stack([np.ones_like(w_bc), w_bc - 1.0, w_cd - w_bc, -w_cd])
        need = np.where(bits == 1, 1.0, -1.0)  # Face.opening_sign
        tiny = 1e-12 * np.max(np.abs(rel), axis=1)
        ok &= np.all(np.abs(rel) > tiny[:, None], axis=1)
        sign = np.sign(rel)
        plus = np.all(sign == need, axis=1)
        minus = np.all(sign == -need, axis=1)
        ok &= plus | minus
        sense = np.where(plus, 1.0, -1.0)
        if np.any(ok):
            out_j.append(quads[ok])
            out_f.append(np.broadcast_to(bits, (int(ok.sum()), 4)))
            out_p.append(np.stack([pa[ok], pb[ok], pc[ok], pd[ok]], axis=1))
            out_r.append(sense[ok, None] * np.column_stack([np.ones(int(ok.sum())), w_bc[ok], w_cd[ok]]))
    if not out_j:
        return MechanismSet(np.zeros((0, 4), np.int64), np.zeros((0, 4), np.int64),
                            np.zeros((0, 4, 2)), np.zeros((0, 3)))
    return MechanismSet(np.vstack(out_j), np.vstack(out_f), np.concatenate(out_p),
                        np.vstack(out_r))


def mechanism_multipliers(arch: VoussoirChain) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Virtual-work load factor of every admissible four-hinge mechanism under a load towards +x.

    Parameters
    ----------
    arch : Arch
        With at most `MAX_KINEMATIC_VOUSSOIRS` voussoirs.

    Returns
    -------
    joints : ndarray of int, shape (m, 4)
        Hinge joints A, B, C, D of each mechanism.
    faces : ndarray of int, shape (m, 4)
        0 for intrados, 1 for extrados.
    multipliers : ndarray, shape (m,)
        lambda (in g) of each mechanism; only mechanisms that a load towards +x drives
        (positive work) are returned.
    """
    mechs = admissible_mechanisms(arch)
    m = arch.voussoir_masses
    cm = np.concatenate([[0.0], np.cumsum(m)])  # mass of voussoirs [0, k)
    cs = np.vstack([np.zeros((1, 2)), np.cumsum(m[:, None] * arch.voussoir_centroids, axis=0)])
    a, b, c, d = mechs.joints.T
    m_bc = cm[c] - cm[b]
    s_ab, s_bc, s_cd = cs[b] - cs[a], cs[c] - cs[b], cs[d] - cs[c]
    m_ab, m_cd = cm[b] - cm[a], cm[d] - cm[c]
    pa, pb, pd = mechs.points[:, 0], mechs.points[:, 1], mechs.points[:, 3]
    w_ab, w_bc, w_cd = mechs.rates.T
    # sum of m v over the three links, per unit opening rate
    p_sum = (
        w_ab[:, None] * (perp(s_ab - m_ab[:, None] * pa) + m_bc[:, None] * perp(pb - pa))
        + w_bc[:, None] * perp(s_bc - m_bc[:, None] * pb)
        + w_cd[:, None] * perp(s_cd - m_cd[:, None] * pd)
    )
    ok = p_sum[:, 0] > 0.0  # a load towards +x does positive work
    return mechs.joints[ok], mechs.faces[ok], p_sum[ok, 1] / p_sum[ok, 0]


def kinematic_collapse(arch: VoussoirChain) -> tuple[float, HingeMechanism]:
    """Least virtual-work load factor over all four-hinge mechanisms (load towards +x).

    Returns
    -------
    multiplier : float
        Collapse acceleration in g (upper-bound theorem; exact over the joint hinges).
    mechanism : HingeMechanism
        The governing mechanism.

    Examples
    --------
    >>> import math
    >>> lam, mech = kinematic_collapse(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> round(lam, 3), mech.joints
    (0.37, (0, 3, 5, 7))
    """
    joints, faces, lam = mechanism_multipliers(arch)
    if lam.size == 0:
        raise InvalidParameterError(
            "no four-hinge mechanism at the joints is driven by a horizontal load for this arch"
        )
    i = int(np.argmin(lam))
    mech = HingeMechanism(
        arch,
        tuple(int(j) for j in joints[i]),  # type: ignore[arg-type]
        tuple(Face.EXTRADOS if f else Face.INTRADOS for f in faces[i]),  # type: ignore[arg-type]
    )
    return float(lam[i]), mech


__all__ = [
    "MAX_KINEMATIC_VOUSSOIRS",
    "MechanismSet",
    "admissible_mechanisms",
    "kinematic_collapse",
    "mechanism_multipliers",
]
