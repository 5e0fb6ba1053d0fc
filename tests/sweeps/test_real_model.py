"""The default case function runs the real four-link model.

Oracles: (1) simulate called directly on the same arch and motion (the sweep's memoised
mechanism and history-free solver options must not change a number); (2) dimensional
analysis: for geometrically similar arches the outcome depends only on a/g and
t_p / sqrt(R/g), so R = 1 m with t_p = 0.1 s and R = 4 m with t_p = 0.2 s must agree, with
every time doubled. Tolerance 1e-6 relative on times: the integrator runs at rtol 1e-9 and
locates events to that order, far inside 1e-6.
"""

from __future__ import annotations

import pytest

from archquake.sweeps import ArchSpec, Case, ExcitationSpec, ResultStore, evaluate_case, run_sweep
from archquake.sweeps.study import parse_study

mechanism = pytest.importorskip("archquake.mechanism")
if not hasattr(mechanism, "simulate"):
    pytest.skip("archquake.mechanism.simulate is not in this build", allow_module_level=True)


def test_evaluate_case_is_simulate():
    case = Case(ArchSpec(10, 0.15, 157.5, 7), ExcitationSpec("step", magnitude_g=1.0,
                                                             duration_s=0.27), "fourlink")
    direct = mechanism.simulate(case.arch.build(), case.excitation.build()).to_dict()
    assert evaluate_case(case) == direct
    # the paper's Figure 4c: Oppenheim's arch collapses after its first impact (at 0.86 s)
    assert direct["outcome"] == "collapse" and direct["collapse_half_cycle"] == 2


def test_sweep_obeys_dimensional_scaling(tmp_path):
    study = parse_study({
        "study": {"name": "scaling", "model": "fourlink"},  # exactly similar (no fixed step)
        "arches": {"radius": [1, 4], "thickness_ratio": 0.15, "embrace_deg": 157.5,
                   "voussoirs": 7},
        "excitation": {"type": "step", "magnitude_g": {"start": 0.4, "stop": 1.6, "num": 7},
                       "duration_s": [0.1, 0.2]},
    })
    with ResultStore(tmp_path / "s.sqlite") as store:
        report = run_sweep(study.cases, store, workers=2)  # default: real model, process pool
        rows = store.rows(flatten_outputs=False)
    assert report.computed == 28
    import json

    out = {(r["radius_m"], r["duration_s"], r["magnitude_g"]): json.loads(r["outputs_json"])
           for r in rows}
    outcomes = set()
    for a in [0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6]:
        small, large = out[(1.0, 0.1, a)], out[(4.0, 0.2, a)]
        outcomes.add(small["outcome"])
        assert small["outcome"] == large["outcome"]
        assert small["collapse_half_cycle"] == large["collapse_half_cycle"]
        assert len(small["impact_times_s"]) == len(large["impact_times_s"])
        for ts, tl in zip(small["impact_times_s"], large["impact_times_s"], strict=True):
            assert tl == pytest.approx(2.0 * ts, rel=1e-6)
        assert large["peak_rotation_rad"] == pytest.approx(small["peak_rotation_rad"], rel=1e-6)
    assert len(outcomes) >= 2  # the range spans more than one regime, so the check has teeth
