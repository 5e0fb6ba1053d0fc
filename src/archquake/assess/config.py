"""The assessment file (TOML): the arch, the seismic input and the options, validated before any
computation.

::

    [arch]          # the study files' arch keys (archquake.sweeps.ArchSpec), one value each
    radius = 5.0            # m  (circular by radius: radius, thickness_ratio, embrace_deg)
    thickness_ratio = 0.12  #    (or shape, span, rise, thickness [m], joints)
    embrace_deg = 180       # degrees
    voussoirs = 15
    density = 1800          # kg/m^3 (default 2000)
    depth = 1.0             # m (default 1)
    friction = 0.6          # friction coefficient of the joints (required)
    # piers: pier_height, pier_width (m), pier_courses
    # or a surveyed arch: blocks = "arch.json" (.json, .csv or .dxf, relative to this file),
    # with only depth, density and friction beside it

    [seismic]
    site_pga_g = 0.15                # the site's peak ground acceleration, g (without [site]:
                                     # with it, a_g S_S S_T of the SLV spectrum is the site PGA)
    site_pga_override = false        # true: site_pga_g replaces the [site] table's PGA
    suite = "near-field-pulse"       # a FEMA P695 set, a folder, a .list file, or a list of files
    units = "g"                      # units of CSV records (g, m/s2, cm/s2): required with them
    vertical_ratio = 0.5             # the pulses' vertical part R (R a s(t) upward), in [-2, 2]:
                                     # the vertical section compares the pulses with and without
                                     # it (a .list suite naming each record's vertical after it
                                     # compares the records the same way)

    [options]
    model = "rigid"         # the model of every verdict: "rigid" (default, the chain of rigid
                            # voussoirs) or "fourlink" (the paper's four-link mechanism)
    impact = "paper"        # fourlink only: impact law, paper, chain or mirror
    restitution = 0.8       # fourlink only: prescribed c_v in (0, 1] (instead of the law's)
    dem = true              # run the distinct-element check

    [loads]         # what the arch carries (docs/loads.md; per metre of barrel width)
    fill_depth = 0.8        # m over the crown's extrados (or fill_level = y, m)
    fill_density = 1900     # kg/m^3
    backing = 1.5           # m above each springing (backing_right if it differs)
    point_loads = [{position = 2.0, load_kN = 30.0}]           # masses that move with the arch
    distributed_loads = [{start = 3.0, end = 5.0, load_kN_m = 40.0}]
    traffic = {axle_kN = 100.0, dispersion_deg = 26.57}      # the traffic check (statics only)

Every problem is one line naming the key as the file spells it (``[arch] radius``), raised as
`StudyFileError` (exit status 2 on the command line). Every record
file of the suite is read and checked here, before anything is computed. A value far outside
practice (a PGA above 1.5 g, a radius below 0.2 m) is accepted with a one-line note naming the
key (`AssessConfig.notes`); one that can only be a mistake (an embrace in radians) is
refused.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from archquake.assess.site import SITE_KEYS, SiteConfig, parse_site
from archquake.errors import ArchquakeError, StudyFileError
from archquake.geometry.loads import LOADS_KEYS  # the keys of [loads], as the study files'

#: Keys of [arch]: the study files' arch keys (one home: archquake.sweeps.study) and friction.
ARCH_KEYS = ("radius", "thickness_ratio", "embrace_deg", "voussoirs", "depth", "density", "shape",
             "span", "rise", "thickness", "joints", "pier_height", "pier_width", "pier_courses",
             "blocks", "friction")
SEISMIC_KEYS = ("site_pga_g", "site_pga_override", "suite", "units", "vertical_ratio")
OPTION_KEYS = ("model", "impact", "restitution", "dem")
#: The models an assessment's verdicts may rest on (the DEM is its check, ``dem = true``).
ASSESS_MODELS = ("rigid", "fourlink")
TABLES = {"arch": ARCH_KEYS, "seismic": SEISMIC_KEYS, "options": OPTION_KEYS,
          "site": SITE_KEYS, "loads": LOADS_KEYS}
_WORDS = ("shape", "joints")
_INTEGERS = ("voussoirs", "pier_courses")


@dataclass(frozen=True)
class AssessConfig:
    """A validated assessment file.

    Attributes
    ----------
    arch : ArchSpec
        The arch, in study units (m, degrees, kg/m^3).
    friction : float
        Friction coefficient of the joints, dimensionless (> 0).
    site_pga_g : float or None
        Site peak ground acceleration, g.
    suite : str or tuple of str or None
        FEMA P695 set name, folder, ``.list`` file, one file, or a tuple of files (absolute).
    units : str or None
        Units of CSV/text records.
    impact : str
        Impact law of the four-link model (`archquake.mechanism.impact.IMPACT_LAWS`).
    restitution : float or None
        Prescribed c_v of the four-link model (overrides the impact law's), in (0, 1].
    dem : bool
        Run the distinct-element check.
    source : str
        The file read (for messages).
    model : str
        The model of the dynamic verdicts, "rigid" (default) or "fourlink"
        (`ASSESS_MODELS`).
    site : SiteConfig or None
        The ``[site]`` table (`archquake.assess.site`): the code check's site, knowledge
        level and position.
    site_pga_source : str or None
        Where ``site_pga_g`` comes from, in words (the [site] table's a_g S_S S_T with its
        factors, or ``[seismic] site_pga_g``).
    notes : tuple of str
        One line per input far outside practice, and per override stated (printed before the
        run and in the report).
    loads : Loads or None
        The ``[loads]`` table (`loads_from_table`): every
        section carries its dead loads (`dead_loads`); its traffic is the traffic
        check's.
    vertical_ratio : float or None
        ``[seismic] vertical_ratio``: the pulses' vertical part R, in [-2, 2] (None: not given).
    suite_vertical : bool
        Some record of the suite carries its vertical component (a ``.list`` file naming it).
    """

    arch: Any
    friction: float
    site_pga_g: float | None
    suite: str | tuple[str, ...] | None
    units: str | None
    impact: str
    restitution: float | None
    dem: bool
    source: str = "assessment"
    model: str = "rigid"
    site: SiteConfig | None = None
    site_pga_source: str | None = None
    notes: tuple[str, ...] = ()
    loads: Any = None
    vertical_ratio: float | None = None
    suite_vertical: bool = False

    @property
    def dead_loads(self):
        """What the arch carries in every section (the ``[loads]`` table without its traffic),
        or None: a bare arch."""
        if self.loads is None:
            return None
        dead = self.loads.without_traffic()
        return None if dead.empty else dead

    def canonical(self) -> dict:
        """Everything that determines the results (the cache key's input). The ``[site]`` and
        ``[loads]`` tables enter only when given, so a file without them keeps its digest."""
        out = {"arch": self.arch.canonical(), "friction": self.friction,
               "site_pga_g": self.site_pga_g,
               "suite": list(self.suite) if isinstance(self.suite, tuple) else self.suite,
               "units": self.units, "impact": self.impact, "restitution": self.restitution,
               "dem": self.dem, "model": self.model}
        if self.site is not None:
            out["site"] = self.site.canonical()
        if self.loads is not None:
            out["loads"] = self.loads.to_dict()
        if self.vertical_ratio is not None:
            out["vertical_ratio"] = self.vertical_ratio
        return out

    @property
    def digest(self) -> str:
        """First 10 hex digits of the SHA-256 of `canonical` (names the cache entries)."""
        text = json.dumps(self.canonical(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:10]

    def build_arch(self):
        """The arch (`ArchSpec.build`)."""
        return self.arch.build()


def _fail(source: str, key: str, what: str) -> StudyFileError:
    return StudyFileError(f"{source}: {key} {what}")


def _number(source: str, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(source, key, f"must be a finite number, got {value!r}")
    return float(value)


def load_config(path: str | Path) -> AssessConfig:
    """Read and validate an assessment file (nothing is computed; record files are only
    checked to exist, FEMA set names to be known).

    Raises
    ------
    StudyFileError
        One line naming the key: unknown table or key, missing [arch], a value out of range, a
        record file or folder that does not exist.
    """
    path = Path(path)
    source = path.name
    from archquake.sweeps.study import read_toml

    data = read_toml(path, "assessment file")
    return parse_config(data, source=source, base_dir=path.parent)


def parse_config(data: dict, *, source: str = "assessment",
                 base_dir: Path | None = None) -> AssessConfig:
    """Validate the parsed TOML ``data`` (see `load_config`); relative record paths are
    relative to ``base_dir``."""
    from archquake.sweeps.cases import ArchSpec

    base_dir = Path.cwd() if base_dir is None else Path(base_dir)
    for name, value in data.items():
        if name not in TABLES:
            raise _fail(source, f"[{name}]", f"is not a known table; expected {list(TABLES)}")
        if not isinstance(value, dict):
            raise _fail(source, name, f"must be a [{name}] table")
        for key in value:
            if key not in TABLES[name]:
                raise _fail(source, f"[{name}] {key}",
                            f"is not a known key; expected one of {list(TABLES[name])}")
    if "arch" not in data:
        raise _fail(source, "[arch]", "is missing: the file must describe the arch")
    arch_t = dict(data["arch"])
    if "friction" not in arch_t:
        raise _fail(source, "[arch] friction", "is missing: the joints' friction coefficient")
    friction = _number(source, "[arch] friction", arch_t.pop("friction"))
    if not 0 < friction <= 10:
        raise _fail(source, "[arch] friction", f"must be in (0, 10], got {friction:g}")
    kwargs: dict[str, Any] = {}
    for key, value in arch_t.items():
        if key == "blocks":
            if not isinstance(value, str) or not value:
                raise _fail(source, "[arch] blocks", f"must be the path of a .json, .csv or "
                                                     f".dxf file, got {value!r}")
            full = (base_dir / value).resolve()
            if not full.is_file():
                raise _fail(source, "[arch] blocks", f"names {value!r}, which does not exist "
                                                     "(paths are relative to the file)")
            kwargs[key] = str(full)
        elif key in _WORDS:
            if not isinstance(value, str):
                raise _fail(source, f"[arch] {key}", f"must be a word, got {value!r}")
            kwargs[key] = value
        elif key in _INTEGERS:
            if isinstance(value, bool) or not isinstance(value, int):
                raise _fail(source, f"[arch] {key}", f"must be a whole number, got {value!r}")
            kwargs[key] = value
        else:
            kwargs[key] = _number(source, f"[arch] {key}", value)
    notes: list[str] = []
    embrace = kwargs.get("embrace_deg")
    from archquake.ranges import PLAUSIBLE_PGA_G, PLAUSIBLE_RADIUS_M, RADIANS_EMBRACE_DEG

    if isinstance(embrace, float) and 0.0 < embrace <= RADIANS_EMBRACE_DEG + 1e-9:
        raise _fail(source, "[arch] embrace_deg", f"= {embrace:g} looks like radians "
                                                  f"({math.degrees(embrace):.4g} degrees): the "
                                                  "key is in degrees, e.g. 180 for a semicircle")

    radius = kwargs.get("radius")
    if isinstance(radius, float) and 0.0 < radius < PLAUSIBLE_RADIUS_M:
        notes.append(f"[arch] radius = {radius:g} m is below {PLAUSIBLE_RADIUS_M:g} m, "
                     "smaller than any masonry arch: is it in m?")
    try:
        spec = ArchSpec(**kwargs)
        arch = spec.build()
    except ArchquakeError as exc:
        text = str(exc)
        if "blocks" in kwargs and text.startswith(f"--blocks {kwargs['blocks']}: "):
            text = text[len(f"--blocks {kwargs['blocks']}: "):]  # read_blocks names the file
        bad = next((k for k in kwargs if text.startswith(k)), None)
        raise _fail(source, f"[arch] {bad}" if bad else "[arch]", f"is invalid: {text}") from None
    from archquake.limit import stands
    if not stands(arch):
        from archquake.limit.static import min_pier_width, unstable_error
        if "pier_width" in kwargs and stands(arch.arch):
            wide = min_pier_width(arch)
            raise _fail(source, "[arch] pier_width",
                        f"= {kwargs['pier_width']:g} m is too narrow: the piers cannot stand "
                        "under the arch's thrust"
                        + ("" if wide is None else f"; piers "
                           f"{math.ceil(wide * 1000.0) / 1000.0:.3f} m wide would stand")
                        + " (or lower pier_height)")
        raise _fail(source, "[arch]", f"is invalid: {unstable_error(arch)}")

    loads = None if "loads" not in data else _loads(source, data["loads"], arch)

    seismic = data.get("seismic", {})
    site = None
    if "site_pga_g" in seismic:
        site = _number(source, "[seismic] site_pga_g", seismic["site_pga_g"])
        if not 0 < site <= 5:
            raise _fail(source, "[seismic] site_pga_g", f"must be in (0, 5] g, got {site:g}")
    override = seismic.get("site_pga_override", False)
    if not isinstance(override, bool):
        raise _fail(source, "[seismic] site_pga_override", f"must be true or false, got "
                                                           f"{override!r}")
    units = seismic.get("units")
    if units is not None:
        from archquake.ground.records import UNITS
        if units not in UNITS:
            raise _fail(source, "[seismic] units", f"must be one of {list(UNITS)}, got {units!r}")
    suite = _suite(source, seismic.get("suite"), base_dir)
    if site is None and suite is None and "site" not in data:
        raise _fail(source, "[seismic]", "needs site_pga_g (g) and/or suite (a record set), "
                                         "or a [site] table")
    suite_vertical = suite is not None and check_suite(source, suite, units, base_dir)
    vertical_ratio = None
    if "vertical_ratio" in seismic:
        vertical_ratio = _number(source, "[seismic] vertical_ratio", seismic["vertical_ratio"])
        if not -2.0 <= vertical_ratio <= 2.0:
            raise _fail(source, "[seismic] vertical_ratio", f"must be in [-2, 2] (the pulses' "
                                                            f"vertical over their horizontal), "
                                                            f"got {vertical_ratio:g}")

    options = data.get("options", {})
    from archquake.models import model_of, takes

    try:  # the words of --model, with a pointer for the retired ones
        model = model_of(options.get("model"), model_name="[options] model").value
    except ArchquakeError as exc:
        raise StudyFileError(f"{source}: {exc}") from None
    if model not in ASSESS_MODELS:
        raise _fail(source, "[options] model", f"must be one of {list(ASSESS_MODELS)}, got "
                                               f"{model!r} (the DEM is the check: dem = true)")
    if not takes(model, "restitution"):
        for key in ("impact", "restitution"):
            if key in options:
                raise _fail(source, f"[options] {key}", f"applies to model = \"fourlink\" "
                                                        f"only: the {model} model's impacts "
                                                        "follow from its contacts; leave it out")
    from archquake.mechanism.impact import IMPACT_LAWS
    impact = options.get("impact", "paper")
    if impact not in IMPACT_LAWS:
        raise _fail(source, "[options] impact", f"must be one of {list(IMPACT_LAWS)}, got "
                                                f"{impact!r}")
    restitution = None
    if "restitution" in options:
        restitution = _number(source, "[options] restitution", options["restitution"])
        if not 0 < restitution <= 1:
            raise _fail(source, "[options] restitution", f"must be in (0, 1], got "
                                                         f"{restitution:g}")
    dem = options.get("dem", True)
    if not isinstance(dem, bool):
        raise _fail(source, "[options] dem", f"must be true or false, got {dem!r}")
    site_table = None if "site" not in data else parse_site(data["site"], source=source)
    if site_table is not None and "time_history" in data["site"]:
        key = "[site] time_history"
        th = _suite(source, data["site"]["time_history"], base_dir, key=key)
        if not isinstance(th, str):
            raise _fail(source, key, "must be one set name or path (a FEMA P695 set, a folder "
                                     "or a .list file)")
        check_suite(source, th, units, base_dir, key=key)
        from dataclasses import replace as _replace

        site_table = _replace(site_table, time_history=th)
    site, site_source = _site_pga(source, site, override, site_table, notes)
    for key, value in (("[seismic] site_pga_g", site),
                       ("[site] ag_g", None if site_table is None else site_table.ag_g)):
        if value is not None and value > PLAUSIBLE_PGA_G:
            notes.append(f"{key} = {value:g} g is above {PLAUSIBLE_PGA_G:g} g, beyond design "
                         "practice: is it in g (not m/s^2)?")
    if site_table is not None and site_table.hazard is not None:
        top = max(p[1] for p in site_table.hazard)
        if top > PLAUSIBLE_PGA_G:
            notes.append(f"[site] hazard has a_g = {top:g} g, above {PLAUSIBLE_PGA_G:g} g, "
                         "beyond design practice: is it in g (not m/s^2)?")
    return AssessConfig(spec, friction, site, suite, units, impact, restitution, dem, source,
                        model=model, site=site_table, site_pga_source=site_source,
                        notes=tuple(notes), loads=loads, vertical_ratio=vertical_ratio,
                        suite_vertical=bool(suite_vertical))


def _loads(source: str, table: Any, arch) -> Any:
    """The ``[loads]`` table read (`loads_from_table`) and
    checked against ``arch``: an arch that can carry loads (no piers, an extrados running left
    to right), positions on its clear span, a fill surface at or above the extrados; and loads
    every section can carry: the dynamic models carry masses that move with the arch, so
    passive pressure and ``moves_with_arch = false`` are refused."""
    from archquake.geometry.loads import Extrados, loads_from_table

    loads = loads_from_table(table, source=source)
    try:
        extrados = Extrados.of(arch)
    except ArchquakeError as exc:
        key = "[arch] pier_height" if "piers" in str(exc) else "[arch]"
        raise _fail(source, "[loads]", f"cannot be carried: {exc} ({key})") from None
    span = extrados.clear_span
    where = (f"must lie on the clear span, 0 to {span:.4g} m from the left springing of the "
             "intrados")
    for i, p in enumerate(loads.point_loads):
        if p.position > span:
            raise _fail(source, f"[loads] point_loads[{i}] position",
                        f"= {p.position:g} m {where}")
        if not p.moves_with_arch:
            raise _fail(source, f"[loads] point_loads[{i}] moves_with_arch",
                        "= false: a weight without mass is statics only, and the assessment's "
                        "dynamic sections carry masses that move with the arch; leave it out "
                        "(archquake static and check take it)")
    for i, d in enumerate(loads.distributed_loads):
        if d.end > span:
            raise _fail(source, f"[loads] distributed_loads[{i}] end", f"= {d.end:g} m {where}")
        if not d.moves_with_arch:
            raise _fail(source, f"[loads] distributed_loads[{i}] moves_with_arch",
                        "= false: a weight without mass is statics only, and the assessment's "
                        "dynamic sections carry masses that move with the arch; leave it out "
                        "(archquake static and check take it)")
    if loads.traffic is not None and loads.traffic.position > span:
        raise _fail(source, "[loads] traffic position", f"= {loads.traffic.position:g} m {where}")
    if loads.passive is not None:
        from archquake.blocks.assembly import PASSIVE_LEFT_OUT

        raise _fail(source, "[loads] passive", f"is not taken by an assessment: "
                                               f"{PASSIVE_LEFT_OUT}; leave it out "
                                               "(archquake static and capacity take it)")
    if loads.fill is not None:
        try:
            loads.fill.surface(arch)
        except ArchquakeError as exc:
            raise _fail(source, "[loads] fill_level", f"is invalid: {exc}") from None
    return loads


def _site_pga(source: str, given: float | None, override: bool, site: SiteConfig | None,
              notes: list[str]) -> tuple[float | None, str | None]:
    """The site PGA of the dynamic sections (g) and where it comes from: with a ``[site]``
    table its a_g S_S S_T (`SiteConfig.site_pga_g`); a ``[seismic] site_pga_g`` beside
    it must agree (to 0.5 %), or be stated to override it (a note says so)."""
    if site is None:
        if override:
            raise _fail(source, "[seismic] site_pga_override", "applies only with a [site] "
                                                               "table (whose PGA it overrides)")
        return given, None if given is None else "[seismic] site_pga_g"
    derived = site.site_pga_g()
    words = site.describe_pga()
    if given is None:
        return derived, words
    if math.isclose(given, derived, rel_tol=5e-3, abs_tol=5e-4):
        return given, f"[seismic] site_pga_g, as the [site] table's {words}"
    if not override:
        raise _fail(source, "[seismic] site_pga_g",
                    f"= {given:g} g differs from the [site] table's {words}: leave site_pga_g "
                    "out (the [site] table sets the site PGA), or state site_pga_override = "
                    f"true to run the dynamic sections at {given:g} g")
    notes.append(f"[seismic] site_pga_g = {given:g} g overrides the [site] table's "
                 f"{derived:.4g} g (site_pga_override = true): the dynamic sections run at "
                 f"{given:g} g, the code check at the [site] table's spectra")
    return given, f"[seismic] site_pga_g (overriding the [site] table's {words})"


def check_suite(source: str, suite: str | tuple[str, ...], units: str | None,
                base_dir: Path, *, key: str = "[seismic] suite") -> bool:
    """Read every record of the suite as the records section will, so that a malformed file or
    a missing ``units`` stops the run before anything is computed, in one line naming the key
    and the file as the assessment file names it (relative to it). True if some record carries
    its vertical component.

    A FEMA P695 set is the records package's own data, which carries the horizontal
    components only: it is not read here (a second of the run's single-threaded start), but
    where it is used, in the records section's thread, beside the other sections' kernels."""
    from archquake.ground.base import has_vertical
    from archquake.ground.suites import FEMA_SUITES, load_suite

    if isinstance(suite, str) and suite in FEMA_SUITES and not Path(suite).exists():
        return False
    try:
        loaded = load_suite(list(suite) if isinstance(suite, tuple) else suite, units=units)
        return any(has_vertical(r) for r in loaded)
    except ArchquakeError as exc:
        text = str(exc)
        for root in {str(base_dir.resolve()), str(base_dir)}:
            text = text.replace(root.rstrip("/") + "/", "")
        which = "[seismic] units" if "units of" in text and "must be given" in text else key
        raise _fail(source, which, f"is invalid: {text}") from None


def _suite(source: str, value: Any, base_dir: Path, *,
           key: str = "[seismic] suite") -> str | tuple[str, ...] | None:
    """The suite as load_suite takes it, with every path checked to exist (absolute)."""
    if value is None:
        return None
    if isinstance(value, list):
        if not value or not all(isinstance(v, str) for v in value):
            raise _fail(source, key, "must be a set name, a path, or a non-empty list of paths")
        out = []
        for v in value:
            p = (base_dir / v).resolve()
            if not p.is_file():
                raise _fail(source, key, f"names {v!r}, which does not exist")
            out.append(str(p))
        return tuple(out)
    if not isinstance(value, str) or not value:
        raise _fail(source, key, f"must be a set name, a path, or a list of paths, got {value!r}")
    from archquake.ground.suites import ALIASES, FEMA_SUITES, fema_available

    p = (base_dir / value)
    if p.exists():
        return str(p.resolve())
    name = ALIASES.get(value.lower(), value.lower())
    if name in FEMA_SUITES:
        if not fema_available():
            raise _fail(source, key, f"{value!r} needs the FEMA P695 records: "
                                     "pip install 'archquake[records]'")
        return name
    known = ", ".join(list(FEMA_SUITES) + sorted(ALIASES))
    raise _fail(source, key, f"{value!r} is not a file or folder that exists, nor a set name "
                             f"({known})")


__all__ = ["ARCH_KEYS", "ASSESS_MODELS", "AssessConfig", "check_suite", "load_config",
           "parse_config"]
