"""Joint forces of the rigid chain (`archquake.rigid`): the line of thrust
and the friction demand of the mechanism in use.

At a recorded sample (q, v) the stepper's next step is repeated (the same contact projection,
`archquake.rigid._step_kernels.project`, at the mid-step configuration, warm-started
from the previous sample's impulses) and each joint's corner impulses over the step, divided by
the time step h, are its forces: N = (p_0 + p_1) / h (compressive), V = p_T / h. Where the
resultant crosses the joint line follows from the two corner forces alone (the tangential one
acts along the joint): e = (p_1 - p_0) / (p_0 + p_1) * d / 2 from the joint's mid-point,
positive towards corner 1 (the extrados of an arch), d the joint's depth; |e| = d/2 at a hinge.

**When the forces are unique.** The impulses are unique exactly when the active contact rows
(every closed corner's normal, one no-slip row per touching joint) are linearly independent:
then H^T p = M (v - v_free) has one solution. That holds while the arch moves on a mechanism
(four or more hinges: 3n - 1 rows or fewer for n blocks) or as a three-hinged arch (3n rows,
independent), and fails whenever a closed part is statically indeterminate: the arch at rest
(3(n + 1) rows for 3n velocities), and every closure that locks a joint while the rest is
closed. There Gauss-Seidel returns one distribution of many, so its |V| / N (the 2.9-14.5 the
rigid-limit study found at isolated closure steps, docs/notes/mechanism.md) bounds nothing.

**Impacts.** A closure that meets a determinate part (a cantilever of locked blocks, a
three-hinged arch) has a unique impulse, but it is an impact, not a force: its corner impulses
over h grow as 1/h, and their ratio is the impact's, not a friction demand (the Coulomb option,
``simulate_rigid(..., friction=mu)``, is the model that answers what friction does there). A
sample is *impulsive* when some block's velocity changes over the step by more than
``IMPULSIVE`` h (g + |x_g''|) (its centroid speed plus L times its rotation rate), an
acceleration no finite force of the motion gives.

**Nearly unloaded joints.** The Moreau step's impulses at a hinge fluctuate from step to step
(the hinge corner's gap crosses the contact tolerance), and at a joint carrying almost nothing
|V| / N is dominated by that: single samples with N a hundredth of its neighbours' and
|V| / N of 16-65 (t/R = 0.19; the semicircle n = 15). Below ``N_MIN`` W (W the weight of the
free blocks) a joint's |V| / N is not reported.

**The rule.** A joint's line of thrust (``eccentricity``) and friction demand are reported at a
sample only where the forces are unique, the sample is not impulsive and the joint carries
N >= ``N_MIN`` W; elsewhere they are NaN, and the summary counts the samples left out. The rank
test: the smallest singular value of the active rows (each scaled to unit norm, in the
mass-scaled velocities) above ``RANK_TOLERANCE`` times the largest.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import archquake.rigid._step_kernels as RK
from archquake.ground.base import has_vertical
from archquake.rigid.model import (
    ACC_SAMPLES,
    DEFAULT_TIME_STEP,
    GAP_TOLERANCE,
    HOLD_TOLERANCE,
    MAX_SWEEPS,
    SOLVER_TOLERANCE,
    RigidModel,
)

#: A sample is impulsive when a block's velocity changes over the step by more than this many
#: h (g + |x_g''|) (module docstring).
IMPULSIVE = 10.0
#: Least normal force, as a fraction of the free blocks' weight, at which |V| / N is reported.
N_MIN = 0.01
#: The line of thrust is at a face of a joint when within this fraction of d/2 of it.
HINGE_TOLERANCE = 1.0e-6
#: Rows are independent when their smallest singular value (rows scaled to unit norm, columns
#: to the bodies' mass and inertia) exceeds this.
RANK_TOLERANCE = 1.0e-8


@dataclass(frozen=True)
class JointForceHistory:
    """Forces at every joint of a rigid-chain run, at its recorded samples.

    Attributes
    ----------
    times : ndarray (nt,)
        s.
    normal, shear : ndarray (nt, nj)
        N: compressive normal force, tangential force (along corner 0 -> 1).
    eccentricity : ndarray (nt, nj)
        m: where the resultant crosses the joint line, from its mid-point, positive towards
        corner 1 (the extrados); NaN where the joint carries no force. Read it where
        ``reported`` (the rule, module docstring).
    half_depth : ndarray (nj,)
        m.
    unique : ndarray (nt,) bool
        The active contacts are independent: the forces are unique (module docstring).
    impulsive : ndarray (nt,) bool
        A block's velocity jumps over the step (an impact, module docstring).
    weight : float
        N, of the free blocks.
    """

    times: np.ndarray
    normal: np.ndarray
    shear: np.ndarray
    eccentricity: np.ndarray
    half_depth: np.ndarray
    unique: np.ndarray
    impulsive: np.ndarray
    weight: float

    @property
    def reported(self) -> np.ndarray:
        """(nt, nj) bool: the rule of the module docstring."""
        return ((self.unique & ~self.impulsive)[:, None]
                & (self.normal >= N_MIN * self.weight))

    @property
    def relative_eccentricity(self) -> np.ndarray:
        """e / (d/2), (nt, nj), where ``reported`` (NaN elsewhere): +-1 at a hinge (the rigid
        corners carry no resultant outside the section)."""
        return np.where(self.reported, self.eccentricity / self.half_depth[None, :], np.nan)

    @property
    def friction_demand(self) -> np.ndarray:
        """|V| / N, (nt, nj); NaN where not reported (no force, or not unique)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            out = np.abs(self.shear) / self.normal
        return np.where(self.reported, out, np.nan)

    def state_at(self, t: float) -> dict:
        """For JSON: the joints at the recorded sample nearest ``t`` (s): its time
        ``sample_time_s``; per joint the line of thrust as e / (d/2) (+-1 at a hinge, the
        resultant at a corner; None where not reported) and |V| / N (None where not reported);
        ``face_joints``, the joints where the line of thrust reaches a face (every open hinge,
        and any closed joint loaded on one corner only: a hinge about to open); the largest
        friction demand and its joint (None if none is reported). The resultant of rigid corner
        contacts never leaves the section."""
        k = int(np.argmin(np.abs(self.times - float(t))))
        rel = self.relative_eccentricity[k]
        fd = self.friction_demand[k]
        faces = [int(j) for j in np.flatnonzero(np.abs(rel) >= 1.0 - HINGE_TOLERANCE)]
        best = int(np.nanargmax(fd)) if np.any(np.isfinite(fd)) else None
        return {"time_s": float(t), "sample_time_s": float(self.times[k]),
                "unique": bool(self.unique[k]), "impulsive": bool(self.impulsive[k]),
                "relative_eccentricity": [None if not np.isfinite(x) else float(x) for x in rel],
                "friction_demand": [None if not np.isfinite(x) else float(x) for x in fd],
                "face_joints": faces,
                "max_friction_demand": None if best is None else float(fd[best]),
                "max_friction_demand_joint": best}

    def summary(self) -> dict:
        """For JSON: the largest friction demand over the reported samples, where and when; the
        largest |e| / (d/2) at a closed joint (both corners loaded: how near the line of thrust
        comes to opening a new hinge; at a hinge it is 1); how many samples were left out."""
        fd = self.friction_demand
        rel = np.abs(self.relative_eccentricity)
        out: dict = {"samples": int(self.unique.size),
                     "indeterminate_samples": int((~self.unique).sum()),
                     "impulsive_samples": int((self.unique & self.impulsive).sum())}
        if np.any(np.isfinite(fd)):
            k, j = np.unravel_index(int(np.nanargmax(fd)), fd.shape)
            out.update(max_friction_demand=float(fd[k, j]), max_friction_demand_time_s=float(
                self.times[k]), max_friction_demand_joint=int(j))
            closed = np.where(rel < 1.0 - 1e-9, rel, np.nan)  # both corners loaded: no hinge
            out["max_relative_eccentricity_closed"] = (float(np.nanmax(closed))
                                                       if np.any(np.isfinite(closed)) else None)
        else:
            out.update(max_friction_demand=None, max_friction_demand_time_s=None,
                       max_friction_demand_joint=None, max_relative_eccentricity_closed=None)
        out["rule"] = (f"reported where the joint forces are unique (not at rest, not at "
                       f"closures locking an indeterminate part), the step is not an impact "
                       f"(no velocity jump above {IMPULSIVE:g} h (g + |a_g|)) and the joint "
                       f"carries N >= {N_MIN:g} W")
        return out


def _rows(q, ja, jb, gaps, nrm, tan, pts, gap_tol, inv_sqrt_m, inv_sqrt_i, p_warm=None,
          hold_tol=0.0) -> np.ndarray:
    """The active rows (as the kernel builds them, its hold included: ``p_warm``, ``hold_tol``),
    in the mass-scaled velocities."""
    nb = q.shape[0]
    rows = []

    def entry(row, body, p, d, sign):
        if body < 0:
            return
        rx, ry = p[0] - q[body, 0], p[1] - q[body, 1]
        row[3 * body] += sign * d[0] * inv_sqrt_m[body]
        row[3 * body + 1] += sign * d[1] * inv_sqrt_m[body]
        row[3 * body + 2] += sign * (rx * d[1] - ry * d[0]) * inv_sqrt_i[body]

    for j in range(len(ja)):
        act = gaps[j] <= gap_tol
        if p_warm is not None:
            act = act | ((p_warm[j, :2] > 0.0) & (gaps[j] <= hold_tol))
        for c in range(2):
            if act[c]:
                r = np.zeros(3 * nb)
                entry(r, ja[j], pts[j, c, 0], nrm[j], -1.0)
                entry(r, jb[j], pts[j, c, 1], nrm[j], 1.0)
                rows.append(r)
        if act[0] or act[1]:
            w = 0.5 if (act[0] and act[1]) else (1.0 if act[0] else 0.0)
            pa = w * pts[j, 0, 0] + (1 - w) * pts[j, 1, 0]
            pb = w * pts[j, 0, 1] + (1 - w) * pts[j, 1, 1]
            r = np.zeros(3 * nb)
            entry(r, ja[j], pa, tan[j], -1.0)
            entry(r, jb[j], pb, tan[j], 1.0)
            rows.append(r)
    return np.array(rows).reshape(len(rows), 3 * nb)


def _independent(h: np.ndarray) -> bool:
    if h.shape[0] == 0:
        return True
    if h.shape[0] > h.shape[1]:
        return False
    h = h / np.linalg.norm(h, axis=1, keepdims=True)
    s = np.linalg.svd(h, compute_uv=False)
    return bool(s[-1] > RANK_TOLERANCE * s[0])


def _setup(run, motion, g: float | None, every: int) -> dict:
    """What both probes of `joint_forces` read: the model, the step and the projection's
    settings, the samples used and their ground accelerations."""
    res = run
    g = res.g if g is None else float(g)
    model = RigidModel.build(res.assembly)
    stepped = bool(np.isfinite(run.stepper_time_step))
    h = run.stepper_time_step if stepped else DEFAULT_TIME_STEP
    lref = res.assembly.reference_length
    # a stepper's run: its step, position-level correction included (the tangential part
    # needs the run's contact history and is left out); an event run's: the plain cone
    correction, hold = (h, HOLD_TOLERANCE * lref) if stepped else (0.0, 0.0)
    picks = np.arange(0, res.times.size, max(1, int(every)))
    times = res.times[picks]
    # each sample's step: the mean of ``ACC_SAMPLES`` mid-points, as ``mean_acceleration``
    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    t = times[:, None] + h * sub[None, :]
    acc = np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(t.shape).mean(1)
    base = res.assembly.base  # the model's joints: those not between two base blocks
    vacc = (np.asarray(motion.vertical_acceleration(t.ravel()), dtype=float).reshape(
        t.shape).mean(1) if has_vertical(motion) else np.empty(0))
    depth = np.array([np.linalg.norm(np.asarray(jt.points[1]) - np.asarray(jt.points[0]))
                      for jt in res.assembly.joints if not (base[jt.left] and base[jt.right])])
    return {"res": res, "g": g, "model": model, "h": h, "lref": lref, "correction": correction,
            "hold": hold, "gap_tol": GAP_TOLERANCE * lref,
            "tol": SOLVER_TOLERANCE * np.sqrt(g * lref),
            "mu": (0.0 if run.friction_coefficient is None
                   else float(run.friction_coefficient)),
            "picks": picks,
            "times": times, "acc": acc, "depth": depth, "vacc": vacc}


def _history(s: dict, imp: np.ndarray, unique: np.ndarray, impulsive: np.ndarray
             ) -> JointForceHistory:
    """The forces from the impulses over each sample's step, ``imp`` (nt, nj, 3), N s."""
    h, depth = s["h"], s["depth"]
    normal = (imp[:, :, 0] + imp[:, :, 1]) / h
    shear = imp[:, :, 2] / h
    pn = imp[:, :, 0] + imp[:, :, 1]
    ok = pn > 0.0
    depths = np.broadcast_to(depth, pn.shape)
    ecc = np.full(pn.shape, np.nan)
    ecc[ok] = (imp[:, :, 1][ok] - imp[:, :, 0][ok]) / pn[ok] * 0.5 * depths[ok]
    return JointForceHistory(times=s["times"].copy(), normal=normal, shear=shear,
                             eccentricity=ecc, half_depth=0.5 * depth, unique=unique,
                             impulsive=impulsive,
                             weight=float(s["g"] * s["model"].mass.sum()))


def _entries(rows, q, body, p, d, sign, isq_m, isq_i) -> None:
    """One body's entries of a contact row, for every sample at once (as `_rows`'s
    ``entry``): ``rows`` (ns, 3 nb), ``q`` (ns, nb, 3), the point ``p`` and direction ``d``
    (ns, 2)."""
    if body < 0:
        return
    rx, ry = p[:, 0] - q[:, body, 0], p[:, 1] - q[:, body, 1]
    rows[:, 3 * body] += sign * d[:, 0] * isq_m[body]
    rows[:, 3 * body + 1] += sign * d[:, 1] * isq_m[body]
    rows[:, 3 * body + 2] += sign * (rx * d[:, 1] - ry * d[:, 0]) * isq_i[body]


def _unique(model: RigidModel, active: np.ndarray, qm: np.ndarray, nrm: np.ndarray,
            tan: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """The rank test of every sample (nt,) bool: the rows of `_rows`, built at once for
    all samples that share a set of active corners, and one batched SVD per set."""
    nt, nj = active.shape[:2]
    nb = qm.shape[1]
    isq_m, isq_i = np.sqrt(1.0 / model.mass), np.sqrt(1.0 / model.inertia)
    unique = np.ones(nt, dtype=bool)
    keys, inverse = np.unique(active.reshape(nt, 2 * nj), axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    for key_index, key in enumerate(keys):
        sel = np.flatnonzero(inverse == key_index)
        act = key.reshape(nj, 2)
        nrows = int(act.sum() + act.any(axis=1).sum())
        if nrows == 0:
            continue
        if nrows > 3 * nb:
            unique[sel] = False
            continue
        rows = np.zeros((sel.size, nrows, 3 * nb))
        q = qm[sel]

        def entry(r, body, p, d, sign, rows=rows, q=q):
            _entries(rows[:, r], q, body, p, d, sign, isq_m, isq_i)

        r = 0
        for j in range(nj):
            ja, jb = int(model.ja[j]), int(model.jb[j])
            n_j, t_j, p_j = nrm[sel, j], tan[sel, j], pts[sel, j]
            for c in range(2):
                if act[j, c]:
                    entry(r, ja, p_j[:, c, 0], n_j, -1.0)
                    entry(r, jb, p_j[:, c, 1], n_j, 1.0)
                    r += 1
            if act[j, 0] or act[j, 1]:
                w = 0.5 if (act[j, 0] and act[j, 1]) else (1.0 if act[j, 0] else 0.0)
                pa = w * p_j[:, 0, 0] + (1 - w) * p_j[:, 1, 0]
                pb = w * p_j[:, 0, 1] + (1 - w) * p_j[:, 1, 1]
                entry(r, ja, pa, t_j, -1.0)
                entry(r, jb, pb, t_j, 1.0)
                r += 1
        rows = rows / np.linalg.norm(rows, axis=2, keepdims=True)
        s = np.linalg.svd(rows, compute_uv=False)
        unique[sel] = s[:, -1] > RANK_TOLERANCE * s[:, 0]
    return unique


def joint_forces(run, motion, *, g: float | None = None, every: int = 1) -> JointForceHistory:
    """The joint forces of ``run`` (a `RigidRun`) at its
    recorded samples, under the ``motion`` it was run with (module docstring).

    Friction: the run's (``run.friction_coefficient``; None, no slip). ``every``: use every
    this many recorded samples. Cost: one contact projection per sample used, all in one
    compiled call (`archquake.rigid._force_kernels.probe`; `joint_forces_reference` is its
    plain twin), which also proves most samples' rank test by a bound; the SVD settles the
    rest. A run of the event integrator (``solver="events"``, no time step of its own)
    is probed with the stepper's default step."""
    import archquake.rigid._force_kernels as FK

    s = _setup(run, motion, g, every)
    res, model, picks = s["res"], s["model"], s["picks"]
    fb = model.free_blocks
    # contiguous, as every caller of the probe passes them (one compiled signature)
    pos = np.ascontiguousarray(res.positions[picks][:, fb, :])
    vel = np.ascontiguousarray(res.velocities[picks][:, fb, :])
    imp, impulsive, active, qm, nrm, tan, pts, certified = FK.probe(
        model.chain, _probe_stepping(s), pos, vel, res.base_displacement[picks],
        res.base_velocity[picks], s["acc"], s["lref"], IMPULSIVE, s["vacc"])
    unique = certified == 1
    open_ = np.flatnonzero(certified < 0)  # not settled by the certificate: the SVD decides
    if open_.size:
        unique[open_] = _unique(model, active[open_], qm[open_], nrm[open_], tan[open_],
                                pts[open_])
    return _history(s, imp, unique, impulsive)


def _probe_stepping(s: dict) -> RK.Stepping:
    """The probe's step and projection settings (`_setup`'s) as a `RK.Stepping`."""
    return RK.Stepping(float(s["h"]), float(s["g"]), float(s["gap_tol"]), float(s["tol"]),
                       MAX_SWEEPS, float(s["mu"]), RK.METHOD_PGS, float(s["correction"]),
                       float(s["hold"]), RK.ACTIVE_SET_ITERATIONS)


def joint_forces_at_rest(run, motion, *, g: float | None = None, every: int = 1
                         ) -> JointForceHistory:
    """`joint_forces` of a run at rest (``run.at_rest``: the motion never reaches the
    onset of hinging), with three projections instead of one a sample.

    The locked arch is statically indeterminate (3(n + 1) independent rows or more for 3n
    velocities, module docstring), so no sample's forces are unique and none is reported, as
    the rank test of every sample would find. The forces themselves are one admissible
    distribution, as the probe's: the projection's at no ground acceleration and at the
    motion's two peaks, and at any sample the convex combination of the two that bracket its
    acceleration, which balances the sample's load exactly (equilibrium is linear in the
    forces and the load) and keeps every contact force inside its cone (a convex set)."""
    import archquake.rigid._force_kernels as FK

    s = _setup(run, motion, g, every)
    model = s["model"]
    acc = s["acc"]
    nt = acc.size
    levels = np.array([0.0, max(float(acc.max(initial=0.0)), 0.0),
                       min(float(acc.min(initial=0.0)), 0.0)])
    q0, v0 = model.rest()
    pos = np.broadcast_to(q0, (3, *q0.shape)).copy()
    vel = np.broadcast_to(v0, (3, *v0.shape)).copy()
    zeros = np.zeros(3)
    imp3 = FK.probe(model.chain, _probe_stepping(s), pos, vel, zeros, zeros, levels, s["lref"],
                    IMPULSIVE, s["vacc"])[0]
    up = acc >= 0.0
    peak = np.where(up, levels[1], levels[2])
    with np.errstate(invalid="ignore", divide="ignore"):
        w = np.where(peak != 0.0, acc / peak, 0.0)
    far = np.where(up[:, None, None], imp3[1][None], imp3[2][None])
    imp = (1.0 - w)[:, None, None] * imp3[0][None] + w[:, None, None] * far
    return _history(s, imp, np.zeros(nt, dtype=bool), np.zeros(nt, dtype=bool))


def joint_forces_reference(run, motion, *, g: float | None = None, every: int = 1
                           ) -> JointForceHistory:
    """`joint_forces` by a plain loop over the samples (one projection and one rank test
    each, in Python): the twin a test holds the compiled probe to."""
    s = _setup(run, motion, g, every)
    res, model, picks, h, acc = s["res"], s["model"], s["picks"], s["h"], s["acc"]
    g, lref, hold = s["g"], s["lref"], s["hold"]
    inv_m, inv_i = 1.0 / model.mass, 1.0 / model.inertia
    isq_m, isq_i = np.sqrt(inv_m), np.sqrt(inv_i)
    fb = model.free_blocks
    nt, nj = picks.size, len(model.ja)
    imp_all = np.zeros((nt, nj, 3))
    unique = np.zeros(nt, dtype=bool)
    impulsive = np.zeros(nt, dtype=bool)
    p_warm = np.zeros((nj, 3))
    for k, i in enumerate(picks):
        q = res.positions[i, fb, :].copy()
        v = res.velocities[i, fb, :].copy()
        q[:, 0] -= res.base_displacement[i]
        v[:, 0] -= res.base_velocity[i]
        qm = q + 0.5 * h * v
        gaps, nrm, tan, pts = RK.geometry(qm, model.ja, model.jb, model.arm_a, model.arm_b,
                                          model.n0, model.t0)
        vf = v.copy()
        gk = g + s["vacc"][k] if s["vacc"].size else g
        vf[:, 0] -= h * acc[k]
        vf[:, 1] -= h * gk
        cfg = RK.solving(s["gap_tol"], s["tol"], MAX_SWEEPS, s["mu"], correction=s["correction"],
                         hold_tol=hold)
        vn, imp, _, _ = RK.project(model.chain, cfg, qm, RK.Geometry(gaps, nrm, tan, pts), vf,
                                   p_warm, np.empty(0), np.empty(0))
        unique[k] = _independent(_rows(qm, model.ja, model.jb, gaps, nrm, tan, pts,
                                       s["gap_tol"], isq_m, isq_i, p_warm, hold))
        p_warm = imp
        dv = vn - v
        jump = float(np.max(np.hypot(dv[:, 0], dv[:, 1]) + np.abs(dv[:, 2]) * lref))
        impulsive[k] = jump > IMPULSIVE * h * (gk + abs(acc[k]))
        imp_all[k] = imp
    return _history(s, imp_all, unique, impulsive)


def joint_numbers(run) -> list[int] | None:
    """The arch's joint number of each joint a rigid run records, or None where they are all
    of the arch's joints in order (the joints inside a backing are not recorded: the assembly's
    ``cut_joints``)."""
    asm = run.assembly
    cuts = asm.meta.get("cut_joints")
    numbers = [int(cuts[j.index]) for j in asm.joints] if cuts else None
    return None if numbers is None or numbers == list(range(len(numbers))) else numbers


def on_arch_joints(state: dict, numbers: list[int] | None, n_joints: int) -> dict:
    """A joint-force state or summary (`JointForceHistory.state_at`, ``.summary()``) with its
    joints numbered as the arch's: ``numbers`` from `joint_numbers` (None: already so),
    ``n_joints`` the arch's joints (voussoirs + 1); the joints not recorded get None."""
    if numbers is None:
        return state
    out = dict(state)
    for key in ("relative_eccentricity", "friction_demand"):
        if key in out:
            full: list = [None] * n_joints
            for j, v in zip(numbers, out[key], strict=True):
                full[j] = v
            out[key] = full
    if "face_joints" in out:
        out["face_joints"] = [numbers[j] for j in out["face_joints"]]
    if out.get("max_friction_demand_joint") is not None:
        out["max_friction_demand_joint"] = numbers[out["max_friction_demand_joint"]]
    return out


__all__ = ["IMPULSIVE", "N_MIN", "RANK_TOLERANCE", "JointForceHistory", "joint_forces",
           "joint_forces_at_rest", "joint_forces_reference", "joint_numbers", "on_arch_joints"]
