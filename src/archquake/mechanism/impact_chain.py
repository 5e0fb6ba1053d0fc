"""Impact of a chain of rigid voussoirs: generalised momentum, maximum restitution, impulse line.

When an open four-hinge mechanism P returns to the undisplaced configuration, every joint of the
arch is closed at once and the voussoirs' velocities jump. This module computes the jump for any
arch, choosing the post-impact mechanism instead of assuming the mirror image of P.

Derivation (in brief; docs/notes/mechanism.md has it in full)
--------------------------------------------------------
Write the velocity of the whole chain as one vector v (centroid velocity and spin of every
voussoir, 3n entries) and M for the block-diagonal mass matrix (m_k, m_k, I_k), so that the
kinetic energy is v.M v / 2. Just before the impact v_pre = -|phi'_i| u_P, u_P being P's
velocity field per unit opening rate. During the instantaneous impact the voussoirs receive the
generalised impulse Pi = M (v_post - v_pre), made of contact impulses at the joints and the
supports, each compressive and acting at a point of its joint (no sliding: the paper's
assumption, and friction demand is reported).

* The admissible velocities form a convex cone K: at every joint the relative motion is a
  rotation about the intrados end, a rotation about the extrados end, or a non-negative
  combination of both (lift-off). Without sliding, K's extreme rays are the four-hinge
  mechanisms (`archquake.limit.kinematic.admissible_mechanisms`), plus rays in which a
  joint lifts off.
* A contact impulse can only act where the post-impact motion keeps the contact closed
  (perfectly plastic contact points, Moreau's impact law with zero restitution). Then Pi does no
  work on v_post, and Pi . w >= 0 on every admissible w (the contact impulses are compressive
  and the relative velocities separating). These are exactly the optimality conditions of
  ``v_post = argmin ||v - v_pre||_M over v in K``: the post-impact velocity is the M-orthogonal
  projection of v_pre onto K, which exists and is unique, and
  ``||v_post||^2 = ||v_pre||^2 - ||v_post - v_pre||^2 <= ||v_pre||^2`` (energy is never created).
* If the projection is a four-hinge mechanism Q at rate s, then Pi . u_Q = 0 gives
  **conservation of Q's generalised momentum**: ``s = u_Q.M v_pre / u_Q.M u_Q`` (for a single
  block, Housner's r = 1 - 1.5 sin^2 alpha), and the retained energy ratio is
  ``c_T = (u_Q.M v_pre)^2 / ((u_Q.M u_Q)(v_pre.M v_pre)) <= 1`` (Cauchy-Schwarz).
* Among all rays, the projection retains the most energy (it is the closest point of K), so Q is
  the four-hinge mechanism of **maximum restitution**; conversely the maximum-restitution
  mechanism is the projection exactly when Pi lies in K's dual cone, i.e. when the impulses can
  be carried by compressive impulses inside every joint: the **impulse line** (the line of
  thrust of the impulses, found by statics from the left support with Q's four hinges as the
  three-times-redundant chain's conditions) stays within the arch. So the two principles are one:
  only the maximum-restitution mechanism can pass the impulse-line check, and when it fails no
  four-hinge mechanism is the response (the arch moves in more than one degree of freedom).
* Whether a post-impact hinge sits at a joint of P, on the same or the other face, makes no
  difference to admissibility: at phi = 0 every joint is closed, so any mechanism is
  kinematically admissible; a hinge of P that opens again on the same face is a rebound of that
  joint, paid for by the impulses at the other joints, and is allowed exactly when the impulse
  line says so.

Everything here is for a unit closing rate, linear in it, and depends on t/R, the embrace and the
number of voussoirs only (the maps are precomputed once per (pre-mechanism, side)).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import HingeMechanism
from archquake.geometry.planar import cross, perp
from archquake.limit.kinematic import MechanismSet, admissible_mechanisms
from archquake.limit.thrust import JointForces, arch_joint_points, joint_forces

#: A mechanism passes the impulse-line check when no joint's impulse lies outside its section by
#: more than this fraction of the joint's half-thickness (numerical round-off only: the check is
#: exact in exact arithmetic).
IMPULSE_LINE_RTOL = 1e-7

#: The response is accepted as "near four-hinge" (``validity == 'near_four_hinge'``) when the
#: exact impact response (the projection onto the cone of admissible motions) differs from the
#: best four-hinge motion by at most this fraction of its own norm (in the kinetic metric: the
#: kinetic energy of the difference is at most 1 % of the response's). Beyond it the four-link
#: model is outside its validity.
NEAR_FOUR_HINGE_TOL = 0.1

#: Validity labels of `ChainImpact` ("not_four_hinge": the impulse line failed and the exact
#: response was not computed, ``exact=False``, or its quadratic program did not converge).
VALIDITY = ("four_hinge", "at_rest", "near_four_hinge", "outside", "not_four_hinge")


# ----------------------------------------------------------------------------- velocity fields
def mechanism_field(points: np.ndarray, rates: np.ndarray, joints, arch: VoussoirChain
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Velocity field of one four-hinge mechanism per unit opening rate, at phi = 0.

    Parameters
    ----------
    points : (4, 2) hinge points A, B, C, D, m;  rates : (3,) link rates (AB, BC, CD), rad/rad;
    joints : 4 hinge joints;  arch : Arch

    Returns
    -------
    velocity : ndarray (n, 2), m/s per rad/s;  spin : ndarray (n,), rad/s per rad/s
    """
    n = arch.voussoirs
    c = arch.voussoir_centroids
    v = np.zeros((n, 2))
    w = np.zeros(n)
    a, b, cc, d = (int(j) for j in joints)
    pa, pb, _, pd = points
    vb = rates[0] * perp(pb - pa)
    v[a:b] = rates[0] * perp(c[a:b] - pa)
    w[a:b] = rates[0]
    v[b:cc] = vb + rates[1] * perp(c[b:cc] - pb)
    w[b:cc] = rates[1]
    v[cc:d] = rates[2] * perp(c[cc:d] - pd)
    w[cc:d] = rates[2]
    return v, w


def mirrored_field(velocity: np.ndarray, spin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The mirror image (in the arch's vertical axis) of a velocity field: voussoir n-1-k moves
    as the mirror of voussoir k. Kinetic energy is unchanged."""
    return (velocity * np.array([-1.0, 1.0]))[::-1].copy(), -spin[::-1].copy()


def kinetic_energy(arch: VoussoirChain, velocity: np.ndarray, spin: np.ndarray) -> float:
    """sum m |v|^2 / 2 + I w^2 / 2, J (per (rad/s)^2 for unit-rate fields)."""
    return 0.5 * float(arch.voussoir_masses @ (velocity**2).sum(axis=1)
                       + arch.voussoir_inertias @ spin**2)


def _prefix(values: np.ndarray) -> np.ndarray:
    return np.concatenate([np.zeros((1,) + values.shape[1:]), np.cumsum(values, axis=0)])


def generalised_momenta(arch: VoussoirChain, mechs: MechanismSet, velocity: np.ndarray,
                        spin: np.ndarray) -> np.ndarray:
    """u_R . M v for every mechanism R of ``mechs`` and one velocity field v of the chain.

    This is R's generalised momentum of the motion v (the virtual power of v's momenta on R's
    unit-rate field): for a link turning at w about a pivot p, w times the angular momentum of
    its voussoirs about p; for the coupler, also the velocity of B times its linear momentum.
    Prefix sums over the voussoirs make it O(1) per mechanism.

    Parameters
    ----------
    arch : Arch;  mechs : MechanismSet (m mechanisms)
    velocity : (n, 2) centroid velocities, m/s;  spin : (n,) angular velocities, rad/s

    Returns
    -------
    ndarray, shape (m,), kg m^2/s per unit rate of R
    """
    m = arch.voussoir_masses
    c = arch.voussoir_centroids
    p = m[:, None] * velocity
    h0 = cross(c, p) + arch.voussoir_inertias * spin  # angular momentum about O
    cp, ch = _prefix(p), _prefix(h0)
    a, b, cc, d = mechs.joints.T
    pa, pb, pd = mechs.points[:, 0], mechs.points[:, 1], mechs.points[:, 3]
    w_ab, w_bc, w_cd = mechs.rates.T

    def about(i, j, pivot):
        return (ch[j] - ch[i]) - cross(pivot, cp[j] - cp[i])

    vb = w_ab[:, None] * perp(pb - pa)
    return (w_ab * about(a, b, pa) + np.einsum("ij,ij->i", vb, cp[cc] - cp[b])
            + w_bc * about(b, cc, pb) + w_cd * about(cc, d, pd))


def generalised_masses(arch: VoussoirChain, mechs: MechanismSet) -> np.ndarray:
    """u_R . M u_R (twice the kinetic energy per unit rate squared) of every mechanism, kg m^2."""
    m = arch.voussoir_masses
    c = arch.voussoir_centroids
    s0, s1 = _prefix(m), _prefix(m[:, None] * c)
    s2 = _prefix(m * (c**2).sum(axis=1) + arch.voussoir_inertias)
    a, b, cc, d = mechs.joints.T
    pa, pb, pd = mechs.points[:, 0], mechs.points[:, 1], mechs.points[:, 3]
    w_ab, w_bc, w_cd = mechs.rates.T

    def rot(i, j, pivot, w):
        m0, m1, m2 = s0[j] - s0[i], s1[j] - s1[i], s2[j] - s2[i]
        return w**2 * (m2 - 2.0 * np.einsum("ij,ij->i", pivot, m1) + (pivot**2).sum(axis=1) * m0)

    vb = w_ab[:, None] * perp(pb - pa)
    m0, m1 = s0[cc] - s0[b], s1[cc] - s1[b]
    coupler = ((vb**2).sum(axis=1) * m0
               + 2.0 * w_bc * np.einsum("ij,ij->i", vb, perp(m1 - m0[:, None] * pb)))
    return rot(a, b, pa, w_ab) + coupler + rot(b, cc, pb, w_bc) + rot(cc, d, pd, w_cd)


# ----------------------------------------------------------------------------- impulse line
def impulse_line(arch: VoussoirChain, impulse_force: np.ndarray, impulse_moment: np.ndarray,
                 hinge_points: np.ndarray, hinge_joints) -> tuple[JointForces, float]:
    """The joint impulses carrying the generalised impulse Pi, with the post-impact hinges' joints
    transmitting their impulse through the hinge points.

    Parameters
    ----------
    impulse_force : (n, 2) linear impulse received by each voussoir, N s
    impulse_moment : (n,) angular impulse received by each voussoir about O, N m s
    hinge_points : (4, 2);  hinge_joints : 4 joints of the post-impact mechanism

    Returns
    -------
    JointForces
        Impulses (N s) in the statics convention of `archquake.limit.thrust`.
    residual : float
        Inconsistency of the four hinge conditions for three unknowns (relative; ~1e-12 when
        Pi does no work on the mechanism, as it must).
    """
    pts = arch_joint_points(arch)
    loads = -np.asarray(impulse_force)  # d'Alembert: contacts + (-Pi) are in equilibrium
    lmom = -np.asarray(impulse_moment)
    cum_f = _prefix(loads)
    cum_m = _prefix(lmom)
    rows, rhs = [], []
    for j, h in zip(hinge_joints, hinge_points):
        j = int(j)
        # moment about h of the impulse crossing joint j is zero
        rows.append([h[1], -h[0], 1.0])
        rhs.append(-cum_m[j] + h[0] * cum_f[j, 1] - h[1] * cum_f[j, 0])
    mat, vec = np.array(rows), np.array(rhs)
    scale = arch.radius
    cols = np.array([1.0, 1.0, scale])  # unknowns (R_x, R_y, M_0 / R): same units
    sol, *_ = np.linalg.lstsq(mat * cols, vec, rcond=None)
    sol = sol * cols
    ref = max(float(np.abs(loads).sum()) * scale, 1e-300)
    residual = float(np.max(np.abs(mat @ sol - vec)) / ref)
    forces = joint_forces(pts, loads, lmom, sol[:2], float(sol[2]))
    return forces, residual


def impulse_line_inside(forces: JointForces, *, rtol: float = IMPULSE_LINE_RTOL) -> tuple[bool, float]:
    """True if every joint's impulse is compressive and passes within its section.

    Returns the verdict and the worst violation as a fraction of the joint half-thickness times
    the largest normal impulse (<= 0 inside).
    """
    scale = max(float(np.max(np.abs(forces.normal))), float(np.max(np.abs(forces.shear))), 1e-300)
    excess = (np.abs(forces.moment) - forces.normal * forces.half_widths) / (forces.half_widths * scale)
    worst = float(max(np.max(excess), np.max(-forces.normal / scale)))
    return bool(worst <= rtol), worst


# ----------------------------------------------------------------------------- cone projection
def _generators(arch: VoussoirChain) -> tuple[np.ndarray, np.ndarray]:
    """Admissible-velocity cone of the chain: v = G x, x >= 0, C x = 0.

    x = (a_0, b_0, ..., a_n, b_n): rotation about the intrados end (relative rotation -a_j) and
    about the extrados end (+b_j) at every joint; the left support is fixed, block k moves with
    the rotations of joints 0..k, and C x = 0 closes the chain on the right support.
    G: (3n, 2(n+1)) rows (vx_k, vy_k, w_k) per voussoir.
    """
    n = arch.voussoirs
    c = arch.voussoir_centroids
    ends = (arch.intrados_points, arch.extrados_points)
    g = np.zeros((3 * n, 2 * (n + 1)))
    con = np.zeros((3, 2 * (n + 1)))
    for j in range(n + 1):
        for side, sign in ((0, -1.0), (1, 1.0)):
            col = 2 * j + side
            p = ends[side][j]
            if j < n:
                v = sign * perp(c[j:] - p)
                g[3 * j::3, col] = v[:, 0]
                g[3 * j + 1::3, col] = v[:, 1]
                g[3 * j + 2::3, col] = sign
            con[:, col] = sign * np.array([1.0, p[0], p[1]])
    return g, con


def cone_projection(arch: VoussoirChain, velocity: np.ndarray, spin: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The exact impact response: the M-projection of a velocity field onto the cone of admissible
    motions of the chain (hinges or lift-off at any joints, no sliding), by a small quadratic
    program (SLSQP on 2(n+1) non-negative joint rotations with the 3 closure equations).

    Returns the projected velocity (n, 2), spin (n,) and the joint rotations x (2(n+1),).

    Raises
    ------
    SolverError
        If the quadratic program does not converge.
    """
    from scipy.optimize import minimize

    n = arch.voussoirs
    g, con = _generators(arch)
    r = arch.radius
    mass = arch.mass
    wdiag = np.repeat(arch.voussoir_masses / mass, 3)
    wdiag[2::3] = arch.voussoir_inertias / (mass * r * r)
    gs = g.copy()
    gs[0::3] /= r
    gs[1::3] /= r  # velocities in units of R per unit rate
    target = np.column_stack([velocity / r, spin]).reshape(-1)
    cs = con / np.array([1.0, r, r])[:, None]
    hq = gs.T @ (wdiag[:, None] * gs)
    lin = gs.T @ (wdiag * target)

    def fun(x):
        return 0.5 * x @ hq @ x - lin @ x, hq @ x - lin

    # warm start: least squares on the closure's null space, clipped
    res = minimize(fun, np.zeros(2 * (n + 1)), jac=True, method="SLSQP",
                   bounds=[(0.0, None)] * (2 * (n + 1)),
                   constraints=[{"type": "eq", "fun": lambda x: cs @ x, "jac": lambda x: cs}],
                   options={"ftol": 1e-15, "maxiter": 2000})
    if not res.success:
        from archquake.errors import SolverError

        raise SolverError(f"the impact's cone projection did not converge: {res.message}")
    x = np.maximum(res.x, 0.0)
    v = g @ x
    return v.reshape(n, 3)[:, :2].copy(), v.reshape(n, 3)[:, 2].copy(), x


# ----------------------------------------------------------------------------- the law
@dataclass(frozen=True)
class ChainImpact:
    """The impact of a closing four-hinge mechanism, for a unit closing rate.

    Attributes
    ----------
    pre : HingeMechanism
        The mechanism whose hinges close.
    post : HingeMechanism or None
        The post-impact mechanism (None if the arch stops, or if no four-hinge mechanism can be
        the response).
    restitution_ct : float
        c_T = T_after / T_before (Eq. 6) of the four-hinge response (<= 1 always).
    restitution_cv : float
        sqrt(c_T): the post-impact rate over the pre-impact one when both are measured in
        kinetically equivalent coordinates; for the mirror mechanism measured as the paper does
        (on the mirror of link AB) it is exactly the paper's c_v of Eq. 5.
    post_rate : float
        Opening rate of ``post``'s own phi (its link AB, `HingeMechanism` convention) per
        unit closing rate of ``pre``, rad/s per rad/s (0 if at rest).
    is_mirror : bool
        True if ``post`` is the mirror image of ``pre`` (the paper's assumption).
    validity : str
        'four_hinge' (the exact impact response is ``post``), 'at_rest' (the exact response is
        rest: a perfectly plastic impact), 'near_four_hinge' (the exact response is a motion of
        more degrees of freedom within `NEAR_FOUR_HINGE_TOL` of ``post``), or 'outside'
        (the four-link model does not describe the impact); 'not_four_hinge' when the
        impulse line failed and the exact response was not computed (``exact=False``).
    distance : float
        ||v_exact - v_four_hinge||_M / ||v_exact||_M (0 when exact).
    exact_ct : float
        c_T of the exact response (the cone projection); equals ``restitution_ct`` when valid.
    impulses : JointForces or None
        The impulse line (joint impulses, N s per rad/s of closing rate) of the chosen response.
    friction_demand : float
        Largest |shear| / normal impulse over the joints that carry impulse.
    candidates : int
        Four-hinge mechanisms with a positive generalised momentum (could start opening).
    exact_hinges : tuple of (joint, face)
        Where the exact response turns (joints whose rotation exceeds 2 % of the largest; a joint
        turning about both ends lifts off and is listed twice); empty when not computed.
    """

    pre: HingeMechanism
    post: HingeMechanism | None
    restitution_ct: float
    restitution_cv: float
    post_rate: float
    is_mirror: bool
    validity: str
    distance: float
    exact_ct: float
    impulses: JointForces | None
    friction_demand: float
    candidates: int
    exact_hinges: tuple = ()

    @property
    def valid(self) -> bool:
        return self.validity in ("four_hinge", "at_rest", "near_four_hinge")

    def to_dict(self) -> dict:
        return {
            "restitution_cv": self.restitution_cv,
            "restitution_ct": self.restitution_ct,
            "post_rate": self.post_rate,
            "post_hinges": None if self.post is None else [h.to_dict() for h in self.post.hinges],
            "is_mirror": self.is_mirror,
            "validity": self.validity,
            "distance": self.distance,
            "exact_ct": self.exact_ct,
            "friction_demand": self.friction_demand,
            "exact_hinges": [[j, f] for j, f in self.exact_hinges],
        }


@lru_cache(maxsize=4)  # ~30 MB per 40-voussoir arch
def _mechanisms(arch: VoussoirChain) -> tuple[MechanismSet, np.ndarray]:
    mechs = admissible_mechanisms(arch)
    return mechs, generalised_masses(arch, mechs)


def _field_of(mech: HingeMechanism) -> tuple[np.ndarray, np.ndarray]:
    return mechanism_field(mech.points, mech.rates, mech.joints, mech.arch)


def _response(pre: HingeMechanism, post: HingeMechanism | None, field_post, rate: float,
              ct: float, validity: str, distance: float, exact_ct: float, candidates: int,
              is_mirror: bool) -> ChainImpact:
    arch = pre.arch
    v_pre, w_pre = _field_of(pre)  # closing at unit rate: v_pre = -u_P
    impulses, friction = None, 0.0
    if post is not None:
        v_q, w_q = field_post
        dv = rate * v_q + v_pre  # Pi = M (s u_Q - (-u_P))
        dw = rate * w_q + w_pre
        pf = arch.voussoir_masses[:, None] * dv
        pm = cross(arch.voussoir_centroids, pf) + arch.voussoir_inertias * dw
        impulses, _ = impulse_line(arch, pf, pm, post.points, post.joints)
        carry = impulses.normal > 1e-9 * max(float(np.max(np.abs(impulses.normal))), 1e-300)
        if np.any(carry):
            friction = float(np.max(np.abs(impulses.shear[carry]) / impulses.normal[carry]))
    return ChainImpact(pre=pre, post=post, restitution_ct=float(ct),
                       restitution_cv=float(np.sqrt(max(ct, 0.0))), post_rate=float(rate),
                       is_mirror=is_mirror, validity=validity, distance=float(distance),
                       exact_ct=float(exact_ct), impulses=impulses, friction_demand=friction,
                       candidates=candidates)


def impact_scores(pre: HingeMechanism) -> tuple[MechanismSet, np.ndarray, np.ndarray]:
    """The generalised-momentum map from ``pre`` closing at unit rate to every four-hinge mechanism.

    Returns
    -------
    mechs : MechanismSet
    post_rate : ndarray (m,)
        Rate of each mechanism's phi after the impact, per unit closing rate (negative: that
        mechanism would start closing, i.e. it cannot be the response).
    ct : ndarray (m,)
        Energy retained if the arch continued on that mechanism (0 where post_rate <= 0).
    """
    arch = pre.arch
    mechs, meff = _mechanisms(arch)
    v_p, w_p = _field_of(pre)
    t_pre = 2.0 * kinetic_energy(arch, v_p, w_p)
    proj = -generalised_momenta(arch, mechs, v_p, w_p)  # u_R . M v_pre with v_pre = -u_P
    rate = proj / meff
    ct = np.where(rate > 0.0, proj * rate / t_pre, 0.0)
    return mechs, rate, ct


def chain_impact(pre: HingeMechanism, *, post: HingeMechanism | str | None = None,
                 exact: bool = True) -> ChainImpact:
    """The impact law for a chain of rigid voussoirs (see the module docstring).

    Parameters
    ----------
    pre : HingeMechanism
        The mechanism whose hinges close (any four-hinge mechanism of an arch of at most
        `MAX_KINEMATIC_VOUSSOIRS` voussoirs, the enumeration's
        limit).
    post : HingeMechanism, 'mirror' or None
        None (default): the post-impact mechanism is chosen (maximum restitution, checked by the
        impulse line). A mechanism or 'mirror' forces it (generalised momentum of that mechanism
        conserved); its validity is still checked.
    exact : bool
        If the four-hinge motion fails the impulse line, compute the exact response (a small
        quadratic program) to tell 'near_four_hinge' from 'outside'. With False that case is
        reported as 'not_four_hinge' with ``distance`` and ``exact_ct`` nan (cheaper).

    Returns
    -------
    ChainImpact
    """
    arch = pre.arch
    v_p, w_p = _field_of(pre)
    t_pre = 2.0 * kinetic_energy(arch, v_p, w_p)
    if post is not None:
        q = pre.mirrored() if isinstance(post, str) and post == "mirror" else post
        if not isinstance(q, HingeMechanism):
            raise ValueError(f"post must be a HingeMechanism, 'mirror' or None, got {post!r}")
        v_q, w_q = _field_of(q)
        proj = -float(arch.voussoir_masses @ (v_q * v_p).sum(axis=1)
                      + arch.voussoir_inertias @ (w_q * w_p))
        meff_q = 2.0 * kinetic_energy(arch, v_q, w_q)
        q_rate = proj / meff_q
        q_ct = proj * q_rate / t_pre
        is_mirror = q.joints == pre.mirrored().joints and q.faces == pre.mirrored().faces
        if q_rate <= 0.0:
            return _response(pre, None, None, 0.0, 0.0, "outside", 1.0, float("nan"), 0, is_mirror)
        resp = _response(pre, q, (v_q, w_q), q_rate, q_ct, "four_hinge", 0.0, q_ct, 1, is_mirror)
        if _inside(resp):
            return resp
        return _diagnose(resp, v_p, w_p, t_pre, exact)
    mechs, rate, ct = impact_scores(pre)
    candidates = int(np.count_nonzero(rate > 0.0))
    if candidates == 0:
        return _response(pre, None, None, 0.0, 0.0, "at_rest", 0.0, 0.0, 0, False)
    i = int(np.argmax(ct))
    q = mechs.mechanism(i, arch)
    mirror = pre.mirrored()
    is_mirror = q.joints == mirror.joints and q.faces == mirror.faces
    resp = _response(pre, q, _field_of(q), float(rate[i]), float(ct[i]), "four_hinge", 0.0,
                     float(ct[i]), candidates, is_mirror)
    if _inside(resp):
        return resp
    return _diagnose(resp, v_p, w_p, t_pre, exact)


def _inside(resp: ChainImpact) -> bool:
    return resp.impulses is not None and impulse_line_inside(resp.impulses)[0]


def _diagnose(resp: ChainImpact, v_p, w_p, t_pre, exact: bool) -> ChainImpact:
    """The chosen four-hinge motion fails the impulse line: compare it with the exact response."""
    from dataclasses import replace

    if not exact or resp.post is None:
        return replace(resp, validity="not_four_hinge", distance=float("nan"),
                       exact_ct=float("nan"))
    arch = resp.pre.arch
    from archquake.errors import SolverError

    try:
        vx, wx, x = cone_projection(arch, -v_p, -w_p)
    except SolverError:
        return replace(resp, validity="not_four_hinge", distance=float("nan"),
                       exact_ct=float("nan"))
    big = x > 0.02 * max(float(x.max()), 1e-300)
    hinges = tuple((int(k // 2), "intrados" if k % 2 == 0 else "extrados") for k in np.flatnonzero(big))
    t_exact = 2.0 * kinetic_energy(arch, vx, wx)
    v_q, w_q = _field_of(resp.post)
    dv, dw = vx - resp.post_rate * v_q, wx - resp.post_rate * w_q
    dist = float(np.sqrt(2.0 * kinetic_energy(arch, dv, dw) / max(t_exact, 1e-300 * t_pre)))
    validity = "near_four_hinge" if dist <= NEAR_FOUR_HINGE_TOL else "outside"
    return replace(resp, validity=validity, distance=dist, exact_ct=t_exact / t_pre,
                   exact_hinges=hinges)


__all__ = [
    "IMPULSE_LINE_RTOL",
    "NEAR_FOUR_HINGE_TOL",
    "ChainImpact",
    "chain_impact",
    "cone_projection",
    "generalised_masses",
    "generalised_momenta",
    "impact_scores",
    "impulse_line",
    "impulse_line_inside",
    "kinetic_energy",
    "mechanism_field",
    "mirrored_field",
]
