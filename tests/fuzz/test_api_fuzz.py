"""Fuzz the Python API: hypothesis-generated bad arguments for the public functions and
constructors (the flat API of :mod:`archquake` and the documented subpackage entry points).

Oracle: the library's promise (``errors.py``, ``_validate.py``): a call with an argument outside
its range or of the wrong kind raises an :class:`~archquake.errors.ArchquakeError` whose message
is one line naming the argument; a call that is accepted returns a result whose ``to_dict()``
holds no NaN or infinity (strict JSON). Any other exception (scipy's, numpy's, Python's
``TypeError``/``AttributeError``/``ZeroDivisionError``...) is a failure, as is a message of
several lines.

Each call does little work (5 voussoirs, runs of a fraction of a second), so the quick version
(over 300 calls across the functions) runs inside ``make test``; ``pytest -m slow tests/fuzz``
runs ten times as many with fresh seeds.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

import archquake as aq
from archquake.dem import ContactLaw, DemSettings
from archquake.domains import DomainSettings
from archquake.errors import ArchquakeError
from archquake.limit import min_thickness, min_thickness_ratio
from archquake.mechanism import SolverOptions

#: No shrinking: the failure message already names the entry point and the junk arguments, and
#: shrinking through ten calls per example costs minutes.
QUICK = settings(max_examples=30, deadline=None, derandomize=True, database=None,
                 phases=[Phase.explicit, Phase.generate],
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
THOROUGH = settings(QUICK, max_examples=300, derandomize=False)

ARCH = aq.Arch(10.0, 1.5, math.radians(157.5), 5)
PULSE = aq.StepImpulse.from_g(0.5, 0.05)

#: Values no numeric, path or object argument accepts, or accepts only at an edge of its range:
#: wrong kinds, non-finite, overflow, underflow, signs.
JUNK = [None, "x", "", b"path", 1 + 1j, [], [1.0, 2.0], {}, object(), True, math.nan, math.inf,
        -math.inf, -1, 0, -0.0, 5e-324, 1e-300, 1e308, 10**400, -1e308, np.float64("nan"),
        np.array([[1.0]]), np.array([1 + 1j, 2.0]), "static", "foo", "\x00", 3.5]


def junk() -> st.SearchStrategy[object]:
    return st.one_of(st.sampled_from(JUNK),
                     st.floats(allow_nan=True, allow_infinity=True),
                     st.integers(min_value=-10**30, max_value=10**30),
                     st.text(max_size=5))


#: Each entry point and a cheap valid value for each of its arguments (positional or keyword).
VALID: dict[str, tuple[object, dict[str, object]]] = {
    "Arch": (aq.Arch, {"radius": 10.0, "thickness": 1.5, "embrace": 2.7, "voussoirs": 5,
                       "depth": 1.0, "density": 2000.0}),
    "limit_analysis": (aq.limit_analysis, {"arch": ARCH, "method": "static", "g": 9.81}),
    "min_thickness_ratio": (min_thickness_ratio, {"embrace": 2.7, "voussoirs": 5, "rtol": 1e-3}),
    "min_thickness": (min_thickness, {"arch": ARCH, "rtol": 1e-3}),
    "StepImpulse": (aq.StepImpulse, {"magnitude": 4.9, "pulse_duration": 0.05, "direction": -1}),
    "StepImpulse.from_g": (aq.StepImpulse.from_g, {"magnitude_g": 0.5, "duration": 0.05,
                                                   "g": 9.81}),
    "SinePulse": (aq.SinePulse, {"magnitude": 4.9, "period": 0.1, "direction": -1}),
    "SinePulse.from_g": (aq.SinePulse.from_g, {"magnitude_g": 0.5, "period": 0.1, "g": 9.81}),
    "Record": (aq.Record, {"accelerations": [0.0, 1.0, 0.0], "dt": 0.01, "name": "r",
                           "scale": 1.0}),
    "read_record": (aq.read_record, {"path": "quake.csv", "units": "g", "dt": None,
                                     "scale": 1.0, "g": 9.81}),
    "simulate": (aq.simulate, {"arch": ARCH, "motion": PULSE, "restitution": None,
                               "impact": None, "t_end": 0.3, "initial_rate": 0.0,
                               "options": SolverOptions(), "t_eval": None, "g": 9.81}),
    "SolverOptions": (SolverOptions, {"rtol": 1e-9, "atol": 1e-12, "rest_rotation": 1e-9,
                                      "max_impacts": 10, "output_interval": None}),
    "failure_domain": (aq.failure_domain, {
        "arch": ARCH, "family": "step", "durations": [0.1], "restitution": None,
        "settings": DomainSettings(max_magnitude_g=1.0, coarse_points=3, fine_points=0,
                                   precision_g=0.1), "g": 9.81}),
    "DomainSettings": (DomainSettings, {"max_magnitude_g": 1.0, "coarse_points": 3,
                                        "fine_points": 0, "precision_g": 0.1}),
    "simulate_dem": (aq.simulate_dem, {"arch_or_assembly": ARCH, "motion": PULSE,
                                       "settings": DemSettings(duration=0.01), "g": 9.81}),
    "DemSettings": (DemSettings, {"duration": 0.01, "output_interval": 0.005, "safety": 0.8,
                                  "time_step": None, "settle_time": 0.0}),
    "ContactLaw": (ContactLaw, {"normal_stiffness": 1e12, "shear_stiffness": 1e12,
                                "friction": 0.7}),
    "simulate_rigid": (aq.simulate_rigid, {"arch_or_assembly": ARCH, "motion": PULSE,
                                           "duration": 0.01, "output_interval": 0.005,
                                           "g": 9.81}),
}

#: Entry points whose first compiled call costs tens of seconds: fuzzed in the slow run only.
COMPILED = {"simulate_dem", "simulate_rigid"}


@st.composite
def bad_call(draw, names: list[str]):
    """An entry point and its arguments, at least one of them junk."""
    name = draw(st.sampled_from(names))
    fn, valid = VALID[name]
    params = list(valid)
    bad = draw(st.lists(st.sampled_from(params), min_size=1, max_size=min(3, len(params)),
                        unique=True))
    kwargs = {p: (draw(junk()) if p in bad else valid[p]) for p in params}
    return name, fn, kwargs, bad


def check_call(name: str, fn, kwargs: dict, bad: list[str]) -> None:
    """Call ``fn(**kwargs)``; fail on any exception but archquake's one-line ones, and on an
    accepted call whose result does not serialise as strict JSON."""
    try:
        result = fn(**kwargs)
    except ArchquakeError as exc:
        message = str(exc)
        assert message and "\n" not in message, f"{name}({bad}): message {message!r}"
        return
    except Exception as exc:  # noqa: BLE001  (the oracle: any other exception is a bug)
        pytest.fail(f"{name} with junk {bad} = {[kwargs[b] for b in bad]!r:.200}: "
                    f"{type(exc).__name__}: {exc}")
    to_dict = getattr(result, "to_dict", None)
    if callable(to_dict):
        try:
            json.dumps(to_dict(), allow_nan=False, default=str)
        except ValueError as exc:
            pytest.fail(f"{name} with {bad} accepted, and to_dict() is not finite: {exc}")


QUICK_NAMES = [n for n in VALID if n not in COMPILED]


@pytest.fixture(autouse=True)
def _in_scratch(scratch: Path) -> None:
    """Run in the fuzz folder, where ``quake.csv`` (a valid record) lies."""


@QUICK
@given(st.data())
def test_api_refuses_bad_arguments_in_one_line(data) -> None:
    """Ten random bad calls per example, 30 examples: 300 calls over the quick entry points."""
    for _ in range(10):
        check_call(*data.draw(bad_call(QUICK_NAMES)))


@pytest.mark.slow
@THOROUGH
@given(st.data())
def test_api_refuses_bad_arguments_thorough(data) -> None:
    for _ in range(10):
        check_call(*data.draw(bad_call(list(VALID))))


@pytest.mark.parametrize("name", list(VALID))
def test_every_entry_point_accepts_its_valid_arguments(name: str) -> None:
    """The fuzz's baseline: with every argument valid each call succeeds (so a refusal above is
    due to the junk, and the valid values stay valid as the ranges change)."""
    if name in COMPILED:
        pytest.skip("compiled kernels: exercised by their own tests")
    fn, valid = VALID[name]
    fn(**valid)


# ------------------------------------------------------------------------------------------
# the campaign's cases, one by one (each reached a non-archquake exception or a wrong answer)
# ------------------------------------------------------------------------------------------
CAMPAIGN = [
    ("g=0", lambda: aq.limit_analysis(ARCH, g=0), "g must be in"),
    ("g=-1", lambda: aq.limit_analysis(ARCH, g=-1), "g must be in"),
    ("g=nan", lambda: aq.limit_analysis(ARCH, g=math.nan), "g must be a finite"),
    ("g=1e308", lambda: aq.limit_analysis(ARCH, g=1e308), "g must be in"),
    ("complex record", lambda: aq.Record([1 + 1j, 2], 0.01), "real numbers"),
    ("complex array", lambda: aq.Record(np.array([1 + 1j, 2]), 0.01), "real numbers"),
    ("dt=1e308", lambda: aq.Record([0, 1, 0], dt=1e308), "dt must be in"),
    ("long record", lambda: aq.Record(np.zeros(20002), dt=1.0), "at most 10000 s"),
    ("thickness 5e-324", lambda: aq.Arch(10.0, 5e-324, 2.7, 7), "thickness must be in"),
    ("embrace 5e-324", lambda: aq.Arch(10.0, 1.5, 5e-324, 7), "embrace must be in"),
    ("read_record(None)", lambda: aq.read_record(None), "path must be a path"),
    ("read_record(12345)", lambda: aq.read_record(12345), "path must be a path"),
    ("read_record(b'path')", lambda: aq.read_record(b"path"), "path must be a path"),
    ("options=None", lambda: aq.simulate(ARCH, PULSE, options=None), "options must be"),
    ("method='foo'", lambda: aq.limit_analysis(ARCH, method="foo"), "method must be one of"),
    ("limit_analysis(None)", lambda: aq.limit_analysis(None), "arch must be"),
    ("settings='x'", lambda: aq.failure_domain(ARCH, settings="x"), "settings must be"),
]


@pytest.mark.parametrize("case, call, words", CAMPAIGN, ids=[c[0] for c in CAMPAIGN])
def test_campaign_case_is_refused_by_name(case: str, call, words: str) -> None:
    with pytest.raises(ArchquakeError, match=words):
        call()


def test_record_refuses_devices_and_pipes(tmp_path: Path) -> None:
    """A device (here through a .csv symlink, which the extension check would pass) and a named
    pipe are refused by type before any byte is read: /dev/zero never ends, a pipe blocks."""
    import os

    link = tmp_path / "zero.csv"
    link.symlink_to("/dev/zero")
    with pytest.raises(aq.GroundMotionFormatError, match="not a regular file"):
        aq.read_record(link, units="g", dt=0.01)
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    with pytest.raises(aq.GroundMotionFormatError, match="not a regular file"):
        aq.read_record(fifo, units="g", dt=0.01)
