"""The arch of a case in study units (lengths in m, angles in degrees): what a study file, a
survey file or an API call describes, checked when built (`archquake.geometry.checks`)
and turned into an arch, in SI, by `ArchSpec.build`.

Its canonical form (`ArchSpec.canonical`) is the arch's part of a sweep case's id
(`archquake.sweeps.cases`).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from archquake._json import canonical_json
from archquake._validate import require_positive
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.checks import (  # the one place where an arch is checked
    MAX_VOUSSOIRS,
    MIN_VOUSSOIRS,
    check_density,
    check_depth,
    check_embrace_deg,
    check_joints,
    check_pier_courses,
    check_pier_values,
    check_piers,
    check_radius,
    check_shape,
    check_thickness_ratio,
    check_voussoirs,
)


@dataclass(frozen=True)
class ArchSpec:
    """The arch of a case, in study units: a circular arch by radius, t/R and embrace (the
    paper's), or any shape by span, rise and thickness (`archquake.geometry.shapes`), with
    optional piers.

    Parameters
    ----------
    radius : float, optional
        Circular arch: centreline radius R, m (1e-3 to 1e4).
    thickness_ratio : float, optional
        Circular arch: t/R, dimensionless (0 < t/R < 2).
    embrace_deg : float, optional
        Circular arch: angle of embrace, degrees (0 < embrace <= 240).
    voussoirs : int
        Number of voussoirs (3 to 2000).
    depth : float
        Out-of-plane depth, m (0 < depth <= 1e4; default 1).
    density : float
        Density, kg/m^3 (0 < density <= 1e5; default 2000).
    shape : str
        One of `archquake.geometry.SHAPES` (default "circular").
    span, rise, thickness : float, optional
        Any shape: centreline span and rise, ring thickness, m (instead of radius, t/R and
        embrace).
    joints : str
        "radial" (default) or "vertical".
    pier_height, pier_width : float, optional
        Piers under the springings, m (both or neither).
    pier_courses : int
        Courses in each pier (default 1).
    blocks : str, optional
        A surveyed arch instead of a shape: the path of a .json, .csv or .dxf block file
        (`archquake.geometry.survey.read_blocks`, the one reader), with only ``depth`` and
        ``density`` beside it. It enters the case id through the file's name and the SHA-256 of
        its bytes (``blocks_sha256``), not its directory, as a record file does.
    blocks_sha256 : str, optional
        SHA-256 of the block file's bytes; computed from ``blocks`` when omitted.

    Examples
    --------
    >>> spec = ArchSpec(10, 0.15, 157.5, 7)
    >>> round(spec.build().thickness, 3)
    1.5
    >>> ArchSpec(voussoirs=15, shape="pointed", span=10, rise=7, thickness=0.8).build().describe()["shape"]
    'pointed'
    """

    radius: float | None = None
    thickness_ratio: float | None = None
    embrace_deg: float | None = None
    voussoirs: int | None = None
    depth: float = 1.0
    density: float = 2000.0
    shape: str = "circular"
    span: float | None = None
    rise: float | None = None
    thickness: float | None = None
    joints: str = "radial"
    pier_height: float | None = None
    pier_width: float | None = None
    pier_courses: int = 1
    blocks: str | None = None
    blocks_sha256: str | None = field(default=None, compare=False)

    #: Keys that describe a shape, which a block file replaces.
    SHAPE_KEYS = ("radius", "thickness_ratio", "embrace_deg", "voussoirs", "span", "rise",
                  "thickness", "pier_height", "pier_width")

    def __post_init__(self) -> None:
        if self.blocks is not None:
            self._check_blocks()
            return
        if self.voussoirs is None:
            raise InvalidParameterError(f"voussoirs is required ({MIN_VOUSSOIRS} to "
                                        f"{MAX_VOUSSOIRS})")
        shape = check_shape(self.shape)
        check_joints(self.joints)
        _set(self, "shape", shape)
        by_radius = (self.radius, self.thickness_ratio, self.embrace_deg)
        by_span = (self.span, self.rise, self.thickness)
        if shape == "circular" and all(v is not None for v in by_radius) and all(
                v is None for v in by_span):
            _set(self, "radius", check_radius(self.radius))
            _set(self, "thickness_ratio", check_thickness_ratio(self.thickness_ratio))
            _set(self, "embrace_deg", check_embrace_deg(self.embrace_deg))
        elif all(v is not None for v in by_span) and all(v is None for v in by_radius):
            for name in ("span", "rise", "thickness"):
                _set(self, name, require_positive(name, getattr(self, name), "m"))
        else:
            raise InvalidParameterError(
                "an arch needs radius, thickness_ratio and embrace_deg (circular), or span, rise "
                "and thickness (any shape), not a mixture")
        _set(self, "voussoirs", check_voussoirs(self.voussoirs))
        _set(self, "depth", check_depth(self.depth))
        _set(self, "density", check_density(self.density))
        if check_piers(self.pier_height, self.pier_width):
            height, width, courses = check_pier_values(self.pier_height, self.pier_width,
                                                       self.pier_courses)
            _set(self, "pier_height", height)
            _set(self, "pier_width", width)
        else:
            courses = check_pier_courses(self.pier_courses)
        _set(self, "pier_courses", courses)

    def _check_blocks(self) -> None:
        """A block file: no shape keys beside it (one line naming them), depth and density in
        range, the file's SHA-256 taken once."""
        if not isinstance(self.blocks, str) or not self.blocks:
            raise InvalidParameterError("blocks must be the path of a .json, .csv or .dxf file")
        mixed = [k for k in self.SHAPE_KEYS if getattr(self, k) is not None]
        mixed += [k for k, default in (("shape", "circular"), ("joints", "radial"),
                                       ("pier_courses", 1)) if getattr(self, k) != default]
        if mixed:
            raise InvalidParameterError(f"blocks (a surveyed arch) does not go with the shape "
                                        f"keys {', '.join(mixed)}: give the block file or a "
                                        "shape, not both")
        _set(self, "depth", check_depth(self.depth))
        _set(self, "density", check_density(self.density))
        if self.blocks_sha256 is None:
            try:
                digest = hashlib.sha256(Path(self.blocks).read_bytes()).hexdigest()
            except OSError as exc:
                raise InvalidParameterError(f"blocks: cannot read {self.blocks!r} "
                                            f"({exc.strerror})") from None
            _set(self, "blocks_sha256", digest)

    @property
    def _circular_by_radius(self) -> bool:
        return self.radius is not None

    def build(self):
        """The arch (`Arch` for the paper's circular arch, else the
        shape's `VoussoirChain`; SI, embrace in rad)."""
        from archquake.geometry import OnPiers, Piers
        from archquake.geometry.shapes import circular, shaped

        arch: VoussoirChain
        if self.blocks is not None:
            from archquake.geometry.survey import read_blocks

            return read_blocks(self.blocks, depth=self.depth, density=self.density)
        if self._circular_by_radius:
            assert (self.radius is not None and self.thickness_ratio is not None  # __post_init__
                    and self.embrace_deg is not None and self.voussoirs is not None)
            if self.joints == "radial":
                arch = Arch.from_ratio(self.thickness_ratio, math.radians(self.embrace_deg),
                                       self.voussoirs, radius=self.radius, depth=self.depth,
                                       density=self.density)
            else:
                arch = circular(radius=self.radius, embrace=math.radians(self.embrace_deg),
                                thickness=self.thickness_ratio * self.radius,
                                voussoirs=self.voussoirs, joints=self.joints, depth=self.depth,
                                density=self.density)
        else:
            arch = shaped(self.shape, span=self.span, rise=self.rise, thickness=self.thickness,
                          voussoirs=self.voussoirs, joints=self.joints, depth=self.depth,
                          density=self.density)
        if self.pier_height is not None:
            assert self.pier_width is not None  # __post_init__: both or neither
            arch = OnPiers(arch, Piers(self.pier_height, self.pier_width, self.pier_courses))
        return arch

    def canonical(self) -> dict[str, Any]:
        """The inputs as a dict: exactly the paper's keys for a circular arch by radius with
        radial joints and no piers (so the case ids of existing studies never change), and the
        shape's keys otherwise."""
        out: dict[str, Any]
        if self.blocks is not None:
            return {"blocks": Path(self.blocks).name, "blocks_sha256": self.blocks_sha256,
                    "depth_m": self.depth, "density_kg_m3": self.density}
        if self._circular_by_radius:
            out = {"radius_m": self.radius, "thickness_ratio": self.thickness_ratio,
                   "embrace_deg": self.embrace_deg, "voussoirs": self.voussoirs,
                   "depth_m": self.depth, "density_kg_m3": self.density}
        else:
            out = {"shape": self.shape, "span_m": self.span, "rise_m": self.rise,
                   "thickness_m": self.thickness, "voussoirs": self.voussoirs,
                   "depth_m": self.depth, "density_kg_m3": self.density}
        if self.joints != "radial":
            out["joints"] = self.joints
        if self.pier_height is not None:
            out.update(pier_height_m=self.pier_height, pier_width_m=self.pier_width,
                       pier_courses=self.pier_courses)
        return out

    @cached_property
    def canonical_json(self) -> str:
        """`canonical_json` of `canonical` (computed once per spec: a grid shares
        its specs across many cases)."""
        return canonical_json(self.canonical())

    def columns(self) -> dict[str, Any]:
        """Flat columns for the store: the canonical inputs plus the thickness in m."""
        cols = self.canonical()
        if self._circular_by_radius:
            assert self.thickness_ratio is not None and self.radius is not None
            cols["thickness_m"] = self.thickness_ratio * self.radius
        return cols


def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


__all__ = ["ArchSpec"]
