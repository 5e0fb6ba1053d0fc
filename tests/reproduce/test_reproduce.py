"""``archquake reproduce --quick``: the report is generated, every line passes (or says why it
does not apply), finished studies are reused, and the HTML page stands on its own.

Oracle: the paper's numbers and statements, each row carrying its own tolerance and source
(archquake.reproduce); here we check the report's integrity and the cache's contract.
"""

from __future__ import annotations

import base64
import io
import json
import re
from pathlib import Path

import pytest
from PIL import Image

from archquake import __version__
from archquake.cli.main import main
from archquake.reproduce import STUDIES, cache_path, run_studies


@pytest.fixture(scope="module")
def quick_report(tmp_path_factory):
    """One quick reproduction through the CLI with --json (the slow part, ~35 s, run once)."""
    out = tmp_path_factory.mktemp("reproduce")
    buf = io.StringIO()
    import contextlib

    with contextlib.redirect_stdout(buf):
        status = main(["reproduce", "--quick", "--out", str(out), "--json"])
    return out, status, json.loads(buf.getvalue())


def test_every_line_passes_or_says_why(quick_report):
    out, status, report = quick_report
    rows = [(s["name"], r) for s in report["studies"] for r in s["rows"]]
    failing = [(n, r["quantity"], r["paper"], r["archquake"]) for n, r in rows if r["pass"] is False]
    assert not failing, failing
    for name, r in rows:
        assert r["pass"] is True or (r["pass"] is None and r["note"].strip()), (name, r)
        assert r["source"] and r["tolerance"] and r["justification"], (name, r)
    assert status == 0
    assert report["summary"]["fail"] == 0
    assert report["summary"]["pass"] >= 40
    assert [s["name"] for s in report["studies"]] == [s.name for s in STUDIES]


def test_report_covers_the_papers_numbers(quick_report):
    """The checklist of docs/reading-the-paper.md: each number the paper states
    (:mod:`archquake.validation.paper`, the values stated on a page of the paper) and each
    worded agreement has a line, with its tolerance."""
    from archquake.validation import paper

    out, _, report = quick_report
    text = (out / "report.md").read_text()
    stated = [v for v in vars(paper).values()
              if isinstance(v, (paper.PaperValue, paper.Agreement)) and v.where.startswith("p. ")]
    assert len(stated) >= 15
    for value in stated:
        assert value.stated in text, value
        assert value.tolerance_text in text, value
    for needle in ("sqrt(R", "t/R 0.11, 0.15 asymmetric", "joint 2"):
        assert needle in text, needle
    assert "## Where archquake departs from the paper, and why" in text


def test_json_lists_files_and_reports(quick_report):
    out, _, report = quick_report
    assert report["quick"] is True and report["archquake_version"] == __version__
    assert Path(report["report_html"]).is_file() and Path(report["report_md"]).is_file()
    for s in report["studies"]:
        for f in s["figures"]:
            assert (out / "figures" / f["file"]).is_file()
    assert report["computed"] == len(STUDIES)


def test_rerun_reuses_finished_studies(quick_report):
    out, _, _ = quick_report
    rerun = run_studies(out, quick=True, report=False)
    assert rerun.computed == 0 and all(r.cached for r in rerun.runs)
    # an interrupted run leaves a study without its cache entry: only that one is recomputed
    cache_path(out, "static", True).unlink()
    rerun = run_studies(out, quick=True, report=False)
    assert rerun.computed == 1 and [r.result.name for r in rerun.runs if not r.cached] == ["static"]
    # a missing figure invalidates its study's entry
    (out / "figures" / "static_collapse.png").unlink()
    assert run_studies(out, quick=True, only=["static"], report=False).computed == 1
    # --force recomputes; the full mode and another version never reuse quick results
    assert run_studies(out, quick=True, only=["static"], force=True, report=False).computed == 1
    assert cache_path(out, "static", True) != cache_path(out, "static", False)
    assert __version__ in cache_path(out, "static", True).name


def test_unknown_study_is_one_line_usage_error(tmp_path, capsys):
    assert main(["reproduce", "--out", str(tmp_path), "--only", "figure99"]) == 2
    err = capsys.readouterr().err
    assert "unknown study figure99" in err and len(err.strip().splitlines()) == 1


def _data_images(html: str) -> list[bytes]:
    srcs = re.findall(r'<img[^>]*src="([^"]+)"', html)
    assert srcs and all(s.startswith("data:image/png;base64,") for s in srcs)
    return [base64.b64decode(s.split(",", 1)[1]) for s in srcs]


def test_html_is_self_contained(quick_report):
    out, _, report = quick_report
    html = (out / "report.html").read_text()
    assert not re.search(r'(src|href)="(?!data:|#)', html), "external asset referenced"
    images = _data_images(html)
    assert len(images) == sum(len(s["figures"]) for s in report["studies"])
    for png in images:
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        img = Image.open(io.BytesIO(png))
        img.verify()
    n_rows = sum(len(s["rows"]) for s in report["studies"])
    assert html.count('<tr class="row ') == n_rows
