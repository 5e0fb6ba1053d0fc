"""What the two block models stand on: the distinct-element model (`archquake.dem`) and the
chain of rigid voussoirs (`archquake.rigid`).

Template -> model -> analysis: `build_arch_assembly` / `block_on_base` build an `Assembly`
(blocks, joints, the rotation link the verdict is read on); either model runs it and hands
its samples to `BlockResult.from_samples`, which classifies them by the thresholds of a
`BlockCriteria` (hinge opening, collapse rotation and drop) in the four-link model's
vocabulary (`Outcome`, impacts, half cycles, ``to_dict()`` keys). `default_window` is the
default length of a block model's run.
"""

from archquake.blocks.assembly import (
    Assembly,
    Joint,
    RotationLink,
    block_on_base,
    build_arch_assembly,
)
from archquake.blocks.criteria import (
    DEFAULT_TAIL,
    BlockCriteria,
    BlockRunSettings,
    default_window,
)
from archquake.blocks.result import BlockResult

__all__ = [
    "Assembly",
    "BlockCriteria",
    "BlockResult",
    "BlockRunSettings",
    "DEFAULT_TAIL",
    "Joint",
    "RotationLink",
    "block_on_base",
    "build_arch_assembly",
    "default_window",
]
