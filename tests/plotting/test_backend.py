"""Importing the plotting package leaves matplotlib's backend as the user chose it, and the one
save helper writes the figure and closes it.

Oracle: ``matplotlib.get_backend()`` in a fresh interpreter before and after the imports (set
through ``MPLBACKEND`` and through ``matplotlib.use``), and the file's own signature bytes."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

PLOTTING = sorted(p.stem for p in (Path(__file__).parents[2] / "src/archquake/plotting").glob("*.py")
                  if p.stem != "__init__")
IMPORTS = "; ".join(f"import archquake.plotting.{m}" for m in PLOTTING)


def _fresh(code: str, **env: str) -> str:
    environ = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), **env)
    done = subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True, text=True,
                          check=True)
    return done.stdout.strip()


def test_every_plotting_module_is_imported_here():
    assert {"arch", "compare", "dem", "domains", "figures", "history", "reproduce", "thrust"} <= set(PLOTTING)


def test_backend_from_the_environment_is_kept():
    out = _fresh(f"{IMPORTS}; import matplotlib; print(matplotlib.get_backend())", MPLBACKEND="svg")
    assert out.lower() == "svg"


def test_backend_chosen_in_the_session_is_kept():
    out = _fresh(f"import matplotlib; matplotlib.use('pdf'); {IMPORTS}; "
                 "import archquake.cli.main; print(matplotlib.get_backend())")
    assert out.lower() == "pdf"


def test_no_module_of_the_library_selects_a_backend():
    src = Path(__file__).parents[2] / "src" / "archquake"
    # the command line selects Agg through MPLBACKEND in its entry point, not matplotlib.use
    offenders = [str(p.relative_to(src)) for p in src.rglob("*.py") if "matplotlib.use(" in p.read_text()]
    assert offenders == []


@pytest.mark.parametrize("give", ["figure", "axes", "axes of a subfigure"])
def test_save_writes_and_closes(tmp_path, give):
    import matplotlib.pyplot as plt

    from archquake.plotting.figures import save

    if give == "axes of a subfigure":
        fig = plt.figure()
        ax = fig.subfigures(1, 2)[1].subplots()
    else:
        fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    out = save(fig if give == "figure" else ax, tmp_path / "f.png", dpi=50)
    assert out == tmp_path / "f.png"
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert fig.number not in plt.get_fignums()


def test_test_session_backend_untouched_by_plotting():
    before = matplotlib.get_backend()
    import archquake.plotting.compare  # noqa: F401
    import archquake.plotting.reproduce  # noqa: F401

    assert matplotlib.get_backend() == before
