"""Blocks from surveyed files (JSON, CSV, DXF): the same arch written out and read back.

Oracle: the builder's own chain. Its blocks, written to a file in shuffled order (and a block
given clockwise), must be read back into the same chain (joints, masses to 1e-12) with the same
lambda and hinges; bad files are one line naming the file.
"""

import csv
import json
import math

import numpy as np
import pytest

from archquake.errors import InvalidParameterError
from archquake.geometry import Arch, pointed
from archquake.geometry.survey import chain_from_polygons, read_blocks
from archquake.limit import limit_analysis

REFERENCE = pointed(span=10.0, rise=7.0, thickness=0.8, voussoirs=9)


def _blocks(chain, shuffle=True):
    polys = [p.tolist() for p in chain.block_polygons]
    polys[2] = polys[2][::-1]  # clockwise: reoriented on reading
    if shuffle:
        order = [4, 0, 8, 2, 6, 1, 7, 3, 5]
        polys = [polys[k] for k in order]
    return polys


def _same(chain, ref):
    np.testing.assert_allclose(chain.intrados_points, ref.intrados_points, atol=1e-12)
    np.testing.assert_allclose(chain.extrados_points, ref.extrados_points, atol=1e-12)
    np.testing.assert_allclose(chain.voussoir_masses, ref.voussoir_masses, rtol=1e-12)
    a, b = limit_analysis(chain, method="both"), limit_analysis(ref, method="both")
    assert a.collapse_acceleration_g == pytest.approx(b.collapse_acceleration_g, rel=1e-10)
    assert a.mechanism.joints == b.mechanism.joints


def test_json_round_trip(tmp_path):
    path = tmp_path / "arch.json"
    path.write_text(json.dumps({"blocks": _blocks(REFERENCE)}))
    _same(read_blocks(path), REFERENCE)


def test_csv_round_trip(tmp_path):
    path = tmp_path / "arch.csv"
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["block", "x", "y"])
        for k, poly in enumerate(_blocks(REFERENCE)):
            for x, y in poly:
                w.writerow([f"b{k}", repr(x), repr(y)])
    _same(read_blocks(path), REFERENCE)


def test_dxf_round_trip(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    msp = doc.modelspace()
    for poly in _blocks(Arch(5.0, 0.6, math.pi, 9)):
        msp.add_lwpolyline(poly, close=True)
    path = tmp_path / "arch.dxf"
    doc.saveas(path)
    chain = read_blocks(path)
    ref = Arch(5.0, 0.6, math.pi, 9)
    # the DXF holds the sampled outlines: lambda equals the closed form's to their sampling
    assert limit_analysis(chain).collapse_acceleration_g == pytest.approx(
        limit_analysis(ref).collapse_acceleration_g, rel=1e-6)
    np.testing.assert_allclose(chain.intrados_points, ref.intrados_points, atol=1e-9)


def test_bad_files_are_one_line(tmp_path):
    polys = _blocks(REFERENCE, shuffle=False)
    overlap = [list(p) for p in polys]
    overlap[4] = [[x + 0.05, y] for x, y in overlap[4]]
    bad = tmp_path / "overlap.json"
    bad.write_text(json.dumps(overlap))
    with pytest.raises(InvalidParameterError, match=r"--blocks .*overlap.json: "):
        read_blocks(bad)
    gap = tmp_path / "gap.json"
    gap.write_text(json.dumps([p for k, p in enumerate(polys) if k != 4]))
    with pytest.raises(InvalidParameterError, match="one chain|gap"):
        read_blocks(gap)
    two = tmp_path / "two.json"
    two.write_text(json.dumps(polys[:2]))
    with pytest.raises(InvalidParameterError, match="at least 3 blocks"):
        read_blocks(two)
    garbage = tmp_path / "x.json"
    garbage.write_text("{nope")
    with pytest.raises(InvalidParameterError, match="not valid JSON"):
        read_blocks(garbage)


def test_open_dxf_polyline_is_refused(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=False)
    path = tmp_path / "open.dxf"
    doc.saveas(path)
    with pytest.raises(InvalidParameterError, match="is not closed"):
        read_blocks(path)


def test_joints_are_found_without_every_pair_of_vertices(monkeypatch):
    """The reader's cost bounded by a count, as solve_ivp's by nfev: the survey's 9 blocks of
    about 2,000 vertices each are 36 pairs of blocks, 1.4e8 vertex-to-vertex distances in all;
    only the vertices within reach of another block (its bounding box grown by the tolerance) are
    compared, and the chain read is the same (oracle: the builder's own, as above). Counted:
    the distances np.hypot is given."""
    taken = []
    hypot = np.hypot
    monkeypatch.setattr(np, "hypot", lambda *a: taken.append(np.broadcast(*a).size) or hypot(*a))
    polys = [np.asarray(p) for p in _blocks(REFERENCE)]
    every = sum(len(p) * len(q) for k, p in enumerate(polys) for q in polys[k + 1:])
    chain = chain_from_polygons(_blocks(REFERENCE))
    monkeypatch.undo()
    _same(chain, REFERENCE)
    assert sum(taken) < 0.01 * every
