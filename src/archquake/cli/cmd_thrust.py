"""``archquake thrust``: the line of thrust of the moving arch at chosen instants (Figure 8)."""

from __future__ import annotations

import argparse
import math

from archquake.cli.common import (
    add_arch_arguments,
    add_ground_motion_arguments,
    add_impact_arguments,
    add_model_argument,
    add_output_arguments,
    arch_from_args,
    comma_numbers,
    ground_motion_from_args,
    impact_from_args,
    model_from_args,
    print_json,
    refuse_unless,
)
from archquake.errors import InvalidParameterError
from archquake.ranges import (
    MAX_TIMES,
    T_END_RANGE_S,
)


def _times(text: str) -> list[float]:
    """``T1,T2,...``: instants in s, each in [0, T_END_RANGE_S[1]], no empty item."""
    values = comma_numbers(text, None, "comma-separated times in s, e.g. 0.2,0.5,0.8")
    if len(values) > MAX_TIMES:
        raise argparse.ArgumentTypeError(f"at most {MAX_TIMES} times, got {len(values)}")
    high = T_END_RANGE_S[1]
    for v in values:
        if not 0.0 <= v <= high:
            raise argparse.ArgumentTypeError(f"each time must be in [0, {high:g}] s, got {v:g}")
    return values


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "thrust",
        help="line of thrust of the moving arch at chosen times (paper Figure 8)",
        description=(
            "Simulate the arch under the excitation and, at each requested time, report its "
            "hinges and its line of thrust. By default (--model rigid) from the joint forces of "
            "the chain of rigid voussoirs at the recorded sample nearest each time: where the "
            "resultant crosses each joint (e / (d/2), +-1 at a hinge; it never leaves the "
            "section) and the friction demand. With --model fourlink, the paper's four-link "
            "mechanism: the displaced arch drawn with --plot and the line of thrust from "
            "self-weight, ground inertia and the links' inertia, with the joints where it "
            "leaves the section (at a jump of the ground acceleration the value just before "
            "it)."
        ),
    )
    add_arch_arguments(p)
    add_ground_motion_arguments(p)
    p.add_argument("--times", type=_times, default=[0.2, 0.5, 0.8, 1.1, 1.5, 2.22], metavar="T1,T2,...",
                   help="instants, s, comma-separated (default: Figure 8's 0.2,0.5,0.8,1.1,1.5,2.22)")
    add_model_argument(p, models=("rigid", "fourlink"))
    from archquake.cli.loads_options import add_loads_arguments

    add_loads_arguments(p)
    add_impact_arguments(p)
    add_output_arguments(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from archquake.models import spec
    from archquake.thrust import states

    model = model_from_args(args, models=("rigid", "fourlink"))
    blocks = spec(model).blocks  # the rigid chain, else the four-link model
    refuse_unless({"--plot": args.plot}, not blocks,
                  "with --model fourlink (the drawing shows the four-link mechanism's displaced "
                  "arch)")
    arch = arch_from_args(args)
    motion = ground_motion_from_args(args)
    if min(args.times) < 0:
        raise InvalidParameterError(f"--times must be >= 0 s, got {min(args.times):g}")
    from archquake.cli.loads_options import dynamic_loads_from_args

    loads = dynamic_loads_from_args(args, arch, model)
    if blocks:
        return _run_rigid(args, arch, motion, loads)
    snapshots = states(arch, motion, args.times, **impact_from_args(args))
    if args.plot is not None:
        from archquake.plotting.thrust import save_thrust_snapshots

        save_thrust_snapshots(arch, snapshots, args.plot, suptitle=f"line of thrust: {motion.name}")
    if args.json:
        print_json({"model": "fourlink", "arch": arch.describe(), "motion": motion.to_dict(),
                    "states": [s.to_dict() for s in snapshots]})
        return 0
    print(f"{motion.name}")
    print("   t (s)  side  phi (deg)  thrust leaves the section   max friction |V|/N")
    for s in snapshots:
        j = s.exit_joint
        where = "inside" if j is None else f"joint {j} by {s.outside[j]:.3f} m"
        k = int(s.friction_demand.argmax())
        print(f"{s.t:8.3f}  {s.side:+d}   {math.degrees(s.phi):8.3f}   {where:<26s} "
              f"{s.friction_demand[k]:.3f} (joint {k})")
    if args.plot is not None:
        print(f"figure: {args.plot}")
    return 0


def _run_rigid(args: argparse.Namespace, arch, motion, loads=None) -> int:
    """``--model rigid``: the chain of rigid voussoirs (carrying ``loads``) run to the last time
    asked (or its collapse), its joints at the recorded sample nearest each time
    (`archquake.rigid.forces.JointForceHistory.state_at`)."""
    from archquake.blocks.assembly import loaded_body
    from archquake.cli.common import rigid_work
    from archquake.rigid import simulate_rigid
    from archquake.rigid.forces import joint_numbers, on_arch_joints
    from archquake.rigid.model import DEFAULT_TIME_STEP

    duration = max(max(args.times), 1e-3) + 1e-3
    progress = rigid_work("thrust", arch, motion, duration, DEFAULT_TIME_STEP, length="--times")
    run = simulate_rigid(loaded_body(arch, loads), motion, duration=duration, progress=progress)
    collapse = run.collapse_time
    if collapse is not None and max(args.times) > collapse:
        raise InvalidParameterError(
            f"--times must be before the collapse at t = {collapse:.3f} s, got "
            f"{max(args.times):g} s")
    forces = run.joint_forces
    numbers = joint_numbers(run)
    snaps = [on_arch_joints(forces.state_at(t), numbers, arch.voussoirs + 1)
             for t in args.times]
    if args.json:
        extra = {} if loads is None else {"assembly": run.assembly.to_dict()}
        print_json({"model": "rigid", "arch": arch.describe(), "motion": motion.to_dict(),
                    "outcome": run.outcome.value,
                    "collapse_time_s": run.collapse_time, "states": snaps, **extra})
        return 0
    print(f"{motion.name} (chain of rigid voussoirs; the line of thrust as e / (d/2) per joint, "
          "+-1 at a face: an open hinge, or one about to open)")
    print("   t (s)  thrust at a face     line of thrust, joints 0..n          max friction |V|/N")
    for s in snaps:
        line = " ".join("  . " if e is None else f"{e:+.1f}" for e in s["relative_eccentricity"])
        fd = s["max_friction_demand"]
        print(f"{s['sample_time_s']:8.3f}  {','.join(map(str, s['face_joints'])) or '-':<19} "
              f"{line:<36} "
              + ("-" if fd is None else f"{fd:.3f} (joint {s['max_friction_demand_joint']})"))
    if run.collapse_time is not None:
        print(f"collapse at t = {run.collapse_time:.3f} s")
    from archquake.cli.loads_options import print_loads

    print_loads(run.assembly.to_dict())
    return 0
