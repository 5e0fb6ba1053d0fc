"""Demo step: equivalent static analysis of Oppenheim's arch (figure and a short report)."""

from __future__ import annotations

import math
import time
from pathlib import Path

from archquake.geometry import Arch
from archquake.limit import limit_analysis, min_thickness_ratio

#: Figure 7 of the paper: (t/R, embrace in degrees), 7 voussoirs, R = 10 m.
FIGURE_7 = [(0.11, 157.5), (0.15, 157.5), (0.17, 157.5), (0.19, 157.5),
            (0.15, 142.5), (0.15, 150.0), (0.15, 165.0)]


def _hinges(result) -> str:
    return ", ".join(f"{label} joint {h.joint} {h.face.value}"
                     for label, h in zip("ABCD", result.mechanism.hinges, strict=True))


def _place(result) -> str:
    j, n = result.min_friction_joint, result.arch.voussoirs
    return {0: " (left springing)", n: " (right springing)"}.get(j, "")


def demo_step(out: Path, quick: bool) -> list[Path]:
    """Write ``out/static_collapse.png`` and ``out/static_report.md``.

    Parameters
    ----------
    out : Path
        Output folder (exists).
    quick : bool
        Quick mode: the semicircle's minimum thickness with 200 voussoirs instead of 1000.
    """
    from archquake.plotting.arch import save_limit_analysis

    arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
    result = limit_analysis(arch, method="both")
    figure = save_limit_analysis(result, out / "static_collapse.png")

    n_min = 200 if quick else 1000
    t0 = time.perf_counter()
    t_semicircle = min_thickness_ratio(math.pi, n_min)
    dt = time.perf_counter() - t0
    t_oppenheim = min_thickness_ratio(arch.embrace, arch.voussoirs)

    lines = [
        "# Equivalent static analysis of Oppenheim's arch",
        "",
        "t/R = 0.15, embrace 157.5 deg, R = 10 m, 7 voussoirs; self-weight plus a uniform "
        "horizontal acceleration towards +x; rigid voussoirs, no tension, no sliding.",
        "",
        "| quantity | archquake | paper |",
        "| --- | --- | --- |",
        f"| collapse acceleration (static LP) | {result.static_collapse_acceleration_g:.4f} g | 0.37 g |",
        f"| collapse acceleration (virtual work) | {result.kinematic_collapse_acceleration_g:.4f} g "
        "| 0.37 g |",
        f"| hinges | {_hinges(result)} | (Figure 1) |",
        f"| hinge locations | {'symmetric' if result.symmetric else 'asymmetric'} | "
        "asymmetric (Figure 7) |",
        f"| friction demand (largest abs(V)/N) | {result.min_friction:.3f} at joint "
        f"{result.min_friction_joint}{_place(result)} | 0.50, at hinge D |",
        f"| minimum t/R of this arch (7 voussoirs) | {t_oppenheim:.4f} | |",
        f"| minimum t/R of a semicircle ({n_min} voussoirs, {dt:.2f} s) | {t_semicircle:.4f} | "
        "0.1075 (Milankovitch; Heyman) |",
        "",
        "## Figure 7 geometries (7 voussoirs)",
        "",
        "| t/R | embrace (deg) | collapse acceleration (g) | hinges | locations |",
        "| --- | --- | --- | --- | --- |",
    ]
    for ratio, embrace in FIGURE_7:
        r = limit_analysis(Arch.from_ratio(ratio, math.radians(embrace), 7, radius=10.0))
        lines.append(f"| {ratio:g} | {embrace:g} | {r.collapse_acceleration_g:.4f} | "
                     f"{_hinges(r)} | {'symmetric' if r.symmetric else 'asymmetric'} |")
    lines += ["", f"![Oppenheim's arch at collapse]({figure.name})", ""]
    report = out / "static_report.md"
    report.write_text("\n".join(lines))
    return [figure, report]
