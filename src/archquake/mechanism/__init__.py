"""The arch in motion: four-link kinematics, equation of motion, impact and time histories."""

from archquake.mechanism.impact import ImpactSolution, solve_impact
from archquake.mechanism.prepared import ImpactTable, PreparedMechanism
from archquake.mechanism.simulate import (
    FinalState,
    History,
    MechanismEvent,
    Outcome,
    SimulationResult,
    SolverOptions,
    simulate,
)

__all__ = [
    "FinalState",
    "History",
    "ImpactSolution",
    "ImpactTable",
    "MechanismEvent",
    "Outcome",
    "PreparedMechanism",
    "SimulationResult",
    "SolverOptions",
    "simulate",
    "solve_impact",
]
