"""Equivalent static (limit) analysis: collapse acceleration, hinges, line of thrust, friction
demand and minimum thickness (Heyman's rigid no-tension voussoirs; paper p. 2120, 2126, 2131).

The statics of a voussoir chain in any configuration (`joint_forces`) lives here too, so
the line of thrust during motion reuses it, and so does the least-friction admissible line of
thrust of the locked arch (`locked_joint_forces`).
"""

from archquake.limit.analysis import (
    LimitAnalysis,
    Method,
    collapse_joint_forces,
    coupled_vertical_analysis,
    hinges_of,
    limit_analysis,
)
from archquake.limit.kinematic import (
    MAX_KINEMATIC_VOUSSOIRS,
    kinematic_collapse,
    mechanism_multipliers,
)
from archquake.limit.locked import locked_joint_forces
from archquake.limit.static import (
    collapse_state,
    geometric_safety_factor,
    min_thickness,
    min_thickness_ratio,
    stands,
    static_collapse,
)
from archquake.limit.thrust import (
    JointForces,
    arch_joint_points,
    joint_forces,
    joint_frames,
    moments_about_origin,
)

__all__ = [
    "hinges_of",
    "JointForces",
    "LimitAnalysis",
    "MAX_KINEMATIC_VOUSSOIRS",
    "Method",
    "arch_joint_points",
    "collapse_joint_forces",
    "collapse_state",
    "geometric_safety_factor",
    "min_thickness",
    "joint_forces",
    "joint_frames",
    "kinematic_collapse",
    "coupled_vertical_analysis",
    "limit_analysis",
    "locked_joint_forces",
    "mechanism_multipliers",
    "min_thickness_ratio",
    "moments_about_origin",
    "stands",
    "static_collapse",
]
