"""Byte identity of the three models' numbers: a guard for changes that must not change a result.

Oracle: the code itself, at the commit that wrote ``tests/data/digests.json``. Each digest is a
sha256 over the float64 bytes of every number a set of runs returns (time histories, energies,
verdicts, event times), so a refactoring that moves code without changing arithmetic keeps them
equal, and any change of a single bit in any sample fails. The tolerance is zero on purpose: a
change meant to alter the numbers (a new default step, a fixed bug) rewrites the file, with the
reason in the commit message::

    .venv/bin/python tests/test_digest.py --write

Every setting a run depends on is given explicitly (time step, solver, tolerances, durations),
so that a change of a default does not pass for a change of the arithmetic. The four-link,
rigid-chain and DEM grids run in the default suite (a few seconds once the kernels are
compiled); the event integrator's runs (half a minute, minutes to compile) and
``reproduce --quick`` (minutes) are marked slow. The digests were checked to be
equal between two runs of the same code (in two processes).
"""

from __future__ import annotations

import enum
import hashlib
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).parent / "data" / "digests.json"

#: Keys of ``reproduce``'s study data that hold wall time (they differ between two runs).
_WALL_KEYS = frozenset({"seconds"})


class _Digest:
    """sha256 over a canonical byte form of numbers, strings and arrays."""

    def __init__(self) -> None:
        self._h = hashlib.sha256()

    def add(self, x: object) -> None:
        h = self._h
        if x is None:
            h.update(b"N")
        elif isinstance(x, enum.Enum):
            self.add(x.value)
        elif isinstance(x, (bool, np.bool_)):
            h.update(b"T" if x else b"F")
        elif isinstance(x, str):
            h.update(b"S" + str(len(x)).encode() + b":" + x.encode())
        elif isinstance(x, (int, np.integer)):
            h.update(b"I" + str(int(x)).encode() + b";")
        elif isinstance(x, (float, np.floating)):
            h.update(b"F" + np.float64(x).tobytes())
        elif isinstance(x, np.ndarray):
            a = np.ascontiguousarray(x, dtype=np.float64) if x.dtype != object else None
            if a is None:
                h.update(b"O" + str(x.shape).encode())
                for item in x.ravel():
                    self.add(item)
            else:
                h.update(b"A" + str(a.shape).encode() + a.tobytes())
        elif isinstance(x, dict):
            h.update(b"D" + str(len(x)).encode())
            for k in sorted(x, key=str):
                if k in _WALL_KEYS:
                    continue
                self.add(str(k))
                self.add(x[k])
        elif isinstance(x, (list, tuple)):
            h.update(b"L" + str(len(x)).encode())
            for item in x:
                self.add(item)
        else:
            raise TypeError(f"no digest for {type(x).__name__}")

    def hexdigest(self) -> str:
        return self._h.hexdigest()


def _arches():
    from archquake import Arch

    out = []
    for thickness in (1.2, 1.5, 1.8, 2.2):
        for embrace_deg in (140.0, 157.5, 170.0):
            out.append(Arch(radius=10.0, thickness=thickness, embrace=math.radians(embrace_deg),
                            voussoirs=7))
    return out


def _pulses():
    from archquake import SinePulse, StepImpulse

    pulses = []
    for a_g in (0.5, 1.0, 2.0):
        for t_p in (0.1, 0.27, 0.44):
            pulses.append(StepImpulse.from_g(a_g, t_p))
    for a_g in (0.6, 1.5):
        for period in (0.3, 0.8):
            pulses.append(SinePulse.from_g(a_g, period, direction=1))
    return pulses


def _cases(n: int, stride: int):
    """``n`` (arch, pulse) pairs spread over the grid (deterministic)."""
    arches, pulses = _arches(), _pulses()
    grid = [(a, p) for a in arches for p in pulses]
    return [grid[(k * stride) % len(grid)] for k in range(n)]


def four_link_digest() -> str:
    """100 histories of the paper's four-link model (``simulate``, default impact law)."""
    from archquake import simulate

    d = _Digest()
    for arch, pulse in _cases(100, 1):
        r = simulate(arch, pulse)
        hist = r.history
        d.add([r.outcome, r.computed_outcome, r.final_state, r.collapse_half_cycle,
               r.collapse_time, r.onset_time, r.impact_times, r.impact_rates, r.peak_rotation,
               r.restitution_cv, r.restitution_ct, r.impact_model_cv, r.collapse_acceleration_g,
               r.critical_rotation, r.toggle_rotation, r.verdict_reason])
        d.add([hist.t, hist.phi, hist.phi_dot, hist.side, hist.ground_acceleration])
    return d.hexdigest()


def _block_numbers(res) -> list:
    return [res.times, res.positions, res.velocities, res.base_displacement, res.base_velocity,
            res.joint_opening, res.joint_slip, res.rotation, res.kinetic, res.potential,
            res.strain, res.damping, res.friction, res.input_work, res.outcome, res.onset_time,
            res.impact_times, res.peak_rotation, res.collapse_half_cycle, res.collapse_time]


def rigid_digest() -> str:
    """20 runs of the rigid-block chain, every setting of the stepper given."""
    from archquake import simulate_rigid

    d = _Digest()
    for k, (arch, pulse) in enumerate(_cases(20, 7)):
        run = simulate_rigid(arch, pulse, duration=0.8, time_step=1e-4, output_interval=5e-4,
                             chunk=0.05, solver_tolerance=1e-11,
                             solver="pgs" if k % 5 == 4 else "direct")
        d.add(_block_numbers(run))
        d.add([run.stepper_time_step, run.max_penetration_m, run.friction_demand, run.max_sweeps,
               run.residual, run.correction_work])
    return d.hexdigest()


def rigid_events_digest() -> str:
    """4 runs of the rigid-block chain's event integrator (``solver="events"``)."""
    from archquake import simulate_rigid

    d = _Digest()
    for arch, pulse in _cases(4, 13):
        run = simulate_rigid(arch, pulse, duration=0.8, output_interval=5e-4, solver="events")
        d.add(_block_numbers(run))
        d.add([run.max_penetration_m, run.friction_demand, run.max_sweeps])
    return d.hexdigest()


def dem_digest() -> str:
    """10 short distinct-element runs."""
    from archquake import simulate_dem
    from archquake.dem import DemSettings

    d = _Digest()
    settings = DemSettings(duration=0.3, output_interval=0.005, time_step=None)
    for arch, pulse in _cases(10, 11):
        d.add(_block_numbers(simulate_dem(arch, pulse, settings)))
    return d.hexdigest()


def reproduce_digest(out: Path) -> str:
    """The numbers of ``archquake reproduce --quick``: every study's data and its table."""
    from archquake.reproduce.runner import run_studies

    rep = run_studies(out, quick=True, force=True, report=False)
    d = _Digest()
    for run in rep.runs:
        s = run.result
        d.add([s.name, s.data, [(r.quantity, r.archquake, r.status) for r in s.rows]])
    return d.hexdigest()


QUICK = {"four_link": four_link_digest, "rigid": rigid_digest, "dem": dem_digest}


def _expected() -> dict:
    return json.loads(DATA.read_text())


@pytest.mark.parametrize("name", sorted(QUICK))
def test_model_digest(name):
    assert QUICK[name]() == _expected()[name]


@pytest.mark.slow
def test_rigid_events_digest():
    assert rigid_events_digest() == _expected()["rigid_events"]


@pytest.mark.slow
def test_reproduce_quick_digest(tmp_path):
    assert reproduce_digest(tmp_path) == _expected()["reproduce_quick"]


def test_digest_sees_one_bit():
    """The digest can fail: one ulp in one sample changes it."""
    a = np.linspace(0.0, 1.0, 11)
    b = a.copy()
    b[5] = np.nextafter(b[5], 2.0)
    d1, d2 = _Digest(), _Digest()
    d1.add(a)
    d2.add(b)
    assert d1.hexdigest() != d2.hexdigest()


if __name__ == "__main__":  # pragma: no cover - rewrites the expected digests
    import tempfile

    if sys.argv[1:] != ["--write"]:
        sys.exit("usage: python tests/test_digest.py --write")
    out = {name: fn() for name, fn in QUICK.items()}
    out["rigid_events"] = rigid_events_digest()
    with tempfile.TemporaryDirectory() as tmp:
        out["reproduce_quick"] = reproduce_digest(Path(tmp))
    DATA.write_text(json.dumps(out, indent=2, sort_keys=True) + "\n")
    print(json.dumps(out, indent=2))
