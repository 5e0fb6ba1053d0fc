"""Sweep cases: one arch x one excitation x one model, frozen, validated, with a stable id.

A case describes its inputs in the units a study file uses (lengths in m, angles in degrees,
accelerations in g) because those are the numbers a user reads back from the store; the
conversion to SI happens once, in `ArchSpec.build` and `ExcitationSpec.build`.

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
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from archquake._json import canonical_json
from archquake._validate import require_gravity, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.loads import Loads
from archquake.geometry.spec import ArchSpec
from archquake.ground.spec import (  # noqa: F401  (re-exported: a case's excitation)
    RECORD_UNITS,
    ExcitationKind,
    ExcitationSpec,
    file_digest,
    motion_digest,
    motion_name,
)
from archquake.models import DEFAULT_MODEL, Model, model_of
from archquake.ranges import T_END_RANGE_S

#: Version of the canonical-JSON layout; bump only if the meaning of an input changes.
CASE_SCHEMA = 1
#: Hex digits of SHA-256 kept in a case id (80 bits: collisions are negligible for any sweep).
CASE_ID_LENGTH = 20


#: The word a model's case ids hash, where it differs from its name (the four-link model was
#: ``analytical`` when stores were first written: their ids stay valid).
_ID_WORDS = {Model.FOURLINK: "analytical"}


def _id_word(model: Model) -> str:
    return _ID_WORDS.get(model, model.value)


@dataclass(frozen=True)
class CaseOptions:
    """Model options of a case.

    Parameters
    ----------
    restitution : float, optional
        Coefficient of restitution on angular velocity, in [0, 1] (0: perfectly plastic); None:
        the impact law's own (four-link model).
    impact : {"paper", "chain", "mirror"}, optional
        Impact law of the four-link model (`archquake.mechanism.impact`); None: "paper".
        Left out of the case's canonical form when None or "paper" (the same model), so existing
        case ids are unchanged.
    t_end_s : float, optional
        End of the simulation, s (> 0); None: the model's default.
    g : float
        Gravity, m/s^2 (> 0), also the factor from study magnitudes in g to m/s^2.
    guard : bool
        The rigid chain's half-step guard on its verdict (`archquake.rigid.rigid_verdicts`;
        False: the verdict at the step alone, as incremental dynamic analysis runs its levels
        before it checks the levels that decide its result). Left out of the canonical form when
        True, so existing case ids are unchanged.
    step_fraction : float
        The rigid chain's time step as a fraction of its verdict's own, in (0, 1] (0.5: the
        half-step guard's rerun of a level an incremental dynamic analysis stores like any
        other case); the rigid chain's verdicts in batches only. Left out of the canonical
        form when 1.
    """

    restitution: float | None = None
    t_end_s: float | None = None
    g: float = STANDARD_GRAVITY
    impact: str | None = None
    guard: bool = True
    step_fraction: float = 1.0

    def __post_init__(self) -> None:
        from archquake.mechanism.impact import check_impact_law, check_restitution

        _set(self, "restitution", check_restitution(self.restitution))
        if self.impact is not None:
            _set(self, "impact", check_impact_law(self.impact))
        if self.t_end_s is not None:
            _set(self, "t_end_s", require_range("t_end_s", self.t_end_s, *T_END_RANGE_S, "s",
                                                low_open=False, high_open=False))
        _set(self, "g", require_gravity(self.g))
        if not isinstance(self.guard, bool):
            raise InvalidParameterError(f"guard must be true or false, got {self.guard!r}")
        _set(self, "step_fraction", require_range("step_fraction", self.step_fraction, 0.0, 1.0,
                                                  high_open=False))

    def canonical(self) -> dict[str, Any]:
        out: dict[str, Any] = {"restitution": self.restitution, "t_end_s": self.t_end_s,
                               "g_m_s2": self.g}
        if self.impact not in (None, "paper"):  # the default law keeps the ids it always had
            out["impact"] = self.impact
        if not self.guard:  # the guarded verdict keeps the ids it always had
            out["guard"] = False
        if self.step_fraction != 1.0:
            out["step_fraction"] = self.step_fraction
        return out

    @cached_property
    def canonical_json(self) -> str:
        """`canonical_json` of `canonical`, computed once per spec."""
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
    #: What the arch carries (None: bare; it enters the id only when given).
    loads: Loads | None = None

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
        if self.loads is not None:
            if not isinstance(self.loads, Loads):
                raise InvalidParameterError(
                    f"loads must be a Loads, got {type(self.loads).__name__}")
            if self.loads.empty:
                _set(self, "loads", None)
            elif (self.loads.traffic is not None or self.loads.passive is not None
                  or any(not p.moves_with_arch for p in self.loads.point_loads)
                  or any(not d.moves_with_arch for d in self.loads.distributed_loads)):
                raise InvalidParameterError(
                    "a case's loads are masses that move with the arch: traffic, passive fill "
                    "pressure and 'still' loads are statics only")

    def canonical(self) -> dict[str, Any]:
        """The inputs that define the case (what its id hashes), as plain JSON values. The
        four-link model is hashed under its earlier word, ``analytical`` (`_ID_WORDS`),
        so stores written before it was named ``fourlink`` resume."""
        out = {"schema": CASE_SCHEMA, "model": _id_word(self.model),
               "arch": self.arch.canonical(),
               "excitation": self.excitation.canonical(), "options": self.options.canonical()}
        if self.loads is not None:
            out["loads"] = self.loads.to_dict()
        return out

    @property
    def canonical_json(self) -> str:
        """`canonical_json` of `canonical`, assembled from the specs' own (cached)
        canonical JSON: the same string, byte for byte, since the top-level keys are written
        in sorted order with the same separators (a test holds the two equal). A grid of a
        million cases then costs one concatenation and one hash per case."""
        loads = ("" if self.loads is None
                 else f'"loads":{canonical_json(self.loads.to_dict())},')
        return (f'{{"arch":{self.arch.canonical_json},'
                f'"excitation":{self.excitation.canonical_json},{loads}'
                f'"model":{json.dumps(_id_word(self.model))},'
                f'"options":{self.options.canonical_json},"schema":{json.dumps(CASE_SCHEMA)}}}')

    @cached_property
    def case_id(self) -> str:
        """Stable id: the first 20 hex digits of SHA-256 of `canonical_json`."""
        return hashlib.sha256(self.canonical_json.encode()).hexdigest()[:CASE_ID_LENGTH]

    def columns(self) -> dict[str, Any]:
        """Flat input columns (see `INPUT_COLUMNS`), None where not applicable."""
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


def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


__all__ = [
    "ArchSpec",
    "Case",
    "CaseOptions",
    "ExcitationKind",
    "ExcitationSpec",
    "INPUT_COLUMNS",
    "RECORD_UNITS",
    "canonical_json",
    "file_digest",
    "motion_digest",
    "motion_name",
]
