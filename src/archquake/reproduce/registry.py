"""The studies of ``archquake reproduce``, in the paper's order."""

from __future__ import annotations

from archquake.reproduce.core import Study

_M = "archquake.reproduce"

#: Every study of the paper: (key, title, what of the paper it covers, "module:function"); the
#: study ``name`` lives in ``archquake.reproduce.<name>`` and reads the paper's numbers from
#: `archquake.validation.paper`.
STUDIES: tuple[Study, ...] = (
    Study(
        "static",
        "Equivalent static analysis",
        "p. 2126 (0.37 g), hinges (Figures 1, 7), p. 2131 (0.50)",
        f"{_M}.static:study",
    ),
    Study(
        "figure4",
        "Time histories (Figure 4)",
        "p. 2126, p. 2132, Figure 4(a)-(d), four-link and DEM",
        f"{_M}.figure4:study",
    ),
    Study(
        "figure5", "Failure domain, step impulse (Figure 5)", "p. 2127, Figure 5", f"{_M}.figure5:study"
    ),
    Study(
        "figure6",
        "Scale effect (Figure 6)",
        "p. 2128, p. 2133, Figure 6(a), (b), four-link and DEM",
        f"{_M}.figure6:study",
    ),
    Study(
        "figure7",
        "Arch geometry (Figure 7)",
        "p. 2128, Figure 7(a), (b); c_v trend p. 2125",
        f"{_M}.figure7:study",
    ),
    Study(
        "figure8",
        "Line of thrust during motion (Figure 8)",
        "p. 2129-2130, Figure 8",
        f"{_M}.figure8:study",
    ),
    Study(
        "friction",
        "Friction to prevent sliding",
        "p. 2131 (0.56, 0.509, 0.50), p. 2134 (DEM 0.55, 0.51)",
        f"{_M}.friction:study",
    ),
    Study(
        "figure9",
        "Hinges in the distinct-element model (Figure 9)",
        "p. 2131-2132, Figure 9",
        f"{_M}.figure9:study",
    ),
    Study(
        "damping",
        "DEM stiffness and damping (Figure 10)",
        "p. 2131, p. 2133-2134, Figure 10",
        f"{_M}.damping:study",
    ),
    Study(
        "figure11",
        "Sine pulse (Figure 11)",
        "p. 2134, Figure 11, four-link and DEM",
        f"{_M}.figure11:study",
    ),
)

__all__ = ["STUDIES"]
