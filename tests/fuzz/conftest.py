"""The fuzz suite's shared pieces: the in-process caller (fuzz_harness) on sys.path, a scratch
folder the commands write into, and small input files (records, a study)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

# --import-mode=importlib: put the harness beside the tests on the path, as tests/sweeps does
sys.path.insert(0, str(Path(__file__).resolve().parent))

os.environ.setdefault("MPLBACKEND", "Agg")

from fuzz_harness import STUDY  # noqa: E402  (the harness is on the path from here)


@pytest.fixture(scope="module")
def scratch(tmp_path_factory) -> Path:
    """A folder that is the working directory while the module's examples run (relative output
    paths land here), holding a valid CSV record and a valid study."""
    folder = tmp_path_factory.mktemp("fuzz")
    (folder / "quake.csv").write_text(
        "time,acc\n" + "\n".join(f"{0.01 * i:.2f},{0.3 if 5 < i < 40 else 0.0:g}"
                                 for i in range(80)) + "\n")
    (folder / "study.toml").write_text(STUDY)
    old = os.getcwd()
    os.chdir(folder)
    try:
        yield folder
    finally:
        os.chdir(old)
