"""Study files: a TOML grid of arches x excitations x options, expanded into `Case` s.

The schema (documented with a full example in ``docs/sweeps.md``)::

    [study]
    name = "scale"                      # required; default store is <name>.sqlite beside the file
    model = "rigid"                     # optional: "rigid" (default, the chain of rigid
                                        # voussoirs), "fourlink" (the paper's four-link
                                        # mechanism) or "dem", as archquake run --model

    [arches]                            # each axis: a number, a list, or {start, stop, num}
    radius = [1, 5, 10, 20]             # m (circular arch: radius, thickness_ratio, embrace_deg)
    thickness_ratio = 0.15              # t/R
    embrace_deg = 157.5                 # degrees
    voussoirs = 7                       # (required)
    depth = 1.0                         # m (optional, default 1)
    density = 2000.0                    # kg/m^3 (optional, default 2000)
    # or any shape (docs/geometry.md): shape = "pointed" (a word or a list of words),
    # span = 10, rise = 7, thickness = 0.8 (m), joints = "radial" | "vertical",
    # pier_height = 4, pier_width = 1.5 (m), pier_courses = 3
    # or surveyed arches: blocks = "survey.json" (or a list of .json/.csv/.dxf files, relative
    # to this file), with only depth and density beside it (voussoirs is then not asked for)

    [excitation]                        # or several [[excitation]] blocks, concatenated
    type = "step"                       # "step", "sine" or "record"
    magnitude_g = {start = 0.3, stop = 1.5, num = 25}   # g (step, sine)
    duration_s = [0.1, 0.25]            # s (step: t_p)
    # period_s = [0.5, 1.0]             # s (sine: T)
    # files = ["a.AT2"]; units = "g"; scale = [0.5, 1, 2]   (record; paths relative to the study)
    direction = -1                      # optional: -1 (default for pulses) or +1, or [-1, 1]
    # vertical_ratio = [0, 0.5]         # optional (step, sine): the vertical part R a s(t), up

    [loads]                             # optional: what every arch carries, as in assess
    fill_depth = 1.0                    # m over the crown (fill_density, backing, point_loads,
                                        # distributed_loads: geometry.loads.loads_from_table)

    [options]                           # optional; axes like the others
    restitution = 0.9                   # c_v in [0, 1] (0 perfectly plastic); omitted: the law's
    impact = "chain"                    # "paper" (Eq. 4), "chain" or "mirror"; omitted: "paper"
    t_end_s = 10.0                      # s; omitted: the model's default

Every error is one line naming the file, the key and what is expected
(`StudyFileError`).
"""

from __future__ import annotations

import itertools
import math
import stat
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

import numpy as np

from archquake.errors import ArchquakeError, InvalidParameterError, StudyFileError
from archquake.models import Model, model_of
from archquake.sweeps.cases import (
    RECORD_UNITS,
    ArchSpec,
    Case,
    CaseOptions,
    ExcitationKind,
    ExcitationSpec,
)

_AXIS = "a number, a list of numbers, or {start, stop, num}"
_TABLES = ("study", "arches", "excitation", "options", "loads")
_STUDY_KEYS = {"name": True, "model": False, "hinges": False}
_ARCH_KEYS = {"radius": False, "thickness_ratio": False, "embrace_deg": False, "voussoirs": True,
              "depth": False, "density": False, "shape": False, "span": False, "rise": False,
              "thickness": False, "joints": False, "pier_height": False, "pier_width": False,
              "pier_courses": False, "blocks": False}
#: Keys of [arches] whose values are words (a word or a list of words), not numbers.
_ARCH_WORDS = ("shape", "joints", "blocks")
_EXCITATION_KEYS = {
    ExcitationKind.STEP: {"magnitude_g": True, "duration_s": True, "direction": False,
                          "vertical_ratio": False},
    ExcitationKind.SINE: {"magnitude_g": True, "period_s": True, "direction": False,
                          "vertical_ratio": False},
    ExcitationKind.RECORD: {"files": True, "units": False, "scale": False, "direction": False},
}
_OPTION_KEYS = {"restitution": False, "impact": False, "t_end_s": False}
#: Keys of [options] whose values are words.
_OPTION_WORDS = ("impact",)


def _words(p, table: dict, where: str, keys) -> dict[str, list]:
    """The word-valued keys of a table (a word or a list of words), as lists."""
    words = {}
    for key in keys:
        if key in table:
            value = table[key]
            values = value if isinstance(value, list) else [value]
            if not values or not all(isinstance(v, str) for v in values):
                p.fail(f"{where}.{key}", f"must be a word or a list of words, got {value!r}")
            words[key] = values
    return words

#: Most cases one study may hold. A case costs about 1 kB in memory and a row in the store;
#: two million build in seconds. Larger grids are refused before they are expanded.
MAX_CASES = 2_000_000


@dataclass(frozen=True)
class Study:
    """A parsed study: its name, model, the file it came from and its cases in grid order.

    Attributes
    ----------
    name : str
    model : Model
    path : Path or None
        The study file (None for a study built from a dict without a file).
    cases : tuple of Case
        Arches (outermost) x excitations x options (innermost), duplicates removed.
    """

    name: str
    model: Model
    path: Path | None
    cases: tuple[Case, ...]

    @property
    def default_store(self) -> Path:
        """``<name>.sqlite`` beside the study file (or in the working directory)."""
        folder = self.path.parent if self.path is not None else Path.cwd()
        return folder / f"{self.name}.sqlite"


#: Largest study file read, bytes: a study is a few tables; its grids are ranges, not lists.
MAX_STUDY_BYTES = 16 * 10**6


def _has_control(text: str) -> bool:
    """True if ``text`` holds a control character (NUL, newline, ...): no file name takes one."""
    return any(ord(c) < 32 or ord(c) == 127 for c in text)


def read_toml(path: Path, what: str) -> dict[str, Any]:
    """The parsed TOML file ``path`` (``what`` names it in messages, e.g. "study file"), read
    only if it is a regular file of reasonable size; every failure is one
    `StudyFileError` line naming the file."""
    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode):  # a device or pipe could stream or block forever
            raise StudyFileError(f"{what} {str(path)!r} is not a regular file")
        if info.st_size > MAX_STUDY_BYTES:
            raise StudyFileError(f"{what} {str(path)!r} is {info.st_size / 1e6:.0f} MB; a "
                                 f"{what} may hold at most {MAX_STUDY_BYTES / 1e6:.0f} MB")
        with path.open("rb") as fh:
            data = tomllib.load(fh)
    except RecursionError:  # tomllib recurses once per level of nested arrays or tables
        raise StudyFileError(f"{path.name}: arrays or tables nested too deeply for the TOML "
                             f"reader (a {what} needs two or three levels)") from None
    except FileNotFoundError:
        raise StudyFileError(f"{what} {str(path)!r} does not exist") from None
    except OSError as exc:
        raise StudyFileError(f"cannot read {what} {str(path)!r}: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise StudyFileError(f"{path.name}: not valid TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        line = data_line(path, exc.start)
        raise StudyFileError(f"{path.name}: line {line}: byte 0x{exc.object[exc.start]:02x} is "
                             "not UTF-8 (TOML files are UTF-8; re-save the file as UTF-8)") from None
    return data


def load_study(path: str | Path) -> Study:
    """Read and validate a ``STUDY.toml`` file.

    Raises
    ------
    StudyFileError
        One line naming the file, the key and what is expected.
    """
    path = Path(path)
    data = read_toml(path, "study file")
    return parse_study(data, source=path.name, base_dir=path.parent, path=path)


def parse_study(data: dict[str, Any], *, source: str = "study", base_dir: Path | None = None,
                path: Path | None = None) -> Study:
    """Validate a study's TOML tables and expand the grid (see the module docstring)."""
    p = _Parser(source, base_dir or Path.cwd())
    unknown = sorted(set(data) - set(_TABLES))
    if unknown:
        p.fail(unknown[0], f"is not a study table; expected tables {list(_TABLES)}")
    study = p.table(data, "study", required=True)
    p.keys(study, "study", _STUDY_KEYS)
    name = study["name"]
    if (not isinstance(name, str) or not name.strip() or any(c in name for c in "/\\")
            or _has_control(name)):
        p.fail("study.name", f"must be a non-empty string without slashes or control "
                             f"characters (it names the store file), got {name!r}")
    try:  # the words of archquake run --model (hinges is retired: a pointer to model)
        model = model_of(study.get("model"), study.get("hinges"),
                         model_name="study.model", hinges_name="study.hinges")
    except InvalidParameterError as exc:
        raise StudyFileError(f"{p.source}: {exc}") from None

    arches_table = p.table(data, "arches", required=True)
    # a block file (a surveyed arch) replaces the shape, voussoirs included
    p.keys(arches_table, "arches", dict(_ARCH_KEYS, voussoirs="blocks" not in arches_table))
    words = _words(p, arches_table, "arches", _ARCH_WORDS)
    if "blocks" in words:
        words["blocks"] = [p.existing("arches.blocks", b) for b in words["blocks"]]
    numbers = {k: v for k, v in arches_table.items() if k not in _ARCH_WORDS}
    arches = p.grid("arches", numbers, ArchSpec, integer={"voussoirs", "pier_courses"},
                    listed=words)

    blocks = data.get("excitation")
    if blocks is None:
        p.fail("excitation", "is missing; expected an [excitation] table")
    if isinstance(blocks, dict):
        blocks = [blocks]
    if not isinstance(blocks, list) or not blocks or not all(isinstance(b, dict) for b in blocks):
        p.fail("excitation", "must be an [excitation] table or [[excitation]] tables")
    excitations: list[ExcitationSpec] = []
    for i, block in enumerate(blocks):
        excitations.extend(p.excitations(block, "excitation" if len(blocks) == 1
                                         else f"excitation[{i}]"))

    options_table = p.table(data, "options", required=False)
    p.keys(options_table, "options", _OPTION_KEYS)
    option_words = _words(p, options_table, "options", _OPTION_WORDS)
    options = p.grid("options", {k: v for k, v in options_table.items()
                                 if k not in _OPTION_WORDS}, CaseOptions, listed=option_words)

    loads = None
    if "loads" in data:
        from archquake.geometry.loads import loads_from_table

        loads = loads_from_table(data["loads"], source=p.source)
        if (loads.traffic is not None or loads.passive is not None
                or any(not q.moves_with_arch for q in loads.point_loads)
                or any(not d.moves_with_arch for d in loads.distributed_loads)):
            p.fail("loads", "a sweep's loads are masses that move with the arch: traffic, "
                            "passive and moves_with_arch = false are statics only")

    total = len(arches) * len(excitations) * len(options)
    if total > MAX_CASES:
        p.fail("grid", f"has {total:,} cases (arches {len(arches):,} x excitations "
                       f"{len(excitations):,} x options {len(options):,}), more than the "
                       f"{MAX_CASES:,} one study may hold; split it into several studies "
                       "(they may share one store with --store)")
    cases: dict[str, Case] = {}
    for arch, excitation, opts in itertools.product(arches, excitations, options):
        case = Case(arch, excitation, model, opts, loads)
        cases.setdefault(case.case_id, case)
    return Study(name=name.strip(), model=model, path=path, cases=tuple(cases.values()))


class _Parser:
    def __init__(self, source: str, base_dir: Path):
        self.source = source
        self.base_dir = base_dir

    def fail(self, key: str, what: str) -> NoReturn:
        raise StudyFileError(f"{self.source}: {key} {what}")

    def table(self, data: dict, name: str, *, required: bool) -> dict:
        value = data.get(name)
        if value is None:
            if required:
                self.fail(name, f"is missing; expected a [{name}] table")
            return {}
        if not isinstance(value, dict):
            self.fail(name, f"must be a [{name}] table, got {type(value).__name__}")
        return value

    def keys(self, table: dict, where: str, spec: dict[str, bool]) -> None:
        for key in table:
            if key not in spec:
                self.fail(f"{where}.{key}", f"is not a known key; expected one of {list(spec)}")
        for key, required in spec.items():
            if required and key not in table:
                self.fail(f"{where}.{key}", "is missing (required)")

    def existing(self, key: str, name: str) -> str:
        """``name`` relative to the study file, absolute; one line if it does not exist."""
        if not isinstance(name, str) or _has_control(name):
            self.fail(key, f"must be a file name without control characters, got {name!r}")
        full = (self.base_dir / name).resolve()
        if not full.is_file():
            self.fail(key, f"names {name!r}, which does not exist (paths are relative to the "
                           "study file)")
        return str(full)

    def axis(self, key: str, value: Any, *, integer: bool = False) -> list:
        """A number, a list of numbers, or {start, stop, num} (inclusive linspace)."""
        if isinstance(value, dict):
            if set(value) != {"start", "stop", "num"}:
                self.fail(key, f"must be {_AXIS}; a range needs exactly start, stop and num, "
                               f"got keys {sorted(value)}")
            start, stop, num = value["start"], value["stop"], value["num"]
            if not (_is_number(start) and _is_number(stop)):
                self.fail(key, f"range start and stop must be numbers, got {start!r}, {stop!r}")
            if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_CASES:
                self.fail(key, f"range num must be a whole number from 1 to {MAX_CASES:,}, "
                               f"got {num!r}")
            # 12 significant digits: 1.05, not linspace's 1.0499999999999998, in ids and tables
            values = [float(f"{v:.12g}") for v in np.linspace(start, stop, num)]
        elif isinstance(value, list):
            if not value:
                self.fail(key, f"must be {_AXIS}, got an empty list")
            values = value
        else:
            values = [value]
        for v in values:
            if not _is_number(v) or not math.isfinite(v):
                self.fail(key, f"must be {_AXIS} (finite), got {v!r}")
            if integer and float(v) != round(float(v)):
                self.fail(key, f"must be whole numbers, got {v!r}")
        return [int(round(v)) if integer else v for v in values]

    def grid(self, where: str, table: dict, build, *, integer: frozenset | set = frozenset(),
             fixed: dict | None = None, listed: dict[str, list] | None = None) -> list:
        names = list(table)
        axes = [self.axis(f"{where}.{k}", table[k], integer=k in integer) for k in names]
        for k, values in (listed or {}).items():
            names.append(k)
            axes.append(values)
        size = math.prod(len(a) for a in axes)
        if size > MAX_CASES:
            self.fail(where, f"has {size:,} combinations, more than the {MAX_CASES:,} cases one "
                             "study may hold; split it into several studies")
        out = []
        for combo in itertools.product(*axes):
            kwargs = dict(zip(names, combo, strict=True), **(fixed or {}))
            try:
                out.append(build(**kwargs))
            except InvalidParameterError as exc:
                bad = next((k for k in names if str(exc).startswith(k)), None)
                self.fail(f"{where}.{bad}" if bad else where, f"is invalid: {exc}")
        return out

    def excitations(self, block: dict, where: str) -> list[ExcitationSpec]:
        kind_text = block.get("type")
        if kind_text is None:
            self.fail(f"{where}.type",
                      f"is missing; expected one of {[k.value for k in ExcitationKind]}")
        try:
            kind = ExcitationKind(kind_text)
        except ValueError:
            self.fail(f"{where}.type", f"must be one of {[k.value for k in ExcitationKind]}, "
                                       f"got {kind_text!r}")
        body = {k: v for k, v in block.items() if k != "type"}
        self.keys(body, where, _EXCITATION_KEYS[kind])
        if "direction" in body:
            dirs = body["direction"] if isinstance(body["direction"], list) else [body["direction"]]
            if not dirs or any(d not in (-1, 1) or isinstance(d, bool) for d in dirs):
                self.fail(f"{where}.direction", f"must be -1, +1 or a list of them, got "
                                                f"{body['direction']!r}")
        if kind is not ExcitationKind.RECORD:
            return self.grid(where, body, ExcitationSpec, integer={"direction"},
                             fixed={"kind": kind})
        files = body.pop("files")
        if isinstance(files, str):
            files = [files]
        if not isinstance(files, list) or not files or not all(isinstance(f, str) for f in files):
            self.fail(f"{where}.files", f"must be a list of record file paths, got {files!r}")
        units = body.pop("units", "g")
        if units not in RECORD_UNITS:
            self.fail(f"{where}.units", f"must be one of {list(RECORD_UNITS)}, got {units!r}")
        resolved = []
        for f in files:
            full = (self.base_dir / f).resolve()
            if not full.is_file():
                self.fail(f"{where}.files", f"names {f!r}, which does not exist (paths are "
                                            f"relative to the study file)")
            try:  # read each record once now, so a bad file stops the study before it runs
                from archquake.ground.records import read_record

                read_record(full, units=units)
            except ArchquakeError as exc:
                self.fail(f"{where}.files", f"names {f!r}, which cannot be used: {exc}")
            resolved.append(str(full))
        return self.grid(where, body, ExcitationSpec, integer={"direction"},
                         fixed={"kind": kind, "units": units}, listed={"file": resolved})


def data_line(path: Path, offset: int) -> int:
    """The 1-based line of byte ``offset`` in the file at ``path``."""
    try:
        return path.read_bytes()[:offset].count(b"\n") + 1
    except OSError:
        return 0


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


__all__ = ["Study", "load_study", "parse_study"]
