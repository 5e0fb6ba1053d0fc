"""The DEM result in the shared vocabulary: the collapse stops the run, the mirrored excitation
gives the mirrored result, one Outcome for both models, and the reference kernel is test-only."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from archquake.blocks.assembly import block_on_base
from archquake.blocks.result import crown_height, mirror_link
from archquake.dem import DemSettings, build_arch_assembly, simulate_dem
from archquake.geometry import Arch
from archquake.ground.pulses import StepImpulse
from archquake.outcome import RESULT_KEYS, Outcome


@pytest.fixture(scope="module")
def arch():
    return Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.fixture(scope="module")
def figure4b(arch):
    """a = 1.0 g, t_p = 0.44 s (paper Figure 4(b)) on the 7-voussoir arch, and its mirror image."""
    motion = StepImpulse.from_g(1.0, 0.44)
    settings = DemSettings(duration=3.0)
    return simulate_dem(arch, motion, settings), simulate_dem(arch, motion.mirrored(), settings)


def test_the_run_stops_at_the_collapse(figure4b, arch):
    """The run stops at the first sample meeting a collapse criterion (the stepper's contract,
    DemSettings.stop_at_collapse), the same instant the result reports. Oracle: the crown point
    carried by its block has fallen by more than collapse_drop * t = 1.5 m since t = 0 at the
    last sample, and not at the one before. (Before the crown's initial height was given to the
    stepper, this run went on to 2.31 s although the collapse is at 1.51 s.)"""
    res, _ = figure4b
    assert res.outcome is Outcome.COLLAPSE and res.collapse_half_cycle == 1
    assert res.end_time == res.collapse_time
    assert res.collapse_time < 1.6
    crown = crown_height(res.assembly, res.positions)
    drop = crown[0] - crown
    assert drop[-1] > arch.thickness >= drop[-2]
    assert res.n_steps < int(math.ceil(3.0 / res.time_step))


def test_a_mirrored_excitation_gives_the_mirrored_result(figure4b):
    """Symmetry: Oppenheim's arch is its own mirror image, so the mirror-image excitation must
    give the mirror image of the run: rotation measure negated, the same impacts (none), the
    same outcome, half cycle and collapse time, every block's position reflected. (Before the
    measure followed the excitation, the mirrored run reported 'collapse in half cycle 2' after
    a spurious impact at 1.45 s.)

    Tolerance: round-off (1e-10) while the joints that hinge stay in contact, up to 1.0 s
    (measured 5e-13 rad, 2e-12 m). From 1.05 s the collapsing voussoirs separate and touch
    again; a contact that forms then is given to the corner of the lower-numbered block of the
    pair, which the mirror image swaps, so the two runs part by 1e-8 m at the first such
    contact (1.11 s) and 6e-5 rad by the collapse (measured); 1e-3 rad there is still 0.4 % of
    the 0.25 rad peak, and every discrete result must agree exactly."""
    res, mir = figure4b
    assert mir.rotation_link != res.rotation_link
    np.testing.assert_array_equal(mir.times, res.times)
    early = res.times <= 1.0
    np.testing.assert_allclose(mir.rotation[early], -res.rotation[early], rtol=0, atol=1e-10)
    np.testing.assert_allclose(mir.rotation, -res.rotation, rtol=0, atol=1e-3)
    assert mir.impact_times.size == res.impact_times.size == 0
    assert (mir.outcome, mir.collapse_half_cycle, mir.collapse_time, mir.onset_time) == (
        res.outcome, res.collapse_half_cycle, res.collapse_time, res.onset_time)
    nb = res.assembly.n_blocks
    image = [1, 0, *range(nb - 1, 1, -1)]  # abutments swap, voussoirs reverse
    reflected = mir.positions[:, image, :] * np.array([-1.0, 1.0, -1.0])
    np.testing.assert_allclose(reflected[early], res.positions[early], rtol=0, atol=1e-10)


def test_mirror_link_of_symmetric_and_asymmetric_assemblies(arch):
    """The mirror image of the rotation link exists for assemblies that are their own mirror
    image (the voussoir arch: link on voussoirs 0..2 -> 6..4; a block on its base: the block
    itself) and not for the arch cut at the (asymmetric) hinges (0, 3, 5, 7)."""
    asm = build_arch_assembly(arch)
    m = mirror_link(asm)
    link = asm.rotation_link
    assert (m.block_a, m.block_b) == (asm.n_blocks + 1 - link.block_a, asm.n_blocks + 1 - link.block_b)
    np.testing.assert_allclose(m.point_a, link.point_a * np.array([-1.0, 1.0]))
    assert m.sign == link.sign
    assert mirror_link(block_on_base(0.4, 2.0)).block_a == 1
    assert mirror_link(build_arch_assembly(arch, cut_joints=(0, 3, 5, 7))) is None


def test_one_outcome_and_one_result_vocabulary(arch, figure4b):
    """Both models classify with the one Outcome enum and their to_dict() start with the same
    keys, in the same units (RESULT_KEYS)."""
    from archquake.mechanism import Outcome as MechanismOutcome
    from archquake.mechanism import simulate

    assert MechanismOutcome is Outcome
    res, _ = figure4b
    an = simulate(arch, StepImpulse.from_g(1.0, 0.44))
    assert an.outcome is res.outcome is Outcome.COLLAPSE
    d, a = res.to_dict(), an.to_dict()
    assert list(d)[: len(RESULT_KEYS)] == list(a)[: len(RESULT_KEYS)] == list(RESULT_KEYS)
    assert (d["model"], a["model"]) == ("dem", "fourlink")
    assert d["collapse_half_cycle"] == a["collapse_half_cycle"] == 1
    assert d["impact_times_s"] == a["impact_times_s"] == []
    assert d["collapse_time_s"] == res.collapse_time and a["collapse_time_s"] == an.collapse_time
    assert d["max_rotation_rad"] == pytest.approx(float(np.max(np.abs(res.rotation))))


def test_production_code_does_not_import_the_reference_kernel():
    """dem/_reference.py is test-only: running the DEM (stable time step included) must not
    load it."""
    code = (
        "import sys, math\n"
        "from archquake.dem import simulate_dem, DemSettings, block_on_base\n"
        "from archquake.ground.pulses import StepImpulse\n"
        "simulate_dem(block_on_base(0.4, 2.0), StepImpulse.from_g(0.1, 0.05), DemSettings(duration=0.01))\n"
        "print('archquake.dem._reference' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_dem_run_cut_short_while_rocking_is_indeterminate(arch):
    """The DEM's verdict follows the block models' rule: Figure 4's 0.20 s step at 1.0 g, run
    for DemSettings()'s default 3 s, ends rocking (impacts up to the end): not 'survives' but
    'indeterminate', with the reason; final_state says 'moving'."""
    res = simulate_dem(arch, StepImpulse.from_g(1.0, 0.20), DemSettings(output_interval=2e-3))
    assert res.collapse_time is None and res.impact_times.size >= 3
    assert res.outcome is Outcome.INDETERMINATE
    d = res.to_dict()
    assert d["final_state"] == "moving" and "still moving" in d["verdict"]


def test_dem_default_run_goes_on_to_a_verdict(capsys):
    """``archquake run --model dem`` without --t-end: Figure 4(d)'s pulse on the seven
    voussoirs still rocks at the default end (excitation + 5 sqrt(R/g) = 5.65 s; last impact
    4.9 s). The run goes on, up to 20 sqrt(R/g), and ends once at rest: 'survives', before
    10 sqrt(R/g) (10.7 s), where a run of that length, the second window the verdict was once
    looked for in by rerunning from the start, is at rest too (dem.run.dem_to_verdict; sweeps
    and IDA use it too)."""
    import json

    from archquake.cli.main import main
    from archquake.dem.run import default_dem_duration

    assert main(["run", "--model", "dem", "--pulse", "step", "--magnitude", "1.0",
                 "--duration", "0.20", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcome"] == "survives" and out["final_state"] == "rest"
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    first, second = (default_dem_duration(arch, motion, tail=t) for t in (5.0, 10.0))
    assert first < out["end_time_s"] < second
    full = simulate_dem(arch, motion, DemSettings(duration=second))
    assert full.outcome.value == "survives"


def test_a_verdict_run_takes_the_longest_tail_its_work_bound_allows(monkeypatch):
    """A long record's run to a verdict may not afford the longest tail within the DEM's work
    bound (``ranges.DEM_MAX_BLOCK_STEPS``): it then runs to the longest tail that fits, where
    it refused to run at all. Oracle: `block_steps` of each tail's window, against a bound set
    between the first tail's work and the longest's, on Figure 4(d)'s pulse."""
    import archquake.dem.run as R
    from archquake.blocks.criteria import default_window
    from archquake.errors import InvalidParameterError

    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    asm = build_arch_assembly(arch)
    base = DemSettings()
    dt = R.stable_time_step(asm, base)[0]
    windows = [default_window(motion, arch.radius, tail=t) for t in R.VERDICT_TAILS]
    work = [R.block_steps(asm, w, dt, base.settle_time) for w in windows]
    assert work[0] < work[1] < work[-1]
    monkeypatch.setattr(R, "DEM_MAX_BLOCK_STEPS", (work[1] + work[-1]) // 2)
    with pytest.raises(InvalidParameterError, match="block-steps"):
        simulate_dem(arch, motion, base.with_(duration=windows[-1]))
    run = R.dem_to_verdict(arch, motion)
    assert run.outcome.value == "survives"  # at rest before the second tail's end
    assert run.end_time <= windows[1]
