"""First impact of free rocking: the impact laws beside the DEM (archquake.compare.impacts).

Quick version of the docs' table (one geometry). Oracles: energy (the DEM's kinetic-energy ratio
across an impact lies in (0, 1]; the DEM's own energy balance closes to 1 %); the chain law's
c_T <= 1 and below the exact response's; Eq. 4 reported as is (the docs' value).
"""

from __future__ import annotations

import math

import pytest

from archquake import Arch
from archquake.compare.impacts import compare_first_impact, hinge_table, markdown_table


def test_oppenheim_first_impact():
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    row = compare_first_impact(arch, "Oppenheim")
    assert row.dem_impact_time_s is not None
    assert 0.0 < row.dem_ct <= 1.0 and 0.0 < row.dem_ct_wide <= 1.0
    assert row.dem_energy_error < 0.01
    assert row.laws["paper"]["ct"] == pytest.approx(0.7663, abs=1e-4)
    assert 0.0 < row.laws["chain"]["ct"] <= row.exact_ct + 1e-6 <= 1.0 + 1e-6
    assert row.dem_hinges_after != "-"
    table = markdown_table([row]) + hinge_table([row])
    assert "Oppenheim" in table
