"""A cheap, deterministic stand-in case function for testing the sweep machinery.

It is NOT a dynamic model: it evaluates real geometry (the arch's mass and the virtual-work
collapse acceleration of the paper's hinge pattern, scaled to the arch's voussoir count) and
derives a pseudo-outcome from the excitation by a fixed rule, so that every output depends on
every input and two evaluations of the same case agree bit for bit. The machinery tests
compare stores produced through different executors, interruptions and clusters against one
another; what matters is determinism and cost, not physics.

Importable by worker processes and Dask workers (tests put this folder on their PYTHONPATH).
"""

from __future__ import annotations

import time

from archquake.errors import InvalidParameterError
from archquake.geometry import Face, HingeMechanism

#: A small study: 3 radii x 4 magnitudes x 2 durations = 24 cases.
SMALL_STUDY = """\
[study]
name = "small"
model = "fourlink"

[arches]
radius = [1, 5, 10]
thickness_ratio = 0.15
embrace_deg = 157.5
voussoirs = 7

[excitation]
type = "step"
magnitude_g = {start = 0.3, stop = 1.2, num = 4}
duration_s = [0.1, 0.4]
"""

FACES = (Face.INTRADOS, Face.EXTRADOS, Face.INTRADOS, Face.EXTRADOS)


def fake_evaluate(case) -> dict:
    arch = case.arch.build()
    n = arch.voussoirs
    joints = (0, round(3 * n / 7), round(5 * n / 7), n)  # (0, 3, 5, 7): the paper's hinges
    lam = HingeMechanism(arch, joints, FACES).collapse_acceleration_g
    exc = case.excitation
    a = exc.magnitude_g
    t_p = exc.duration_s if exc.duration_s is not None else exc.period_s
    demand = a * t_p**2 * case.options.g / arch.thickness  # dimensionless pulse "strength"
    if a <= lam:
        outcome = "no_hinging"
    else:
        outcome = "collapse" if demand > 0.5 else "survives"
    return {"outcome": outcome, "collapse_acceleration_g": lam, "mass_kg": arch.mass,
            "demand": demand, "impact_times": [t_p * k for k in range(1, 4)],
            "summary": {"span_m": arch.span, "hinges": list(joints)}}


def slow_fake_evaluate(case) -> dict:
    """fake_evaluate after 50 ms of sleep, so that tasks are in flight long enough to kill a
    worker in the middle of a sweep."""
    time.sleep(0.05)
    return fake_evaluate(case)


def picky_evaluate(case) -> dict:
    """fake_evaluate, but refuses radius >= 10 m with an ArchquakeError (a stored error row)."""
    if case.arch.radius >= 10.0:
        raise InvalidParameterError(f"radius {case.arch.radius:g} m is refused by this model")
    return fake_evaluate(case)


class CountingEvaluate:
    """fake_evaluate that counts its calls and raises KeyboardInterrupt on call number
    ``stop_at`` (1-based), as Ctrl-C would during that case. Serial executor only."""

    def __init__(self, stop_at: int | None = None):
        self.calls = 0
        self.evaluated: list[str] = []
        self.stop_at = stop_at

    def __call__(self, case) -> dict:
        self.calls += 1
        if self.stop_at is not None and self.calls == self.stop_at:
            raise KeyboardInterrupt
        self.evaluated.append(case.case_id)
        return fake_evaluate(case)
