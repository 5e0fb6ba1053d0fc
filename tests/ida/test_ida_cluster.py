"""IDA on a real Dask cluster (loopback scheduler and two workers, the fixture of
tests/sweeps/test_cluster.py) gives the serial run's result: the rounds go through the same
executors as a sweep, and the records travel with the cases (no files on the workers).

Marked slow: starting the cluster and loading the compiled kernels in two fresh workers takes
15-40 s on a shared 2-core machine; the same runner's cluster path is tested quickly by
tests/sweeps/test_cluster.py."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

pytest.importorskip("distributed")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "sweeps"))

from ida_inputs import OPPENHEIM  # noqa: E402
from test_cluster import cluster  # noqa: E402, F401  (the fixture)

from archquake.ida import incremental_dynamic_analysis  # noqa: E402
from archquake.parallel import (
    SerialExecutor,  # noqa: E402
    open_executor,  # noqa: E402
)
from archquake.sweeps import ResultStore  # noqa: E402


@pytest.mark.slow
def test_ida_on_a_dask_cluster_equals_the_serial_run(tmp_path, cluster, records):  # noqa: F811
    address = cluster.address
    kwargs = dict(ceiling=3.0, precision=0.05, fill=0.3)
    with ResultStore(tmp_path / "serial.sqlite") as store:
        serial = incremental_dynamic_analysis(OPPENHEIM, records[:2], "pga", store, model="fourlink",
                                              executor=SerialExecutor(), **kwargs)
    with ResultStore(tmp_path / "dask.sqlite") as store, \
            open_executor(scheduler=address) as (executor, n):
        on_dask = incremental_dynamic_analysis(OPPENHEIM, records[:2], "pga", store, model="fourlink",
                                               executor=executor, workers=n, chunk_size=3,
                                               **kwargs)
    assert on_dask.computed == serial.total
    assert on_dask.to_dict()["records"] == serial.to_dict()["records"]
