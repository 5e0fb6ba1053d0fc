"""Time histories that follow the chain law's post-impact mechanisms (issue 10).

Oracles, each independent of the kernel's impact table:

* energy: the kinetic energy 1/2 m_eff(0) phi'^2 (m_eff from the packed kinematics) across every
  impact is the chain law's c_T (generalised momentum on the voussoir velocity fields,
  :func:`~archquake.mechanism.impact_chain.chain_impact`);
* the rate ratio is the law's ``post_rate`` (the post mechanism's own phi, HingeMechanism
  convention) measured in the kinetic metric of the voussoir fields;
* mirror symmetry: the ground motion negated gives the same times and mirrored hinges;
* where the reachable set is {P, mirror(P)} the history is the "mirror" law's (one row) and
  Eq. 4's;
* dynamic similarity: R x4 with the pulse duration x2 scales every time by 2;
* a plain solve_ivp integration that packs each post-impact mechanism as the law returns it
  (no canonical rows, no mirror bookkeeping) and takes the law's ``post_rate``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from archquake import Arch
from archquake.ground import StepImpulse
from archquake.limit import hinges_of
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.mechanism.impact_chain import chain_impact, kinetic_energy, mechanism_field
from archquake.mechanism.kinematics import acceleration
from archquake.mechanism.prepared import pack_mechanism
from archquake.outcome import Outcome

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
SEMICIRCLE = Arch(5.0, 0.6, math.pi, 15)
G = 9.80665


def test_table_rate_ratio_is_the_laws_post_rate():
    """sqrt(2 T_post) per unit closing rate two ways: the table's ratio with the packed m_eff(0),
    and the law's post_rate with the post mechanism's own voussoir field (to 1e-9)."""
    table = PreparedMechanism.build(SEMICIRCLE, "chain").table
    meff = table.meff0()
    for i, mech in enumerate(table.mechanisms):
        sol = chain_impact(mech)
        j = int(table.next_row[i])
        if sol.post is None or j < 0:
            continue
        v, w = mechanism_field(sol.post.points, sol.post.rates, sol.post.joints, SEMICIRCLE)
        law = sol.post_rate * math.sqrt(2.0 * kinetic_energy(SEMICIRCLE, v, w))
        assert table.rate_ratio[i] * math.sqrt(meff[j]) == pytest.approx(law, rel=1e-9)
        assert table.restitution_ct[i] == pytest.approx(sol.restitution_ct, rel=1e-12)


@pytest.mark.parametrize("arch, a, tp", [(OPPENHEIM, 1.0, 0.20), (SEMICIRCLE, 0.15, 0.10),
                                         (SEMICIRCLE, 0.10, 0.20)])
def test_energy_across_every_impact_is_the_laws(arch, a, tp):
    prep = PreparedMechanism.build(arch, "chain")
    r = simulate(prep, StepImpulse.from_g(a, tp), options=SolverOptions(output_interval=0.0))
    table = prep.table
    meff = table.meff0()
    impacts = [e for e in r.mechanisms if e.kind != "onset"]
    assert len(impacts) == r.impact_times.size >= 2
    law: dict[int, float] = {}  # the law's c_T of each row's impact, solved on first use
    pre = 0
    for e, (before, after) in zip(impacts, r.impact_rates):
        if e.row < 0:
            break
        if pre not in law:
            law[pre] = chain_impact(table.mechanisms[pre], exact=False).restitution_ct
        law_ct = law[pre]
        t_before = 0.5 * meff[pre] * before**2
        t_after = 0.5 * meff[e.row] * after**2
        if e.kind == "impact":
            assert t_after / t_before == pytest.approx(law_ct, rel=1e-12)
            assert law_ct <= 1.0
        pre = e.row if e.kind == "impact" else 0


def test_mirror_symmetry_of_the_whole_history():
    """The ground motion towards +x instead of -x: the same times (exactly: the kernel sees
    side * a), each mechanism the mirror image of the other run's."""
    prep = PreparedMechanism.build(SEMICIRCLE, "chain")
    a = simulate(prep, StepImpulse.from_g(0.15, 0.10, direction=-1))
    b = simulate(prep, StepImpulse.from_g(0.15, 0.10, direction=+1))
    assert a.outcome == b.outcome
    assert np.array_equal(a.impact_times, b.impact_times) and a.impact_times.size >= 2
    assert len(a.mechanisms) == len(b.mechanisms)
    for ea, eb in zip(a.mechanisms, b.mechanisms):
        assert ea.row == eb.row and ea.side == -eb.side and ea.time_s == eb.time_s
        assert prep.table.hinges_label(max(ea.row, 0), -ea.side) == eb.hinges


def test_symmetric_set_history_equals_the_mirror_law_and_the_paper():
    """t/R = 0.19 (hinges 0i 2e 5i 7e, symmetric): the set is {P, mirror(P)}, one row, and the
    chain history is the "mirror" law's (the same c_T from two code paths of the law: 1e-12) and
    Eq. 4's (c_v equal to 1e-10)."""
    arch = Arch(10.0, 1.9, math.radians(157.5), 7)
    prep = PreparedMechanism.build(arch, "chain")
    assert prep.table.size == 1 and prep.table.flip[0] == -1
    motion = StepImpulse.from_g(1.2, 0.2)
    opts = SolverOptions(output_interval=0.0)
    c = simulate(prep, motion, options=opts)
    m = simulate(arch, motion, impact="mirror", options=opts)
    p = simulate(arch, motion, impact="paper", options=opts)
    assert c.impact_times.size >= 2 and c.outcome == m.outcome == p.outcome
    assert np.allclose(c.impact_times, m.impact_times, rtol=0, atol=1e-12)
    assert np.allclose(c.impact_rates, m.impact_rates, rtol=1e-12)
    assert np.allclose(c.impact_times, p.impact_times, rtol=0, atol=1e-8)


def test_dynamic_similarity():
    """R x4 and t_p x2 (sqrt(4)): every time x2, rates /2, the same mechanisms (1e-9)."""
    small = simulate(Arch(5.0, 0.6, math.pi, 15), StepImpulse.from_g(0.15, 0.10), impact="chain")
    big = simulate(Arch(20.0, 2.4, math.pi, 15), StepImpulse.from_g(0.15, 0.20), impact="chain")
    assert small.impact_times.size >= 2
    assert np.allclose(big.impact_times, 2.0 * small.impact_times, rtol=1e-9)
    assert np.allclose(big.impact_rates, 0.5 * small.impact_rates, rtol=1e-9)
    assert [e.hinges for e in big.mechanisms] == [e.hinges for e in small.mechanisms]
    assert big.outcome == small.outcome


def _oracle_impacts(arch, motion, n):
    """solve_ivp (DOP853, rtol 1e-12) on the law's own post mechanisms, packed as returned, at
    the law's post_rate; the step pulse is piecewise constant between its breakpoints."""
    mech = hinges_of(arch)
    packed = pack_mechanism(mech)
    bps = [b for b in sorted(float(x) for x in motion.breakpoints()) if b > 0.0] + [30.0]
    t, phi, v = 0.0, 0.0, 0.0
    times, hinges = [], []
    while len(times) < n:
        right = next(b for b in bps if b > t + 1e-15)
        a = float(motion.acceleration(0.5 * (t + right)))

        def closure(tt, y):
            return y[0]
        closure.terminal, closure.direction = True, -1
        sol = solve_ivp(lambda tt, y, p=packed, a=a: [y[1], acceleration(p, y[0], y[1], a, G)],
                        (t, right), [phi, v], method="DOP853", rtol=1e-12, atol=1e-14,
                        events=closure)
        if sol.status == 1:
            t = float(sol.t_events[0][0])
            closing = float(sol.y_events[0][0][1])
            imp = chain_impact(mech)
            mech = imp.post
            packed = pack_mechanism(mech)  # its own phi, whatever its load direction
            phi, v = 0.0, imp.post_rate * abs(closing)
            times.append(t)
            hinges.append(" ".join(f"{j}{f.value[0]}" for j, f in zip(mech.joints, mech.faces)))
        else:
            t, phi, v = right, float(sol.y[0, -1]), float(sol.y[1, -1])
    return np.array(times), hinges


@pytest.mark.parametrize("arch, a, tp", [(OPPENHEIM, 1.0, 0.20), (SEMICIRCLE, 0.15, 0.10)])
def test_first_impacts_agree_with_solve_ivp_on_the_laws_mechanisms(arch, a, tp):
    motion = StepImpulse.from_g(a, tp)
    r = simulate(arch, motion, impact="chain", options=SolverOptions(output_interval=0.0))
    n = min(4, r.impact_times.size)
    assert n >= 2
    times, hinges = _oracle_impacts(arch, motion, n)
    assert np.allclose(r.impact_times[:n], times, rtol=0, atol=1e-6)
    assert [e.hinges for e in r.mechanisms if e.kind != "onset"][:n] == hinges


def test_per_impact_validity_decides_the_verdict():
    """Semicircle n = 15: the first mechanism's impact is 'outside' (the law's own validity),
    so a verdict after it is indeterminate; a collapse in half cycle 1 stands."""
    prep = PreparedMechanism.build(SEMICIRCLE, "chain")
    assert prep.table.validity[0] == "outside"
    r = simulate(prep, StepImpulse.from_g(0.15, 0.10))
    assert r.mechanisms[1].validity == "outside" and not r.mechanisms[1].described
    assert r.outcome is Outcome.INDETERMINATE
    first = simulate(prep, StepImpulse.from_g(0.15, 0.30))
    assert first.outcome is Outcome.COLLAPSE and first.collapse_half_cycle == 1


def test_an_impact_beyond_the_table_stops_the_history_flagged():
    """The table capped at 3 rows (semicircle n = 16: 8 reachable): the impact whose post
    mechanism would be the 4th is recorded 'unresolved' (beyond_set), the history stops there and
    the verdict is indeterminate; up to it the history is the full table's."""
    from archquake.mechanism.prepared import impact_table
    from archquake.mechanism.simulate import FinalState

    arch = Arch(5.0, 0.6, math.pi, 16)
    full = PreparedMechanism.build(arch, "chain")
    capped = PreparedMechanism.build(arch, "chain")
    capped.__dict__["table"] = impact_table(capped, cap=3)  # the cached property, capped
    assert full.table.size == 8 and capped.table.size == 3 and not capped.follows_law
    motion = StepImpulse.from_g(0.15, 0.15)
    r_full = simulate(full, motion)
    r = simulate(capped, motion)
    assert not r.impact_followed and r.final_state is FinalState.UNRESOLVED
    last = r.mechanisms[-1]
    assert last.kind == "unresolved" and last.validity == "beyond_set" and not last.described
    assert r.outcome is Outcome.INDETERMINATE and r.computed_outcome is Outcome.SURVIVES
    n = r.impact_times.size
    assert 1 <= n < r_full.impact_times.size
    assert np.array_equal(r.impact_times, r_full.impact_times[:n])


def test_prescribed_restitution_keeps_the_laws_mechanisms():
    """restitution = 0.9 under the chain law: the same mechanisms as the law's, and every impact
    keeps exactly 0.81 of the kinetic energy (1e-12)."""
    prep = PreparedMechanism.build(OPPENHEIM, "chain")
    law = simulate(prep, StepImpulse.from_g(1.0, 0.20))
    r = simulate(prep, StepImpulse.from_g(1.0, 0.20), restitution=0.9)
    assert r.restitution_prescribed and r.impact_times.size >= 2
    meff = prep.table.meff0()
    rows = [e.row for e in r.mechanisms if e.kind == "impact"]
    assert rows[:2] == [1, 1]
    pre = 0
    for row, (before, after) in zip(rows, r.impact_rates):
        ratio = (meff[row] * after**2) / (meff[pre] * before**2)
        assert ratio == pytest.approx(0.81, rel=1e-12)
        pre = row
    assert [e.hinges for e in r.mechanisms[:3]] == [e.hinges for e in law.mechanisms[:3]]


def test_run_plot_and_animation_under_the_chain_law(tmp_path, capsys):
    """archquake run --impact chain prints the sequence of mechanisms; the plot labels the
    impacts and the animation draws the open row."""
    from archquake.cli.main import main
    from archquake.plotting.history import animate_history

    plot, gif = tmp_path / "r.png", tmp_path / "r.gif"
    assert main(["run", "--model", "fourlink", "--pulse", "step", "--magnitude", "1.0",
                 "--duration", "0.20", "--impact", "chain", "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    assert "impact     0e 2i 5e 7i (near_four_hinge)" in out
    assert plot.stat().st_size > 10_000
    prep = PreparedMechanism.build(OPPENHEIM, "chain")
    r = simulate(prep, StepImpulse.from_g(1.0, 0.20))
    assert set(np.unique(r.history.mechanism_row)) == {0, 1}
    animate_history(prep, r, gif, frames=6, t_end=2.0)  # frames on rows 0 and 1
    assert gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
