"""A real accelerogram end to end: the same record read from AT2 and from CSV drives the arch
identically (oracle: the two readers must produce the same samples, so the responses must be
bit-identical), and both mirror images of a record can start either mechanism."""

from __future__ import annotations

import math
from importlib import resources

import numpy as np
import pytest

from archquake.constants import STANDARD_GRAVITY
from archquake.geometry import Arch
from archquake.ground.records import read_at2, read_csv
from archquake.mechanism import Outcome, PreparedMechanism, simulate


def _northridge_csv():
    return resources.files("pyslammer") / "sample_ground_motions" / "Northridge_1994_PAC-175.csv"


def _write_at2(path, record_g: np.ndarray, dt: float) -> None:
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD",
             "NORTHRIDGE 01/17/94, PACOIMA DAM, 175 (copied for a test)",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {record_g.size:6d}, DT= {dt:.4f} SEC"]
    for i in range(0, record_g.size, 5):
        lines.append("".join(f"{v:15.7E}" for v in record_g[i:i + 5]))
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture(scope="module")
def small_arch():
    # a 1 m arch of Oppenheim's proportions: short rocking periods, so the record's pulses matter
    return PreparedMechanism.build(Arch(1.0, 0.15, math.radians(157.5), 7))


def test_same_record_from_at2_and_csv_gives_the_same_response(tmp_path, small_arch):
    with resources.as_file(_northridge_csv()) as csv_path:
        from_csv = read_csv(csv_path, units="g", scale=1.5)
        raw = read_csv(csv_path, units="g")
    at2 = tmp_path / "PAC175.AT2"
    _write_at2(at2, raw.accelerations / STANDARD_GRAVITY, raw.dt)
    from_at2 = read_at2(at2, scale=1.5)
    np.testing.assert_allclose(from_at2.kernel_spec()[1], from_csv.kernel_spec()[1], rtol=1e-7, atol=1e-9)
    a = simulate(small_arch, from_csv)
    b = simulate(small_arch, from_at2)
    assert a.outcome is not Outcome.NO_HINGING  # 1.5 x 0.415 g > 0.37 g: the record rocks the arch
    assert a.outcome is b.outcome and a.collapse_half_cycle == b.collapse_half_cycle
    np.testing.assert_allclose(a.impact_times, b.impact_times, atol=1e-5)


def test_a_record_can_start_either_mechanism(small_arch):
    with resources.as_file(_northridge_csv()) as csv_path:
        rec = read_csv(csv_path, units="g", scale=1.5)
    first = simulate(small_arch, rec).history
    mirror = simulate(small_arch, rec.mirrored()).history
    s1 = first.side[first.side != 0][0]
    s2 = mirror.side[mirror.side != 0][0]
    assert s1 == -s2
