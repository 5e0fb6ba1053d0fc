"""Fixtures of the paper's checks: Oppenheim's arch as :mod:`archquake.validation.paper` defines
it, and its mechanism."""

from __future__ import annotations

import pytest

from archquake.mechanism import PreparedMechanism
from archquake.validation import paper


@pytest.fixture(scope="module")
def arch():
    return paper.oppenheim_arch()


@pytest.fixture(scope="module")
def prepared(arch):
    return PreparedMechanism.build(arch)
