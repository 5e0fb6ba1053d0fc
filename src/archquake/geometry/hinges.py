"""Hinges at voussoir joints and the four-hinge mechanism they define.

A hinge at the *intrados* end of a joint opens the joint at the extrados, and vice versa.
For a joint whose right-hand block turns by ``delta`` (counter-clockwise positive) relative
to its left-hand block, an intrados hinge needs ``delta < 0`` and an extrados hinge
``delta > 0`` (the opening side moves into the right-hand block's side of the joint).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from functools import cached_property

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.fourbar import link_rates
from archquake.geometry.planar import perp


class Face(str, Enum):
    """Which end of a joint a hinge sits at."""

    INTRADOS = "intrados"
    EXTRADOS = "extrados"

    @property
    def opposite(self) -> Face:
        return Face.EXTRADOS if self is Face.INTRADOS else Face.INTRADOS

    @property
    def opening_sign(self) -> int:
        """Sign of the right block's rotation relative to the left block when the joint opens."""
        return -1 if self is Face.INTRADOS else +1


@dataclass(frozen=True)
class Hinge:
    """A hinge: joint index (0 = left springing), face, and its coordinates in m."""

    joint: int
    face: Face
    x: float
    y: float

    def to_dict(self) -> dict:
        return {"joint": self.joint, "face": self.face.value, "x": self.x, "y": self.y}


@dataclass(frozen=True)
class HingeMechanism:
    """The four-hinge mechanism A, B, C, D (left to right) of an arch.

    Links: AB = voussoirs joints[0]..joints[1]-1, BC = joints[1]..joints[2]-1,
    CD = joints[2]..joints[3]-1; voussoirs outside [joints[0], joints[3]) stay on the ground.

    The opening motion is the one whose relative rotations at the four hinges all match the
    hinge faces (see the module docstring); ``phi`` (the paper's theta0 - theta) is the
    rotation of link AB in that sense, so ``phi > 0`` while the mechanism is open.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch (`archquake.geometry`): a chain of blocks between two supports.
    joints : tuple of 4 ints, strictly increasing, in [0, n]
    faces : tuple of 4 Face
    """

    arch: VoussoirChain
    joints: tuple[int, int, int, int]
    faces: tuple[Face, Face, Face, Face]

    def __post_init__(self) -> None:
        j = tuple(int(x) for x in self.joints)
        n = self.arch.voussoirs
        if len(j) != 4 or not all(0 <= x <= n for x in j) or not (j[0] < j[1] < j[2] < j[3]):
            raise InvalidParameterError(
                f"hinge joints must be four strictly increasing joint indices in [0, {n}], got {j}"
            )
        object.__setattr__(self, "joints", j)
        object.__setattr__(self, "faces", tuple(Face(f) for f in self.faces))
        if self.opening_sign == 0:
            raise InvalidParameterError(
                f"hinges at joints {j} with faces {[f.value for f in self.faces]} do not form an "
                "admissible mechanism: no sense of motion opens all four joints on their free faces"
            )

    # ------------------------------------------------------------------ geometry
    @cached_property
    def points(self) -> np.ndarray:
        """Hinge points A, B, C, D in the undisplaced arch, m, shape (4, 2)."""
        return np.array([self.arch.joint_point(j, f.value) for j, f in zip(self.joints, self.faces)])

    @cached_property
    def impact_points(self) -> np.ndarray:
        """The opposite ends of the four hinge joints, where the joints close at impact, m, (4, 2)."""
        return np.array(
            [self.arch.joint_point(j, f.opposite.value) for j, f in zip(self.joints, self.faces)]
        )

    @property
    def hinges(self) -> tuple[Hinge, Hinge, Hinge, Hinge]:
        return tuple(
            Hinge(j, f, float(p[0]), float(p[1]))
            for j, f, p in zip(self.joints, self.faces, self.points)
        )  # type: ignore[return-value]

    @cached_property
    def link_voussoirs(self) -> tuple[range, range, range]:
        """Voussoir indices of links AB, BC, CD."""
        a, b, c, d = self.joints
        return (range(a, b), range(b, c), range(c, d))

    @cached_property
    def rates(self) -> np.ndarray:
        """Link angular velocities (AB, BC, CD) per unit phi-dot at phi = 0, rad/rad (CCW +)."""
        return self.opening_sign * link_rates(self.points)

    @cached_property
    def opening_sign(self) -> int:
        """Sense (+1 CCW, -1 CW) of link AB's rotation when the mechanism opens; 0 if none."""
        w = link_rates(self.points)
        if not np.all(np.isfinite(w)):
            return 0
        rel = np.array([w[0], w[1] - w[0], w[2] - w[1], -w[2]])
        need = np.array([f.opening_sign for f in self.faces])
        tol = 1e-12 * np.max(np.abs(rel))
        if np.any(np.abs(rel) <= tol):
            return 0
        if np.all(np.sign(rel) == need):
            return +1
        if np.all(np.sign(rel) == -need):
            return -1
        return 0

    def voussoir_velocities(self) -> tuple[np.ndarray, np.ndarray]:
        """Centroid velocity (n, 2) and angular velocity (n,) of every voussoir per unit
        phi-dot at phi = 0 (zero for voussoirs that stay on the ground)."""
        arch = self.arch
        n = arch.voussoirs
        v = np.zeros((n, 2))
        w = np.zeros(n)
        pivots = (self.points[0], self.points[1], self.points[3])
        # BC's velocity is that of B (on AB) plus its own rotation about B
        vb = self.rates[0] * perp(self.points[1] - self.points[0])
        for link, (rng, pivot) in enumerate(zip(self.link_voussoirs, pivots)):
            for k in rng:
                r = arch.voussoir_centroids[k] - pivot
                v[k] = self.rates[link] * perp(r) + (vb if link == 1 else 0.0)
                w[k] = self.rates[link]
        return v, w

    @cached_property
    def load_direction(self) -> int:
        """+1 if a horizontal load towards +x does positive work as the mechanism opens
        (ground acceleration towards -x drives it, the paper's Figure 1), else -1."""
        v, _ = self.voussoir_velocities()
        work = float(self.arch.voussoir_masses @ v[:, 0])
        return 1 if work > 0 else -1

    @property
    def collapse_acceleration_g(self) -> float:
        """lambda of this mechanism: the horizontal acceleration, in g, at which it is in limit
        equilibrium, by virtual work at phi = 0.

        Gravity does work -g sum(m v_y) and the load lambda g (towards ``load_direction``)
        does lambda g |sum(m v_x)|, so lambda = sum(m v_y) / |sum(m v_x)|.
        """
        v, _ = self.voussoir_velocities()
        m = self.arch.voussoir_masses
        return float((m @ v[:, 1]) / abs(m @ v[:, 0]))

    # ------------------------------------------------------------------ symmetry
    def mirrored(self) -> HingeMechanism:
        """The mirror image in the vertical axis (joint j -> n - j, order reversed, same faces).

        Only for symmetric arches (``arch.symmetric``); an asymmetric chain (blocks from a
        survey) is analysed for each load direction on its own."""
        if not self.arch.symmetric:
            raise InvalidParameterError(
                "the mirror-image mechanism exists only for an arch symmetric about x = 0"
            )
        n = self.arch.voussoirs
        return HingeMechanism(
            self.arch,
            tuple(n - j for j in reversed(self.joints)),  # type: ignore[arg-type]
            tuple(reversed(self.faces)),  # type: ignore[arg-type]
        )

    @property
    def symmetric(self) -> bool:
        """True if the hinges sit at mirror-image joints (the paper's "symmetric mechanism").

        Only the joints are compared: the faces of a mechanism opened by a horizontal load are
        never their own mirror image (the mirror-image faces form the mirror mechanism, which
        the opposite load opens).
        """
        if not self.arch.symmetric:
            return False
        return self.mirrored().joints == self.joints

    def to_dict(self) -> dict:
        return {
            "hinges": [h.to_dict() for h in self.hinges],
            "symmetric": self.symmetric,
            "load_direction": self.load_direction,
        }


__all__ = ["Face", "Hinge", "HingeMechanism"]
