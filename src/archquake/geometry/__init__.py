"""Arch geometry: voussoirs, joints, hinges and four-bar kinematics at an instant."""

from archquake.geometry.arch import MAX_EMBRACE, MAX_VOUSSOIRS, Arch
from archquake.geometry.hinges import Face, Hinge, HingeMechanism

__all__ = ["Arch", "Face", "Hinge", "HingeMechanism", "MAX_EMBRACE", "MAX_VOUSSOIRS"]
