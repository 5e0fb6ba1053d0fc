"""Joint resultants and the line of thrust of a chain of rigid voussoirs, in any configuration.

This is the one place where the internal forces of an arch are computed from equilibrium. It
is pure statics: given where the joints are and what acts on each voussoir, the resultant
carried by every joint follows from the equilibrium of the voussoirs to its left, starting
from the left support reaction. The equivalent static (limit) analysis uses it at rest with
self-weight plus a horizontal body force; the line of thrust during motion (paper, section
"Line of thrust during motion") uses it on the displaced voussoirs with their inertia forces.

Conventions (SI, global axes: x right, y up, moments counter-clockwise positive):

- ``joint_points[j, 0]`` is the intrados end of joint j and ``joint_points[j, 1]`` its
  extrados end, shape (n+1, 2, 2). Joint 0 is the left springing, joint n the right one;
  voussoir k lies between joints k and k+1.
- The joint's unit vector ``u`` points from the intrados end to the extrados end (along the
  joint line); its normal ``nu`` is ``u`` turned 90 degrees clockwise, which points from the
  left part of the arch into the right part (tangential to the arch, towards increasing j).
- ``force[j]`` is the force that the part on the left of joint j (for j = 0: the left
  support) exerts on the part on its right. Compression is ``N = force . nu > 0``; the shear
  is ``V = force . u`` (positive towards the extrados); ``-force[n]`` is the right support
  reaction.
- ``moment[j]`` is the moment of that force about the joint's mid point (its centreline
  point); the line of action crosses the joint line at ``mid + e u`` with eccentricity
  ``e = -moment / N`` (positive towards the extrados). A line of thrust lies inside the
  section where ``-N h <= moment <= N h``, ``h`` being the joint's half-length.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class JointForces:
    """Resultants carried by the n+1 joints of an arch (see the module docstring for signs).

    Attributes
    ----------
    mid_points : ndarray, shape (n+1, 2)
        Centre of each joint, m.
    tangents : ndarray, shape (n+1, 2)
        Unit vector u along each joint, intrados to extrados.
    normals : ndarray, shape (n+1, 2)
        Unit normal nu of each joint, pointing from the left part into the right part.
    half_widths : ndarray, shape (n+1,)
        Half the length of each joint (t/2 for the undisplaced arch), m.
    force : ndarray, shape (n+1, 2)
        Force of the left part on the right part, N.
    normal : ndarray, shape (n+1,)
        Normal component N (compression positive), N.
    shear : ndarray, shape (n+1,)
        Shear component V along the joint (towards the extrados positive), N.
    moment : ndarray, shape (n+1,)
        Moment of the force about the joint's mid point, N m (counter-clockwise positive).
    """

    mid_points: np.ndarray
    tangents: np.ndarray
    normals: np.ndarray
    half_widths: np.ndarray
    force: np.ndarray
    normal: np.ndarray
    shear: np.ndarray
    moment: np.ndarray

    @property
    def eccentricity(self) -> np.ndarray:
        """Signed distance from the joint centre to where the line of action crosses the
        joint, towards the extrados positive, m, shape (n+1,); nan where N = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            e = -self.moment / self.normal
        return np.where(self.normal != 0.0, e, np.nan)

    @property
    def thrust_points(self) -> np.ndarray:
        """Where the line of action crosses each joint line (the line of thrust), m, (n+1, 2)."""
        return self.mid_points + self.eccentricity[:, None] * self.tangents

    @property
    def relative_eccentricity(self) -> np.ndarray:
        """Eccentricity over the joint's half-width, shape (n+1,): |.| <= 1 inside the section."""
        return self.eccentricity / self.half_widths

    @property
    def friction_ratio(self) -> np.ndarray:
        """|V| / N at every joint, the friction coefficient each joint needs not to slide,
        shape (n+1,); inf where N <= 0 (tension or no contact)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.abs(self.shear) / self.normal
        return np.where(self.normal > 0.0, r, np.inf)

    def admissible(self, rtol: float = 1e-9) -> bool:
        """True if every joint is in compression and its thrust point lies in the section."""
        n_scale = np.max(np.abs(self.normal), initial=0.0)
        m_scale = n_scale * np.max(self.half_widths, initial=0.0)
        return bool(
            np.all(self.normal >= -rtol * n_scale)
            and np.all(np.abs(self.moment) <= self.normal * self.half_widths + rtol * m_scale)
        )


def joint_frames(joint_points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Mid points, unit tangents u, unit normals nu and half-widths of the joints.

    Parameters
    ----------
    joint_points : array_like, shape (n+1, 2, 2)
        Intrados end ``[j, 0]`` and extrados end ``[j, 1]`` of each joint, m.

    Returns
    -------
    mid : (n+1, 2), u : (n+1, 2), nu : (n+1, 2), half : (n+1,)
    """
    p = np.asarray(joint_points, dtype=float)
    if p.ndim != 3 or p.shape[1:] != (2, 2):
        raise ValueError(f"joint_points must have shape (n+1, 2, 2), got {p.shape}")
    mid = 0.5 * (p[:, 0] + p[:, 1])
    d = p[:, 1] - p[:, 0]
    length = np.hypot(d[:, 0], d[:, 1])
    u = d / length[:, None]
    nu = np.column_stack([u[:, 1], -u[:, 0]])
    return mid, u, nu, 0.5 * length


def moments_about_origin(
    forces: np.ndarray, points: np.ndarray, couples: np.ndarray | float = 0.0
) -> np.ndarray:
    """Moment about the origin O of forces applied at points plus free couples, N m.

    Parameters
    ----------
    forces, points : array_like, shape (..., 2)
        Forces (N) and their points of application (m).
    couples : array_like, shape (...) or float
        Free couples (N m), counter-clockwise positive.

    Examples
    --------
    >>> moments_about_origin(np.array([[0.0, -10.0]]), np.array([[2.0, 5.0]]))
    array([-20.])
    """
    f = np.asarray(forces, dtype=float)
    p = np.asarray(points, dtype=float)
    return p[..., 0] * f[..., 1] - p[..., 1] * f[..., 0] + np.asarray(couples, dtype=float)


def joint_forces(
    joint_points: np.ndarray,
    forces: np.ndarray,
    moments: np.ndarray,
    reaction_force: np.ndarray,
    reaction_moment: float,
) -> JointForces:
    """Resultant at every joint from the equilibrium of the voussoirs to its left.

    Parameters
    ----------
    joint_points : array_like, shape (n+1, 2, 2)
        Intrados ``[j, 0]`` and extrados ``[j, 1]`` end of every joint, m, in whatever
        configuration the voussoirs are in (undisplaced or moved).
    forces : array_like, shape (n, 2)
        Resultant external force on each voussoir (weight, body forces, inertia forces), N.
    moments : array_like, shape (n,)
        Moment of all external actions on each voussoir about the origin O, N m (see
        `moments_about_origin`).
    reaction_force : array_like, shape (2,)
        Force of the left support on voussoir 0 (through joint 0), N.
    reaction_moment : float
        Moment of that reaction about the origin O, N m.

    Returns
    -------
    JointForces
        ``force[0]`` is the left reaction itself; ``-force[n]`` the right support reaction.

    Examples
    --------
    One weightless unit-square voussoir squeezed by a horizontal thrust of 5 N at y = 0.75 m
    (a quarter of the joint above its centre, towards the extrados):

    >>> pts = np.array([[[0.0, 0.0], [0.0, 1.0]], [[1.0, 0.0], [1.0, 1.0]]])
    >>> jf = joint_forces(pts, np.zeros((1, 2)), np.zeros(1), np.array([5.0, 0.0]), -3.75)
    >>> jf.normal.tolist(), jf.shear.tolist(), jf.eccentricity.tolist()
    ([5.0, 5.0], [0.0, 0.0], [0.25, 0.25])
    """
    mid, u, nu, half = joint_frames(joint_points)
    f = np.asarray(forces, dtype=float).reshape(-1, 2)
    m = np.asarray(moments, dtype=float).reshape(-1)
    if f.shape[0] != mid.shape[0] - 1 or m.shape[0] != f.shape[0]:
        raise ValueError(
            f"{mid.shape[0]} joints need forces of shape ({mid.shape[0] - 1}, 2) and moments of "
            f"shape ({mid.shape[0] - 1},), got {f.shape} and {m.shape}"
        )
    r = np.asarray(reaction_force, dtype=float).reshape(2)
    # the part left of joint j is voussoirs 0..j-1: its resultant on the right part is the
    # support reaction plus every load on it (cumulative sums), and likewise for moments about O
    force = r + np.vstack([np.zeros((1, 2)), np.cumsum(f, axis=0)])
    moment_o = float(reaction_moment) + np.concatenate([[0.0], np.cumsum(m)])
    moment_mid = moment_o - (mid[:, 0] * force[:, 1] - mid[:, 1] * force[:, 0])
    return JointForces(
        mid_points=mid,
        tangents=u,
        normals=nu,
        half_widths=half,
        force=force,
        normal=np.einsum("ij,ij->i", force, nu),
        shear=np.einsum("ij,ij->i", force, u),
        moment=moment_mid,
    )


def arch_joint_points(arch) -> np.ndarray:
    """Joint end points of an undisplaced arch (any `VoussoirChain`),
    m, (n+1, 2, 2)."""
    return np.stack([arch.intrados_points, arch.extrados_points], axis=1)


__all__ = [
    "JointForces",
    "arch_joint_points",
    "joint_forces",
    "joint_frames",
    "moments_about_origin",
]
