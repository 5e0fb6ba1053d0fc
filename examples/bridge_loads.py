"""A bridge arch with what it carries: fill, backing and a wall, then the traffic it can take.

    python examples/bridge_loads.py            # the example bridge's semicircle, 95 positions
    python examples/bridge_loads.py --quick    # 20 positions (a second)

SI units inside archquake: loads in N per metre of barrel width, lengths in m, densities in
kg/m^3; accelerations named *_g are in g.
"""

from __future__ import annotations

import argparse
import math

from archquake import Arch
from archquake.geometry.loads import Backing, Fill, Loads, PointLoad, Traffic
from archquake.limit import limit_analysis
from archquake.limit.capacity import capacity_scan


def main(quick: bool = False) -> None:
    arch = Arch(radius=5.0, thickness=0.6, embrace=math.pi, voussoirs=15, density=1800.0)
    bare = limit_analysis(arch, method="both")
    loads = Loads(fill=Fill(depth=1.0, density=1800.0), backing=Backing(1.0),
                  point_loads=(PointLoad(position=7.0, load=20e3),))  # a parapet's weight
    loaded = limit_analysis(arch, method="both", loads=loads)
    print(f"bare ring: lambda {bare.collapse_acceleration_g:.4f} g")
    print(f"with fill, backing and the load: lambda {loaded.collapse_acceleration_g:.4f} g "
          f"towards +x, {loaded.opposite_collapse_acceleration_g:.4f} g towards -x; hinges at "
          f"joints {loaded.mechanism.joints}")
    axle = Traffic(load=100e3, dispersion=26.57)  # 100 kN per metre of width, spread at 2:1
    scan = capacity_scan(arch, loads, axle, 20 if quick else 95)
    crit = scan.critical
    print(f"adequacy factor of a 100 kN/m axle: {scan.adequacy_factor:.3f} at "
          f"{crit.traffic.position:.2f} m (collapse load {crit.collapse_load_N_m / 1e3:.1f} kN/m)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer positions along the span")
    main(parser.parse_args().quick)
