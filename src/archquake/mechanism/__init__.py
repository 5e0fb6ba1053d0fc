"""The arch in motion: four-link kinematics, equation of motion, impact and time histories."""

from archquake.mechanism.impact import ImpactSolution, solve_impact
from archquake.mechanism.simulate import (
    FinalState,
    History,
    Outcome,
    PreparedMechanism,
    SimulationResult,
    SolverOptions,
    default_mechanism,
    simulate,
)

__all__ = [
    "FinalState",
    "History",
    "ImpactSolution",
    "Outcome",
    "PreparedMechanism",
    "SimulationResult",
    "SolverOptions",
    "default_mechanism",
    "simulate",
    "solve_impact",
]
