"""Fixtures for the sweep tests: small studies, and the sweep command alone in the CLI."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

# the fake case functions live beside the tests; worker processes (forked, or Dask workers given
# PYTHONPATH) import them by module name, so the folder must be on sys.path with
# --import-mode=importlib too
sys.path.insert(0, str(Path(__file__).resolve().parent))

from sweep_fake_model import SMALL_STUDY  # noqa: E402

from archquake.sweeps import load_study


@pytest.fixture
def small_study_file(tmp_path: Path) -> Path:
    """3 radii x 4 magnitudes x 2 durations = 24 cases."""
    path = tmp_path / "small.toml"
    path.write_text(SMALL_STUDY)
    return path


@pytest.fixture
def small_cases(small_study_file: Path):
    return load_study(small_study_file).cases


@pytest.fixture
def sweep_cli(monkeypatch):
    """archquake.cli.main.main with only the sweep command registered (so these tests do not
    depend on the other commands' modules) and the fake case function injected."""
    import sweep_fake_model

    from archquake.cli import cmd_sweep
    from archquake.cli import main as cli_main

    monkeypatch.setattr(cli_main, "COMMANDS", ("sweep",))
    monkeypatch.setattr(cmd_sweep, "case_function", lambda model: sweep_fake_model.fake_evaluate)
    return cli_main.main
