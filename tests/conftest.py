"""Shared fixtures (the paper's arches), and the order the test files run in."""

from __future__ import annotations

import math
from collections import Counter

import pytest

from archquake.geometry import Arch


@pytest.fixture
def oppenheim() -> Arch:
    """Oppenheim's arch: t/R = 0.15, embrace 157.5 deg, R = 10 m, 7 voussoirs (paper, p. 2126)."""
    return Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)


#: The test files that take longest (``pytest --durations``: each from about ten seconds to a
#: minute of CPU time on the two-core machines ``make test`` is sized for), longest first.
#: ``make test`` gives its two workers whole files (``--dist loadfile``) in the order collected
#: (``--no-loadscope-reorder``): these start first, so that no long file is left to run alone
#: while the other worker waits. Re-measure with ``--durations=60`` when a file grows.
LONGEST_FIRST: tuple[str, ...] = (
    "tests/assess/test_assess.py",
    "tests/reproduce/test_reproduce.py",
    "tests/docs/test_manual.py",
    "tests/ida/test_ida.py",
    "tests/rigid/test_vertical.py",
    "tests/examples/test_examples.py",
    "tests/mechanism/test_bounds.py",
    "tests/dem/test_vertical.py",
    "tests/sweeps/test_cluster.py",
    "tests/compare/test_cli.py",
    "tests/assess/test_vertical.py",
    "tests/rigid/test_input_kernels.py",
)


def pytest_collection_modifyitems(config, items):
    """Run `LONGEST_FIRST` first, then the other files by their number of tests (most first, as
    pytest-xdist orders them), each file's tests in their own order."""
    rank = {path: k for k, path in enumerate(LONGEST_FIRST)}
    files = [item.nodeid.split("::", 1)[0] for item in items]
    count = Counter(files)
    order = sorted(range(len(items)), key=lambda i: (rank.get(files[i], len(rank)),
                                                     -count[files[i]]))
    items[:] = [items[i] for i in order]
