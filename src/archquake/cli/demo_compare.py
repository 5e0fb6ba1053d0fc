"""Demo step: the analytical model beside the distinct-element model (paper pp. 2131-2135):
Figure 4(b)-(d) time histories with both DEM arches, Figure 8 next to Figure 9 (hinges),
Figure 10 (reduced damping), an animation, and (full mode) the failure domains of Figures 6
and 11 with the DEM boundaries."""

from __future__ import annotations

import math
import time
from pathlib import Path

#: Full mode: DEM domain durations t_p (s) for the step impulse and periods T (s) for the sine.
STEP_DURATIONS = (0.1, 0.2, 0.3, 0.5, 0.8)
SINE_PERIODS = (0.5, 1.0, 2.0, 3.0)
RADII = (5.0, 10.0, 20.0)


def demo_step(out: Path, quick: bool) -> list[Path]:
    """Write ``compare_fig4.png``, ``compare_fig9.png``, ``compare_fig10.png``,
    ``compare_dem_rocking.gif``, ``compare.md`` (and in full mode ``compare_domains.png``).

    Quick mode (~30 s on 2 cores): everything but the failure domains. Full mode adds the DEM
    domains: step impulse for R = 5, 10, 20 m, the sine pulse and the reduced damping for
    R = 10 m (tens of minutes on 2 cores).
    """
    from archquake.compare import (
        compare_domains,
        compare_hinges,
        figure4_comparisons,
        reduced_damping_snapshot,
    )
    from archquake.compare.report import (
        domain_costs,
        domain_table,
        figure4_table,
        hinge_table,
        reduced_damping_table,
    )
    from archquake.geometry import Arch
    from archquake.plotting.compare import (
        domain_comparison_figure,
        figure4_comparison,
        figure9_comparison,
        figure10,
    )
    from archquake.plotting.dem import animate_dem

    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    files: list[Path] = []
    t0 = time.perf_counter()
    f4 = figure4_comparisons(arch, duration=5.0)
    t_f4 = time.perf_counter() - t0
    files.append(figure4_comparison(f4, out / "compare_fig4.png", t_end=4.5))
    hinges = compare_hinges(arch)
    files.append(figure9_comparison(arch, hinges.states, hinges.dem_result, out / "compare_fig9.png"))
    snap = reduced_damping_snapshot(arch)
    files.append(figure10(snap.reduced, snap.time, out / "compare_fig10.png", reference=snap.paper))
    t1 = time.perf_counter()
    files.append(animate_dem(f4[(0.27, "voussoirs")].dem, out / "compare_dem_rocking.gif",
                             fps=8 if quick else 15))
    t_gif = time.perf_counter() - t1
    red = snap.to_dict()
    lines = [
        "# The analytical model beside the distinct-element model (paper pp. 2131-2135)", "",
        "Oppenheim's arch (R = 10 m, t/R = 0.15, embrace 157.5 deg, 7 voussoirs), joint stiffness "
        "1e12 Pa/m, Rayleigh damping alpha = 6.28e-5 1/s, beta = 1.59e-4 s (the paper's). "
        "DEM arches: every voussoir a block (7 blocks), or cut at the analytical hinges "
        "(0, 3, 5, 7: the paper's three-voussoir arch).", "",
        f"## Time histories (Figure 4(b)-(d); `compare_fig4.png`; {t_f4:.1f} s for all runs)", "",
        figure4_table(f4), "",
        "The difference is taken over the first half cycle (to the earliest first impact or the "
        "analytical collapse) against the analytical peak there. DEM collapse: the crown has "
        "fallen by t (later than the analytical crest criterion).", "",
        "## Hinges: Figure 8 (analytical) beside Figure 9 (DEM), a = 1.0 g, t_p = 0.20 s "
        "(`compare_fig9.png`)", "",
        hinge_table(hinges), "",
        "## Reduced damping (Figure 10; `compare_fig10.png`): a = 1.0 g, t_p = 0.22 s, t = 1.29 s", "",
        f"f_min = 0.05 Hz, xi_min = 0.001 %: alpha = {red['reduced']['rayleigh'][0]:.3g} 1/s, "
        f"beta = {red['reduced']['rayleigh'][1]:.3g} s. Largest inter-stone slip at t = 1.29 s: "
        f"**{red['reduced']['max_slip_mm']:.1f} mm** with the reduced damping, "
        f"{red['paper']['max_slip_mm']:.1f} mm with the paper's (friction coefficient 1e6: no "
        "Coulomb sliding is possible; the offsets are the 'relative inter-stone displacements "
        "similar to sliding' of the paper).", "",
        reduced_damping_table(snap), "",
        f"Animation: `compare_dem_rocking.gif` (7 blocks, t_p = 0.27 s; {t_gif:.1f} s to render).",
    ]
    if not quick:
        t2 = time.perf_counter()
        comps = [compare_domains(Arch(r, 0.15 * r, math.radians(157.5), 7), "step", STEP_DURATIONS,
                                 label=f"step, R = {r:g} m") for r in RADII]
        from archquake.dem import DemSettings

        reduced = DemSettings(damping=DemSettings.rayleigh_from_minimum(0.05, 1e-5))
        comps.append(compare_domains(arch, "step", STEP_DURATIONS, first=False, dem_settings=reduced,
                                     label="step, R = 10 m, reduced damping"))
        comps.append(compare_domains(arch, "sine", SINE_PERIODS, label="sine, R = 10 m"))
        files.append(domain_comparison_figure(comps, out / "compare_domains.png"))
        lines += ["", f"## Failure domains (Figures 6, 11; `compare_domains.png`; "
                  f"{time.perf_counter() - t2:.0f} s)", "",
                  "DEM search: the analytical search (`failure_domain`) with a DEM evaluation, "
                  "8 + 4 magnitudes per duration, brackets of 0.01 g; analytical 0.001 g.", "",
                  domain_table(comps), "", domain_costs(comps)]
    else:
        lines += ["", "Failure domains with the DEM: `archquake demo --full` (tens of minutes), or "
                  "`archquake domain --model dem`."]
    report = out / "compare.md"
    report.write_text("\n".join(lines) + "\n")
    files.append(report)
    return files
