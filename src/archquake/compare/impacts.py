"""The first impact of free rocking: the impact laws against the distinct-element model.

The arch is set rocking by one rectangular ground pulse towards -x (which opens the first
mechanism), sized so that the four-link model's first half cycle peaks at ``target`` times the
crest rotation; after the pulse the ground moves at constant velocity, so the motion is free rocking in
an inertial frame. In the DEM (every voussoir a block, the paper's stiffness and damping):

* the impact is the first zero crossing of the rotation measure (``BlockResult.first_impact_time``);
* the kinetic-energy ratio across it is measured with the mechanical energy (kinetic + potential +
  contact strain, relative to the ground), which carries the kinetic energy through the
  finite-duration impact:  ``c_T = (E(t_i + window) - E_rest) / (E(t_i - window) - E_rest)``,
  E_rest being the settled arch's energy at t = 0 (the rocking arch's potential energy at the
  undisplaced configuration);
* the joints open ``after`` s after the impact (`archquake.compare.dem_hinges`) are set
  beside the mechanism each law selects.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from archquake.compare.snapshots import dem_hinges
from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch

#: Half-width of the window across the DEM impact, s.
DEM_IMPACT_WINDOW = 0.01
#: Half-width of the wide window, s: in the DEM the joints close one after another over tens of
#: milliseconds (Oppenheim's arch: energy steps at -50, -20, 0 and +10 ms around the zero crossing),
#: so the whole impact sequence is measured over +-50 ms as well.
WIDE_WINDOW = 0.05
#: When the DEM's open joints are read after the impact, s (the issue's "~10 ms").
DEM_HINGES_AFTER = 0.01


def _hinge_label(joints, faces) -> str:
    return " ".join(f"{int(j)}{str(getattr(f, 'value', f))[0]}" for j, f in zip(joints, faces))


def rocking_pulse(arch: Arch, *, target: float = 0.35, magnitude_factor: float = 2.0,
                  g: float = STANDARD_GRAVITY):
    """A rectangular pulse towards -x of ``magnitude_factor`` times the static collapse
    acceleration, whose duration makes the four-link model's first half cycle peak at ``target``
    times the crest rotation (bisection on the duration; the first half cycle does not depend on
    the impact law). Returns (Record, duration_s, the four-link model's first impact time_s)."""
    from archquake.dem.studies import bisect, rectangular_pulse
    from archquake.mechanism import PreparedMechanism
    from archquake.mechanism.simulate import (
        simulate,  # the function (the module of its name can shadow it on the package)
    )

    prep = PreparedMechanism.build(arch)
    lam = prep.collapse_acceleration_g
    crit = prep.critical_rotation
    acc = -magnitude_factor * lam * g
    tau = math.sqrt(arch.radius / g)

    def peak(tp):
        r = simulate(prep, rectangular_pulse(acc, tp), restitution=0.0, t_end=tp + 20 * tau, g=g,
                     options=_quiet())
        return float(r.peak_rotation[0]) if r.peak_rotation.size else 0.0

    tp = bisect(lambda d: peak(d) > target * crit, 1e-3 * tau, 2.0 * tau, rtol=1e-3)
    pulse = rectangular_pulse(acc, tp)
    r = simulate(prep, pulse, restitution=0.0, t_end=tp + 20 * tau, g=g, options=_quiet())
    return pulse, tp, float(r.impact_times[0])


def _quiet():
    from archquake.mechanism import SolverOptions

    return SolverOptions(output_interval=0.0)


@dataclass(frozen=True)
class ImpactComparison:
    """One geometry: the impact laws' c_v, c_T and post-impact mechanisms beside the DEM's."""

    label: str
    arch: Arch
    pre_hinges: str
    laws: dict  # law -> {"cv", "ct", "post", "validity", "is_mirror"}
    exact_ct: float
    pulse_duration_s: float
    dem_impact_time_s: float | None
    dem_ct: float | None
    dem_ct_wide: float | None
    dem_hinges_before: str
    dem_hinges_after: str
    dem_energy_error: float
    exact_hinges: str = "-"
    dem_hinges_just_before: str = "-"
    chain_from_dem_pre: dict | None = None

    def to_dict(self) -> dict:
        return {
            "label": self.label,
            "arch": self.arch.describe(),
            "pre_hinges": self.pre_hinges,
            "laws": self.laws,
            "exact_ct": self.exact_ct,
            "pulse_duration_s": self.pulse_duration_s,
            "dem_impact_time_s": self.dem_impact_time_s,
            "dem_ct": self.dem_ct,
            "dem_ct_wide": self.dem_ct_wide,
            "dem_hinges_before": self.dem_hinges_before,
            "dem_hinges_after": self.dem_hinges_after,
            "dem_energy_error": self.dem_energy_error,
            "exact_hinges": self.exact_hinges,
            "dem_hinges_just_before": self.dem_hinges_just_before,
            "chain_from_dem_pre": self.chain_from_dem_pre,
        }


def fourlink_impacts(arch: Arch, pre=None) -> tuple[str, dict, float, str]:
    """(pre-impact hinges, {law: summary}, exact c_T, exact response's hinges) of the four-link
    model's impact laws for ``pre`` (default: the arch's own first mechanism)."""
    from archquake.limit import hinges_of
    from archquake.mechanism.impact import IMPACT_LAWS, solve_impact

    pre = hinges_of(arch) if pre is None else pre
    laws = {}
    exact = float("nan")
    exact_h = "-"
    for law in IMPACT_LAWS:
        sol = solve_impact(pre, law)
        post = sol.post
        laws[law] = {
            "cv": sol.restitution_cv,
            "ct": sol.restitution_ct,
            "post": "-" if post is None else _hinge_label(post.joints, post.faces),
            "validity": sol.validity,
            "is_mirror": None if sol.chain is None else sol.chain.is_mirror,
        }
        if law == "chain" and sol.chain is not None:
            exact = sol.chain.exact_ct
            if sol.chain.exact_hinges:
                exact_h = " ".join(f"{j}{f[0]}" for j, f in sol.chain.exact_hinges)
    return _hinge_label(pre.joints, pre.faces), laws, exact, exact_h


def analytical_impacts(arch: Arch, pre=None) -> tuple[str, dict, float, str]:
    """Deprecated: `fourlink_impacts` under its former name (a DeprecationWarning)."""
    warnings.warn("analytical_impacts is deprecated and will be removed in the next release: "
                  "use fourlink_impacts", DeprecationWarning, stacklevel=2)
    return fourlink_impacts(arch, pre)


def _mechanism_from(arch: Arch, hinges):
    """The HingeMechanism of four DEM hinges [(joint, face)], or None if not admissible."""
    from archquake.errors import InvalidParameterError
    from archquake.geometry.hinges import HingeMechanism

    if len(hinges) != 4 or len({j for j, _ in hinges}) != 4:
        return None
    hinges = sorted(hinges)
    try:
        return HingeMechanism(arch, tuple(j for j, _ in hinges), tuple(f for _, f in hinges))
    except InvalidParameterError:
        return None


def compare_first_impact(arch: Arch, label: str = "", *, target: float = 0.35,
                         window: float = DEM_IMPACT_WINDOW, after: float = DEM_HINGES_AFTER,
                         settings=None, g: float = STANDARD_GRAVITY) -> ImpactComparison:
    """Run the DEM through the first impact of free rocking and set it beside the laws."""
    from archquake.dem import simulate_dem
    from archquake.dem.settings import DemSettings

    pre, laws, exact, exact_h = fourlink_impacts(arch)
    pulse, tp, t_imp = rocking_pulse(arch, target=target, g=g)
    settings = DemSettings() if settings is None else settings
    settings = settings.with_(duration=t_imp * 1.5 + 0.1, output_interval=5e-4,
                              stop_at_collapse=True)
    res = simulate_dem(arch, pulse, settings, g=g)
    ti = res.first_impact_time
    ct = ct_wide = None
    before = after_h = just = "-"
    from_dem = None
    if ti is not None:
        e = res.kinetic + res.potential + res.strain
        e_rest = float(res.potential[0] + res.strain[0])

        def at(t):
            return float(np.interp(t, res.times, e)) - e_rest

        ct = at(ti + window) / at(ti - window)
        ct_wide = at(ti + WIDE_WINDOW) / at(ti - WIDE_WINDOW)
        sel = res.times < ti
        t_peak = float(res.times[sel][np.argmax(np.abs(res.rotation[sel]))])
        before = " ".join(f"{j}{f[0]}" for j, f in dem_hinges(res, t_peak))
        after_h = " ".join(f"{j}{f[0]}" for j, f in dem_hinges(res, ti + after))
        h_just = dem_hinges(res, ti - 2 * window)
        just = " ".join(f"{j}{f[0]}" for j, f in h_just)
        mech = _mechanism_from(arch, h_just) or _mechanism_from(arch, dem_hinges(res, t_peak))
        if mech is not None:
            if mech.load_direction < 0:  # the DEM rotation sense defines "closing"; keep as is
                pass
            p2, laws2, exact2, exact_h2 = fourlink_impacts(arch, mech)
            from_dem = {"pre": p2, "chain_ct": laws2["chain"]["ct"],
                        "chain_post": laws2["chain"]["post"],
                        "chain_validity": laws2["chain"]["validity"], "exact_ct": exact2,
                        "exact_hinges": exact_h2, "paper_ct": laws2["paper"]["ct"],
                        "mirror_ct": laws2["mirror"]["ct"]}
    return ImpactComparison(
        label=label, arch=arch, pre_hinges=pre, laws=laws, exact_ct=exact,
        pulse_duration_s=tp, dem_impact_time_s=ti, dem_ct=ct, dem_ct_wide=ct_wide,
        dem_hinges_before=before, dem_hinges_after=after_h, dem_energy_error=res.energy_error,
        exact_hinges=exact_h, dem_hinges_just_before=just, chain_from_dem_pre=from_dem,
    )


#: The geometries of the docs' table: (label, R m, t m, embrace deg, voussoirs).
IMPACT_GEOMETRIES = (
    ("Oppenheim", 10.0, 1.5, 157.5, 7),
    ("t/R=0.11", 10.0, 1.1, 157.5, 7),
    ("t/R=0.13", 10.0, 1.3, 157.5, 7),
    ("t/R=0.19 (sym)", 10.0, 1.9, 157.5, 7),
    ("142.5 deg (sym)", 10.0, 1.5, 142.5, 7),
    ("semi t=0.6 n=9", 5.0, 0.6, 180.0, 9),
    ("semi t=0.6 n=12", 5.0, 0.6, 180.0, 12),
    ("semi t=0.6 n=15", 5.0, 0.6, 180.0, 15),
    ("semi t=0.6 n=16", 5.0, 0.6, 180.0, 16),
    ("semi t=0.9 n=15", 5.0, 0.9, 180.0, 15),
)


def impact_table(geometries=IMPACT_GEOMETRIES, **kwargs) -> list[ImpactComparison]:
    """`compare_first_impact` over ``geometries`` (label, R, t, embrace deg, n)."""
    out = []
    for label, r, t, emb, n in geometries:
        out.append(compare_first_impact(Arch(r, t, math.radians(emb), n), label, **kwargs))
    return out


def markdown_table(rows: list[ImpactComparison]) -> str:
    """The docs' table: c_T per law beside the DEM's, and the mechanisms after the impact."""
    head = ("| arch | pre-impact hinges | paper c_v / c_T | mirror c_T | chain c_T (validity) "
            "| exact c_T | DEM c_T (+-10 / +-50 ms) | chain from DEM's pre hinges: c_T (exact) |\n|"
            + "---|" * 8)
    lines = [head]
    for r in rows:
        p, m, c = r.laws["paper"], r.laws["mirror"], r.laws["chain"]
        dem = "-" if r.dem_ct is None else f"{r.dem_ct:.2f} / {r.dem_ct_wide:.2f}"
        fd = r.chain_from_dem_pre
        fds = "-" if fd is None else f"{fd['chain_ct']:.3f} ({fd['exact_ct']:.3f})"
        lines.append(
            f"| {r.label} | {r.pre_hinges} | {p['cv']:.3f} / {p['ct']:.3f} | {m['ct']:.3f} "
            f"| {c['ct']:.3f} ({c['validity']}) | {r.exact_ct:.3f} | {dem} | {fds} |"
        )
    return "\n".join(lines)


def hinge_table(rows: list[ImpactComparison]) -> str:
    """Post-impact mechanisms: each law's, the exact response's, and the DEM's open joints."""
    head = ("| arch | paper / mirror post | chain post | exact response turns at | DEM open 10 ms "
            "after | DEM at peak / 20 ms before |\n|" + "---|" * 6)
    lines = [head]
    for r in rows:
        lines.append(
            f"| {r.label} | {r.laws['paper']['post']} | {r.laws['chain']['post']} "
            f"| {r.exact_hinges} | {r.dem_hinges_after} | {r.dem_hinges_before} / "
            f"{r.dem_hinges_just_before} |"
        )
    return "\n".join(lines)


#: (label, R m, t m, embrace deg, voussoirs) of the hinge-migration comparison: the energy kept
#: over the first half cycle and the hinge sequence, fixed hinges (Eq. 4 and the chain law)
#: against the DEM and the rigid chain (`archquake.compare.rigid`), under this module's
#: pulse.
MIGRATION_GEOMETRIES = (
    ("Oppenheim", 10.0, 1.5, 157.5, 7),
    ("t/R=0.13", 10.0, 1.3, 157.5, 7),
    ("semicircle R=5 t=0.9 n=15", 5.0, 0.9, 180.0, 15),
    ("t/R=0.19 (sym)", 10.0, 1.9, 157.5, 7),
)


@dataclass(frozen=True)
class DemHalfCycle:
    """The DEM through its first impact under the comparison's pulse.

    ``kept`` = E(t_i + 10 ms) / E(t_p); ``kept_before`` = E(t_i - 10 ms) / E(t_p) (what the
    swing itself lost); ``sequence``: (t s, open joints) each time the DEM's hinge set
    (`archquake.compare.dem_hinges`, sampled every 5 ms) changes, from t_p to t_i + 0.1 s.
    """

    pulse_duration_s: float
    impact_time_s: float | None
    kept: float | None
    kept_before: float | None
    kept_wide: float | None
    sequence: tuple
    t: np.ndarray
    energy_fraction: np.ndarray
    energy_error: float


def dem_half_cycle(arch: Arch, *, settings=None, window: float = 0.01, g: float = STANDARD_GRAVITY
                   ) -> DemHalfCycle:
    """Run the DEM (the paper's stiffness and damping, no sliding: ``DemSettings()``) through the
    first impact after the comparison's pulse (`rocking_pulse`),
    measuring energy as `compare_first_impact` does."""
    from archquake.dem import simulate_dem
    from archquake.dem.settings import DemSettings

    pulse, tp, t_imp = rocking_pulse(arch, g=g)
    settings = DemSettings() if settings is None else settings
    settings = settings.with_(duration=t_imp * 1.5 + 0.1, output_interval=5e-4,
                              stop_at_collapse=True)
    res = simulate_dem(arch, pulse, settings, g=g)
    return half_cycle_of(res, tp, t_imp, window=window)


def half_cycle_of(res, tp: float, t_imp: float, *, window: float = 0.01) -> DemHalfCycle:
    """The `DemHalfCycle` measures of a recorded run ``res`` (a
    `archquake.blocks.BlockResult`, from the DEM or from the rigid chain,
    `archquake.rigid`) under the comparison's pulse of duration ``tp`` s,
    ``t_imp`` s being the fixed-hinge model's first impact (the end of the hinge sequence when
    the run has none)."""
    ti = res.first_impact_time
    e = res.kinetic + res.potential + res.strain
    e_rest = float(res.potential[0] + res.strain[0])

    def at(t):
        return float(np.interp(t, res.times, e)) - e_rest

    e0 = at(tp)
    seq: list[tuple[float, str]] = []
    for t in np.arange(tp, min(float(res.times[-1]), (ti or t_imp) + 0.1), 0.005):
        h = " ".join(f"{j}{f[0]}" for j, f in dem_hinges(res, t))
        if not seq or seq[-1][1] != h:
            seq.append((round(float(t), 4), h))
    return DemHalfCycle(
        pulse_duration_s=tp, impact_time_s=ti,
        kept=None if ti is None else at(ti + window) / e0,
        kept_before=None if ti is None else at(ti - window) / e0,
        kept_wide=None if ti is None else at(ti + WIDE_WINDOW) / e0,
        sequence=tuple(seq), t=res.times, energy_fraction=(e - e_rest) / e0,
        energy_error=res.energy_error)


def fixed_hinge_kept(arch: Arch) -> dict:
    """c_T of Eq. 4 and of the chain law for the arch's limit-analysis mechanism."""
    _, laws, _, _ = fourlink_impacts(arch)
    return {"paper": laws["paper"]["ct"], "chain": laws["chain"]["ct"]}


__all__ = [
    "DEM_HINGES_AFTER",
    "MIGRATION_GEOMETRIES",
    "DemHalfCycle",
    "dem_half_cycle",
    "fixed_hinge_kept",
    "half_cycle_of",
    "DEM_IMPACT_WINDOW",
    "WIDE_WINDOW",
    "IMPACT_GEOMETRIES",
    "ImpactComparison",
    "analytical_impacts",
    "compare_first_impact",
    "fourlink_impacts",
    "hinge_table",
    "impact_table",
    "markdown_table",
    "rocking_pulse",
]
