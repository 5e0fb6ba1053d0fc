"""Arch geometry: the voussoir chain (one description of every arch), its builders, hinges and
four-bar kinematics at an instant."""

from archquake.geometry.arch import MAX_EMBRACE, MAX_VOUSSOIRS, Arch
from archquake.geometry.chain import BlockChain, OnPiers, Piers, VoussoirChain, check_tiling
from archquake.geometry.hinges import Face, Hinge, HingeMechanism
from archquake.geometry.shapes import JOINTS, SHAPES, ShapedArch, circular, pointed, segmental, shaped

__all__ = [
    "Arch",
    "BlockChain",
    "Face",
    "Hinge",
    "HingeMechanism",
    "JOINTS",
    "MAX_EMBRACE",
    "MAX_VOUSSOIRS",
    "OnPiers",
    "Piers",
    "SHAPES",
    "ShapedArch",
    "VoussoirChain",
    "check_tiling",
    "circular",
    "pointed",
    "segmental",
    "shaped",
]
