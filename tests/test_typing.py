"""The package type-checks: mypy on src/archquake reports no error (issue 11).

Oracle: mypy itself, configured by pyproject.toml [tool.mypy]; `make lint` runs the same check.
Slow (a cold mypy run over the package takes ~20-60 s), so it runs with the slow tests and in lint.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_mypy_reports_no_error_on_the_package():
    run = subprocess.run(
        [sys.executable, "-m", "mypy", "--no-incremental", "src/archquake"],
        cwd=ROOT, capture_output=True, text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
    )
    assert run.returncode == 0, run.stdout[-5000:] + run.stderr[-2000:]
    assert "Success: no issues found" in run.stdout
