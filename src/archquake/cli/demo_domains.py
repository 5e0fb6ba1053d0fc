"""Demo step: failure domains of Oppenheim's arch (paper Figures 5, 6, 7 and 11) and the
scale-effect comparison (exact similarity vs the paper's sqrt(R) rule)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np


def demo_step(out: Path, quick: bool) -> list[Path]:
    from archquake.domains import (
        DomainSettings,
        compare_scaling,
        geometry_study,
        oppenheim_arch,
        scale_study,
    )
    from archquake.domains.domain import failure_domain
    from archquake.plotting.domains import plot_domain, plot_domains, plot_scaling, save

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    n = 14 if quick else 40
    settings = DomainSettings(coarse_points=30, fine_points=16) if quick else DomainSettings()
    written: list[Path] = []
    steps = np.linspace(0.05, 1.5, n)
    arch = oppenheim_arch()

    fig5 = failure_domain(arch, "step", steps, settings=settings)
    written.append(save(plot_domain(fig5, title="Figure 5: Oppenheim's arch, step impulse"),
                        out / "figure5_domain_step.png"))
    written.append(fig5.write_csv(out / "figure5_domain_step.csv"))

    scale = scale_study(durations=steps, settings=settings)
    ref = next(c.domain for c in scale if c.arch.radius == 10.0)
    others = [c.domain for c in scale if c.arch.radius != 10.0 and c.domain is not None]
    written.append(save(plot_domains(scale, boundary="first_half_cycle",
                                     title="Figure 6a: scale effect, 1st half cycle"),
                        out / "figure6a_scale_first.png"))
    written.append(save(plot_domains(scale, title="Figure 6b: scale effect, governing boundary"),
                        out / "figure6b_scale_collapse.png"))
    written.append(save(plot_scaling(ref, others), out / "figure6_scaling_laws.png"))
    comparison = {f"R = {d.arch.radius:g} m": compare_scaling(ref, d).to_dict() for d in others}
    p = out / "figure6_scaling_comparison.json"
    p.write_text(json.dumps(comparison, indent=2))
    written.append(p)

    durations7 = np.linspace(0.05, 1.0, 10 if quick else 30)
    by_ratio, by_embrace = geometry_study(durations=durations7, settings=settings)
    written.append(save(plot_domains(by_ratio, title="Figure 7a: t/R (157.5 deg, R = 10 m)"),
                        out / "figure7a_thickness.png"))
    written.append(save(plot_domains(by_embrace, title="Figure 7b: embrace (t/R = 0.15, R = 10 m)"),
                        out / "figure7b_embrace.png"))
    notes = {c.label: c.problem for c in (*by_ratio, *by_embrace) if c.problem}
    p = out / "figure7_geometry_notes.json"
    p.write_text(json.dumps(notes, indent=2))
    written.append(p)

    fig11 = failure_domain(arch, "sine", np.linspace(0.2, 4.0, n), settings=settings)
    written.append(save(plot_domain(fig11, title="Figure 11: Oppenheim's arch, one-cycle sine pulse"),
                        out / "figure11_domain_sine.png"))
    written.append(fig11.write_csv(out / "figure11_domain_sine.csv"))
    return written
