"""Part-circular voussoir arches: exact annular-sector geometry and mass properties.

Coordinates (SI, metres): origin at the centre O of the centreline circle, x to the right,
y up. The arch is symmetric about the y axis. Joints are radial and numbered from the left
springing (joint 0) to the right springing (joint n); voussoir k lies between joints k and k+1.
Joint j sits at the polar angle (counter-clockwise from +x)

    alpha_j = pi/2 + embrace/2 - j * embrace/n.

Intrados radius R - t/2, extrados radius R + t/2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from archquake._validate import require_positive
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.checks import (  # noqa: F401  (the ranges are re-exported here)
    MAX_DENSITY,
    MAX_DEPTH,
    MAX_EMBRACE,
    MAX_EMBRACE_DEG,
    MAX_VOUSSOIRS,
    MIN_DENSITY,
    MIN_DEPTH,
    MIN_EMBRACE,
    MIN_EMBRACE_DEG,
    MIN_THICKNESS_RATIO,
    RADIUS_RANGE,
    check_density,
    check_depth,
    check_embrace,
    check_radius,
    check_thickness,
    check_voussoirs,
)


@dataclass(frozen=True)
class Arch(VoussoirChain):
    """A symmetric part-circular arch of ``voussoirs`` equal voussoirs with radial joints.

    The circular builder of the voussoir chain (`
    VoussoirChain`), with closed-form annular-sector mass properties; its characteristic
    length is its radius R.

    Parameters
    ----------
    radius : float
        Centreline radius R, m (> 0).
    thickness : float
        Radial thickness t, m (1e-6 R <= t < 2R).
    embrace : float
        Angle of embrace beta, rad (1e-3 deg <= beta <= 240 deg), symmetric about the vertical
        axis.
    voussoirs : int
        Number of voussoirs n (>= 3).
    depth : float, optional
        Out-of-plane depth, m (default 1 m).
    density : float, optional
        Mass density, kg/m^3 (default 2000 kg/m^3, the paper's value).

    Examples
    --------
    Oppenheim's arch (t/R = 0.15, beta = 157.5 deg, R = 10 m, 7 voussoirs):

    >>> import math
    >>> arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
    >>> round(arch.thickness_ratio, 3), round(arch.span, 3)
    (0.15, 19.616)
    >>> round(float(arch.voussoir_masses.sum()), 1)  # kg: rho * depth * beta * R * t
    82466.8
    """

    radius: float
    thickness: float
    embrace: float
    voussoirs: int
    depth: float = 1.0
    density: float = 2000.0

    def __post_init__(self) -> None:
        r = check_radius(self.radius)
        check_thickness(self.thickness, r)
        check_embrace(self.embrace)
        check_voussoirs(self.voussoirs)
        check_depth(self.depth)
        check_density(self.density)
        # store plain Python numbers so that the dataclass hashes and pickles predictably
        for name in ("radius", "thickness", "embrace", "depth", "density"):
            object.__setattr__(self, name, float(getattr(self, name)))
        object.__setattr__(self, "voussoirs", int(self.voussoirs))

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_ratio(
        cls,
        thickness_ratio: float,
        embrace: float,
        voussoirs: int,
        *,
        radius: float = 1.0,
        depth: float = 1.0,
        density: float = 2000.0,
    ) -> Arch:
        """Build from t/R (dimensionless) and R (m)."""
        require_positive("thickness ratio t/R", thickness_ratio)
        return cls(radius, thickness_ratio * radius, embrace, voussoirs, depth, density)

    def scaled(self, factor: float) -> Arch:
        """The geometrically similar arch with every length multiplied by ``factor``."""
        require_positive("scale factor", factor)
        return Arch(
            self.radius * factor,
            self.thickness * factor,
            self.embrace,
            self.voussoirs,
            self.depth * factor,
            self.density,
        )

    # ------------------------------------------------------------------ scalars
    @property
    def thickness_ratio(self) -> float:
        """t/R, dimensionless."""
        return self.thickness / self.radius

    @property
    def intrados_radius(self) -> float:
        """R - t/2, m."""
        return self.radius - 0.5 * self.thickness

    @property
    def extrados_radius(self) -> float:
        """R + t/2, m."""
        return self.radius + 0.5 * self.thickness

    @property
    def voussoir_angle(self) -> float:
        """Angle subtended by one voussoir, rad."""
        return self.embrace / self.voussoirs

    @property
    def span(self) -> float:
        """Centreline span between the springings, m (the chord; for beta > 180 deg the
        widest centreline width is 2R)."""
        return 2.0 * self.radius * math.sin(0.5 * self.embrace)

    @property
    def rise(self) -> float:
        """Centreline rise from the springings to the crown, m."""
        return self.radius * (1.0 - math.cos(0.5 * self.embrace))

    @property
    def springing_y(self) -> float:
        """y of the springings' centreline points, m (negative when beta > 180 deg)."""
        return self.radius * math.cos(0.5 * self.embrace)

    @property
    def mass(self) -> float:
        """Total mass, kg."""
        return float(self.voussoir_masses.sum())

    # ------------------------------------------------------------------ joints
    @cached_property
    def joint_angles(self) -> np.ndarray:
        """Polar angles alpha_j of the n+1 joints, rad, shape (n+1,), decreasing left to right."""
        j = np.arange(self.voussoirs + 1, dtype=float)
        return 0.5 * math.pi + 0.5 * self.embrace - j * self.voussoir_angle

    @cached_property
    def intrados_points(self) -> np.ndarray:
        """Intrados end of each joint, m, shape (n+1, 2)."""
        a = self.joint_angles
        return self.intrados_radius * np.column_stack([np.cos(a), np.sin(a)])

    @cached_property
    def extrados_points(self) -> np.ndarray:
        """Extrados end of each joint, m, shape (n+1, 2)."""
        a = self.joint_angles
        return self.extrados_radius * np.column_stack([np.cos(a), np.sin(a)])

    # ------------------------------------------------------------------ voussoirs
    @cached_property
    def voussoir_mid_angles(self) -> np.ndarray:
        """Polar angle of each voussoir's bisector, rad, shape (n,)."""
        a = self.joint_angles
        return 0.5 * (a[:-1] + a[1:])

    @cached_property
    def voussoir_area(self) -> float:
        """Area of one voussoir (annular sector), m^2: (beta/n) * R * t exactly."""
        return self.voussoir_angle * self.radius * self.thickness

    @cached_property
    def centroid_radius(self) -> float:
        """Distance from O to each voussoir's centroid, m (annular sector, exact)."""
        ri, ro = self.intrados_radius, self.extrados_radius
        h = 0.5 * self.voussoir_angle
        # (ro^3 - ri^3) / (ro^2 - ri^2) without the cancellation that ruins very thin arches
        return 2.0 * math.sin(h) * (ro * ro + ro * ri + ri * ri) / (3.0 * h * (ro + ri))

    @cached_property
    def voussoir_masses(self) -> np.ndarray:
        """Mass of each voussoir, kg, shape (n,)."""
        m = self.density * self.depth * self.voussoir_area
        return np.full(self.voussoirs, m)

    @cached_property
    def voussoir_centroids(self) -> np.ndarray:
        """Centroid of each voussoir, m, shape (n, 2)."""
        a = self.voussoir_mid_angles
        return self.centroid_radius * np.column_stack([np.cos(a), np.sin(a)])

    @cached_property
    def voussoir_inertias(self) -> np.ndarray:
        """Mass moment of inertia of each voussoir about its own centroid, kg m^2, shape (n,)."""
        ri, ro = self.intrados_radius, self.extrados_radius
        h = 0.5 * self.voussoir_angle
        polar_about_o = h * (ro**4 - ri**4) / 2.0  # m^4, area polar moment about O
        area_term = polar_about_o - self.voussoir_area * self.centroid_radius**2
        return np.full(self.voussoirs, self.density * self.depth * area_term)

    def voussoir_outline(self, k: int, arc_points: int = 8) -> np.ndarray:
        """Closed outline of voussoir k (intrados arc, then extrados arc back), m, shape (2*arc_points, 2).

        Counter-clockwise. Arcs are sampled with ``arc_points`` points each; used for drawing.
        """
        a0, a1 = self.joint_angles[k], self.joint_angles[k + 1]
        ang = np.linspace(a1, a0, arc_points)
        inner = self.intrados_radius * np.column_stack([np.cos(ang), np.sin(ang)])
        outer = self.extrados_radius * np.column_stack([np.cos(ang[::-1]), np.sin(ang[::-1])])
        return np.vstack([inner, outer])

    def voussoir_polygon(self, k: int) -> np.ndarray:
        """Voussoir k as the quadrilateral of its four joint end points, m, shape (4, 2),
        counter-clockwise: intrados right, extrados right, extrados left, intrados left."""
        return np.array(
            [
                self.intrados_points[k + 1],
                self.extrados_points[k + 1],
                self.extrados_points[k],
                self.intrados_points[k],
            ]
        )

    def _build_layout(self) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
        """The joints' ends and the voussoir outlines, from the closed forms (the properties
        below override the base class's readers of this layout with the same values)."""
        return (np.stack([self.intrados_points, self.extrados_points], axis=1),
                self.block_polygons)

    @property
    def block_polygons(self) -> tuple[np.ndarray, ...]:
        """Outline of every voussoir, its arcs sampled every ~0.05 degrees (drawing, tiling
        checks and the pier courses; the mass properties are the closed forms), m."""
        per = max(2, int(math.ceil(math.degrees(self.voussoir_angle) / 0.05)) + 1)
        return tuple(self.voussoir_outline(k, per)[::-1] for k in range(self.voussoirs))  # CCW

    @property
    def crown_point(self) -> np.ndarray:
        """The crown of the extrados, (0, R + t/2), m."""
        return np.array([0.0, self.extrados_radius])

    def with_thickness(self, thickness: float) -> Arch:
        """The same arch with ring thickness ``thickness``, m."""
        return Arch(self.radius, thickness, self.embrace, self.voussoirs, self.depth, self.density)

    def describe(self) -> dict:
        """Plain dict of the inputs in SI (and degrees for the embrace), for JSON output."""
        return {
            "radius_m": self.radius,
            "thickness_m": self.thickness,
            "thickness_ratio": self.thickness_ratio,
            "embrace_deg": math.degrees(self.embrace),
            "voussoirs": self.voussoirs,
            "depth_m": self.depth,
            "density_kg_m3": self.density,
        }


__all__ = ["Arch", "MAX_DENSITY", "MAX_DEPTH", "MAX_EMBRACE", "MAX_EMBRACE_DEG", "MAX_VOUSSOIRS",
           "MIN_DENSITY", "MIN_EMBRACE", "MIN_EMBRACE_DEG", "MIN_DEPTH", "MIN_THICKNESS_RATIO",
           "RADIUS_RANGE"]
