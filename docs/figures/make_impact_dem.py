"""Figure for docs/notes/mechanism.md: the DEM's mechanical energy across the first impact of free
rocking (archquake.compare.impacts protocol), against the c_T of each impact law.

Run: PYTHONPATH=src python docs/figures/make_impact_dem.py   (about a minute)
"""

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from archquake import Arch
from archquake.compare.impacts import fourlink_impacts, rocking_pulse
from archquake.dem import simulate_dem
from archquake.dem.settings import DemSettings

CASES = (
    ("Oppenheim (t/R 0.15, 157.5 deg, n 7)", Arch(10.0, 1.5, math.radians(157.5), 7)),
    ("symmetric hinges (t/R 0.15, 142.5 deg, n 7)", Arch(10.0, 1.5, math.radians(142.5), 7)),
    ("semicircle R 5 m, t 0.6 m, n 15", Arch(5.0, 0.6, math.pi, 15)),
)
fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), sharey=True)
for ax, (label, arch) in zip(axes, CASES):
    _, laws, exact, _ = fourlink_impacts(arch)
    pulse, tp, t_imp = rocking_pulse(arch)
    res = simulate_dem(arch, pulse, DemSettings(duration=1.5 * t_imp + 0.1, output_interval=5e-4))
    ti = res.first_impact_time
    e = res.kinetic + res.potential + res.strain - (res.potential[0] + res.strain[0])
    ref = float(np.interp(ti - 0.05, res.times, e))
    sel = (res.times > ti - 0.15) & (res.times < ti + 0.15)
    ax.plot(1e3 * (res.times[sel] - ti), e[sel] / ref, "k-", lw=1.2, label="DEM (E - E_rest) / E(-50 ms)")
    styles = {"paper": ("C3", "--"), "mirror": ("C1", ":"), "chain": ("C0", "-.")}
    for law, (colour, ls) in styles.items():
        ct = laws[law]["ct"]
        if ct <= 1.2:
            ax.axhline(ct, color=colour, ls=ls, label=f"{law}: c_T = {ct:.3f}")
        else:
            ax.text(-140, 1.12, f"paper: c_T = {ct:.0f} (off scale)", color=colour, fontsize=8)
    ax.axhline(exact, color="C2", lw=0.8, label=f"exact response: {exact:.3f}")
    ax.axvline(0.0, color="0.6", lw=0.5)
    ax.set_title(label, fontsize=9)
    ax.set_xlabel("time from the DEM's zero crossing (ms)")
    ax.set_ylim(0.0, 1.2)
    ax.legend(fontsize=7, loc="lower left")
axes[0].set_ylabel("mechanical energy above rest, relative")
fig.tight_layout()
fig.savefig(Path(__file__).with_name("impact_dem.png"), dpi=110)
