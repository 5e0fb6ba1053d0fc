"""``archquake demo``: ``archquake reproduce --quick --out DIR`` (DIR = out/ by default) plus
DIR/rocking.gif, the arch of Figure 4(d) rocking to rest. What ``make demo`` runs."""

from __future__ import annotations

import argparse
from pathlib import Path

from archquake.cli.cmd_reproduce import reproduce
from archquake.cli.common import output_folder


def register(sub: argparse._SubParsersAction) -> None:
    d = sub.add_parser(
        "demo",
        help="reproduce Oppenheim's arch: figures and a short report",
        description="'archquake reproduce --quick' into one folder, plus DIR/rocking.gif: the arch of "
        "Figure 4(d) rocking to rest. The report is DIR/report.html.",
    )
    d.add_argument(
        "--out", type=output_folder, default=Path("out"), metavar="DIR", help="output folder (default out/)"
    )
    d.add_argument("--json", action="store_true", help="print the results as JSON on stdout")
    d.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """`reproduce` in quick mode, then the animation of
    Figure 4(d)."""
    from archquake.reproduce.figure4 import animation
    from archquake.validation.paper import oppenheim_arch

    def gif(out: Path) -> dict:
        return {"animation": str(animation(oppenheim_arch(), out / "rocking.gif", quick=True))}

    return reproduce(args.out, quick=True, json=args.json, prefix="demo", extra=gif)
