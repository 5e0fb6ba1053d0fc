"""The result of a block model's run (the distinct-element model, the rigid chain), in the
four-link model's vocabulary.

`BlockResult` holds the sampled histories of a run (`archquake.dem.simulate_dem`,
`archquake.rigid.simulate_rigid`) and computes from them what the four-link
`SimulationResult` reports: the `Outcome`, the onset of hinging, the impacts, the peak
rotation of each half cycle, the collapse half cycle and time, and ``to_dict()`` with the keys
of `archquake.outcome.RESULT_KEYS`. The post-processing (joint openings and slips, the
rotation measure, the collapse criteria of `archquake.blocks.criteria.BlockCriteria`) lives
here too; the drivers (`archquake.dem.run`, `archquake.rigid.run`) only pack, step and
record.

The rotation measure
--------------------
``rotation`` is the rotation of a chord of the assembly, ``RotationLink``: for an arch the chord
from hinge A to hinge B of the four-link model's first mechanism (the one a ground acceleration towards
-x opens), signed > 0 in that mechanism's opening sense, like the four-link
``History.signed_rotation``. When the assembly is its own mirror image (x -> -x) and the
mirror-image mechanism opens first (the ground accelerates towards +x when the hinges open:
`mirror_opens_first`), the measure is the mirror-image chord's, so that a mirrored
excitation gives the exact mirror of the measure (negative first), with the same impacts, half
cycles and outcome.

Impacts
-------
The DEM's impacts are the sign changes of the rotation measure before the collapse, each
counted only after the rotation has exceeded ``criteria.hinge_opening`` rad on the current side
(small rocking below it, contact vibration at rest, is not counted); times are interpolated
linearly between samples. The collapse half cycle is 1 + the impacts before the collapse.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol, Self

import numpy as np

import archquake.blocks._kernels as K
from archquake.blocks.assembly import Assembly, RotationLink
from archquake.blocks.criteria import BlockCriteria
from archquake.outcome import Outcome
from archquake.result import shared_columns, shared_keys, write_csv


class RunSettings(Protocol):
    """What a `BlockResult` records of its run's settings: their ``criteria``, the planned
    ``duration`` (s) and ``to_dict()`` (JSON ``settings``): an
    `archquake.dem.DemSettings` for the distinct-element model, a
    `archquake.blocks.criteria.BlockRunSettings` for the rigid chain."""

    @property
    def criteria(self) -> BlockCriteria: ...

    @property
    def duration(self) -> float: ...

    def to_dict(self) -> dict: ...


# --------------------------------------------------------------------------- kinematics
def carry(assembly: Assembly, pos: np.ndarray, block: int, point) -> np.ndarray:
    """World position (nt, 2), m, of a point fixed to ``block`` (given in the undisplaced
    assembly), for the recorded positions ``pos`` (nt, nb, >= 3)."""
    local = np.asarray(point, dtype=float) - assembly.centroids[block]
    th = pos[:, block, 2]
    c, s = np.cos(th), np.sin(th)
    return np.column_stack(
        [pos[:, block, 0] + c * local[0] - s * local[1], pos[:, block, 1] + s * local[0] + c * local[1]]
    )


def _joint_frames(assembly: Assembly) -> tuple[np.ndarray, ...]:
    """Per recorded joint: left and right blocks (nj,), the normal and the tangent of the
    undisplaced joint (nj, 2), and each end's position relative to the left and to the right
    block's centroid (nj, 2 ends, 2), m. The normal points from left into right."""
    nj = len(assembly.joints)
    left = np.zeros(nj, dtype=np.int64)
    right = np.zeros(nj, dtype=np.int64)
    nrm0 = np.zeros((nj, 2))
    tan0 = np.zeros((nj, 2))
    local_left = np.zeros((nj, 2, 2))
    local_right = np.zeros((nj, 2, 2))
    for j, joint in enumerate(assembly.joints):
        p0, p1 = joint.points
        tan = (p1 - p0) / np.linalg.norm(p1 - p0)
        nrm = np.array([tan[1], -tan[0]])
        if np.dot(assembly.centroids[joint.right] - assembly.centroids[joint.left], nrm) < 0:
            nrm = -nrm
        left[j], right[j], nrm0[j], tan0[j] = joint.left, joint.right, nrm, tan
        for end in range(2):
            point = np.asarray(joint.points[end], dtype=float)
            local_left[j, end] = point - assembly.centroids[joint.left]
            local_right[j, end] = point - assembly.centroids[joint.right]
    return left, right, nrm0, tan0, local_left, local_right


def joint_kinematics(assembly: Assembly, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Opening (nt, nj, 2) at both ends and slip (nt, nj) of every recorded joint, m.

    Each end's gap is the right block's copy of the end point minus the left block's
    (`carry`), resolved on the joint's normal and tangent turned with the left block;
    the slip is the tangential gap at the more closed end. One compiled loop,
    `archquake.blocks._kernels.joint_openings`, over every sample and joint."""
    nt = pos.shape[0]
    nj = len(assembly.joints)
    opening = np.zeros((nt, nj, 2))
    slip = np.zeros((nt, nj))
    if nj and nt:
        left, right, nrm0, tan0, local_left, local_right = _joint_frames(assembly)
        theta = pos[:, :, 2]
        K.joint_openings(np.ascontiguousarray(pos, dtype=float), np.cos(theta), np.sin(theta),
                         left, right, nrm0, tan0, local_left, local_right, opening, slip)
    return opening, slip


def link_rotation(assembly: Assembly, pos: np.ndarray, link: RotationLink) -> np.ndarray:
    """``link.sign`` times the rotation of the chord from A to B, rad, (nt,), unwrapped."""
    a = carry(assembly, pos, link.block_a, link.point_a)
    b = carry(assembly, pos, link.block_b, link.point_b)
    d0 = np.asarray(link.point_b) - np.asarray(link.point_a)
    d = b - a
    ang = np.arctan2(d[:, 1], d[:, 0]) - math.atan2(d0[1], d0[0])
    ang = (ang + np.pi) % (2 * np.pi) - np.pi
    return link.sign * np.unwrap(ang)


def mirror_link(assembly: Assembly, *, rtol: float = 1e-9) -> RotationLink | None:
    """The mirror image (x -> -x) of ``assembly.rotation_link``, or None if the assembly is not
    its own mirror image (every block's polygon reflected onto another block's, to ``rtol``
    of the assembly's size, with the same mass).

    The sign stays: reflection reverses angles, so in the mirror-image motion the mirrored
    chord's measure is minus the original chord's measure in the original motion.
    """
    polys = assembly.polygons
    tol = rtol * max(float(np.max(np.abs(p))) for p in polys)
    base = [bool(b) for b in assembly.base]
    masses = [float(m) for m in assembly.masses]
    groups: dict[tuple, list[int]] = {}  # blocks by polygon shape, in order
    for j, pj in enumerate(polys):
        groups.setdefault(pj.shape, []).append(j)
    stacks = {shape: np.stack([polys[j] for j in js]) for shape, js in groups.items()}
    image = {}
    for i, p in enumerate(polys):
        q = p * np.array([-1.0, 1.0])
        # for each candidate: the farthest of q's vertices from the candidate's nearest vertex
        d = q[None, :, None, :] - stacks[q.shape][:, None, :, :]
        far = np.max(np.min(np.hypot(d[..., 0], d[..., 1]), axis=2), axis=1)
        for j, dist in zip(groups[q.shape], far):
            if (base[i] == base[j] and float(dist) <= tol
                    and (base[i] or math.isclose(masses[i], masses[j], rel_tol=1e-9))):
                image[i] = j
                break
        else:
            return None
    link = assembly.rotation_link
    flip = np.array([-1.0, 1.0])
    return RotationLink(image[link.block_a], np.asarray(link.point_a) * flip,
                        image[link.block_b], np.asarray(link.point_b) * flip, link.sign)


def rotation_measure(assembly: Assembly, pos: np.ndarray, *, mirrored: bool
                     ) -> tuple[np.ndarray, RotationLink]:
    """The rotation measure, rad, (nt,), and the link it is taken on (module docstring).

    The assembly's link, unless ``mirrored`` (the mirror-image mechanism opened first: see
    `mirror_opens_first`) and the assembly is its own mirror image.
    """
    link = assembly.rotation_link
    mirror = mirror_link(assembly) if mirrored else None
    if mirror is None:
        return link_rotation(assembly, pos, link), link
    return link_rotation(assembly, pos, mirror), mirror


def mirror_opens_first(times: np.ndarray, base_velocity: np.ndarray, onset: float | None,
                       window: float = 0.01) -> bool:
    """Whether the ground drove the arch towards -x when its hinges opened, so that the
    mirror image of the first mechanism opened (a ground acceleration towards -x loads the
    arch towards +x and opens the first mechanism; towards +x, its mirror).

    Read from the ground velocity's change over the ``window`` s (at least one sample) before
    the onset of hinging: an acceleration at the onset must exceed the arch's collapse
    acceleration, so its sign is the driving direction. A mirrored excitation flips that sign
    exactly, so the choice, and with it the rotation measure, is mirror-symmetric. (An earlier
    rule compared which of the two chords turned first; on an arch whose hinges are not
    symmetric the DEM's real mechanism turns both chords and that rule picked the wrong one.)
    """
    if onset is None or times.size < 2:
        return False
    i = int(np.searchsorted(times, onset))
    i = min(max(i, 1), times.size - 1)
    j = min(int(np.searchsorted(times, times[i] - window)), i - 1)
    return bool(base_velocity[i] - base_velocity[j] > 0.0)


def crown_height(assembly: Assembly, pos: np.ndarray) -> np.ndarray:
    """Height of the crown point, m, (nt,) (NaN without a crown block)."""
    if assembly.crown_block < 0:
        return np.full(pos.shape[0], np.nan)
    return carry(assembly, pos, assembly.crown_block, assembly.crown_point)[:, 1]


def collapse_parameters(assembly: Assembly, criteria: BlockCriteria, crown_y0: float
                        ) -> np.ndarray:
    """The packed collapse criteria of `archquake.blocks._kernels.collapsed`: a free block's
    centroid below the springings, a block turned by more than ``collapse_rotation``, or the
    crown fallen by more than ``collapse_drop`` reference lengths below ``crown_y0`` (m, its
    height at the start of the ground motion)."""
    cpar = np.zeros(K.N_COLLAPSE)
    cpar[K.C_BASE] = assembly.base_level
    cpar[K.C_ROT] = criteria.collapse_rotation
    cpar[K.C_CROWN_BLOCK] = assembly.crown_block
    cpar[K.C_CROWN_LX], cpar[K.C_CROWN_LY] = (
        np.asarray(assembly.crown_point) - assembly.centroids[assembly.crown_block]
    )
    cpar[K.C_CROWN_Y0] = crown_y0
    cpar[K.C_CROWN_DROP] = criteria.collapse_drop * assembly.reference_length
    return cpar


def collapse_time(assembly: Assembly, criteria: BlockCriteria, t: np.ndarray, pos: np.ndarray
                  ) -> float | None:
    """The first sample meeting a collapse criterion, s (the crown's drop measured from the
    first sample), or None."""
    if len(t) == 0:
        return None
    cpar = collapse_parameters(assembly, criteria, float(crown_height(assembly, pos[:1])[0]))
    free = (~np.asarray(assembly.base)).astype(np.int64)
    k = K.first_collapsed(np.ascontiguousarray(pos[:, :, :3], dtype=float), free, cpar)
    return float(t[k]) if k >= 0 else None


# --------------------------------------------------------------------------- half cycles
def crossings(t: np.ndarray, rot: np.ndarray, threshold: float, stop: int | None = None
              ) -> np.ndarray:
    """Times (s) at which ``rot`` changes sign, each after it exceeded ``threshold`` on the
    current side, among the first ``stop`` samples: the DEM's impacts (module docstring).

    Armed at the first sample beyond the threshold, a crossing is the next sample on the other
    side (or at zero); the time is interpolated linearly between it and the sample before, and
    the next arming is that sample itself if it is beyond the threshold, else the next one that
    is. Each step is a search in the sorted indices of the samples beyond the threshold and of
    those <= 0 and >= 0, so the cost grows with the crossings, not with the samples."""
    stop = len(t) if stop is None else stop
    r = np.asarray(rot[:stop], dtype=float)
    beyond = np.flatnonzero(np.abs(r) > threshold)
    side = {1.0: np.flatnonzero(r <= 0.0), -1.0: np.flatnonzero(r >= 0.0)}
    out: list[float] = []
    k = -1  # the last sample looked at
    while True:
        i = int(np.searchsorted(beyond, k, side="right"))
        if i == beyond.size:
            break
        armed = beyond[i]
        while True:
            sign = math.copysign(1.0, r[armed])
            other = side[sign]
            i = int(np.searchsorted(other, armed, side="right"))
            if i == other.size:
                return np.array(out)
            k = int(other[i])
            r0, r1 = rot[k - 1], rot[k]
            frac = r0 / (r0 - r1) if r0 != r1 else 1.0
            out.append(float(t[k - 1] + frac * (t[k] - t[k - 1])))
            if not abs(r1) > threshold:
                break
            armed = k
    return np.array(out)


def half_cycle_peaks(t: np.ndarray, rot: np.ndarray, impacts: np.ndarray, end: float) -> np.ndarray:
    """Largest |rot| (rad) between consecutive impacts, and from the last one to ``end`` (s)."""
    edges = np.concatenate([[-np.inf], impacts, [end]])
    mag = np.abs(rot)
    peaks = []
    for a, b in zip(edges[:-1], edges[1:]):
        sel = (t > a) & (t <= b)
        if np.any(sel):
            peaks.append(float(mag[sel].max()))
    return np.array(peaks)


# --------------------------------------------------------------------------- rest
#: A block model is at rest when its kinetic energy relative to the ground stays below this
#: fraction of W L (W the weight of the free blocks, L the assembly's reference length) for
#: `REST_WINDOW` sqrt(L/g) after the end of the excitation (`settled`). A rocking
#: arch passes through zero kinetic energy only at the instants its motion reverses, never
#: over a window. 1e-6 W L would lift the arch's weight by a millionth of L, an order below
#: what opening a hinge by the hinge threshold (``hinge_opening`` = 1e-4 L) takes, and after
#: the excitation the energy can only decrease. Measured (Oppenheim's arch after a 1.0 g,
#: 0.20 s step; last impact 4.1 s rigid, 4.9 s DEM): the rigid chain falls to ~1e-35 W L at
#: once; the DEM's contacts keep vibrating, 2.4e-6 W L at 6 s, 5e-8 at 7-8 s.
REST_KINETIC = 1.0e-6
REST_WINDOW = 1.0


def rest_threshold(assembly: Assembly, g: float) -> tuple[float, float]:
    """(kinetic energy below which a block model counts as still, J; the window it must stay
    there, s): `REST_KINETIC` W L and `REST_WINDOW` sqrt(L/g)."""
    free = ~np.asarray(assembly.base, dtype=bool)
    weight = g * float(np.asarray(assembly.masses, dtype=float)[free].sum())
    lref = float(assembly.reference_length)
    return REST_KINETIC * weight * lref, REST_WINDOW * math.sqrt(lref / g)


def excitation_end(motion) -> float | None:
    """When a ground motion ends (its ``duration``), s; None if it does not say."""
    try:
        return float(motion.duration)
    except (AttributeError, TypeError, ValueError):
        return None


def settled(assembly: Assembly, g: float, times: np.ndarray, kinetic: np.ndarray,
            excitation_end: float | None) -> bool:
    """Whether a block model's run ends at rest: its kinetic energy (J, relative to the
    ground) stays below `rest_threshold` over the last window, and that window begins
    after ``excitation_end`` (s; None: not checked)."""
    if len(times) < 2:
        return False
    k_max, window = rest_threshold(assembly, g)
    t_last = float(times[-1])
    if excitation_end is not None and t_last - window < float(excitation_end):
        return False
    if t_last - float(times[0]) < window:
        return False
    sel = np.asarray(times) >= t_last - window
    return bool(np.max(np.asarray(kinetic)[sel]) <= k_max)


# --------------------------------------------------------------------------- hinges
#: A joint is a hinge when its wider end is open by more than this fraction of the widest
#: opening at that instant (`open_hinges`).
HINGE_RELATIVE = 0.1
#: Hinge sets are read every this many s (`hinge_sets`).
HINGE_SAMPLING_S = 0.005


def _hinges_at(assembly: Assembly, criteria: BlockCriteria, opening_k: np.ndarray,
               relative: float) -> list[tuple[int, str]]:
    widest = opening_k.max(axis=1)
    floor = max(criteria.hinge_opening * assembly.reference_length,
                relative * float(widest.max(initial=0.0)))
    joints = assembly.meta.get("cut_joints", list(range(len(opening_k))))
    out = []
    for j, joint in enumerate(assembly.joints):
        if widest[j] > floor:
            closed = int(np.argmin(opening_k[j]))
            out.append((int(joints[j]), joint.faces[closed]))
    return out


def open_hinges(result: BlockResult, time: float, *, relative: float = HINGE_RELATIVE
                ) -> list[tuple[int, str]]:
    """(joint, face) of the hinges of a block model at the recorded sample nearest ``time`` (s).

    A joint is a hinge when its wider end is open by more than ``relative`` times the widest
    opening of any joint at that instant (and by more than ``criteria.hinge_opening`` t); its
    face is the other, more closed, end. The relative threshold keeps the four-or-so working
    hinges and drops the sub-millimetre gaps that the rocking blocks open at other joints
    (at t = 0.5 s of Figure 9: 76 and 99 mm at the working hinges, < 5 mm elsewhere but one).
    (Also `archquake.compare.dem_hinges`.)
    """
    k = int(np.argmin(np.abs(result.times - time)))
    return _hinges_at(result.assembly, result.criteria, result.joint_opening[k], relative)


def hinge_label(hinges: list[tuple[int, str]]) -> str:
    """``"0i 2e 3e 5i 7e"``: joint and face initial of each hinge, as the four-link model's
    `MechanismEvent` writes them."""
    return " ".join(f"{j}{f[0]}" for j, f in hinges)


@dataclass(frozen=True)
class HingeSet:
    """The hinges of a block model from ``time_s`` on (`hinge_sets`).

    ``hinges``: the label (`hinge_label`, "" when every joint is closed);
    ``degrees_of_freedom``: hinges - 3 (an arch between two fixed supports; 0 when fewer than
    four hinges are open); ``kind``: ``onset`` (hinges open from a closed arch), ``change``,
    or ``rest`` (every joint closed again). Keys as `MechanismEvent`'s."""

    time_s: float
    hinges: str
    degrees_of_freedom: int
    kind: str

    def to_dict(self) -> dict:
        return {"time_s": self.time_s, "hinges": self.hinges,
                "degrees_of_freedom": self.degrees_of_freedom, "kind": self.kind}


def hinge_sets(result: BlockResult, *, every: float = HINGE_SAMPLING_S,
               relative: float = HINGE_RELATIVE) -> tuple[HingeSet, ...]:
    """Every hinge set the arch passed through, with the time it was first seen: the open
    hinges (`open_hinges`) read every ``every`` s (at least every sample) until the
    collapse or the end, one entry each time the set changes. Sets lasting less than ``every``
    may be missed (the staggered closures of an impact last a few ms)."""
    t = result.times
    if t.size == 0:
        return ()
    dt = float(np.median(np.diff(t))) if t.size > 1 else every
    stride = max(1, int(round(every / dt))) if dt > 0 else 1
    end = t.size if result.collapse_time is None else int(np.searchsorted(t, result.collapse_time)) + 1
    ks = np.arange(0, min(end, t.size), stride)
    if ks.size == 0:
        return ()
    # the hinges of every read sample at once (as _hinges_at); a label is written only where
    # the open joints or their closed ends change from the sample read before
    opening = result.joint_opening[ks]
    widest = opening.max(axis=2)
    top = relative * widest.max(axis=1, initial=0.0)
    thr = result.criteria.hinge_opening * result.assembly.reference_length
    floor = np.where(top > thr, top, thr)
    hinge = widest > floor[:, None]
    closed = np.where(hinge, np.argmin(opening, axis=2), -1)
    changed = np.ones(ks.size, dtype=bool)
    changed[1:] = np.any(closed[1:] != closed[:-1], axis=1)
    cuts = result.assembly.meta.get("cut_joints", list(range(opening.shape[1])))
    joints = [cuts[jt.index] for jt in result.assembly.joints]  # the recorded ones
    faces = [joint.faces for joint in result.assembly.joints]
    out: list[HingeSet] = []
    last = ""
    for r in np.flatnonzero(changed):
        h = [(int(joints[j]), faces[j][closed[r, j]]) for j in np.flatnonzero(hinge[r])]
        label = hinge_label(h)
        if label == last:
            continue
        kind = "rest" if not label else ("onset" if not last else "change")
        out.append(HingeSet(round(float(t[ks[r]]), 9), label, max(len(h) - 3, 0), kind))
        last = label
    return tuple(out)


# --------------------------------------------------------------------------- result
@dataclass(frozen=True)
class BlockResult:
    """Histories of a block model's run (the distinct-element model, the rigid chain), sampled
    every ``output_interval``, and what became of the assembly in the four-link model's
    vocabulary. (``archquake.dem.DemResult`` is this class, under its former name.)

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
        The rotation measure, rad (module docstring): comparable with the four-link
        ``History.signed_rotation``, > 0 while the first mechanism opens, < 0 in its mirror.
    rotation_link : RotationLink
        The chord ``rotation`` is measured on (the assembly's, or its mirror image).
    kinetic, potential, strain, damping, friction, input_work : ndarray (nt,)
        Energies relative to the ground, J: kinetic, gravitational (from t = 0), elastic in the
        contact springs, dissipated by Rayleigh damping, dissipated by friction (slip, and the
        shear energy released when a contact opens), work of the inertial load -m x_g''.
    outcome : Outcome
    onset_time : float or None
        s: first sample with a joint open by more than ``criteria.hinge_opening *
        reference_length``.
    impact_times : ndarray (k,)
        s: the sign changes of ``rotation`` before the collapse (module docstring).
    peak_rotation : ndarray (half cycles,)
        Largest |rotation| in each half cycle (before the collapse), rad; empty without hinging.
    collapse_half_cycle : int or None
        1 + the impacts before the collapse.
    collapse_time : float or None
        s: first sample where a free block's centroid is below the springings, the crown has
        fallen by ``collapse_drop`` reference lengths, or a block has turned by
        ``collapse_rotation`` (later than the four-link crest: compare outcomes and half
        cycles, not collapse times).
    time_step : float
        s. ``n_steps`` steps were taken after settling (fewer if the run stopped at the
        collapse), ``settle_steps`` before.
    omega_max : float
        rad/s, the highest contact frequency of the distinct-element model (NaN where it does
        not apply).
    settings : RunSettings
        The run's settings as ``to_dict()`` records them: their ``criteria`` (a
        `BlockCriteria`) classify the samples, ``duration`` (s) is the planned length.
    assembly : Assembly
    motion : dict
        The ground motion's ``to_dict()``.
    g : float
        m/s^2.
    final_state : str
        ``collapsed``, ``rest`` or ``moving``.
    excitation_end : float or None
        s, when the ground motion ends.
    """

    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    base_displacement: np.ndarray
    base_velocity: np.ndarray
    joint_opening: np.ndarray
    joint_slip: np.ndarray
    rotation: np.ndarray
    rotation_link: RotationLink
    kinetic: np.ndarray
    potential: np.ndarray
    strain: np.ndarray
    damping: np.ndarray
    friction: np.ndarray
    input_work: np.ndarray
    outcome: Outcome
    onset_time: float | None
    impact_times: np.ndarray
    peak_rotation: np.ndarray
    collapse_half_cycle: int | None
    collapse_time: float | None
    time_step: float
    omega_max: float
    n_steps: int
    settle_steps: int
    settings: RunSettings
    assembly: Assembly
    motion: dict
    g: float
    final_state: str = "moving"
    excitation_end: float | None = None

    @classmethod
    def from_samples(cls, assembly: Assembly, settings: RunSettings, motion: dict, g: float,
                     time_step: float, omega_max: float, n_steps: int, settle_steps: int,
                     times: np.ndarray, states: np.ndarray, energies: np.ndarray, *,
                     excitation_end: float | None = None, **extras: Any) -> Self:
        """Post-process the recorded samples of a run.

        The verdict (docs/notes/mechanism.md, "An honest verdict for the block models"):
        ``collapse`` at the first sample meeting a collapse criterion; ``no_hinging`` if no
        joint opened; ``survives`` only if the run ends at rest (`settled`: kinetic
        energy below ``REST_KINETIC`` W L for ``REST_WINDOW`` sqrt(L/g) after the end of the
        excitation); otherwise, hinges having opened and the arch still moving at the end,
        ``indeterminate``.

        Parameters
        ----------
        settings : RunSettings
            Its ``criteria`` are read; it is recorded as it is.
        excitation_end : float, optional
            s: when the ground motion ends (None: the rest window is not checked against it).
        times : (nt,), s
        states : (nt, nb, 6): x, y, theta, vx, vy, omega per block
        energies : (nt, 8): kinetic, potential, strain, damping, friction, input work (J),
            base displacement (m), base velocity (m/s)
        **extras
            Further fields of a subclass (the rigid chain's `archquake.rigid.RigidRun`).
        """
        t = np.array(times, dtype=float)
        pos = states[:, :, :3].copy()
        vel = states[:, :, 3:].copy()
        e = energies
        opening, slip = joint_kinematics(assembly, pos)
        criteria = settings.criteria
        thr = criteria.hinge_opening * assembly.reference_length
        open_any = np.any(opening > thr, axis=(1, 2)) if opening.size else np.zeros(len(t), bool)
        onset = float(t[np.argmax(open_any)]) if np.any(open_any) else None
        rot, link = rotation_measure(assembly, pos,
                                     mirrored=mirror_opens_first(t, e[:, 7], onset))
        t_collapse = collapse_time(assembly, criteria, t, pos)
        stop = len(t) if t_collapse is None else int(np.searchsorted(t, t_collapse))
        impacts = crossings(t, rot, criteria.hinge_opening, stop)
        if onset is None:
            peaks = np.zeros(0)
        else:
            end = float(t[-1]) if t_collapse is None else t_collapse
            peaks = half_cycle_peaks(t, rot, impacts, end)
        if t_collapse is not None:
            outcome, half, final = Outcome.COLLAPSE, 1 + int(impacts.size), "collapsed"
        else:
            rest = settled(assembly, g, t, e[:, 0], excitation_end)
            final = "rest" if rest else "moving"
            if onset is None:
                outcome = Outcome.NO_HINGING
            else:
                outcome = Outcome.SURVIVES if rest else Outcome.INDETERMINATE
            half = None
        return cls(
            times=t, positions=pos, velocities=vel,
            base_displacement=e[:, 6].copy(), base_velocity=e[:, 7].copy(),
            joint_opening=opening, joint_slip=slip, rotation=rot, rotation_link=link,
            kinetic=e[:, 0].copy(), potential=e[:, 1].copy(), strain=e[:, 2].copy(),
            damping=e[:, 3].copy(), friction=e[:, 4].copy(), input_work=e[:, 5].copy(),
            outcome=outcome, onset_time=onset, impact_times=impacts, peak_rotation=peaks,
            collapse_half_cycle=half, collapse_time=t_collapse, time_step=time_step,
            omega_max=omega_max, n_steps=n_steps, settle_steps=settle_steps, settings=settings,
            assembly=assembly, motion=motion, g=g, final_state=final,
            excitation_end=excitation_end, **extras,
        )

    @property
    def criteria(self) -> BlockCriteria:
        """The thresholds the samples were classified by (``settings.criteria``)."""
        return self.settings.criteria

    @property
    def verdict_reason(self) -> str:
        """One sentence: why the outcome is what it is (the rule of `from_samples`)."""
        k_max, window = rest_threshold(self.assembly, self.g)
        if self.outcome is Outcome.COLLAPSE:
            return "a collapse criterion was met (crown fallen, a block below the springings or turned)"
        if self.final_state == "rest":
            return (f"at rest: kinetic energy below {REST_KINETIC:g} W L over the last "
                    f"{window:.3g} s, after the excitation")
        if self.outcome is Outcome.NO_HINGING:
            return "no joint opened"
        return (f"still moving at the end of the run ({self.end_time:.3g} s): kinetic energy "
                f"above {REST_KINETIC:g} W L in the last {window:.3g} s"
                + ("" if self.excitation_end is None or self.end_time - window >= self.excitation_end
                   else ", or the run ends before a rest window after the excitation")
                + "; run longer to decide")

    def hinge_sets(self, *, every: float = HINGE_SAMPLING_S) -> tuple[HingeSet, ...]:
        """Every hinge set the arch passed through, with times (`hinge_sets`)."""
        return hinge_sets(self, every=every)

    @property
    def first_impact_time(self) -> float | None:
        """The first of ``impact_times``, s (None before any impact)."""
        return float(self.impact_times[0]) if self.impact_times.size else None

    @property
    def half_cycles(self) -> int:
        return int(self.peak_rotation.shape[0])

    @property
    def end_time(self) -> float:
        """Time of the last sample, s (the collapse, when the run stopped there)."""
        return float(self.times[-1]) if self.times.size else 0.0

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
        thr = self.criteria.hinge_opening * self.assembly.reference_length
        return self.joint_opening > thr

    def to_dict(self) -> dict:
        """Summary for JSON (no histories): the keys of `archquake.outcome.RESULT_KEYS`,
        shared with the four-link result (``final_state``: ``collapsed`` or None, the DEM runs
        for a fixed time with no rest criterion), then the DEM's own."""
        return {
            **shared_keys(self, "dem", self.final_state),
            "mechanisms": [e.to_dict() for e in self.hinge_sets()],
            "verdict": self.verdict_reason,
            "excitation_end_s": self.excitation_end,
            "end_time_s": self.end_time,
            "energy_error": self.energy_error,
            "dissipated_damping_J": float(self.damping[-1]) if self.damping.size else 0.0,
            "dissipated_friction_J": float(self.friction[-1]) if self.friction.size else 0.0,
            "assembly": self.assembly.to_dict(),
            "excitation": self.motion,
            "settings": self.settings.to_dict(),
            "solver": {"steps": self.n_steps, "settle_steps": self.settle_steps,
                       "time_step_s": self.time_step, "omega_max_rad_s": _finite_or_none(self.omega_max),
                       "t_end_s": self.settings.duration},
        }

    @property
    def crown_displacement(self) -> np.ndarray:
        """(nt, 2): the crown point's displacement dx, dy relative to the ground, m, from its
        place in the undisplaced assembly (NaN without a crown block)."""
        if self.assembly.crown_block < 0:
            return np.full((self.times.size, 2), np.nan)
        point = np.asarray(self.assembly.crown_point, dtype=float)
        moved = carry(self.assembly, self.positions, self.assembly.crown_block, point) - point
        moved[:, 0] -= self.base_displacement
        return moved

    @property
    def hinge_events(self) -> tuple[HingeSet, ...]:
        """Every hinge set the arch passed through (`hinge_sets` at its default
        sampling), as `archquake.result.ModelResult.hinge_events`."""
        return self.hinge_sets()

    def to_table(self) -> dict[str, np.ndarray]:
        """Columns for a tabular export: `archquake.result.TABLE_COLUMNS` (time, crown
        displacement, rotation, kinetic and potential energy), then the other energies and the
        base motion."""
        return {
            **shared_columns(self),
            "strain_J": self.strain,
            "damping_J": self.damping,
            "friction_J": self.friction,
            "input_work_J": self.input_work,
            "base_displacement_m": self.base_displacement,
            "base_velocity_m_s": self.base_velocity,
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write `to_table` as CSV (`archquake.result.write_csv`)."""
        return write_csv(self.to_table(), path)



def _finite_or_none(value: float) -> float | None:
    """``value``, or None where it does not apply (the rigid chain has no omega_max: NaN)."""
    return float(value) if math.isfinite(value) else None


__all__ = [
    "HINGE_RELATIVE",
    "REST_KINETIC",
    "REST_WINDOW",
    "HINGE_SAMPLING_S",
    "BlockResult",
    "RunSettings",
    "HingeSet",
    "collapse_parameters",
    "collapse_time",
    "crossings",
    "crown_height",
    "excitation_end",
    "half_cycle_peaks",
    "hinge_label",
    "hinge_sets",
    "joint_kinematics",
    "link_rotation",
    "mirror_link",
    "mirror_opens_first",
    "open_hinges",
    "rest_threshold",
    "rotation_measure",
    "settled",
]
