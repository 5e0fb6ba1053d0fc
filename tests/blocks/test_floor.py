"""The floor under the two block models (`archquake.blocks`): their thresholds, their default
window and their result, held once for both.

Oracles: the closed form of the default window (end of the excitation + tail sqrt(R/g));
the DEM settings' own validation (the same refusals, field for field); the rigid chain's result
against itself run with the old kind of settings (bit for bit); the class dictionaries (what
`RigidRun` defines beside what it inherits).
"""

import math
import warnings

import numpy as np
import pytest

from archquake import Arch
from archquake.blocks import (
    BlockCriteria,
    BlockResult,
    BlockRunSettings,
    default_window,
)
from archquake.constants import STANDARD_GRAVITY as G
from archquake.dem import DemResult, DemSettings
from archquake.errors import InvalidParameterError
from archquake.ground import StepImpulse
from archquake.rigid import RigidRun, simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


# ----------------------------------------------------------------------------- criteria
def test_dem_settings_hold_the_block_criteria():
    s = DemSettings(collapse_drop=0.5, collapse_rotation=1.0, hinge_opening=2e-4,
                    stop_at_collapse=False)
    assert s.criteria == BlockCriteria(hinge_opening=2e-4, collapse_rotation=1.0,
                                       collapse_drop=0.5, stop_at_collapse=False)
    assert DemSettings().criteria == BlockCriteria()


@pytest.mark.parametrize("name", ["collapse_drop", "collapse_rotation", "hinge_opening"])
@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf])
def test_criteria_refuse_what_dem_settings_refuse(name, value):
    """Both constructors refuse a threshold that is not a finite positive number, naming it,
    with the same sentence."""
    with pytest.raises(InvalidParameterError, match=name) as dem:
        DemSettings(**{name: value})
    with pytest.raises(InvalidParameterError, match=name) as floor:
        BlockCriteria(**{name: value})
    assert str(dem.value) == str(floor.value)


def test_default_window_is_the_closed_form():
    """End of the excitation + tail sqrt(R/g), R the arch's radius (10 m), in one home: the
    compare package's and the rigid verdict's windows are this function."""
    from archquake.compare import default_dem_duration
    from archquake.ranges import DEM_T_END_MAX_S
    from archquake.rigid.verdict import WINDOW_TAIL
    from archquake.rigid.verdict import default_window as verdict_window

    pulse = StepImpulse.from_g(1.0, 0.27)
    end = pulse.duration  # the step and its return: 3 t_p
    assert end == pytest.approx(0.81, rel=1e-15)
    want = end + 5.0 * math.sqrt(10.0 / G)
    assert default_window(pulse, 10.0) == pytest.approx(want, rel=1e-15)
    assert default_dem_duration(OPPENHEIM, pulse) == default_window(pulse, OPPENHEIM.radius)
    tail = default_window(pulse, 10.0, tail=WINDOW_TAIL)
    assert tail == pytest.approx(end + 60.0 * math.sqrt(10.0 / G), rel=1e-15)
    assert verdict_window(OPPENHEIM, pulse, G) == min(tail, DEM_T_END_MAX_S)


# ----------------------------------------------------------------------------- result
def test_dem_result_is_the_block_result():
    assert DemResult is BlockResult


def test_rigid_run_is_a_block_result_with_no_forwarder():
    """`RigidRun` is the block result plus the stepper's fields: of what `BlockResult`
    defines, it redefines only its two exports (to read its own extras), nothing that hands a
    read on to another object."""
    assert issubclass(RigidRun, BlockResult)
    inherited = {name for name in vars(BlockResult) if not name.startswith("__")}
    redefined = {name for name in vars(RigidRun) if not name.startswith("__")} & inherited
    assert redefined == {"to_dict", "to_table"}


@pytest.fixture(scope="module")
def short_runs():
    """One short rocking history, with its thresholds given both ways."""
    pulse = StepImpulse.from_g(1.0, 0.2)
    criteria = BlockCriteria(collapse_drop=0.8)
    new = simulate_rigid(OPPENHEIM, pulse, duration=0.3, settings=criteria)
    with pytest.warns(DeprecationWarning, match="BlockCriteria"):
        old = simulate_rigid(OPPENHEIM, pulse, duration=0.3,
                             settings=DemSettings(collapse_drop=0.8))
    return new, old


def test_dem_settings_still_accepted_with_a_warning(short_runs):
    """A `DemSettings` (deprecated) gives the run its criteria give, bit for bit."""
    new, old = short_runs
    assert new.criteria == old.criteria == BlockCriteria(collapse_drop=0.8)
    np.testing.assert_array_equal(new.positions, old.positions)
    np.testing.assert_array_equal(new.rotation, old.rotation)
    assert new.to_dict(joint_forces=False)["settings"] == old.to_dict(
        joint_forces=False)["settings"]


def test_rigid_run_records_its_own_settings(short_runs):
    new, _ = short_runs
    assert isinstance(new.settings, BlockRunSettings)
    assert new.to_dict(joint_forces=False)["settings"] == {
        "duration_s": 0.3, "output_interval_s": new.settings.output_interval,
        "time_step_s": new.time_step, "collapse_drop": 0.8,
        "collapse_rotation_rad": 0.5 * math.pi, "hinge_opening": 1e-4}
    assert new.stepper_time_step == new.time_step  # the time stepper: the same step


def test_result_is_the_run_itself_with_a_warning(short_runs):
    new, _ = short_runs
    with pytest.warns(DeprecationWarning, match="run.result"):
        assert new.result is new
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert new.outcome is new.outcome  # reading a field warns nothing


def test_other_settings_are_refused_in_one_line():
    with pytest.raises(InvalidParameterError, match="settings must be a BlockCriteria"):
        simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.2), duration=0.1,
                       settings={"collapse_drop": 1.0})
