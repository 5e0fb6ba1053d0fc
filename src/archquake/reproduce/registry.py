"""The studies of ``archquake reproduce``, in the paper's order."""

from __future__ import annotations

from archquake.reproduce.core import Study

_A = "archquake.reproduce.analytical"
_N = "archquake.reproduce.numerical"

#: Every study of the paper: (key, title, what of the paper it covers, "module:function").
STUDIES: tuple[Study, ...] = (
    Study(
        "static",
        "Equivalent static analysis",
        "p. 2126 (0.37 g), hinges (Figures 1, 7), p. 2131 (0.50)",
        f"{_A}:static_study",
    ),
    Study(
        "figure4",
        "Time histories (Figure 4)",
        "p. 2126, p. 2132, Figure 4(a)-(d), analytical and DEM",
        f"{_A}:figure4_study",
    ),
    Study(
        "figure5", "Failure domain, step impulse (Figure 5)", "p. 2127, Figure 5", f"{_A}:figure5_study"
    ),
    Study(
        "figure6",
        "Scale effect (Figure 6)",
        "p. 2128, p. 2133, Figure 6(a), (b), analytical and DEM",
        f"{_A}:figure6_study",
    ),
    Study(
        "figure7",
        "Arch geometry (Figure 7)",
        "p. 2128, Figure 7(a), (b); c_v trend p. 2125",
        f"{_A}:figure7_study",
    ),
    Study(
        "figure8",
        "Line of thrust during motion (Figure 8)",
        "p. 2129-2130, Figure 8",
        f"{_A}:figure8_study",
    ),
    Study(
        "friction",
        "Friction to prevent sliding",
        "p. 2131 (0.56, 0.509, 0.50), p. 2134 (DEM 0.55, 0.51)",
        f"{_A}:friction_study",
    ),
    Study(
        "figure9",
        "Hinges in the distinct-element model (Figure 9)",
        "p. 2131-2132, Figure 9",
        f"{_N}:figure9_study",
    ),
    Study(
        "damping",
        "DEM stiffness and damping (Figure 10)",
        "p. 2131, p. 2133-2134, Figure 10",
        f"{_N}:damping_study",
    ),
    Study(
        "figure11",
        "Sine pulse (Figure 11)",
        "p. 2134, Figure 11, analytical and DEM",
        f"{_A}:figure11_study",
    ),
)

__all__ = ["STUDIES"]
