"""Driver of the distinct-element model: pack, settle, step, record, classify.

The three layers follow scipy's ``solve_ivp``: the compiled step
(:func:`archquake.dem._kernels.step`, twin in :mod:`archquake.dem._twin`), a stepper loop
with a written contract (:func:`archquake.dem._kernels.run`), and this driver that packs the
assembly, chooses the time step, brings the assembly to rest under gravity, runs and packs a
frozen :class:`DemResult`.

Frames. Positions and velocities are absolute; the base blocks move with the ground, whose
velocity and displacement are the central-difference integrals of x_g''(t_n) taken inside the
same time stepping (v_b^(n+1/2) = v_b^(n-1/2) + x_g''(t_n) dt). Mass-proportional damping acts
on the block velocities *relative to the base*: a rigid translation with the ground is not
resisted (damping the absolute velocity, as UDEC does, would add a spurious drag
-alpha m v_g that depends on the ground's velocity, i.e. on the frame; with the paper's
alpha = 6.28e-5 1/s either choice changes the forces by < 1e-4 of the weight).
Stiffness-proportional damping acts on the contact relative velocities (frame-independent).
Energies are those of the motion relative to the ground, where the ground's acceleration is
the inertial body force -m x_g'': kinetic + potential + strain + damping + friction - input
work stays constant (:attr:`DemResult.energy_error`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.dem import _kernels as K
from archquake.dem import _twin
from archquake.dem.assembly import Assembly, build_arch_assembly
from archquake.dem.settings import DemSettings
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import GroundMotion

#: Most time steps a run may take (guards against absurd stiffness/duration choices).
MAX_STEPS = 200_000_000


class DemOutcome(StrEnum):
    """What happened to the assembly: the analytical model's three outcomes."""

    NO_HINGING = "no_hinging"
    SURVIVES = "survives"
    COLLAPSE = "collapse"


# --------------------------------------------------------------------------- packing
@dataclass
class Packed:
    """The packed arrays of one assembly (mutable working state, private to a run)."""

    state: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    free: np.ndarray
    y_ref: np.ndarray
    vloc: np.ndarray
    vstart: np.ndarray
    radius: np.ndarray
    sl_i: np.ndarray = field(default_factory=lambda: np.zeros((0, 5), np.int64))
    sl_edge: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    sl_f: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)))


def pack(assembly: Assembly) -> Packed:
    """Blocks at rest in the undisplaced configuration (theta = 0, local = polygon - centroid)."""
    nb = assembly.n_blocks
    cents = np.array(assembly.centroids, dtype=float)
    counts = np.array([len(p) for p in assembly.polygons])
    vstart = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    vloc = np.vstack([p - c for p, c in zip(assembly.polygons, cents)])
    radius = np.array([np.max(np.hypot(*(p - c).T)) for p, c in zip(assembly.polygons, cents)])
    state = np.zeros((nb, 6))
    state[:, :2] = cents
    free = (~np.asarray(assembly.base)).astype(np.int64)
    return Packed(
        state=state,
        mass=np.where(free == 1, assembly.masses, 1.0).astype(float),
        inertia=np.where(free == 1, assembly.inertias, 1.0).astype(float),
        free=free,
        y_ref=cents[:, 1].copy(),
        vloc=vloc,
        vstart=vstart,
        radius=radius,
    )


def neighbour_pairs(packed: Packed, margin: float) -> list[tuple[int, int]]:
    """Block pairs (a < b, not both base) whose bounding circles are closer than ``margin``."""
    xy = packed.state[:, :2]
    r = packed.radius
    d = np.hypot(xy[:, None, 0] - xy[None, :, 0], xy[:, None, 1] - xy[None, :, 1])
    close = d < r[:, None] + r[None, :] + margin
    pairs = []
    nb = len(r)
    for a in range(nb):
        for b in range(a + 1, nb):
            if close[a, b] and (packed.free[a] or packed.free[b]):
                pairs.append((a, b))
    return pairs


def build_slots(packed: Packed, pairs: list[tuple[int, int]]) -> None:
    """(Re)build the contact slots for ``pairs``, keeping the state of surviving contacts."""
    old = {}
    for s in range(packed.sl_i.shape[0]):
        if packed.sl_edge[s] >= 0:
            old[(int(packed.sl_i[s, 0]), int(packed.sl_i[s, 2]))] = (
                packed.sl_edge[s],
                packed.sl_f[s].copy(),
            )
    rows = []
    vs = packed.vstart
    for a, b in pairs:
        na, nbv = vs[a + 1] - vs[a], vs[b + 1] - vs[b]
        s0 = len(rows)
        for v in range(vs[a], vs[a + 1]):
            rows.append((v, a, b, s0 + na, s0 + na + nbv))
        for v in range(vs[b], vs[b + 1]):
            rows.append((v, b, a, s0, s0 + na))
    sl_i = np.array(rows, dtype=np.int64).reshape(-1, 5)
    sl_edge = np.full(len(rows), -1, dtype=np.int64)
    sl_f = np.zeros((len(rows), 5))
    sl_f[:, K.F_KS] = 1.0
    for s, (v, _, b, _, _) in enumerate(rows):
        kept = old.get((v, b))
        if kept is not None:
            sl_edge[s], sl_f[s] = kept
    packed.sl_i, packed.sl_edge, packed.sl_f = sl_i, sl_edge, sl_f


def _params(assembly: Assembly, settings: DemSettings, dt: float, g: float) -> np.ndarray:
    law = settings.contact
    par = np.zeros(K.N_PAR)
    par[K.P_DT] = dt
    par[K.P_G] = g
    par[K.P_ALPHA], par[K.P_BETA] = settings.damping
    par[K.P_MU] = law.friction
    par[K.P_KN] = law.normal_stiffness * assembly.depth
    par[K.P_KS] = law.shear_stiffness * assembly.depth
    par[K.P_TOL] = contact_tolerance(assembly)
    par[K.P_DMAX] = 0.25 * assembly.min_edge
    return par


def contact_tolerance(assembly: Assembly) -> float:
    """Length (m) within which two corners count as the same point and a contact may slide
    past the end of its edge before it is dropped: 1e-3 of the shortest polygon edge."""
    return 1e-3 * assembly.min_edge


# --------------------------------------------------------------------------- time step
def stable_time_step(
    assembly: Assembly, settings: DemSettings, *, g: float = STANDARD_GRAVITY
) -> tuple[float, float]:
    """Stable central-difference time step, s, and the bound on the highest circular
    frequency, rad/s, used for it.

    omega_max^2 is the largest eigenvalue of the mass-normalised stiffness M^-1/2 K M^-1/2 of
    the contacts present at rest (normal and shear spring of every corner contact, lever arms
    included; base blocks rigid): exact for up to 500 blocks, Gershgorin's bound beyond.
    With Rayleigh damping the lagged-velocity central-difference scheme is stable for
    omega dt < 2 (sqrt(1 + xi^2) - xi), xi = alpha / (2 omega) + beta omega / 2, so

        dt = safety * 2 / omega_max * (sqrt(1 + xi_max^2) - xi_max).

    Contacts that form later (impacts) use the same tributary lengths, so the bound holds
    while the contact set does not grow beyond the one at rest (true for arches and rocking
    blocks; pass ``DemSettings.time_step`` for assemblies that start apart).
    """
    packed = pack(assembly)
    build_slots(packed, neighbour_pairs(packed, 0.1 * float(packed.radius.min())))
    par = _params(assembly, settings, 1.0, g)
    acc = np.zeros(K.N_ACC)
    vw, edir = _twin.world_vertices(packed.state, packed.vloc, packed.vstart)
    _twin.update_contacts(
        vw, edir, packed.vstart, packed.sl_i, packed.sl_edge, packed.sl_f, par, acc,
        allowance=par[K.P_TOL],
    )
    act = np.flatnonzero(packed.sl_edge >= 0)
    if act.size == 0:
        raise InvalidParameterError(
            "no contacts at rest: give DemSettings.time_step explicitly for assemblies that start apart"
        )
    st = packed.state
    nb = st.shape[0]
    stiff = np.zeros((3 * nb, 3 * nb))
    for s in act:
        v, a, b = packed.sl_i[s, :3]
        e = packed.sl_edge[s]
        p = vw[v]
        _, _, n, t, _ = _twin._edge_frame(vw, edir, e, p)
        for k, direction in ((packed.sl_f[s, K.F_KN], n), (packed.sl_f[s, K.F_KS], t)):
            w = np.zeros(3 * nb)
            for blk, sgn in ((a, 1.0), (b, -1.0)):
                if not packed.free[blk]:
                    continue
                r = p - st[blk, :2]
                lever = r[0] * direction[1] - r[1] * direction[0]
                sm, si = math.sqrt(packed.mass[blk]), math.sqrt(packed.inertia[blk])
                w[3 * blk : 3 * blk + 3] = sgn * np.array(
                    [direction[0] / sm, direction[1] / sm, lever / si]
                )
            stiff += k * np.outer(w, w)
    if nb <= 500:
        lam = float(np.linalg.eigvalsh(stiff)[-1])
    else:  # Gershgorin bound
        lam = float(np.max(np.sum(np.abs(stiff), axis=1)))
    rows = np.array([lam])
    omega = math.sqrt(float(rows.max()))
    alpha, beta = settings.damping
    xi = alpha / (2 * omega) + beta * omega / 2
    dt = settings.safety * 2.0 / omega * (math.sqrt(1 + xi * xi) - xi)
    return dt, omega


# --------------------------------------------------------------------------- result
@dataclass(frozen=True)
class DemResult:
    """Histories of a distinct-element run, sampled every ``output_interval``.

    Attributes
    ----------
    times : ndarray (nt,)
        s, from the start of the ground motion.
    positions : ndarray (nt, nb, 3)
        Centroid x, y (m) and rotation (rad, counter-clockwise from the undisplaced block) of
        every block (base blocks included; absolute frame).
    velocities : ndarray (nt, nb, 3)
        vx, vy (m/s, absolute) and omega (rad/s), averaged over the two half steps.
    base_displacement, base_velocity : ndarray (nt,)
        The ground's x_g (m) and x_g' (m/s) as integrated inside the stepping.
    joint_opening : ndarray (nt, nj, 2)
        Gap at each end of every recorded joint (m, > 0 open; overlaps are negative), the two
        ends being ``assembly.joints[j].faces`` (intrados, extrados for arches).
    joint_slip : ndarray (nt, nj)
        Tangential offset of the two blocks at the more closed end of each joint, m.
    rotation : ndarray (nt,)
        The rotation measure (rad; see :func:`build_arch_assembly`): comparable with the
        analytical phi, > 0 while the first mechanism opens, < 0 in the mirrored one.
    kinetic, potential, strain, damping, friction, input_work : ndarray (nt,)
        Energies relative to the ground, J: kinetic, gravitational (from t = 0), elastic in the
        contact springs, dissipated by Rayleigh damping, dissipated by friction (slip, and the
        shear energy released when a contact opens), work of the inertial load -m x_g''.
    outcome : DemOutcome
    collapse_time, first_impact_time, first_hinge_time : float or None
        s. ``first_hinge_time``: first sample with a joint open by more than
        ``settings.hinge_opening * reference_length``. ``first_impact_time``: after that, the
        first time the rotation measure returns to zero (linear interpolation between samples),
        i.e. the first link's joints close: the analytical model's first impact.
    time_step : float
        s. ``n_steps`` steps were taken after settling, ``settle_steps`` before.
    """

    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    base_displacement: np.ndarray
    base_velocity: np.ndarray
    joint_opening: np.ndarray
    joint_slip: np.ndarray
    rotation: np.ndarray
    kinetic: np.ndarray
    potential: np.ndarray
    strain: np.ndarray
    damping: np.ndarray
    friction: np.ndarray
    input_work: np.ndarray
    outcome: DemOutcome
    collapse_time: float | None
    first_impact_time: float | None
    first_hinge_time: float | None
    time_step: float
    omega_max: float
    n_steps: int
    settle_steps: int
    settings: DemSettings
    assembly: Assembly
    motion: dict
    g: float

    @property
    def total_energy(self) -> np.ndarray:
        """kinetic + potential + strain + dissipated - input, J (constant up to the scheme)."""
        return (
            self.kinetic + self.potential + self.strain + self.damping + self.friction
            - self.input_work
        )

    @property
    def energy_error(self) -> float:
        """max |total energy - its initial value| / max(input work, kinetic, strain), -."""
        e = self.total_energy
        scale = max(
            float(np.max(np.abs(self.input_work))),
            float(np.max(self.kinetic)),
            float(np.max(self.strain)),
            1e-300,
        )
        return float(np.max(np.abs(e - e[0])) / scale)

    @property
    def hinge_open(self) -> np.ndarray:
        """(nt, nj, 2) bool: joint end open beyond the hinge threshold."""
        thr = self.settings.hinge_opening * self.assembly.reference_length
        return self.joint_opening > thr

    def to_dict(self) -> dict:
        """Summary for JSON (no histories)."""
        return {
            "outcome": self.outcome.value,
            "collapse_time_s": self.collapse_time,
            "first_impact_time_s": self.first_impact_time,
            "first_hinge_time_s": self.first_hinge_time,
            "max_rotation_rad": float(np.max(np.abs(self.rotation))) if self.rotation.size else 0.0,
            "time_step_s": self.time_step,
            "omega_max_rad_s": self.omega_max,
            "steps": self.n_steps,
            "settle_steps": self.settle_steps,
            "energy_error": self.energy_error,
            "dissipated_damping_J": float(self.damping[-1]),
            "dissipated_friction_J": float(self.friction[-1]),
            "g_m_s2": self.g,
            "assembly": self.assembly.to_dict(),
            "motion": self.motion,
            "settings": self.settings.to_dict(),
        }

    def to_table(self) -> dict[str, np.ndarray]:
        """Columns for a tabular export: time, rotation, energies, base motion."""
        return {
            "time_s": self.times,
            "rotation_rad": self.rotation,
            "kinetic_J": self.kinetic,
            "potential_J": self.potential,
            "strain_J": self.strain,
            "damping_J": self.damping,
            "friction_J": self.friction,
            "input_work_J": self.input_work,
            "base_displacement_m": self.base_displacement,
            "base_velocity_m_s": self.base_velocity,
        }


# --------------------------------------------------------------------------- driver
def simulate_dem(
    arch_or_assembly: Arch | Assembly,
    motion: GroundMotion,
    settings: DemSettings | None = None,
    *,
    g: float = STANDARD_GRAVITY,
) -> DemResult:
    """Run the distinct-element model of an arch (or any block assembly) under ``motion``.

    Parameters
    ----------
    arch_or_assembly : Arch or Assembly
        An Arch is built with :func:`build_arch_assembly` (every voussoir a block).
    motion : GroundMotion
        Horizontal ground acceleration (any archquake motion: pulses, records).
    settings : DemSettings, optional
        Default ``DemSettings()`` (the paper's stiffness and damping).
    g : float
        Gravity, m/s^2.

    Returns
    -------
    DemResult
    """
    assembly = (
        build_arch_assembly(arch_or_assembly) if isinstance(arch_or_assembly, VoussoirChain)
        else arch_or_assembly
    )
    if not isinstance(assembly, Assembly):
        raise InvalidParameterError(
            f"simulate_dem needs an Arch or an Assembly, got {type(arch_or_assembly).__name__}"
        )
    settings = DemSettings() if settings is None else settings
    if not isinstance(settings, DemSettings):
        raise InvalidParameterError(f"settings must be a DemSettings, got {type(settings).__name__}")
    kind, gparams = motion.kernel_spec()
    gparams = np.ascontiguousarray(gparams, dtype=float)
    omega = float("nan")
    if settings.time_step is None:
        dt, omega = stable_time_step(assembly, settings, g=g)
    else:
        dt = settings.time_step
    n_steps = int(math.ceil(settings.duration / dt - 1e-9))
    settle_steps = int(math.ceil(settings.settle_time / dt - 1e-9))
    if n_steps + settle_steps > MAX_STEPS:
        raise InvalidParameterError(
            f"{n_steps + settle_steps} time steps of {dt:.3g} s exceed {MAX_STEPS}: shorten the "
            "duration or soften the contact stiffness"
        )
    packed = pack(assembly)
    margin = 0.2 * float(packed.radius[packed.free == 1].min())
    build_slots(packed, neighbour_pairs(packed, margin))
    par = _params(assembly, settings, dt, g)
    acc = np.zeros(K.N_ACC)
    cpar = np.zeros(K.N_COLLAPSE)
    cpar[K.C_BASE] = assembly.base_level
    cpar[K.C_ROT] = settings.collapse_rotation
    cpar[K.C_CROWN_BLOCK] = assembly.crown_block
    crown_local = np.asarray(assembly.crown_point) - assembly.centroids[assembly.crown_block]
    cpar[K.C_CROWN_LX], cpar[K.C_CROWN_LY] = crown_local
    cpar[K.C_CROWN_DROP] = settings.collapse_drop * assembly.reference_length
    dummy_t = np.zeros(0)
    dummy_s = np.zeros((0, assembly.n_blocks, 6))
    dummy_e = np.zeros((0, 8))
    count = np.zeros(1, dtype=np.int64)

    def advance(n0, n_end, out_every, ground_on, settle, out_t, out_s, out_e):
        n = n0
        ref = packed.state[:, :3].copy()
        while True:
            n, status = K.run(
                packed.state, packed.mass, packed.inertia, packed.free, packed.y_ref,
                packed.vloc, packed.vstart, packed.sl_i, packed.sl_edge, packed.sl_f, par, acc,
                kind, gparams, n, n_end, out_every, ground_on, settle, cpar,
                settings.stop_at_collapse and not settle, ref, packed.radius, margin,
                out_t, out_s, out_e, count,
            )
            if not np.all(np.isfinite(packed.state)):
                raise SolverError(
                    "the distinct-element state became non-finite: reduce DemSettings.safety or "
                    "time_step"
                )
            if status == K.STATUS_REBUILD:
                build_slots(packed, neighbour_pairs(packed, margin))
                ref = packed.state[:, :3].copy()
                continue
            return status

    if settle_steps:
        advance(0, settle_steps, 0, False, True, dummy_t, dummy_s, dummy_e)
    # start from rest, with the settled contact forces
    packed.state[:, 3:] = 0.0
    packed.y_ref = packed.state[:, 1].copy()
    acc[:] = 0.0
    out_every = max(1, int(round(settings.output_interval / dt)))
    n_out = n_steps // out_every + 2
    out_t = np.zeros(n_out)
    out_s = np.zeros((n_out, assembly.n_blocks, 6))
    out_e = np.zeros((n_out, 8))
    count[0] = 0
    advance(0, n_steps, out_every, True, False, out_t, out_s, out_e)
    k = int(count[0])
    return _pack_result(
        assembly, settings, motion, g, dt, omega, n_steps, settle_steps,
        out_t[:k], out_s[:k], out_e[:k],
    )


def _pack_result(assembly, settings, motion, g, dt, omega, n_steps, settle_steps, t, s, e):
    pos = s[:, :, :3].copy()
    vel = s[:, :, 3:].copy()
    opening, slip = joint_kinematics(assembly, pos)
    rot = rotation_measure(assembly, pos)
    thr = settings.hinge_opening * assembly.reference_length
    open_any = np.any(opening > thr, axis=(1, 2)) if opening.size else np.zeros(len(t), bool)
    first_hinge = float(t[np.argmax(open_any)]) if np.any(open_any) else None
    collapse_time = _collapse_time(assembly, settings, t, pos)
    first_impact = _first_impact(t, rot, settings.hinge_opening)
    if collapse_time is not None:
        outcome = DemOutcome.COLLAPSE
    elif first_hinge is None:
        outcome = DemOutcome.NO_HINGING
    else:
        outcome = DemOutcome.SURVIVES
    return DemResult(
        times=t.copy(), positions=pos, velocities=vel,
        base_displacement=e[:, 6].copy(), base_velocity=e[:, 7].copy(),
        joint_opening=opening, joint_slip=slip, rotation=rot,
        kinetic=e[:, 0].copy(), potential=e[:, 1].copy(), strain=e[:, 2].copy(),
        damping=e[:, 3].copy(), friction=e[:, 4].copy(), input_work=e[:, 5].copy(),
        outcome=outcome, collapse_time=collapse_time, first_impact_time=first_impact,
        first_hinge_time=first_hinge, time_step=dt, omega_max=omega, n_steps=n_steps,
        settle_steps=settle_steps, settings=settings, assembly=assembly,
        motion=motion.to_dict() if hasattr(motion, "to_dict") else {"name": str(motion)}, g=g,
    )


def _carry(assembly: Assembly, pos: np.ndarray, block: int, point: np.ndarray) -> np.ndarray:
    """World position (nt, 2) of a point fixed to ``block`` (given in the undisplaced assembly)."""
    local = np.asarray(point) - assembly.centroids[block]
    th = pos[:, block, 2]
    c, s = np.cos(th), np.sin(th)
    return np.column_stack(
        [pos[:, block, 0] + c * local[0] - s * local[1], pos[:, block, 1] + s * local[0] + c * local[1]]
    )


def joint_kinematics(assembly: Assembly, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Opening (nt, nj, 2) at both ends and slip (nt, nj) of every recorded joint, m."""
    nt = pos.shape[0]
    nj = len(assembly.joints)
    opening = np.zeros((nt, nj, 2))
    slip = np.zeros((nt, nj))
    for j, joint in enumerate(assembly.joints):
        p0, p1 = joint.points
        tan0 = (p1 - p0) / np.linalg.norm(p1 - p0)
        nrm0 = np.array([tan0[1], -tan0[0]])
        if np.dot(assembly.centroids[joint.right] - assembly.centroids[joint.left], nrm0) < 0:
            nrm0 = -nrm0
        th = pos[:, joint.left, 2]
        c, s = np.cos(th), np.sin(th)
        nrm = np.column_stack([c * nrm0[0] - s * nrm0[1], s * nrm0[0] + c * nrm0[1]])
        tan = np.column_stack([c * tan0[0] - s * tan0[1], s * tan0[0] + c * tan0[1]])
        tang = np.zeros((nt, 2))
        for end in range(2):
            gap = _carry(assembly, pos, joint.right, joint.points[end]) - _carry(
                assembly, pos, joint.left, joint.points[end]
            )
            opening[:, j, end] = np.sum(gap * nrm, axis=1)
            tang[:, end] = np.sum(gap * tan, axis=1)
        closed_end = np.argmin(opening[:, j, :], axis=1)
        slip[:, j] = tang[np.arange(nt), closed_end]
    return opening, slip


def rotation_measure(assembly: Assembly, pos: np.ndarray) -> np.ndarray:
    """The rotation of the assembly's rotation link (see :class:`DemResult`), rad, (nt,)."""
    link = assembly.rotation_link
    a = _carry(assembly, pos, link.block_a, link.point_a)
    b = _carry(assembly, pos, link.block_b, link.point_b)
    d0 = np.asarray(link.point_b) - np.asarray(link.point_a)
    d = b - a
    ang = np.arctan2(d[:, 1], d[:, 0]) - math.atan2(d0[1], d0[0])
    ang = (ang + np.pi) % (2 * np.pi) - np.pi
    return link.sign * np.unwrap(ang)


def _collapse_time(assembly, settings, t, pos) -> float | None:
    cpar = np.zeros(K.N_COLLAPSE)
    cpar[K.C_BASE] = assembly.base_level
    cpar[K.C_ROT] = settings.collapse_rotation
    cpar[K.C_CROWN_BLOCK] = assembly.crown_block
    cpar[K.C_CROWN_LX], cpar[K.C_CROWN_LY] = (
        np.asarray(assembly.crown_point) - assembly.centroids[assembly.crown_block]
    )
    cpar[K.C_CROWN_DROP] = settings.collapse_drop * assembly.reference_length
    if len(t) == 0:
        return None
    crown = _carry(assembly, pos, assembly.crown_block, assembly.crown_point)
    cpar[K.C_CROWN_Y0] = crown[0, 1]
    free = (~np.asarray(assembly.base)).astype(np.int64)
    for k in range(len(t)):
        if K.collapsed(pos[k], free, cpar):
            return float(t[k])
    return None


def _first_impact(t: np.ndarray, rot: np.ndarray, threshold: float) -> float | None:
    big = np.flatnonzero(np.abs(rot) > threshold)
    if big.size == 0:
        return None
    k0 = big[0]
    sign = np.sign(rot[k0])
    after = np.flatnonzero(sign * rot[k0:] <= 0.0)
    if after.size == 0:
        return None
    k = k0 + after[0]
    r0, r1 = rot[k - 1], rot[k]
    frac = r0 / (r0 - r1) if r0 != r1 else 1.0
    return float(t[k - 1] + frac * (t[k] - t[k - 1]))


__all__ = [
    "DemOutcome",
    "DemResult",
    "contact_tolerance",
    "simulate_dem",
    "stable_time_step",
]
