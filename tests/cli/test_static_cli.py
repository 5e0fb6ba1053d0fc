"""``archquake static`` and ``archquake min-thickness`` through the real entry point."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

from archquake.cli import main as cli_main
from archquake.validation import paper


@pytest.fixture(autouse=True)
def _registered_commands(monkeypatch):
    """The real COMMANDS, less any sibling command whose module is not written yet (several
    commands are developed in parallel); ours must be registered."""
    assert {"static", "min_thickness"} <= set(cli_main.COMMANDS)
    present = tuple(name for name in cli_main.COMMANDS
                    if importlib.util.find_spec(f"archquake.cli.cmd_{name}") is not None)
    monkeypatch.setattr(cli_main, "COMMANDS", present)


OPPENHEIM = ["--radius", "10", "--thickness", "1.5", "--embrace", "157.5", "--voussoirs", "7"]


def test_static_text(capsys):
    assert cli_main.main(["static", *OPPENHEIM]) == 0
    out = capsys.readouterr().out
    assert "collapse acceleration: 0.3700 g" in out  # paper p. 2126: 0.37 g
    for line in ("A  joint   0  intrados", "B  joint   3  extrados", "C  joint   5  intrados",
                 "D  joint   7  extrados"):
        assert line in out
    assert "asymmetric" in out
    assert "friction demand at the onset of motion: 0.495" in out  # paper p. 2131: 0.50


def test_static_json(capsys):
    assert cli_main.main(["static", *OPPENHEIM, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert paper.ONSET_ACCELERATION.within(data["collapse_acceleration_g"])
    assert [(h["joint"], h["face"]) for h in data["hinges"]] == [
        (0, "intrados"), (3, "extrados"), (5, "intrados"), (7, "extrados")]
    assert all({"x", "y"} <= h.keys() for h in data["hinges"])
    assert data["symmetric"] is False
    assert paper.STATIC_FRICTION.within(data["min_friction"])
    assert data["static_collapse_acceleration_g"] == pytest.approx(
        data["kinematic_collapse_acceleration_g"], abs=1e-6)


def test_static_plot(tmp_path, capsys):
    target = tmp_path / "collapse.png"
    assert cli_main.main(["static", *OPPENHEIM, "--plot", str(target)]) == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert str(target) in capsys.readouterr().out


def test_min_thickness_json(capsys):
    """Milankovitch / Heyman: the semicircle's minimum thickness (tests/paper/test_static.py)."""
    assert cli_main.main(["min-thickness", "--embrace", "180", "--voussoirs", "200",
                          "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert paper.SEMICIRCLE_MIN_THICKNESS.within(data["min_thickness_ratio"])


@pytest.mark.parametrize(
    "args, names",
    [
        (["--thickness", "0"], ("--thickness", "[1e-05, 20) m")),
        (["--thickness", "-1"], ("--thickness", "[1e-05, 20) m")),
        (["--thickness", "20"], ("--thickness", "[1e-05, 20) m")),
        (["--thickness", "25"], ("--thickness", "[1e-05, 20) m")),
        (["--embrace", "0"], ("--embrace", "[0.001, 240] degrees")),
        (["--embrace", "-10"], ("--embrace", "[0.001, 240] degrees")),
        (["--embrace", "250"], ("--embrace", "[0.001, 240] degrees")),
        (["--voussoirs", "2"], ("--voussoirs", "from 3 to")),
        (["--voussoirs", "2.5"], ("--voussoirs", "whole number")),
        (["--thickness", "abc"], ("--thickness", "expected a number")),
        (["--radius", "nan"], ("--radius", "finite number")),
        (["--radius", "0"], ("--radius", "[0.001, 10000] m")),
    ],
)
def test_bad_input_is_one_line_exit_2(args, names, capsys):
    assert cli_main.main(["static", *args]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err
    for name in names:
        assert name in lines[0]
    assert captured.out == ""


@pytest.mark.parametrize("args, name", [
    (["--embrace", "0"], "--embrace"), (["--embrace", "241"], "--embrace"),
    (["--voussoirs", "2"], "--voussoirs"), (["--voussoirs", "x"], "--voussoirs"),
])
def test_min_thickness_bad_input(args, name, capsys):
    assert cli_main.main(["min-thickness", *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and name in err[0]


def test_too_thin_names_the_minimum(capsys):
    """Oppenheim's geometry at t/R = 0.05 cannot stand: 7 voussoirs need t/R >= 0.0592."""
    assert cli_main.main(["static", *OPPENHEIM[:2], "--thickness", "0.5", *OPPENHEIM[4:]]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "t/R >= 0.0592" in err[0] and "t >= 0.5921 m" in err[0]


def test_installed_script_reports_bad_input():
    """The console script itself: one line on stderr, status 2, no traceback."""
    script = Path(sys.executable).parent / "archquake"
    if not script.exists():
        pytest.skip("the archquake console script is not installed in this environment")
    proc = subprocess.run([str(script), "static", "--thickness", "0"], capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert len(proc.stderr.strip().splitlines()) == 1
    assert "--thickness" in proc.stderr and "Traceback" not in proc.stderr


def test_plot_arch_moved_voussoirs():
    """plot_arch draws rigidly moved voussoirs: a zero displacement leaves the outline where it
    is, and a rotation about the centroid keeps every distance to it."""
    import numpy as np

    from archquake.geometry import Arch
    from archquake.plotting.arch import moved_outline, plot_arch

    arch = Arch(10.0, 1.5, 2.75, 7)
    outline, centroid = arch.voussoir_outline(2), arch.voussoir_centroids[2]
    assert np.allclose(moved_outline(outline, centroid, [0, 0, 0]), outline)
    moved = moved_outline(outline, centroid, [0.3, -0.2, 0.4])
    assert np.allclose(np.linalg.norm(moved - (centroid + [0.3, -0.2]), axis=1),
                       np.linalg.norm(outline - centroid, axis=1))
    positions = np.zeros((7, 3))
    positions[:, 2] = 0.05
    ax = plot_arch(arch, voussoir_positions=positions, show_ghost=True,
                   hinges=np.array([[0.0, 10.75]]), hinge_labels=["H"])
    assert len(ax.patches) == 7 * 2 + 2  # ghosts, moved voussoirs, two supports
    with pytest.raises(ValueError, match=r"shape \(7, 3\)"):
        plot_arch(arch, ax, voussoir_positions=np.zeros((6, 3)))
