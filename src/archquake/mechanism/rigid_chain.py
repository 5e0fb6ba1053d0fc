"""The rigid limit of the distinct-element model: rigid blocks with unilateral, plastic, no-slip
joint contacts, any number of open hinges (issue 16).

Why this model. The four-link mechanism (Eq. 2) moves with one degree of freedom and its hinges
fixed; the migrating reference (:mod:`archquake.mechanism.migration`) switches between one-degree
mechanisms and has to re-express the configuration at each switch. The DEM shows five-hinge
phases of 0.1-0.4 s and joints closing one after another. A chain of rigid blocks whose joints
may open at either corner has all of these motions at once, and needs no choice of mechanism:

* each block (every voussoir, :class:`archquake.dem.assembly.Assembly`, the DEM's own
  description, so both models read the same blocks, masses and joints) is a rigid body
  (x, y, theta), in the frame of the ground (inertial load -m x_g'');
* each joint has two corner contacts (intrados, extrados) with a unilateral normal constraint
  (gap >= 0, compressive impulse), and while either corner is in contact, no sliding (tangential
  relative velocity zero; the friction demand |p_T| / p_N is recorded and reported, to be read
  against mu = 0.8), or optionally Coulomb friction (``friction=mu``);
* Moreau-Jean time stepping at velocity level (:mod:`archquake.mechanism._rigid_kernels`): each
  step's velocity is the kinetic-metric projection of the unconstrained velocity onto the cone of
  admissible velocities of the contacts that are closed at mid-step, i.e. perfectly plastic
  impacts (e = 0), Moreau's sweeping process, with a position-level correction: an open
  contact corner's row closes its gap within the step (a penetration is not pushed out), its
  joint's no-slip row undoes the slip since the contact began, and a corner that pushed stays
  in contact within ``HOLD_TOLERANCE`` (without it a pivot's drift, second order in h, opened
  it and the block slid). Hinges open anywhere (a
  contact whose impulse would be tensile separates), migrate, two or more degrees of freedom
  move at once, closures are staggered or simultaneous as the geometry makes them; for a
  simultaneous closure at phi = 0 the step is exactly the chain law's cone projection
  (:func:`archquake.mechanism.impact_chain.cone_projection`; test).

Why time stepping and not events: the number of possible contact states is 3^(n+1), the set of
active contacts changes during a half cycle tens of times, and closures accumulate (a closing
joint can reopen its neighbour at once); Moreau-Jean needs no event location and is robust to
accumulation, at first order in h. The convergence in h is measured (docs/mechanism.md).

Energies are relative to the ground. The results are a :class:`archquake.dem.DemResult` built
by the DEM's own post-processing (:meth:`DemResult.from_samples`, through
:func:`_samples_to_result`, which any stepper of this model hands its samples to), so impacts,
hinges, collapse criteria and the rotation measure are read exactly as in the DEM; in it,
``strain`` is zero and the ``damping`` column holds the energy removed by the contact
projections (the plastic impacts, the scheme's O(h) loss in persistent contacts, and the
position correction's work, ``RigidRun.correction_work``), not Rayleigh damping.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from archquake._validate import require_gravity, require_positive, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.dem.assembly import Assembly, build_arch_assembly
from archquake.dem.result import DemResult, collapse_parameters, crown_height, excitation_end
from archquake.dem.settings import MAX_DURATION, DemSettings
from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import check_motion
from archquake.mechanism import _rigid_kernels as RK

#: Default time step, s (convergence in docs/mechanism.md: halving it changes the energy kept
#: over Oppenheim's first half cycle by < 0.01).
DEFAULT_TIME_STEP = 1.0e-4
#: A corner is in contact when its gap is below this fraction of the assembly's reference length.
GAP_TOLERANCE = 1.0e-9
#: The stepper's position-level correction (``_rigid_kernels.run``): a corner that pushed at the
#: previous step stays in contact while its gap is below this fraction of the reference length
#: (it must exceed a step's drift, r omega^2 h^2 / 2: 7e-8 m on the parabolic arch of
#: docs/mechanism.md), and every contact's normal row is bound to close its gap in one step.
HOLD_TOLERANCE = 1.0e-6
#: Gauss-Seidel stops when a sweep changes no velocity by more than this times sqrt(g L), L the
#: reference length (or after ``MAX_SWEEPS``). 1e-9 runs 2 times faster and changes the energy
#: kept over Oppenheim's half cycle by < 1e-4, but mirror symmetry then holds to 1e-4 t only
#: (1e-6 t at this default) and the slow onset agrees with Eq. 2 to 3e-5 (1e-6).
SOLVER_TOLERANCE = 1.0e-11
MAX_SWEEPS = 5000
#: Most samples at which ``RigidRun.joint_forces`` evaluates the forces (strided evenly).
FORCE_SAMPLES = 4000
#: Sub-samples per step for the step's mean ground acceleration.
ACC_SAMPLES = 16


@dataclass(frozen=True)
class RigidModel:
    """An :class:`Assembly` packed for the stepper: free bodies and joint corners.

    ``body`` maps assembly block -> free-body index (-1 for base blocks); for joint j,
    ``ja[j]``/``jb[j]`` are the free bodies on its ``left``/``right`` side (-1: the base),
    ``arm_a[j, c]``/``arm_b[j, c]`` corner c's position relative to that body's centroid in the
    undisplaced assembly (for a base side, the corner itself), m; ``n0[j]`` the joint normal
    from left into right, ``t0[j]`` the direction from corner 0 to corner 1."""

    assembly: Assembly
    body: np.ndarray
    free_blocks: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    centroids: np.ndarray
    ja: np.ndarray
    jb: np.ndarray
    arm_a: np.ndarray
    arm_b: np.ndarray
    n0: np.ndarray
    t0: np.ndarray

    @classmethod
    def build(cls, arch_or_assembly: VoussoirChain | Assembly) -> RigidModel:
        asm = (build_arch_assembly(arch_or_assembly)
               if isinstance(arch_or_assembly, VoussoirChain) else arch_or_assembly)
        if not isinstance(asm, Assembly):
            raise InvalidParameterError(
                f"the rigid model needs an arch or an Assembly, got {type(asm).__name__}")
        base = np.asarray(asm.base, dtype=bool)
        free_blocks = np.flatnonzero(~base)
        body = np.full(len(base), -1, dtype=np.int64)
        body[free_blocks] = np.arange(free_blocks.size)
        cents = np.asarray(asm.centroids, dtype=float)
        nj = len(asm.joints)
        ja = np.zeros(nj, np.int64)
        jb = np.zeros(nj, np.int64)
        arm_a = np.zeros((nj, 2, 2))
        arm_b = np.zeros((nj, 2, 2))
        n0 = np.zeros((nj, 2))
        t0 = np.zeros((nj, 2))
        for j, joint in enumerate(asm.joints):
            p = np.asarray(joint.points, dtype=float)
            tan = (p[1] - p[0]) / np.linalg.norm(p[1] - p[0])
            nrm = np.array([tan[1], -tan[0]])
            if np.dot(cents[joint.right] - cents[joint.left], nrm) < 0:  # as joint_kinematics
                nrm = -nrm
            n0[j], t0[j] = nrm, tan
            ja[j], jb[j] = body[joint.left], body[joint.right]
            arm_a[j] = p - (cents[joint.left] if ja[j] >= 0 else 0.0)
            arm_b[j] = p - (cents[joint.right] if jb[j] >= 0 else 0.0)
        return cls(asm, body, free_blocks, np.asarray(asm.masses, float)[free_blocks].copy(),
                   np.asarray(asm.inertias, float)[free_blocks].copy(), cents[free_blocks].copy(),
                   ja, jb, arm_a, arm_b, n0, t0)

    @property
    def n_bodies(self) -> int:
        return int(self.free_blocks.size)

    def rest(self) -> tuple[np.ndarray, np.ndarray]:
        """The undisplaced configuration and zero velocity, (nb, 3) each."""
        q = np.zeros((self.n_bodies, 3))
        q[:, :2] = self.centroids
        return q, np.zeros_like(q)

    def gaps(self, q: np.ndarray) -> np.ndarray:
        """Corner gaps (nj, 2), m, of the configuration ``q`` (nb, 3), positive open."""
        return RK.geometry(np.asarray(q, float), self.ja, self.jb, self.arm_a, self.arm_b,
                           self.n0, self.t0)[0]

    def kinetic_energy(self, v: np.ndarray) -> float:
        """J, of the velocities ``v`` (nb, 3)."""
        return 0.5 * float(self.mass @ (v[:, 0] ** 2 + v[:, 1] ** 2) + self.inertia @ v[:, 2] ** 2)

    def potential_energy(self, q: np.ndarray, g: float = STANDARD_GRAVITY) -> float:
        """J, relative to the undisplaced configuration."""
        return float(g * self.mass @ (q[:, 1] - self.centroids[:, 1]))

    def project(self, q: np.ndarray, v: np.ndarray, *, tol: float | None = None,
                max_sweeps: int = 100_000) -> tuple[np.ndarray, np.ndarray]:
        """One contact projection at configuration ``q`` of the velocity ``v`` (no time step:
        an impact): the velocities after it (nb, 3) and the joint impulses (nj, 3), N s."""
        q = np.asarray(q, float)
        gaps, nrm, tan, pts = RK.geometry(q, self.ja, self.jb, self.arm_a, self.arm_b, self.n0,
                                          self.t0)
        scale = max(float(np.max(np.abs(v))), 1e-300)
        tol = 1e-14 * scale if tol is None else tol
        vn, imp, _, _ = RK.project(q, np.asarray(v, float), 1.0 / self.mass, 1.0 / self.inertia,
                                   self.ja, self.jb, gaps, nrm, tan, pts,
                                   GAP_TOLERANCE * self.assembly.reference_length,
                                   np.zeros((len(self.ja), 3)), tol, max_sweeps, 0.0)
        return vn, imp


@dataclass(frozen=True)
class RigidRun:
    """A rigid-chain history.

    ``result``: the samples as a :class:`DemResult` (module docstring); ``time_step`` s;
    ``max_penetration_m``: largest negative gap of the run (the velocity-level scheme's drift);
    ``correction_work``: J, the part of the ``damping`` column (the kinetic energy the contact
    projections removed) that is the work of the position-level correction
    (``_rigid_kernels.D_CORRECTION``; 0 for the event integrator, whose own time steps leave it
    out);
    ``friction_demand``: (nt,) largest |p_T| / p_N of any joint since the previous sample;
    ``max_sweeps``: most Gauss-Seidel sweeps of a step; ``residual``: largest velocity
    correction of a step's last sweep, m/s; ``wall_s``: wall time of the stepping;
    ``friction``: the joints' Coulomb coefficient, None for no sliding; ``motion``: the ground
    motion it was run with; ``events``: with ``solver="events"``, the event integrator's
    record (:func:`archquake.mechanism.rigid_events.run_events`: counters, the event log, the
    times the time stepper took over), else None (and ``time_step`` is then NaN: the step is
    adaptive).
    """

    result: DemResult
    time_step: float
    max_penetration_m: float
    friction_demand: np.ndarray
    max_sweeps: int
    residual: float
    wall_s: float
    friction: float | None = None
    motion: object = field(default=None, repr=False, compare=False)
    correction_work: float = 0.0
    events: dict | None = field(default=None, repr=False, compare=False)

    @property
    def max_friction_demand(self) -> float:
        return float(self.friction_demand.max(initial=0.0))

    @cached_property
    def joint_forces(self):
        """The joint forces, line of thrust and friction demand at the recorded samples (at most
        ``FORCE_SAMPLES`` of them, evenly strided):
        :func:`archquake.mechanism.rigid_forces.joint_forces`, with its reporting rule."""
        from archquake.mechanism.rigid_forces import joint_forces

        if self.motion is None:
            raise InvalidParameterError("this run does not know its ground motion")
        every = max(1, -(-self.result.times.size // FORCE_SAMPLES))
        return joint_forces(self, self.motion, every=every)

    @property
    def outcome(self):
        """The :class:`~archquake.outcome.Outcome` (the DEM's post-processing, ``result``)."""
        return self.result.outcome

    def to_dict(self, *, joint_forces: bool = True) -> dict:
        """Summary for JSON: ``DemResult.to_dict()`` (the keys of
        :data:`archquake.outcome.RESULT_KEYS` first) with ``model`` ``"rigid_chain"``, then the
        stepper's own diagnostics under ``rigid``. ``joint_forces=False`` leaves out the joint
        forces' summary (a post-processing that costs more than the run: sweeps skip it)."""
        out = self.result.to_dict()
        out["model"] = "rigid_chain"
        out["hinges_model"] = "moving"
        out["friction_coefficient"] = self.friction
        if joint_forces and self.motion is not None:
            out["joint_forces"] = self.joint_forces.summary()
        out["rigid"] = {"solver": "events" if self.events is not None else "time stepping",
                        "time_step_s": (None if self.events is not None else self.time_step),
                        "max_penetration_m": self.max_penetration_m,
                        "correction_work_j": self.correction_work,
                        "max_sweeps": self.max_sweeps, "residual_m_s": self.residual,
                        "wall_s": self.wall_s}
        if self.events is not None:
            from archquake.mechanism.rigid_events import events_summary

            out["rigid"]["events"] = events_summary(self.events)
        return out


def _at_rest(model: RigidModel, g: float, times: list, vs: list, motion) -> bool:
    """The samples so far end at rest (:func:`archquake.dem.result.settled`). ``times`` and
    ``vs`` are the recorded chunks, (n,) and (n, nb, 3) each; only the last window's are read."""
    from archquake.dem.result import rest_threshold, settled

    window = rest_threshold(model.assembly, g)[1]
    t_last = float(times[-1][-1])
    first = len(times) - 1  # the chunks from this one on hold the window and the sample before
    while first > 0 and not times[first][0] <= t_last - window:
        first -= 1
    t = np.concatenate(times[first:])
    v = np.concatenate(vs[first:])
    k = len(t)
    while k > 1 and t[k - 1] > t_last - window:
        k -= 1
    kin = [model.kinetic_energy(vk) for vk in v[k - 1:]]
    return settled(model.assembly, g, t[k - 1:], np.array(kin), excitation_end(motion))


def _mean_acceleration(motion, t0: float, h: float, n: int) -> np.ndarray:
    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    t = t0 + h * (np.arange(n)[:, None] + sub[None, :])
    return np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(n, ACC_SAMPLES).mean(1)


def simulate_rigid(arch_or_assembly: VoussoirChain | Assembly | RigidModel, motion, *,
                   duration: float = 3.0, time_step: float = DEFAULT_TIME_STEP,
                   output_interval: float = 5e-4, settings: DemSettings | None = None,
                   initial: tuple[np.ndarray, np.ndarray] | None = None,
                   g: float = STANDARD_GRAVITY, chunk: float = 0.05,
                   solver_tolerance: float = SOLVER_TOLERANCE,
                   friction: float | None = None, solver: str = "direct",
                   until_rest: float | None = None) -> RigidRun:
    """Run the rigid-block chain under ``motion`` (ground acceleration, m/s^2) from rest.

    Parameters
    ----------
    arch_or_assembly : VoussoirChain, Assembly or RigidModel
        An arch is built with :func:`archquake.dem.assembly.build_arch_assembly` (every
        voussoir a block), as the DEM does.
    motion : GroundMotion
    duration, time_step, output_interval : float
        s. The output interval is rounded to a whole number of steps.
    settings : DemSettings, optional
        Only its thresholds are read (``hinge_opening``, the collapse criteria,
        ``stop_at_collapse``), so that the results are classified as the DEM's are.
    initial : (q, v), optional
        Initial configuration and velocity, (nb, 3) each (default: rest, undisplaced).
    g : float
        Gravity, m/s^2.
    chunk : float
        The run is checked for collapse every ``chunk`` s.
    solver_tolerance : float
        Gauss-Seidel tolerance, a fraction of sqrt(g L) (:data:`SOLVER_TOLERANCE`).
    friction : float, optional
        Coulomb coefficient mu (> 0) of every joint; None (default): no sliding, the paper's
        assumption. With mu the step is no longer a projection (``_rigid_kernels`` docstring).
    solver : {"direct", "pgs", "events"}
        The contact step's solver: "direct" (default) solves the guessed active set exactly and
        falls back to Gauss-Seidel when the guess fails (``_rigid_kernels.project_direct``);
        "pgs", projected Gauss-Seidel alone, the plain reference. With ``friction`` the step
        is always Gauss-Seidel. "events": the same model integrated from contact event to
        contact event (:mod:`archquake.mechanism.rigid_events`; no friction, from rest;
        ``time_step`` and ``chunk`` are not used).
    until_rest : float, optional
        s: if the arch has neither collapsed nor come to rest (:func:`archquake.dem.result.settled`)
        by ``duration``, go on, checking every ``chunk`` s, until it does or this time is
        reached. Without it (default) the run ends at ``duration``; the verdict is
        ``indeterminate`` if the arch is still moving then.
    """
    import time as _time

    from archquake.dem import _kernels as DK

    g = require_gravity(g)
    check_motion(motion)
    duration = require_range("duration", duration, 0.0, MAX_DURATION, "s", high_open=False)
    output_interval = require_range("output_interval", output_interval, 0.0, MAX_DURATION, "s",
                                    high_open=False)
    chunk = require_range("chunk", chunk, 0.0, MAX_DURATION, "s", high_open=False)
    solver_tolerance = require_positive("solver_tolerance", solver_tolerance)
    if until_rest is not None:
        until_rest = require_range("until_rest", until_rest, 0.0, MAX_DURATION, "s",
                                   high_open=False)
    model = arch_or_assembly if isinstance(arch_or_assembly, RigidModel) else RigidModel.build(
        arch_or_assembly)
    asm = model.assembly
    settings = DemSettings() if settings is None else settings
    mu = 0.0 if friction is None else float(friction)
    if friction is not None and not (mu > 0 and math.isfinite(mu)):
        raise InvalidParameterError(f"friction must be a finite coefficient > 0, got {friction!r}")
    methods = {"direct": RK.METHOD_DIRECT, "pgs": RK.METHOD_PGS}
    if solver == "events":
        if friction is not None or initial is not None:
            raise InvalidParameterError(
                "solver='events' runs the no-slip chain from rest: leave friction and initial "
                "unset, or use solver='direct'")
        return _simulate_events(model, motion, settings, duration=duration,
                                output_interval=output_interval, g=g, until_rest=until_rest)
    if solver not in methods:
        raise InvalidParameterError(
            f"solver must be 'direct', 'pgs' or 'events', got {solver!r}")
    h = float(time_step)
    if not (h > 0 and math.isfinite(h)):
        raise InvalidParameterError(f"time_step must be > 0 s, got {time_step!r}")
    out_every = max(1, int(round(output_interval / h)))
    n_total = int(math.ceil(duration / h - 1e-9))
    per_chunk = max(out_every, int(round(chunk / h)) // out_every * out_every)
    q, v = model.rest() if initial is None else (np.array(initial[0], float),
                                                  np.array(initial[1], float))
    p_warm = np.zeros((len(model.ja), 3))
    slip_ref = np.full(len(model.ja), np.nan)  # the joints' tangential offsets at contact, m
    diag = np.zeros(RK.N_DIAG)
    lref = asm.reference_length
    tol = float(solver_tolerance) * math.sqrt(g * lref)
    gap_tol = GAP_TOLERANCE * lref
    free = (~np.asarray(asm.base, dtype=bool)).astype(np.int64)
    cpar = collapse_parameters(asm, settings, math.nan)
    # the samples, one array per chunk (the first chunk: the initial state)
    times: list[np.ndarray] = [np.zeros(1)]
    qs, vs, ds = [q[None].copy()], [v[None].copy()], [diag[None].copy()]
    ug: list[np.ndarray] = [np.zeros(1)]
    vg: list[np.ndarray] = [np.zeros(1)]
    u_cur = v_cur = 0.0
    step = 0
    worst = 0
    t_wall = _time.perf_counter()
    cpar[DK.C_CROWN_Y0] = crown_height(asm, absolute_states(model, q[None], v[None], np.zeros(1),
                                                            np.zeros(1))[:, :, :3])[0]
    collapsed = False
    n_cap = n_total if until_rest is None else max(n_total, int(math.ceil(until_rest / h - 1e-9)))
    while step < n_cap and not collapsed:
        if step >= n_total and _at_rest(model, g, times, vs, motion):
            break
        n = min(per_chunk, n_cap - step)
        n -= n % out_every if n >= out_every else 0
        n = max(n, 1)
        acc = _mean_acceleration(motion, step * h, h, n)
        n_out = n // out_every
        oq = np.zeros((n_out, model.n_bodies, 3))
        ov = np.zeros_like(oq)
        od = np.zeros((n_out, RK.N_DIAG))
        w = RK.run(q, v, p_warm, model.mass, model.inertia, model.ja, model.jb, model.arm_a,
                   model.arm_b, model.n0, model.t0, acc, h, g, gap_tol, tol, MAX_SWEEPS, mu,
                   out_every, oq, ov, od, diag, methods[solver], True, HOLD_TOLERANCE * lref,
                   slip_ref)
        worst = max(worst, int(w))
        if not np.all(np.isfinite(q)):
            from archquake.errors import SolverError

            raise SolverError("the rigid-chain state became non-finite")
        # the ground's velocity and displacement (trapezoid on the step means: exact for them)
        vg_steps = v_cur + h * np.cumsum(acc)
        ug_steps = u_cur + h * np.cumsum(0.5 * (np.concatenate([[v_cur], vg_steps[:-1]])
                                                 + vg_steps))
        if n_out:
            k = (np.arange(n_out) + 1) * out_every - 1  # the recorded steps of the chunk
            times.append((step + k + 1) * h)
            qs.append(oq)
            vs.append(ov)
            ds.append(od)
            ug.append(ug_steps[k])
            vg.append(vg_steps[k])
        u_cur, v_cur = float(ug_steps[-1]), float(vg_steps[-1])
        step += n
        if settings.stop_at_collapse and n_out:
            last = absolute_states(model, oq[-1:], ov[-1:], ug[-1][-1:], vg[-1][-1:])[0]
            collapsed = bool(DK.collapsed(last, free, cpar))
    wall = _time.perf_counter() - t_wall
    da = np.concatenate(ds)
    res = _samples_to_result(model, motion, settings, g=g, time_step=h, duration=duration,
                             output_interval=out_every * h, n_steps=step,
                             times=np.concatenate(times), q=np.concatenate(qs),
                             v=np.concatenate(vs), dissipated=da[:, RK.D_DISSIPATED],
                             input_work=da[:, RK.D_INPUT], ground_displacement=np.concatenate(ug),
                             ground_velocity=np.concatenate(vg))
    return RigidRun(result=res, time_step=h,
                    max_penetration_m=float(da[:, RK.D_PENETRATION].max(initial=0.0)),
                    friction_demand=da[:, RK.D_FRICTION].copy(), max_sweeps=worst,
                    residual=float(da[:, RK.D_RESIDUAL].max(initial=0.0)), wall_s=wall,
                    friction=friction, motion=motion,
                    correction_work=float(da[-1, RK.D_CORRECTION]))


def _simulate_events(model: RigidModel, motion, settings: DemSettings, *, duration: float,
                     output_interval: float, g: float, until_rest: float | None) -> RigidRun:
    """``simulate_rigid(..., solver="events")``: :func:`~archquake.mechanism.rigid_events.
    run_events` and the same post-processing as the time stepper's."""
    from archquake.mechanism.rigid_events import EventModel, ground_kinematics, run_events

    em = EventModel.of(model)
    raw = run_events(em, motion, duration=duration, output_interval=output_interval, g=g,
                     settings=settings, until_rest=until_rest)
    q0, v0 = model.rest()
    times = np.r_[0.0, raw["times"]]
    q = np.concatenate([q0[None], raw["q"]])
    v = np.concatenate([v0[None], raw["v"]])
    e = np.vstack([np.zeros((1, raw["e"].shape[1])), raw["e"]])
    ug, vg = ground_kinematics(motion, times)
    # the settings record a finite step: the output interval (the integrator's own is adaptive)
    res = _samples_to_result(model, motion, settings, g=g, time_step=output_interval,
                             duration=duration, output_interval=output_interval,
                             n_steps=int(raw["counters"][0]), times=times, q=q, v=v,
                             dissipated=e[:, 2], input_work=e[:, 3], ground_displacement=ug,
                             ground_velocity=vg)
    return RigidRun(result=res, time_step=math.nan, max_penetration_m=raw["max_drift_m"],
                    friction_demand=e[:, 4].copy(), max_sweeps=int(raw["counters"][9]),
                    residual=0.0, wall_s=raw["wall_s"], friction=None, motion=motion,
                    events=raw)


def absolute_states(model: RigidModel, q: np.ndarray, v: np.ndarray,
                    ground_displacement: np.ndarray, ground_velocity: np.ndarray) -> np.ndarray:
    """The DEM's recorded states of every block of the assembly (base blocks included) in the
    absolute frame, (nt, n_blocks, 6): x, y (m), theta (rad), vx, vy (m/s), omega (rad/s).

    Parameters
    ----------
    model : RigidModel
    q, v : ndarray (nt, nb, 3)
        The free bodies' configurations and velocities relative to the ground: x, y (m),
        theta (rad); vx, vy (m/s), omega (rad/s).
    ground_displacement, ground_velocity : ndarray (nt,)
        x_g (m) and x_g' (m/s): added to every block's x and vx (the base blocks move with
        the ground, at their undisplaced centroids).
    """
    u = np.asarray(ground_displacement, dtype=float)[:, None]
    w = np.asarray(ground_velocity, dtype=float)[:, None]
    blocks = model.free_blocks
    st = np.zeros((q.shape[0], len(model.assembly.base), 6))
    st[:, :, :2] = model.assembly.centroids
    st[:, :, 0] += u
    st[:, :, 3] = w
    st[:, blocks, :3] = q
    st[:, blocks, 0] += u
    st[:, blocks, 3:] = v
    st[:, blocks, 3] += w
    return st


def _samples_to_result(model: RigidModel, motion, settings: DemSettings, *, g: float,
                       time_step: float, duration: float, output_interval: float, n_steps: int,
                       times: np.ndarray, q: np.ndarray, v: np.ndarray, dissipated: np.ndarray,
                       input_work: np.ndarray, ground_displacement: np.ndarray,
                       ground_velocity: np.ndarray) -> DemResult:
    """The recorded samples of a rigid-chain run as a :class:`DemResult` (the DEM's
    post-processing, :meth:`DemResult.from_samples`; module docstring): what any stepper of
    this model hands back.

    Parameters
    ----------
    model : RigidModel
    motion : GroundMotion
        Recorded by its ``to_dict()``; its ``duration`` is the end of the excitation.
    settings : DemSettings
        The thresholds of the verdict; recorded with ``duration``, ``time_step`` and
        ``output_interval`` (s) replaced.
    g : float
        m/s^2.
    n_steps : int
        Steps taken.
    times : ndarray (nt,)
        s, from the start of the ground motion.
    q, v : ndarray (nt, nb, 3)
        Configurations and velocities of the free bodies relative to the ground
        (:func:`absolute_states`).
    dissipated, input_work : ndarray (nt,)
        J: energy removed by the contact step (the ``damping`` column) and work of the
        inertial load, since t = 0.
    ground_displacement, ground_velocity : ndarray (nt,)
        The ground's x_g (m) and x_g' (m/s).
    """
    states = absolute_states(model, q, v, ground_displacement, ground_velocity)
    kin = 0.5 * ((v[:, :, 0] ** 2 + v[:, :, 1] ** 2) @ model.mass + v[:, :, 2] ** 2 @ model.inertia)
    pot = g * (q[:, :, 1] - model.centroids[None, :, 1]) @ model.mass
    energies = np.zeros((len(times), 8))
    energies[:, 0] = kin
    energies[:, 1] = pot
    energies[:, 3] = dissipated
    energies[:, 5] = input_work
    energies[:, 6] = ground_displacement
    energies[:, 7] = ground_velocity
    motion_d = motion.to_dict() if hasattr(motion, "to_dict") else {"name": str(getattr(
        motion, "name", motion))}
    return DemResult.from_samples(model.assembly,
                                  settings.with_(duration=duration, time_step=time_step,
                                                 output_interval=output_interval),
                                  motion_d, g, time_step, math.nan, n_steps, 0, times, states,
                                  energies, excitation_end=excitation_end(motion))


__all__ = ["DEFAULT_TIME_STEP", "RigidModel", "RigidRun", "absolute_states", "simulate_rigid"]
