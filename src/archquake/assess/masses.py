"""The masses an assessment reports: the masonry's and what its blocks carry."""

from __future__ import annotations

import numpy as np


def carried_masses(arch, loads) -> dict:
    """The masses the models move, kg: the masonry's, and what its blocks carry (the fill
    columns, the loads on the extrados that move with the arch), from
    `block_extras`; the blocks the backing holds (numbered
    from 1) belong to the support. ``loads`` None: the bare arch."""
    from archquake.geometry.loads import Loads, block_extras

    masonry = float(np.sum(arch.voussoir_masses))
    if loads is None:
        return {"masonry_mass_kg": masonry, "fill_mass_kg": 0.0, "superimposed_mass_kg": 0.0,
                "carried_mass_kg": 0.0, "held_blocks": []}
    extras = block_extras(arch, loads)
    fill = (0.0 if loads.fill is None else
            float(block_extras(arch, Loads(fill=loads.fill, backing=loads.backing)).mass.sum()))
    carried = float(extras.mass.sum())
    held = np.asarray(extras.held, dtype=bool)
    blocks = [int(k) + 1 for k in np.flatnonzero(held[:-1] & held[1:])]  # both joints held
    still = np.zeros(arch.voussoirs, dtype=bool)
    still[[b - 1 for b in blocks]] = True
    return {"masonry_mass_kg": masonry, "fill_mass_kg": fill,
            "superimposed_mass_kg": carried - fill, "carried_mass_kg": carried,
            "held_joints": [int(j) for j in np.flatnonzero(held)], "held_blocks": blocks,
            "held_mass_kg": float(np.sum(np.asarray(arch.voussoir_masses)[still])
                                  + np.sum(extras.mass[still]))}


__all__ = ["carried_masses"]
