"""A small parameter sweep through the Python API, stored in a temporary SQLite store.

    python examples/sweep.py            # 3 radii x 12 magnitudes x 2 durations
    python examples/sweep.py --quick    # 2 radii x 2 magnitudes x 1 duration

Every case runs the default model, the chain of rigid voussoirs (~0.2-1 s a case);
``Case(..., model="fourlink")`` runs the paper's four-link mechanism instead (~1 ms a case).

The same study as a TOML file is examples/sweep_scale.toml (``archquake sweep``); on a Dask
cluster, pass ``executor=client.get_executor()`` to run_sweep (docs/sweeps.md).
"""

from __future__ import annotations

import argparse
import tempfile
from collections import Counter
from pathlib import Path

import numpy as np

from archquake.parallel import SerialExecutor
from archquake.sweeps import ArchSpec, Case, ExcitationSpec, ResultStore, run_sweep


def main(quick: bool = False) -> None:
    radii = (5.0, 10.0) if quick else (1.0, 10.0, 20.0)
    magnitudes = np.linspace(0.3, 1.5, 2 if quick else 12)
    durations = (0.3,) if quick else (0.25, 0.5)
    cases = [Case(ArchSpec(r, 0.15, 157.5, 7), ExcitationSpec("step", magnitude_g=float(a), duration_s=tp))
             for r in radii for tp in durations for a in magnitudes]
    with tempfile.TemporaryDirectory() as tmp, ResultStore(Path(tmp) / "sweep.sqlite") as store:
        report = run_sweep(cases, store, executor=SerialExecutor())
        print(f"{report.total} cases, {report.computed} computed; outcomes {report.outcomes}")
        again = run_sweep(cases, store, executor=SerialExecutor())  # resumable: nothing left to do
        print(f"rerun: {again.computed} computed, {again.already_stored} already stored")
        by_radius = Counter()
        for row in store.rows():
            if row["outcome"] == "collapse":
                by_radius[row["radius_m"]] += 1
        for r in radii:
            print(f"R = {r:4g} m: {by_radius[r]} of {len(magnitudes) * len(durations)} pulses collapse it")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="4 cases instead of 72")
    main(parser.parse_args().quick)
