"""Running the rigid-block chain (`archquake.rigid.model`) to a verdict: ``simulate_rigid``
and its result, `RigidRun`.

One driver, ``simulate_rigid``: it validates the run, picks the integrator (a strategy:
the time stepper, `archquake.rigid.steps`, through `_time_steps`; the event
integrator, `archquake.rigid.events`, through `_events`; or none, `_below_onset`, for a
motion that never reaches the onset of hinging), each of which runs (and goes on until rest)
its own way and hands back its samples, an `Integrated`; they become a `RigidRun`, a
`archquake.blocks.BlockResult` built by the block models' own post-processing
(`BlockResult.from_samples`, through `_samples_to_run`), so impacts, hinges,
collapse criteria and the rotation measure are read exactly as in the DEM. In it, ``strain`` is
zero and the ``damping`` column holds the energy removed by the contact projections (the
plastic impacts, the scheme's O(h) loss in persistent contacts, and the position correction's
work, ``RigidRun.correction_work``), not Rayleigh damping.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

import archquake.rigid._step_kernels as RK
from archquake._validate import require_gravity, require_positive, require_range
from archquake.blocks.assembly import Assembly
from archquake.blocks.criteria import (
    MAX_DURATION,
    BlockCriteria,
    BlockRunSettings,
    block_criteria,
    default_window,
)
from archquake.blocks.result import BlockResult, excitation_end
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import check_motion, check_motion_lift_off
from archquake.outcome import Outcome
from archquake.rigid.events import (
    EventModel,
    events_summary,
    ground_kinematics,
    run_events,
    stays_at_rest,
)
from archquake.rigid.forces import joint_forces as _joint_forces
from archquake.rigid.model import (
    DEFAULT_TIME_STEP,
    FORCE_SAMPLES,
    SOLVER_TOLERANCE,
    RigidModel,
    absolute_states,
    check_work,
)
from archquake.rigid.steps import METHODS, run_steps


@dataclass(frozen=True, kw_only=True)
class RigidRun(BlockResult):
    """A rigid-chain history: the block post-processing's result (`BlockResult`: times,
    positions, outcome, impacts, ... read exactly as the DEM's, module docstring) and the
    stepper's own record.

    The stepper's fields: ``stepper_time_step``: the time stepper's step h, s (NaN for the
    event integrator, whose step is adaptive; ``time_step`` is then the output interval, as the
    settings record it);
    ``max_penetration_m``: largest negative gap of the run (the velocity-level scheme's drift);
    ``correction_work``: J, the part of the ``damping`` column (the kinetic energy the contact
    projections removed) that is the work of the position-level correction
    (``_step_kernels.D_CORRECTION``; 0 for the event integrator, whose own time steps leave it
    out);
    ``friction_demand``: (nt,) largest |p_T| / p_N of any joint since the previous sample;
    ``max_sweeps``: most Gauss-Seidel sweeps of a step; ``residual``: largest velocity
    correction of a step's last sweep, m/s; ``wall_s``: wall time of the stepping;
    ``contact_work``, ``friction_work``: (nt,) J, the work done on the contacts since t = 0
    (``_step_kernels.D_CONTACT_WORK``, the energy they dissipate: what closes the balance,
    `energy`) and its part on the slipping joints (``D_FRICTION_WORK``); None for the
    event integrator, whose ``damping`` column is its impacts' loss;
    ``friction_coefficient``: the joints' Coulomb coefficient, None for no sliding (the
    ``friction`` column is the block result's energy, J); ``ground_motion``: the ground motion
    it was run with (``motion`` is its ``to_dict()``); ``events``: with ``solver="events"``,
    the event integrator's record (`archquake.rigid.events.run_events`: counters, the event
    log, the times the time stepper took over), else None; ``at_rest``: the motion never
    reaches the onset of hinging (`archquake.rigid.events.stays_at_rest`), so no step was
    taken: the samples are the chain at rest on the moving ground.
    """

    stepper_time_step: float
    max_penetration_m: float
    friction_demand: np.ndarray
    max_sweeps: int
    residual: float
    wall_s: float
    friction_coefficient: float | None = None
    ground_motion: object = field(default=None, repr=False, compare=False)
    correction_work: float = 0.0
    events: dict | None = field(default=None, repr=False, compare=False)
    contact_work: np.ndarray | None = field(default=None, repr=False, compare=False)
    friction_work: np.ndarray | None = field(default=None, repr=False, compare=False)
    at_rest: bool = False

    @property
    def result(self) -> RigidRun:
        """The run itself (deprecated: a `RigidRun` is its block result; read its fields
        directly, ``run.outcome`` for ``run.result.outcome``)."""
        warnings.warn("RigidRun.result is the run itself: read run.<name> for "
                      "run.result.<name>; this is accepted until the next release",
                      DeprecationWarning, stacklevel=2)
        return self

    @cached_property
    def energy(self) -> EnergyBalance:
        """The run's energy balance (`EnergyBalance`, `energy_balance`)."""
        contacts = self.damping if self.contact_work is None else self.contact_work
        friction = np.zeros_like(contacts) if self.friction_work is None else self.friction_work
        asm = self.assembly
        free_mass = float(np.sum(asm.masses[~np.asarray(asm.base, dtype=bool)]))
        ground = 0.5 * free_mass * float(np.max(np.abs(self.base_velocity), initial=0.0)) ** 2
        return energy_balance(self.times, self.kinetic, self.potential, contacts, friction,
                              self.input_work, ground_kinetic=ground)

    @property
    def max_friction_demand(self) -> float:
        return float(self.friction_demand.max(initial=0.0))

    @cached_property
    def joint_forces(self):
        """The joint forces, line of thrust and friction demand at the recorded samples (at most
        ``FORCE_SAMPLES`` of them, evenly strided):
        `archquake.rigid.forces.joint_forces`, with its reporting rule."""
        if self.ground_motion is None:
            raise InvalidParameterError("this run does not know its ground motion")
        if self.at_rest:  # the locked arch: indeterminate at every sample (forces module)
            from archquake.rigid.forces import joint_forces_at_rest

            return joint_forces_at_rest(self, self.ground_motion)
        every = max(1, -(-self.times.size // FORCE_SAMPLES))
        return _joint_forces(self, self.ground_motion, every=every)

    def to_table(self) -> dict[str, np.ndarray]:
        """Columns for a tabular export: `BlockResult.to_table`
        (`archquake.result.TABLE_COLUMNS` first) with the contacts' work in place of the
        DEM's sinks (``dissipated_contacts_J``, ``dissipated_friction_J``: its part on slipping
        joints; `energy`), then the friction demand."""
        out = super().to_table()
        for key in ("strain_J", "damping_J", "friction_J"):
            del out[key]
        contacts = self.damping if self.contact_work is None else self.contact_work
        out["dissipated_contacts_J"] = contacts
        out["dissipated_friction_J"] = (np.zeros_like(contacts) if self.friction_work is None
                                        else self.friction_work)
        if self.friction_demand.shape == self.times.shape:
            out["friction_demand"] = self.friction_demand
        return out

    def to_dict(self, *, joint_forces: bool = True) -> dict:
        """Summary for JSON: `BlockResult.to_dict` (the keys of
        `archquake.outcome.RESULT_KEYS` first) with ``model`` ``"rigid"`` (as ``--model``
        names it), then the
        stepper's own diagnostics under ``rigid``. ``joint_forces=False`` leaves out the joint
        forces' summary (a post-processing that costs more than the run: sweeps skip it)."""
        out = super().to_dict()
        del out["dissipated_damping_J"], out["dissipated_friction_J"]  # the DEM's sinks
        out.update(self.energy.to_dict())
        out["model"] = "rigid"
        out["friction_coefficient"] = self.friction_coefficient
        if joint_forces and self.ground_motion is not None:
            out["joint_forces"] = self.joint_forces.summary()
        solver = ("none: below the onset" if self.at_rest
                  else "events" if self.events is not None else "time stepping")
        out["rigid"] = {"solver": solver,
                        "time_step_s": (None if self.events is not None or self.at_rest
                                        else self.stepper_time_step),
                        "max_penetration_m": self.max_penetration_m,
                        "correction_work_j": self.correction_work,
                        "max_sweeps": self.max_sweeps, "residual_m_s": self.residual,
                        "wall_s": self.wall_s, "below_onset": self.at_rest}
        if self.events is not None:
            out["rigid"]["events"] = events_summary(self.events)
        return out


def simulate_rigid(arch_or_assembly: VoussoirChain | Assembly | RigidModel, motion, *,
                   duration: float = 3.0, time_step: float = DEFAULT_TIME_STEP,
                   output_interval: float = 5e-4, settings: BlockCriteria | None = None,
                   initial: tuple[np.ndarray, np.ndarray] | None = None,
                   g: float = STANDARD_GRAVITY, chunk: float = 0.05,
                   solver_tolerance: float = SOLVER_TOLERANCE,
                   friction: float | None = None, solver: str = "direct",
                   until_rest: float | None = None, progress=None) -> RigidRun:
    """Run the rigid-block chain under ``motion`` (ground acceleration, m/s^2) from rest.

    Parameters
    ----------
    arch_or_assembly : VoussoirChain, Assembly or RigidModel
        An arch is built with `archquake.blocks.assembly.build_arch_assembly` (every
        voussoir a block), as the DEM does.
    motion : GroundMotion
    duration, time_step, output_interval : float
        s. The output interval is rounded to a whole number of steps.
    settings : BlockCriteria, optional
        The thresholds the samples are classified by (``hinge_opening``, the collapse
        criteria, ``stop_at_collapse``), as the DEM's are (default ``BlockCriteria()``). A
        `archquake.dem.DemSettings` is still accepted for one release (its ``criteria``
        are read), with a `DeprecationWarning`.
    initial : (q, v), optional
        Initial configuration and velocity, (nb, 3) each (default: rest, undisplaced).
    g : float
        Gravity, m/s^2.
    chunk : float
        The run is checked for collapse every ``chunk`` s.
    solver_tolerance : float
        Gauss-Seidel tolerance, a fraction of sqrt(g L) (`SOLVER_TOLERANCE`).
    friction : float, optional
        Coulomb coefficient mu (> 0) of every joint; None (default): no sliding, the paper's
        assumption. With mu the step is no longer a projection (``_step_kernels`` docstring).
    solver : {"direct", "pgs", "events"}
        The contact step's solver: "direct" (default) solves the guessed active set exactly and
        falls back to Gauss-Seidel when the guess fails (``_step_kernels.project_direct``);
        "pgs", projected Gauss-Seidel alone, the plain reference. With ``friction``,
        "direct" keeps the exact no-slip solution of a step where every joint's tangential
        impulse lies in its Coulomb cone (every joint sticks) and runs Gauss-Seidel with the
        Coulomb clamp only where a joint slips; "pgs" runs the clamped Gauss-Seidel at every
        step. "events": the same model integrated from contact event to
        contact event (`archquake.rigid.events`; no friction, from rest;
        ``time_step`` and ``chunk`` are not used).
    until_rest : float, optional
        s: if the arch has neither collapsed nor come to rest (`archquake.blocks.result.settled`)
        by ``duration``, go on, checking every ``chunk`` s, until it does or this time is
        reached. Without it (default) the run ends at ``duration``; the verdict is
        ``indeterminate`` if the arch is still moving then.
    progress : callable, optional
        With the time stepper: ``progress(steps_done, steps_at_most)`` after each ``chunk``
        (the command line prints a long run's progress with it).
    """
    g = require_gravity(g)
    check_motion(motion, needs=("acceleration", "duration", "breakpoints"))  # what the steps read
    check_motion_lift_off(motion, g)
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
    settings = block_criteria(settings, caller="simulate_rigid")
    mu = 0.0 if friction is None else float(friction)
    if friction is not None and not (mu > 0 and math.isfinite(mu)):
        raise InvalidParameterError(f"friction must be a finite coefficient > 0, got {friction!r}")
    if solver == "events" and (friction is not None or initial is not None):
        raise InvalidParameterError(
            "solver='events' runs the no-slip chain from rest: leave friction and initial "
            "unset, or use solver='direct'")
    if solver not in (*METHODS, "events"):
        raise InvalidParameterError(
            f"solver must be 'direct', 'pgs' or 'events', got {solver!r}")
    h = float(time_step)
    if not (h > 0 and math.isfinite(h)):
        raise InvalidParameterError(f"time_step must be > 0 s, got {time_step!r}")
    if solver != "events":  # the bound first (arithmetic; the onset test projects the chain)
        check_work(model.n_bodies, duration if until_rest is None else max(duration, until_rest),
                   h)
    # the integrator (a strategy: each runs, and resumes until rest, its own way), then the
    # one result
    got: Integrated
    if friction is None and initial is None and stays_at_rest(model, motion, g=g):
        got = _below_onset(model, motion, duration=duration, output_interval=output_interval,
                           time_step=math.nan if solver == "events" else h)
    elif solver == "events":
        got = _events(model, motion, settings, duration=duration,
                      output_interval=output_interval, g=g, until_rest=until_rest)
    else:
        got = _time_steps(model, motion, settings, duration=duration, time_step=h,
                          output_interval=output_interval, initial=initial, g=g, chunk=chunk,
                          solver_tolerance=solver_tolerance, friction=friction, solver=solver,
                          until_rest=until_rest, progress=progress)
    return _samples_to_run(model, motion, settings, got, g=g, duration=duration)


#: A residual of the energy balance above this fraction of its scale is a warning on the run.
ENERGY_WARNING = 0.03


@dataclass(frozen=True)
class EnergyBalance:
    """The energy balance of a rigid-chain run, in the ground's frame (relative motion).

    The input is the work of the inertial load -m x_g'' on the relative velocities, W(t) =
    -int x_g'' sum m_i x_i' dt: in this frame the ground's own velocity and displacement,
    including what a record leaves behind at its end (a residual velocity, a drift), do no work.
    The balance T + V + D - W = T(0) + V(0), T the kinetic energy of the relative motion, V the
    gravitational energy, D the work done on the contacts (the energy they dissipate), holds
    for the Moreau-Jean step exactly (module docstring of ``_step_kernels``, "Energy"), so its
    ``residual`` is the rounding of the sums and the sampling, unless something is off.

    ``input_work_J``, ``peak_kinetic_J``, ``contacts_J`` (D at the end), ``friction_J`` (its
    part on slipping joints), ``impacts_J`` (the rest: plastic impacts, the step's loss in
    persistent contact and the position correction's work), ``scale_J`` = max(|W|, T, |V -
    V(0)|, 1/2 M max |x_g'|^2) over the run (`energy_balance`), 0 only without
    excitation and motion; ``residual``: max |T + V + D - W - E(0)| /
    ``scale_J`` (0 when nothing moved); ``warning``: a sentence when ``residual`` exceeds
    `ENERGY_WARNING` or a dissipation is negative, else None. A broken balance is
    located at the sample where it jumps most, and the sentence names the term whose change
    there departs most from its changes at the ten samples around it."""

    input_work_J: float
    peak_kinetic_J: float
    contacts_J: float
    impacts_J: float
    friction_J: float
    scale_J: float
    residual: float
    warning: str | None

    def to_dict(self) -> dict:
        """The JSON keys: ``energy_error`` (the residual, a fraction of ``energy_scale_J``),
        ``energy_scale_J``, ``input_work_J``, ``peak_kinetic_J``, ``dissipated_contacts_J``,
        ``dissipated_impacts_J``, ``dissipated_friction_J``, ``energy_warning``."""
        return {"energy_error": self.residual, "energy_scale_J": self.scale_J,
                "input_work_J": self.input_work_J, "peak_kinetic_J": self.peak_kinetic_J,
                "dissipated_contacts_J": self.contacts_J,
                "dissipated_impacts_J": self.impacts_J,
                "dissipated_friction_J": self.friction_J, "energy_warning": self.warning}


def energy_balance(times: np.ndarray, kinetic: np.ndarray, potential: np.ndarray,
                   contacts: np.ndarray, friction: np.ndarray, input_work: np.ndarray, *,
                   ground_kinetic: float = 0.0) -> EnergyBalance:
    """The `EnergyBalance` of the samples (each (nt,), J; ``times`` s): ``contacts`` the
    work done on the contacts since t = 0, ``friction`` its part on slipping joints;
    ``ground_kinetic`` J, 1/2 M max |x_g'|^2 (M the free blocks' mass), the kinetic energy the
    ground's motion gives the arch carried along with it: a scale that only vanishes without
    excitation, so that a run in which almost nothing moves relative to the ground is not
    judged against its own rounding."""
    if times.size == 0:
        return EnergyBalance(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, None)
    total = kinetic + potential + contacts - input_work
    drift = np.abs(total - total[0])
    scale = max(float(np.max(np.abs(input_work))), float(np.max(kinetic)),
                float(np.max(np.abs(potential - potential[0]))), float(ground_kinetic))
    residual = float(np.max(drift)) / scale if scale > 0.0 else 0.0
    if not math.isfinite(residual):
        residual = math.inf
    d_c, d_f = float(contacts[-1]), float(friction[-1])
    warning = None
    if residual > ENERGY_WARNING:
        # the sample where the balance jumps most, and the term whose change there departs
        # most from its changes at the samples around it
        k = int(np.argmax(np.abs(np.diff(total)))) + 1 if times.size > 1 else 0
        terms = {"the kinetic energy": kinetic, "the potential energy": potential,
                 "the work done on the contacts": contacts, "the input work": input_work}

        def anomaly(arr: np.ndarray) -> float:
            if k == 0:
                return 0.0
            inc = np.diff(arr)
            around = np.r_[inc[max(0, k - 6):k - 1], inc[k:k + 5]]
            return abs(inc[k - 1] - (float(np.median(around)) if around.size else 0.0))

        name, arr = max(terms.items(), key=lambda kv: anomaly(kv[1]))
        warning = (f"the energy balance is off by {residual:.1%} of {scale:.3g} J: it jumps by "
                   f"{total[k] - total[k - 1]:.3g} J at t = {times[k]:.4g} s, where "
                   f"{name} changes by {arr[k] - arr[k - 1]:.3g} J")
    elif min(d_c, d_c - d_f, d_f) < -ENERGY_WARNING * scale:
        warning = (f"the contacts did positive work: dissipated {d_c:.4g} J "
                   f"({d_c - d_f:.4g} J in impacts, {d_f:.4g} J in friction)")
    return EnergyBalance(input_work_J=float(input_work[-1]), peak_kinetic_J=float(np.max(kinetic)),
                         contacts_J=d_c, impacts_J=d_c - d_f, friction_J=d_f, scale_J=scale,
                         residual=residual, warning=warning)


@dataclass(frozen=True)
class Integrated:
    """What an integrator of the chain hands `simulate_rigid`, which builds the result from
    it, once (`_samples_to_run`).

    ``time_step``: the step the run's settings record, s; ``output_interval`` s;
    ``n_steps``: steps taken; ``times`` (nt,) s; ``q``, ``v`` (nt, nb, 3): the free bodies'
    configurations and velocities relative to the ground; ``dissipated``, ``input_work`` (nt,)
    J: the energy the contacts removed (the ``damping`` column) and the inertial load's work,
    since t = 0; ``ground_displacement`` (m), ``ground_velocity`` (m/s) (nt,); ``extras``: the
    integrator's own fields of `RigidRun` (``stepper_time_step``, ``max_penetration_m``,
    ...)."""

    time_step: float
    output_interval: float
    n_steps: int
    times: np.ndarray
    q: np.ndarray
    v: np.ndarray
    dissipated: np.ndarray
    input_work: np.ndarray
    ground_displacement: np.ndarray
    ground_velocity: np.ndarray
    extras: dict = field(default_factory=dict)


def _time_steps(model: RigidModel, motion, settings: BlockCriteria, *, duration: float,
                time_step: float, output_interval: float,
                initial: tuple[np.ndarray, np.ndarray] | None, g: float, chunk: float,
                solver_tolerance: float, friction: float | None, solver: str,
                until_rest: float | None, progress) -> Integrated:
    """The Moreau-Jean time stepper (`archquake.rigid.steps.run_steps`; ``solver`` "direct"
    or "pgs", ``friction`` the joints' Coulomb coefficient or None), arguments validated by
    `simulate_rigid`."""
    h = time_step
    s = run_steps(model, motion, settings, duration=duration, time_step=h,
                  output_interval=output_interval, initial=initial, g=g, chunk=chunk,
                  solver_tolerance=solver_tolerance,
                  friction=0.0 if friction is None else float(friction), solver=solver,
                  until_rest=until_rest, progress=progress)
    da = s.diag
    return Integrated(
        time_step=h, output_interval=s.output_interval, n_steps=s.n_steps, times=s.times,
        q=s.q, v=s.v, dissipated=da[:, RK.D_DISSIPATED], input_work=da[:, RK.D_INPUT],
        ground_displacement=s.ground_displacement, ground_velocity=s.ground_velocity,
        extras={"stepper_time_step": h,
                "max_penetration_m": float(da[:, RK.D_PENETRATION].max(initial=0.0)),
                "friction_demand": da[:, RK.D_FRICTION].copy(), "max_sweeps": s.max_sweeps,
                "residual": float(da[:, RK.D_RESIDUAL].max(initial=0.0)), "wall_s": s.wall_s,
                "friction_coefficient": friction, "ground_motion": motion,
                "correction_work": float(da[-1, RK.D_CORRECTION]),
                "contact_work": da[:, RK.D_CONTACT_WORK].copy(),
                "friction_work": da[:, RK.D_FRICTION_WORK].copy()})


#: Most samples of a run at rest (`_below_onset`): its history is constant, so a long
#: window is sampled more coarsely than ``output_interval``.
REST_SAMPLES = 10_000


def _below_onset(model: RigidModel, motion, *, duration: float, output_interval: float,
                 time_step: float) -> Integrated:
    """The run of a chain that the motion never moves (`stays_at_rest`): at rest relative
    to the ground over ``duration`` s, sampled every ``output_interval`` s (at most
    `REST_SAMPLES` samples), no step taken, no energy exchanged (the inertia force does
    no work on a body that does not move relative to the ground), read by the same
    post-processing as a stepped run: ``no_hinging``. ``time_step``: the stepper's, s (NaN
    for the event integrator)."""
    import time as _time

    start = _time.perf_counter()
    interval = max(output_interval, duration / REST_SAMPLES)
    n = max(1, int(math.ceil(duration / interval - 1e-9)))
    times = np.minimum(np.arange(n + 1) * interval, duration)
    q0, v0 = model.rest()
    q = np.broadcast_to(q0, (n + 1, *q0.shape)).copy()
    v = np.zeros((n + 1, *v0.shape))
    ug, vg = ground_kinematics(motion, times, step=max(1e-4, duration / 1e6))
    zeros = np.zeros(n + 1)
    h = time_step if math.isfinite(time_step) else output_interval
    return Integrated(
        time_step=h, output_interval=interval, n_steps=0, times=times, q=q, v=v,
        dissipated=zeros, input_work=zeros, ground_displacement=ug, ground_velocity=vg,
        extras={"stepper_time_step": time_step, "max_penetration_m": 0.0,
                "friction_demand": zeros.copy(), "max_sweeps": 0, "residual": 0.0,
                "wall_s": _time.perf_counter() - start, "friction_coefficient": None,
                "ground_motion": motion, "contact_work": zeros.copy(),
                "friction_work": zeros.copy(), "at_rest": True})


def _events(model: RigidModel, motion, settings: BlockCriteria, *, duration: float,
            output_interval: float, g: float, until_rest: float | None) -> Integrated:
    """``simulate_rigid(..., solver="events")``: the event integrator,
    `archquake.rigid.events.run_events`, its samples from the rest state on."""
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
    return Integrated(
        time_step=output_interval, output_interval=output_interval,
        n_steps=int(raw["counters"][0]), times=times, q=q, v=v, dissipated=e[:, 2],
        input_work=e[:, 3], ground_displacement=ug, ground_velocity=vg,
        extras={"stepper_time_step": math.nan, "max_penetration_m": raw["max_drift_m"],
                "friction_demand": e[:, 4].copy(), "max_sweeps": int(raw["counters"][9]),
                "residual": 0.0, "wall_s": raw["wall_s"], "friction_coefficient": None,
                "ground_motion": motion, "events": raw})


def _samples_to_run(model: RigidModel, motion, settings: BlockCriteria, got: Integrated, *,
                    g: float, duration: float) -> RigidRun:
    """The recorded samples of a rigid-chain run as a `RigidRun` (the block models'
    post-processing, `BlockResult.from_samples`; module docstring): what any integrator of
    this model hands back.

    Parameters
    ----------
    model : RigidModel
    motion : GroundMotion
        Recorded by its ``to_dict()``; its ``duration`` is the end of the excitation.
    settings : BlockCriteria
        The thresholds of the verdict; recorded with ``duration``, ``time_step`` and
        ``output_interval`` (s), a `BlockRunSettings`.
    got : Integrated
        What the integrator recorded (its samples, and its own fields of `RigidRun` in
        ``extras``).
    g : float
        m/s^2.
    duration : float
        The run's asked length, s.
    """
    q, v, times = got.q, got.v, got.times
    ground_displacement, ground_velocity = got.ground_displacement, got.ground_velocity
    states = absolute_states(model, q, v, ground_displacement, ground_velocity)
    kin = 0.5 * ((v[:, :, 0] ** 2 + v[:, :, 1] ** 2) @ model.mass + v[:, :, 2] ** 2 @ model.inertia)
    pot = g * (q[:, :, 1] - model.centroids[None, :, 1]) @ model.mass
    energies = np.zeros((len(times), 8))
    energies[:, 0] = kin
    energies[:, 1] = pot
    energies[:, 3] = got.dissipated
    energies[:, 5] = got.input_work
    energies[:, 6] = ground_displacement
    energies[:, 7] = ground_velocity
    motion_d = motion.to_dict() if hasattr(motion, "to_dict") else {"name": str(getattr(
        motion, "name", motion))}
    record = BlockRunSettings(settings, duration=duration, time_step=got.time_step,
                              output_interval=got.output_interval)
    return RigidRun.from_samples(model.assembly, record, motion_d, g, got.time_step, math.nan,
                                 got.n_steps, 0, times, states, energies,
                                 excitation_end=excitation_end(motion), **got.extras)


__all__ = ["ENERGY_WARNING", "EnergyBalance", "RigidRun", "energy_balance", "simulate_rigid"]


# ----------------------------------------------------------------------------- to a verdict
def rigid_window(arch, motion, *, g: float = STANDARD_GRAVITY) -> tuple[float, float]:
    """The window of `rigid_to_verdict`, s: its first run (`archquake.blocks.default_window`,
    the end of the excitation + 5 sqrt(R/g)) and the latest it goes on to while the arch
    still moves (`archquake.ranges.default_t_end`: the end of the excitation + 60 sqrt(R/g),
    the four-link model's default end). Its length is bounded only by the work it costs
    (`archquake.rigid.model.check_work`): the chain resumes where it stopped, and skips
    nothing it needs. ``arch``: anything with a ``radius``, m."""
    from archquake.ranges import default_t_end

    d = default_window(motion, arch.radius, g=g)
    return d, max(d, float(default_t_end(np.asarray(motion.duration), arch.radius, g)))


def rigid_to_verdict(arch, motion, *, friction: float | None = None,
                     g: float = STANDARD_GRAVITY, settings=None, solver: str = "direct",
                     time_step: float | None = None, progress=None, loads=None) -> RigidRun:
    """The rigid chain (`simulate_rigid`) run to a verdict: to
    `archquake.blocks.default_window` (the end of the excitation + 5 sqrt(R/g)) and, if
    the arch still moves then, on until it is at rest or collapses, up to the end of the
    excitation + 60 sqrt(R/g) (`rigid_window`), however long the record. The rigid chain
    resumes where it stopped, so a long tail costs only its own steps.

    The default window of ``archquake run`` (``--model rigid``), sweeps and the rigid IDA.

    Parameters
    ----------
    arch : Arch
    motion : GroundMotion
        Ground acceleration, m/s^2.
    friction : float, optional
        Coulomb coefficient of every joint; None: no sliding.
    g : float
        m/s^2.
    settings : BlockCriteria, optional
        Thresholds of the verdict (default ``BlockCriteria()``).
    solver : {"direct", "events"}
        How the chain is integrated (`simulate_rigid`).
    time_step : float, optional
        The stepper's step, s (default: ``simulate_rigid``'s).
    progress : callable, optional
        ``simulate_rigid``'s.
    loads : Loads, optional
        What the arch carries (`archquake.blocks.assembly.build_arch_assembly`).

    Returns
    -------
    RigidRun

    Raises
    ------
    InvalidParameterError
        If its work exceeds ``ranges.RIGID_MAX_WORK`` (`archquake.rigid.model.check_work`).
    """
    d, cap = rigid_window(arch, motion, g=g)
    body = arch
    if loads is not None and not loads.empty:
        from archquake.blocks.assembly import build_arch_assembly

        body = build_arch_assembly(arch, loads=loads)
    if time_step is None:
        return simulate_rigid(body, motion, duration=d, friction=friction, until_rest=cap, g=g,
                              settings=settings, solver=solver, progress=progress)
    return simulate_rigid(body, motion, duration=d, friction=friction, until_rest=cap, g=g,
                          settings=settings, solver=solver, time_step=time_step,
                          progress=progress)


__all__ += ["rigid_to_verdict", "rigid_window"]


@dataclass(frozen=True)
class GuardedRun:
    """A recorded run of the rigid chain at the verdict's step, with the verdict path's
    half-step guard (`run_guarded`): one integration gives the history and the verdict.

    Attributes
    ----------
    run : RigidRun
        The recorded history, at ``time_step_s``.
    outcome : Outcome
        The verdict: the run's, or ``indeterminate`` where the guard's rerun at half the step
        ends otherwise.
    verdict_reason : str
        Why, in one sentence.
    time_step_s : float
        The verdict's step, s (`archquake.rigid.verdict.verdict_time_step`).
    lengthening : float
        The longest half cycle after the first (a collapse's up to the collapse) over the
        first (0 without an impact): the guard's measure of nearness to a threshold.
    guard_ran : bool
        Whether the run was repeated at half the step (``lengthening`` above
        `archquake.rigid.verdict.GUARD_LENGTHENING` after an impact).
    guard_outcome : Outcome or None
        The outcome at half the step.
    """

    run: RigidRun
    outcome: Outcome
    verdict_reason: str
    time_step_s: float
    lengthening: float
    guard_ran: bool
    guard_outcome: Outcome | None

    def __getattr__(self, name: str):
        """Every other attribute is the run's (times, rotation, impacts, ``to_csv``...: the
        `archquake.result.ModelResult` interface)."""
        if name.startswith("__") or name == "run":
            raise AttributeError(name)
        return getattr(self.run, name)

    @property
    def collapse_half_cycle(self) -> int | None:
        """The run's, where the verdict is the run's (None otherwise)."""
        return self.run.collapse_half_cycle if self.outcome is self.run.outcome else None

    @property
    def collapse_time(self) -> float | None:
        """s: the run's, where the verdict is the run's (None otherwise)."""
        return self.run.collapse_time if self.outcome is self.run.outcome else None

    def to_dict(self, *, joint_forces: bool = True) -> dict:
        """``RigidRun.to_dict()`` with the verdict in its outcome, collapse half cycle and time
        (s) and ``verdict``, and the guard under ``guard`` (the step in s, whether it ran, its
        outcome, the lengthening)."""
        out = self.run.to_dict(joint_forces=joint_forces)
        same = self.outcome is self.run.outcome
        out.update({"outcome": self.outcome.value, "verdict": self.verdict_reason,
                    "collapse_half_cycle": out["collapse_half_cycle"] if same else None,
                    "collapse_time_s": out["collapse_time_s"] if same else None})
        out["guard"] = {"time_step_s": self.time_step_s, "ran": self.guard_ran,
                        "outcome": None if self.guard_outcome is None
                        else self.guard_outcome.value,
                        "lengthening": self.lengthening}
        return out


def lengthening(run) -> float:
    """The longest half cycle after the first (a collapse's up to the collapse) over the first,
    of a run's rotation measure (0 without an impact): the guard's measure
    (`archquake.rigid.verdict`), read from the recorded impacts."""
    impacts = np.asarray(run.impact_times, dtype=float)
    onset = run.onset_time
    if impacts.size == 0 or onset is None or not impacts[0] > onset:
        return 0.0
    ends = list(impacts)
    if run.collapse_time is not None:
        ends.append(float(run.collapse_time))
    longest = float(np.max(np.diff(ends), initial=0.0))
    return longest / float(impacts[0] - onset)


def run_guarded(arch, motion, *, g: float = STANDARD_GRAVITY, loads=None,
                progress=None, guard: bool = True,
                settings: BlockCriteria | None = None) -> GuardedRun:
    """The rigid chain to a verdict (`rigid_to_verdict`), integrated once at the verdict
    path's step (`archquake.rigid.verdict.verdict_time_step`: scaled with the voussoirs'
    thickness, 1e-3 s on Oppenheim's arch), under the verdict path's guard: a run whose
    verdict depends on an impact and whose later half cycles lasted more than
    `archquake.rigid.verdict.GUARD_LENGTHENING` times the first (the arch lingered near a
    crest) is run again at half the step; where the two outcomes differ the verdict is
    ``indeterminate``, with the reason.

    Parameters
    ----------
    arch : Arch
    motion : GroundMotion
        Ground acceleration, m/s^2.
    g : float
        m/s^2.
    loads : Loads, optional
        What the arch carries.
    progress : callable, optional
        ``simulate_rigid``'s, for the run at the verdict's step (not for the guard's rerun).
    guard : bool
        False: no rerun (the verdict at the step alone).
    settings : BlockCriteria, optional
        Thresholds of the verdict (default ``BlockCriteria()``).

    Returns
    -------
    GuardedRun
    """
    from archquake.rigid.verdict import GUARD_LENGTHENING, verdict_time_step

    h = verdict_time_step(arch, g=g)
    run = rigid_to_verdict(arch, motion, g=g, time_step=h, progress=progress, loads=loads,
                           settings=settings)
    stretch = lengthening(run)
    outcome, reason = run.outcome, run.verdict_reason
    near = (guard and run.impact_times.size >= 1 and outcome in (Outcome.SURVIVES, Outcome.COLLAPSE)
            and stretch > GUARD_LENGTHENING)
    half = None
    if near:
        half = rigid_to_verdict(arch, motion, g=g, time_step=0.5 * h, loads=loads,
                                settings=settings).outcome
        if half is not outcome:
            reason = (f"near the threshold: {outcome.value} at the step {h:.3g} s, "
                      f"{half.value} at {0.5 * h:.3g} s; a finer step (--t-end with the "
                      "default 1e-4 s step) or --integrator events decides")
            outcome = Outcome.INDETERMINATE
        else:
            reason += f" (confirmed at half the step, {0.5 * h:.3g} s)"
    return GuardedRun(run, outcome, reason, h, stretch, near, half)


__all__ += ["GuardedRun", "lengthening", "run_guarded"]
