"""``archquake demo``: the main job. Oppenheim's arch reproduced into one folder.

Each capability contributes a step: a function ``step(out: Path, quick: bool) -> list[Path]``
listed in ``STEPS`` as ``(title, "module:function")``; steps are imported lazily so one
capability's import cost does not slow another's.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from pathlib import Path

STEPS: list[tuple[str, str]] = [
    ("Equivalent static analysis of Oppenheim's arch", "archquake.cli.demo_static:demo_step"),
    ("The arch in motion (Figure 4) and an animation", "archquake.cli.demo_dynamics:demo_step"),
    ("Line of thrust during motion (Figure 8) and friction demand", "archquake.cli.demo_thrust:demo_step"),
    ("Failure domains (Figures 5, 6, 7, 11) and the scale effect", "archquake.cli.demo_domains:demo_step"),
    ("Analytical vs distinct-element model (Figures 4b-d, 9, 10; 6, 11 with --full)",
     "archquake.cli.demo_compare:demo_step"),
    ("The paper regenerated side by side (archquake reproduce)", "archquake.cli.cmd_reproduce:demo_step"),
]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("demo", help="reproduce Oppenheim's arch: figures and a short report")
    p.add_argument("--out", type=Path, default=Path("out"), help="output folder (default out/)")
    p.add_argument("--full", action="store_true", help="full resolution (slower)")
    p.add_argument("--json", action="store_true",
                   help="print a JSON summary (steps, files, seconds) on stdout; progress goes to stderr")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    report = ["# archquake demo: Oppenheim's arch", ""]
    progress = sys.stderr if getattr(args, "json", False) else sys.stdout
    steps = []
    for title, target in STEPS:
        module_name, func_name = target.split(":")
        t0 = time.perf_counter()
        print(f"[demo] {title} ...", flush=True, file=progress)
        files = getattr(importlib.import_module(module_name), func_name)(out, not args.full)
        dt = time.perf_counter() - t0
        print(f"[demo]   done in {dt:.1f} s: " + ", ".join(str(f) for f in files), flush=True,
              file=progress)
        written.extend(files)
        steps.append({"title": title, "seconds": round(dt, 3), "files": [str(f) for f in files]})
        report.append(f"- {title} ({dt:.1f} s): " + ", ".join(f.name for f in files))
    (out / "index.md").write_text("\n".join(report) + "\n")
    print(f"[demo] wrote {len(written)} files to {out}/ (index: {out / 'index.md'})", file=progress)
    if (out / "report.html").is_file():
        print(f"[demo] the paper side by side: {out / 'report.html'}", file=progress)
    if getattr(args, "json", False):
        from archquake.cli.common import print_json

        print_json({"out": str(out), "index": str(out / "index.md"), "steps": steps})
    return 0
