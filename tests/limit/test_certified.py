"""The hinges without the linear program (`certified_mechanism`, which `hinges_of` tries first).

Oracle: the static linear program itself (`limit_analysis`, HiGHS). Where the certificate
holds (the enumeration's least mechanism is a vertex of the program that is primal and dual
feasible with margins), the program's optimum is that vertex and no other, so its hinges
must be the same joints on the same faces, exactly; where the program fails (an arch too thin
to stand, a strut, a joint lifting off), the certificate must not hold.
"""

import math

import pytest

from archquake.errors import ArchquakeError
from archquake.geometry import Arch, OnPiers, Piers, pointed, segmental
from archquake.limit import hinges_of
from archquake.limit.analysis import CERTIFIED_VOUSSOIRS, certified_mechanism, limit_analysis


def _chains():
    out = []
    for n in (3, 5, 7, 10, 15, 20):
        for ratio in (0.06, 0.1, 0.15, 0.19, 0.3, 0.45):
            for embrace in (100.0, 135.0, 157.5, 180.0, 220.0):
                try:
                    out.append(Arch(10.0, 10.0 * ratio, math.radians(embrace), n))
                except ArchquakeError:
                    pass
    for n in (7, 11, 15):
        for rise, thickness in ((5.5, 0.5), (6.0, 0.8), (7.0, 0.8), (7.0, 0.4)):
            out.append(pointed(span=10.0, rise=rise, thickness=thickness, voussoirs=n))
            out.append(segmental(span=10.0, rise=rise - 3.5, thickness=thickness, voussoirs=n))
    for piers in (Piers(2.0, 3.0, 4), Piers(4.0, 1.5, 4), Piers(8.0, 1.5, 4)):
        out.append(OnPiers(Arch(5.0, 0.75, math.pi, 7), piers))
    return out


def test_the_certificate_gives_the_programs_hinges_or_nothing():
    certified = 0
    for chain in _chains():
        try:
            ref = limit_analysis(chain).mechanism
        except ArchquakeError:
            ref = None
        mech = certified_mechanism(chain)
        if mech is None:
            continue
        assert ref is not None, f"certified where the program fails: {chain}"
        assert (mech.joints, mech.faces) == (ref.joints, ref.faces), chain
        certified += 1
    assert certified > 100  # the certificate holds for the ordinary arches


def test_what_the_program_refuses_is_not_certified():
    thin = Arch(10.0, 0.6, math.pi, 15)  # t/R = 0.06 < 0.107: cannot stand
    with pytest.raises(ArchquakeError):
        limit_analysis(thin)
    assert certified_mechanism(thin) is None
    with pytest.raises(ArchquakeError):
        hinges_of(thin)  # the program's error, as before


def test_large_arches_go_to_the_program():
    big = Arch(10.0, 1.5, math.radians(157.5), CERTIFIED_VOUSSOIRS + 1)
    assert certified_mechanism(big) is None
    assert hinges_of(big).joints == limit_analysis(big).mechanism.joints
