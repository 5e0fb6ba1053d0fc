"""One quick assessment of the bridge example under the four-link model (c_v prescribed 0.8, as
the example prescribed before the rigid chain became the default: its report machinery and its
c_v sensitivity), shared by the tests of this folder (about 30 s). The default model's
assessments are in test_rigid.py."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def bare_bridge():
    """examples/bridge.toml's ring without its [loads] table: the bare semicircle (R 5 m, t
    0.6 m, 15 voussoirs) whose sections these tests set beside the library's bare-arch calls
    (the loaded bridge's are in test_loads.py)."""
    import tomllib

    from archquake.assess.config import parse_config

    data = tomllib.loads((EXAMPLES / "bridge.toml").read_text())
    data.pop("loads", None)
    return parse_config(data, source="bridge.toml", base_dir=EXAMPLES)


def fourlink_bridge():
    """:func:`bare_bridge` with [options] model = "fourlink" and restitution = 0.8."""
    import tomllib

    from archquake.assess.config import parse_config

    data = tomllib.loads((EXAMPLES / "bridge.toml").read_text())
    data.pop("loads", None)
    data["options"] = {**data.get("options", {}), "model": "fourlink", "restitution": 0.8}
    return parse_config(data, source="bridge.toml", base_dir=EXAMPLES)


@pytest.fixture(scope="session")
def bridge(tmp_path_factory):
    """(Assessment, results.json as a dict, output folder, progress lines) of
    :func:`fourlink_bridge` in quick mode."""
    from archquake.assess import run_assessment
    from archquake.ground.suites import fema_available

    if not fema_available():
        pytest.skip("the bridge example uses the FEMA P695 records (archquake[records])")

    out = tmp_path_factory.mktemp("bridge")
    lines: list[str] = []
    rep = run_assessment(fourlink_bridge(), out, quick=True, progress=lines.append)
    return rep, json.loads((out / "results.json").read_text()), out, lines
