"""Compiled verdict-only run of the rigid chain (numba): the Moreau-Jean step of
`archquake.rigid._step_kernels.run` (the same step, through ``project_direct``, with its work
arrays kept over the whole run where the recorded stepper keeps them over a chunk of steps: the
kept factor and extrapolated start of `project_direct` then serve on different steps, so the
two agree to the solver's tolerance, not bit for bit), with the verdict of
`archquake.blocks.result.BlockResult.from_samples` read on the fly instead of from recorded
samples, and three shortcuts that do not change it:

* **skip at rest**: while the chain is untouched at rest (q, v exactly the rest state) and the
  step's mean ground acceleration lies inside the safe domain (-lambda_- g, lambda_+ g) (the
  no-slip chain's onset multipliers, `archquake.rigid.events.EventModel.onset_g`), the
  exact solution does not move, so the step is not computed. Once the chain has moved, every
  step is computed: a chain that has settled again (kinetic energy below ``REST_KINETIC`` W L)
  still moves a little, and on records the verdict near a threshold depends on that motion
  (zeroing it and skipping changed verdicts at threshold levels of the bridge example under
  near-field records);
* **stop at collapse**: at the first step meeting a collapse criterion
  (`archquake.blocks._kernels.collapsed`);
* **stop at proven rest**: at rest with the rest of the ground motion inside the safe domain
  (past the last step whose ground acceleration reaches the domain's bound, `REST_LAST`):
  untouched, or, after a motion, settled (kinetic
  energy below ``REST_KINETIC`` W L for a rest window, every joint closed, the safe domain
  narrowed by ``REST_MARGIN``, the configuration being only near the undisplaced one); or
  settled after the end of the excitation (`settled`'s rule).

A sampled record's step means are computed as the run reaches them (`record`, in blocks of
`MEAN_BLOCK` steps), not for the whole window before it starts: a run that collapses or
proves its rest early does not pay for the steps it never takes. The last steps reaching the
safe domain's bounds are found from the record's samples
(`archquake.rigid._input_kernels.record_last_at_least`), the same steps as from all the
means.

Every step is checked (the recorded runs check at their output samples); the hinge onset is
read on the step's mid-step corner gaps (``_rigid_kernels.geometry``), the DEM's on the recorded
joint openings: both are the opening of a joint end beyond ``hinge_opening`` L.

The impacts before a collapse (its half cycle) are the sign changes of the rotation measure
(`archquake.blocks.result.crossings`), counted on both the assembly's rotation link and its
mirror image; the caller picks one with `archquake.blocks.result.mirror_opens_first`'s rule.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

import archquake.rigid._input_kernels as IK
import archquake.rigid._step_kernels as RK
from archquake._kernel_cache import stamp_kernels
from archquake.blocks import _kernels as DK

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: Parameters, ``par`` (float64).
P_H = 0  # s, time step
P_G = 1  # m/s^2
P_GAP_TOL = 2  # m
P_TOL = 3  # m/s, solver tolerance
P_MAX_ITER = 4
P_HOLD_TOL = 5  # m
P_SAFE_POS = 6  # m/s^2, the ground acceleration towards +x below which the resting chain stays
P_SAFE_NEG = 7  # m/s^2, the same towards -x (a magnitude)
P_EXC_END = 8  # s, the end of the excitation
P_OPEN = 9  # m, a joint end open by more than this is a hinge
P_REST_KIN = 10  # J
P_REST_WINDOW = 11  # s
P_ROT_THR = 12  # rad, the rotation measure's arming threshold (hinge_opening)
P_SKIP = 13  # 1: skip at rest and stop at proven rest; 0: step every step
P_STOP_COLLAPSE = 14  # 1: stop at collapse
P_REST_MARGIN = 15  # -, the safe domain after a motion, a fraction of the onset's
P_SUB_SAMPLES = 16  # sub-samples of a step's mean ground acceleration (a record's, in the run)
N_PAR = 17

#: Outputs, ``out`` (float64).
O_OUTCOME = 0  # 0 no_hinging, 1 survives, 2 collapse, 3 indeterminate
O_T_END = 1  # s
O_T_COLLAPSE = 2  # s, NaN if none
O_ONSET_STEP = 3  # the step whose mid-step gaps first opened a hinge, -1 if none
O_IMPACTS_0 = 4  # sign changes of the rotation measure before the verdict, assembly's link
O_IMPACTS_1 = 5  # the same, mirror link
O_STEPS = 6  # steps computed
O_SKIPPED = 7  # steps skipped at rest
O_PEAK_DROP = 8  # -, largest crown drop before the collapse, a fraction of the collapse drop
O_MAX_SWEEPS = 9
O_FINAL = 10  # 0 moving, 1 rest, 2 collapsed
O_REST_PROVEN = 11  # 1: ended at rest with the remaining ground motion inside the safe domain
O_FIRST_IMPACT_0 = 12  # s, the first sign change of the rotation measure, link 0 (NaN: none)
O_FIRST_IMPACT_1 = 13  # the same, link 1
O_LONGEST_0 = 14  # s, the longest time between two consecutive sign changes, or from the last
#: one to the collapse, link 0 (0: none)
O_LONGEST_1 = 15  # the same, link 1
O_PEAK_ROT_0 = 16  # rad, the largest |rotation measure| before the verdict, link 0
O_PEAK_ROT_1 = 17  # the same, link 1
O_MEANS = 18  # the steps whose means ``acc`` holds (a record's: those the run reached)
N_OUT = 19

OUTCOME_NO_HINGING = 0
OUTCOME_SURVIVES = 1
OUTCOME_COLLAPSE = 2
OUTCOME_INDETERMINATE = 3


class Frame(NamedTuple):
    """The assembly's arrays the verdict reads besides the `Chain`:
    ``base_state`` (n_blocks, 3) every block's undisplaced x, y (m), theta (rad);
    ``free_blocks`` (nb,) int the assembly index of each free body; ``free_mask`` (n_blocks,)
    int 1 for a free block; ``cpar``: `archquake.blocks.result.collapse_parameters`;
    ``links_block`` (2, 2) int, ``links_local`` (2, 2, 2) m, ``links_sign`` (2,): the two
    rotation links (the assembly's, its mirror image), their blocks and points relative to the
    blocks' centroids."""

    base_state: np.ndarray
    free_blocks: np.ndarray
    free_mask: np.ndarray
    cpar: np.ndarray
    links_block: np.ndarray
    links_local: np.ndarray
    links_sign: np.ndarray


#: ``rest_last`` (4,): the last step whose at-rest ground acceleration (``skip_acc``) reaches,
#: towards +x and -x, the safe domain's bounds at rest untouched (``P_SAFE_POS``,
#: ``P_SAFE_NEG``) and settled after a motion (times ``P_REST_MARGIN``); -1: none; the steps'
#: count where a bound is not above 0 (nothing is inside). A chain at rest from step k on
#: stays there when k is past both of its bounds' steps.
REST_LAST = 4
#: Steps whose means a record's run computes at once.
MEAN_BLOCK = 1024


class Histories(NamedTuple):
    """Histories for `verdict_batch`, end to end: history i's steps are
    ``acc[starts[i]:starts[i + 1]]`` (the steps' mean ground accelerations, m/s^2), with
    ``rest_last[i]`` (`REST_LAST`) and the parameters ``pars[i]`` (`N_PAR`, P_*)."""

    acc: np.ndarray
    rest_last: np.ndarray
    starts: np.ndarray
    pars: np.ndarray
    #: the steps' mean upward ground accelerations, m/s^2 (empty: none), and the horizontal
    #: ones as the at-rest tests read them, acc g / (g + a_v) (the direction of the body force
    #: decides whether a chain at rest moves; ``acc`` itself when there is no vertical)
    vacc: np.ndarray
    skip_acc: np.ndarray
    #: history i's sampled record, ``record[record_starts[i]:record_starts[i + 1]]`` (its
    #: ``kernel_spec`` parameters), when its ``acc`` is to be computed as the run reaches it
    #: (`MEAN_BLOCK` steps at a time; ``skip_acc`` is then ``acc``); an empty slice: ``acc``
    #: is given whole
    record: np.ndarray
    record_starts: np.ndarray


@nb.njit(cache=True, inline="always")
def _chord_angle(st, links_block, links_local, ell):
    """Angle (rad) of the chord of rotation link ``ell`` in the block states ``st``."""
    ba = links_block[ell, 0]
    bb = links_block[ell, 1]
    ca = math.cos(st[ba, 2])
    sa = math.sin(st[ba, 2])
    cb = math.cos(st[bb, 2])
    sb = math.sin(st[bb, 2])
    ax = st[ba, 0] + ca * links_local[ell, 0, 0] - sa * links_local[ell, 0, 1]
    ay = st[ba, 1] + sa * links_local[ell, 0, 0] + ca * links_local[ell, 0, 1]
    bx = st[bb, 0] + cb * links_local[ell, 1, 0] - sb * links_local[ell, 1, 1]
    by = st[bb, 1] + sb * links_local[ell, 1, 0] + cb * links_local[ell, 1, 1]
    return math.atan2(by - ay, bx - ax)


@nb.njit(cache=True, nogil=True)
def verdict_run(chain, frame, acc, rest_last, par, out, vacc, skip_acc, record):
    """Run the chain (`Chain` ``chain``, `Frame` ``frame``)
    from rest under ``acc`` (n,) (the steps' mean ground accelerations, m/s^2) up to a verdict
    (module docstring) and write it into ``out`` (`N_OUT`).

    ``rest_last`` (`REST_LAST`); ``par``: `N_PAR` parameters (P_*); ``vacc``, ``skip_acc``,
    ``record``: as `Histories` (with a record, ``acc`` is filled as the run reaches its
    steps)."""
    nb_ = chain.mass.shape[0]
    nj = chain.ja.shape[0]
    q = np.zeros((nb_, 3))
    for i in range(nb_):
        for c in range(3):
            q[i, c] = frame.base_state[frame.free_blocks[i], c]
    state = RK.State(q, np.zeros((nb_, 3)), np.zeros((nj, 3)), np.full(nj, np.nan))
    # the rotation measure on both links: unwrapped angle, arming state (0: not armed, else
    # the sign of the side it is armed on), impacts and their times, peaks
    measure = Rotation(np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2),
                       np.full(2, np.nan), np.full(2, np.nan), np.zeros(2), np.zeros(2),
                       np.zeros(2))
    frac = IK.sub_fractions(int(par[P_SUB_SAMPLES]))
    _verdict_steps(chain, frame, acc, rest_last, par, out, vacc, skip_acc,
                   RecordMeans(record, frac, np.empty(frac.shape[0])), state,
                   RK.workspace(nb_, nj), frame.base_state.copy(), measure)


class RecordMeans(NamedTuple):
    """A record's step means computed as the run reaches them: its ``kernel_spec``
    parameters ``record`` (empty: the means are given whole), the sub-samples' places in a
    step ``frac`` and their scratch ``values`` (``P_SUB_SAMPLES`` each)."""

    record: np.ndarray
    frac: np.ndarray
    values: np.ndarray


class Rotation(NamedTuple):
    """The rotation measure of `verdict_run` on its two links (2,) each: ``rot0`` and
    ``ang_prev`` the chord's first and latest angle (rad), ``rot`` its unwrapped change,
    ``armed`` (0, or the sign of the side armed on), ``impacts``, ``last_impact``,
    ``first_impact`` (s, NaN: none), ``longest`` (s), ``prev_rot``, ``peak_rot`` (rad)."""

    rot0: np.ndarray
    ang_prev: np.ndarray
    rot: np.ndarray
    armed: np.ndarray
    impacts: np.ndarray
    last_impact: np.ndarray
    first_impact: np.ndarray
    longest: np.ndarray
    prev_rot: np.ndarray
    peak_rot: np.ndarray


@nb.njit(cache=True, nogil=True, **RK.NO_REFCOUNT)
def _verdict_steps(chain, frame, acc, rest_last, par, out, vacc, skip_acc, means, state, ws, st,
                   measure):
    """`verdict_run`'s loop from the rest state ``state`` (`RK.State`), in the work arrays
    ``ws`` (`RK.workspace`), ``st`` (n_blocks, 3) the blocks' states, ``measure`` (`Rotation`,
    zeroed), ``means`` (`RecordMeans`) a record's means as the run reaches them: compiled
    without reference counting (`RK.advance`), it allocates nothing."""
    mass = chain.mass
    inertia = chain.inertia
    free_blocks = frame.free_blocks
    free_mask = frame.free_mask
    cpar = frame.cpar
    links_block = frame.links_block
    links_local = frame.links_local
    links_sign = frame.links_sign
    h = par[P_H]
    g = par[P_G]
    nb_ = mass.shape[0]
    nj = chain.ja.shape[0]
    n_steps = acc.shape[0]
    filled = 0 if means.record.shape[0] > 0 else n_steps  # the steps of acc computed so far
    skip = par[P_SKIP] > 0.0
    safe_pos = par[P_SAFE_POS]
    safe_neg = par[P_SAFE_NEG]
    margin = par[P_REST_MARGIN]
    q = state.q
    v = state.v
    p_warm = state.p_warm
    cfg = RK.Stepping(h, g, par[P_GAP_TOL], par[P_TOL], int(par[P_MAX_ITER]), 0.0,
                      RK.METHOD_DIRECT, h, par[P_HOLD_TOL], RK.ACTIVE_SET_ITERATIONS)
    gaps = ws.gaps
    vn = ws.vn
    imp = ws.imp
    qm = ws.qm
    rot0 = measure.rot0
    ang_prev = measure.ang_prev
    rot = measure.rot
    armed = measure.armed
    impacts = measure.impacts
    last_impact = measure.last_impact
    first_impact = measure.first_impact
    longest = measure.longest
    prev_rot = measure.prev_rot
    peak_rot = measure.peak_rot
    for ell in range(2):
        rot0[ell] = _chord_angle(st, links_block, links_local, ell)
        ang_prev[ell] = rot0[ell]
    pristine = True  # q, v exactly the rest state
    closed = True  # no joint end open beyond hinge_opening L after the last step
    t_still = 0.0  # since when the kinetic energy has stayed below the rest threshold
    onset = -1
    peak_drop = 0.0
    worst = 0
    computed = 0
    skipped = 0
    outcome = -1
    final = 0
    rest_proven = 0
    t_collapse = math.nan
    k = 0
    t = 0.0
    while k < n_steps:
        t = k * h  # the state's time
        if k >= filled:
            fill_to = min(filled + MEAN_BLOCK, n_steps)
            IK.step_means_into(means.record, 0.0, h, means.frac, means.values, acc, filled,
                               fill_to)
            filled = fill_to
        resting = pristine or (closed and t - t_still > par[P_REST_WINDOW])
        if skip and resting:
            lim_p = safe_pos if pristine else margin * safe_pos
            lim_n = safe_neg if pristine else margin * safe_neg
            last = 0 if pristine else 2
            if k > rest_last[last] and k > rest_last[last + 1]:
                # at rest, and nothing left can move it: the verdict is reached
                rest_proven = 1
                final = 1
                break
            if pristine and -lim_n < skip_acc[k] < lim_p:
                skipped += 1
                k += 1
                t = k * h
                continue
        # one Moreau-Jean step, as _rigid_kernels.run (method direct, correction on)
        if pristine:
            # the chain starts to move: it has been still only from here on (a chain just set
            # moving has little kinetic energy, and is not at rest)
            t_still = t
        t = (k + 1) * h
        pristine = False
        computed += 1
        sweeps, res = RK.advance(chain, cfg, state, acc[k], ws,
                                 vacc[k] if vacc.shape[0] > 0 else 0.0)
        if sweeps > worst:
            worst = sweeps
        closed = True
        for j in range(nj):
            p_warm[j, 0] = imp[j, 0]
            p_warm[j, 1] = imp[j, 1]
            p_warm[j, 2] = imp[j, 2]
            if gaps[j, 0] > par[P_OPEN] or gaps[j, 1] > par[P_OPEN]:
                closed = False
                if onset < 0:
                    onset = k
        for i in range(nb_):
            for c in range(3):
                v[i, c] = vn[i, c]
                q[i, c] = qm[i, c] + 0.5 * h * vn[i, c]
        kin = 0.0
        for i in range(nb_):
            kin += 0.5 * (mass[i] * (v[i, 0] ** 2 + v[i, 1] ** 2) + inertia[i] * v[i, 2] ** 2)
            for c in range(3):
                st[free_blocks[i], c] = q[i, c]
        if kin > par[P_REST_KIN]:
            t_still = t
        k += 1
        # collapse (the crown's drop from its undisplaced height, as cpar says)
        yc = DK.crown_height(st, cpar)
        if par[P_STOP_COLLAPSE] > 0.0 and DK.collapsed_at(st, free_mask, cpar, yc):
            outcome = OUTCOME_COLLAPSE
            final = 2
            t_collapse = t
            # the collapsing half cycle, from the last impact, counts among the half cycles
            for ell in range(2):
                if not math.isnan(last_impact[ell]) and t - last_impact[ell] > longest[ell]:
                    longest[ell] = t - last_impact[ell]
            break
        if int(cpar[DK.C_CROWN_BLOCK]) >= 0:
            drop = (cpar[DK.C_CROWN_Y0] - yc) / cpar[DK.C_CROWN_DROP]
            if drop > peak_drop:
                peak_drop = drop
        # the rotation measure's sign changes (archquake.blocks.result.crossings)
        for ell in range(2):
            a = _chord_angle(st, links_block, links_local, ell)
            # d wrapped into [-pi, pi), the modulo only when needed (the same numbers)
            x = a - ang_prev[ell] + math.pi
            if not 0.0 <= x < 2.0 * math.pi:
                x = x % (2.0 * math.pi)
            d = x - math.pi
            ang_prev[ell] = a
            prev_rot[ell] = rot[ell]
            rot[ell] += d
            if abs(rot[ell]) > peak_rot[ell]:
                peak_rot[ell] = abs(rot[ell])
            r = links_sign[ell] * rot[ell]
            r_prev = links_sign[ell] * prev_rot[ell]
            if armed[ell] == 0.0:
                if abs(r) > par[P_ROT_THR]:
                    armed[ell] = 1.0 if r > 0.0 else -1.0
            elif (armed[ell] > 0.0 and r <= 0.0) or (armed[ell] < 0.0 and r >= 0.0):
                impacts[ell] += 1.0
                frac = r_prev / (r_prev - r) if r_prev != r else 1.0
                t_imp = t - h + frac * h
                if math.isnan(first_impact[ell]):
                    first_impact[ell] = t_imp
                elif t_imp - last_impact[ell] > longest[ell]:
                    longest[ell] = t_imp - last_impact[ell]
                last_impact[ell] = t_imp
                if abs(r) > par[P_ROT_THR]:
                    armed[ell] = 1.0 if r > 0.0 else -1.0
                else:
                    armed[ell] = 0.0
        if t - par[P_REST_WINDOW] >= par[P_EXC_END] and t - t_still > par[P_REST_WINDOW]:
            final = 1  # settled after the excitation: the ground is still, the chain stays
            break
    if outcome < 0:
        if final == 0 and t - par[P_REST_WINDOW] >= par[P_EXC_END] \
                and t - t_still > par[P_REST_WINDOW]:
            final = 1
        if onset < 0:
            outcome = OUTCOME_NO_HINGING
        elif final == 1:
            outcome = OUTCOME_SURVIVES
        else:
            outcome = OUTCOME_INDETERMINATE
    out[O_OUTCOME] = outcome
    out[O_T_END] = t
    out[O_T_COLLAPSE] = t_collapse
    out[O_ONSET_STEP] = onset
    out[O_IMPACTS_0] = impacts[0]
    out[O_IMPACTS_1] = impacts[1]
    out[O_STEPS] = computed
    out[O_SKIPPED] = skipped
    out[O_PEAK_DROP] = peak_drop
    out[O_MAX_SWEEPS] = worst
    out[O_FINAL] = final
    out[O_REST_PROVEN] = rest_proven
    out[O_FIRST_IMPACT_0] = first_impact[0]
    out[O_FIRST_IMPACT_1] = first_impact[1]
    out[O_LONGEST_0] = longest[0]
    out[O_LONGEST_1] = longest[1]
    out[O_PEAK_ROT_0] = peak_rot[0]
    out[O_PEAK_ROT_1] = peak_rot[1]
    out[O_MEANS] = filled


@nb.njit(cache=True, nogil=True)
def verdict_batch(chain, frame, hist, outs, first, last):
    """`verdict_run` for histories ``first`` to ``last - 1`` of ``hist``
    (`Histories`), history i's verdict into ``outs[i]``. Releases the GIL: a thread
    pool runs slices."""
    for i in range(first, last):
        a = hist.starts[i]
        b = hist.starts[i + 1]
        vertical = hist.vacc.shape[0] > 0
        acc = hist.acc[a:b]
        record = hist.record[hist.record_starts[i]:hist.record_starts[i + 1]]
        verdict_run(chain, frame, acc, hist.rest_last[i], hist.pars[i], outs[i],
                    hist.vacc[a:b] if vertical else hist.vacc,
                    acc if record.shape[0] > 0 else hist.skip_acc[a:b], record)
