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
    add_model_argument,
    add_output_arguments,
    arch_from_args,
    ground_motion_from_args,
    impact_from_args,
    model_from_args,
    print_json,
)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "friction",
        help="least friction coefficient that prevents sliding during the motion (paper p. 2131)",
        description=(
            "Simulate the arch and find the largest |shear| / normal force over every joint and "
            "instant of the motion, with the joint and time where it occurs, beside the demand "
            "of the equivalent static analysis: by default from the joint forces of the chain "
            "of rigid voussoirs (--model rigid; where they are unique, not at an impact, and "
            "the joint carries at least 1 % of the weight), or from the line of thrust of the "
            "paper's four-link mechanism (--model fourlink)."
        ),
    )
    add_arch_arguments(p)
    add_ground_motion_arguments(p)
    add_model_argument(p, models=("rigid", "fourlink"))
    from archquake.cli.loads_options import add_loads_arguments

    add_loads_arguments(p)
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
    drawn, a long examination (`LINE_PROGRESS_WORK`) prints a line at each quarter."""
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
    from archquake.models import spec
    from archquake.thrust.friction import friction_demand

    model = model_from_args(args, models=("rigid", "fourlink"))
    arch = arch_from_args(args)
    motion = ground_motion_from_args(args)
    from archquake.cli.loads_options import dynamic_loads_from_args

    loads = dynamic_loads_from_args(args, arch, model)
    if spec(model).blocks:  # the rigid chain, else the four-link model
        return _run_rigid(args, arch, motion, loads)
    with _progress_bar(arch.voussoirs) as progress:
        result = friction_demand(arch, motion, progress=progress, **impact_from_args(args))
    if args.json:
        out = {"model": model.value, **result.to_dict()}
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


def _run_rigid(args: argparse.Namespace, arch, motion, loads=None) -> int:
    """``--model rigid``: the friction demand of the chain of rigid voussoirs' joint forces
    (`archquake.rigid.forces`, with its reporting rule), run to a verdict; with ``loads``
    the chain carries them and the static analysis beside it too."""
    import numpy as np

    from archquake.cli.common import length_option, rigid_work
    from archquake.limit import limit_analysis
    from archquake.rigid.forces import joint_numbers, on_arch_joints
    from archquake.rigid.model import DEFAULT_TIME_STEP
    from archquake.rigid.run import rigid_to_verdict, rigid_window

    progress = rigid_work("friction", arch, motion, rigid_window(arch, motion)[1],
                          DEFAULT_TIME_STEP, length=length_option(args))
    run = rigid_to_verdict(arch, motion, progress=progress, loads=loads)
    forces = run.joint_forces
    summary = on_arch_joints(forces.summary(), joint_numbers(run), arch.voussoirs + 1)
    during = forces.friction_demand[forces.times <= motion.duration]
    ground = (float(np.nanmax(during)) if during.size and np.any(np.isfinite(during))
              else None)
    static = limit_analysis(arch, loads=loads)
    out = {"model": "rigid", "outcome": run.outcome.value,
           "max_friction_demand": summary["max_friction_demand"],
           "joint": summary["max_friction_demand_joint"],
           "time_s": summary["max_friction_demand_time_s"],
           "max_friction_demand_excitation": ground,
           "static_friction_demand": static.min_friction,
           "static_joint": static.min_friction_joint,
           "joint_forces": summary, "arch": arch.describe(), "motion": motion.to_dict()}
    if loads is not None:
        out["assembly"] = run.assembly.to_dict()
    if args.json:
        print_json(out)
        return 0
    n = arch.voussoirs
    place = {0: " (left springing)", n: " (right springing)"}
    print(f"{motion.name}: {out['outcome']} (chain of rigid voussoirs)")
    if out["max_friction_demand"] is None:
        print("friction needed during the motion  none reported (no sample with unique joint "
              "forces)")
    else:
        j = out["joint"]
        print(f"friction needed during the motion  {out['max_friction_demand']:.3f} at joint "
              f"{j}{place.get(j, '')}, t = {out['time_s']:.3f} s")
    if ground is not None:
        print(f"while the ground moves             {ground:.3f}")
    print(f"equivalent static analysis         {static.min_friction:.3f} at joint "
          f"{static.min_friction_joint}")
    print(f"left out                           {summary['indeterminate_samples']} indeterminate "
          f"and {summary['impulsive_samples']} impact samples of {summary['samples']}, and "
          "joints carrying < 1 % of the weight")
    from archquake.cli.loads_options import print_loads

    print_loads(run.assembly.to_dict())
    return 0
