"""``archquake reproduce``: the paper regenerated, side by side, in one
command.

Runs every study of De Lorenzis, DeJong & Ochsendorf (2007) on Oppenheim's arch, writes the
figures (Figures 4 to 11, with the distinct-element overlays) and a report (report.md and one
self-contained report.html) setting each number the paper states beside archquake's, with its
tolerance and a pass/fail mark. Finished studies are cached in DIR/cache/ and reused by a rerun.
Exit status 0 when no line fails, 1 when some line fails, 2 on a usage error.

``archquake demo`` (cli/cmd_demo.py) runs `reproduce` in quick mode plus an animation.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

from archquake.cli.common import output_folder, print_json


def register(sub: argparse._SubParsersAction) -> None:
    from archquake.reproduce import STUDIES

    p = sub.add_parser(
        "reproduce",
        help="regenerate the paper: every study, its figures and a side-by-side report",
        description=__doc__.split("\n\n")[1] + " Studies: " + ", ".join(s.name for s in STUDIES) + ".",
    )
    p.add_argument("--out", type=output_folder, required=True, metavar="DIR", help="output folder (created)")
    p.add_argument(
        "--quick",
        action="store_true",
        help="coarse domains and fewer distinct-element runs (about a minute)",
    )
    p.add_argument("--force", action="store_true", help="recompute studies even if cached in DIR/cache/")
    p.add_argument("--only", nargs="+", metavar="STUDY", help="run only these studies")
    p.add_argument("--json", action="store_true", help="print the results as JSON on stdout")
    p.set_defaults(func=run)



def run(args: argparse.Namespace) -> int:
    return reproduce(args.out, quick=args.quick, force=args.force, only=args.only, json=args.json)


def reproduce(
    out: Path,
    *,
    quick: bool,
    json: bool,
    force: bool = False,
    only=None,
    prefix: str = "reproduce",
    extra: Callable[[Path], dict] | None = None,
) -> int:
    """Run the studies into ``out``, print the summary (or the JSON), return the exit status.

    ``extra(out)`` writes more files after the report (``archquake demo``: the animation) and
    returns what ``--json`` adds (file paths)."""
    from archquake.cli.common import check_output_folder
    from archquake.reproduce import run_studies

    check_output_folder(Path(out), "--out")  # before any study: a file, or an unwritable place, fails now
    stream = sys.stderr if json else sys.stdout

    def progress(line: str) -> None:
        print(f"[{prefix}] {line}", file=stream, flush=True)

    rep = run_studies(out, quick=quick, force=force, only=only, progress=progress)
    more = {} if extra is None else extra(Path(out))
    c = rep.counts
    if json:
        print_json(dict(rep.to_dict(), **more))
    else:
        print(
            f"[{prefix}] {c['pass']} pass, {c['fail']} fail, {c['departure']} departures, "
            f"{c['n/a']} n/a; {rep.computed} of {len(rep.runs)} studies computed, the rest cached"
        )
        print(f"[{prefix}] report: {rep.report_html} (and {rep.report_md})")
        for key, path in more.items():
            print(f"[{prefix}] {key}: {path}")
    return 1 if c["fail"] else 0
