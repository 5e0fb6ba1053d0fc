"""IDA on the FEMA P695 near-field pulse set (needs the records extra; skipped without it).

The quick test runs 3 components; the slow one the whole set and holds the numbers published in
docs/earthquakes.md (the computation is deterministic: same kernel, same levels, same seed)."""

from __future__ import annotations

import numpy as np
import pytest
from ida_inputs import OPPENHEIM

from archquake.ida import incremental_dynamic_analysis
from archquake.ida.fragility import dispersion_by_im, fragility_of
from archquake.parallel import SerialExecutor
from archquake.sweeps import ResultStore

suites = pytest.importorskip("archquake.ground.suites")
if not suites.fema_available():
    pytest.skip("the FEMA P695 records are not installed", allow_module_level=True)


def _ida(tmp_path, records):
    with ResultStore(tmp_path / "nf.sqlite") as store:
        return incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", ceiling=5.0,
                                            precision=0.02, fill=0.10, executor=SerialExecutor())


def test_three_near_field_components(tmp_path):
    records = suites.load_suite("near-field-pulse").records
    res = _ida(tmp_path, records[:3])
    first = res.first_collapse_levels
    # docs/earthquakes.md: IMPVALL-H-E06_233, E06_323, E07_233 first collapse at 0.731, 0.787,
    # 0.577 g, each with one resurrection
    np.testing.assert_allclose(first, [0.7308, 0.7872, 0.5771], rtol=2e-4)
    assert [len(r.resurrections) for r in res.records] == [1, 1, 1]
    assert all(r.first_collapse.low / r.first_collapse.below - 1 <= 0.02 for r in res.records)


@pytest.mark.slow
def test_whole_near_field_pulse_set_as_documented(tmp_path):
    res = _ida(tmp_path, suites.load_suite("near-field-pulse").records)
    assert res.total == 1246
    assert sum(1 for r in res.records if r.resurrections) == 19
    fits = fragility_of(res, rng=np.random.default_rng(0), bootstrap=500)
    assert fits["first_collapse"].median == pytest.approx(0.8668, rel=2e-4)
    assert fits["first_collapse"].beta == pytest.approx(0.428, abs=6e-4)
    assert fits["collapse_fraction"].median == pytest.approx(0.984, rel=1e-3)
    assert fits["collapse_fraction"].beta == pytest.approx(0.535, abs=6e-4)
    best = min(dispersion_by_im(res, ["pga", "pgv", "sa:1.0"]), key=lambda r: r["beta"])
    assert best["im"] == "pgv" and best["beta"] == pytest.approx(0.269, abs=6e-4)
