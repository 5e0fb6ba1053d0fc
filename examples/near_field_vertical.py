"""The example bridge under near-field motions with and without their vertical component.

No recorded three-component near-field motion ships with archquake (the FEMA P695 sets carry
the two horizontal components only), so the motions here are synthetic and say so: the
horizontal is the velocity-pulse model of Mavroeidis & Papageorgiou (2003, BSSA 93(3)),

    v(t) = A/2 [1 + cos(2 pi f_p (t - t0) / gamma)] cos(2 pi f_p (t - t0) + nu),
    |t - t0| <= gamma / (2 f_p),

differentiated exactly and sampled at 0.005 s; the vertical is the same model at a quarter of
the horizontal's period, arriving a quarter period of the horizontal early, with a peak
V/H = 0.8 times the horizontal's (near-fault verticals are of higher frequency than the
horizontal pulse and reach or exceed 2/3 of its PGA: Bozorgnia & Campbell 2004, J. Earthq. Eng.
8(2)). The table this prints is that of docs/ground-motions.md:

* the first collapsing PGA: each motion scaled (both components together) on a grid 1 %
  apart from lambda g, the rigid chain's verdicts (`rigid_verdicts`);
* the critical pulse period: at the site PGA 0.18 g (the bridge's SLV), the least T_p of the
  same shape that collapses the arch, on a grid 1 % apart from 0.1 to 4 s.

Run: ``python examples/near_field_vertical.py`` (a few minutes); ``--quick`` runs the first
motion on 12 % grids;
``--dem`` adds the DEM's verdicts 3 % either side of the rigid chain's first collapsing PGA.
"""

from __future__ import annotations

import argparse
import math
import time
import tomllib
from pathlib import Path

import numpy as np

from archquake.assess.config import parse_config
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import Record
from archquake.ground.vertical import WithVertical
from archquake.limit import limit_analysis
from archquake.rigid import rigid_verdicts

HERE = Path(__file__).resolve().parent
DT = 0.005  # s
V_OVER_H = 0.8
SITE_PGA_G = 0.18
#: (label, T_p s, gamma, nu deg): pulse periods of M 6-7 near-fault records (the FEMA P695
#: near-field pulse set's 0.6-4 s, Baker 2007), one to two and a half cycles.
MOTIONS = (("MP-0.8s", 0.8, 1.8, 90.0), ("MP-1.2s", 1.2, 2.2, 0.0), ("MP-2.0s", 2.0, 2.0, 90.0))


def mp_acceleration(t: np.ndarray, period: float, gamma: float, nu_deg: float,
                    t0: float) -> np.ndarray:
    """d/dt of the Mavroeidis-Papageorgiou velocity pulse of unit A, 1/s (zero outside)."""
    f = 1.0 / period
    x = t - t0
    inside = np.abs(x) <= gamma / (2.0 * f)
    w, nu = 2.0 * math.pi * f, math.radians(nu_deg)
    env = 0.5 * (1.0 + np.cos(w * x / gamma))
    denv = -0.5 * (w / gamma) * np.sin(w * x / gamma)
    a = denv * np.cos(w * x + nu) - env * w * np.sin(w * x + nu)
    return np.where(inside, a, 0.0)


def near_field(label: str, period: float, gamma: float, nu_deg: float, pga_g: float = 1.0):
    """(horizontal Record, the WithVertical of it and its vertical), the horizontal's PGA
    ``pga_g`` g, the vertical's V_OVER_H times that."""
    t0 = gamma * period / 2.0 + 0.5  # s: the pulse starts at 0.5 s
    t = np.arange(0.0, t0 + gamma * period / 2.0 + 1.0, DT)
    h = mp_acceleration(t, period, gamma, nu_deg, t0)
    v = mp_acceleration(t, period / 4.0, 3.0, 0.0, t0 - period / 4.0)
    h *= pga_g * G / np.max(np.abs(h))
    v *= V_OVER_H * pga_g * G / np.max(np.abs(v))
    horizontal = Record(h, DT, name=label)
    return horizontal, WithVertical(horizontal, Record(v, DT, name=f"{label}-UP"))


def first_collapse(arch, motions, levels) -> float | None:
    """The first level whose motion the rigid chain's verdict collapses, or None."""
    for level, verdict in zip(levels, rigid_verdicts(arch, motions), strict=True):
        if verdict.outcome.value == "collapse":
            return float(level)
    return None


def bridge_arch():
    """examples/bridge.toml's ring, without its fill and loads."""
    data = tomllib.loads((HERE / "bridge.toml").read_text())
    data.pop("loads", None)
    return parse_config(data, source="bridge.toml", base_dir=HERE).build_arch()


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    p.add_argument("--quick", action="store_true", help="the first motion, 12 %% grids")
    p.add_argument("--dem", action="store_true", help="the DEM 3 %% either side (minutes)")
    args = p.parse_args(argv)
    step = 1.12 if args.quick else 1.01
    arch = bridge_arch()
    lam = limit_analysis(arch).collapse_acceleration_g
    started = time.perf_counter()
    print(f"bridge ring: lambda {lam:.4f} g; synthetic near-field motions, V/H {V_OVER_H:g}")
    print("motion   | 1st collapsing PGA (g): without | with vertical | critical T_p (s) at "
          f"{SITE_PGA_G:g} g: without | with vertical")
    pgas = lam * step ** np.arange(int(math.log(0.8 / lam) / math.log(step)) + 1)
    periods = 0.1 * step ** np.arange(int(math.log(40.0) / math.log(step)) + 1)
    rows = []
    for label, period, gamma, nu in MOTIONS[:1] if args.quick else MOTIONS:
        h, both = near_field(label, period, gamma, nu)
        pga = [first_collapse(arch, [m.scaled(a) for a in pgas], pgas) for m in (h, both)]
        tps = []
        for k in (0, 1):
            motions = [near_field(label, tp, gamma, nu, SITE_PGA_G)[k] for tp in periods]
            tps.append(first_collapse(arch, motions, periods))
        rows.append((label, both, pga))
        fmt = [("none" if x is None else f"{x:.3f}") for x in (*pga, *tps)]
        print(f"{label:8s} | {fmt[0]:>31s} | {fmt[1]:>13s} | {fmt[2]:>26s} | {fmt[3]:>13s}")
    print(f"rigid chain's verdicts: {time.perf_counter() - started:.0f} s")
    if args.dem:
        from archquake.dem import DemSettings, simulate_dem

        for label, both, pga in rows:
            if pga[1] is None:
                continue
            words = [simulate_dem(arch, both.scaled(f * pga[1]),
                                  DemSettings(duration=both.duration + 6.0)).outcome.value
                     for f in (0.97, 1.03)]
            print(f"DEM {label}: at 0.97 x {pga[1]:.3f} g {words[0]}, at 1.03 x {words[1]}")


if __name__ == "__main__":
    main()
