"""restitution= and impact= in every API function that runs a history, and the honest verdict.

Oracles: the one time-history driver (:func:`archquake.mechanism.simulate`) with the same law and
c_v (every other function must reproduce its outcome exactly: discrete results, exact equality);
the impact laws' own c_v (:func:`archquake.mechanism.impact.solve_impact`); the rule of
:func:`archquake.outcome.qualify` (a collapse in the first half cycle never depends on an impact).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.domains import DomainSettings, evaluate_pulses, failure_domain
from archquake.domains.batch import evaluate_pulses_scalar
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, simulate
from archquake.mechanism.impact import check_restitution, solve_impact
from archquake.outcome import Outcome, qualify

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
#: The semicircular bridge arch of issue 10: Eq. 4 gives c_v = 49.9 (energy gain).
BRIDGE = Arch(5.0, 0.6, math.pi, 15)


# ----------------------------------------------------------------------------- restitution
@pytest.mark.parametrize("bad", [-0.01, 1.5, math.nan])
def test_simulate_refuses_restitution_outside_0_1(bad):
    with pytest.raises(InvalidParameterError, match=r"^restitution must be .*\[0, 1\]"):
        simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.27), restitution=bad)


def test_restitution_check_names_the_option_and_accepts_the_ends():
    assert check_restitution(0) == 0.0 and check_restitution(1) == 1.0
    assert check_restitution(None) is None
    with pytest.raises(InvalidParameterError, match=r"^--restitution must be in \[0, 1\]"):
        check_restitution(2, "--restitution")


def test_perfectly_plastic_stops_the_arch_at_the_first_impact():
    r = simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.2), restitution=0.0)
    assert r.impact_times.size == 1 and r.final_state.value == "rest"
    assert r.outcome is Outcome.SURVIVES and r.restitution_cv == 0.0


@pytest.mark.parametrize("impact,restitution", [("paper", None), ("chain", None), ("paper", 0.5),
                                                ("mirror", 0.9)])
def test_domain_batch_uses_the_chosen_law_and_restitution(impact, restitution):
    """The compiled batch, its scalar twin and simulate agree case by case under each law."""
    a = np.array([0.5, 0.8, 1.0, 1.0, 1.0, 1.3])
    d = np.array([0.25, 0.25, 0.2, 0.27, 0.44, 0.3])
    fast = evaluate_pulses(OPPENHEIM, "step", a, d, restitution=restitution, impact=impact)
    slow = evaluate_pulses_scalar(OPPENHEIM, "step", a, d, restitution=restitution, impact=impact)
    np.testing.assert_array_equal(fast.outcome, slow.outcome)
    np.testing.assert_array_equal(fast.collapse_half_cycle, slow.collapse_half_cycle)
    for i in range(a.size):
        r = simulate(OPPENHEIM, StepImpulse.from_g(a[i], d[i]), restitution=restitution,
                     impact=impact)
        assert r.outcome is fast.outcome[i]
        assert r.impact_law == impact
        if restitution is None:
            assert r.restitution_cv == pytest.approx(
                max(solve_impact(PreparedMechanism.build(OPPENHEIM).mechanism,
                                 impact).restitution_cv, 0.0), rel=1e-12)


def test_laws_differ_where_the_paper_says_collapse():
    """Figure 4c (1.0 g, 0.27 s): Eq. 4 (c_v 0.875) collapses in half cycle 2; the chain law
    (c_v 0.746) survives (docs/notes/mechanism.md table). So the batch must not take Eq. 4's c_v."""
    r = evaluate_pulses(OPPENHEIM, "step", [1.0, 1.0], [0.27, 0.27])
    c = evaluate_pulses(OPPENHEIM, "step", [1.0, 1.0], [0.27, 0.27], impact="chain")
    assert r.outcome.tolist() == [Outcome.COLLAPSE] * 2
    assert c.outcome.tolist() == [Outcome.SURVIVES] * 2


def test_failure_domain_takes_restitution_and_impact():
    s = DomainSettings(coarse_points=12, fine_points=4)
    paper = failure_domain(OPPENHEIM, "step", [0.27], settings=s, model="fourlink")
    chain = failure_domain(OPPENHEIM, "step", [0.27], settings=s, impact="chain", model="fourlink")
    plastic = failure_domain(OPPENHEIM, "step", [0.27], settings=s, restitution=0.0,
                             model="fourlink")
    assert paper.impact_law == "paper" and chain.impact_law == "chain"
    assert chain.restitution_cv == pytest.approx(0.7461, abs=1e-4)
    assert plastic.restitution_cv == 0.0 and plastic.restitution_prescribed
    # less restitution cannot lower the governing boundary (the second half cycle starts slower)
    assert plastic.collapse_g[0] >= chain.collapse_g[0] >= paper.collapse_g[0]
    # plastic: nothing after the first impact, so the governing boundary is the first half cycle's
    assert plastic.collapse_half_cycle[0] == 1
    assert plastic.collapse_g[0] == pytest.approx(plastic.first_half_cycle_g[0], abs=2e-3)
    for d in (paper, chain, plastic):
        assert d.impact_described and d.collapse_verdict == ("collapse",)
        assert d.summary()["impact_law"] == d.impact_law


def test_prepared_mechanism_takes_another_law_without_repacking():
    p = PreparedMechanism.build(OPPENHEIM)
    c = PreparedMechanism.build(p, "chain")
    assert c.packed is p.packed and c.impact.law == "chain" and p.impact.law == "paper"
    assert PreparedMechanism.build(c) is c and PreparedMechanism.build(c, "chain") is c
    with pytest.raises(InvalidParameterError, match="impact must be one of paper, chain, mirror"):
        PreparedMechanism.build(p, "elastic")


def test_thrust_states_and_friction_follow_the_law():
    from archquake.thrust import states
    from archquake.thrust.friction import friction_demand

    motion = StepImpulse.from_g(1.0, 0.27)
    chain = simulate(OPPENHEIM, motion, impact="chain")
    t = float(chain.impact_times[0]) + 0.3  # after the first impact: the laws' rates differ
    s_paper = states(OPPENHEIM, motion, [t])[0]
    s_chain = states(OPPENHEIM, motion, [t], impact="chain")[0]
    ref = simulate(OPPENHEIM, motion, impact="chain", t_eval=[t]).evaluated
    assert s_chain.configuration.phi == pytest.approx(float(ref.phi[0]), rel=1e-12)
    assert abs(s_paper.configuration.phi - s_chain.configuration.phi) > 1e-4
    fd = friction_demand(OPPENHEIM, StepImpulse.from_g(0.5, 0.27), restitution=0.0)
    fd_ref = friction_demand(OPPENHEIM, StepImpulse.from_g(0.5, 0.27),
                             result=simulate(OPPENHEIM, StepImpulse.from_g(0.5, 0.27),
                                             restitution=0.0))
    assert fd.max_friction_demand == fd_ref.max_friction_demand


# ----------------------------------------------------------------------------- sweeps and IDA
def test_case_options_take_impact_without_changing_existing_ids():
    from archquake.sweeps import ArchSpec, Case, CaseOptions, ExcitationSpec

    arch = ArchSpec(10, 0.15, 157.5, 7)
    exc = ExcitationSpec("step", magnitude_g=1.0, duration_s=0.27)
    base = Case(arch, exc, "fourlink")
    assert Case(arch, exc, "fourlink", CaseOptions(impact="paper")).case_id == base.case_id
    chain = Case(arch, exc, "fourlink", CaseOptions(impact="chain"))
    assert chain.case_id != base.case_id
    assert CaseOptions(restitution=0).restitution == 0.0
    with pytest.raises(InvalidParameterError, match="restitution"):
        CaseOptions(restitution=1.2)
    with pytest.raises(InvalidParameterError, match="impact"):
        CaseOptions(impact="mirrored")
    from archquake.sweeps import evaluate_case

    out = evaluate_case(chain)
    assert out["impact_law"] == "chain" and out["outcome"] == "survives"
    assert evaluate_case(base)["outcome"] == "collapse"


def test_study_file_options_impact(tmp_path):
    from archquake.errors import StudyFileError
    from archquake.sweeps import load_study

    text = """
[study]
name = "laws"
[arches]
radius = 10
thickness_ratio = 0.15
embrace_deg = 157.5
voussoirs = 7
[excitation]
type = "step"
magnitude_g = 1.0
duration_s = 0.27
[options]
restitution = [0, 0.5]
impact = {impact}
"""
    path = tmp_path / "s.toml"
    path.write_text(text.replace("{impact}", '["paper", "chain"]'))
    study = load_study(path)
    assert {(c.options.restitution, c.options.impact) for c in study.cases} == {
        (0.0, "paper"), (0.5, "paper"), (0.0, "chain"), (0.5, "chain")}
    path.write_text(text.replace("{impact}", '"elastic"'))
    with pytest.raises(StudyFileError, match="options.impact"):
        load_study(path)


def test_ida_batch_reports_the_law_and_qualifies_verdicts():
    from archquake.ida.batch import evaluate_cases
    from archquake.sweeps import ArchSpec, Case, CaseOptions, ExcitationSpec

    bridge = ArchSpec(5.0, 0.12, 180.0, 15)
    cases = [Case(bridge, ExcitationSpec("step", magnitude_g=0.15, duration_s=tp), "fourlink",
                  CaseOptions(impact="paper")) for tp in (0.1, 0.3)]
    out = evaluate_cases(cases)
    assert [o["impact_law"] for o in out] == ["paper", "paper"]
    assert [o["outcome"] for o in out] == ["indeterminate", "collapse"]
    assert [o["computed_outcome"] for o in out] == ["collapse", "collapse"]


# ----------------------------------------------------------------------------- the verdict
def test_qualify_rule():
    q = qualify
    assert q(Outcome.COLLAPSE, collapse_half_cycle=1, impacts=0, impact_described=False) \
        is Outcome.COLLAPSE
    assert q(Outcome.COLLAPSE, collapse_half_cycle=3, impacts=2, impact_described=False) \
        is Outcome.INDETERMINATE
    assert q(Outcome.SURVIVES, collapse_half_cycle=None, impacts=1, impact_described=False) \
        is Outcome.INDETERMINATE
    assert q(Outcome.SURVIVES, collapse_half_cycle=None, impacts=0, impact_described=False) \
        is Outcome.SURVIVES
    assert q(Outcome.NO_HINGING, collapse_half_cycle=None, impacts=0, impact_described=False) \
        is Outcome.NO_HINGING
    for o in (Outcome.COLLAPSE, Outcome.SURVIVES):
        assert q(o, collapse_half_cycle=2, impacts=1, impact_described=True) is o


def test_bridge_arch_under_eq4_is_never_a_certain_verdict_after_an_impact():
    """Issue 10's semicircle (c_v = 49.9 under Eq. 4): every pulse whose verdict comes after an
    impact is indeterminate; a collapse before any impact stays a collapse."""
    prep = PreparedMechanism.build(BRIDGE, "paper")
    assert prep.impact.energy_gain and not prep.describes_impact()
    seen = set()
    for a_g, tp in [(0.06, 0.2), (0.1, 0.1), (0.15, 0.15), (0.15, 0.3), (0.04, 0.2)]:
        r = simulate(prep, StepImpulse.from_g(a_g, tp))
        seen.add(r.outcome)
        d = r.to_dict()
        assert d["impact_validity"] == "outside" and d["impact_described"] is False
        if r.impact_times.size and r.computed_outcome is not Outcome.NO_HINGING:
            if r.computed_outcome is Outcome.COLLAPSE and r.collapse_half_cycle == 1:
                assert r.outcome is Outcome.COLLAPSE
            else:
                assert r.outcome is Outcome.INDETERMINATE
                assert d["outcome"] == "indeterminate"
        else:
            assert r.outcome is r.computed_outcome
    assert {Outcome.INDETERMINATE, Outcome.COLLAPSE, Outcome.NO_HINGING} <= seen
    # a prescribed c_v in [0, 1] replaces Eq. 4's number: the verdict is stated again
    r = simulate(prep, StepImpulse.from_g(0.15, 0.15), restitution=0.7)
    assert r.impact_described and r.outcome in (Outcome.COLLAPSE, Outcome.SURVIVES)


def test_oppenheim_under_eq4_keeps_figure4():
    """c_v = 0.875 (valid): the paper's three outcomes, all stated as certain."""
    got = []
    for tp in (0.44, 0.27, 0.20):
        r = simulate(OPPENHEIM, StepImpulse.from_g(1.0, tp))
        assert r.impact_described and r.impact_validity == "assumed"
        got.append((r.outcome.value, r.collapse_half_cycle))
    assert got == [("collapse", 1), ("collapse", 2), ("survives", None)]


# ----------------------------------------------------------------------------- plots
def test_plots_say_indeterminate(tmp_path):
    """The domain figure hatches the indeterminate region and the history title names the law's
    validity (read back from the figure's artists, not from pixels)."""
    import matplotlib.pyplot as plt

    from archquake.plotting.domains import plot_domain
    from archquake.plotting.history import verdict_text

    s = DomainSettings(coarse_points=8, fine_points=2, precision_g=0.01)
    dom = failure_domain(BRIDGE, "step", [0.15, 0.3], settings=s, impact="paper", model="fourlink")
    assert not dom.impact_described
    assert dom.collapse_verdict == ("indeterminate", "indeterminate")
    ax = plot_domain(dom)
    labels = [h.get_label() for h in ax.get_legend_handles_labels()[0]]
    assert any(lab.startswith("indeterminate: impact law paper outside") for lab in labels)
    plt.close(ax.figure)
    r = simulate(BRIDGE, StepImpulse.from_g(0.15, 0.1))
    assert verdict_text(r) == ("indeterminate (computed: collapse in half cycle 2); "
                               "impact paper: outside")
    r = simulate(OPPENHEIM, StepImpulse.from_g(1.0, 0.27))
    assert verdict_text(r) == "collapse in half cycle 2; impact paper: assumed"
