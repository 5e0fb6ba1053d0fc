"""``archquake reproduce``: the paper regenerated, side by side, in one command.

Runs every study of De Lorenzis, DeJong & Ochsendorf (2007) on Oppenheim's arch, writes the
figures (Figures 4 to 11, with the distinct-element overlays) and a report (report.md and one
self-contained report.html) setting each number the paper states beside archquake's, with its
tolerance and a pass/fail mark. Finished studies are cached in DIR/cache/ and reused by a rerun.
Exit status 0 when no line fails, 1 when some line fails, 2 on a usage error.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from archquake.cli.common import print_json


def register(sub: argparse._SubParsersAction) -> None:
    from archquake.reproduce import STUDIES

    p = sub.add_parser(
        "reproduce",
        help="regenerate the paper: every study, its figures and a side-by-side report",
        description=__doc__.split("\n\n")[1] + " Studies: " + ", ".join(s.name for s in STUDIES) + ".",
    )
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder (created)")
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
    from archquake.reproduce import run_studies

    def progress(line: str) -> None:
        print(f"[reproduce] {line}", file=sys.stderr if args.json else sys.stdout, flush=True)

    rep = run_studies(args.out, quick=args.quick, force=args.force, only=args.only, progress=progress)
    c = rep.counts
    if args.json:
        print_json(rep.to_dict())
    else:
        print(
            f"[reproduce] {c['pass']} pass, {c['fail']} fail, {c['departure']} departures, "
            f"{c['n/a']} n/a; {rep.computed} of {len(rep.runs)} studies computed, the rest cached"
        )
        print(f"[reproduce] report: {rep.report_html} (and {rep.report_md})")
    return 1 if c["fail"] else 0


def demo_step(out: Path, quick: bool) -> list[Path]:
    """``archquake demo`` step: the reproduction (quick unless ``--full``) into ``out``; progress
    on stderr (the demo's stdout may be JSON). Returns the two reports."""
    from archquake.reproduce import run_studies

    rep = run_studies(out, quick=quick, progress=lambda line: print(f"[demo]   {line}", file=sys.stderr))
    c = rep.counts
    print(f"[demo]   paper regenerated: {c['pass']} pass, {c['fail']} fail, {c['departure']} departures, "
          f"{c['n/a']} n/a", file=sys.stderr)
    return [rep.report_html, rep.report_md]
