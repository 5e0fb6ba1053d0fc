"""One quick assessment of the bridge example, shared by the tests of this folder (about 30 s)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="session")
def bridge(tmp_path_factory):
    """(Assessment, results.json as a dict, output folder, progress lines) of
    examples/bridge.toml in quick mode."""
    from archquake.assess import load_config, run_assessment
    from archquake.ground.suites import fema_available

    if not fema_available():
        pytest.skip("the bridge example uses the FEMA P695 records (archquake[records])")

    out = tmp_path_factory.mktemp("bridge")
    lines: list[str] = []
    rep = run_assessment(load_config(EXAMPLES / "bridge.toml"), out, quick=True,
                         progress=lines.append)
    return rep, json.loads((out / "results.json").read_text()), out, lines
