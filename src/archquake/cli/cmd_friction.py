"""``archquake friction``: the friction coefficient the joints need during the motion
(paper p. 2131)."""

from __future__ import annotations

import argparse
import contextlib
import sys

from archquake.cli.common import (
    add_arch_arguments,
    add_ground_motion_arguments,
    add_impact_arguments,
    add_output_arguments,
    arch_from_args,
    ground_motion_from_args,
    impact_from_args,
    print_json,
)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "friction",
        help="least friction coefficient that prevents sliding during the motion (paper p. 2131)",
        description=(
            "Simulate the arch and find the largest |shear| / normal force over every joint and "
            "instant of the motion (from the line of thrust of the moving arch), with the joint "
            "and time where it occurs, beside the demand of the equivalent static analysis."
        ),
    )
    add_arch_arguments(p)
    add_ground_motion_arguments(p)
    add_impact_arguments(p)
    add_output_arguments(p, plot=False)
    p.set_defaults(func=run)


#: Work (instants x voussoirs) above which a run off a terminal prints its progress as lines:
#: about half a minute (Oppenheim's arch at 1000 voussoirs examines ~30 instants a second).
LINE_PROGRESS_WORK = 100_000


@contextlib.contextmanager
def _progress_bar(voussoirs: int = 0):
    """A progress bar on stderr over the instants examined (a long record has thousands of
    instants, the locked ones a few linear programs each). Off a terminal, where the bar is not
    drawn, a long examination (:data:`LINE_PROGRESS_WORK`) prints a line at each quarter."""
    from tqdm import tqdm

    bar = tqdm(total=0, desc="instants", unit="", file=sys.stderr, disable=None, leave=False)
    said = set()

    def update(done: int, total: int) -> None:
        if bar.disable:
            if total * voussoirs > LINE_PROGRESS_WORK:
                quarter = 4 * done // max(total, 1)
                if quarter not in said:
                    said.add(quarter)
                    print(f"archquake: friction: {done} of {total} instants examined "
                          f"({voussoirs} voussoirs)", file=sys.stderr, flush=True)
            return
        if bar.total != total:
            bar.total = total
        bar.update(done - bar.n)

    try:
        yield update
    finally:
        bar.close()


def run(args: argparse.Namespace) -> int:
    from archquake.thrust.friction import friction_demand

    arch = arch_from_args(args)
    motion = ground_motion_from_args(args)
    with _progress_bar(arch.voussoirs) as progress:
        result = friction_demand(arch, motion, progress=progress, **impact_from_args(args))
    if args.json:
        out = result.to_dict()
        out["arch"] = arch.describe()
        out["motion"] = motion.to_dict()
        print_json(out)
        return 0
    n = arch.voussoirs
    place = {0: " (left springing)", n: " (right springing)"}
    print(f"{motion.name}: {result.simulation.outcome.value}")
    print(f"friction needed during the motion  {result.max_friction_demand:.3f} at joint "
          f"{result.joint}{place.get(result.joint, '')}, t = {result.time:.3f} s")
    if result.onset_demand is not None:
        print(f"at the onset of hinging            {result.onset_demand:.3f} at joint {result.onset_joint}")
    print(f"equivalent static analysis         {result.static_friction_demand:.3f} at joint "
          f"{result.static_joint}")
    if result.tension_time is not None:
        print(f"note: from t = {result.tension_time:.3f} s joint {result.tension_joint} would need "
              "tension (the mechanism loses contact); later instants are left out")
    return 0
