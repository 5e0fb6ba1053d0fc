"""Fixtures of the IDA tests (the inputs live in ida_inputs.py beside them)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

# with --import-mode=importlib the test folder is not on sys.path: put it there for ida_inputs
sys.path.insert(0, str(Path(__file__).resolve().parent))

from ida_inputs import synthetic_record  # noqa: E402


@pytest.fixture(scope="session")
def records():
    return [synthetic_record(s) for s in range(3)]
