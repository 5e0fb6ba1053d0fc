"""Extreme DEM inputs are refused at the dataclass that takes them (issue 15)."""

from __future__ import annotations

import pytest

from archquake.dem.settings import ContactLaw, DemSettings
from archquake.errors import InvalidParameterError


@pytest.mark.parametrize("kwargs, name", [
    ({"normal_stiffness": 1e308}, "normal_stiffness"),
    ({"normal_stiffness": 1e-300}, "normal_stiffness"),
    ({"shear_stiffness": 1e150}, "shear_stiffness"),
    ({"friction": 1e308}, "friction"),
])
def test_contact_law_extremes(kwargs, name):
    with pytest.raises(InvalidParameterError, match=name):
        ContactLaw(**kwargs)


@pytest.mark.parametrize("kwargs, name", [
    ({"damping": (1e308, 0.0)}, "Rayleigh alpha"),
    ({"damping": (0.0, 1e150)}, "Rayleigh beta"),
    ({"duration": 1e308}, "duration"),
    ({"time_step": 1e-300}, "time_step"),
    ({"time_step": 1e150}, "time_step"),
    ({"settle_time": 1e308}, "settle_time"),
])
def test_dem_settings_extremes(kwargs, name):
    with pytest.raises(InvalidParameterError, match=name):
        DemSettings(**kwargs)


def test_paper_values_stay_accepted():
    # the paper's stiffness read literally (1e21 Pa/m) and its damping
    ContactLaw(normal_stiffness=1e21)
    DemSettings(damping=DemSettings.rayleigh_from_minimum(0.1, 1e-4))


def test_output_larger_than_its_bound_is_refused_before_running():
    import math

    from archquake.compare import dem_assembly
    from archquake.dem import simulate_dem
    from archquake.geometry import Arch
    from archquake.ground import StepImpulse

    asm = dem_assembly(Arch(10.0, 1.5, math.radians(157.5), 7), "voussoirs")
    with pytest.raises(InvalidParameterError, match="raise output_interval"):
        simulate_dem(asm, StepImpulse.from_g(1.0, 0.27),
                     DemSettings(duration=1e5, output_interval=1e-9, time_step=1e-3))
