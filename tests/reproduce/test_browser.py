"""The HTML report opened in headless Chromium: the DOM has the table and the embedded figures,
and a screenshot is not blank. Installed by ``make test`` (Debian's chromium); skipped only if
chromium is truly unavailable."""

from __future__ import annotations

import base64
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from archquake.reproduce.core import Figure, Row, StudyResult
from archquake.reproduce.report import write_html
from archquake.reproduce.runner import Reproduction, StudyRun

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed and could not be "
                                "(make test installs Debian's chromium with apt-get)")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def _chromium(tmp_path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", *args],
                          capture_output=True, text=True, timeout=120)


@pytest.fixture
def small_report(tmp_path):
    """A report of two real rows and one real figure (the quick report itself is checked in
    test_reproduce; this keeps the browser test to a few seconds)."""
    from archquake.domains import oppenheim_arch
    from archquake.reproduce.static import study as static_study

    figures = tmp_path / "figures"
    figures.mkdir()
    res = static_study(oppenheim_arch(), True, figures)
    extra = StudyResult("demo", "A not applicable line", (Row("q", "p. 1", "1", "-", "-", "-", None, "why"),),
                        (Figure(res.figures[0].file, "again"),))
    rep = Reproduction((StudyRun(res, False), StudyRun(extra, True)), tmp_path, True)
    return write_html(rep, tmp_path / "report.html"), len(res.rows) + 1


def test_dom_has_table_rows_and_png_images(tmp_path, small_report):
    page, n_rows = small_report
    run = _chromium(tmp_path, "--dump-dom", page.as_uri())
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    assert dom.count('<tr class="row ') == n_rows
    import re

    srcs = re.findall(r'<img[^>]*src="(data:image/png;base64,[^"]+)"', dom)
    assert len(srcs) == 2
    for s in srcs:
        assert base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    assert "pass" in dom and "n/a" in dom


def test_screenshot_is_not_blank(tmp_path, small_report):
    page, _ = small_report
    shot = tmp_path / "shot.png"
    run = _chromium(tmp_path, f"--screenshot={shot}", "--window-size=1200,1600", page.as_uri())
    assert run.returncode == 0 and shot.is_file(), run.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert img.shape[0] >= 1000 and img.shape[1] >= 1000
    # text, table borders and the figure: many grey levels and real contrast, not one flat colour
    assert img.std() > 10 and len(np.unique(img)) > 50
