"""The vertical ground acceleration: pulses with a vertical part, and the four-link model under
gravity g + a_v(t).

Oracles: the pulse's own shape (the step's +1, -1/2, 0); the onset of hinging, exact,
|a_h| > lambda (g + a_v), i.e. a > lambda g / (1 - R lambda) for the step's first lobe; the time
similarity of a constant vertical c g, A(t_p; c) = (1 + c) A(t_p sqrt(1 + c); 0), exact for
the four-link model up to its tolerances (checked to 1e-8, the bisection's resolution being
1e-11); and R = 0 describing the motion exactly as before (so every digest holds).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.cli.main import main
from archquake.constants import STANDARD_GRAVITY as G
from archquake.dem import simulate_dem
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.ground import SinePulse, StepImpulse
from archquake.ground._kernel import vertical_in_piece
from archquake.limit import limit_analysis
from archquake.mechanism import simulate
from archquake.rigid import simulate_rigid

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


# ------------------------------------------------------------------ the pulses
def test_step_vertical_part_is_the_pulse_shape():
    p = StepImpulse.from_g(0.8, 0.2, vertical=0.5)
    t = np.array([0.1, 0.3, 0.7])
    assert np.allclose(p.vertical_acceleration(t) / G, [0.4, -0.2, 0.0], rtol=0, atol=1e-15)
    kind, params = p.kernel_spec()
    compiled = [vertical_in_piece(kind, params, x, x) for x in t]
    assert np.array_equal(compiled, p.vertical_acceleration(t))
    # the first lobe is +1 whichever side the horizontal starts: mirrored keeps the vertical
    assert np.array_equal(p.mirrored().vertical_acceleration(t), p.vertical_acceleration(t))
    # scaled(-1) multiplies every acceleration, the vertical too
    assert np.allclose(p.scaled(-1.0).vertical_acceleration(t), -p.vertical_acceleration(t))


def test_sine_vertical_part_and_negative_ratio():
    p = SinePulse.from_g(0.5, 1.0, vertical=-0.4)
    t = np.array([0.25, 0.75, 1.5])
    assert np.allclose(p.vertical_acceleration(t) / G, [-0.2, 0.2, 0.0], atol=1e-15)


def test_no_vertical_is_described_as_before():
    for p in (StepImpulse.from_g(1.0, 0.27), SinePulse.from_g(0.5, 1.0)):
        assert p.kernel_spec()[1].shape == (3,)
        assert "vertical_ratio" not in p.to_dict()
    assert StepImpulse.from_g(1.0, 0.27, vertical=0.5).to_dict()["vertical_ratio"] == 0.5


@pytest.mark.parametrize("ratio", [2.5, math.nan])
def test_ratio_out_of_range(ratio):
    with pytest.raises(InvalidParameterError, match="vertical ratio"):
        StepImpulse.from_g(1.0, 0.2, vertical=ratio)


# ------------------------------------------------------------------ the four-link model
@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_onset_of_hinging_reads_g_plus_av(ratio):
    """A long step (t_p 5 s): the arch hinges iff a > lambda (g + R a)."""
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    threshold = lam / (1.0 - ratio * lam)
    below = simulate(OPPENHEIM, StepImpulse.from_g(threshold * 0.999, 5.0, vertical=ratio))
    above = simulate(OPPENHEIM, StepImpulse.from_g(threshold * 1.001, 5.0, vertical=ratio))
    assert below.outcome.value == "no_hinging"
    assert above.outcome.value != "no_hinging"
    # without the vertical the same magnitudes both hinge (R > 0) or neither does (R < 0)
    plain = simulate(OPPENHEIM, StepImpulse.from_g(threshold * (0.999 if ratio > 0 else 1.001),
                                                   5.0))
    assert (plain.outcome.value != "no_hinging") == (ratio > 0)


def _critical(tp: float, c: float) -> float:
    lo, hi = 0.3, 5.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        motion = StepImpulse(mid * G, tp, steady_vertical=c * G)
        if simulate(OPPENHEIM, motion).outcome.value == "collapse":
            hi = mid
        else:
            lo = mid
    return hi


@pytest.mark.parametrize("c", [0.4, -0.3])
@pytest.mark.parametrize("tp", [0.15, 0.3])
def test_constant_vertical_time_similarity(c, tp):
    """A(t_p; c) = (1 + c) A(t_p sqrt(1 + c); 0): the vertical rescales gravity, hence time."""
    assert _critical(tp, c) == pytest.approx((1 + c) * _critical(tp * math.sqrt(1 + c), 0.0),
                                             rel=1e-8)


def _record(c_g: float | None = None):
    """A record (0.8 g towards -x for 0.3 s, 0.4 g back for 0.6 s, 3 s at 0.005 s), and with
    it a vertical of a constant ``c_g`` g over the same samples."""
    from archquake.ground import Record
    from archquake.ground.vertical import WithVertical

    dt = 0.005
    t = np.arange(0.0, 3.0 + dt / 2, dt)
    x = np.where(t < 0.3, -0.8 * G, np.where(t < 0.9, 0.4 * G, 0.0))
    x[-1] = 0.0
    h = Record(x, dt, name="h")
    return h if c_g is None else WithVertical(h, Record(np.full(t.size, c_g * G), dt, name="v"))


@pytest.mark.parametrize("c", [0.3, -0.25])
def test_a_constant_vertical_record_is_gravity_g_plus_c(c):
    """Oracles: the same record under gravity (1 + c) g (simulate's g), and under g with time
    scaled, x(t) -> x(t sqrt(1 + c)) / (1 + c) (the record's dt times sqrt(1 + c)): the first
    half cycle's peak rotation and the impact times to 1e-9 (the solver's tolerances), and
    the outcome. The collapse itself is reported where each run detects it (the record's no-return
    criterion counts the rest of the vertical too), so the later peaks are not compared."""
    from archquake.ground import Record

    up = simulate(OPPENHEIM, _record(c), t_end=3.0).to_dict()
    heavier = simulate(OPPENHEIM, _record(), t_end=3.0, g=(1 + c) * G).to_dict()
    h = _record()
    slow = simulate(OPPENHEIM, Record(h.accelerations / (1 + c), h.dt * math.sqrt(1 + c)),
                    t_end=3.0 * math.sqrt(1 + c)).to_dict()
    for other, clock in ((heavier, 1.0), (slow, math.sqrt(1 + c))):
        assert up["outcome"] == other["outcome"] == "collapse"
        assert up["peak_rotation_rad"][0] == pytest.approx(other["peak_rotation_rad"][0],
                                                           rel=1e-9)
        assert np.allclose(np.asarray(up["impact_times_s"]) * clock, other["impact_times_s"],
                           rtol=1e-9, atol=0)


def test_a_zero_vertical_record_runs_as_before():
    """Oracle: today's run of the horizontal alone, every number."""
    plain = simulate(OPPENHEIM, _record()).to_dict()
    zero = simulate(OPPENHEIM, _record(0.0)).to_dict()
    assert repr(zero) == repr(plain)


def test_zero_vertical_runs_as_before():
    a = simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.27)).to_dict()
    b = simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.27, vertical=0.0)).to_dict()
    assert repr(a) == repr(b)


def test_lift_off_is_refused():
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.27, vertical=-1.2))
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        simulate(OPPENHEIM, StepImpulse(0.1, 0.27, steady_vertical=-1.0 * G))


def test_lift_off_is_refused_by_every_model():
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        simulate_dem(OPPENHEIM, StepImpulse.from_g(1.0, 0.27, vertical=-1.2))
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        simulate_rigid(OPPENHEIM, StepImpulse.from_g(1.0, 0.27, vertical=-1.2), solver="events")
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        simulate_rigid(OPPENHEIM, _record(-1.1), solver="events")


def test_cli_record_vertical_fourlink(tmp_path, capsys):
    h = _record()
    t = h.times
    np.savetxt(tmp_path / "h.csv", np.column_stack([t, h.accelerations / G]), delimiter=",")
    np.savetxt(tmp_path / "v.csv", np.column_stack([t, np.full(t.size, 0.2)]), delimiter=",")
    assert main(["run", "--model", "fourlink", "--record", str(tmp_path / "h.csv"), "--units",
                 "g", "--record-vertical", str(tmp_path / "v.csv"), "--t-end", "2",
                 "--json"]) == 0
    assert '"vertical": {' in capsys.readouterr().out


def test_cli_vertical(capsys):
    assert main(["run", "--model", "fourlink", "--pulse", "step", "--magnitude", "1",
                 "--duration", "0.27", "--vertical", "0.5", "--json"]) == 0
    assert '"vertical_ratio": 0.5' in capsys.readouterr().out
    assert main(["run", "--model", "fourlink", "--pulse", "step", "--magnitude", "1",
                 "--duration", "0.27", "--vertical", "-1.5"]) == 2
    assert "--vertical -1.5" in capsys.readouterr().err
    assert main(["run", "--integrator", "events", "--pulse", "step", "--magnitude", "1",
                 "--duration", "0.27", "--vertical", "0.5", "--json"]) == 0
    assert '"vertical_ratio": 0.5' in capsys.readouterr().out


# ------------------------------------------------------------------ study files and the API
def test_study_file_vertical_ratio_axis():
    from archquake.ground.spec import ExcitationSpec
    from archquake.sweeps.study import parse_study

    study = parse_study({
        "study": {"name": "s"},
        "arches": {"radius": 10, "thickness_ratio": 0.15, "embrace_deg": 157.5, "voussoirs": 7},
        "excitation": {"type": "step", "magnitude_g": 1.0, "duration_s": 0.27,
                       "vertical_ratio": [0.0, 0.5, -0.5]},
    })
    motions = [c.excitation.build() for c in study.cases]
    assert sorted(m.vertical for m in motions) == [-0.5, 0.0, 0.5]
    assert len({c.case_id for c in study.cases}) == 3
    # a case without a vertical keeps its id
    plain = ExcitationSpec("step", magnitude_g=1.0, duration_s=0.27)
    zero = [c for c in study.cases if not c.excitation.vertical_ratio][0]
    assert zero.excitation.canonical() == plain.canonical()
    with pytest.raises(InvalidParameterError, match="vertical_ratio does not apply"):
        ExcitationSpec("record", file="x.AT2", vertical_ratio=0.5)
