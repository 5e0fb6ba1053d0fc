"""The command line starts without importing the commands it does not run.

Oracle: ``sys.modules`` of a fresh interpreter after ``main([...])`` (which starts without
numba, scipy, matplotlib or any command module), and argparse's own record of the help each
command module registers (the registry's summaries must be those strings)."""

from __future__ import annotations

import argparse
import importlib
import json
import os
import subprocess
import sys

import pytest

from archquake.cli import main as cli_main

HEAVY = ("numba", "scipy", "matplotlib", "dask", "distributed", "pyarrow", "pandas")


def _modules_after(argv: list[str]) -> tuple[int, set[str]]:
    code = ("import sys, json\nfrom archquake.cli.main import main\n"
            f"try:\n    code = main({argv!r})\nexcept SystemExit as e:\n    code = e.code\n"
            "print(json.dumps([code, sorted(sys.modules)]))")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True)
    code, modules = json.loads(done.stdout.strip().splitlines()[-1])
    return code, set(modules)


def _heavy(modules: set[str]) -> list[str]:
    return sorted(m for m in modules if m.split(".")[0] in HEAVY)


@pytest.mark.parametrize("argv", [["--version"], ["--help"], []])
def test_top_level_imports_no_command_and_no_numerics(argv):
    code, modules = _modules_after(argv)
    assert code == (2 if not argv else 0)
    assert _heavy(modules) == []
    assert not any(m.startswith("archquake.cli.cmd_") for m in modules)


def test_importing_the_command_line_imports_no_numerics():
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    code = "import sys, json\nimport archquake.cli.main\nprint(json.dumps(sorted(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True)
    modules = set(json.loads(done.stdout.strip().splitlines()[-1]))
    assert "archquake.cli.main" in modules and _heavy(modules) == []


@pytest.mark.parametrize("command", ["run", "domain", "friction", "thrust", "ida", "sweep", "warm"])
def test_the_help_of_a_command_that_runs_kernels_imports_none(command):
    code, modules = _modules_after([command, "--help"])
    assert code == 0
    assert _heavy(modules) == []


def test_static_analysis_imports_no_numba():
    """The equivalent static analysis is linear programming: no kernel, so no numba."""
    code, modules = _modules_after(["static", "--json"])
    assert code == 0
    assert "scipy.optimize" in modules  # the linear program ran (the check can fail)
    assert _heavy(modules) == sorted(m for m in modules if m.split(".")[0] == "scipy")


#: What a time history does not use: plotting, clusters, tables, the other studies' packages.
#: (archquake.sweeps is imported: --model reads its Model.)
NOT_IN_A_RUN = ("matplotlib", "dask", "distributed", "pyarrow", "pandas", "scipy.stats",
                "scipy.integrate", "scipy.signal", "archquake.plotting", "archquake.ida",
                "archquake.reproduce", "archquake.assess")


@pytest.mark.parametrize("extra", [["--model", "fourlink"], ["--t-end", "0.1"]])
def test_a_run_imports_only_what_it_uses(extra):
    code, modules = _modules_after(["run", "--pulse", "step", "--magnitude", "1.0", "--duration",
                                    "0.27", "--json", *extra])
    assert code == 0
    assert "numba" in modules  # the kernels ran (the check can fail)
    assert sorted(m for m in modules if m.startswith(NOT_IN_A_RUN)) == []
    if extra[0] == "--model":  # the four-link model builds no blocks, needs no run-length rule
        others = ("archquake.dem", "archquake.compare", "archquake.domains")
        assert sorted(m for m in modules if m.startswith(others)) == []


def test_a_command_imports_its_own_module_only():
    code, modules = _modules_after(["min-thickness", "--help"])
    assert code == 0
    assert {m for m in modules if m.startswith("archquake.cli.cmd_")} == {"archquake.cli.cmd_min_thickness"}


def test_summaries_are_the_help_each_module_registers():
    assert set(cli_main.SUMMARIES) == set(cli_main.COMMANDS)
    for name in cli_main.COMMANDS:
        sub = argparse.ArgumentParser().add_subparsers()
        importlib.import_module(f"archquake.cli.cmd_{name}").register(sub)
        (choice,) = sub._choices_actions  # the one entry --help lists
        assert choice.dest == cli_main.command_name(name)
        assert choice.help == cli_main.SUMMARIES[name], name


def test_unknown_command_is_a_usage_error(capsys):
    assert cli_main.main(["no-such-command"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'no-such-command'" in err
    assert err.count("\n") == 1


def test_full_parser_registers_every_command():
    parser = cli_main.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert list(sub.choices) == [cli_main.command_name(n) for n in cli_main.COMMANDS]
    # every entry is the command's full parser (each takes --json, as every command must)
    for name, p in sub.choices.items():
        assert any("--json" in a.option_strings for a in p._actions), name


def test_the_program_selects_agg_and_main_leaves_the_backend_alone():
    """The console script writes figures only: Agg, whatever the environment says; ``main()``
    called from a session keeps the session's backend (oracle: ``matplotlib.get_backend()``)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="svg")
    program = ("from archquake.cli import main as m\nm.main = lambda: 0\ntry:\n    m.entry_point()\n"
               "except SystemExit:\n    pass\nimport matplotlib\nprint(matplotlib.get_backend())")
    session = ("from archquake.cli.main import main\nmain(['min-thickness', '--json'])\n"
               "import matplotlib\nprint(matplotlib.get_backend())")
    outs = [subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                           check=True).stdout.strip().splitlines()[-1].lower() for code in (program, session)]
    assert outs == ["agg", "svg"]
