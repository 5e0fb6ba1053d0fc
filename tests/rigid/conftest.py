"""A rigid block on its base released from rest, tilted on its right corner, with Housner's
exact free rocking (:func:`archquake.validation.housner.free_rocking`): the case both
integrations of the rigid chain are held to."""

import math

import numpy as np
import pytest

from archquake.blocks.assembly import block_on_base
from archquake.constants import STANDARD_GRAVITY as G
from archquake.rigid import RigidModel
from archquake.validation import housner


def _released_block(b: float = 0.4, height: float = 2.0, fraction: float = 0.5):
    """(model, (q, v), oracle) for the block tilted by ``fraction`` of its slenderness: oracle
    ``t1``, ``t2`` (the first two impacts, s), ``th1`` (the tilt after the first, rad), ``r``
    (Housner's restitution), ``e0`` (the released energy, J)."""
    model = RigidModel.build(block_on_base(b, height))
    alpha, radius = housner.slenderness(b, height), housner.half_diagonal(b, height)
    th0 = fraction * alpha
    q, v = model.rest()
    pivot = np.array([0.5 * b, 0.0])
    c, s = math.cos(-th0), math.sin(-th0)
    d = model.centroids[0] - pivot
    q[0, :2] = pivot + [c * d[0] - s * d[1], s * d[0] + c * d[1]]
    q[0, 2] = -th0
    e0 = float(model.mass[0]) * G * radius * (math.cos(alpha - th0) - math.cos(alpha))
    (t1, t2), (th1, _) = housner.free_rocking(b, height, th0, 2, g=G)
    return model, (q, v), dict(t1=t1, t2=t2, th1=th1, r=housner.restitution(b, height), e0=e0)


@pytest.fixture(scope="session")
def released_block():
    """The factory :func:`_released_block`: ``released_block(b, height, fraction)``."""
    return _released_block
