"""Sweep cases: one arch x one excitation x one model, frozen, validated, with a stable id.

A case describes its inputs in the units a study file uses (lengths in m, angles in degrees,
accelerations in g) because those are the numbers a user reads back from the store; the
conversion to SI happens once, in :meth:`ArchSpec.build` and :meth:`ExcitationSpec.build`.

The case id is the first 20 hex digits of the SHA-256 of the case's *canonical JSON*: its
inputs as a JSON object with sorted keys, every real number written as a float
(``1`` and ``1.0`` hash alike), and a schema version. Reordering a study file, rerunning it, or
listing the same case in two studies gives the same id. A record excitation enters the id
through its file name and the SHA-256 of its bytes, not its directory, so moving the records
folder keeps the ids and editing a record changes them.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from enum import StrEnum
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from archquake._validate import require_gravity, require_positive, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.checks import (  # the one place where an arch is checked
    MAX_VOUSSOIRS,
    MIN_VOUSSOIRS,
    check_density,
    check_depth,
    check_embrace_deg,
    check_joints,
    check_pier_courses,
    check_pier_values,
    check_piers,
    check_radius,
    check_shape,
    check_thickness_ratio,
    check_voussoirs,
)
from archquake.ranges import (
    MAGNITUDE_RANGE_G,
    PULSE_TIME_RANGE_S,
    SCALE_RANGE,
    T_END_RANGE_S,
)

#: Version of the canonical-JSON layout; bump only if the meaning of an input changes.
CASE_SCHEMA = 1
#: Hex digits of SHA-256 kept in a case id (80 bits: collisions are negligible for any sweep).
CASE_ID_LENGTH = 20


class ExcitationKind(StrEnum):
    """The excitations a sweep can apply."""

    STEP = "step"
    SINE = "sine"
    RECORD = "record"


class Model(StrEnum):
    """The model a case is evaluated with, named as ``--model`` names it: the chain of rigid
    voussoirs (``rigid``, the default: hinges open, migrate and close anywhere, impacts follow
    from plastic contacts), the paper's four-link mechanism with hinges fixed between impacts
    and Eq. 4's coefficient of restitution (``fourlink``), or the distinct-element model
    (``dem``)."""

    RIGID = "rigid"
    FOURLINK = "fourlink"
    DEM = "dem"


#: The model every command and API function uses unless told otherwise.
DEFAULT_MODEL = Model.RIGID

#: The word a model's case ids hash, where it differs from its name (the four-link model was
#: ``analytical`` when stores were first written: their ids stay valid).
_ID_WORDS = {Model.FOURLINK: "analytical"}


def _id_word(model: Model) -> str:
    return _ID_WORDS.get(model, model.value)

#: The words of earlier versions and what they are now (for a one-line pointer).
_RETIRED = {"analytical": "fourlink (hinges fixed) or rigid (hinges moving, the default)",
            "rigid_chain": "rigid"}


def model_of(model: str | Model | None = None, hinges: str | None = None, *,
             model_name: str = "model", hinges_name: str = "hinges") -> Model:
    """The :class:`Model` a user names (``rigid``, ``fourlink`` or ``dem``; None: the default,
    rigid), with a one-line pointer for the words of earlier versions.

    ``hinges`` is the retired ``--hinges fixed|moving`` (None when not given): any value is
    refused with the ``--model`` that replaces it. ``model_name`` and ``hinges_name`` are the
    option or key as the user typed it (``--model``, ``study.model``...).

    Examples
    --------
    >>> model_of().value
    'rigid'
    >>> model_of("fourlink").value
    'fourlink'
    >>> model_of("dem", model_name="--model").value
    'dem'
    """
    if hinges is not None:
        now = {"moving": "rigid", "fixed": "fourlink"}.get(str(hinges))
        hint = (f"{model_name} {now}" if now is not None
                else f"{model_name} rigid (hinges moving) or {model_name} fourlink (hinges fixed)")
        raise InvalidParameterError(f"{hinges_name} is retired: use {hint}")
    if model is None:
        return DEFAULT_MODEL
    word = str(getattr(model, "value", model))
    if word in _RETIRED:
        raise InvalidParameterError(f"{model_name} {word} is retired: use {model_name} "
                                    f"{_RETIRED[word]}")
    try:
        return Model(word)
    except ValueError:
        raise InvalidParameterError(f"{model_name} must be one of "
                                    f"{', '.join(m.value for m in Model)}, got {word!r}") from None


#: Units a record file's accelerations may be given in (PEER .AT2 files are always in g).
RECORD_UNITS: tuple[str, ...] = ("g", "m/s2")


@dataclass(frozen=True)
class ArchSpec:
    """The arch of a case, in study units: a circular arch by radius, t/R and embrace (the
    paper's), or any shape by span, rise and thickness (:mod:`archquake.geometry.shapes`), with
    optional piers.

    Parameters
    ----------
    radius : float, optional
        Circular arch: centreline radius R, m (1e-3 to 1e4).
    thickness_ratio : float, optional
        Circular arch: t/R, dimensionless (0 < t/R < 2).
    embrace_deg : float, optional
        Circular arch: angle of embrace, degrees (0 < embrace <= 240).
    voussoirs : int
        Number of voussoirs (3 to 2000).
    depth : float
        Out-of-plane depth, m (0 < depth <= 1e4; default 1).
    density : float
        Density, kg/m^3 (0 < density <= 1e5; default 2000).
    shape : str
        One of :data:`archquake.geometry.SHAPES` (default "circular").
    span, rise, thickness : float, optional
        Any shape: centreline span and rise, ring thickness, m (instead of radius, t/R and
        embrace).
    joints : str
        "radial" (default) or "vertical".
    pier_height, pier_width : float, optional
        Piers under the springings, m (both or neither).
    pier_courses : int
        Courses in each pier (default 1).
    blocks : str, optional
        A surveyed arch instead of a shape: the path of a .json, .csv or .dxf block file
        (:func:`archquake.geometry.survey.read_blocks`, the one reader), with only ``depth`` and
        ``density`` beside it. It enters the case id through the file's name and the SHA-256 of
        its bytes (``blocks_sha256``), not its directory, as a record file does.
    blocks_sha256 : str, optional
        SHA-256 of the block file's bytes; computed from ``blocks`` when omitted.

    Examples
    --------
    >>> spec = ArchSpec(10, 0.15, 157.5, 7)
    >>> round(spec.build().thickness, 3)
    1.5
    >>> ArchSpec(voussoirs=15, shape="pointed", span=10, rise=7, thickness=0.8).build().describe()["shape"]
    'pointed'
    """

    radius: float | None = None
    thickness_ratio: float | None = None
    embrace_deg: float | None = None
    voussoirs: int | None = None
    depth: float = 1.0
    density: float = 2000.0
    shape: str = "circular"
    span: float | None = None
    rise: float | None = None
    thickness: float | None = None
    joints: str = "radial"
    pier_height: float | None = None
    pier_width: float | None = None
    pier_courses: int = 1
    blocks: str | None = None
    blocks_sha256: str | None = field(default=None, compare=False)

    #: Keys that describe a shape, which a block file replaces.
    SHAPE_KEYS = ("radius", "thickness_ratio", "embrace_deg", "voussoirs", "span", "rise",
                  "thickness", "pier_height", "pier_width")

    def __post_init__(self) -> None:
        if self.blocks is not None:
            self._check_blocks()
            return
        if self.voussoirs is None:
            raise InvalidParameterError(f"voussoirs is required ({MIN_VOUSSOIRS} to "
                                        f"{MAX_VOUSSOIRS})")
        shape = check_shape(self.shape)
        check_joints(self.joints)
        _set(self, "shape", shape)
        by_radius = (self.radius, self.thickness_ratio, self.embrace_deg)
        by_span = (self.span, self.rise, self.thickness)
        if shape == "circular" and all(v is not None for v in by_radius) and all(
                v is None for v in by_span):
            _set(self, "radius", check_radius(self.radius))
            _set(self, "thickness_ratio", check_thickness_ratio(self.thickness_ratio))
            _set(self, "embrace_deg", check_embrace_deg(self.embrace_deg))
        elif all(v is not None for v in by_span) and all(v is None for v in by_radius):
            for name in ("span", "rise", "thickness"):
                _set(self, name, require_positive(name, getattr(self, name), "m"))
        else:
            raise InvalidParameterError(
                "an arch needs radius, thickness_ratio and embrace_deg (circular), or span, rise "
                "and thickness (any shape), not a mixture")
        _set(self, "voussoirs", check_voussoirs(self.voussoirs))
        _set(self, "depth", check_depth(self.depth))
        _set(self, "density", check_density(self.density))
        if check_piers(self.pier_height, self.pier_width):
            height, width, courses = check_pier_values(self.pier_height, self.pier_width,
                                                       self.pier_courses)
            _set(self, "pier_height", height)
            _set(self, "pier_width", width)
        else:
            courses = check_pier_courses(self.pier_courses)
        _set(self, "pier_courses", courses)

    def _check_blocks(self) -> None:
        """A block file: no shape keys beside it (one line naming them), depth and density in
        range, the file's SHA-256 taken once."""
        if not isinstance(self.blocks, str) or not self.blocks:
            raise InvalidParameterError("blocks must be the path of a .json, .csv or .dxf file")
        mixed = [k for k in self.SHAPE_KEYS if getattr(self, k) is not None]
        mixed += [k for k, default in (("shape", "circular"), ("joints", "radial"),
                                       ("pier_courses", 1)) if getattr(self, k) != default]
        if mixed:
            raise InvalidParameterError(f"blocks (a surveyed arch) does not go with the shape "
                                        f"keys {', '.join(mixed)}: give the block file or a "
                                        "shape, not both")
        _set(self, "depth", check_depth(self.depth))
        _set(self, "density", check_density(self.density))
        if self.blocks_sha256 is None:
            try:
                digest = hashlib.sha256(Path(self.blocks).read_bytes()).hexdigest()
            except OSError as exc:
                raise InvalidParameterError(f"blocks: cannot read {self.blocks!r} "
                                            f"({exc.strerror})") from None
            _set(self, "blocks_sha256", digest)

    @property
    def _circular_by_radius(self) -> bool:
        return self.radius is not None

    def build(self):
        """The arch (:class:`~archquake.geometry.Arch` for the paper's circular arch, else the
        shape's :class:`~archquake.geometry.VoussoirChain`; SI, embrace in rad)."""
        from archquake.geometry import OnPiers, Piers
        from archquake.geometry.shapes import circular, shaped

        arch: VoussoirChain
        if self.blocks is not None:
            from archquake.geometry.survey import read_blocks

            return read_blocks(self.blocks, depth=self.depth, density=self.density)
        if self._circular_by_radius:
            assert (self.radius is not None and self.thickness_ratio is not None  # __post_init__
                    and self.embrace_deg is not None and self.voussoirs is not None)
            if self.joints == "radial":
                arch = Arch.from_ratio(self.thickness_ratio, math.radians(self.embrace_deg),
                                       self.voussoirs, radius=self.radius, depth=self.depth,
                                       density=self.density)
            else:
                arch = circular(radius=self.radius, embrace=math.radians(self.embrace_deg),
                                thickness=self.thickness_ratio * self.radius,
                                voussoirs=self.voussoirs, joints=self.joints, depth=self.depth,
                                density=self.density)
        else:
            arch = shaped(self.shape, span=self.span, rise=self.rise, thickness=self.thickness,
                          voussoirs=self.voussoirs, joints=self.joints, depth=self.depth,
                          density=self.density)
        if self.pier_height is not None:
            assert self.pier_width is not None  # __post_init__: both or neither
            arch = OnPiers(arch, Piers(self.pier_height, self.pier_width, self.pier_courses))
        return arch

    def canonical(self) -> dict[str, Any]:
        """The inputs as a dict: exactly the paper's keys for a circular arch by radius with
        radial joints and no piers (so the case ids of existing studies never change), and the
        shape's keys otherwise."""
        out: dict[str, Any]
        if self.blocks is not None:
            return {"blocks": Path(self.blocks).name, "blocks_sha256": self.blocks_sha256,
                    "depth_m": self.depth, "density_kg_m3": self.density}
        if self._circular_by_radius:
            out = {"radius_m": self.radius, "thickness_ratio": self.thickness_ratio,
                   "embrace_deg": self.embrace_deg, "voussoirs": self.voussoirs,
                   "depth_m": self.depth, "density_kg_m3": self.density}
        else:
            out = {"shape": self.shape, "span_m": self.span, "rise_m": self.rise,
                   "thickness_m": self.thickness, "voussoirs": self.voussoirs,
                   "depth_m": self.depth, "density_kg_m3": self.density}
        if self.joints != "radial":
            out["joints"] = self.joints
        if self.pier_height is not None:
            out.update(pier_height_m=self.pier_height, pier_width_m=self.pier_width,
                       pier_courses=self.pier_courses)
        return out

    @cached_property
    def canonical_json(self) -> str:
        """:func:`canonical_json` of :meth:`canonical` (computed once per spec: a grid shares
        its specs across many cases)."""
        return canonical_json(self.canonical())

    def columns(self) -> dict[str, Any]:
        """Flat columns for the store: the canonical inputs plus the thickness in m."""
        cols = self.canonical()
        if self._circular_by_radius:
            assert self.thickness_ratio is not None and self.radius is not None
            cols["thickness_m"] = self.thickness_ratio * self.radius
        return cols


@dataclass(frozen=True)
class ExcitationSpec:
    """The excitation of a case, in study units.

    Parameters
    ----------
    kind : ExcitationKind or str
        ``"step"`` (Oppenheim's impulse), ``"sine"`` (one-cycle sine pulse) or ``"record"``.
    magnitude_g : float, optional
        Pulse magnitude, multiples of g (>= 0), for ``step`` and ``sine``.
    duration_s : float, optional
        Step impulse duration t_p, s (> 0), for ``step``.
    period_s : float, optional
        Sine period T, s (> 0), for ``sine``.
    direction : {-1, +1}
        Side of the pulse's first lobe (-1, towards -x, drives the paper's first mechanism);
        for a record, -1 reverses its sign. Default -1 for pulses, +1 for records.
    file : str, optional
        Path of the record file (``record`` only); read when the case runs.
    units : {"g", "m/s2"}
        Units of the record's accelerations (``record`` only; default "g", the only units of a
        PEER ``.AT2`` file; CSV records must say).
    scale : float
        Factor applied to the record's accelerations (> 0; ``record`` only, default 1).
    file_sha256 : str, optional
        SHA-256 of the record file's bytes; computed from ``file`` when omitted.
    motion : GroundMotion, optional
        ``record`` only, instead of ``file``: a ground motion held in memory (a
        :class:`~archquake.ground.Record` of a suite, or any motion with ``kernel_spec`` and
        ``scaled``), in m/s^2, travelling with the case to the worker. It enters the id through
        its name and the SHA-256 of its kernel description (:func:`motion_digest`), and
        ``units`` is then "m/s2". This is the case kind "a record scaled by a factor" of
        incremental dynamic analysis (:mod:`archquake.ida`).
    """

    kind: ExcitationKind
    magnitude_g: float | None = None
    duration_s: float | None = None
    period_s: float | None = None
    direction: int | None = None
    file: str | None = None
    units: str | None = None
    scale: float | None = None
    file_sha256: str | None = field(default=None, compare=False)
    motion: Any = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        try:
            kind = ExcitationKind(getattr(self.kind, "value", self.kind))
        except ValueError:
            raise InvalidParameterError(
                f"excitation type must be one of {[k.value for k in ExcitationKind]}, "
                f"got {self.kind!r}"
            ) from None
        _set(self, "kind", kind)
        allowed = {ExcitationKind.STEP: {"magnitude_g", "duration_s", "direction"},
                   ExcitationKind.SINE: {"magnitude_g", "period_s", "direction"},
                   ExcitationKind.RECORD: {"file", "units", "scale", "direction"}}[kind]
        for name in ("magnitude_g", "duration_s", "period_s", "file", "units", "scale"):
            if getattr(self, name) is not None and name not in allowed:
                raise InvalidParameterError(f"{name} does not apply to a {kind.value} excitation")
        direction = -1 if self.direction is None and kind is not ExcitationKind.RECORD else (
            1 if self.direction is None else self.direction)
        if direction not in (-1, 1) or isinstance(direction, bool):
            raise InvalidParameterError(f"direction must be -1 or +1, got {direction!r}")
        _set(self, "direction", int(direction))
        if self.motion is not None and kind is not ExcitationKind.RECORD:
            raise InvalidParameterError(f"motion does not apply to a {kind.value} excitation")
        if kind is ExcitationKind.RECORD and self.motion is not None:
            if self.file is not None:
                raise InvalidParameterError("a record excitation takes file or motion, not both")
            if self.units not in (None, "m/s2"):
                raise InvalidParameterError(f"an in-memory motion is in m/s2, got units "
                                            f"{self.units!r}")
            _set(self, "units", "m/s2")
            scale = 1.0 if self.scale is None else self.scale
            _set(self, "scale", require_positive("scale", scale))
            if self.file_sha256 is None:
                _set(self, "file_sha256", motion_digest(self.motion))
            return
        if kind is ExcitationKind.RECORD:
            if not isinstance(self.file, str) or not self.file:
                raise InvalidParameterError("a record excitation needs file = path of the record")
            units = "g" if self.units is None else self.units
            if units not in RECORD_UNITS:
                raise InvalidParameterError(
                    f"units must be one of {list(RECORD_UNITS)}, got {units!r}")
            _set(self, "units", units)
            scale = 1.0 if self.scale is None else self.scale
            _set(self, "scale", require_range("scale", scale, *SCALE_RANGE, high_open=False))
            if self.file_sha256 is None:
                _set(self, "file_sha256", file_digest(self.file))
            return
        magnitude = require_range("magnitude_g", self.magnitude_g, *MAGNITUDE_RANGE_G, "g",
                                  low_open=False, high_open=False)
        _set(self, "magnitude_g", magnitude)
        time_name = "duration_s" if kind is ExcitationKind.STEP else "period_s"
        _set(self, time_name, require_range(time_name, getattr(self, time_name),
                                            *PULSE_TIME_RANGE_S, "s", low_open=False,
                                            high_open=False))

    def build(self, *, g: float = STANDARD_GRAVITY):
        """The :class:`~archquake.ground.GroundMotion` (SI)."""
        from archquake.ground.pulses import SinePulse, StepImpulse

        assert self.direction is not None  # __post_init__ sets -1 or +1
        if self.kind is ExcitationKind.STEP:
            assert self.magnitude_g is not None and self.duration_s is not None
            return StepImpulse.from_g(self.magnitude_g, self.duration_s, self.direction, g=g)
        if self.kind is ExcitationKind.SINE:
            assert self.magnitude_g is not None and self.period_s is not None
            return SinePulse.from_g(self.magnitude_g, self.period_s, self.direction, g=g)
        if self.motion is not None:
            assert self.scale is not None  # __post_init__ sets it for a record
            return self.motion.scaled(self.scale * self.direction)
        return _load_record(self, g=g)

    @property
    def record_name(self) -> str | None:
        """The record's label: its file name, or an in-memory motion's ``name``."""
        if self.file:
            return Path(self.file).name
        if self.motion is not None:
            return motion_name(self.motion)
        return None

    def canonical(self) -> dict[str, Any]:
        out: dict[str, Any] = {"type": self.kind.value, "direction": self.direction}
        if self.kind is ExcitationKind.RECORD:
            out.update(record=self.record_name, record_sha256=self.file_sha256,
                       units=self.units, scale=self.scale)
        elif self.kind is ExcitationKind.STEP:
            out.update(magnitude_g=self.magnitude_g, duration_s=self.duration_s)
        else:
            out.update(magnitude_g=self.magnitude_g, period_s=self.period_s)
        return out

    @cached_property
    def canonical_json(self) -> str:
        """:func:`canonical_json` of :meth:`canonical`, computed once per spec."""
        return canonical_json(self.canonical())


@dataclass(frozen=True)
class CaseOptions:
    """Model options of a case.

    Parameters
    ----------
    restitution : float, optional
        Coefficient of restitution on angular velocity, in [0, 1] (0: perfectly plastic); None:
        the impact law's own (analytical model).
    impact : {"paper", "chain", "mirror"}, optional
        Impact law of the analytical model (:mod:`archquake.mechanism.impact`); None: "paper".
        Left out of the case's canonical form when None or "paper" (the same model), so existing
        case ids are unchanged.
    t_end_s : float, optional
        End of the simulation, s (> 0); None: the model's default.
    g : float
        Gravity, m/s^2 (> 0), also the factor from study magnitudes in g to m/s^2.
    """

    restitution: float | None = None
    t_end_s: float | None = None
    g: float = STANDARD_GRAVITY
    impact: str | None = None

    def __post_init__(self) -> None:
        from archquake.mechanism.impact import check_impact_law, check_restitution

        _set(self, "restitution", check_restitution(self.restitution))
        if self.impact is not None:
            _set(self, "impact", check_impact_law(self.impact))
        if self.t_end_s is not None:
            _set(self, "t_end_s", require_range("t_end_s", self.t_end_s, *T_END_RANGE_S, "s",
                                                low_open=False, high_open=False))
        _set(self, "g", require_gravity(self.g))

    def canonical(self) -> dict[str, Any]:
        out: dict[str, Any] = {"restitution": self.restitution, "t_end_s": self.t_end_s,
                               "g_m_s2": self.g}
        if self.impact not in (None, "paper"):  # the default law keeps the ids it always had
            out["impact"] = self.impact
        return out

    @cached_property
    def canonical_json(self) -> str:
        """:func:`canonical_json` of :meth:`canonical`, computed once per spec."""
        return canonical_json(self.canonical())


@dataclass(frozen=True)
class Case:
    """One arch under one excitation, evaluated with one model.

    Examples
    --------
    >>> case = Case(ArchSpec(10, 0.15, 157.5, 7), ExcitationSpec("step", magnitude_g=0.5,
    ...             duration_s=0.25))
    >>> same = Case(ArchSpec(10.0, 0.15, 157.5, 7.0), ExcitationSpec("step", magnitude_g=0.5,
    ...             duration_s=0.25, direction=-1))
    >>> case.case_id == same.case_id, len(case.case_id)
    (True, 20)
    """

    arch: ArchSpec
    excitation: ExcitationSpec
    model: Model = DEFAULT_MODEL
    options: CaseOptions = field(default_factory=CaseOptions)

    def __post_init__(self) -> None:
        if not isinstance(self.arch, ArchSpec):
            raise InvalidParameterError(f"arch must be an ArchSpec, got {type(self.arch).__name__}")
        if not isinstance(self.excitation, ExcitationSpec):
            raise InvalidParameterError(
                f"excitation must be an ExcitationSpec, got {type(self.excitation).__name__}")
        if not isinstance(self.options, CaseOptions):
            raise InvalidParameterError(
                f"options must be a CaseOptions, got {type(self.options).__name__}")
        _set(self, "model", model_of(self.model))

    def canonical(self) -> dict[str, Any]:
        """The inputs that define the case (what its id hashes), as plain JSON values. The
        four-link model is hashed under its earlier word, ``analytical`` (:data:`_ID_WORDS`),
        so stores written before it was named ``fourlink`` resume."""
        return {"schema": CASE_SCHEMA, "model": _id_word(self.model),
                "arch": self.arch.canonical(),
                "excitation": self.excitation.canonical(), "options": self.options.canonical()}

    @property
    def canonical_json(self) -> str:
        """:func:`canonical_json` of :meth:`canonical`, assembled from the specs' own (cached)
        canonical JSON: the same string, byte for byte, since the top-level keys are written
        in sorted order with the same separators (a test holds the two equal). A grid of a
        million cases then costs one concatenation and one hash per case."""
        return (f'{{"arch":{self.arch.canonical_json},'
                f'"excitation":{self.excitation.canonical_json},'
                f'"model":{json.dumps(_id_word(self.model))},'
                f'"options":{self.options.canonical_json},"schema":{json.dumps(CASE_SCHEMA)}}}')

    @cached_property
    def case_id(self) -> str:
        """Stable id: the first 20 hex digits of SHA-256 of :attr:`canonical_json`."""
        return hashlib.sha256(self.canonical_json.encode()).hexdigest()[:CASE_ID_LENGTH]

    def columns(self) -> dict[str, Any]:
        """Flat input columns (see :data:`INPUT_COLUMNS`), None where not applicable."""
        exc = self.excitation
        cols = {"model": self.model.value, **self.arch.columns(),
                "excitation": exc.kind.value, "magnitude_g": exc.magnitude_g,
                "duration_s": exc.duration_s, "period_s": exc.period_s,
                "direction": exc.direction,
                "record": exc.record_name,
                "record_sha256": exc.file_sha256, "record_units": exc.units, "scale": exc.scale,
                "restitution": self.options.restitution, "t_end_s": self.options.t_end_s,
                "g_m_s2": self.options.g}
        return {name: cols.get(name) for name in INPUT_COLUMNS}


#: Flat input columns of the store, in order, with their SQLite types.
INPUT_COLUMNS: dict[str, str] = {
    "model": "TEXT", "radius_m": "REAL", "thickness_ratio": "REAL", "thickness_m": "REAL",
    "embrace_deg": "REAL", "voussoirs": "INTEGER", "depth_m": "REAL", "density_kg_m3": "REAL",
    "excitation": "TEXT", "magnitude_g": "REAL", "duration_s": "REAL", "period_s": "REAL",
    "direction": "INTEGER", "record": "TEXT", "record_sha256": "TEXT", "record_units": "TEXT",
    "scale": "REAL", "restitution": "REAL", "t_end_s": "REAL", "g_m_s2": "REAL",
}


def canonical_json(obj: Any) -> str:
    """Sorted keys, no whitespace, reals as floats (so 1 and 1.0 agree), NaN rejected."""
    return json.dumps(_floats(obj), sort_keys=True, separators=(",", ":"), allow_nan=False)


def file_digest(path: str | Path) -> str:
    """SHA-256 (hex) of a file's bytes; a missing file is a one-line error naming it."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as exc:
        raise InvalidParameterError(
            f"cannot read record file {str(path)!r}: {exc.strerror}") from None


def motion_name(motion: Any) -> str:
    """Label of an in-memory motion: its ``name`` attribute, else its class name."""
    name = getattr(motion, "name", None)
    return name if isinstance(name, str) and name else type(motion).__name__


def motion_digest(motion: Any) -> str:
    """SHA-256 (hex) of a ground motion's compiled description (its kind and parameters, e.g.
    a record's t0, dt and samples in m/s^2): equal motions give equal digests on any machine."""
    try:
        kind, params = motion.kernel_spec()
    except AttributeError:
        raise InvalidParameterError(f"motion must be a ground motion with kernel_spec(), got "
                                    f"{type(motion).__name__}") from None
    h = hashlib.sha256(str(int(kind)).encode())
    h.update(np.ascontiguousarray(params, dtype="<f8").tobytes())
    return h.hexdigest()


def _floats(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _floats(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_floats(v) for v in obj]
    if isinstance(obj, float) and obj == 0.0:
        return 0.0  # -0.0 and 0.0 are the same input
    return obj


def _load_record(spec: ExcitationSpec, *, g: float):
    """Read a record file into a GroundMotion in m/s^2, scaled and signed as the spec says."""
    from archquake.ground.records import read_record

    assert spec.file is not None and spec.scale is not None and spec.direction is not None
    return read_record(spec.file, units=spec.units, scale=spec.scale * spec.direction, g=g)


def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


__all__ = [
    "ArchSpec",
    "Case",
    "CaseOptions",
    "ExcitationKind",
    "ExcitationSpec",
    "INPUT_COLUMNS",
    "DEFAULT_MODEL",
    "Model",
    "model_of",
    "RECORD_UNITS",
    "canonical_json",
    "file_digest",
    "motion_digest",
    "motion_name",
]
