"""The arch's internal forces during motion: line of thrust (paper Figure 8) and the friction
the joints need not to slide (paper p. 2131)."""

from archquake.thrust.states import MotionState, state_at, states

__all__ = ["MotionState", "state_at", "states"]
