"""An arch whose voussoirs carry their loads: the same joints and outlines, each voussoir's mass
properties with its fill column and moving loads added, for the analyses that read an arch's
blocks as masses (the four-link model, its impacts).

Each voussoir's mass is its own plus what it carries that moves with the arch
(`block_extras`), at the combined centroid, with the rotational
inertia about it by the parallel-axis theorem. Loads whose mass does not move (``still``),
traffic and passive fill pressure are not masses, so a carrying chain refuses them.

Examples
--------
>>> import math
>>> from archquake.geometry.arch import Arch
>>> from archquake.geometry.loads import Fill, Loads
>>> arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
>>> chain = CarryingChain(arch, Loads(fill=Fill(depth=1.0, density=1800.0)))
>>> round(chain.mass - arch.mass, 1)   # the fill between the extrados and the surface
40781.4
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from archquake.errors import InvalidParameterError
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.loads import Loads, block_extras


@dataclass(frozen=True, eq=True)
class CarryingChain(VoussoirChain):
    """``base`` with the masses of ``loads`` on its voussoirs (module docstring).

    Parameters
    ----------
    base : VoussoirChain
        The bare arch (its geometry is this chain's).
    loads : Loads
        What it carries: a fill, a backing, point and distributed loads whose mass moves.
    """

    base: VoussoirChain
    loads: Loads

    def __post_init__(self) -> None:
        if not isinstance(self.base, VoussoirChain) or isinstance(self.base, CarryingChain):
            raise InvalidParameterError("a carrying chain needs a bare arch")
        if not isinstance(self.loads, Loads):
            raise InvalidParameterError("loads must be a Loads")
        if any(not p.moves_with_arch for p in self.loads.point_loads) or any(
                not d.moves_with_arch for d in self.loads.distributed_loads):
            raise InvalidParameterError(
                "loads marked 'still' (weight without mass) are statics only: the dynamic models "
                "carry loads whose mass moves with the arch")
        if self.loads.traffic is not None or self.loads.passive is not None:
            raise InvalidParameterError("traffic and passive fill pressure are statics only")

    # the bare arch's geometry and scalars
    @property
    def voussoirs(self) -> int:  # type: ignore[override]
        return self.base.voussoirs

    @property
    def thickness(self) -> float:  # type: ignore[override]
        return self.base.thickness

    @property
    def depth(self) -> float:  # type: ignore[override]
        return self.base.depth

    @property
    def density(self) -> float:  # type: ignore[override]
        return self.base.density

    @property
    def radius(self) -> float:
        return self.base.radius

    @property
    def embrace(self) -> float:
        return self.base.embrace

    def _build_layout(self) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        return self.base._layout

    def describe(self) -> dict:
        return {**self.base.describe(), "loads": self.loads.to_dict(),
                "carried_mass_kg": float(np.sum(self._carried[0]))}

    def scaled(self, factor: float) -> VoussoirChain:
        raise InvalidParameterError("a carrying chain is not scaled: scale the arch and its loads")

    # the voussoirs with what they carry
    @cached_property
    def _carried(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        ex = block_extras(self.base, self.loads)
        return ex.mass, ex.centroid, ex.inertia

    @cached_property
    def voussoir_masses(self) -> np.ndarray:
        """Each voussoir's mass with what it carries, kg."""
        return self.base.voussoir_masses + self._carried[0]

    @cached_property
    def voussoir_centroids(self) -> np.ndarray:
        """Their combined centroids, m."""
        vm, vc = self.base.voussoir_masses, self.base.voussoir_centroids
        em, ec, _ = self._carried
        return (vm[:, None] * vc + em[:, None] * ec) / self.voussoir_masses[:, None]

    @cached_property
    def voussoir_inertias(self) -> np.ndarray:
        """Rotational inertias about the combined centroids (parallel-axis), kg m^2."""
        vm, vc, vi = (self.base.voussoir_masses, self.base.voussoir_centroids,
                      self.base.voussoir_inertias)
        em, ec, ei = self._carried
        c = self.voussoir_centroids
        return (vi + vm * np.sum((vc - c) ** 2, axis=1)
                + ei + em * np.sum((ec - c) ** 2, axis=1))


__all__ = ["CarryingChain"]
