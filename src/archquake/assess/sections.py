"""The sections of an assessment, in the order an engineer reads them.

Each section is a pure function ``section(ctx) -> StudyResult`` (the reproduction's result type:
its ``data`` holds every number, its ``figures`` the files it wrote), so the reproduction's
cache stores and resumes it (`archquake.assess.runner`). A later section reads the numbers
of the earlier ones from ``ctx.prior`` (their ``data``), never recomputes them.

Numbers in ``data`` carry their units in the key (``_g``, ``_m``, ``_s``, ``_kg``).
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from archquake import models
from archquake.assess.masses import carried_masses
from archquake.assess.site import section_code_check
from archquake.constants import STANDARD_GRAVITY
from archquake.ground.measures import strong_motion_end
from archquake.parallel import interruptible_pool, usable_cores
from archquake.reproduce.core import Figure, StudyResult

#: The assumptions every verdict rests on.
ASSUMPTIONS = ("rigid blocks", "no tension at the joints", "infinite compressive strength",
               "in-plane motion only", "no backfill or spandrel walls")
#: The last assumption for an arch that carries loads (docs/loads.md): the fill as columns.
LOADS_ASSUMPTION = ("the fill as columns riding on the voussoirs (weight and horizontal inertia "
                    "at each column's centroid; no arching, no shear between columns, no passive "
                    "pressure), no spandrel walls")


def assumptions(config) -> tuple[str, ...]:
    """The assumptions every verdict on ``config``'s arch rests on: `ASSUMPTIONS`, the
    last one the fill's model when the arch carries loads (`LOADS_ASSUMPTION`)."""
    if getattr(config, "loads", None) is None:
        return ASSUMPTIONS
    return ASSUMPTIONS[:-1] + (LOADS_ASSUMPTION,)


def rigid_scan_ceiling(lam_g: float, site_g: float | None) -> float:
    """The ceiling of the rigid chain's scans in an assessment (its pulse domains and its IDA),
    g: max(1 g, 4 x the site PGA, 6 lambda), at most 5 g (5 g without a site PGA).

    In the IDA, every level above the first collapse is filled up to the ceiling (hunt-and-fill
    looks for resurrections): up to 5 g that was 32 of the 40 levels of a record on the bridge
    example (first collapse 0.107 g), 13 of them above 1 g, where nothing bears on a verdict at
    a site PGA of 0.15 g. A record that does not collapse up to the ceiling is censored there
    by the fragility fit, as before at 5 g.

    The coarse scan is geometric from lambda to its ceiling with a fixed number of magnitudes,
    so the ceiling sets its spacing. Up to 5 g, 8 magnitudes on the bridge example (lambda =
    0.049 g) are 1.78 apart and the first one, 0.087 g, fell in a survival window 0.7 mg wide
    above a band that collapses from 0.065 g (t_p = 0.331 s): the quick search reported 0.0955
    g. Up to 1 g the same 8 magnitudes are 1.46 apart, and at the same cost the quick search's
    boundaries lie within its 0.01 g precision of a 60-magnitude scan at all six durations of
    both families (docs/notes/measurements.md). A boundary above the ceiling
    (only the shortest pulses, far above the site PGA) is reported as none found."""
    if site_g is None:
        return 5.0
    return float(min(5.0, max(1.0, 4.0 * site_g, 6.0 * lam_g)))


@dataclass(frozen=True)
class Mode:
    """How fine each part of the assessment is (``quick`` or full)."""

    quick: bool

    @property
    def durations(self) -> np.ndarray:
        """Pulse durations of the failure domains (t_p of the step, T of the sine), s."""
        return np.geomspace(0.1, 2.0, 6 if self.quick else 14)

    @property
    def domain_settings(self):
        from archquake.domains import DomainSettings

        if self.quick:
            return DomainSettings(coarse_points=16, fine_points=6, precision_g=5e-3)
        return DomainSettings(coarse_points=40, fine_points=20, precision_g=2e-3)

    def rigid_domain_settings(self, lam_g: float, site_g: float | None):
        """The domain search of the rigid chain (one time history per point): coarser than the
        four-link batch's, and scanned from lambda (``lam_g``, g) up to
        `rigid_scan_ceiling`, so that its magnitudes fall where the verdict is decided."""
        from archquake.domains import DomainSettings

        top = rigid_scan_ceiling(lam_g, site_g)
        if self.quick:
            return DomainSettings(max_magnitude_g=top, scan_reference_g=top, coarse_points=8,
                                  fine_points=4, precision_g=1e-2, early=False)
        return DomainSettings(max_magnitude_g=top, scan_reference_g=top, coarse_points=16,
                              fine_points=8, precision_g=5e-3, early=False)


    def records(self, records: tuple) -> tuple:
        """The records analysed: all of them, or four spread over the suite (quick)."""
        if not self.quick or len(records) <= 4:
            return tuple(records)
        step = len(records) / 4
        return tuple(records[int(k * step)] for k in range(4))

    @property
    def ida(self) -> dict:
        return {"precision": 0.05, "fill": 0.25} if self.quick else {"precision": 0.02,
                                                                      "fill": 0.10}

    @property
    def bootstrap(self) -> int:
        return 200 if self.quick else 1000

    @property
    def dem_factors(self) -> tuple[float, ...]:
        """Fractions of the model's collapse level at which the DEM runs."""
        return (0.85,) if self.quick else (1.0, 0.85, 0.7)


@dataclass(frozen=True)
class Context:
    """What a section needs: the configuration, the arch, the mode, where figures go, and
    the data of the sections before it (by name)."""

    config: Any
    arch: Any
    mode: Mode
    figures: Path
    out: Path
    prior: dict = field(default_factory=dict)
    progress: Callable[[str], None] | None = None
    #: Hands a value of this section's data to the sections side by side that read it with
    #: `early` before this section is done (the runner's; None: nobody reads early).
    share_to: Callable[[str, Any], None] | None = None

    def share(self, key: str, value: Any) -> None:
        """Hand ``key`` of this section's data (the value its result will hold) to the
        sections that wait for it (`early`), before this section is done."""
        if self.share_to is not None:
            self.share_to(key, value)

    def early(self, name: str, key: str, default: Any = None) -> Any:
        """``key`` of section ``name``'s data: side by side, as soon as that section shares it
        (`share`) or is done; ``default`` if it does not run or holds no such key."""
        reader = getattr(self.prior, "early", None)
        if reader is not None:
            return reader(name, key, default)
        return self.prior.get(name, {}).get(key, default)

    def say(self, line: str) -> None:
        if self.progress is not None:
            self.progress(line)

    def counter(self, what: str, total: int) -> Progress:
        """A `Progress` of ``total`` items (``what``: their name) through `say`."""
        return Progress(self.say if self.progress is not None else None, what, total)

    @property
    def site(self) -> float | None:
        return self.config.site_pga_g

    @property
    def loads(self):
        """What the arch carries in every section (the ``[loads]`` table without its traffic),
        or None."""
        return self.config.dead_loads

    def rigid_body(self):
        """What the rigid chain and the DEM run: the arch, or with loads its assembly whose
        blocks carry them (`archquake.ida.batch.rigid_body`: one object for the whole
        assessment, its IDA's rounds included)."""
        from archquake.ida.batch import rigid_body

        return rigid_body(self.arch, self.loads)

    def collapse_acceleration_g(self) -> float:
        """lambda, g: the equivalent static analysis's, with the loads when the arch carries
        them (`archquake.limit.loaded`)."""
        if self.loads is None:
            from archquake.limit import hinges_of
            from archquake.limit.static import collapse_state

            return float(collapse_state(hinges_of(self.arch))[0])
        from archquake.limit.loaded import loaded_collapse, seismic_case

        return float(loaded_collapse(seismic_case(self.arch, self.loads)).multiplier)


class Progress:
    """Progress of one step on the ``say`` line: ``what: done/total, about N s left``, once the
    step has run for `QUIET_S` seconds and then at most every `EVERY_S` seconds,
    and when it ends; nothing for a step shorter than that. The time left is the time per item
    so far times the items left (``total`` may be an estimate, raised if passed, and said to
    be one).

    Call it with the number of items done (and the total, if it changed)."""

    QUIET_S = 2.0
    EVERY_S = 10.0

    def __init__(self, say: Callable[[str], None] | None, what: str, total: int,
                 *, estimate: bool = False, clock: Callable[[], float] | None = None):
        self._say = say
        self._what = what
        self._total = max(int(total), 1)
        self._estimate = estimate
        self._clock = time.perf_counter if clock is None else clock
        self._start = self._clock()
        self._last = -math.inf  # the first line comes once QUIET_S has passed
        self._lock = threading.Lock()
        self._done = 0

    def __enter__(self) -> Progress:
        """While the step runs, a line every `EVERY_S` seconds even when no item has
        finished since (the first items of a step may take minutes: a line that says how many
        are done and for how long the step has run)."""
        self._stop = threading.Event()

        def beat() -> None:
            while not self._stop.wait(self.EVERY_S):
                self(self._done)

        if self._say is not None:
            threading.Thread(target=beat, daemon=True, name="progress").start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()

    def __call__(self, done: int, total: int | None = None) -> None:
        if self._say is None:
            return
        with self._lock:
            self._done = max(self._done, int(done))
            done = self._done
            if total is not None:  # an estimate is only raised by the work found
                self._total = (max(int(total), self._total) if self._estimate
                               else max(int(total), 1))
            if done > self._total:  # an estimate passed: the rest is unknown, say so
                self._total = int(done * 1.25) + 1
                self._estimate = True
            now = self._clock()
            elapsed = now - self._start
            end = done >= self._total and not self._estimate
            if elapsed < self.QUIET_S or (now - self._last < self.EVERY_S and not end):
                return
            self._last = now
            line = f"  {self._what}: {done}/{'~' if self._estimate else ''}{self._total}"
            if end:
                line += f", done in {elapsed:.0f} s"
            elif done > 0:
                left = elapsed / done * (self._total - done)
                line += f", about {_duration(left)} left"
            else:
                line += f", running for {_duration(elapsed)}"
            self._say(line)


def _duration(seconds: float) -> str:
    """``'45 s'``, ``'3 min'``, for a time left."""
    return f"{seconds:.0f} s" if seconds < 90 else f"{seconds / 60:.0f} min"


def prepared_mechanism(arch, impact: str = "paper", loads=None):
    """The arch's prepared mechanism under its impact law, its links carrying ``loads`` (a
    prescribed c_v is passed to each analysis as ``restitution=``, so that the law's validity
    and the verdict's dependence on it are judged in one place:
    `archquake.outcome.qualify`)."""
    from archquake.mechanism.prepared import PreparedMechanism

    if loads is None:
        return PreparedMechanism.build(arch, impact)
    return PreparedMechanism.build(arch, impact, loads=loads)


def used_restitution(config, arch) -> tuple[float, Any]:
    """c_v the time histories use (prescribed, or the law's clipped at 0) and the law's own
    `ImpactSolution`."""
    own = prepared_mechanism(arch, config.impact, config.dead_loads).impact
    cv = config.restitution if config.restitution is not None else max(own.restitution_cv, 0.0)
    return float(cv), own


def dynamics_refusal(arch, model: str = "rigid") -> str | None:
    """Why the time histories (pulses, records, DEM check) cannot run on ``arch`` with
    ``model``, or None.

    The chain of rigid voussoirs (``rigid``) takes any arch. The four-link model switches to
    the mirror-image mechanism after each impact, which exists only for a symmetric chain
    (`VoussoirChain.symmetric`, docs/geometry.md); with it a surveyed asymmetric arch
    gets its static capacity and this one-line reason instead."""
    if models.spec(model).blocks or getattr(arch, "symmetric", True):
        return None
    return ("the arch is not symmetric about x = 0 (blocks from a file): the four-link model "
            "switches to the mirror-image mechanism after each impact, which exists only for a "
            "symmetric arch, so the pulse, record and DEM sections are not run; the static "
            "capacity (section 2) stands (model = \"rigid\" runs them)")


def _num(x) -> float | None:
    return float(x) if x is not None and math.isfinite(float(x)) else None


def workers() -> int:
    return max(1, usable_cores())


# ----------------------------------------------------------------------------- 1. the arch
def section_arch(ctx: Context) -> StudyResult:
    from matplotlib.figure import Figure as MplFigure

    from archquake.plotting.arch import plot_arch
    from archquake.plotting.figures import save

    arch = ctx.arch
    masses = np.asarray(arch.voussoir_masses)
    cents = np.asarray(arch.voussoir_centroids)
    pts = np.vstack([np.asarray(p) for p in arch.block_polygons])
    width = float(np.ptp(pts[:, 0]))
    height = float(np.ptp(pts[:, 1]))
    desc = arch.describe()
    fig = MplFigure(figsize=(8, 5))
    ax = fig.subplots()
    plot_arch(arch, ax)
    loads = ctx.config.loads
    carried = None
    if loads is not None:
        from archquake.geometry.loads import block_extras
        from archquake.plotting.arch import draw_loads

        carried = block_extras(arch, ctx.loads) if ctx.loads is not None else None
        if carried is not None:
            draw_loads(ax, arch, carried, ctx.loads)
        if loads.traffic is not None:
            draw_traffic(ax, arch, carried, loads.traffic)
        ax.legend(loc="upper left", fontsize=7, frameon=False)
    for k, c in enumerate(cents):
        ax.text(c[0], c[1], str(k + 1), ha="center", va="center", fontsize=7)
    x0, x1 = float(pts[:, 0].min()), float(pts[:, 0].max())
    y0, y1 = float(pts[:, 1].min()), float(pts[:, 1].max())
    if carried is not None and carried.surface is not None:
        y1 = max(y1, float(carried.surface))
    if loads is not None:  # room above for the loads' arrows
        y1 += 0.12 * float(arch.radius)
    ax.annotate("", (x0, y0 - 0.08 * height), (x1, y0 - 0.08 * height),
                arrowprops={"arrowstyle": "<->", "color": "k"})
    ax.text(0.5 * (x0 + x1), y0 - 0.12 * height, f"overall width {width:.2f} m", ha="center",
            va="top", fontsize=8)
    ax.annotate("", (x1 + 0.05 * width, y0), (x1 + 0.05 * width, y1),
                arrowprops={"arrowstyle": "<->", "color": "k"})
    ax.text(x1 + 0.07 * width, 0.5 * (y0 + y1), f"overall height\n{height:.2f} m", va="center",
            fontsize=8)
    dims = ", ".join(f"{k.removesuffix('_m')} {v:.3g} m" for k, v in desc.items()
                     if k.endswith("_m") and k not in ("depth_m", "length_scale_m"))
    ax.set_title(f"{desc.get('shape', 'circular')} arch: {dims}", fontsize=9)
    ax.set_xlim(x0 - 0.1 * width, x1 + 0.25 * width)
    ax.set_ylim(y0 - 0.2 * height, y1 + 0.08 * height)
    save(fig, ctx.figures / "arch.png", dpi=120)
    blocks = [{"block": k + 1, "mass_kg": float(m), "centroid_x_m": float(c[0]),
               "centroid_y_m": float(c[1])} for k, (m, c) in enumerate(zip(masses, cents,
                                                                            strict=True))]
    data = {"describe": desc, "blocks": blocks, "total_mass_kg": float(masses.sum()),
            "overall_width_m": width, "overall_height_m": height,
            "friction_coefficient": ctx.config.friction,
            "density_kg_m3": float(ctx.config.arch.density), "depth_m": float(ctx.config.arch.depth)}
    caption = "The arch: blocks numbered from the left springing, with its overall dimensions."
    if loads is not None:
        data["loads"] = loads.to_dict()
        data["masses"] = carried_masses(arch, ctx.loads)
        caption = ("The arch and what it carries: blocks numbered from the left springing, the "
                   "fill columns shaded under the fill surface, the backing's top, the loads on "
                   "the extrados" + (" and the traffic load (at the position the file gives; "
                                     "the traffic check moves it along the span)"
                                     if loads.traffic is not None else "") + ".")
    return StudyResult("arch", "1. The arch", (), (Figure("arch.png", caption),), (), data)


def draw_traffic(ax, arch, carried, traffic) -> None:
    """The traffic load's arrow (an axle) or bar (a patch) above the fill, at its position."""
    from archquake.geometry.loads import Extrados

    ex = Extrados.of(arch)
    x = ex.x0 + traffic.position
    top = (carried.surface if carried is not None and carried.surface is not None
           else float(arch.crown_point[1]))
    r = float(arch.radius)
    if traffic.length > 0:
        ax.plot([x - 0.5 * traffic.length, x + 0.5 * traffic.length], [top + 0.05 * r] * 2,
                color="tab:red", linewidth=3, label=f"traffic {traffic.load / 1e3:g} kN/m")
    else:
        ax.annotate("", (x, top), (x, top + 0.2 * r),
                    arrowprops={"arrowstyle": "-|>", "color": "tab:red", "linewidth": 2})
        ax.plot([], [], color="tab:red", label=f"axle {traffic.load / 1e3:g} kN/m")


# ----------------------------------------------------------------------------- 2. statics
def section_static(ctx: Context) -> StudyResult:
    from archquake.errors import InvalidParameterError
    from archquake.limit import geometric_safety_factor, limit_analysis, min_thickness
    from archquake.plotting.arch import save_limit_analysis

    loads = ctx.loads
    la = limit_analysis(ctx.arch) if loads is None else limit_analysis(ctx.arch, loads=loads)
    try:
        if loads is None:
            t_min: float | None = min_thickness(ctx.arch)
            fos: float | None = geometric_safety_factor(ctx.arch)
        else:  # the ring thinned under the same fill surface and loads
            from archquake.limit.loaded import min_thickness_loaded

            t_min = float(min_thickness_loaded(ctx.arch, loads))
            fos = float(ctx.arch.thickness) / t_min
        t_min_note = None
    except InvalidParameterError as exc:  # blocks from a file: no ring thickness to vary
        t_min = fos = None
        t_min_note = str(exc)
    save_limit_analysis(la, ctx.figures / "static.png")
    demand = la.min_friction
    mu = ctx.config.friction
    data = {
        "collapse_acceleration_g": la.collapse_acceleration_g,
        "hinges": [h.to_dict() for h in la.mechanism.hinges],
        "symmetric": la.symmetric,
        "thickness_m": float(ctx.arch.thickness),
        "min_thickness_m": t_min,
        "geometric_safety_factor": fos,
        "min_thickness_note": t_min_note,
        "static_friction_demand": demand,
        "static_friction_joint": la.min_friction_joint,
        "friction_coefficient": mu,
        "sliding": bool(demand > mu),
        "thrust_x_m": la.thrust_line[:, 0], "thrust_y_m": la.thrust_line[:, 1],
    }
    if loads is not None:
        data["loads"] = la.to_dict().get("loads")
    if ctx.site is not None:
        data["site_over_lambda"] = ctx.site / la.collapse_acceleration_g
    return StudyResult("static", "2. Static capacity", (),
                       (Figure("static.png", "The four-hinge mechanism at the collapse "
                               "acceleration lambda (load towards +x) and its line of thrust."),),
                       (), data)


# ----------------------------------------------------------------------------- traffic
#: Positions of the traffic check's scan along the span (quick, full).
TRAFFIC_POSITIONS = {True: 26, False: 51}


def section_traffic(ctx: Context) -> StudyResult:
    """The traffic check: the ``[loads]`` table's traffic moved along the clear span over the
    dead loads (`archquake.limit.capacity.capacity_scan`); its least collapse multiplier
    is the adequacy factor, at the critical position analysed again with both bounds."""
    from matplotlib.figure import Figure as MplFigure

    from archquake.limit.capacity import capacity_scan
    from archquake.plotting.figures import DRAWING, save
    from archquake.plotting.loads import plot_capacity, plot_capacity_scan

    loads = ctx.config.loads
    traffic = loads.traffic
    scan = capacity_scan(ctx.arch, loads, traffic, TRAFFIC_POSITIONS[ctx.mode.quick])
    crit = scan.critical
    data = scan.to_dict()
    data.update({"load_kN_m": traffic.load / 1e3, "kind": "axle" if traffic.length == 0
                 else f"patch {traffic.length:g} m long",
                 "dispersion_deg": traffic.dispersion, "boussinesq": traffic.boussinesq,
                 "positions": int(scan.positions_m.size),
                 "collapse_load_kN_m": crit.collapse_load_N_m / 1e3,
                 "hinge_joints": list(crit.mechanism.joints)})
    with DRAWING:  # the figures of sections run side by side, one at a time
        fig = MplFigure(figsize=(13, 4.8))
        a1, a2 = fig.subplots(1, 2)
        plot_capacity(crit, a1)
        plot_capacity_scan(scan, a2)
        fig.tight_layout()  # room for the two-line title
        save(fig, ctx.figures / "traffic.png", dpi=110)
    return StudyResult("traffic", "Traffic check", (),
                       (Figure("traffic.png", "The traffic load at its critical position: the "
                               "collapse mechanism and line of thrust over the fill (left), and "
                               "its collapse multiplier against its position along the span "
                               "(right)."),), (), data)


# ----------------------------------------------------------------------------- 3. pulses
def _domain_data(d, site: float | None) -> dict:
    coll = np.asarray(d.collapse_g, dtype=float)
    out = {"durations_s": d.durations, "no_hinging_g": d.no_hinging_g,
           "first_half_cycle_g": d.first_half_cycle_g, "collapse_g": coll,
           "non_monotonic_bands": [b.to_dict() for b in d.non_monotonic_bands],
           "restitution_cv": _num(d.restitution_cv), "evaluations": d.evaluations,
           "min_collapse_g": _num(np.nanmin(coll)) if np.any(np.isfinite(coll)) else None}
    if site is not None:
        below = np.isfinite(coll) & (coll <= site)
        out["durations_collapsing_at_site_s"] = d.durations[below]
        # a non-monotonic band reaching below the site PGA also counts: a pulse in it collapses
        out["collapses_at_site"] = bool(np.any(below))
    return out


def pulse_domains(ctx: Context, cv: float | None) -> dict:
    """Step and sine failure domains (FailureDomain objects) of the configuration's model: the
    rigid chain's governing boundary (every voussoir a block, searched by
    `archquake.compare.dem_failure_domain` with ``model='rigid'``: batches of
    `archquake.rigid.verdict.rigid_verdicts`, threaded), or the four-link model's at
    restitution ``cv``."""
    if models.takes(ctx.config.model, "guard"):  # batches of the chain's verdicts, threaded
        from archquake.compare import dem_failure_domain

        lam = ctx.collapse_acceleration_g()
        settings = ctx.mode.rigid_domain_settings(lam, ctx.site)
        n = ctx.mode.durations.size
        guess = n * (settings.coarse_points + 2 * settings.fine_points)  # about, per family
        out = {}
        for fam in ("step", "sine"):
            with Progress(ctx.say if ctx.progress is not None else None,
                          f"{fam} domain time histories", guess, estimate=True) as tick:
                out[fam] = dem_failure_domain(ctx.arch, fam, ctx.mode.durations,
                                              settings=settings, governing_only=True,
                                              model="rigid", progress=tick,
                                              **({} if ctx.loads is None
                                                 else {"loads": ctx.loads})).domain
        return out
    from archquake.domains import failure_domain

    prep = prepared_mechanism(ctx.arch, ctx.config.impact, ctx.loads)
    prescribed = ctx.config.restitution is not None or cv != prep.restitution
    return {fam: failure_domain(prep, fam, ctx.mode.durations,
                                settings=ctx.mode.domain_settings,
                                restitution=cv if prescribed else None, model="fourlink")
            for fam in ("step", "sine")}


def section_pulses(ctx: Context) -> StudyResult:
    from matplotlib.figure import Figure as MplFigure

    from archquake.plotting.domains import plot_domain
    from archquake.plotting.figures import DRAWING, save

    rigid = models.spec(ctx.config.model).blocks
    cv = None if rigid else used_restitution(ctx.config, ctx.arch)[0]
    domains = pulse_domains(ctx, cv)
    data: dict[str, Any] = {"model": ctx.config.model, "restitution_cv": cv}
    with DRAWING:  # the figures of sections run side by side, one at a time
        figs = []
        for fam, d in domains.items():
            ctx.say(f"  {fam} domain: {d.evaluations} time histories")
            data[fam] = _domain_data(d, ctx.site)
            fig = MplFigure(figsize=(7, 4.6))
            ax = fig.subplots()
            plot_domain(d, ax, title=f"{fam} pulse, " + ("chain of rigid voussoirs" if rigid
                                                          else f"c_v = {cv:.3g}"))
            if ctx.site is not None:
                ax.axhline(ctx.site, color="crimson", ls="--", lw=1.5,
                           label=f"site PGA {ctx.site:.3g} g")
                ax.legend(loc="upper right", fontsize=7)
            save(fig, ctx.figures / f"domain_{fam}.png", dpi=120)
            figs.append(Figure(f"domain_{fam}.png", f"Failure domain of the {fam} pulse (magnitude "
                               f"against {'t_p' if fam == 'step' else 'T'}), site PGA dashed."))
    return StudyResult("pulses", "3. Pulses", (), tuple(figs), (), data)


# ----------------------------------------------------------------------------- 4. records
def _p_at_site_ci(first: np.ndarray, ceiling: float, site: float, n: int,
                  confidence: float = 0.9) -> tuple[float, float] | None:
    """Percentile-bootstrap interval of P(collapse | site PGA) over the records (resampled
    with replacement, the first-collapse fit refitted each time)."""
    from archquake.errors import ArchquakeError
    from archquake.ida.fragility import fit_first_collapse

    rng = np.random.default_rng(0)
    ps = []
    for _ in range(n):
        sample = first[rng.integers(0, first.size, first.size)]
        try:
            fit = fit_first_collapse(list(sample), ceiling=ceiling, bootstrap=0)
        except ArchquakeError:
            continue
        ps.append(float(fit.probability(site)))
    if len(ps) < max(10, n // 2):
        return None
    q = [50 * (1 - confidence), 50 * (1 + confidence)]
    lo, hi = np.percentile(ps, q)
    return float(lo), float(hi)


#: About how many runs the IDA takes per record (hunt, bracket and fill), quick and full: 94
#: runs for the bridge's four records in quick mode, 1444 for its 28 in full mode at a 1 g
#: ceiling (docs/notes/measurements.md). Only the progress lines' estimate of the time left.
IDA_RUNS_PER_RECORD = {True: 24, False: 52}


def _ida_progress(ctx: Context, records: int) -> Callable[[int, int, int], None]:
    """The IDA's ``progress(stored, total_so_far, round)`` as a `Progress` of runs:
    the total grows as hunt-and-fill proposes levels, so the line's total is an estimate
    (`IDA_RUNS_PER_RECORD`), raised when the work found passes it."""
    tick = Progress(ctx.say if ctx.progress is not None else None, "IDA runs",
                    records * IDA_RUNS_PER_RECORD[ctx.mode.quick], estimate=True)
    return lambda done, total, rounds: tick(done, total)


def run_ida(ctx: Context, restitution: float | None, *, bootstrap: int | None = None,
            analysed: Callable[[Any, Any, Any, Any], None] | None = None):
    """The IDA in PGA of the mode's records (all, or four in quick mode) with the
    configuration's model (the four-link model at ``restitution``, None: the impact law's
    own), its runs kept in a SQLite store under ``out/cache`` named by
    the input's digest, the restitution and the mode (so an interrupted run resumes them).

    ``analysed(suite, records, partial, first_fit)``, if given, is called once every record's
    first collapse is settled, while the IDA goes on above them (its ``first_collapses``):
    ``partial`` the analysis so far, whose first collapses are the result's, and
    ``first_fit`` the first-collapse fit without its interval (None if it cannot be made).

    Returns
    -------
    (suite, records, IDAResult, fits)
        ``fits`` as `archquake.ida.fragility.fragility_of` gives them.
    """
    from archquake.ground.suites import load_suite
    from archquake.ida import incremental_dynamic_analysis
    from archquake.ida.fragility import fragility_of
    from archquake.sweeps import CaseOptions, ResultStore

    cfg = ctx.config
    suite = load_suite(list(cfg.suite) if isinstance(cfg.suite, tuple) else cfg.suite,
                       units=cfg.units)
    records = ctx.mode.records(suite.records)
    fourlink = models.takes(cfg.model, "restitution")
    options = (CaseOptions(restitution=restitution, impact=cfg.impact) if fourlink
               else CaseOptions())
    tag = "" if restitution == cfg.restitution else f"-cv{restitution:.4g}"
    store_path = (ctx.out / "cache" /
                  f"ida-{cfg.digest}{tag}-{'quick' if ctx.mode.quick else 'full'}.sqlite")
    store_path.parent.mkdir(parents=True, exist_ok=True)
    ctx.say(f"  IDA of {len(records)} of the {len(suite.records)} records of {suite.name}"
            + (f" at c_v = {restitution:.3g}" if tag else "") + f" (store {store_path.name})")
    loaded: dict[str, Any] = {} if ctx.loads is None else {"loads": ctx.loads}
    if analysed is not None:
        def first_collapses(partial) -> None:
            from archquake.errors import InvalidParameterError
            from archquake.ida.fragility import fit_first_collapse

            try:  # the fragility below makes it again from its memo
                first_fit = fit_first_collapse(partial.first_collapse_levels.tolist(),
                                               ceiling=partial.ceiling)
            except InvalidParameterError:
                first_fit = None
            analysed(suite, records, partial, first_fit)

        loaded["first_collapses"] = first_collapses
    if models.takes(cfg.model, "guard"):  # one threaded batch of verdicts per round, here
        lam = ctx.collapse_acceleration_g()
        with ResultStore(store_path) as store:
            res = incremental_dynamic_analysis(cfg.arch, records, "pga", store, options=options,
                                               model=cfg.model,
                                               ceiling=rigid_scan_ceiling(lam, ctx.site),
                                               **loaded,
                                               progress=_ida_progress(ctx, len(records)),
                                               **ctx.mode.ida)
    else:
        n = workers()
        with ResultStore(store_path) as store, interruptible_pool(n) as executor:
            res = incremental_dynamic_analysis(cfg.arch, records, "pga", store, options=options,
                                               model=cfg.model, executor=executor, workers=n,
                                               **loaded,
                                               progress=_ida_progress(ctx, len(records)),
                                               **ctx.mode.ida)
    fits = fragility_of(res, rng=np.random.default_rng(0),
                        bootstrap=ctx.mode.bootstrap if bootstrap is None else bootstrap)
    return suite, records, res, fits


def records_axis_top(first_g, site_g: float | None, ceiling_g: float) -> float:
    """The top of the records figure's PGA axes, g: where the first collapses and the site PGA
    are (1.25 x the largest first collapse, at least 1.5 x the site PGA), not the IDA's
    ceiling, at most that ceiling. Without a first collapse, the ceiling.

    Examples
    --------
    >>> records_axis_top([0.08, 0.11, float("nan")], 0.18, 1.0)
    0.27
    >>> records_axis_top([float("nan")], 0.18, 1.0)
    1.0
    """
    first = np.asarray(first_g, dtype=float)
    finite = first[np.isfinite(first)]
    if finite.size == 0:
        return float(ceiling_g)
    top = 1.25 * float(finite.max())
    if site_g is not None:
        top = max(top, 1.5 * float(site_g))
    return float(min(top, ceiling_g))


def _fit_records_axes(a1, a2, res, site: float | None, named: int = 3) -> float:
    """The records figure read at a glance: PGA axes fitted to the data
    (`records_axis_top`), the ``named`` records that collapse first named at their first
    collapse, legends below the axes. Returns the axes' top, g."""
    first = np.asarray(res.first_collapse_levels, dtype=float)
    top = records_axis_top(first, site, res.ceiling)
    a1.set_ylim(0.0, 1.02 * top)
    a2.set_xlim(0.0, 1.02 * top)
    order = [int(i) for i in np.argsort(np.where(np.isfinite(first), first, np.inf))
             if np.isfinite(first[i])][:named]
    placed: list[float] = []
    for i in order:
        y = float(first[i])
        while any(abs(y - p) < 0.045 * top for p in placed):
            y += 0.045 * top
        placed.append(y)
        a1.annotate(res.records[i].name, xy=(1.0, float(first[i])), xytext=(0.55, y),
                    fontsize=6.5, va="center", ha="right",
                    bbox={"fc": "white", "ec": "0.7", "lw": 0.5, "pad": 1.5, "alpha": 0.9},
                    arrowprops={"arrowstyle": "-", "color": "0.5", "lw": 0.6})
    for ax in (a1, a2):
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=7,
                  frameon=False)
    return top


def section_records(ctx: Context) -> StudyResult:
    from matplotlib.figure import Figure as MplFigure

    from archquake.plotting.figures import DRAWING, save
    from archquake.plotting.ida import plot_fragility, plot_ida_curves

    cfg = ctx.config
    cv = used_restitution(cfg, ctx.arch)[0] if models.takes(cfg.model, "restitution") else None
    # the prescribed c_v, or None: the law's own, whose validity then qualifies each verdict
    governing: list = []

    def analysed(suite, records, res, first_fit) -> None:
        # the DEM check and the validity section wait for it: known once every record's first
        # collapse is, while the IDA fills the levels above them
        governing.append(_governing(suite, records, res, first_fit))
        ctx.share("governing", governing[0])

    suite, records, res, fits = run_ida(ctx, cfg.restitution, analysed=analysed)
    with DRAWING:  # the figures of sections run side by side, one at a time
        fig = MplFigure(figsize=(12, 6.0))
        a1, a2 = fig.subplots(1, 2)
        plot_ida_curves(res, a1)
        plot_fragility(res, fits, a2)
        first = res.first_collapse_levels
        data: dict[str, Any] = {
            "suite": suite.name, "records_in_suite": len(suite.records),
            "records_used": [r.name for r in res.records], "model": cfg.model,
            "restitution_cv": cv,
            "ceiling_g": res.ceiling, "runs": res.total,
            "first_collapse_g": [_num(x) for x in first],
            "records_collapsing": int(np.sum(np.isfinite(first))),
            "records_with_resurrections": sum(1 for r in res.records if r.resurrections),
            "fragility": {k: (None if fits[k] is None else fits[k].to_dict("g"))
                          for k in ("first_collapse", "collapse_fraction")},
        }
        fit = fits["first_collapse"]
        if ctx.site is not None:
            for ax in (a1, a2):
                (ax.axhline if ax is a1 else ax.axvline)(ctx.site, color="crimson", ls="--",
                                                          label=f"site PGA {ctx.site:.3g} g")
            data["fraction_collapsing_at_site"] = float(res.collapse_fraction([ctx.site])[0])
            if fit is not None:
                data["p_collapse_at_site"] = float(fit.probability(ctx.site))
                ci = _p_at_site_ci(first, res.ceiling, ctx.site, ctx.mode.bootstrap)
                data["p_collapse_at_site_ci"] = None if ci is None else list(ci)
                data["p_collapse_confidence"] = 0.9
        data["axis_top_g"] = _fit_records_axes(a1, a2, res, ctx.site)
        save(fig, ctx.figures / "records.png", dpi=110)
    data["governing"] = governing[0]
    return StudyResult("records", "4. Records", (),
                       (Figure("records.png", "IDA curves (left: PGA against peak rotation over "
                               "the crest rotation; the records that collapse first named) and "
                               "the fragility curves (right), site PGA dashed; PGA axes cut at "
                               f"{data['axis_top_g']:.3g} g (the IDA ran up to "
                               f"{res.ceiling:.3g} g)."),), (), data)


def _governing(suite, records, res, fit) -> dict | None:
    """The governing record of an IDA: the one whose first collapse is nearest the median of
    the first-collapse fit ``fit`` (None without a fit or a collapse)."""
    first = res.first_collapse_levels
    if fit is None or not np.any(np.isfinite(first)):
        return None
    i = int(np.nanargmin(np.where(np.isfinite(first), np.abs(np.log(first / fit.median)),
                                  np.nan)))
    rec = res.records[i]
    assert rec.first_collapse is not None  # its first-collapse level is finite
    return {"record": rec.name, "index": int(suite.records.index(records[i])),
            "first_collapse_g": float(first[i]), "survives_below_g": _num(rec.first_collapse.below),
            "pga_unscaled_g": float(rec.im_unscaled)}


# ----------------------------------------------------------------------------- the vertical
def section_vertical(ctx: Context) -> StudyResult:
    """What the vertical ground motion changes, side by side with the runs without it: the
    least collapsing step magnitude at the mode's durations under the pulses' vertical part
    (``[seismic] vertical_ratio``) and without it, on a grid 2 % apart (4 % quick) from lambda
    up to the records' ceiling or the vertical's lift-off; and each record that carries its
    vertical component: its first collapsing PGA in the records section (both components scaled
    together) beside the IDA of its horizontal alone."""
    from archquake.ground.base import has_vertical, lift_off_factor
    from archquake.ground.pulses import StepImpulse

    cfg = ctx.config
    data: dict[str, Any] = {"model": cfg.model, "vertical_ratio": cfg.vertical_ratio}
    lam = ctx.collapse_acceleration_g()
    if cfg.vertical_ratio:
        ratio = float(cfg.vertical_ratio)
        top = rigid_scan_ceiling(lam, ctx.site)
        lift = lift_off_factor(StepImpulse.from_g(1.0, 1.0, vertical=ratio), STANDARD_GRAVITY)
        top = min(top, 0.999 * lift)
        grid = np.exp(np.arange(math.log(lam), math.log(top), math.log(
            1.04 if ctx.mode.quick else 1.02)))
        rows: list[dict[str, Any]] = []
        durations = ctx.mode.durations[::2]
        with ctx.counter("vertical pulse time histories", 2 * durations.size) as tick:
            for tp in durations:
                first = []
                for r in (0.0, ratio):
                    motions = [StepImpulse.from_g(float(a), float(tp), vertical=r)
                               for a in grid]
                    outcomes = _model_outcomes(ctx, motions, [None] * len(motions))
                    hit = [a for a, o in zip(grid, outcomes, strict=True) if o == "collapse"]
                    first.append(float(hit[0]) if hit else None)
                    tick(len(rows) * 2 + len(first))
                rows.append({"duration_s": float(tp), "first_collapse_g": first[0],
                             "first_collapse_vertical_g": first[1]})
        data["pulses"] = {"family": "step", "grid_step": 0.04 if ctx.mode.quick else 0.02,
                          "top_g": float(top), "lift_off_g": float(lift), "rows": rows}
    records = ctx.prior.get("records")
    if cfg.suite_vertical and records is not None:
        from archquake.ground.suites import load_suite
        from archquake.ida import incremental_dynamic_analysis
        from archquake.sweeps import CaseOptions, ResultStore

        suite = load_suite(list(cfg.suite) if isinstance(cfg.suite, tuple) else cfg.suite,
                           units=cfg.units)
        used = ctx.mode.records(suite.records)
        both = [(i, r) for i, r in enumerate(used) if has_vertical(r)]
        store_path = (ctx.out / "cache" / f"ida-horizontal-{cfg.digest}-"
                      f"{'quick' if ctx.mode.quick else 'full'}.sqlite")
        store_path.parent.mkdir(parents=True, exist_ok=True)
        options = (CaseOptions(restitution=cfg.restitution, impact=cfg.impact)
                   if models.takes(cfg.model, "restitution") else CaseOptions())
        ctx.say(f"  IDA of the horizontal alone of {len(both)} records")
        with ResultStore(store_path) as store:
            res = incremental_dynamic_analysis(
                cfg.arch, [r.horizontal for _, r in both], "pga", store, options=options,
                model=cfg.model, ceiling=records["ceiling_g"],
                **({} if ctx.loads is None else {"loads": ctx.loads}), **ctx.mode.ida)
        data["records"] = [
            {"record": records["records_used"][i], "horizontal": r.horizontal.name,
             "vertical": r.vertical.name,
             "v_over_h_pga": float(r.vertical.peak / r.horizontal.peak),
             "first_collapse_g": records["first_collapse_g"][i],
             "first_collapse_horizontal_only_g": _num(x)}
            for (i, r), x in zip(both, res.first_collapse_levels, strict=True)]
        data["records_ceiling_g"] = records["ceiling_g"]
    return StudyResult("vertical", "The vertical component", (), (), (), data)


# ----------------------------------------------------------------------------- 5. DEM
#: The DEM check's window after a step pulse, in the tails of the model's own pulse runs
#: (`archquake.domains.blocks.DOMAIN_TAIL` sqrt(R/g) after the pulse). The DEM's elastic
#: contacts keep vibrating after a rigid chain would be still (Oppenheim's arch after a 1 g,
#: 0.20 s step: kinetic energy 2.4e-6 W L at 6 s, 5e-8 at 7-8 s), and it reads "survives"
#: only once still (`archquake.blocks.result.settled`). Measured on the bridge example's
#: governing pulse at 0.85 of the chain's collapse level: at rest at about 5.1-5.3 s (as the
#: DEM's last bits round), past the chain's window (4.54 s: "indeterminate" there, as at 3 s
#: after the pulse at every level). Its runs
#: stop at rest, so a long window costs only the runs that need it.
DEM_PULSE_TAILS = 2.0


def _dem_outcome(arch, motion, duration: float) -> str:
    """One DEM run, at most ``duration`` s, ending at collapse or at rest: its outcome's word
    (module level: picklable)."""
    from archquake.dem import simulate_dem
    from archquake.dem.settings import DemSettings

    res = simulate_dem(arch, motion, DemSettings().with_(duration=duration, stop_at_rest=True))
    return str(getattr(res.outcome, "value", res.outcome))


def _model_outcomes(ctx: Context, motions: list, windows: list) -> list[str]:
    """The configuration's model's outcome words for ``motions`` (s windows, None: the model's
    own, run to a verdict): the rigid chain's verdict path, or the four-link model at the
    restitution its pulses and records used."""
    if not motions:
        return []
    if models.takes(ctx.config.model, "guard"):
        from archquake.rigid import rigid_verdicts

        return [v.outcome.value for v in rigid_verdicts(ctx.rigid_body(), motions,
                                                        duration=_windows(ctx, motions, windows))]
    from archquake.mechanism.simulate import simulate

    prep = prepared_mechanism(ctx.arch, ctx.config.impact, ctx.loads)
    return [simulate(prep, m, restitution=ctx.config.restitution, t_end=w).outcome.value
            for m, w in zip(motions, windows, strict=True)]


def _windows(ctx: Context, motions: list, windows: list) -> list | None:
    """The rigid chain's window of each motion, s: as given, or the verdict's default
    (the end of the excitation + the verdict's tail in sqrt(R/g), as
    `archquake.rigid.rigid_verdicts` takes it for an arch, scaled by the arch's radius: a
    loaded assembly has none of its own). For the bare arch, ``windows`` as given."""
    if ctx.loads is None:
        return windows
    from archquake.rigid.verdict import default_window

    return [default_window(ctx.arch, m, STANDARD_GRAVITY) if w is None else w
            for m, w in zip(motions, windows, strict=True)]


def _bump(count: list) -> int:
    """Add one to ``count[0]`` and return it (a done-callback's counter)."""
    count[0] += 1
    return count[0]


def _runs(ctx: Context, name: str) -> bool:
    """Whether section ``name``'s data is among ``ctx.prior``'s keys (run, or running side by
    side): the keys are listed without waiting for the data."""
    return any(key == name for key in ctx.prior)


def _dem_pulse_jobs(ctx: Context) -> list[tuple[str, float, Any, float, float]]:
    """The DEM check's step-pulse runs: (case, factor, motion, longest duration s, level g) at
    each of the mode's factors of the governing step boundary (read from the pulses section),
    to `DEM_PULSE_TAILS` times the model's tail after the pulse."""
    from archquake.domains.blocks import DOMAIN_TAIL

    tail = DEM_PULSE_TAILS * DOMAIN_TAIL * math.sqrt(float(ctx.arch.radius) / STANDARD_GRAVITY)
    jobs: list[tuple[str, float, Any, float, float]] = []
    step = ctx.prior.get("pulses", {}).get("step")
    if step is None:
        return jobs
    coll = np.asarray(step["collapse_g"], dtype=float)
    durs = np.asarray(step["durations_s"], dtype=float)
    lam = ctx.prior["static"]["collapse_acceleration_g"]
    finite = np.flatnonzero(np.isfinite(coll))
    # the longest duration whose boundary stays well above lambda (1.2x) at every factor run
    clear = [j for j in finite if min(ctx.mode.dem_factors) * coll[j] > 1.2 * lam]
    if finite.size:
        i = int(clear[-1] if clear else finite[finite.size // 2])
        from archquake.ground.pulses import StepImpulse

        for f in ctx.mode.dem_factors:
            mag = f * coll[i]
            jobs.append((f"step pulse t_p = {durs[i]:.3g} s", f,
                         StepImpulse.from_g(mag, float(durs[i]), -1), float(durs[i]) + tail,
                         mag))
    return jobs


def _dem_record_jobs(ctx: Context, data: dict) -> list[tuple[str, float, Any, float, float]]:
    """The DEM check's runs of the governing record (read from the records section: side by
    side, this waits for it), as `_dem_pulse_jobs`; ``data`` gets ``record_case`` and,
    with a record, its cut and window."""
    from archquake.ground.suites import load_suite

    jobs: list[tuple[str, float, Any, float, float]] = []
    gov = ctx.early("records", "governing")
    data["record_case"] = gov is not None
    if gov is None:
        return jobs
    cfg = ctx.config
    suite = load_suite(list(cfg.suite) if isinstance(cfg.suite, tuple) else cfg.suite,
                       units=cfg.units)
    rec = suite.records[gov["index"]]
    # the record cut where 95 % of its Arias intensity has arrived, and run 3 s past the
    # cut: a window that ends after the motion does, so the DEM can find the arch at rest
    # (survives), not only collapsed; the model runs the same cut record
    cut = min(float(rec.duration), strong_motion_end(rec))
    rec = rec.truncated(cut)
    end = float(rec.duration) + 3.0
    for f in ctx.mode.dem_factors:
        level = f * gov["first_collapse_g"]
        jobs.append((f"record {gov['record']}", f, rec.scaled(level / gov["pga_unscaled_g"]),
                     end, level))
    data["record_cut_s"] = float(rec.duration)
    data["record_window_s"] = end
    return jobs


def section_dem(ctx: Context) -> StudyResult:
    """The DEM check: the DEM and the configuration's model at fractions of the model's
    collapse level, for the governing step pulse and the governing record.

    The pulse's runs start first; side by side with the other sections they run while the
    records' IDA goes on, and only the record's runs wait for it (`_dem_record_jobs`)."""
    data: dict[str, Any] = {"model": ctx.config.model, "factors": list(ctx.mode.dem_factors),
                            "cases": []}
    # the model's own verdict at each level run, beside the DEM's: a level below the model's
    # reported one is not assumed to survive (a search can miss a band of collapses below it)
    # (a pulse's as its domain search ran it, a record's to a verdict as the IDA ran it)
    from archquake.domains.blocks import DOMAIN_TAIL

    tail = DOMAIN_TAIL * math.sqrt(float(ctx.arch.radius) / STANDARD_GRAVITY)

    def windows(jobs: list) -> list:
        return [None if case.startswith("record") or not models.spec(ctx.config.model).blocks
                else float(m.duration) + tail for case, _, m, _, _ in jobs]

    body = ctx.rigid_body()  # the DEM's blocks carry the loads as the rigid chain's do
    jobs = _dem_pulse_jobs(ctx)
    if jobs:
        data["dem_pulse_tail_s"] = DEM_PULSE_TAILS * tail
    # the record's runs, if the records section runs (known before it ends)
    planned = len(jobs) + (len(ctx.mode.dem_factors) if _runs(ctx, "records") else 0)
    ctx.say(f"  {planned} DEM runs")
    if planned <= 1:
        jobs += _dem_record_jobs(ctx, data)
        model = _model_outcomes(ctx, [m for _, _, m, _, _ in jobs], windows(jobs))
        outcomes = [_dem_outcome(body, m, dur) for _, _, m, dur, _ in jobs]
    else:
        # a worker for each run: the record's runs start once the records' IDA has settled
        # every first collapse (it fills the levels above meanwhile) and are then what the
        # assessment waits for; side by side on the cores they end together,
        # where two workers left the last run alone on one core
        with interruptible_pool(planned) as pool:
            tick, ran = ctx.counter("DEM runs", planned), [0]
            with tick:
                futures = []

                def submit(batch: list) -> None:
                    for _, _, m, dur, _ in batch:
                        fu = pool.submit(_dem_outcome, body, m, dur)
                        fu.add_done_callback(lambda _: tick(_bump(ran)))
                        futures.append(fu)

                submit(jobs)
                model = _model_outcomes(ctx, [m for _, _, m, _, _ in jobs], windows(jobs))
                later = _dem_record_jobs(ctx, data)
                submit(later)
                tick(ran[0], len(jobs) + len(later))
                model += _model_outcomes(ctx, [m for _, _, m, _, _ in later], windows(later))
                jobs += later
                outcomes = [fu.result() for fu in futures]
    by_case: dict[str, dict] = {}
    for (case, f, _, dur, level), outcome, mine in zip(jobs, outcomes, model, strict=True):
        c = by_case.setdefault(case, {"case": case, "runs": []})
        c["runs"].append({"factor": f, "level_g": level, "duration_s": dur,
                          "dem_outcome": outcome, "model_outcome": mine})
    for c in by_case.values():
        dem_collapses = [r["factor"] for r in c["runs"] if r["dem_outcome"] == "collapse"]
        lowest = min(dem_collapses) if dem_collapses else None
        # the DEM is more vulnerable where it collapses and the model does not
        worse = [r["factor"] for r in c["runs"] if r["factor"] < 1.0
                 and r["dem_outcome"] == "collapse" and r["model_outcome"] != "collapse"]
        below = [r["factor"] for r in c["runs"] if r["factor"] < 1.0
                 and r["model_outcome"] == "collapse"]
        c["model_level_g"] = c["runs"][0]["level_g"] / c["runs"][0]["factor"]
        c["lowest_dem_collapse_factor"] = lowest
        c["dem_more_vulnerable"] = bool(worse)
        c["unconservative_by_at_least"] = (1.0 - min(worse)) if worse else 0.0
        c["model_collapses_below_its_level_factor"] = min(below) if below else None
        data["cases"].append(c)
    data["dem_more_vulnerable"] = any(c["dem_more_vulnerable"] for c in data["cases"])
    return StudyResult("dem", "5. The DEM check", (), (), (), data)


# ----------------------------------------------------------------------------- 6. validity
def section_validity(ctx: Context) -> StudyResult:
    cfg = ctx.config
    warnings: list[dict] = []

    def warn(key: str, text: str, means: str, serious: bool = True) -> None:
        warnings.append({"key": key, "warning": text, "meaning": means, "serious": serious})

    refusal = dynamics_refusal(ctx.arch, cfg.model)
    if refusal is not None:
        # serious unless the site PGA is below lambda: then the arch does not rock at all
        lam = ctx.prior.get("static", {}).get("collapse_acceleration_g", math.inf)
        warn("asymmetric", "the dynamic sections were not run", refusal,
             serious=ctx.site is None or ctx.site > lam)
    impact: dict[str, Any] = {"law": cfg.impact, "prescribed_restitution_cv": cfg.restitution}
    cv = math.nan
    if models.spec(cfg.model).blocks:
        impact = {"law": "plastic contacts (the chain of rigid voussoirs: no restitution)",
                  "prescribed_restitution_cv": None}
    elif refusal is not None:
        cv = cfg.restitution if cfg.restitution is not None else math.nan
    else:
        cv, own = used_restitution(cfg, ctx.arch)
        impact.update({"law_restitution_cv": own.restitution_cv,
                       "law_restitution_ct": own.restitution_ct, "law_validity": own.validity,
                       "law_energy_gain": own.energy_gain, "used_restitution_cv": cv})
        law_outside = own.validity == "outside" or own.energy_gain or own.restitution_cv < 0
        if law_outside and cfg.restitution is None:
            warn("impact_law", f"the {cfg.impact} impact law is outside its validity for this "
                 f"arch (c_v = {own.restitution_cv:.3g}, c_T = {own.restitution_ct:.3g}, validity "
                 f"'{own.validity}')",
                 "the rocking after the first impact is not trustworthy; prescribe a restitution "
                 "or use the chain law")
        elif law_outside:
            warn("impact_law", f"the {cfg.impact} impact law gives c_v = "
                 f"{own.restitution_cv:.3g} (validity '{own.validity}') for this arch; a "
                 f"prescribed c_v = {cv:g} is used",
                 "the result depends on the prescribed restitution: see the sensitivity below",
                 serious=False)
        elif own.validity == "near_four_hinge":
            warn("impact_law", f"the {cfg.impact} impact law is near the edge of its validity "
                 "(near_four_hinge)", "the post-impact mechanism is approximate", serious=False)
    static = ctx.prior.get("static", {})
    if static.get("sliding"):
        warn("sliding", f"the joints need a friction coefficient of "
             f"{static['static_friction_demand']:.3f} at the onset of rocking, more than the "
             f"given {cfg.friction:g}",
             "the arch slides before it rocks: the rocking models (four-link and the rigid "
             "chain without friction) do not cover sliding; the capacities are upper bounds")
    for fam in ("step", "sine"):
        bands = ctx.prior.get("pulses", {}).get(fam, {}).get("non_monotonic_bands", [])
        if bands:
            warn(f"non_monotonic_{fam}", f"{len(bands)} non-monotonic band(s) in the {fam} "
                 "domain", "a stronger pulse is not always worse: some pulses above a collapsing "
                 "one leave the arch standing (do not read safety from a larger survived pulse)",
                 serious=False)
    # the sensitivity runs start before the records are read (side by side, its pulses' runs
    # go while the records' IDA does); its warnings come after the records' in the list
    later: list[tuple[tuple, dict]] = []
    step_sens = (_rigid_sensitivity(ctx, lambda *a, **k: later.append((a, k)))
                 if models.takes(cfg.model, "guard") and ctx.site is not None
                 and "pulses" in ctx.prior else [])
    rec = ctx.prior.get("records", {})
    if rec.get("records_with_resurrections"):
        warn("resurrections", f"{rec['records_with_resurrections']} record(s) collapse the arch "
             "at some scale and not at a larger one", "the IDA curves are not monotonic; the "
             "first-collapse fit is the one that counts", serious=False)
    for args, kwargs in later:
        warn(*args, **kwargs)
    # restitution sensitivity (four-link model): the pulse verdict at c_v +- 0.1
    sens = []
    if models.takes(cfg.model, "restitution") and ctx.site is not None and "pulses" in ctx.prior:
        base = ctx.prior["pulses"]
        for dcv in (-0.1, 0.1):
            c2 = min(max(cv + dcv, 0.0), 1.0)
            if c2 == cv:
                continue
            ctx.say(f"  step and sine domains at c_v = {c2:.3g}")
            doms = pulse_domains(ctx, c2)
            entry: dict[str, Any] = {"restitution_cv": c2}
            for fam, d in doms.items():
                dd = _domain_data(d, ctx.site)
                entry[fam] = {"min_collapse_g": dd["min_collapse_g"],
                              "collapses_at_site": dd["collapses_at_site"]}
            sens.append(entry)
        changed = [e for e in sens if any(e[f]["collapses_at_site"] != base[f]
                                          ["collapses_at_site"] for f in ("step", "sine"))]
        if changed:
            warn("restitution", "the pulse verdict at the site PGA changes within c_v +- 0.1 "
                 f"(at c_v = {', '.join(format(e['restitution_cv'], '.2g') for e in changed)})",
                 "the verdict rests on the restitution, which the rigid-block model cannot "
                 "fix: treat it as uncertain")
    ida_sens = (_ida_sensitivity(ctx, cv, warn) if models.takes(cfg.model, "restitution")
                and "p_collapse_at_site" in rec else [])
    data = {"model": cfg.model, "impact": impact, "warnings": warnings,
            "step_sensitivity": step_sens, "restitution_sensitivity": sens,
            "restitution_sensitivity_ida": ida_sens,
            "serious": any(w["serious"] for w in warnings)}
    return StudyResult("validity", "6. Validity", (), (), (), data)


#: The keys of the DEM check's warnings in the validity section.
_DEM_KEYS = ("dem", "model_below_level")
#: The keys of the validity warnings that come after the DEM check's (the sensitivity runs').
_AFTER_DEM = ("time_step", "friction_collapse", "friction_survival", "restitution",
              "restitution_ida", "restitution_ida_order")


def with_dem_warnings(validity: dict, dem: dict | None, model: str) -> dict:
    """The validity section's data with the DEM check's warnings in it, placed before the
    sensitivity runs' warnings (as the report lists them), and ``serious`` updated: per
    governing case, a serious warning where the model itself collapses at a fraction of the
    collapse level its search reported (the search missed a band below it), and one where the
    DEM collapses at a fraction where the model survives (the model is unconservative).

    The validity section does not wait for the DEM check (the two run side by side); its data
    is completed here once both are done, the same way for a fresh and a resumed run (any
    ``dem`` warning already present is replaced)."""
    warnings = [w for w in validity.get("warnings", []) if w["key"] not in _DEM_KEYS]
    extra = []
    for c in (dem or {}).get("cases", []):
        below = c.get("model_collapses_below_its_level_factor")
        if below is not None:
            extra.append({
                "key": "model_below_level",
                "warning": f"the {model} model itself collapses under the {c['case']} at "
                           f"{below:g} x the collapse level its search reported "
                           f"({c['model_level_g']:.3g} g)",
                "meaning": "the search missed collapses below the boundary it reported (a "
                           "band where a weaker motion brings the arch down): the capacity "
                           "there is lower than the section reports",
                "serious": True})
        if c["dem_more_vulnerable"]:
            extra.append({
                "key": "dem",
                "warning": f"the DEM collapses under the {c['case']} at "
                           f"{1.0 - c['unconservative_by_at_least']:g} x the {model} model's "
                           f"collapse level ({c['model_level_g']:.3g} g), where the {model} "
                           "model survives",
                "meaning": f"the {model} model's result is unconservative there by at least "
                           f"{100 * c['unconservative_by_at_least']:.0f} %",
                "serious": True})
    at = next((k for k, w in enumerate(warnings) if w["key"] in _AFTER_DEM), len(warnings))
    warnings[at:at] = extra
    return dict(validity, warnings=warnings, serious=any(w["serious"] for w in warnings))


def _nearest_boundaries(domain: dict, site: float, count: int | None) -> np.ndarray:
    """Indices of the durations of a domain's data (`_domain_data`), all or the
    ``count`` whose governing boundary is nearest ``site`` in ratio (no boundary: farthest)."""
    coll = np.asarray(domain["collapse_g"], dtype=float)
    if count is None or count >= coll.size:
        return np.arange(coll.size)
    gap = np.where(np.isfinite(coll), np.abs(np.log(np.where(np.isfinite(coll), coll, 1.0)
                                                    / site)), np.inf)
    return np.sort(np.argsort(gap, kind="stable")[:count])


def _rigid_friction_outcome(arch, motion, friction: float, time_step: float,
                            loads=None) -> str:
    """One recorded run of the rigid chain (its blocks carrying ``loads``) with Coulomb joints
    to a verdict, at ``time_step`` (s; the verdict path has no friction): its outcome's word
    (module level: picklable)."""
    from archquake.rigid.run import rigid_to_verdict

    run = rigid_to_verdict(arch, motion, friction=friction, time_step=time_step,
                           **({} if loads is None else {"loads": loads}))
    return str(run.outcome.value)


def _rigid_sensitivity(ctx: Context, warn) -> list[dict]:
    """What the rigid chain's verdicts at the site PGA rest on, in place of a restitution: the
    time step and sliding. The pulses of the site PGA at every scanned duration (quick mode:
    the two of each family whose governing boundary is nearest the site PGA, the verdicts a
    small change would flip first) and the governing record scaled to it are run on the
    verdict path (`archquake.rigid.rigid_verdicts`) at its step (guarded) and at half of
    it (guarded at a quarter), and with Coulomb joints of the given friction coefficient (the
    recorded stepper, `archquake.rigid.run.rigid_to_verdict`: the verdict path has no
    friction) at the verdict's step; a friction verdict that differs from the no-slip one is
    run again at `archquake.rigid.DEFAULT_TIME_STEP` (1e-4 s) and that one kept, so that
    every verdict the report counts as changed by sliding, or warns about, is the fine step's
    (``friction_time_step_s``: the step of each). A verdict that changes at
    half the step is a serious warning (the step does not resolve the motion); one that changes
    from survival to collapse with friction too (the joints slide, which the default no-slip
    chain leaves out); from collapse to survival with friction only a note."""
    from archquake.ground.pulses import SinePulse, StepImpulse
    from archquake.rigid import DEFAULT_TIME_STEP, rigid_verdicts
    from archquake.rigid.verdict import verdict_time_step

    assert ctx.site is not None  # called only with a site PGA
    site = float(ctx.site)
    cases: list[tuple[str, Any]] = []
    pulses = ctx.prior["pulses"]
    for fam, make, sym in (("step", StepImpulse.from_g, "t_p"), ("sine", SinePulse.from_g, "T")):
        durs = np.asarray(pulses[fam]["durations_s"], dtype=float)
        for d in durs[_nearest_boundaries(pulses[fam], site, 2 if ctx.mode.quick else None)]:
            cases.append((f"{fam} {sym} = {d:.3g} s", make(site, float(d), -1)))
    # the governing record's case, if the records section runs (known before it ends)
    planned = len(cases) + (1 if _runs(ctx, "records") else 0)
    ctx.say(f"  {planned} cases at the site PGA x 3 (step, half step, friction)")
    body = ctx.rigid_body()
    h = verdict_time_step(body)
    mu = ctx.config.friction
    fine = min(h, DEFAULT_TIME_STEP)
    tick = ctx.counter("sensitivity runs", 3 * planned)
    done = [0]
    default: list = []
    half: list = []
    futures: list = []

    def start(batch: list) -> None:
        """The runs of ``batch``'s cases: Coulomb joints at the verdict's step in worker
        processes, while the verdicts at the step and at half of it run here."""
        motions = [m for _, m in batch]
        windows = _windows(ctx, motions, [None] * len(motions))
        for m in motions:
            fu = pool.submit(_rigid_friction_outcome, ctx.arch, m, mu, h, ctx.loads)
            fu.add_done_callback(lambda _: tick(_bump(done)))
            futures.append(fu)
        if not motions:
            return
        default.extend(rigid_verdicts(body, motions, time_step=h, duration=windows))
        done[0] += len(motions) - 1
        tick(_bump(done))
        half.extend(rigid_verdicts(body, motions, time_step=0.5 * h, duration=windows))
        done[0] += len(motions) - 1
        tick(_bump(done))

    with tick, interruptible_pool(min(workers(), max(planned, 1))) as pool:
        # the pulses' cases first; side by side, they run while the records' IDA goes on
        start(cases)
        gov = ctx.early("records", "governing")  # side by side: waits for it
        if gov is not None:
            from archquake.ground.suites import load_suite

            cfg = ctx.config
            suite = load_suite(list(cfg.suite) if isinstance(cfg.suite, tuple) else cfg.suite,
                               units=cfg.units)
            rec = suite.records[gov["index"]]
            record = [(f"record {gov['record']}", rec.scaled(site / gov["pga_unscaled_g"]))]
            cases += record
            start(record)
        motions = [m for _, m in cases]
        tick(done[0], 3 * len(motions))
        slid = [fu.result() for fu in futures]
        slid_steps = [h] * len(motions)
        # a friction verdict that differs from the no-slip chain's (one the report warns about
        # or counts as changed by sliding) is run again at the recorded stepper's fine step,
        # and that one is kept
        again = [k for k in range(len(motions))
                 if fine < h and slid[k] != default[k].outcome.value]
        tick(done[0], 3 * len(motions) + len(again))
        futures = [pool.submit(_rigid_friction_outcome, ctx.arch, motions[k], mu, fine,
                               ctx.loads)
                   for k in again]
        for k, fu in zip(again, futures, strict=True):
            slid[k], slid_steps[k] = fu.result(), fine
            tick(_bump(done))
    out = []
    for k, (case, _) in enumerate(cases):
        out.append({"case": case, "time_step_s": h, "friction_coefficient": ctx.config.friction,
                    "default_step": default[k].outcome.value,
                    "half_step": half[k].outcome.value, "friction": slid[k],
                    "friction_time_step_s": slid_steps[k],
                    "friction_recheck_time_step_s": fine})
    step_changed = [r["case"] for r in out if r["half_step"] != r["default_step"]]
    if step_changed:
        warn("time_step", f"the verdict at the site PGA changes at half the time step under "
             f"{', '.join(step_changed)}",
             "the time step does not resolve these motions: treat their verdicts as uncertain")
    slides = [r["case"] for r in out if r["default_step"] != "collapse" and
              r["friction"] == "collapse"]
    if slides:
        warn("friction_collapse", f"with Coulomb joints (mu = {ctx.config.friction:g}) the arch "
             f"collapses at the site PGA under {', '.join(slides)}, where the no-slip chain "
             "does not",
             "the joints slide: the no-slip verdicts are unconservative there")
    held = [r["case"] for r in out if r["default_step"] == "collapse" and
            r["friction"] != "collapse"]
    if held:
        warn("friction_survival", f"with Coulomb joints (mu = {ctx.config.friction:g}) the arch "
             f"does not collapse at the site PGA under {', '.join(held)}, where the no-slip "
             "chain does", "sliding changes the mechanism; the no-slip verdict is the "
             "conservative one", serious=False)
    return out


def _ida_sensitivity(ctx: Context, cv: float, warn) -> list[dict]:
    """P(collapse | site PGA) of the records at c_v - 0.1, c_v and c_v + 0.1 (clipped to
    [0, 1]; the same records and IDA settings as section 4, whose value is the middle one).

    A larger c_v keeps more energy through each impact, so P(collapse) should not fall as c_v
    grows; where it does, the warning says why (the IDA's first-collapse levels are not
    monotonic in c_v: a different c_v shifts the rocking's phase against the record's pulses,
    as the non-monotonic bands of the pulse domains show). A verdict level that changes within
    c_v +- 0.1 is a serious warning, as for the pulses."""
    rec = ctx.prior["records"]
    out = [{"restitution_cv": cv, "p_collapse_at_site": rec["p_collapse_at_site"],
            "fragility_median_g": rec["fragility"]["first_collapse"]["median_g"],
            "records_collapsing": rec["records_collapsing"], "section": "records"}]
    for dcv in (-0.1, 0.1):
        c2 = min(max(cv + dcv, 0.0), 1.0)
        if c2 == cv:
            continue
        _, _, res, fits = run_ida(ctx, c2, bootstrap=0)
        fit = fits["first_collapse"]
        out.append({"restitution_cv": c2,
                    "p_collapse_at_site": None if fit is None else float(
                        fit.probability(ctx.site)),
                    "fragility_median_g": None if fit is None else float(fit.median),
                    "records_collapsing": int(np.sum(np.isfinite(res.first_collapse_levels))),
                    "section": "validity"})
    out.sort(key=lambda e: e["restitution_cv"])
    ps = [e["p_collapse_at_site"] for e in out]
    if any(p is None for p in ps):
        warn("restitution_ida", "no first-collapse fit at c_v = " + ", ".join(
             format(e["restitution_cv"], ".2g") for e in out if e["p_collapse_at_site"] is None),
             "P(collapse) cannot be compared across c_v there", serious=False)
        return out
    if any(b < a - 1e-12 for a, b in zip(ps, ps[1:], strict=False)):
        warn("restitution_ida_order", "P(collapse) at the site PGA is not non-decreasing in c_v "
             "(" + ", ".join(f"{p:.2f} at c_v = {e['restitution_cv']:.2g}"
                             for p, e in zip(ps, out, strict=True)) + ")",
             "a larger c_v keeps more energy through each impact, yet here it changes the "
             "rocking's phase against the records' pulses (as the domains' non-monotonic bands "
             "do), and with few records each first collapse moves the fit", serious=False)
    levels = {_p_level(p) for p in ps}
    if len(levels) > 1:
        warn("restitution_ida", "the records' verdict at the site PGA changes within c_v +- 0.1 "
             "(" + ", ".join(f"P = {p:.2f} at c_v = {e['restitution_cv']:.2g}"
                             for p, e in zip(ps, out, strict=True)) + ")",
             "the probability of collapse rests on the restitution, which the rigid-block model "
             "cannot fix: treat it as uncertain")
    return out


def _p_level(p: float) -> str:
    """The verdict's level from P(collapse | site PGA) (one rule for verdict and validity)."""
    return "collapse likely" if p >= 0.5 else "at risk" if p >= 0.1 else "rocks but survives"


# ----------------------------------------------------------------------------- 8. verdict
#: The validity warnings that can only make collapse likelier than the verdict says (the joints
#: slide; the DEM, or the model itself, collapses below the reported level): with the verdict
#: already "collapse likely" they do not make it inconclusive.
COLLAPSE_LIKELIER = ("friction_collapse", "dem", "model_below_level", "sliding")
#: The colour of the verdict by outcome: "fails" (collapse likely, or the code check fails),
#: "at-risk", "passes" (stands, or rocks but survives, and the code check passes or is not
#: run), "open" (capacity only).
OUTCOMES = ("fails", "at-risk", "passes", "open")


def verdict(config, prior: dict, *, quick: bool = False) -> dict:
    """The one-paragraph verdict and the numbers it rests on (from the sections' data).

    The text opens with the level word (``'Collapse likely'``, ``'At risk'``, ``'Rocks but
    survives'``, ``'Stands'``, ...), the code check's outcome with a ``[site]`` table, and
    "indicative" in quick mode; ``outcome`` (`OUTCOMES`) follows the outcome, not the
    certainty. A serious validity warning makes it not conclusive, unless the verdict is
    already as high as that warning can raise it ("collapse likely", or "at risk" from the
    pulses with no records) and the warning can only make collapse likelier
    (`COLLAPSE_LIKELIER`)."""
    site = config.site_pga_g
    st = prior["static"]
    lam = st["collapse_acceleration_g"]
    pul = prior.get("pulses", {})
    rec = prior.get("records")
    val = prior.get("validity", {})
    numbers = {"collapse_acceleration_g": lam, "geometric_safety_factor":
               st["geometric_safety_factor"], "site_pga_g": site,
               "step_min_collapse_g": pul.get("step", {}).get("min_collapse_g"),
               "sine_min_collapse_g": pul.get("sine", {}).get("min_collapse_g")}
    parts = []
    if site is None:
        level = "capacity only"
        parts.append(f"No site PGA was given: the arch starts to rock at lambda = {lam:.3f} g.")
    elif site <= lam:
        level = "stands"
        parts.append(f"The site PGA ({site:.3g} g) is below the static collapse acceleration "
                     f"lambda = {lam:.3f} g: the arch moves rigidly with the ground and does "
                     "not even start to rock.")
    elif "pulses" not in prior:
        level = "rocks: dynamics not assessed"
        parts.append(f"The site PGA ({site:.3g} g) is {site / lam:.1f} times the static collapse "
                     f"acceleration lambda = {lam:.3f} g: the arch rocks, and whether it "
                     "collapses was not assessed (the dynamic sections were not run).")
    else:
        parts.append(f"The site PGA ({site:.3g} g) is {site / lam:.1f} times the static collapse "
                     f"acceleration lambda = {lam:.3f} g: the arch rocks; whether it collapses "
                     "depends on the duration of the motion.")
        pulses_collapse = [f for f in ("step", "sine") if pul.get(f, {}).get("collapses_at_site")]
        if pulses_collapse:
            which = []
            for f in pulses_collapse:
                durs = pul[f]["durations_collapsing_at_site_s"]
                sym = "t_p" if f == "step" else "T"
                span = (f"{sym} = {min(durs):.3g} s" if min(durs) == max(durs) else
                        f"{sym} from {min(durs):.3g} s to {max(durs):.3g} s")
                which.append(f"{f} pulses with {span} ({len(durs)} of the "
                             f"{len(pul[f]['durations_s'])} durations scanned)")
            parts.append("Pulses of the site PGA collapse it: " + "; ".join(which) + ".")
        else:
            parts.append("No step or sine pulse of the site PGA in the scanned durations "
                         "collapses it.")
        p = None if rec is None else rec.get("p_collapse_at_site")
        if rec is not None and p is not None:
            ci = rec.get("p_collapse_at_site_ci")
            numbers["p_collapse_at_site"] = p
            numbers["p_collapse_at_site_ci"] = ci
            ci_text = "" if ci is None else f" (90 % interval {ci[0]:.2f} to {ci[1]:.2f})"
            parts.append(f"Under the {rec['suite']} records scaled to the site PGA the "
                         f"probability of collapse is {p:.2f}{ci_text}, fragility median "
                         f"{rec['fragility']['first_collapse']['median_g']:.3f} g.")
            level = _p_level(p)
        else:
            level = "at risk" if pulses_collapse else "rocks but survives"
    imp = val.get("impact", {})
    if "used_restitution_cv" in imp:
        numbers["restitution_cv"] = imp["used_restitution_cv"]
        how = ("prescribed" if imp.get("prescribed_restitution_cv") is not None
               else f"from the {imp['law']} impact law")
        sens = val.get("restitution_sensitivity", [])
        text = f"Impacts use c_v = {imp['used_restitution_cv']:.3g} ({how})"
        if sens and site is not None and site > lam:
            same = all(e[f]["collapses_at_site"] == pul[f]["collapses_at_site"]
                       for e in sens for f in ("step", "sine"))
            cvs = " and ".join(format(e["restitution_cv"], ".2g") for e in sens)
            text += (f"; the pulse verdict is the same at c_v = {cvs}" if same else
                     f"; the pulse verdict changes at c_v = {cvs}")
        ida = val.get("restitution_sensitivity_ida", [])
        if len(ida) > 1 and all(e["p_collapse_at_site"] is not None for e in ida):
            text += ("; P(collapse) of the records is " + ", ".join(
                f"{e['p_collapse_at_site']:.2f} at c_v = {e['restitution_cv']:.2g}" for e in ida))
        parts.append(text + ".")
    steps = val.get("step_sensitivity", [])
    if steps:
        n_same = sum(r["half_step"] == r["default_step"] for r in steps)
        n_slid = sum(r["friction"] == r["default_step"] for r in steps)
        parts.append(f"The chain of rigid voussoirs decides the verdicts (no coefficient of "
                     f"restitution): at the site PGA, {n_same} of {len(steps)} verdicts are the "
                     f"same at half the time step and {n_slid} of {len(steps)} with Coulomb "
                     f"joints (mu = {config.friction:g}).")
    if st.get("sliding"):
        parts.append(f"The joints would slide (friction demand {st['static_friction_demand']:.3f}"
                     f" > {config.friction:g}).")
    if site is not None and getattr(config, "site", None) is not None and getattr(
            config, "site_pga_source", None):  # the site PGA from (or against) a [site] table
        parts.insert(0, f"Site PGA {site:.3g} g: {config.site_pga_source}.")
    code = prior.get("codecheck")
    code_fails = False
    head_code = ""
    if code is not None:
        gov = [c for c in code["limit_states"] if c["governing"]]
        failing = [c["limit_state"] for c in gov if not c["passes"]]
        code_fails = bool(failing)
        worst = min(gov, key=lambda c: c["ratio"])
        head_code = (f"; code check FAILS at {', '.join(failing)}" if failing
                     else "; code check passes")
        missing = code.get("not_checked", {})
        numbers["code_check_passes"] = not code_fails
        numbers["code_check_least_ratio"] = worst["ratio"]
        parts.append("Code check (kinematic analysis, NTC 2018 §8.7.1): "
                     + (f"FAILS at {', '.join(failing)}" if failing else "passes at "
                        + ", ".join(c["limit_state"] for c in gov))
                     + f" (least ratio capacity a_g / site a_g {worst['ratio']:.3f}, "
                       f"{worst['limit_state']} {worst['method']})"
                     + (f"; {', '.join(missing)} not checked (no hazard of its own)"
                        if missing else "") + ".")
    indicative = bool(quick and site is not None and site > lam and "pulses" in prior)
    if indicative:
        what = (f"P(collapse) from {len(rec['records_used'])} of the "
                f"{rec['records_in_suite']} records, " if rec is not None else "")
        parts.append(f"Indicative only: quick mode ({what}coarse domains); run without --quick "
                     "before relying on it.")
    serious = [w for w in val.get("warnings", []) if w["serious"]]
    likelier = [w for w in serious if w["key"] in COLLAPSE_LIKELIER]
    # the verdict's level already as high as these can raise it: collapse likely, or at risk
    # from the pulses alone (with no records there is no higher level)
    top = level == "collapse likely" or (level == "at risk" and numbers.get(
        "p_collapse_at_site") is None)
    blocking = [w for w in serious if not (top and w["key"] in COLLAPSE_LIKELIER)]
    certain = not blocking
    if not certain:
        parts.insert(0, "The models are outside their validity here ("
                     + "; ".join(w["warning"] for w in blocking) + ").")
    elif likelier and top:
        parts.append("What the models leave out can only make collapse likelier here ("
                     + "; ".join(w["warning"] for w in likelier) + ").")
    tr = prior.get("traffic")
    if tr is not None:
        parts.append(f"Traffic check (statics): the {tr['load_kN_m']:g} kN/m "
                     f"{tr['kind']} collapses the arch at {tr['adequacy_factor']:.3g} times "
                     f"itself, at {tr['critical_position_m']:.3g} m from the left springing "
                     "(the adequacy factor).")
        numbers["traffic_adequacy_factor"] = tr["adequacy_factor"]
    parts.append("Assumptions: " + ", ".join(assumptions(config)) + ".")
    if level in ("collapse likely",) or code_fails:
        outcome = "fails"
    elif level in ("at risk", "rocks: dynamics not assessed"):
        outcome = "at-risk"
    elif level == "capacity only":
        outcome = "open"
    else:
        outcome = "passes"
    headline = (level[0].upper() + level[1:] + (", indicative" if indicative else "")
                + ("" if certain else ", NOT CONCLUSIVE") + head_code)
    return {"level": level, "certain": certain, "outcome": outcome, "indicative": indicative,
            "headline": headline, "text": headline + ". " + " ".join(parts),
            "numbers": numbers}


SECTIONS: tuple[tuple[str, Callable[[Context], StudyResult]], ...] = (
    ("arch", section_arch), ("static", section_static), ("traffic", section_traffic),
    ("pulses", section_pulses),
    ("records", section_records), ("dem", section_dem), ("validity", section_validity),
    ("vertical", section_vertical), ("codecheck", section_code_check))

__all__ = ["ASSUMPTIONS", "COLLAPSE_LIKELIER", "LOADS_ASSUMPTION", "TRAFFIC_POSITIONS",
           "assumptions", "OUTCOMES", "Context", "Mode", "Progress",
           "SECTIONS", "dynamics_refusal",
           "prepared_mechanism", "rigid_scan_ceiling",
           "run_ida",
           "strong_motion_end", "used_restitution", "verdict", "with_dem_warnings"]
