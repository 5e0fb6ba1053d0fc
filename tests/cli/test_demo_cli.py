"""``archquake demo`` is ``archquake reproduce --quick`` plus the rocking animation: the same
report and JSON, and DIR/rocking.gif (progress on stderr under --json)."""

from __future__ import annotations

import json

from archquake.cli.main import main
from archquake.reproduce import registry, runner


def test_demo_writes_the_quick_report_and_the_animation(tmp_path, capsys, monkeypatch):
    # one study keeps the test short; the full quick reproduction has its own tests
    static = tuple(s for s in registry.STUDIES if s.name == "static")
    monkeypatch.setattr(runner, "STUDIES", static)
    assert main(["demo", "--out", str(tmp_path), "--json"]) == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out)
    assert "[demo]" in captured.err
    assert summary["quick"] is True
    assert [s["name"] for s in summary["studies"]] == ["static"]
    assert summary["summary"]["fail"] == 0 and summary["summary"]["pass"] == 4
    for key in ("report_html", "report_md", "animation"):
        assert (tmp_path / summary[key].split("/")[-1]).stat().st_size > 0
    assert summary["animation"].endswith("rocking.gif")
    # the same study, run again: cached, and the same rows as `reproduce --quick`
    assert main(["reproduce", "--quick", "--out", str(tmp_path), "--json"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["computed"] == 0
    assert again["studies"][0]["rows"] == summary["studies"][0]["rows"]
