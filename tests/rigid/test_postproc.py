"""The rigid chain's post-processing, vectorised (the samples -> BlockResult path that any stepper
of the model calls, ``rigid_chain._samples_to_run``), gives what the per-sample code did.

Oracle: the per-sample and per-joint code of main before the vectorisation, kept verbatim as
plain references in :mod:`archquake.blocks._result_reference` (test and benchmark only), run on
the very samples a history hands to ``_samples_to_run``. The new code performs the same
floating-point operations in the same order, so arrays are compared exactly, except the
joint kinematics (a compiled loop: 1e-12 m, against openings of 1e-4..1e-1 m; measured
bit-identical here); discrete results (outcome, onset sample, number of impacts, hinge
labels) must agree exactly.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys
from dataclasses import fields

import numpy as np
import pytest

from archquake import Arch
from archquake.blocks import _result_reference as REF
from archquake.blocks.assembly import block_on_base, build_arch_assembly
from archquake.blocks.criteria import BlockCriteria
from archquake.blocks.result import collapse_time, crossings, joint_kinematics, mirror_link
from archquake.ground import StepImpulse
from archquake.outcome import Outcome
from archquake.rigid import run as RC
from archquake.rigid import steps as RS

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


# ----------------------------------------------------------------------- the histories
def _run(monkeypatch, motion, duration):
    """A history and the samples its stepper handed to ``_samples_to_run``."""
    seen = {}
    inner = RC._samples_to_run

    def spy(model, motion, settings, got, **kw):
        seen.update({f.name: getattr(got, f.name) for f in fields(got)}, model=model,
                    settings=settings)
        return inner(model, motion, settings, got, **kw)

    monkeypatch.setattr(RC, "_samples_to_run", spy)
    return RC.simulate_rigid(OPPENHEIM, motion, duration=duration), seen


@pytest.mark.parametrize("motion, duration, outcome", [
    (StepImpulse.from_g(1.0, 0.20), 2.0, Outcome.INDETERMINATE),  # rocking, impacts
    (StepImpulse.from_g(1.0, 0.20, direction=1), 2.0, Outcome.INDETERMINATE),  # mirror
    (StepImpulse.from_g(2.0, 0.40), 3.0, Outcome.COLLAPSE),  # stops at the collapse
])
def test_vectorised_post_processing_is_mains(monkeypatch, motion, duration, outcome):
    run, s = _run(monkeypatch, motion, duration)
    res, model = run, s["model"]
    assert res.outcome is outcome
    # states and energies: as main's per-sample closure and sums built them
    states = np.array([REF.absolute(model, a, b, u, w) for a, b, u, w in zip(
        s["q"], s["v"], s["ground_displacement"], s["ground_velocity"])])
    assert np.array_equal(res.times, s["times"])
    assert np.array_equal(res.positions, states[:, :, :3])
    assert np.array_equal(res.velocities, states[:, :, 3:])
    va, qa = s["v"], s["q"]
    kin = 0.5 * ((va[:, :, 0] ** 2 + va[:, :, 1] ** 2) @ model.mass + va[:, :, 2] ** 2 @ model.inertia)
    pot = res.g * (qa[:, :, 1] - model.centroids[None, :, 1]) @ model.mass
    assert np.array_equal(res.kinetic, kin)
    assert np.array_equal(res.potential, pot)
    assert np.array_equal(res.damping, s["dissipated"])
    assert np.array_equal(res.input_work, s["input_work"])
    assert np.array_equal(res.base_displacement, s["ground_displacement"])
    assert np.array_equal(res.base_velocity, s["ground_velocity"])
    # the joint kinematics, the onset, the collapse, the impacts, the hinge sets
    asm = model.assembly
    opening, slip = REF.joint_kinematics(asm, states[:, :, :3])
    np.testing.assert_allclose(res.joint_opening, opening, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.joint_slip, slip, rtol=0, atol=1e-12)
    thr = res.criteria.hinge_opening * asm.reference_length
    assert res.onset_time == float(res.times[np.argmax(np.any(opening > thr, axis=(1, 2)))])
    assert res.collapse_time == REF.collapse_time(asm, res.criteria, res.times, states[:, :, :3])
    stop = len(res.times) if res.collapse_time is None else int(
        np.searchsorted(res.times, res.collapse_time))
    impacts = REF.crossings(res.times, res.rotation, res.criteria.hinge_opening, stop)
    assert impacts.size == res.impact_times.size
    np.testing.assert_allclose(res.impact_times, impacts, rtol=0, atol=1e-12)
    if outcome is not Outcome.COLLAPSE:
        assert impacts.size >= 2
    assert res.hinge_sets() == REF.hinge_sets(res)
    assert len(res.hinge_sets()) >= 2


@pytest.mark.parametrize("arch", [OPPENHEIM, Arch(5.0, 0.9, math.radians(180.0), 15)])
def test_compiled_joint_kinematics_and_collapse_match_the_per_joint_code(arch):
    """Blocks displaced by up to 0.1 m and turned by up to 0.6 rad at random (joints open,
    overlap, slide; some samples meet a collapse criterion), and the undisplaced assembly,
    whose openings are +-0 (the sign of zero as main's ``np.sum`` gives it)."""
    asm = build_arch_assembly(arch)
    rng = np.random.default_rng(3)
    nt, nb = 400, len(asm.base)
    pos = np.zeros((nt, nb, 3))
    pos[:, :, :2] = asm.centroids
    scale = np.geomspace(1e-6, 1.0, nt)[:, None]
    pos[:, :, :2] += 0.1 * scale[:, :, None] * rng.uniform(-1, 1, size=(nt, nb, 2))
    pos[:, :, 2] = 0.6 * scale * rng.uniform(-1, 1, size=(nt, nb))
    pos[0, :, 2] = 0.0
    pos[0, :, :2] = asm.centroids
    opening, slip = joint_kinematics(asm, pos)
    want_opening, want_slip = REF.joint_kinematics(asm, pos)
    np.testing.assert_allclose(opening, want_opening, rtol=0, atol=1e-12)
    np.testing.assert_allclose(slip, want_slip, rtol=0, atol=1e-12)
    assert np.array_equal(np.signbit(opening[0]), np.signbit(want_opening[0]))
    t = np.arange(nt) * 1e-3
    settings = BlockCriteria()
    assert collapse_time(asm, settings, t, pos) is None
    pos[-30:, asm.crown_block, 2] = 2.0  # turned past collapse_rotation
    pos[-20:, :, 1] -= 2.0 * asm.reference_length  # the crown has fallen
    assert collapse_time(asm, settings, t, pos) == REF.collapse_time(asm, settings, t, pos) == t[-30]
    pos[-30:, asm.crown_block, 2] = 0.0
    assert collapse_time(asm, settings, t, pos) == REF.collapse_time(asm, settings, t, pos) == t[-20]


def test_mirror_link_matches_the_per_pair_loop():
    """Mirror-symmetric assemblies (two arches, a block on its base) give the same mirrored
    chord; the three-voussoir cut of Oppenheim's arch (blocks of 3, 2 and 2 voussoirs) and an
    arch with one voussoir's mass changed have no mirror image (None)."""
    symmetric = [build_arch_assembly(OPPENHEIM), block_on_base(0.4, 2.0),
                 build_arch_assembly(Arch(5.0, 0.9, math.radians(180.0), 15))]
    asm = symmetric[0]
    masses = np.array(asm.masses, dtype=float)
    masses[2] *= 1.01
    broken = [build_arch_assembly(OPPENHEIM, cut_joints=(0, 3, 5, 7)),
              dataclasses.replace(asm, masses=masses)]
    for assembly in symmetric + broken:
        got, want = mirror_link(assembly), REF.mirror_link(assembly)
        assert (got is None) == (want is None) == any(assembly is b for b in broken)
        if got is not None:
            assert (got.block_a, got.block_b, got.sign) == (want.block_a, want.block_b, want.sign)
            assert np.array_equal(got.point_a, want.point_a)
            assert np.array_equal(got.point_b, want.point_b)


def test_crossings_match_the_per_sample_loop():
    """Random walks crossing zero hundreds of times, with exact zeros, values at the threshold,
    runs that never arm and a cut at ``stop``."""
    rng = np.random.default_rng(7)
    for trial in range(40):
        n = int(rng.integers(1, 3000))
        rot = np.cumsum(rng.normal(size=n)) * 10.0 ** rng.uniform(-4, 0)
        rot[rng.random(n) < 0.05] = 0.0
        threshold = float(np.quantile(np.abs(rot), rng.uniform(0, 1.0)))
        rot[rng.random(n) < 0.02] = threshold * rng.choice([-1.0, 1.0])
        t = np.cumsum(rng.uniform(1e-4, 1e-3, size=n))
        stop = None if trial % 3 else int(rng.integers(0, n + 1))
        got, want = crossings(t, rot, threshold, stop), REF.crossings(t, rot, threshold, stop)
        assert got.shape == want.shape and np.array_equal(got, want)
    assert crossings(np.arange(5.0), np.array([0.0, 2.0, -2.0, 2.0, -2.0]), 1.0).size == 3


def test_rest_check_on_chunks_is_the_per_sample_check():
    """``_at_rest`` reads the recorded chunks; the per-sample version read flat lists. Both, on
    a history that comes to rest, at every chunk boundary and for chunks of several sizes."""
    motion = StepImpulse.from_g(0.6, 0.10)
    run = RC.simulate_rigid(OPPENHEIM, motion, duration=3.5, until_rest=8.0)
    model = RC.RigidModel.build(OPPENHEIM)
    g = run.g
    t, v = run.times, run.velocities[:, model.free_blocks]
    answers = set()
    for size in (1, 7, 100):
        for end in range(2, len(t) + 1, 450):
            edges = list(range(1, end, size)) + [end]
            chunks_t = [t[:1]] + [t[a:b] for a, b in zip(edges[:-1], edges[1:])]
            chunks_v = [v[:1]] + [v[a:b] for a, b in zip(edges[:-1], edges[1:])]
            want = REF.at_rest(model, g, list(t[:end]), list(v[:end]), motion)
            assert RS._at_rest(model, g, chunks_t, chunks_v, motion) == want
            answers.add(want)
    assert answers == {True, False}


def test_production_code_does_not_import_the_plain_reference():
    """blocks/_result_reference.py is test and benchmark only: a rigid run to its summary does not
    load it."""
    code = (
        "import sys, math\n"
        "from archquake import Arch\n"
        "from archquake.ground import StepImpulse\n"
        "from archquake.rigid import simulate_rigid\n"
        "run = simulate_rigid(Arch(10.0, 1.5, math.radians(157.5), 7), StepImpulse.from_g(1.0, 0.2),"
        " duration=0.3)\n"
        "run.to_dict(joint_forces=False)\n"
        "print('archquake.blocks._result_reference' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
