"""archquake.plotting: the only package that imports matplotlib.

Plot functions take a result and an optional ``ax``, draw into it (a new figure if None) and
return it; they never call ``show()`` and never choose a backend, so importing this package in a
notebook leaves its backend alone. Functions that write a file go through the one helper
`archquake.plotting.figures.save`.
"""

import sys
from typing import TYPE_CHECKING

from archquake._lazy import attach

#: The figures a user draws (each takes a result and an optional ``ax`` and returns it), the
#: animations and the one saver; their modules (and matplotlib) load on first access.
_LAZY: dict[str, str] = {
    **{name: "archquake.plotting.arch" for name in ("plot_arch", "plot_limit_analysis",
                                                     "plot_shapes")},
    "plot_code_check": "archquake.plotting.codecheck",
    **{name: "archquake.plotting.compare" for name in ("plot_domain_comparison",
                                                        "plot_hinge_sets",
                                                        "plot_history_comparison")},
    **{name: "archquake.plotting.dem" for name in ("animate_dem", "plot_dem_rotation",
                                                    "plot_dem_snapshot", "plot_dem_snapshots")},
    **{name: "archquake.plotting.domains" for name in ("plot_domain", "plot_domains",
                                                        "plot_scaling")},
    "save": "archquake.plotting.figures",
    **{name: "archquake.plotting.history" for name in ("animate_history", "plot_ground_motion",
                                                        "plot_history")},
    **{name: "archquake.plotting.ida" for name in ("plot_fragility", "plot_ida_curves")},
    **{name: "archquake.plotting.spectra" for name in ("plot_elastic_spectrum",
                                                        "plot_record_spectra",
                                                        "plot_selection")},
    "plot_motion_state": "archquake.plotting.thrust",
}

if TYPE_CHECKING:  # pragma: no cover - what the lazy names resolve to, for type checkers
    from archquake.plotting.arch import plot_arch, plot_limit_analysis, plot_shapes
    from archquake.plotting.codecheck import plot_code_check
    from archquake.plotting.compare import (
        plot_domain_comparison,
        plot_hinge_sets,
        plot_history_comparison,
    )
    from archquake.plotting.dem import (
        animate_dem,
        plot_dem_rotation,
        plot_dem_snapshot,
        plot_dem_snapshots,
    )
    from archquake.plotting.domains import plot_domain, plot_domains, plot_scaling
    from archquake.plotting.figures import save
    from archquake.plotting.history import animate_history, plot_ground_motion, plot_history
    from archquake.plotting.ida import plot_fragility, plot_ida_curves
    from archquake.plotting.spectra import (
        plot_elastic_spectrum,
        plot_record_spectra,
        plot_selection,
    )
    from archquake.plotting.thrust import plot_motion_state

__getattr__, __dir__ = attach(sys.modules[__name__], _LAZY)

__all__ = [
    "animate_dem",
    "animate_history",
    "plot_arch",
    "plot_code_check",
    "plot_dem_rotation",
    "plot_dem_snapshot",
    "plot_dem_snapshots",
    "plot_domain",
    "plot_domain_comparison",
    "plot_domains",
    "plot_elastic_spectrum",
    "plot_fragility",
    "plot_ground_motion",
    "plot_hinge_sets",
    "plot_history",
    "plot_history_comparison",
    "plot_ida_curves",
    "plot_limit_analysis",
    "plot_motion_state",
    "plot_record_spectra",
    "plot_scaling",
    "plot_selection",
    "plot_shapes",
    "save",
]
