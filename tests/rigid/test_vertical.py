"""The rigid chain (Moreau-Jean stepper, and its verdict path) under a vertical ground
acceleration: gravity g + a_v(t) in every step.

Oracles: the onset of hinging |a_h| > lambda (g + a_v) of the limit analysis (a long step
pulse 2 % either side of lambda g / (1 - R lambda)); the time similarity of a steady vertical
c g, A(t_p; c) = (1 + c) A(t_p sqrt(1 + c); 0), exact for the equations and within the fixed
step's error here (measured 5e-4 at h = 1e-4 s on Oppenheim's arch, checked to 3e-3); the
energy balance, which closes only if the input work counts the vertical's work -m a_v on the
relative vertical velocities (residual 1e-10, checked to 1e-8); R = 0 as before. The verdict
path (its step 1e-3 s here) meets the similarity law to 0.04-0.9 % (checked to 2 %) and agrees
with the recorded run at 1e-4 s on the onset.
"""

from __future__ import annotations

import math

import pytest

from archquake._json import to_jsonable
from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis
from archquake.rigid import rigid_verdict
from archquake.rigid.run import simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_onset_of_hinging_reads_g_plus_av(ratio):
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    threshold = lam / (1.0 - ratio * lam)
    below = simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.98 * threshold, 1.0, vertical=ratio),
                           duration=3.5)
    above = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.02 * threshold, 1.0, vertical=ratio),
                           duration=3.5)
    assert below.outcome.value == "no_hinging"
    assert above.outcome.value != "no_hinging"


@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_energy_balance_counts_the_vertical_work(ratio):
    run = simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.5, 0.2, vertical=ratio), duration=6.0)
    plain = simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.5, 0.2), duration=6.0)
    assert run.energy.residual < 1e-8 and run.energy.warning is None
    assert abs(run.energy.input_work_J / plain.energy.input_work_J - 1.0) > 0.1


def test_zero_vertical_runs_as_before():
    a = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.27), duration=3.0).to_dict()
    b = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.27, vertical=0.0),
                       duration=3.0).to_dict()
    for d in (a, b):
        del d["rigid"]["wall_s"]  # the wall time of the stepping
    assert repr(to_jsonable(a)) == repr(to_jsonable(b))


def _critical(tp: float, c: float, iterations: int) -> float:
    lo, hi = 0.3, 4.0
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        run = simulate_rigid(OPPENHEIM, StepImpulse(mid * G, tp, steady_vertical=c * G),
                             duration=8.0, output_interval=0.01)
        if run.outcome.value == "collapse":
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def test_steady_vertical_time_similarity_quick():
    c, tp = 0.4, 0.2
    assert _critical(tp, c, 13) == pytest.approx(
        (1 + c) * _critical(tp * math.sqrt(1 + c), 0.0, 13), rel=3e-3)


@pytest.mark.slow
@pytest.mark.parametrize("c", [0.4, -0.3, 0.8])
@pytest.mark.parametrize("tp", [0.2, 0.35])
def test_steady_vertical_time_similarity(c, tp):
    assert _critical(tp, c, 18) == pytest.approx(
        (1 + c) * _critical(tp * math.sqrt(1 + c), 0.0, 18), rel=3e-3)


# ------------------------------------------------------------------ records with a vertical
def _records():
    import numpy as np

    from archquake.ground import Record

    dt = 0.005
    t = np.arange(0.0, 3.0 + dt / 2, dt)
    x = np.where(t < 0.3, -0.8 * G, np.where(t < 0.9, 0.4 * G, 0.0))
    x[-1] = 0.0
    return Record(x, dt, name="h"), t, dt


def test_a_constant_vertical_record_is_gravity_g_plus_c():
    """Oracle: the same record under gravity g + c (simulate_rigid's g), to 1e-8 (the stepper's
    tolerances scale with g, the equations do not differ)."""
    import numpy as np

    from archquake.ground import Record
    from archquake.ground.vertical import WithVertical

    h, t, dt = _records()
    c = 0.3 * G
    up = simulate_rigid(OPPENHEIM, WithVertical(h, Record(np.full(t.size, c), dt)), duration=3.0)
    heavier = simulate_rigid(OPPENHEIM, h, duration=3.0, g=G + c)
    assert up.outcome == heavier.outcome
    assert up.to_dict()["max_rotation_rad"] == pytest.approx(
        heavier.to_dict()["max_rotation_rad"], rel=1e-8)
    assert up.energy.residual < 1e-8
    zero = simulate_rigid(OPPENHEIM, WithVertical(h, Record(np.zeros(t.size), dt)), duration=3.0)
    plain = simulate_rigid(OPPENHEIM, h, duration=3.0)
    assert zero.to_dict()["max_rotation_rad"] == plain.to_dict()["max_rotation_rad"]


def test_cli_record_vertical(tmp_path, capsys):
    import numpy as np

    from archquake.cli.main import main

    h, t, _dt = _records()
    np.savetxt(tmp_path / "h.csv", np.column_stack([t, h.accelerations / G]), delimiter=",")
    np.savetxt(tmp_path / "v.csv", np.column_stack([t, np.full(t.size, 0.2)]), delimiter=",")
    np.savetxt(tmp_path / "down.csv", np.column_stack([t, np.full(t.size, -0.6)]), delimiter=",")
    base = ["run", "--record", str(tmp_path / "h.csv"), "--units", "g", "--t-end", "2"]
    assert main([*base, "--record-vertical", str(tmp_path / "v.csv"), "--json"]) == 0
    out = capsys.readouterr().out
    assert '"vertical": {' in out
    # --scale scales both: 2 x -0.6 g lifts the arch off
    assert main([*base, "--record-vertical", str(tmp_path / "down.csv"), "--scale", "2"]) == 2
    assert "lifts the arch off" in capsys.readouterr().err
    # the four-link model reads it too
    assert main([*base, "--model", "fourlink", "--record-vertical",
                 str(tmp_path / "v.csv")]) == 0


# ------------------------------------------------------------------ the verdict path
@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_verdict_onset_reads_g_plus_av(ratio):
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    threshold = lam / (1.0 - ratio * lam)
    outcomes = [rigid_verdict(OPPENHEIM, StepImpulse.from_g(f * threshold, 1.0,
                                                             vertical=ratio)).outcome.value
                for f in (0.98, 1.02)]
    assert outcomes[0] == "no_hinging" and outcomes[1] != "no_hinging"


def _verdict_critical(tp: float, c: float) -> float:
    lo, hi = 0.3, 4.0
    for _ in range(16):
        mid = 0.5 * (lo + hi)
        motion = StepImpulse(mid * G, tp, steady_vertical=c * G)
        if rigid_verdict(OPPENHEIM, motion).outcome.value == "collapse":
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("c", [0.4, -0.3])
@pytest.mark.parametrize("tp", [0.2, 0.35])
def test_verdict_steady_vertical_time_similarity(c, tp):
    assert _verdict_critical(tp, c) == pytest.approx(
        (1 + c) * _verdict_critical(tp * math.sqrt(1 + c), 0.0), rel=2e-2)


def test_verdict_refuses_lift_off():
    from archquake.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        rigid_verdict(OPPENHEIM, StepImpulse.from_g(2.0, 0.12, vertical=-0.5))


# ------------------------------------------------------------------ the forces during motion
def test_joint_forces_under_a_steady_vertical_are_those_at_g_plus_c():
    """The line of thrust and the friction demand during motion read g + a_v: a steady c gives
    the forces of the same run under gravity g + c (to 1e-6 of the largest normal force);
    the compiled probe and its Python twin agree with a pulse's vertical part."""
    import numpy as np

    from archquake.rigid.forces import joint_forces, joint_forces_reference

    c = 0.3 * G
    up = StepImpulse(0.6 * G, 0.3, steady_vertical=c)
    plain = StepImpulse(0.6 * G, 0.3)
    fa = joint_forces(simulate_rigid(OPPENHEIM, up, duration=1.5), up, every=20)
    fb = joint_forces(simulate_rigid(OPPENHEIM, plain, duration=1.5, g=G + c), plain,
                      g=G + c, every=20)
    scale = np.nanmax(np.abs(fb.normal))
    assert np.nanmax(np.abs(fa.normal - fb.normal)) < 1e-6 * scale
    assert np.nanmax(np.abs(fa.shear - fb.shear)) < 1e-6 * scale
    pulse = StepImpulse.from_g(0.6, 0.3, vertical=0.5)
    run = simulate_rigid(OPPENHEIM, pulse, duration=1.5)
    a, b = joint_forces(run, pulse, every=20), joint_forces_reference(run, pulse, every=20)
    assert np.allclose(a.normal, b.normal, rtol=1e-9, atol=1e-9 * scale)


@pytest.mark.parametrize("c", [0.3, -0.25])
def test_verdict_constant_vertical_record_is_gravity_g_plus_c(c):
    """Oracle: the verdict path under gravity (1 + c) g. Its default step scales with
    sqrt(R/g), so the two differ by the step's error, not the equations: the same outcome and
    collapse half cycle, the collapse time within 1 %, the largest rotation within 3 %
    (measured 0.5 %, 0.08 % and 1.4 %). A zero vertical record gives the verdict without it,
    every number."""
    import numpy as np

    from archquake.ground import Record
    from archquake.ground.vertical import WithVertical

    h, _t, dt = _records()
    long = np.arange(0.0, 12.0, dt)  # the vertical holds through the 10 s window
    up = rigid_verdict(OPPENHEIM, WithVertical(h, Record(np.full(long.size, c * G), dt)),
                       duration=10.0).to_dict()
    heavier = rigid_verdict(OPPENHEIM, h, g=(1 + c) * G, duration=10.0).to_dict()
    assert up["outcome"] == heavier["outcome"] == "collapse"
    assert up["collapse_half_cycle"] == heavier["collapse_half_cycle"]
    assert up["collapse_time_s"] == pytest.approx(heavier["collapse_time_s"], rel=0.01)
    assert up["max_rotation_rad"] == pytest.approx(heavier["max_rotation_rad"], rel=0.03)
    zero = rigid_verdict(OPPENHEIM, WithVertical(h, Record(np.zeros(long.size), dt))).to_dict()
    assert zero == rigid_verdict(OPPENHEIM, h).to_dict()



# ------------------------------------------------------------------ the event integrator
@pytest.mark.parametrize("c", [0.3, -0.25])
def test_events_constant_vertical_record_is_gravity_g_plus_c(c):
    """Oracle: the event integrator under gravity (1 + c) g: the same outcome and largest
    rotation to 1e-7 (its tolerances; measured 2e-9), the energy balance closing as well
    (the vertical's work counted in the input work). A zero vertical record gives the run
    without it, every number."""
    import numpy as np

    from archquake.ground import Record
    from archquake.ground.vertical import WithVertical

    h, t, dt = _records()
    up = simulate_rigid(OPPENHEIM, WithVertical(h, Record(np.full(t.size, c * G), dt)),
                        duration=3.0, solver="events")
    heavier = simulate_rigid(OPPENHEIM, h, duration=3.0, g=(1 + c) * G, solver="events")
    assert up.outcome == heavier.outcome
    assert up.to_dict()["max_rotation_rad"] == pytest.approx(
        heavier.to_dict()["max_rotation_rad"], rel=1e-7)
    assert up.energy.residual < 2.0 * heavier.energy.residual + 1e-8
    zero = simulate_rigid(OPPENHEIM, WithVertical(h, Record(np.zeros(t.size), dt)),
                          duration=3.0, solver="events").to_dict()
    plain = simulate_rigid(OPPENHEIM, h, duration=3.0, solver="events").to_dict()
    for d in (zero, plain):
        d.pop("excitation")
        del d["rigid"]["wall_s"]
    assert repr(to_jsonable(zero)) == repr(to_jsonable(plain))


@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_events_and_stepper_agree_under_a_pulse_vertical(ratio):
    """Oracle: the time stepper at 1e-4 s. A 0.6 g step of 0.4 s with R = +-0.5 on
    Oppenheim's arch, to 2.5 s (both lobes of the vertical act before the first impact): the
    first two peak rotations within 0.5 %, the first impact within 0.1 % (measured 0.05 % and
    4e-5); the event integrator's energy balance closes with the vertical's work (residual
    below 1e-7; measured 3e-9 and 9e-10)."""
    motion = StepImpulse.from_g(0.6, 0.4, vertical=ratio)
    ev = simulate_rigid(OPPENHEIM, motion, duration=2.5, solver="events")
    st = simulate_rigid(OPPENHEIM, motion, duration=2.5)
    assert ev.outcome == st.outcome
    for a, b in zip(ev.peak_rotation[:2], st.peak_rotation[:2], strict=True):
        assert a == pytest.approx(b, rel=5e-3)
    assert ev.first_impact_time == pytest.approx(st.first_impact_time, rel=1e-3)
    assert ev.energy.residual < 1e-7


@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_events_onset_reads_g_plus_av(ratio):
    """Oracle: the limit analysis, |a_h| > lambda (g + R a): a long step 2 % either side of
    lambda g / (1 - R lambda), as the time stepper is held."""
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    threshold = lam / (1.0 - ratio * lam)
    below = simulate_rigid(OPPENHEIM, StepImpulse.from_g(0.98 * threshold, 1.0, vertical=ratio),
                           duration=3.5, solver="events")
    above = simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.02 * threshold, 1.0, vertical=ratio),
                           duration=3.5, solver="events")
    assert below.outcome.value == "no_hinging"
    assert above.outcome.value != "no_hinging"
