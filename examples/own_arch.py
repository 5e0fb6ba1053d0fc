"""Your own arch: equivalent static analysis, one pulse, and a slice of its failure domain.

    python examples/own_arch.py            # a 12 m, 1.9 m thick, 150 degree arch of 9 voussoirs
    python examples/own_arch.py --quick    # the same, coarser domain (a few seconds)

SI units inside archquake (m, s, rad, m/s^2); magnitudes named *_g are in g.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from archquake import Arch
from archquake.domains import DomainSettings, failure_domain
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis
from archquake.mechanism import simulate


def main(quick: bool = False) -> None:
    arch = Arch(radius=12.0, thickness=1.9, embrace=math.radians(150.0), voussoirs=9)

    # 1. equivalent static analysis: the acceleration that starts hinging, and where
    static = limit_analysis(arch)
    print(f"hinging starts at {static.collapse_acceleration_g:.3f} g; hinges at joints "
          f"{static.mechanism.joints} ({'symmetric' if static.symmetric else 'asymmetric'}); "
          f"friction needed {static.min_friction:.3f}")

    # 2. one step impulse (a for t_p, then -a/2 for 2 t_p), twice the onset acceleration
    a_g, t_p = 2.0 * static.collapse_acceleration_g, 0.3
    result = simulate(arch, StepImpulse.from_g(a_g, t_p))
    print(f"a = {a_g:.2f} g, t_p = {t_p} s: {result.outcome.value}"
          + (f" in half cycle {result.collapse_half_cycle}" if result.collapse_half_cycle else "")
          + f"; {result.impact_times.size} impacts, c_v = {result.restitution_cv:.3f}")
    if result.energy_gain:  # thin or very wide arches: the paper's impact model creates energy
        print("  warning: c_v > 1 for this geometry, so rocking grows at every impact (docs/guide.md)")

    # 3. a slice of the same model's failure domain: the governing boundary at a few durations
    #    (model="fourlink": the model of step 2; failure_domain's default is the rigid chain)
    durations = np.linspace(0.2, 1.0, 3 if quick else 9)
    settings = DomainSettings(coarse_points=16, fine_points=6, precision_g=1e-2) if quick else None
    domain = failure_domain(arch, "step", durations, settings=settings, model="fourlink")
    print("t_p [s]  no hinging [g]  collapse [g]  1st half cycle [g]")
    for row in domain.to_dict():
        print(f"{row['duration_s']:7.2f}  {row['no_hinging_g']:14.3f}  "
              f"{row['collapse_g'] or float('nan'):12.3f}  {row['first_half_cycle_g'] or float('nan'):18.3f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarser domain slice")
    main(parser.parse_args().quick)
