"""The reproduce cache trusts no file blindly (issue 15): every cached file is written
atomically and checked against the size and SHA-256 its entry records."""

from __future__ import annotations

import json
import os

import pytest

from archquake.reproduce.core import atomic_write_text, file_seal, seal_intact
from archquake.reproduce.runner import cache_path, run_studies


@pytest.fixture(scope="module")
def static_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("repro")
    first = run_studies(out, quick=True, only=["static"], report=False)
    return out, first


def _figure(out, run):
    return out / "figures" / run.runs[0].result.figures[0].file


def test_cache_entry_records_each_figure_size_and_hash(static_run):
    out, first = static_run
    entry = json.loads(cache_path(out, "static", True).read_text())
    fig = _figure(out, first)
    assert entry["figure_seals"][fig.name] == file_seal(fig)
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # no staging folder or temporary file is left behind
    assert not [p for p in (out / "figures").iterdir() if p.name.startswith(".")]
    assert not [p for p in (out / "cache").iterdir() if p.suffix == ".tmp"]


@pytest.mark.parametrize("damage", ["truncate", "empty", "flip"])
def test_damaged_figure_is_recomputed_not_embedded(static_run, damage):
    # before: a 0-byte PNG left by kill -9 counted as cached and went into report.html
    out, first = static_run
    fig = _figure(out, first)
    good = fig.read_bytes()
    if damage == "truncate":
        fig.write_bytes(good[: len(good) // 2])
    elif damage == "empty":
        fig.write_bytes(b"")
    else:  # same size, one byte changed
        fig.write_bytes(good[:100] + bytes([good[100] ^ 0xFF]) + good[101:])
    again = run_studies(out, quick=True, only=["static"], report=False)
    assert again.runs[0].cached is False
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    entry = json.loads(cache_path(out, "static", True).read_text())
    assert seal_intact(fig, entry["figure_seals"][fig.name])
    # and now intact: the next run takes the cache
    assert run_studies(out, quick=True, only=["static"], report=False).runs[0].cached is True
    assert again.runs[0].result.rows == first.runs[0].result.rows


def test_entry_without_seals_is_not_trusted(static_run):
    # an entry written before the seals existed (or edited by hand) is recomputed
    out, first = static_run
    path = cache_path(out, "static", True)
    entry = json.loads(path.read_text())
    del entry["figure_seals"]
    path.write_text(json.dumps(entry))
    assert run_studies(out, quick=True, only=["static"], report=False).runs[0].cached is False


def test_atomic_write_replaces_whole_and_leaves_no_temporary(tmp_path):
    p = tmp_path / "a.json"
    atomic_write_text(p, "x" * 1000)
    atomic_write_text(p, "short")
    assert p.read_text() == "short"
    assert os.listdir(tmp_path) == ["a.json"]
    assert not seal_intact(p, None) and not seal_intact(tmp_path / "missing", file_seal(p))
