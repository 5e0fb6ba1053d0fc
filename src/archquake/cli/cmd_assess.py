"""``archquake assess``: one report on the user's own arch.

Reads ARCH.toml (the arch, the seismic input and the options; see docs/assess.md), validates it
before computing anything, and writes DIR/report.html (self-contained), DIR/report.md,
DIR/results.json and DIR/figures/: the arch, its static capacity, the pulse failure domains,
the records' IDA and fragility, the distinct-element check, the models' validity and a verdict.
Finished sections are cached in DIR/cache/ and reused by a rerun.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from archquake.cli.common import output_folder, path_argument, print_json


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "assess",
        help="assess your own arch: statics, pulses, records, DEM check, validity, verdict",
        description=__doc__.split("\n\n")[1],
    )
    p.add_argument("file", type=path_argument, metavar="ARCH.toml", help="the assessment file")
    p.add_argument("--out", type=output_folder, required=True, metavar="DIR", help="output folder (created)")
    p.add_argument("--quick", action="store_true",
                   help="coarse domains, four records of the suite, fewer DEM runs (about a "
                        "minute)")
    p.add_argument("--model", default=None, metavar="{rigid,fourlink}",
                   help="the model of the verdicts, instead of the file's [options] model: "
                        "'rigid' (default), the chain of rigid voussoirs; 'fourlink', the "
                        "paper's four-link mechanism (needs a restitution the arch may not have)")
    p.add_argument("--force", action="store_true", help="recompute sections cached in DIR/cache/")
    p.add_argument("--json", action="store_true", help="print results.json on stdout")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress lines on stderr (warnings about the input still print)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    return assess(args.file, args.out, quick=args.quick, force=args.force, json=args.json,
                  model=args.model, progress=not args.no_progress)


def assess(file: Path, out: Path, *, quick: bool, json: bool, force: bool = False,
           prefix: str = "assess", model: str | None = None, progress: bool = True) -> int:
    """Validate ``file``, run the assessment into ``out``, print where the report is;
    ``model`` (``--model``) replaces the file's [options] model; ``progress``: the progress
    lines on stderr (the input's warnings print either way)."""
    from dataclasses import replace

    from archquake.assess import load_config
    from archquake.assess.config import ASSESS_MODELS
    from archquake.errors import InvalidParameterError
    from archquake.models import model_of, takes

    config = load_config(file)  # every input error is raised here, before any computation
    if model is not None:
        word = model_of(model, model_name="--model").value
        if word not in ASSESS_MODELS:
            raise InvalidParameterError(f"--model must be rigid or fourlink for assess, got "
                                        f"{word!r} (the DEM is the check: [options] dem = true)")
        if not takes(word, "restitution") and config.restitution is not None:
            raise InvalidParameterError(f"--model {word}: the file prescribes [options] "
                                        "restitution, which applies to the four-link model only")
        config = replace(config, model=word)
    from archquake.assess import run_assessment

    for note in config.notes:
        print(f"[{prefix}] warning: {config.source}: {note}", file=sys.stderr, flush=True)

    def say(line: str) -> None:
        # one write, the newline with it: an interrupt between the two writes of a print would
        # leave the line open, and "archquake: interrupted" would follow on the same line
        sys.stderr.write(f"[{prefix}] {line}\n")
        sys.stderr.flush()

    rep = run_assessment(config, out, quick=quick, force=force,
                         progress=say if progress else None)
    if json:
        print_json(rep.to_dict())
        return 0
    v = rep.verdict
    print(f"[{prefix}] verdict: {v['text']}")
    print(f"[{prefix}] report: {Path(out) / 'report.html'} (and report.md, results.json)")
    return 0
