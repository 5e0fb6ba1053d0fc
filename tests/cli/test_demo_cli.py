"""``archquake demo``: every step writes its files, and --json reports them (progress on stderr)."""

from __future__ import annotations

import json

from archquake.cli import cmd_demo
from archquake.cli.main import main


def test_demo_json_lists_every_step_and_its_files(tmp_path, capsys, monkeypatch):
    # the analytical steps only: the DEM comparison step has its own tests
    steps = [s for s in cmd_demo.STEPS if "static" in s[1] or "dynamics" in s[1]]
    monkeypatch.setattr(cmd_demo, "STEPS", steps)
    assert main(["demo", "--out", str(tmp_path), "--json"]) == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out)
    assert "[demo]" in captured.err
    assert [s["title"] for s in summary["steps"]] == [t for t, _ in steps]
    for step in summary["steps"]:
        assert step["files"]
        for f in step["files"]:
            assert (tmp_path / f.split("/")[-1]).stat().st_size > 0
    assert (tmp_path / "index.md").exists()
