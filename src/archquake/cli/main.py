"""Entry point of the ``archquake`` command.

Each sub-command lives in its own module ``archquake.cli.cmd_<name>`` exposing
``register(subparsers) -> None``; the parser it adds sets ``func=run`` where
``run(args) -> int``. Add a new command by adding its module name to ``COMMANDS`` and its
one-line summary to ``SUMMARIES``.

The command line starts at once: only the module of the command being run is imported (with
the numerics it needs). The top-level ``--help`` lists the commands from ``SUMMARIES`` and
``--version`` needs nothing, so neither imports numba, scipy or matplotlib.

User errors (any `ArchquakeError`, and malformed arguments) print
one line on stderr and exit with status 2; anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path

from archquake import __version__
from archquake.cli.input_warnings import print_input_warnings, take_input_warnings
from archquake.errors import ArchquakeError, UsageError

#: Sub-command modules, in the order ``--help`` lists them.
COMMANDS: tuple[str, ...] = (
    "static",
    "check",
    "min_thickness",
    "capacity",
    "run",
    "record",
    "records",
    "spectrum",
    "sweep",
    "ida",
    "thrust",
    "friction",
    "domain",
    "reproduce",
    "assess",
    "demo",
    "warm",
)

#: The line each command shows in ``archquake --help``, by module name (the command's name is
#: the module's with ``-`` for ``_``). It is the help its module registers; a test holds the two
#: equal, so that listing the commands imports none of them.
SUMMARIES: dict[str, str] = {
    "static": "equivalent static analysis: collapse acceleration (g), hinges, friction demand",
    "check": "code check of the arch's collapse mechanism (NTC 2018 §8.7.1 kinematic analysis)",
    "min_thickness": "minimum thickness ratio t/R of an arch under its own weight",
    "capacity": "traffic capacity: the load multiplier that collapses the arch, and its critical position",
    "run": "time history of the arch under a pulse or an accelerogram (paper Eqs. 2-7)",
    "record": "check an accelerogram file (.AT2 or CSV): points, dt, PGA, PGV, Arias, Sa(T), ...",
    "sweep": "run a study file's grid of cases into a resumable SQLite store",
    "thrust": "line of thrust of the moving arch at chosen times (paper Figure 8)",
    "friction": "least friction coefficient that prevents sliding during the motion (paper p. 2131)",
    "domain": "failure domain: pulse magnitudes (g) and durations (s) that collapse the arch",
    "reproduce": "regenerate the paper: every study, its figures and a side-by-side report",
    "assess": "assess your own arch: statics, pulses, records, DEM check, validity, verdict",
    "demo": "reproduce Oppenheim's arch: figures and a short report",
    "records": "list the record suites (FEMA P695 sets, folders) with their intensity measures",
    "spectrum": "a site's elastic spectrum (NTC 2018, EN 1998-1): Sa (g) and Sd (m) against T (s)",
    "ida": "incremental dynamic analysis of the arch under a record suite, and fragility",
    "warm": "compile the numerical kernels once (after installing), so that no command waits",
}


def command_name(module: str) -> str:
    """The command a module of ``COMMANDS`` registers (``min_thickness`` -> ``min-thickness``)."""
    return module.replace("_", "-")


def _requested(argv: Sequence[str]) -> str | None:
    """The module of the command on the command line (its first word that is not an option),
    or None (no command, ``--help``, ``--version`` or an unknown word argparse will reject)."""
    by_name = {command_name(module): module for module in COMMANDS}
    for word in argv:
        if word == "--":
            return None
        if not word.startswith("-"):
            return by_name.get(word)
    return None


class OneLineParser(argparse.ArgumentParser):
    """argparse that reports a bad command line as one line and exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        # main() prints the one "archquake: error: " prefix; name the command, not the program
        command = self.prog.removeprefix("archquake").strip()
        where = f"{command}: " if command else ""
        raise UsageError(f"{where}{message} (see '{self.prog} --help')")


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The parser for ``argv``: the full parser of the command it names (its module imported),
    a one-line entry for every other command.

    Parameters
    ----------
    argv : sequence of str, optional
        The command line without the program name; None registers every command in full
        (imports all their modules, as documentation tools need).
    """
    wanted = _requested(argv) if argv is not None else None
    parser = OneLineParser(
        prog="archquake",
        description=(
            "Masonry arches under impulse base motion and earthquakes (De Lorenzis, DeJong & "
            "Ochsendorf 2007). Lengths in m, times in s, angles in degrees, accelerations in g."
        ),
    )
    parser.add_argument("--version", action="version", version=f"archquake {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    sub.required = True
    for name in COMMANDS:
        if argv is None or name == wanted:
            importlib.import_module(f"archquake.cli.cmd_{name}").register(sub)
        else:
            sub.add_parser(command_name(name), help=SUMMARIES.get(name), add_help=False)
    return parser


def _show(caught: list[warnings.WarningMessage]) -> None:
    """Print archquake's own deprecation warnings as one line each on stderr; show the others
    as Python would have."""
    seen = set()
    for w in caught:
        text = str(w.message)
        if issubclass(w.category, DeprecationWarning) and "archquake" in Path(w.filename).parts:
            if text not in seen:
                seen.add(text)
                print(f"archquake: warning: {text}", file=sys.stderr, flush=True)
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 user error)."""
    argv = list(argv) if argv is not None else sys.argv[1:]
    previous = _stop_on_sigterm()
    take_input_warnings()  # none left from an earlier call in the same process
    try:
        parser = build_parser(argv)
        args = parser.parse_args(argv)
        with warnings.catch_warnings(record=True) as caught:
            # the words of earlier versions (a model named "analytical"...) warn once a run
            warnings.filterwarnings("always", category=DeprecationWarning, module=r"archquake\.")
            status = int(args.func(args) or 0)
        _show(caught)
        print_input_warnings()  # after the command: a refusal stays one line
        return status
    except ArchquakeError as exc:
        take_input_warnings()
        print(f"archquake: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("archquake: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the reader went away (e.g. piped into `head`): stop quietly, as Unix tools do
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _sigterm(signum, frame) -> None:
    raise KeyboardInterrupt  # the command stops as on Ctrl-C: workers ended, stores closed


def _stop_on_sigterm():
    """Treat SIGTERM as Ctrl-C while a command runs (in the main thread only): the command's
    cleanup runs (worker processes are ended, a sweep says how to resume), where the default
    action would end this process alone and leave its workers waiting. Returns the previous
    handler (None if not installed)."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, _sigterm)


def entry_point() -> None:
    """Console-script entry point.

    The program only writes figures to files, so it selects matplotlib's Agg backend (through
    the environment: free if no figure is drawn, inherited by worker processes). ``main()``
    called from a session leaves the session's backend alone.
    """
    os.environ["MPLBACKEND"] = "Agg"
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    entry_point()
