"""The flat top-level API: every name resolves to the object its home module defines, and
``import archquake`` loads none of the heavy dependencies or subpackages (PEP 562 laziness).

Oracle: identity with the defining module's object (``is``), and ``sys.modules`` of a fresh
interpreter, which starts without any of the modules checked."""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys

import pytest

import archquake

#: name -> (module that defines or re-exports it, attribute there)
HOMES = {
    "Arch": ("archquake.geometry.arch", "Arch"),
    "Face": ("archquake.geometry.hinges", "Face"),
    "Hinge": ("archquake.geometry.hinges", "Hinge"),
    "HingeMechanism": ("archquake.geometry.hinges", "HingeMechanism"),
    "limit_analysis": ("archquake.limit.analysis", "limit_analysis"),
    "simulate": ("archquake.mechanism.simulate", "simulate"),
    "Outcome": ("archquake.mechanism", "Outcome"),
    "ModelResult": ("archquake.result", "ModelResult"),
    "simulate_dem": ("archquake.dem", "simulate_dem"),
    "failure_domain": ("archquake.domains.domain", "failure_domain"),
    "StepImpulse": ("archquake.ground.pulses", "StepImpulse"),
    "SinePulse": ("archquake.ground.pulses", "SinePulse"),
    "Record": ("archquake.ground.records", "Record"),
    "read_record": ("archquake.ground.records", "read_record"),
    "ArchquakeError": ("archquake.errors", "ArchquakeError"),
    "InvalidParameterError": ("archquake.errors", "InvalidParameterError"),
    "UnstableArchError": ("archquake.errors", "UnstableArchError"),
    "GroundMotionFormatError": ("archquake.errors", "GroundMotionFormatError"),
    "StudyFileError": ("archquake.errors", "StudyFileError"),
    "SolverError": ("archquake.errors", "SolverError"),
    "STANDARD_GRAVITY": ("archquake.constants", "STANDARD_GRAVITY"),
}

#: modules a bare ``import archquake`` must not load
HEAVY = ("numba", "scipy", "matplotlib")
SUBPACKAGES = ("cli", "compare", "dem", "domains", "geometry", "ground", "limit", "mechanism",
               "plotting", "reproduce", "sweeps", "thrust", "validation")


def _fresh(code: str) -> str:
    """Run ``code`` in a new interpreter with this test's sys.path; return its stdout."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True)
    return done.stdout


def test_import_loads_no_heavy_module_and_no_subpackage():
    out = _fresh("import sys, json, archquake; print(json.dumps(sorted(sys.modules)))")
    loaded = set(json.loads(out))
    assert "archquake" in loaded
    for name in HEAVY:
        assert not any(m == name or m.startswith(name + ".") for m in loaded), name
    for sub in SUBPACKAGES:
        assert f"archquake.{sub}" not in loaded, sub


@pytest.mark.parametrize("name", sorted(HOMES))
def test_lazy_name_is_its_home_object(name):
    module, attribute = HOMES[name]
    assert getattr(archquake, name) is getattr(importlib.import_module(module), attribute)


def test_flat_import_of_the_documented_names():
    from archquake import (  # noqa: F401
        Arch,
        Outcome,
        Record,
        SinePulse,
        StepImpulse,
        errors,
        failure_domain,
        g,
        limit_analysis,
        read_record,
        simulate,
        simulate_dem,
    )

    assert errors is importlib.import_module("archquake.errors")
    assert g == 9.80665  # standard gravity, m/s^2 (CGPM 1901), by definition exact


def test_all_and_dir_list_every_public_name_and_each_resolves():
    names = set(archquake.__all__)
    assert set(HOMES) <= names
    assert names <= set(dir(archquake))
    for name in names:
        getattr(archquake, name)


def test_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        archquake.nonexistent  # noqa: B018
    assert not hasattr(archquake, "simulate_everything")


def test_a_lazy_name_loads_only_its_own_subpackage():
    out = _fresh("import sys, json, archquake; archquake.StepImpulse; "
                 "print(json.dumps(sorted(sys.modules)))")
    loaded = set(json.loads(out))
    assert "archquake.ground" in loaded
    for sub in ("dem", "domains", "plotting", "cli", "reproduce", "sweeps"):
        assert f"archquake.{sub}" not in loaded, sub
    assert "matplotlib" not in loaded
