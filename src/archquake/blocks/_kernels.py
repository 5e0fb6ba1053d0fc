"""Compiled kernels of the block models' post-processing (numba), shared by the
distinct-element model (`archquake.dem`) and the rigid chain (`archquake.rigid`): the collapse
criteria on a configuration (`collapsed`, `crown_height`, `collapsed_at`, `first_collapsed`,
their packed parameters ``cpar``, the C_* indices, built by
`archquake.blocks.result.collapse_parameters`) and the joints' openings and slips
(`joint_openings`).

Everything here is private.
"""

from __future__ import annotations

import math

import numba as nb

from archquake._kernel_cache import stamp_kernels

stamp_kernels()  # the cache checks each kernel against every source compiled into it

# collapse-parameter indices
C_BASE, C_ROT, C_CROWN_BLOCK, C_CROWN_LX, C_CROWN_LY, C_CROWN_Y0, C_CROWN_DROP = range(7)
N_COLLAPSE = 7


@nb.njit(cache=True)
def collapsed(state, free, cpar):
    """Collapse criteria on a recorded configuration (x, y, theta per block)."""
    return collapsed_at(state, free, cpar, crown_height(state, cpar))


@nb.njit(cache=True)
def crown_height(state, cpar):
    """The height of the crown's point (m) in the configuration ``state``, NaN when ``cpar``
    names no crown block."""
    cb = int(cpar[C_CROWN_BLOCK])
    if cb < 0:
        return math.nan
    c = math.cos(state[cb, 2])
    s = math.sin(state[cb, 2])
    return state[cb, 1] + s * cpar[C_CROWN_LX] + c * cpar[C_CROWN_LY]


@nb.njit(cache=True)
def collapsed_at(state, free, cpar, yc):
    """`collapsed` with the crown's height ``yc`` (m, `crown_height`) already computed (the
    verdict's loop reads it for the crown's drop as well)."""
    for i in range(state.shape[0]):
        if free[i] == 0:
            continue
        if state[i, 1] < cpar[C_BASE]:
            return True
        if abs(state[i, 2]) > cpar[C_ROT]:
            return True
    return int(cpar[C_CROWN_BLOCK]) >= 0 and cpar[C_CROWN_Y0] - yc > cpar[C_CROWN_DROP]


@nb.njit(cache=True)
def joint_openings(pos, cos, sin, left, right, nrm0, tan0, local_left, local_right, opening,
                   slip):
    """Opening (nt, nj, 2) at both ends and slip (nt, nj) of every recorded joint, m, into
    ``opening`` and ``slip``: `archquake.blocks.result.joint_kinematics`, which packs the
    joints (``left``/``right`` blocks, undisplaced normal and tangent, each end relative to
    either centroid) and passes ``cos``/``sin`` of every block's rotation (nt, nb).

    Each end's gap is the right block's copy of the end point minus the left block's, resolved
    on the normal and tangent turned with the left block; the slip is the tangential gap at the
    more closed end (the first on a tie, as ``argmin``). Sums of two products get ``+ 0.0``,
    as ``np.sum`` over the pair does (-0.0 + -0.0 is +0.0 there): bit for bit the per-joint
    NumPy expressions (test)."""
    for k in range(pos.shape[0]):
        for j in range(left.shape[0]):
            a = left[j]
            b = right[j]
            c, s, cr, sr = cos[k, a], sin[k, a], cos[k, b], sin[k, b]
            nx = c * nrm0[j, 0] - s * nrm0[j, 1]
            ny = s * nrm0[j, 0] + c * nrm0[j, 1]
            tx = c * tan0[j, 0] - s * tan0[j, 1]
            ty = s * tan0[j, 0] + c * tan0[j, 1]
            tang0 = 0.0
            tang1 = 0.0
            for end in range(2):
                la0, la1 = local_left[j, end, 0], local_left[j, end, 1]
                lb0, lb1 = local_right[j, end, 0], local_right[j, end, 1]
                gx = (pos[k, b, 0] + cr * lb0 - sr * lb1) - (pos[k, a, 0] + c * la0 - s * la1)
                gy = (pos[k, b, 1] + sr * lb0 + cr * lb1) - (pos[k, a, 1] + s * la0 + c * la1)
                opening[k, j, end] = (gx * nx + gy * ny) + 0.0
                if end == 0:
                    tang0 = (gx * tx + gy * ty) + 0.0
                else:
                    tang1 = (gx * tx + gy * ty) + 0.0
            o0 = opening[k, j, 0]
            o1 = opening[k, j, 1]
            if o1 < o0 or (math.isnan(o1) and not math.isnan(o0)):
                slip[k, j] = tang1
            else:
                slip[k, j] = tang0


@nb.njit(cache=True)
def first_collapsed(states, free, cpar):
    """Index of the first recorded configuration (nt, nb, >= 3) meeting a collapse criterion
    (`collapsed`), -1 if none does."""
    for k in range(states.shape[0]):
        if collapsed(states[k], free, cpar):
            return k
    return -1
