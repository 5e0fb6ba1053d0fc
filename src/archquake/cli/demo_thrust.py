"""Demo step: line of thrust during motion (paper Figure 8) and the friction the joints need
(paper p. 2131), for Oppenheim's arch under the step impulse."""

from __future__ import annotations

import math
from pathlib import Path

from archquake.geometry import Arch
from archquake.ground import StepImpulse

#: Figure 8: a = 1.0 g, t_p = 0.20 s, snapshots at these times (s).
FIGURE_8_TIMES = (0.2, 0.5, 0.8, 1.1, 1.5, 2.22)

#: Paper p. 2131 and p. 2135: (a in g, analytical, UDEC).
PAPER_FRICTION = ((0.5, "0.509", "0.51"), (1.0, "~0.56", "0.55"))


def demo_step(out: Path, quick: bool) -> list[Path]:
    """Write ``out/fig8_thrust.png`` and ``out/friction.md``.

    Parameters
    ----------
    out : Path
        Output folder (exists).
    quick : bool
        Quick mode: friction demand for t_p = 0.27 s only (full: also 0.20 s and 0.44 s).
    """
    from archquake.mechanism.simulate import PreparedMechanism
    from archquake.plotting.thrust import save_thrust_snapshots
    from archquake.thrust import states
    from archquake.thrust.friction import friction_demand

    arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
    prepared = PreparedMechanism.build(arch)
    motion = StepImpulse.from_g(1.0, 0.20)
    snaps = states(prepared, motion, FIGURE_8_TIMES)
    fig = save_thrust_snapshots(arch, snaps, out / "fig8_thrust.png",
                                suptitle="Figure 8: Oppenheim's arch, step impulse 1.0 g, 0.20 s")
    lines = ["# Line of thrust during motion and friction demand (Oppenheim's arch)", "",
             "## Figure 8 (a = 1.0 g, t_p = 0.20 s): where the line of thrust leaves the section", "",
             "| t (s) | mechanism | phi (deg) | leaves at joint | by (m) | max friction demand (joint) |",
             "| --- | --- | --- | --- | --- | --- |"]
    for s in snaps:
        j = s.exit_joint
        k = int(s.friction_demand.argmax())
        lines.append(f"| {s.t:.2f} | {'first' if s.side > 0 else 'mirrored'} | "
                     f"{math.degrees(s.phi):.3f} | {'-' if j is None else j} | "
                     f"{0.0 if j is None else s.outside[j]:.3f} | {s.friction_demand[k]:.3f} ({k}) |")
    durations = (0.27,) if quick else (0.20, 0.27, 0.44)
    lines += ["", "## Friction needed to prevent sliding (paper p. 2131, p. 2135)", "",
              "| a (g) | t_p (s) | ours | joint | time (s) | paper analytical | UDEC | static (ours) |",
              "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for a, paper, udec in PAPER_FRICTION:
        for tp in durations:
            fd = friction_demand(prepared, StepImpulse.from_g(a, tp))
            lines.append(f"| {a:.1f} | {tp:.2f} | {fd.max_friction_demand:.3f} | {fd.joint} | "
                         f"{fd.time:.3f} | {paper} | {udec} | {fd.static_friction_demand:.3f} |")
    lines += ["", "Joint 7 is the right springing (hinge D). The paper's equivalent static value is "
              "0.50. See docs/thrust-and-friction.md for the assumptions and the comparison."]
    report = out / "friction.md"
    report.write_text("\n".join(lines) + "\n")
    return [fig, report]
