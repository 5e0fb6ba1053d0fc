"""Benchmark: the whole code check of an arch (capacity curve at large displacements, then every
limit state's capacity a_g), target < 2 s, beside the equivalent static analysis it starts from
(the plain reference: the check needs it, so the ratio says what the rest costs).

Run: .venv/bin/python benchmarks/bench_codecheck.py
"""

from __future__ import annotations

import math

from timing import best_of  # benchmarks/timing.py

from archquake.codecheck.check import kinematic_check
from archquake.codecheck.kinematic import capacity_curve
from archquake.codes.spectra import ntc2018_spectrum
from archquake.geometry import Arch
from archquake.limit import limit_analysis


def main() -> dict:
    spectrum = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
    spectra = {"SLD": spectrum.with_ag(0.08 * spectrum.g), "SLV": spectrum,
               "SLC": spectrum.with_ag(0.32 * spectrum.g)}
    arches = {
        "bridge (R 5 m, t 0.6 m, 180 deg, 15 voussoirs)": lambda: Arch(5.0, 0.6, math.pi, 15),
        "Oppenheim (R 10 m, t 1.5 m, 157.5 deg, 7)": lambda: Arch(10.0, 1.5,
                                                                  math.radians(157.5), 7),
        "semicircle, 60 voussoirs": lambda: Arch(5.0, 0.6, math.pi, 60),
    }
    kinematic_check(capacity_curve(arches["bridge (R 5 m, t 0.6 m, 180 deg, 15 voussoirs)"]()),
                    spectra)  # warm: compiled kernels loaded, LP set up
    out = {}
    print("the whole code check (fresh arch each call: geometry, limit analysis, curve, checks)")
    for name, make in arches.items():
        t_check = best_of(lambda m=make: kinematic_check(capacity_curve(m()), spectra), 3, 1)
        t_limit = best_of(lambda m=make: limit_analysis(m()), 3, 1)
        print(f"  {name:<48s}{t_check * 1e3:8.1f} ms  (target < 2000 ms)  "
              f"{t_check / t_limit:6.1f} x its limit analysis ({t_limit * 1e3:.1f} ms)")
        out[name] = {"check_s": t_check, "ratio_to_limit": t_check / t_limit}
    return out


if __name__ == "__main__":
    main()
