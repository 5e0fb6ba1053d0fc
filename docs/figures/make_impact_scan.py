"""Figure for docs/notes/mechanism.md: c_v against the number of voussoirs, semicircles R = 5 m,
under Eq. 4 (the paper's law) and the chain law.

Run: PYTHONPATH=src python docs/figures/make_impact_scan.py
"""

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from archquake import Arch
from archquake.limit import hinges_of
from archquake.mechanism.impact import solve_impact

ns = np.arange(9, 32)
fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
for t, colour in zip((0.6, 0.75, 0.9), ("C0", "C1", "C2")):
    paper, chain, mirror = [], [], []
    for n in ns:
        pre = hinges_of(Arch(5.0, t, math.pi, int(n)))
        paper.append(solve_impact(pre, "paper").restitution_cv)
        chain.append(solve_impact(pre, "chain").restitution_cv)
        mirror.append(solve_impact(pre, "mirror").restitution_cv)
    axes[0].plot(ns, paper, "o-", color=colour, ms=3, label=f"t = {t} m")
    axes[1].plot(ns, chain, "o-", color=colour, ms=3, label=f"chain, t = {t} m")
    axes[1].plot(ns, mirror, "x:", color=colour, ms=3, label=f"mirror forced, t = {t} m")
axes[0].set_yscale("symlog", linthresh=1.0)
axes[0].axhspan(0, 1, color="0.9")
axes[0].set_title("Eq. 4 (paper law): c_v (symlog; grey = [0, 1])")
axes[1].set_title("chain law (generalised momentum, max. restitution)")
axes[1].set_ylim(0, 1)
for ax in axes:
    ax.set_xlabel("voussoirs n (semicircle, R = 5 m)")
    ax.set_ylabel("c_v")
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(Path(__file__).with_name("impact_scan.png"), dpi=110)
