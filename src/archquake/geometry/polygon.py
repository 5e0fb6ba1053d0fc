"""Mass properties of uniform planar polygons (the one home of the shoelace formulas).

A block of masonry of out-of-plane ``depth`` (m) and ``density`` (kg/m^3) whose cross-section
is a simple polygon. Curved faces are sampled densely enough that the polygon's properties
equal the curved block's to the precision the caller needs (see
`archquake.geometry.shapes`).
"""

from __future__ import annotations

import numpy as np


def polygon_area(p: np.ndarray) -> float:
    """Signed area of a polygon, m^2 (positive when counter-clockwise). ``p``: (m, 2), m."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def polygon_mass_properties(
    p: np.ndarray, density: float, depth: float
) -> tuple[float, np.ndarray, float]:
    """Mass, centroid and centroidal mass moment of inertia of a uniform polygon.

    The shoelace formulas (Green's theorem) for the area A, first moments and polar second
    moment J_o of the region, evaluated about the mean vertex (so that blocks far from the
    origin lose no digits to the parallel-axis subtraction J_c = J_o - A |c|^2).

    Parameters
    ----------
    p : ndarray, shape (m, 2)
        Vertices, m, counter-clockwise, not repeating the first.
    density : float
        kg/m^3.
    depth : float
        Out-of-plane depth, m.

    Returns
    -------
    mass : float
        kg.
    centroid : ndarray, shape (2,)
        m.
    inertia : float
        About the centroid, out of plane, kg m^2.

    Examples
    --------
    A 2 m x 1 m rectangle of unit density and depth: m = 2, I = m (a^2 + b^2) / 12.

    >>> m, c, i = polygon_mass_properties(np.array([[0, 0], [2, 0], [2, 1], [0, 1.0]]), 1.0, 1.0)
    >>> m, c.tolist(), round(i, 12)
    (2.0, [1.0, 0.5], 0.833333333333)
    """
    p = np.asarray(p, dtype=float)
    ref = p.mean(axis=0)
    q = p - ref
    x, y = q[:, 0], q[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    area = 0.5 * cr.sum()
    cx = ((x + x1) * cr).sum() / (6 * area)
    cy = ((y + y1) * cr).sum() / (6 * area)
    jo = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * cr).sum() / 12.0
    rho = density * depth
    return float(rho * area), np.array([cx, cy]) + ref, float(rho * (jo - area * (cx * cx + cy * cy)))


__all__ = ["polygon_area", "polygon_mass_properties"]
