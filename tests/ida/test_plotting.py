"""IDA figures: take an optional ax and return it, write files, never pick a backend at import."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from ida_inputs import OPPENHEIM

from archquake.ida import incremental_dynamic_analysis
from archquake.ida.fragility import fragility_of
from archquake.parallel import SerialExecutor
from archquake.sweeps import ResultStore


@pytest.fixture(scope="module")
def result(tmp_path_factory, records):
    with ResultStore(tmp_path_factory.mktemp("plot") / "p.sqlite") as store:
        return incremental_dynamic_analysis(OPPENHEIM, records, "pga", store, model="fourlink", ceiling=4.0,
                                            precision=0.05, fill=0.2, executor=SerialExecutor())


def test_plots_use_the_given_axes_and_save(result, tmp_path):
    from matplotlib.figure import Figure

    from archquake.plotting.ida import plot_fragility, plot_ida_curves, save_ida

    fits = fragility_of(result, rng=np.random.default_rng(0), bootstrap=20)
    ax1, ax2 = Figure().subplots(1, 2)
    assert plot_ida_curves(result, ax1) is ax1
    assert plot_fragility(result, fits, ax2) is ax2
    # one line per record in the IDA panel, the data points and fits in the fragility panel
    assert len([ln for ln in ax1.lines if ln.get_linestyle() == "-"]) == len(result.records)
    assert any(np.allclose(ln.get_ydata(), fits["fraction"]) for ln in ax2.lines)
    path = save_ida(result, fits, tmp_path / "ida.png")
    assert path.stat().st_size > 10_000


def test_importing_the_module_does_not_choose_a_backend():
    code = ("import matplotlib; before = matplotlib.get_backend(); "
            "import archquake.plotting.ida; "
            "assert matplotlib.rcParams._get_backend_or_none() in (None, before)")
    subprocess.run([sys.executable, "-c", code], check=True)
