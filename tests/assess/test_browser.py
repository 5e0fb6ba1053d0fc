"""The assessment's HTML report in headless Chromium, with the reproduction's browser helper:
the seven sections in the DOM, every figure embedded as a PNG, a screenshot that is not blank."""

from __future__ import annotations

import base64
import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "reproduce"))
from test_browser import CHROMIUM, _chromium  # noqa: E402  (the reproduction's helper)

pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed")


def test_dom_has_every_section_and_embedded_figures(tmp_path, bridge):
    _, _, out, _ = bridge
    run = _chromium(tmp_path, "--dump-dom", (out / "report.html").as_uri())
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    for sid in ("arch", "static", "pulses", "records", "dem", "validity", "verdict"):
        assert f'<section id="{sid}">' in dom, sid
    srcs = re.findall(r'<img[^>]*src="(data:image/png;base64,[^"]+)"', dom)
    assert len(srcs) == 6  # the five figures of the dynamics, and the code check's capacity curve
    for s in srcs:
        assert base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    assert "src=\"figures/" not in dom and "http" not in dom.split("<body>")[1][:200]


def test_screenshot_is_not_blank(tmp_path, bridge):
    from PIL import Image

    _, _, out, _ = bridge
    shot = tmp_path / "shot.png"
    run = _chromium(tmp_path, f"--screenshot={shot}", "--window-size=1200,1600",
                    (out / "report.html").as_uri())
    assert run.returncode == 0 and shot.is_file(), run.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert img.std() > 10 and len(np.unique(img)) > 50
