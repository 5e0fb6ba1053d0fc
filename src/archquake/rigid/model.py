"""The rigid limit of the distinct-element model: rigid blocks with unilateral, plastic, no-slip
joint contacts, any number of open hinges.

Why this model. The four-link mechanism (Eq. 2) moves with one degree of freedom and its hinges
fixed; a migrating one-degree model (removed; docs/notes/mechanism.md) switched between one-degree
mechanisms and had to re-express the configuration at each switch. The DEM shows five-hinge
phases of 0.1-0.4 s and joints closing one after another. A chain of rigid blocks whose joints
may open at either corner has all of these motions at once, and needs no choice of mechanism:

* each block (every voussoir, `archquake.blocks.assembly.Assembly`, the DEM's own
  description, so both models read the same blocks, masses and joints) is a rigid body
  (x, y, theta), in the frame of the ground (inertial load -m x_g'');
* each joint has two corner contacts (intrados, extrados) with a unilateral normal constraint
  (gap >= 0, compressive impulse), and while either corner is in contact, no sliding (tangential
  relative velocity zero; the friction demand |p_T| / p_N is recorded and reported, to be read
  against mu = 0.8), or optionally Coulomb friction (``friction=mu``);
* Moreau-Jean time stepping at velocity level (`archquake.rigid._step_kernels`): each
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
  (`archquake.mechanism.impact_chain.cone_projection`; test).

Why time stepping and not events: the number of possible contact states is 3^(n+1), the set of
active contacts changes during a half cycle tens of times, and closures accumulate (a closing
joint can reopen its neighbour at once); Moreau-Jean needs no event location and is robust to
accumulation, at first order in h. The convergence in h is measured (docs/notes/mechanism.md).

Energies are relative to the ground. The results are a `archquake.blocks.BlockResult` built
by the DEM's own post-processing (`BlockResult.from_samples`, through
`archquake.rigid.run._samples_to_run`, which any integrator's samples go to), so impacts,
hinges, collapse criteria and the rotation measure are read exactly as in the DEM; in it,
``strain`` is zero and the ``damping`` column holds the energy removed by the contact
projections (the plastic impacts, the scheme's O(h) loss in persistent contacts, and the
position correction's work, ``RigidRun.correction_work``), not Rayleigh damping.
"""


from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

import archquake.rigid._input_kernels as IK
import archquake.rigid._step_kernels as RK
from archquake.blocks.assembly import Assembly, build_arch_assembly
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import has_vertical
from archquake.ground.pulses import RectangularPulse, SinePulse, StepImpulse
from archquake.ground.records import Record
from archquake.ranges import RIGID_MAX_WORK, RIGID_SECONDS_PER_WORK

#: Default time step, s (convergence in docs/notes/mechanism.md: halving it changes the energy kept
#: over Oppenheim's first half cycle by < 0.01).
DEFAULT_TIME_STEP = 1.0e-4
#: A corner is in contact when its gap is below this fraction of the assembly's reference length.
GAP_TOLERANCE = 1.0e-9
#: The stepper's position-level correction (``_step_kernels.run``): a corner that pushed at the
#: previous step stays in contact while its gap is below this fraction of the reference length
#: (it must exceed a step's drift, r omega^2 h^2 / 2: 7e-8 m on the parabolic arch of
#: docs/notes/mechanism.md), and every contact's normal row is bound to close its gap in one step.
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



@dataclass(frozen=True, eq=False)
class RigidModel:
    """An `Assembly` packed for the stepper: free bodies and joint corners.

    ``body`` maps assembly block -> free-body index (-1 for base blocks); for joint j,
    ``ja[j]``/``jb[j]`` are the free bodies on its ``left``/``right`` side (-1: the base),
    ``arm_a[j, c]``/``arm_b[j, c]`` corner c's position relative to that body's centroid in the
    undisplaced assembly (for a base side, the corner itself), m; ``n0[j]`` the joint normal
    from left into right, ``t0[j]`` the direction from corner 0 to corner 1; ``arch`` the arch
    it was built from (None: built from an assembly).

    A model is built once and its derived forms are computed once, on it: the compiled
    kernels' packed arrays (`chain`) and the event integrator's layout with its onset
    accelerations (`events`). Models compare and hash by identity (their arrays have no
    equality of their own), so functions of a model can be memoised on it."""

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
    arch: VoussoirChain | None = None

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
        # a joint between two base blocks (a base that takes in voussoirs: the arch cut at the
        # four-link model's hinges with a hinge above the springing) moves nothing: left out
        joints = [jt for jt in asm.joints if not (base[jt.left] and base[jt.right])]
        nj = len(joints)
        ja = np.zeros(nj, np.int64)
        jb = np.zeros(nj, np.int64)
        arm_a = np.zeros((nj, 2, 2))
        arm_b = np.zeros((nj, 2, 2))
        n0 = np.zeros((nj, 2))
        t0 = np.zeros((nj, 2))
        for j, joint in enumerate(joints):
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
                   ja, jb, arm_a, arm_b, n0, t0,
                   arch_or_assembly if isinstance(arch_or_assembly, VoussoirChain) else None)

    @property
    def n_bodies(self) -> int:
        return int(self.free_blocks.size)

    def rest(self) -> tuple[np.ndarray, np.ndarray]:
        """The undisplaced configuration and zero velocity, (nb, 3) each."""
        q = np.zeros((self.n_bodies, 3))
        q[:, :2] = self.centroids
        return q, np.zeros_like(q)

    @cached_property
    def chain(self) -> RK.Chain:
        """The packed arrays of the compiled kernels (`archquake.rigid._step_kernels.Chain`),
        built once."""
        return RK.pack_chain(self)

    def geometry(self, q: np.ndarray) -> RK.Geometry:
        """The corner gaps, joint normals and tangents and corner positions
        (`archquake.rigid._step_kernels.Geometry`) of the configuration ``q`` (nb, 3)."""
        return RK.geometry(np.asarray(q, float), self.ja, self.jb, self.arm_a, self.arm_b,
                           self.n0, self.t0)

    def gaps(self, q: np.ndarray) -> np.ndarray:
        """Corner gaps (nj, 2), m, of the configuration ``q`` (nb, 3), positive open."""
        return self.geometry(q).gaps

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
        scale = max(float(np.max(np.abs(v))), 1e-300)
        tol = 1e-14 * scale if tol is None else tol
        cfg = RK.solving(GAP_TOLERANCE * self.assembly.reference_length, tol, max_sweeps)
        vn, imp, _, _ = RK.project(self.chain, cfg, q, self.geometry(q), np.asarray(v, float),
                                   np.zeros((len(self.ja), 3)), np.empty(0), np.empty(0))
        return vn, imp



def mean_vertical(motion, t0: float, h: float, n: int) -> np.ndarray:
    """The upward ground acceleration, m/s^2, averaged over each of ``n`` steps of ``h`` s from
    ``t0`` s, (n,); empty when the motion has no vertical (the stepper's gravity is then g).

    A pulse's vertical is R direction x_g''(t) + c (`archquake.ground.pulses`): the mean
    of each step is R direction times `mean_acceleration`'s, plus c. A record's vertical
    component (`WithVertical`) is averaged as a record.
    """
    if not has_vertical(motion):
        return np.empty(0)
    if isinstance(motion.vertical, Record):  # a record's vertical component
        return mean_acceleration(motion.vertical, t0, h, n)
    return (motion.vertical * motion.direction * mean_acceleration(motion, t0, h, n)
            + motion.steady_vertical)


def mean_acceleration(motion, t0: float, h: float, n: int) -> np.ndarray:
    """The ground acceleration, m/s^2, averaged over each of ``n`` steps of ``h`` s from ``t0``
    s (``ACC_SAMPLES`` mid-point sub-samples a step), (n,).

    The mean of a step is that of its sub-samples ``motion.acceleration(t0 + h (k + (j + 1/2)
    / ACC_SAMPLES))`` as ``ndarray.mean`` computes it, to the bit, by three routes:

    * a sampled record (`Record`): compiled
      (`archquake.rigid._input_kernels.step_means`: the same interpolation and NumPy's
      order of summation), without the (n, ``ACC_SAMPLES``) array of sub-samples;
    * a pulse constant between its breakpoints (the step impulse, the rectangular pulse): only
      the steps that straddle a breakpoint are sub-sampled: every other step's sub-samples are
      equal, and so is their mean (a sum of 16 equal values is exact);
    * the sine pulse: the steps after its period are 0 without being sub-sampled (the mean of
      zeros);
    * any other motion: all sub-samples, then ``mean``.
    """
    motion = getattr(motion, "horizontal", motion)  # a record with its vertical
    if isinstance(motion, Record):
        out = np.empty(n)
        IK.step_means(motion.kernel_spec()[1], float(t0), float(h), ACC_SAMPLES, out)
        return out
    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    k = np.arange(n)
    if isinstance(motion, SinePulse):
        # zero from its period on: a step whose first sub-sample is past it is 0 (the mean
        # of zeros), and only the steps before are sub-sampled
        out = np.zeros(n)
        live = int(np.searchsorted(t0 + h * (k + sub[0]), motion.period, side="left"))
        t = t0 + h * (k[:live, None] + sub[None, :])
        out[:live] = np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(
            live, ACC_SAMPLES).mean(1)
        return out
    if not isinstance(motion, (StepImpulse, RectangularPulse)):
        t = t0 + h * (k[:, None] + sub[None, :])
        return np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(
            n, ACC_SAMPLES).mean(1)
    first = t0 + h * (k + sub[0])  # each step's first and last sub-sample, as in ``t`` above
    last = t0 + h * (k + sub[-1])
    breaks = np.asarray(motion.breakpoints(), dtype=float)
    mixed = np.flatnonzero(np.searchsorted(breaks, first, side="right")
                           != np.searchsorted(breaks, last, side="right"))
    out = np.asarray(motion.acceleration(first), dtype=float).copy()
    if mixed.size:
        t = t0 + h * (k[mixed][:, None] + sub[None, :])
        out[mixed] = np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(
            mixed.size, ACC_SAMPLES).mean(1)
    return out


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


__all__ = ["ACC_SAMPLES", "DEFAULT_TIME_STEP", "FORCE_SAMPLES", "GAP_TOLERANCE", "HOLD_TOLERANCE",
           "MAX_SWEEPS", "SOLVER_TOLERANCE", "RigidModel", "absolute_states", "mean_acceleration",
           "mean_vertical"]


def check_work(n_bodies: int, duration: float, time_step: float, *, runs: int = 1,
               passes: int = 1, change: str = "use fewer voussoirs or a shorter duration") -> float:
    """Refuse a run of the chain whose work exceeds `archquake.ranges.RIGID_MAX_WORK`.

    Parameters
    ----------
    n_bodies : int
        Blocks of the chain (voussoirs, and piers where there are any).
    duration : float
        Simulated time of the run, s.
    time_step : float
        Its time step, s.
    runs : int
        Histories of this size in the call (a batch of verdicts: each one is checked).
    passes : int
        Times one history is integrated in a row (a command that finds the verdict, then
        records the history): their sum is checked.
    change : str
        What the refusal tells the user to change (the command line names its options).

    Returns
    -------
    float
        The estimated time of the whole call, s (the work of every run and pass times
        `archquake.ranges.RIGID_SECONDS_PER_WORK`), when it is accepted.

    Raises
    ------
    InvalidParameterError
        With the estimate and what to change, before any step is taken.
    """
    steps = math.ceil(duration / time_step)
    work = float(steps) * (n_bodies + 1) ** 3 * passes
    if work > RIGID_MAX_WORK:
        raise InvalidParameterError(
            f"{n_bodies} blocks over {steps:,} time steps of {time_step:.3g} s"
            + (f", {passes} times," if passes > 1 else "")
            + f" are {work:.3g} units of work (steps x (blocks + 1)^3), more than "
            f"{RIGID_MAX_WORK:.0e}: about {work * RIGID_SECONDS_PER_WORK / 60:.3g} min"
            + (f" for each of {runs} histories" if runs > 1 else "")
            + " (each step solves every joint's contacts together, so the cost grows as the "
            f"cube of the blocks): {change} (now {duration:g} s)")
    return work * runs * RIGID_SECONDS_PER_WORK
