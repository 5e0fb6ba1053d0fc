"""Blocks of a surveyed arch from a file: JSON, CSV or DXF (through ezdxf, the optional extra
``archquake[dxf]``).

Formats (coordinates in m, x to the right, y up; any order of blocks and vertices):

- JSON: ``{"blocks": [[[x, y], [x, y], ...], ...]}`` (or just the list of blocks);
- CSV: a header ``block,x,y`` and one vertex a row, blocks told apart by their ``block`` label;
- DXF: every closed LWPOLYLINE or POLYLINE in modelspace is a block (drawing units = m).

The blocks must form one chain: consecutive blocks share a joint (an edge: two vertices in
common), the two end blocks stand on the supports on their lowest free edge, and no block
overlaps another (`check_tiling`). Anything else is one line
naming the file and what is wrong.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from archquake.errors import ArchquakeError, InvalidParameterError
from archquake.geometry.chain import BlockChain
from archquake.geometry.polygon import polygon_area, polygon_mass_properties


def read_blocks(path: str | Path, *, depth: float = 1.0, density: float = 2000.0) -> BlockChain:
    """Read the blocks of an arch from ``path`` (.json, .csv or .dxf) into a `BlockChain`.

    Raises
    ------
    InvalidParameterError
        One line naming the file: unreadable, not closed, fewer than 3 blocks, blocks that do
        not form a chain, or overlapping blocks.
    """
    path = Path(path)
    where = f"--blocks {path}"
    if not path.is_file():
        raise InvalidParameterError(f"{where}: no such file")
    suffix = path.suffix.lower()
    try:
        if suffix == ".json":
            polys = _read_json(path)
        elif suffix == ".csv":
            polys = _read_csv(path)
        elif suffix == ".dxf":
            polys = _read_dxf(path)
        else:
            raise InvalidParameterError("expected a .json, .csv or .dxf file")
        return chain_from_polygons(polys, depth=depth, density=density, name=f"blocks from {path.name}")
    except ArchquakeError as exc:
        raise InvalidParameterError(f"{where}: {exc}") from None


def _as_polygon(raw, label) -> np.ndarray:
    try:
        arr = np.array(raw, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"block {label} is not a list of [x, y] pairs") from None
    if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) < 3:
        raise InvalidParameterError(f"block {label} needs 3 or more [x, y] vertices")
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(f"block {label} has a non-finite coordinate")
    return arr


def _read_json(path: Path) -> list[np.ndarray]:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InvalidParameterError(f"not valid JSON ({exc})") from None
    blocks = data.get("blocks") if isinstance(data, dict) else data
    if not isinstance(blocks, list):
        raise InvalidParameterError('expected {"blocks": [[[x, y], ...], ...]}')
    return [_as_polygon(b, k) for k, b in enumerate(blocks)]


def _read_csv(path: Path) -> list[np.ndarray]:
    try:
        with path.open(newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    except UnicodeDecodeError:
        raise InvalidParameterError("not a UTF-8 text file") from None
    if not rows or not {"block", "x", "y"} <= set(rows[0]):
        raise InvalidParameterError("expected a header block,x,y and one vertex a row")
    order: dict[str, list] = {}
    for i, row in enumerate(rows, start=2):
        try:
            order.setdefault(row["block"], []).append([float(row["x"]), float(row["y"])])
        except (TypeError, ValueError):
            raise InvalidParameterError(f"line {i}: x and y must be numbers") from None
    return [_as_polygon(v, k) for k, v in order.items()]


def _read_dxf(path: Path) -> list[np.ndarray]:
    try:
        import ezdxf
    except ImportError:
        raise InvalidParameterError(
            "reading DXF needs ezdxf: pip install 'archquake[dxf]'") from None
    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError) as exc:
        raise InvalidParameterError(f"not a readable DXF file ({exc})") from None
    polys = []
    for k, e in enumerate(doc.modelspace().query("LWPOLYLINE POLYLINE")):
        if not e.closed:
            raise InvalidParameterError(f"polyline {k} ({e.dxftype()}) is not closed")
        if e.dxftype() == "LWPOLYLINE":
            pts = [(p[0], p[1]) for p in e.get_points("xy")]
        else:
            pts = [(v.dxf.location.x, v.dxf.location.y) for v in e.vertices]
        polys.append(_as_polygon(pts, k))
    if not polys:
        raise InvalidParameterError("no closed LWPOLYLINE or POLYLINE in modelspace")
    return polys


def chain_from_polygons(polygons, *, depth: float = 1.0, density: float = 2000.0,
                        name: str = "blocks") -> BlockChain:
    """Order the blocks along the chain and find its joints (see the module docstring)."""
    polys = []
    for k, p in enumerate(polygons):
        p = np.asarray(p, dtype=float)
        if np.allclose(p[0], p[-1]):
            p = p[:-1]
        area = polygon_area(p)
        if area == 0:
            raise InvalidParameterError(f"block {k} has zero area")
        polys.append(p if area > 0 else p[::-1])
    if len(polys) < 3:
        raise InvalidParameterError(f"an arch needs at least 3 blocks, got {len(polys)}")
    size = float(np.ptp(np.vstack(polys), axis=0).max())
    tol = 1e-6 * size
    nb = len(polys)
    shared: dict[tuple[int, int], np.ndarray] = {}
    # a vertex within tol of another block lies in that block's bounding box grown by tol: the
    # distances are taken between those vertices only (a surveyed block has thousands)
    box_low = [p.min(axis=0) - tol for p in polys]
    box_high = [p.max(axis=0) + tol for p in polys]
    for a in range(nb):
        for b in range(a + 1, nb):
            near_a = np.nonzero(np.all((polys[a] >= box_low[b]) & (polys[a] <= box_high[b]), axis=1))[0]
            near_b = np.all((polys[b] >= box_low[a]) & (polys[b] <= box_high[a]), axis=1)
            if len(near_a) < 2 or not near_b.any():
                continue
            d = np.hypot(*(polys[a][near_a, None, :] - polys[b][None, near_b, :])
                         .transpose(2, 0, 1))
            ia = near_a[np.nonzero(d.min(axis=1) <= tol)[0]]
            if len(ia) >= 2:
                pts = polys[a][ia]
                # the two extreme shared vertices are the joint's ends
                far = np.hypot(*(pts[:, None] - pts[None]).transpose(2, 0, 1))
                i, j = map(int, np.unravel_index(np.argmax(far), far.shape))
                shared[(a, b)] = np.array([pts[i], pts[j]])
    degree = np.zeros(nb, dtype=int)
    for a, b in shared:
        degree[a] += 1
        degree[b] += 1
    if np.any(degree == 0):
        k = int(np.argmin(degree))
        raise InvalidParameterError(f"block {k} shares no joint (edge) with any other: a gap")
    if np.any(degree > 2) or np.count_nonzero(degree == 1) != 2:
        raise InvalidParameterError(
            "the blocks do not form one chain between two supports (each block must share a "
            "joint with at most two others, and two end blocks with one)")
    ends = [int(k) for k in np.nonzero(degree == 1)[0]]
    cent = [polygon_mass_properties(p, 1.0, 1.0)[1] for p in polys]
    start = min(ends, key=lambda k: cent[k][0])
    order, prev = [start], None
    while len(order) < nb:
        cur = order[-1]
        nxt = [b if a == cur else a for (a, b) in shared if cur in (a, b)]
        nxt = [k for k in nxt if k != prev and k not in order]
        if not nxt:
            raise InvalidParameterError("the blocks do not form one chain between two supports")
        prev = cur
        order.append(nxt[0])
    joints = []
    for side, k in ((0, order[0]), (1, order[-1])):
        p = polys[k]
        nbr = order[1] if side == 0 else order[-2]
        joint = shared[(min(k, nbr), max(k, nbr))]
        edges = [(p[i], p[(i + 1) % len(p)]) for i in range(len(p))]
        free = [e for e in edges
                if not (min(np.hypot(*(e[0] - joint).T)) <= tol and min(np.hypot(*(e[1] - joint).T)) <= tol)]
        low = min(free, key=lambda e: 0.5 * (e[0][1] + e[1][1]))
        joints.append(np.array(low))
    inner = [shared[(min(a, b), max(a, b))] for a, b in zip(order, order[1:])]
    ends_ = [joints[0], *inner, joints[1]]
    blocks = [polys[k] for k in order]
    oriented = []
    for j, seg in enumerate(ends_):
        into = cent[order[j]] if j < nb else None
        outof = cent[order[j - 1]] if j > 0 else None
        p, q = seg
        u = (q - p) / np.hypot(*(q - p))
        nu = np.array([u[1], -u[0]])
        mid = 0.5 * (p + q)
        s = np.dot(nu, into - mid) if into is not None else -np.dot(nu, outof - mid)
        oriented.append((tuple(p), tuple(q)) if s > 0 else (tuple(q), tuple(p)))
    return BlockChain(tuple(tuple(map(tuple, b)) for b in blocks), tuple(oriented), depth, density,
                      name)


__all__ = ["chain_from_polygons", "read_blocks"]
