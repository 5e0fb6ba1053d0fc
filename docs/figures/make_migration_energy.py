"""docs/figures/migration_energy.png and the table of docs/notes/mechanism.md "Hinges that move".

Run: PYTHONPATH=src python docs/figures/make_migration_energy.py  (about a minute: four DEM runs
and eight migrating histories). Prints the table rows and the hinge sequences as JSON.
"""

import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archquake import Arch  # noqa: E402
from archquake.compare.impacts import rocking_pulse  # noqa: E402
from archquake.compare.migration import (  # noqa: E402
    MIGRATION_GEOMETRIES,
    RectangularPulse,
    dem_half_cycle,
    fixed_hinge_kept,
)
from archquake.mechanism.migration import simulate_migrating  # noqa: E402

rows = []
fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
for (label, r, t, emb, n), ax in zip(MIGRATION_GEOMETRIES, axes.ravel()):
    arch = Arch(r, t, math.radians(emb), n)
    fixed = fixed_hinge_kept(arch)
    pulse, tp, t_imp = rocking_pulse(arch)
    rect = RectangularPulse(float(pulse.acceleration(0.0)), tp)
    dem = dem_half_cycle(arch)
    row = {"label": label, "t_p_s": tp, "paper": fixed["paper"], "chain": fixed["chain"],
           "dem": dem.kept, "dem_before": dem.kept_before, "dem_impact_s": dem.impact_time_s,
           "fixed_impact_s": t_imp, "dem_sequence": dem.sequence}
    sel = dem.t >= tp
    ax.plot(dem.t[sel], dem.energy_fraction[sel], "k-", lw=1.2, label=f"DEM ({dem.kept:.2f})")
    t_hi = max(dem.impact_time_s or t_imp, t_imp)
    for mode, c in (("potential", "C2"), ("position", "C3")):
        res = simulate_migrating(arch, rect, t_end=3 * t_imp, stop_after_impacts=1, reexpress=mode)
        e_tp = res.energy_at(tp)
        imp = res.impacts[0] if res.impacts else None
        row[mode] = None if imp is None else imp.energy_after / e_tp
        row[mode + "_before"] = None if imp is None else imp.energy_before / e_tp
        row[mode + "_impact_s"] = None if imp is None else imp.t
        row[mode + "_outcome"] = res.outcome
        row[mode + "_sequence"] = [(round(s.t, 4), s.kind, s.after, round(s.kept, 3),
                                    round(s.position_jump_m, 4)) for s in res.switches]
        row[mode + "_outside"] = [(round(a, 4), b, c_) for a, b, c_ in res.outside]
        s = res.t >= tp
        tx = np.append(res.t[s], imp.t if imp else res.t[-1])
        ex = np.append(res.energy[s], imp.energy_after if imp else res.energy[-1]) / e_tp
        name = "migrating, equal potential" if mode == "potential" else "migrating, nearest positions"
        ax.plot(tx, ex, c + "-", lw=1.0,
                label=f"{name} ({row[mode]:.2f})" if imp else f"{name} ({res.outcome})")
        t_hi = max(t_hi, tx[-1])
    tt = np.linspace(tp, t_hi + 0.1, 400)
    ax.plot(tt, np.where(tt < t_imp, 1.0, fixed["paper"]), "C0--",
            label=f"fixed, Eq. 4 ({fixed['paper']:.2f})")
    ax.plot(tt, np.where(tt < t_imp, 1.0, fixed["chain"]), "C1--",
            label=f"fixed, chain law ({fixed['chain']:.2f})")
    ax.set_title(label, fontsize=10)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("E / E(end of pulse)")
    ax.set_ylim(0, 1.15)
    ax.legend(fontsize=7, loc="lower left")
    rows.append(row)
fig.suptitle("Energy from the end of the pulse (2 lambda g towards -x) to 10 ms after the first "
             "impact", fontsize=10)
fig.tight_layout()
fig.savefig("docs/figures/migration_energy.png", dpi=110)
print(json.dumps(rows, indent=1, default=str))


# --- docs/figures/migration_hinges.png: Oppenheim's hinges over the first half cycle, side by side
def _intervals(sequence, t_stop):
    """[(t0, t1, 'ji ...')] from [(t, labels)]."""
    out = []
    for k, (t0, lab) in enumerate(sequence):
        t1 = sequence[k + 1][0] if k + 1 < len(sequence) else t_stop
        out.append((t0, t1, lab))
    return out


opp = rows[0]
t_stop = max(opp["dem_impact_s"], opp["potential_impact_s"]) + 0.1
fig2, ax2 = plt.subplots(figsize=(10, 4.2))
model = [(s[0], s[2]) for s in opp["potential_sequence"]]
lanes = (("DEM", [tuple(s) for s in opp["dem_sequence"]], "k", -0.18),
         ("migrating model (equal potential)", model, "C2", 0.18))
for name, seq, color, dy in lanes:
    first = True
    for t0, t1, lab in _intervals(seq, t_stop):
        for h in lab.split():
            if h == "-":
                continue
            j, f = int(h[:-1]), h[-1]
            ax2.plot([t0, t1], [j + dy, j + dy], color=color, lw=4 if f == "e" else 2,
                     solid_capstyle="butt", label=name if first else None)
            first = False
for t_i, c in ((opp["dem_impact_s"], "k"), (opp["potential_impact_s"], "C2")):
    ax2.axvline(t_i, color=c, ls=":", lw=1)
ax2.axvline(opp["t_p_s"], color="0.6", ls="--", lw=1)
ax2.set_yticks(range(8))
ax2.set_ylabel("joint (thick: extrados hinge, thin: intrados)")
ax2.set_xlabel("t (s)  (dashed: end of pulse; dotted: first impact)")
ax2.set_title("Oppenheim's arch, pulse 2 lambda g: hinges of the migrating model and open joints of the DEM",
              fontsize=10)
ax2.legend(fontsize=8, loc="upper left")
fig2.tight_layout()
fig2.savefig("docs/figures/migration_hinges.png", dpi=110)
