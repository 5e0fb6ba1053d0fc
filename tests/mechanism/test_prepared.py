"""The one place that prepares a mechanism from an arch (archquake.mechanism.prepared).

Oracles: the equivalent static analysis (archquake.limit, whose static LP and kinematic virtual
work agree to 1e-6 g), the definitions of the crest (G(phi) = 0, Eq. 2's gravity term) and of the
toggle (the four-bar cannot be assembled beyond it), and the package layout (no import cycle, no
packed-array indexing outside archquake.mechanism).
"""

from __future__ import annotations

import ast
import math
import re
from pathlib import Path

import pytest

import archquake
from archquake.geometry import Arch
from archquake.limit import hinges_of, limit_analysis
from archquake.mechanism import PreparedMechanism
from archquake.mechanism.kinematics import eom_terms, fourbar

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
#: A semicircle whose hinge A sits three joints above the left springing (hinges (3, 7, 12, 15)).
SEMICIRCLE = Arch(5.0, 0.6, math.pi, 15)
#: Above the 60 voussoirs the kinematic enumeration accepts: only the static LP answers.
MANY = Arch(10.0, 1.5, math.radians(157.5), 100)

SRC = Path(archquake.__file__).parent


@pytest.mark.parametrize("arch", [OPPENHEIM, SEMICIRCLE, MANY], ids=["oppenheim", "semicircle", "n100"])
def test_hinges_are_those_of_the_limit_analysis_opened_by_a_load_towards_plus_x(arch):
    """hinges_of is limit_analysis' mechanism, oriented so that a ground acceleration towards -x
    (an inertial load towards +x) opens it; its lambda by virtual work is the LP's to 1e-6 g
    (the tolerance at which archquake.limit holds the two bounds equal)."""
    la = limit_analysis(arch)
    mech = hinges_of(arch)
    assert mech.load_direction == 1
    assert mech.joints in (la.mechanism.joints, la.mechanism.mirrored().joints)
    prepared = PreparedMechanism.build(arch)
    assert prepared.mechanism.joints == mech.joints
    assert prepared.collapse_acceleration_g == pytest.approx(la.collapse_acceleration_g, abs=1e-6)


def test_semicircle_hinges_sit_above_the_springing():
    assert hinges_of(SEMICIRCLE).joints == (3, 7, 12, 15)
    assert hinges_of(MANY).joints[0] > 0


@pytest.mark.parametrize("arch", [OPPENHEIM, SEMICIRCLE], ids=["oppenheim", "semicircle"])
def test_crest_and_toggle_are_what_their_names_say(arch):
    """Crest: the gravity term G of Eq. 2 changes sign there (> 0 below, <= 0 above, 1e-9 rad
    either side: the bisection runs to round-off). Toggle: the four-bar assembles just below it and
    not just above (or the linkage never toggles and pi is reported)."""
    p = PreparedMechanism.build(arch)
    crit, toggle = p.critical_rotation, p.toggle_rotation
    assert 0.0 < crit <= toggle <= math.pi
    if crit < toggle:
        assert eom_terms(p.packed, crit - 1e-9)[3] > 0.0 >= eom_terms(p.packed, crit + 1e-9)[3]
    assert fourbar(p.packed, toggle * (1 - 1e-9))[0]
    if toggle < math.pi:
        assert not fourbar(p.packed, toggle * (1 + 1e-6))[0]


def test_build_takes_an_arch_a_mechanism_or_a_prepared_mechanism():
    p = PreparedMechanism.build(OPPENHEIM)
    assert PreparedMechanism.build(p) is p
    mirrored = PreparedMechanism.build(p.mechanism.mirrored())
    assert mirrored.mechanism.joints == p.mechanism.joints  # re-oriented to the first mechanism
    assert mirrored.collapse_acceleration_g == pytest.approx(p.collapse_acceleration_g, rel=1e-12)
    assert p.restitution == pytest.approx(max(p.impact.restitution_cv, 0.0))


def test_kinematics_imports_nothing_from_the_mechanism_layer():
    """The jitable kinematics sit at the bottom of archquake.mechanism: the kernels import them,
    never the reverse (the kinematics <-> _kernels cycle is gone)."""
    tree = ast.parse((SRC / "mechanism" / "kinematics.py").read_text())
    imported = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    imported += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    assert not [m for m in imported if m and m.startswith("archquake")]


def test_no_code_outside_mechanism_reads_the_packed_layout():
    """lambda, the crest and the toggle are properties of PreparedMechanism: nothing outside
    archquake.mechanism indexes ``.packed[...]``."""
    offenders = [
        str(path.relative_to(SRC))
        for path in SRC.rglob("*.py")
        if path.parent.name != "mechanism" and re.search(r"\.packed\[", path.read_text())
    ]
    assert offenders == []
