"""Plain references of the block models' post-processing: main's per-sample, per-joint and
per-pair code before it was vectorised (the rigid chain's ``absolute`` closure and rest check;
`archquake.blocks.result`'s ``joint_kinematics``, ``collapse_time``, ``crossings``,
``hinge_sets`` and ``mirror_link``), kept verbatim. Test and benchmark only: no production
code imports it (tests/rigid/test_postproc.py holds the fast code to it, and
benchmarks/bench_rigid_postproc.py measures against it).
"""

from __future__ import annotations

import math

import numpy as np

import archquake.blocks._kernels as K
from archquake.blocks.assembly import RotationLink
from archquake.blocks.result import (
    HingeSet,
    _hinges_at,
    carry,
    collapse_parameters,
    crown_height,
    excitation_end,
    hinge_label,
    rest_threshold,
    settled,
)


def absolute(model, qk, vk, u, w):
    """One sample of the rigid chain (``model``: a RigidModel; q, v (nb, 3) relative to the
    ground, u, w its displacement and velocity) as the DEM's recorded state (n_blocks, 6)."""
    free = (~np.asarray(model.assembly.base, dtype=bool)).astype(np.int64)
    st = np.zeros((len(free), 6))
    st[:, :2] = np.asarray(model.assembly.centroids, float)
    st[:, 0] += u
    st[:, 3] = w
    st[model.free_blocks, :3] = qk
    st[model.free_blocks, 0] += u
    st[model.free_blocks, 3:] = vk
    st[model.free_blocks, 3] += w
    return st


def joint_kinematics(assembly, pos):
    """Opening (nt, nj, 2) and slip (nt, nj), m: one joint at a time."""
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
            gap = carry(assembly, pos, joint.right, joint.points[end]) - carry(
                assembly, pos, joint.left, joint.points[end])
            opening[:, j, end] = np.sum(gap * nrm, axis=1)
            tang[:, end] = np.sum(gap * tan, axis=1)
        closed_end = np.argmin(opening[:, j, :], axis=1)
        slip[:, j] = tang[np.arange(nt), closed_end]
    return opening, slip


def collapse_time(assembly, settings, t, pos):
    """The first sample meeting a collapse criterion, s, or None: one sample at a time."""
    if len(t) == 0:
        return None
    cpar = collapse_parameters(assembly, settings, float(crown_height(assembly, pos[:1])[0]))
    free = (~np.asarray(assembly.base)).astype(np.int64)
    for k in range(len(t)):
        if K.collapsed(np.ascontiguousarray(pos[k]), free, cpar):  # the kernels' one layout
            return float(t[k])
    return None


def crossings(t, rot, threshold, stop=None):
    """The impacts, s: one sample at a time."""
    stop = len(t) if stop is None else stop
    out = []
    armed_sign = 0.0
    for k in range(stop):
        r = rot[k]
        if armed_sign == 0.0:
            if abs(r) > threshold:
                armed_sign = math.copysign(1.0, r)
            continue
        if armed_sign * r <= 0.0 and k > 0:
            r0 = rot[k - 1]
            frac = r0 / (r0 - r) if r0 != r else 1.0
            out.append(float(t[k - 1] + frac * (t[k] - t[k - 1])))
            armed_sign = 0.0
            if abs(r) > threshold:
                armed_sign = math.copysign(1.0, r)
    return np.array(out)


def hinge_sets(result, every=0.005, relative=0.1):
    """The hinge sets: the hinges of every read sample, one at a time."""
    t = result.times
    dt = float(np.median(np.diff(t))) if t.size > 1 else every
    stride = max(1, int(round(every / dt))) if dt > 0 else 1
    end = t.size if result.collapse_time is None else int(np.searchsorted(t, result.collapse_time)) + 1
    out = []
    last = ""
    for k in range(0, min(end, t.size), stride):
        h = _hinges_at(result.assembly, result.criteria, result.joint_opening[k], relative)
        label = hinge_label(h)
        if label == last:
            continue
        kind = "rest" if not label else ("onset" if not last else "change")
        out.append(HingeSet(round(float(t[k]), 9), label, max(len(h) - 3, 0), kind))
        last = label
    return tuple(out)


def at_rest(model, g, times, vs, motion):
    """The samples so far (flat lists of times, s, and velocities (nb, 3)) end at rest."""
    window = rest_threshold(model.assembly, g)[1]
    k = len(times)
    while k > 1 and times[k - 1] > times[-1] - window:
        k -= 1
    kin = [model.kinetic_energy(v) for v in vs[k - 1:]]
    return settled(model.assembly, g, np.array(times[k - 1:]), np.array(kin),
                   excitation_end(motion))


def mirror_link(assembly, *, rtol=1e-9):
    """The mirror image of ``assembly.rotation_link``, or None: one pair of blocks at a time."""
    polys = assembly.polygons
    tol = rtol * max(float(np.max(np.abs(p))) for p in polys)
    image = {}
    for i, p in enumerate(polys):
        q = p * np.array([-1.0, 1.0])
        for j, pj in enumerate(polys):
            if (pj.shape == q.shape and bool(assembly.base[i]) == bool(assembly.base[j])
                    and float(np.max(np.min(np.hypot(*(q[:, None, :] - pj[None, :, :]).T), axis=0)))
                    <= tol
                    and (assembly.base[i] or math.isclose(float(assembly.masses[i]),
                                                          float(assembly.masses[j]), rel_tol=1e-9))):
                image[i] = j
                break
        else:
            return None
    link = assembly.rotation_link
    flip = np.array([-1.0, 1.0])
    return RotationLink(image[link.block_a], np.asarray(link.point_a) * flip,
                        image[link.block_b], np.asarray(link.point_b) * flip, link.sign)
