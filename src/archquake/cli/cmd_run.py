"""``archquake run``: one time history of an arch under a pulse or a record."""

from __future__ import annotations

import argparse
from dataclasses import replace

from archquake.cli.common import (
    add_arch_arguments,
    add_ground_motion_arguments,
    add_impact_arguments,
    add_model_argument,
    add_output_arguments,
    arch_from_args,
    ground_motion_from_args,
    impact_from_args,
    impact_line,
    model_from_args,
    output_file,
    print_json,
    ranged,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.ground.base import motion_label
from archquake.ranges import (
    ANIMATION_SUFFIXES,
    CSV_SUFFIXES,
    T_END_RANGE_S,
)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="time history of the arch under a pulse or an accelerogram (paper Eqs. 2-7)",
        description=(
            "Rocking of the arch until collapse or rest: by default the chain of rigid voussoirs "
            "(--model rigid), or the paper's four-link mechanism (--model fourlink) or the "
            "distinct-element model (--model dem). Lengths in m, times in s, angles in degrees, "
            "accelerations in g. Example: archquake run --pulse step --magnitude 1.0 "
            "--duration 0.27"
        ),
    )
    add_arch_arguments(p)
    from archquake.cli.loads_options import add_loads_arguments

    add_loads_arguments(p)
    add_ground_motion_arguments(p)
    add_impact_arguments(p)
    p.add_argument("--t-end", type=ranged(*T_END_RANGE_S, "s"), metavar="S",
                   help=f"end of the analysis, s ({T_END_RANGE_S[0]:g} to {T_END_RANGE_S[1]:g}; "
                        "default: end of the excitation + 60 sqrt(R/g)); a run it cuts before "
                        "the survival is shown is indeterminate, with the reason")
    add_model_argument(p, extra="~30 ms per 4 s simulated for rigid on a 7-voussoir arch, "
                                "~0.4 ms a history for fourlink")
    p.add_argument("--integrator", choices=("steps", "events"), default=None,
                   help="with --model rigid: how the chain of rigid voussoirs is integrated: "
                        "'steps' (default), Moreau-Jean time steps (to a verdict, the step "
                        "scaled with the voussoirs' thickness, 1e-3 s on Oppenheim's arch; with "
                        "--t-end or --friction, 1e-4 s); 'events', from "
                        "contact event to contact event, the precise option (energy conserved "
                        "between impacts, every hinge opening and closure located and listed; "
                        "no --friction)")
    from archquake.cli.dem_run import add_dem_arguments

    add_dem_arguments(p)
    add_output_arguments(p)
    p.add_argument("--animate", metavar="FILE.gif", type=output_file(*ANIMATION_SUFFIXES),
                   help="write an animated GIF of the rocking arch")
    p.add_argument("--history", metavar="FILE.csv", type=output_file(*CSV_SUFFIXES),
                   help="write the time history as CSV, the same first columns for every "
                        "model (time s, crown displacement m, rotation rad, kinetic and "
                        "potential energy J), then the model's own")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from archquake import models
    from archquake.cli.dem_run import refuse_dem_options

    model = model_from_args(args)
    arch = arch_from_args(args)
    motion = ground_motion_from_args(args)
    # --friction is the rigid chain's as well as the DEM's
    refuse_dem_options(args, friction_too=not models.takes(model, "integrator"))
    impact = impact_from_args(args)
    from archquake.cli.loads_options import dynamic_loads_from_args

    loads = dynamic_loads_from_args(args, arch, model, fourlink=True)
    options = models.RunOptions(t_end=args.t_end, loads=loads,
                                restitution=impact["restitution"], impact=impact["impact"],
                                friction=args.friction, integrator=args.integrator)
    spec = models.spec(model)
    if spec.deformable:  # the DEM: its stiffness, damping and assembly from the options
        from archquake.cli import dem_run

        return dem_run.run(args, arch, motion, options)
    if spec.blocks:  # the rigid chain
        from archquake.cli import rigid_run

        return rigid_run.run(args, arch, motion, options)
    return _run_fourlink(args, arch, motion, options)


def _run_fourlink(args: argparse.Namespace, arch, motion, options) -> int:
    """The four-link model's history: print, plot, animate as asked."""
    from archquake import models
    from archquake.cli.loads_options import fourlink_masses
    from archquake.mechanism import PreparedMechanism

    loads = options.loads
    prepared = PreparedMechanism.build(arch, options.impact, loads=loads)
    result = models.run(models.Model.FOURLINK, prepared, motion,
                        options=replace(options, impact=None, loads=None))
    assert result.history is not None  # a history run records it
    g = STANDARD_GRAVITY
    if args.plot:
        from archquake.plotting.history import figure4

        t_show = result.collapse_time if result.collapse_time is not None else None
        t_show = max(1.2 * (t_show or 0.0), min(float(result.history.t[-1]), 1.5 * motion.duration + 3.0))
        figure4([result], [motion], [motion_label(motion)], args.plot, t_end=t_show, title="(a) excitation")
    if args.animate:
        from archquake.plotting.history import animate_history

        t_show = float(result.history.t[-1])
        if result.collapse_time is None:
            t_show = min(t_show, motion.duration + 10.0)
        animate_history(prepared, result, args.animate, fps=15, t_end=t_show)
    if args.history:
        result.to_csv(args.history)
    out = result.to_dict()
    out["arch"] = arch.describe()
    out["excitation"] = motion.to_dict()
    masses = None if loads is None else fourlink_masses(prepared)
    if masses is not None:
        out["loads"] = loads.to_dict()
        out["masses"] = masses
    if args.json:
        print_json(out)
        return 0
    _print_text(result, motion, g)
    if masses is not None:
        from archquake.cli.dem_run import print_loads

        print_loads({"masses": masses})
    for what, path in (("plot", args.plot), ("animation", args.animate), ("history", args.history)):
        if path:
            print(f"{what}: {path}")
    return 0


def _print_text(result, motion, g: float) -> None:
    print(f"excitation          {motion_label(motion)}")
    hinges = ", ".join(f"joint {h.joint} {h.face.value}" for h in result.mechanism.hinges)
    print(f"hinges (A, B, C, D) {hinges}")
    print(f"onset of hinging    {result.collapse_acceleration_g:.4f} g (equivalent static analysis)")
    print(f"restitution         c_v = {result.restitution_cv:.4f}, c_T = {result.restitution_ct:.4f}"
          + (" (prescribed)" if result.restitution_prescribed else "")
          + ("  (c_T > 1: the impact model gains energy for this geometry)" if result.energy_gain else ""))
    print(impact_line(result.impact_law, result.impact_validity, result.impact_described,
                      result.restitution_prescribed))
    if not result.impact_followed:
        print("                    the law's mechanisms reach beyond the tabulated set: an impact "
              "leaving it stops the history (unresolved)")
    if result.impact_law == "chain" and result.mechanisms:
        events = list(result.mechanisms)[:8]
        for k, e in enumerate(events):
            what = (f"{e.kind:<10} {e.hinges}" + (f" ({e.validity})" if e.validity else ""))
            print(f"{'mechanisms' if k == 0 else '':<19} t = {e.time_s:.3f} s  {what}")
        if len(result.mechanisms) > len(events):
            print(f"{'':<19} ... {len(result.mechanisms) - len(events)} more")
    if not result.impact_admissible:
        print(f"                    the impact model gives c_v = {result.impact_model_cv:.4f} < 0 for this "
              "geometry (inadmissible): impacts computed as perfectly plastic; see --restitution")
    computed = result.computed_outcome or result.outcome
    when = (f" in half cycle {result.collapse_half_cycle} at t = {result.collapse_time:.3f} s"
            if result.collapse_half_cycle else f" ({result.final_state.value})")
    if result.outcome is computed:
        print(f"outcome             {result.outcome.value}{when}")
    elif not result.impact_described:
        print(f"outcome             {result.outcome.value}: the model computed {computed.value}{when}, "
              "but only through an impact its law does not describe (see --impact, --restitution)")
    else:
        print(f"outcome             {result.outcome.value}: the model computed {computed.value}{when}, "
              "but the run ended before that could be shown (see --t-end)")
    if result.verdict_reason:
        print(f"verdict             {result.verdict_reason}")
    if result.impact_times.size:
        shown = ", ".join(f"{t:.3f}" for t in result.impact_times[:6])
        more = f" ... ({result.impact_times.size} in all)" if result.impact_times.size > 6 else ""
        print(f"impacts [s]         {shown}{more}")
    if result.peak_rotation.size:
        shown = ", ".join(f"{p:.4f}" for p in result.peak_rotation[:6])
        print(f"peak phi [rad]      {shown}" + (" ..." if result.peak_rotation.size > 6 else ""))
