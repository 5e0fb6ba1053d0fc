"""Entry point of the ``archquake`` command.

Each sub-command lives in its own module ``archquake.cli.cmd_<name>`` exposing
``register(subparsers) -> None``; the parser it adds sets ``func=run`` where
``run(args) -> int``. Add a new command by adding its module name to ``COMMANDS``.

User errors (any :class:`~archquake.errors.ArchquakeError`, and malformed arguments) print
one line on stderr and exit with status 2; anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from archquake import __version__
from archquake.errors import ArchquakeError

#: Sub-command modules, in the order ``--help`` lists them.
COMMANDS: tuple[str, ...] = (
    "static",
    "min_thickness",
    "run",
    "record",
    "records",
    "sweep",
    "ida",
    "thrust",
    "friction",
    "domain",
    "reproduce",
    "demo",
)


class UsageError(ArchquakeError):
    """A malformed command line."""


class OneLineParser(argparse.ArgumentParser):
    """argparse that reports a bad command line as one line and exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: {message} (see '{self.prog} --help')")


def build_parser() -> argparse.ArgumentParser:
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
        module = importlib.import_module(f"archquake.cli.cmd_{name}")
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 user error)."""
    try:
        parser = build_parser()
        args = parser.parse_args(list(argv) if argv is not None else None)
        return int(args.func(args) or 0)
    except ArchquakeError as exc:
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


def entry_point() -> None:
    """Console-script entry point."""
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    entry_point()
