"""The code check's two routes side by side (NTC 2018 §8.7.1, Circolare 2019 C8.7.1.2): the
static route (capacity curve, d_SLV = 0.4 d0 at T_SLV against the elastic spectrum at 8 %
damping) and the time-history route (C8.7.1.2.1.9: seven natural records, spectrum-compatible
with the site's SLV spectrum, run on the chain of rigid voussoirs; the arch passes if no record
takes it beyond d0 and the mean peak displacement stays below d_SLV), each as the capacity a_g.

The site is the [site] of examples/bridge.toml (illustrative hazard, soil B, LC1). Records: the
FEMA P695 far-field set (pip install 'archquake[records]'), the seven chosen and scaled by
archquake.ground.selection to the NTC band (-10 / +30 %) over 0.1 s to 1.2 T_SLC.

Each record is run to the time its Arias intensity reaches 95 % plus 2 s (the rest of a record
adds almost no energy; the chain then runs on to a verdict as always), which halves the cost.

Run:  .venv/bin/python examples/code_check_routes.py [--quick] [--arch NAME] [--states SLV,SLC]
      [--bisections N] [--json FILE]
(--quick: Oppenheim's arch alone, SLV, no bisection. A level is seven records on the rigid
chain: about a minute of one core for these arches.)
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

import numpy as np

from archquake._json import to_jsonable
from archquake.codecheck.check import kinematic_check, limit_state_spectra
from archquake.codecheck.kinematic import capacity_curve
from archquake.codecheck.timehistory import time_history_capacity
from archquake.codes.spectra import NTCHazard
from archquake.geometry import Arch
from archquake.ground.response_spectra import record_spectra
from archquake.ground.selection import select_records
from archquake.ground.suites import load_suite

HAZARD = [(50, 0.05, 2.50, 0.26), (475, 0.15, 2.45, 0.30), (975, 0.19, 2.50, 0.31)]
ARCHES = {
    "bridge": Arch(5.0, 0.6, math.pi, 15),
    "oppenheim": Arch(10.0, 1.5, math.radians(157.5), 7),
}


def _strong_part(record, tail_s: float = 2.0):
    """The record up to its 95 % Arias time plus ``tail_s`` seconds."""
    from dataclasses import replace

    from archquake.ground.measures import strong_motion_end

    n = min(record.points, int(math.ceil((strong_motion_end(record) + tail_s) / record.dt)) + 1)
    return replace(record, accelerations=record.accelerations[:n])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--arch", choices=tuple(ARCHES), action="append")
    ap.add_argument("--states", default="SLV,SLC")
    ap.add_argument("--bisections", type=int, default=3)
    ap.add_argument("--json", metavar="FILE")
    args = ap.parse_args(argv)
    spectra = limit_state_spectra(NTCHazard(HAZARD), soil="B")
    suite = list(load_suite("fema-p695-far-field"))
    names = ["oppenheim"] if args.quick else (args.arch or list(ARCHES))
    arches = {n: ARCHES[n] for n in names}
    states = ("SLV",) if args.quick else tuple(args.states.split(","))
    out = {}
    for name, arch in arches.items():
        curve = capacity_curve(arch)
        static = kinematic_check(curve, spectra, knowledge="LC1")
        t_slc = static.check("SLC", "nonlinear").period_s
        periods = np.geomspace(0.1, 1.2 * t_slc, 25)
        rs = record_spectra(suite, periods)
        row = {"alpha0": curve.alpha0, "d0_m": curve.d0_m}
        for state in states:
            spectrum = spectra[state]
            sel = select_records(rs, lambda t, s=spectrum: s.sa(t), count=7)
            records = [_strong_part(suite[i]).scaled(f)
                       for i, f in zip(sel.indices, sel.scale_factors)]
            site_ag = spectrum.ag / spectrum.g
            start = static.check(state, "nonlinear").capacity_ag_g
            t0 = time.perf_counter()
            cap = time_history_capacity(
                curve, records, site_ag, start, state, bisections=0 if args.quick else args.bisections,
                progress=lambda line, n=name, s=state: print(f"  {n} {s} {line}", flush=True))
            row[state] = {
                "static_capacity_ag_g": start,
                "time_history_capacity_ag_g": cap.capacity_ag_g,
                "bracket_g": cap.bracket_g,
                "ratio_time_history_to_static": cap.capacity_ag_g / start,
                "records": [suite[i].name for i in sel.indices],
                "scale_factors": sel.scale_factors,
                "compatible": sel.compatible,
                "seconds": time.perf_counter() - t0,
                "levels": cap.to_dict()["levels"],
            }
            print(f"{name} {state}: static a_g {start:.4f} g, time histories "
                  f"{cap.capacity_ag_g:.4f} g (bracket {cap.bracket_g[0]:.4f}-"
                  f"{cap.bracket_g[1]:.4f} g), ratio {cap.capacity_ag_g / start:.2f}", flush=True)
        out[name] = row
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(to_jsonable(out), fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
