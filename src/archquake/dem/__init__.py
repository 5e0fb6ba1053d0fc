"""Distinct-element model: rigid polygonal blocks on deformable, frictional, no-tension
contacts, explicit central-difference time stepping with Rayleigh damping (in the spirit of
UDEC as used by De Lorenzis, DeJong & Ochsendorf 2007).

Template -> model -> contacts -> analysis: `build_arch_assembly` /
`block_on_base` build an `Assembly` (`archquake.blocks.assembly`, shared with the rigid
chain); `simulate_dem` runs it under any ground motion and returns a frozen
`archquake.blocks.BlockResult`, which speaks the four-link model's vocabulary (`Outcome`,
impacts, half cycles, ``to_dict()`` keys). ``DemResult`` is the same class under its former
name, kept for one release.
"""

from archquake.blocks.assembly import Assembly, Joint, RotationLink, block_on_base, build_arch_assembly
from archquake.blocks.result import BlockResult
from archquake.dem.run import simulate_dem, stable_time_step
from archquake.dem.settings import NO_SLIDING, ContactLaw, DemSettings

#: The result of `simulate_dem`: `archquake.blocks.BlockResult` under its former name (kept for
#: one release).
DemResult = BlockResult

__all__ = [
    "Assembly",
    "ContactLaw",
    "DemResult",
    "DemSettings",
    "Joint",
    "NO_SLIDING",
    "RotationLink",
    "block_on_base",
    "build_arch_assembly",
    "simulate_dem",
    "stable_time_step",
]
