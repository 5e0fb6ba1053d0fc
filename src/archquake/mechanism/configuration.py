"""The displaced arch: where every voussoir is, and how it accelerates, for a mechanism state.

One home for the arch's geometry along the motion. The plots (`archquake.plotting.history`,
`archquake.plotting.thrust`) and the joint forces of the moving arch
(`archquake.thrust.states`) all read it from `displaced_arch`.

A mechanism state (``phi``, ``phi_dot``, ``phi_ddot``, which mechanism is open) fixes the rigid
motion of each of the three links (the four-bar linkage of `archquake.mechanism.kinematics`):
a voussoir of a link turns by the link's rotation ``psi`` about the link's pivot. Its centroid
accelerates, relative to the ground, by ``a_c = r' phi'' + r'' phi'^2`` and turns with
``alpha = psi' phi'' + psi'' phi'^2`` (primes on ``r``, ``psi`` are d/dphi). Voussoirs outside
the mechanism (below a hinge off the springings) stay where they are.

Joint geometry: a joint inside a link keeps its two faces together; at a hinge the faces open
by the links' relative rotation and touch only at the hinge point. The joint line reported
there is the bisector of the two faces, drawn from the hinge point over the full thickness
(at ``phi = 0`` both faces coincide and the choice does not matter).

Side convention: side +1 is the packed (first) mechanism; side -1 is its mirror image in the
vertical axis (x -> -x, voussoir k -> n-1-k, joint j -> n-j); side 0 is the locked arch,
undisplaced.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import Face
from archquake.geometry.planar import rotation_matrix
from archquake.limit.thrust import arch_joint_points
from archquake.mechanism.kinematics import eom_terms, fourbar, link_states, potential
from archquake.mechanism.prepared import PreparedMechanism

#: Relative tolerance (on the thickness) below which two faces of a joint count as closed.
_CLOSED = 1e-12


@dataclass(frozen=True)
class DisplacedArch:
    """The arch in a mechanism state (physical frame, origin at the centre of the intrados).

    Attributes
    ----------
    arch : Arch
    phi, phi_dot, phi_ddot : float
        Rotation (rad), rate (rad/s) and acceleration (rad/s^2) of the open mechanism.
    side : int
        +1 the first mechanism, -1 its mirror image, 0 locked (undisplaced, at rest).
    left_faces, right_faces : ndarray, (n, 2, 2)
        Joint k and joint k+1 of voussoir k as [intrados, extrados] points, m.
    centroids : ndarray, (n, 2)
        Voussoir centroids, m.
    rotations : ndarray, (n,)
        Rotation of each voussoir, rad (counter-clockwise).
    translations : ndarray, (n, 2)
        With ``rotations``, the rigid motion x -> Rot(rotation) x + translation of each
        voussoir's undisplaced points, m.
    accelerations : ndarray, (n, 2)
        Centroid accelerations relative to the ground, m/s^2.
    angular_accelerations : ndarray, (n,)
        rad/s^2.
    joint_points : ndarray, (n+1, 2, 2)
        Intrados and extrados ends of every joint line (the common face of a closed joint, the
        bisector from the hinge point at an open hinge), m.
    hinge_joints : tuple of 4 int, or None
        Joints of the open mechanism's hinges A, B, C, D (None while locked).
    hinge_faces : tuple of 4 Face, or None
    hinge_points : ndarray, (4, 2), or None
        A, B, C, D in the displaced arch, m.
    """

    arch: VoussoirChain = field(repr=False)
    phi: float
    phi_dot: float
    phi_ddot: float
    side: int
    left_faces: np.ndarray = field(repr=False)
    right_faces: np.ndarray = field(repr=False)
    centroids: np.ndarray = field(repr=False)
    rotations: np.ndarray = field(repr=False)
    translations: np.ndarray = field(repr=False)
    accelerations: np.ndarray = field(repr=False)
    angular_accelerations: np.ndarray = field(repr=False)
    joint_points: np.ndarray = field(repr=False)
    hinge_joints: tuple[int, int, int, int] | None
    hinge_faces: tuple[Face, Face, Face, Face] | None = field(repr=False)
    hinge_points: np.ndarray | None = field(repr=False)

    @property
    def positions(self) -> np.ndarray:
        """Centroid displacement dx, dy (m) and rotation (rad) of each voussoir, (n, 3): the
        format `archquake.plotting.arch.plot_arch` draws."""
        return np.column_stack([self.centroids - self.arch.voussoir_centroids, self.rotations])


def _packed(prepared: PreparedMechanism, phi: float, phi_dot: float, phi_ddot: float):
    """Faces, centroids, rigid motions and accelerations of the packed (side +1) mechanism."""
    mech = prepared.mechanism
    arch = mech.arch
    n = arch.voussoirs
    fb = fourbar(prepared.packed, phi)
    ls = link_states(prepared.packed, phi)
    if not (fb[0] and ls[0]):
        raise SolverError(f"the mechanism cannot be assembled at phi = {phi:.6g} rad (beyond its toggle)")
    a0, b0, c0, d0 = mech.points
    b1, b2 = np.array([fb[3], fb[4]]), np.array([fb[5], fb[6]])
    if phi == 0.0:  # the undisplaced arch, exactly (the linkage solve leaves round-off)
        b, c_pt, psi_ab, psi_bc, psi_cd = np.asarray(b0), np.asarray(c0), 0.0, 0.0, 0.0
    else:
        b, c_pt = np.array([fb[1], fb[2]]), np.array([fb[7], fb[8]])
        psi_ab, psi_bc, psi_cd = ls[1], ls[4], ls[7]
    zero = np.zeros(2)
    # per link: pivot now, pivot undisplaced, pivot' and pivot'', psi, psi', psi''
    links = (
        (a0, a0, zero, zero, psi_ab, ls[2], ls[3]),
        (b, b0, b1, b2, psi_bc, ls[5], ls[6]),
        (d0, d0, zero, zero, psi_cd, ls[8], ls[9]),
    )
    pts = arch_joint_points(arch)
    cen0 = arch.voussoir_centroids
    left = pts[:-1].copy()
    right = pts[1:].copy()
    cen = cen0.copy()
    rotation = np.zeros(n)
    translation = np.zeros((n, 2))
    acc = np.zeros((n, 2))
    alpha = np.zeros(n)
    for rng, (p, p0, p1, p2, psi, w, a) in zip(mech.link_voussoirs, links, strict=True):
        rot = rotation_matrix(psi)
        shift = p - rot @ p0
        omega = w * phi_dot
        alph = w * phi_ddot + a * phi_dot**2
        pivot_acc = p1 * phi_ddot + p2 * phi_dot**2
        for k in rng:
            left[k] = pts[k] @ rot.T + shift
            right[k] = pts[k + 1] @ rot.T + shift
            cen[k] = rot @ cen0[k] + shift
            r = cen[k] - p
            acc[k] = pivot_acc + alph * np.array([-r[1], r[0]]) - omega**2 * r
            alpha[k] = alph
            rotation[k] = psi
            translation[k] = shift
    hinges = np.array([a0, b, c_pt, d0])
    return left, right, cen, rotation, translation, acc, alpha, mech.joints, mech.faces, hinges


def _mirrored(parts, n: int):
    """The mirror image in the vertical axis: x -> -x, voussoir k -> n-1-k, joint j -> n-j."""
    left, right, cen, rotation, translation, acc, alpha, joints, faces, hinges = parts
    flip = np.array([-1.0, 1.0])
    idx = np.arange(n)[::-1]
    return (right[idx] * flip, left[idx] * flip, cen[idx] * flip, -rotation[idx],
            translation[idx] * flip, acc[idx] * flip, -alpha[idx],
            tuple(n - j for j in reversed(joints)), tuple(reversed(faces)), hinges[::-1] * flip)


def _joint_lines(arch: VoussoirChain, left: np.ndarray, right: np.ndarray, joints, faces,
                 hinges: np.ndarray) -> np.ndarray:
    """Joint end points (n+1, 2, 2) of the displaced arch: the common face where the two sides
    touch, the bisector from the hinge point where a hinge has opened."""
    pts = arch_joint_points(arch)
    n = arch.voussoirs
    out = np.empty_like(pts)
    tol = _CLOSED * arch.thickness + 1e-15 * arch.radius
    hinge_of = dict(zip(joints, zip(faces, hinges, strict=True), strict=True))
    for j in range(n + 1):
        lf = pts[0] if j == 0 else right[j - 1]
        rf = pts[n] if j == n else left[j]
        if np.max(np.abs(lf - rf)) <= tol or j not in hinge_of:
            out[j] = 0.5 * (lf + rf)
            continue
        face, point = hinge_of[j]
        u = (lf[1] - lf[0]) / np.linalg.norm(lf[1] - lf[0]) + (rf[1] - rf[0]) / np.linalg.norm(rf[1] - rf[0])
        u *= arch.thickness / np.linalg.norm(u)
        out[j] = (point, point + u) if face is Face.INTRADOS else (point - u, point)
    return out


def displaced_arch(prepared: PreparedMechanism, phi: float, side: int = 1, *,
                   phi_dot: float = 0.0, phi_ddot: float = 0.0) -> DisplacedArch:
    """The arch in a mechanism state: positions, joint lines, hinges and accelerations.

    Parameters
    ----------
    prepared : PreparedMechanism
        The first mechanism (side +1).
    phi : float
        Rotation of the open mechanism, rad (>= 0; ignored while locked).
    side : {+1, -1, 0}
        +1 the first mechanism, -1 its mirror image, 0 locked (undisplaced, at rest).
    phi_dot, phi_ddot : float
        Rate (rad/s) and acceleration (rad/s^2) of the open mechanism: they set the voussoirs'
        accelerations only (``phi_ddot`` is an input here; `archquake.thrust.state_at`
        takes it from the equation of motion, Eq. 2).

    Returns
    -------
    DisplacedArch

    Raises
    ------
    SolverError
        ``phi`` is beyond the linkage's toggle (the mechanism cannot be assembled).

    Examples
    --------
    Oppenheim's arch: the crown hinge B moves right and down as the first mechanism opens.

    >>> import math
    >>> from archquake import Arch
    >>> prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> d = displaced_arch(prep, 0.02)
    >>> d.hinge_joints, bool(d.hinge_points[1, 0] > prep.mechanism.points[1][0])
    ((0, 3, 5, 7), True)
    >>> bool(displaced_arch(prep, 0.0).positions.any())
    False
    """
    arch = prepared.mechanism.arch
    side = int(side)
    if side not in (-1, 0, 1):
        raise InvalidParameterError(f"side must be -1, 0 or +1, got {side}")
    n = arch.voussoirs
    if side == 0:
        pts = arch_joint_points(arch)
        return DisplacedArch(
            arch=arch, phi=0.0, phi_dot=0.0, phi_ddot=0.0, side=0, left_faces=pts[:-1].copy(),
            right_faces=pts[1:].copy(), centroids=arch.voussoir_centroids.copy(),
            rotations=np.zeros(n), translations=np.zeros((n, 2)), accelerations=np.zeros((n, 2)),
            angular_accelerations=np.zeros(n), joint_points=pts, hinge_joints=None,
            hinge_faces=None, hinge_points=None,
        )
    phi = float(phi)
    if phi < 0:
        raise InvalidParameterError(f"phi must be >= 0 rad while a mechanism is open, got {phi:g}")
    parts = _packed(prepared, phi, float(phi_dot), float(phi_ddot))
    if side < 0:
        parts = _mirrored(parts, n)
    left, right, cen, rotation, translation, acc, alpha, joints, faces, hinges = parts
    return DisplacedArch(
        arch=arch, phi=phi, phi_dot=float(phi_dot), phi_ddot=float(phi_ddot), side=side,
        left_faces=left, right_faces=right, centroids=cen, rotations=rotation,
        translations=translation, accelerations=acc, angular_accelerations=alpha,
        joint_points=_joint_lines(arch, left, right, joints, faces, hinges),
        hinge_joints=joints, hinge_faces=faces, hinge_points=hinges,
    )


def voussoir_positions(prepared: PreparedMechanism, phi: float, side: int = 1) -> np.ndarray:
    """Centroid displacement dx, dy (m) and rotation (rad) of every voussoir, (n, 3), when the
    mechanism on ``side`` has turned by ``phi``: `DisplacedArch.positions`.

    Examples
    --------
    >>> import math
    >>> from archquake import Arch
    >>> prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> voussoir_positions(prep, 0.0).any()
    np.False_
    """
    return displaced_arch(prepared, phi, side).positions


def hinge_points(prepared: PreparedMechanism, phi: float, side: int = 1) -> np.ndarray:
    """The four hinge points A, B, C, D of the open mechanism (side +1 or -1) in the displaced
    arch, m, (4, 2): `DisplacedArch.hinge_points`."""
    points = displaced_arch(prepared, phi, side).hinge_points
    if points is None:
        raise InvalidParameterError("the locked arch (side 0) has no hinges")
    return points


def crown_and_energies(prepared: PreparedMechanism, phi: np.ndarray, phi_dot: np.ndarray,
                       side: np.ndarray, row: np.ndarray | None = None, *,
                       g: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The crown's displacement and the energies along a time history of the four-link model.

    Parameters
    ----------
    prepared : PreparedMechanism
        The run's first mechanism under its impact law (the rows of ``row`` are rows of its
        `table`).
    phi, phi_dot, side : ndarray (nt,)
        The history's samples (`archquake.mechanism.simulate.History`): rotation (rad)
        and rate (rad/s) of the open mechanism, and its side (+1, -1 mirror image, 0 locked).
    row : ndarray (nt,) of int, optional
        The open mechanism's row of the table (None: row 0 throughout).
    g : float
        Gravity, m/s^2.

    Returns
    -------
    crown : ndarray (nt, 2)
        Displacement dx, dy of the crown point (`VoussoirChain.crown_point`, carried by
        the middle voussoir ``n // 2`` as the block models carry it) relative to the ground, m.
    kinetic : ndarray (nt,)
        ``1/2 m_eff(phi) phi'^2`` (Eq. 2's generalised mass), J.
    potential : ndarray (nt,)
        ``g sum m_k (y_k - y_k0)`` of the open mechanism, J (0 in the undisplaced arch).

    Examples
    --------
    >>> import math
    >>> from archquake import Arch
    >>> prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> crown, kinetic, pot = crown_and_energies(
    ...     prep, np.array([0.0, 0.02]), np.array([0.0, 0.1]), np.array([0, 1]), g=9.81)
    >>> crown[0].tolist(), bool(pot[1] > 0.0), bool(kinetic[1] > 0.0)
    ([0.0, 0.0], True, True)
    """
    arch = prepared.mechanism.arch
    k = min(arch.voussoirs // 2, arch.voussoirs - 1)
    point = np.asarray(arch.crown_point, dtype=float)
    nt = np.asarray(phi).shape[0]
    crown = np.zeros((nt, 2))
    kinetic = np.zeros(nt)
    potential_ = np.zeros(nt)
    members: dict[int, PreparedMechanism] = {}
    for i in range(nt):
        s = int(side[i])
        if s == 0:
            continue  # locked: the arch moves with the ground, undisplaced
        r = 0 if row is None else int(row[i])
        member = members.get(r)
        if member is None:
            member = members[r] = prepared.member(r)
        p = float(phi[i])
        config = displaced_arch(member, p, s)
        c, sn = math.cos(config.rotations[k]), math.sin(config.rotations[k])
        crown[i] = (c * point[0] - sn * point[1] + config.translations[k, 0] - point[0],
                    sn * point[0] + c * point[1] + config.translations[k, 1] - point[1])
        meff = eom_terms(member.packed, p)[1]
        kinetic[i] = 0.5 * meff * float(phi_dot[i]) ** 2
        potential_[i] = g * potential(member.packed, p)
    return crown, kinetic, potential_


__all__ = ["DisplacedArch", "crown_and_energies", "displaced_arch", "hinge_points",
           "voussoir_positions"]
