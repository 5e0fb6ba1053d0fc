"""Read an accelerogram, scale it, and run Oppenheim's arch through it.

    python examples/earthquake_record.py                   # a synthetic record written to a temp file
    python examples/earthquake_record.py RSN953.AT2        # your PEER .AT2 file (in g)
    python examples/earthquake_record.py quake.csv --units m/s2 --scale 1.5

Any two-column CSV (time s, acceleration; --units says in what, since a CSV file does not) or PEER
.AT2 file (in g) works (docs/ground-motions.md).
Without a path, a small synthetic record (a decaying 1.2 Hz burst, about 0.6 g peak) is written to a
temporary CSV file first, so the example needs no external data.
"""

from __future__ import annotations

import argparse
import math
import tempfile
from pathlib import Path

import numpy as np

from archquake import Arch
from archquake.ground import read_record
from archquake.mechanism import simulate


def synthetic_record(path: Path, *, duration: float = 6.0, dt: float = 0.01) -> Path:
    """Write a decaying 1.2 Hz burst (peak about 0.6 g) as a CSV file in g."""
    t = np.arange(0.0, duration + dt / 2, dt)
    acc_g = 0.8 * np.exp(-0.6 * t) * np.sin(2 * math.pi * 1.2 * t) * np.minimum(t / 0.3, 1.0)
    np.savetxt(path, np.column_stack([t, acc_g]), delimiter=",", header="time_s,acc_g", fmt="%.6g")
    return path


def main(path: str | None = None, *, units: str | None = None, scale: float = 1.0,
         quick: bool = False) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        if path is None:
            path = str(synthetic_record(Path(tmp) / "synthetic.csv", duration=3.0 if quick else 6.0))
            units = "g"
        if units is None and Path(path).suffix.lower() in (".csv", ".txt"):
            raise SystemExit(f"{Path(path).name} needs --units g|m/s2|cm/s2: a CSV file does not "
                             "say its units")
        record = read_record(path, units=units, scale=scale)
    arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
    print(f"{record.name}: {record.duration:.2f} s, peak {record.peak / 9.80665:.3f} g (scaled x{scale:g})")
    for factor in (1.0,) if quick else (0.5, 1.0, 1.5, 2.0):
        result = simulate(arch, record.scaled(factor))
        what = result.outcome.value + (f" in half cycle {result.collapse_half_cycle}"
                                       if result.collapse_half_cycle else "")
        print(f"  x{factor:g}: {what}; {result.impact_times.size} impacts; "
              f"largest rotation {float(np.max(result.peak_rotation, initial=0.0)):.4f} rad")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("path", nargs="?", help="record file (.AT2 or CSV); default: a synthetic one")
    parser.add_argument("--units", choices=("g", "m/s2", "cm/s2"),
                        help="CSV acceleration units (required with a CSV file)")
    parser.add_argument("--scale", type=float, default=1.0, help="factor on the accelerations")
    parser.add_argument("--quick", action="store_true", help="one run instead of four")
    a = parser.parse_args()
    main(a.path, units=a.units, scale=a.scale, quick=a.quick)
