"""``archquake warm``: compile every numba kernel once, so that no later command waits for it."""

from __future__ import annotations

import argparse

from archquake.cli.common import print_json


def register(sub: argparse._SubParsersAction) -> None:
    from archquake.warm import WORKLOADS

    p = sub.add_parser(
        "warm",
        help="compile the numerical kernels once (after installing), so that no command waits",
        description=(
            "Compile every numerical kernel (numba) on a tiny problem and keep the machine code "
            "in numba's cache, so that the first 'archquake run' of each model loads its kernels "
            "instead of compiling them (10-40 s per model). Run once after installing; 'make "
            "demo' does. Running it again only loads the kernels. The cache is numba's: "
            "NUMBA_CACHE_DIR if set, else beside the installed package if writable, else "
            "~/.cache/numba (each user of a read-only install warms their own)."
        ),
    )
    p.add_argument("--only", nargs="+", choices=tuple(WORKLOADS), metavar="MODEL",
                   help=f"warm these only: {', '.join(WORKLOADS)} (default all)")
    p.add_argument("--json", action="store_true", help="print the report as JSON on stdout")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from archquake.warm import WarmStep, warm

    def progress(step: WarmStep) -> None:
        if not args.json:
            print(f"{step.name:<10} {step.seconds:6.1f} s ({step.cpu_seconds:6.1f} s CPU)  "
                  f"{step.compiled:3d} compiled, {step.loaded:3d} loaded from the cache",
                  flush=True)

    report = warm(args.only, progress=progress)
    if args.json:
        print_json(report.to_dict())
        return 0
    print(f"{'total':<10} {report.seconds:6.1f} s ({report.cpu_seconds:6.1f} s CPU)  "
          f"{report.compiled:3d} kernel signatures compiled")
    for path in report.cache_dirs:
        print(f"cache      {path}")
    return 0
