"""docs/figures/rigid_energy.png and rigid_hinges.png (docs/notes/mechanism.md, "The rigid limit").

Energy from the end of the pulse through the first impact: the rigid-block chain
(`rigid`, h = 1e-4 s) against the DEM at the paper's contact stiffness and at
ten times it, on the four arches of the migration table; and Oppenheim's open joints in both
models, read by the same code (`compare.dem_hinges`).

Run: PYTHONPATH=src python docs/figures/make_rigid_limit.py  (a few minutes: eight DEM runs,
four rigid-chain runs). Prints the energy-kept rows as JSON.
"""

import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import Arch  # noqa: E402
from archquake.compare.impacts import (  # noqa: E402
    MIGRATION_GEOMETRIES,
    dem_half_cycle,
    fixed_hinge_kept,
)
from archquake.compare.rigid import rigid_half_cycle, scaled_contact  # noqa: E402

rows = []
seqs = {}
fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
for (label, r, t, emb, n), ax in zip(MIGRATION_GEOMETRIES, axes.ravel()):
    arch = Arch(r, t, math.radians(emb), n)
    fixed = fixed_hinge_kept(arch)
    rigid, run = rigid_half_cycle(arch)
    tp = rigid.pulse_duration_s
    row = {"label": label, "paper": fixed["paper"], "chain": fixed["chain"],
           "rigid": rigid.kept, "rigid_before": rigid.kept_before,
           "rigid_impact_s": rigid.impact_time_s}
    curves = [("rigid chain", rigid, "C3", 1.6)]
    for k, c in ((1.0, "k"), (10.0, "0.55")):
        dem = dem_half_cycle(arch, settings=scaled_contact(k))
        row[f"dem_k{k:g}"] = dem.kept
        row[f"dem_k{k:g}_before"] = dem.kept_before
        row[f"dem_k{k:g}_impact_s"] = dem.impact_time_s
        curves.append((f"DEM, k x{k:g}", dem, c, 1.0))
        if label == "Oppenheim" and k == 1.0:
            seqs["DEM (paper's k)"] = dem.sequence
    if label == "Oppenheim":
        seqs["rigid chain"] = rigid.sequence
    t_hi = max((cv.impact_time_s or 0.0) for _, cv, _, _ in curves) + 0.05
    for name, cv, c, lw in curves:
        sel = (cv.t >= tp) & (cv.t <= t_hi)
        kept = "-" if cv.kept is None else f"{cv.kept:.3f}"
        ax.plot(cv.t[sel], cv.energy_fraction[sel], color=c, lw=lw, label=f"{name} ({kept})")
    ax.axhline(fixed["paper"], color="C0", ls="--", lw=0.8, label=f"Eq. 4 fixed ({fixed['paper']:.2f})")
    ax.axhline(fixed["chain"], color="C1", ls="--", lw=0.8, label=f"chain law fixed ({fixed['chain']:.2f})")
    ax.set_title(label, fontsize=10)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("E / E(end of pulse)")
    ax.set_ylim(0, 1.15)
    ax.legend(fontsize=7, loc="lower left")
    rows.append(row)
fig.suptitle("Energy from the end of the pulse through the first impact: rigid-block chain and DEM "
             "(in brackets: kept 10 ms after the first impact)", fontsize=10)
fig.tight_layout()
fig.savefig("docs/figures/rigid_energy.png", dpi=110)
print(json.dumps(rows, indent=1, default=str))

# --- Oppenheim's open joints, both models
fig2, ax2 = plt.subplots(figsize=(10, 4.2))
t_stop = max(s[-1][0] for s in seqs.values()) + 0.02
for (name, seq), color, dy in zip(seqs.items(), ("k", "C3"), (-0.18, 0.18)):
    first = True
    for i, (t0, lab) in enumerate(seq):
        t1 = seq[i + 1][0] if i + 1 < len(seq) else t_stop
        for h in lab.split():
            j, f = int(h[:-1]), h[-1]
            ax2.plot([t0, t1], [j + dy, j + dy], color=color, lw=4 if f == "e" else 2,
                     solid_capstyle="butt", label=name if first else None)
            first = False
ax2.set_yticks(range(8))
ax2.set_ylabel("joint (thick: extrados hinge, thin: intrados)")
ax2.set_xlabel("t (s), from the end of the pulse")
ax2.set_title("Oppenheim's arch, pulse 2 lambda g: open joints of the DEM and of the rigid chain",
              fontsize=10)
ax2.legend(fontsize=8, loc="upper left")
fig2.tight_layout()
fig2.savefig("docs/figures/rigid_hinges.png", dpi=110)
