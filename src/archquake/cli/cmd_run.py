"""``archquake run``: one time history of an arch under a pulse or a record, by any of the
three models (`archquake.models`).

The command parses, runs ``models.run`` and prints ``models.to_dict`` of the result (as JSON
with ``--json``, else as text), and writes the ``--plot``, ``--animate`` and ``--history``
files. The text lines are read from that dict: the lines every model shares, and each model's
own where its keys are present (the four-link mechanism's fixed hinges and impact law, the
rigid chain's stepper and joint forces, the DEM's stiffness and damping).

With the rigid chain (the default) and without ``--t-end``, ``--friction`` or ``--integrator
events``, the chain is integrated once, at the verdict's step (scaled with the arch, 1e-3 s
on Oppenheim's arch), and rerun at half the step only near a threshold, ``indeterminate``
where the two differ (`archquake.rigid.run.run_guarded`); the guard is under ``guard`` in the
JSON. With ``--friction`` or ``--integrator events`` the recorded run's verdict is printed, at
1e-4 s.
"""

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
from archquake.errors import InvalidParameterError
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
    from archquake.cli.dem_options import add_dem_arguments

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
    from archquake.cli.dem_options import refuse_dem_options
    from archquake.cli.loads_options import dynamic_loads_from_args

    model = model_from_args(args)
    arch = arch_from_args(args)
    motion = ground_motion_from_args(args)
    # --friction is the rigid chain's as well as the DEM's
    refuse_dem_options(args, friction_too=not models.takes(model, "integrator"))
    impact = impact_from_args(args)
    loads = dynamic_loads_from_args(args, arch, model, fourlink=True)
    options = models.RunOptions(t_end=args.t_end, loads=loads,
                                restitution=impact["restitution"], impact=impact["impact"],
                                friction=args.friction, integrator=args.integrator)
    spec = models.spec(model)
    body, options, progress = _inputs(args, spec, arch, motion, options)
    result = models.run(model, body, motion, options=options, progress=progress)
    _write_files(args, spec, result, motion)
    out = models.to_dict(result, arch, motion)
    if args.json:
        print_json(out)
        return 0
    print_text(out)
    for what, path in (("plot", args.plot), ("animation", args.animate), ("history", args.history)):
        if path:
            print(f"{what}: {path}")
    return 0


def _inputs(args: argparse.Namespace, spec, arch, motion, options):
    """What ``models.run`` is given besides the motion: the body it runs (the arch, or the
    DEM's assembly from ``--dem-assembly``), the options (the DEM's settings from its own
    options) and the rigid stepper's progress (None: no announcement)."""
    from archquake import models

    if spec.deformable:  # the DEM: its assembly, stiffness, damping and length from the options
        from archquake.cli.dem_options import block_duration, settings_from_args
        from archquake.compare import dem_assembly

        duration = block_duration(args, arch, motion, "--model dem",
                                  "the explicit DEM needs millions of steps")
        settings = settings_from_args(args, duration)  # its contact law holds --friction
        assembly = dem_assembly(arch, args.dem_assembly, loads=options.loads)
        return assembly, replace(options, loads=None, friction=None, dem=settings), None
    if models.takes(spec.model, "integrator"):  # the rigid chain: its work estimate
        return arch, options, _rigid_progress(args, arch, motion)
    return arch, options, None


def _rigid_progress(args: argparse.Namespace, arch, motion):
    """The rigid chain's work, refused above the bound in one line naming the options, and its
    ``progress`` for a long run (`archquake.cli.common.rigid_work`)."""
    from archquake.cli.common import length_option, rigid_work
    from archquake.rigid.model import DEFAULT_TIME_STEP
    from archquake.rigid.run import rigid_window

    events = args.integrator == "events"
    if events and args.friction is not None:
        raise InvalidParameterError(
            "--integrator events has no sliding: leave --friction out, or use --integrator steps")
    if events:  # the event integrator's steps are its own
        return None
    if args.t_end is not None:  # a given --t-end is run as given
        return rigid_work("run", arch, motion, args.t_end, DEFAULT_TIME_STEP)
    if args.friction is None:  # once, at the verdict's step
        from archquake.rigid.verdict import verdict_time_step

        # the run, and near a threshold the guard's rerun at half the step (twice the steps)
        return rigid_work("run", arch, motion, rigid_window(arch, motion)[1],
                          verdict_time_step(arch), passes=3, length=length_option(args))
    return rigid_work("run", arch, motion, rigid_window(arch, motion)[1],
                      DEFAULT_TIME_STEP, length=length_option(args))


def _write_files(args: argparse.Namespace, spec, result, motion) -> None:
    """The ``--plot``, ``--animate`` and ``--history`` files of a run: a block model's rotation
    and hinge sets, or the four-link model's Figure 4 and its mechanism in motion."""
    recorded = getattr(result, "run", result)  # a guarded rigid run: the history it guards
    if args.plot:
        if spec.blocks:
            from archquake.plotting.compare import save_dem_rotation

            # the DEM's curve is labelled with its assembly, the rigid chain's with its kind
            save_dem_rotation(recorded, args.plot, label=None if spec.deformable else spec.kind)
        else:
            from archquake.plotting.history import figure4

            t_show = result.collapse_time if result.collapse_time is not None else None
            t_show = max(1.2 * (t_show or 0.0),
                         min(float(result.history.t[-1]), 1.5 * motion.duration + 3.0))
            figure4([result], [motion], [motion_label(motion)], args.plot, t_end=t_show,
                    title="(a) excitation")
    if args.animate:
        if spec.blocks:
            from archquake.plotting.dem import animate_dem

            animate_dem(recorded, args.animate, fps=15)
        else:
            from archquake.mechanism import PreparedMechanism
            from archquake.plotting.history import animate_history

            t_show = float(result.history.t[-1])
            if result.collapse_time is None:
                t_show = min(t_show, motion.duration + 10.0)
            prepared = PreparedMechanism.build(result.mechanism, result.impact_law)
            animate_history(prepared, result, args.animate, fps=15, t_end=t_show)
    if args.history:
        recorded.to_csv(args.history)


def print_text(out: dict) -> None:
    """The text output of a run, read from its ``models.to_dict``: the excitation, each
    model's own description where its keys are present, the verdict, the peaks, the energy
    balance and what the arch carries."""
    print(f"excitation          {motion_label(out['excitation'])}")
    stepper = out.get("rigid")  # the rigid chain's time stepper or event integrator
    if "hinges" in out:  # the four-link mechanism: its fixed hinges and impact law
        _print_mechanism(out)
    elif stepper is not None:
        _print_stepper(out, stepper)
    else:  # the DEM's contacts and damping
        s = out["settings"]
        print(f"model               distinct elements: {out['assembly']['name']}, "
              f"k = {s['contact']['normal_stiffness_Pa_m']:.3g} Pa/m, Rayleigh alpha = "
              f"{s['rayleigh_alpha_1_s']:.3g} 1/s, beta = {s['rayleigh_beta_s']:.3g} s")
        print(f"time step           {out['solver']['time_step_s']:.3g} s, "
              f"{out['solver']['steps']} steps, {out['end_time_s']:.2f} s simulated")
    if "computed_outcome" in out:
        _print_mechanism_verdict(out)
    else:
        _print_block_verdict(out, "" if stepper is not None else "DEM criterion: ")
    guard = out.get("guard")
    if guard is not None:
        print(f"verdict's step      {guard['time_step_s']:.3g} s, "
              + (f"rerun at half the step: {guard['outcome']}" if guard["ran"]
                 else "not near a threshold (no rerun)"))
    if stepper is not None:  # the hinge sets the chain passed through
        events = out["mechanisms"]
        for k, e in enumerate(events[:10]):
            print(f"{'hinge sets' if k == 0 else '':<19} t = {e['time_s']:.3f} s  {e['kind']:<7} "
                  f"{e['hinges'] or '(all joints closed)'}"
                  + (f"  ({e['degrees_of_freedom']} dof)" if e["hinges"] else ""))
        if len(events) > 10:
            print(f"{'':<19} ... {len(events) - 10} more (--json lists them all)")
    peaks = out["peak_rotation_rad"]
    if peaks:  # the four-link model's rotation is its mechanism's angle phi
        print(("peak phi [rad]      " if "hinges" in out else "peak rotation [rad] ")
              + ", ".join(f"{p:.4f}" for p in peaks[:6]) + (" ..." if len(peaks) > 6 else ""))
    jf = out.get("joint_forces")
    if jf and jf["max_friction_demand"] is not None:
        print(f"friction demand     max |V|/N = {jf['max_friction_demand']:.3f} at joint "
              f"{jf['max_friction_demand_joint']}, t = {jf['max_friction_demand_time_s']:.3f} s "
              f"({jf['indeterminate_samples']} indeterminate and {jf['impulsive_samples']} impact "
              f"samples of {jf['samples']} left out)")
    _print_energy(out)
    from archquake.cli.loads_options import print_loads

    print_loads(out if "masses" in out else out.get("assembly", {}))


def _print_mechanism(out: dict) -> None:
    """The four-link mechanism's lines: hinges, onset, restitution, impact law."""
    hinges = ", ".join(f"joint {h['joint']} {h['face']}" for h in out["hinges"])
    print(f"hinges (A, B, C, D) {hinges}")
    print(f"onset of hinging    {out['collapse_acceleration_g']:.4f} g (equivalent static analysis)")
    print(f"restitution         c_v = {out['restitution_cv']:.4f}, c_T = {out['restitution_ct']:.4f}"
          + (" (prescribed)" if out["restitution_prescribed"] else "")
          + ("  (c_T > 1: the impact model gains energy for this geometry)"
             if out["energy_gain"] else ""))
    print(impact_line(out["impact_law"], out["impact_validity"], out["impact_described"],
                      out["restitution_prescribed"]))
    if not out["impact_followed"]:
        print("                    the law's mechanisms reach beyond the tabulated set: an impact "
              "leaving it stops the history (unresolved)")
    mechanisms = out["mechanisms"]
    if out["impact_law"] == "chain" and mechanisms:
        for k, e in enumerate(mechanisms[:8]):
            what = f"{e['kind']:<10} {e['hinges']}" + (f" ({e['validity']})" if e["validity"] else "")
            print(f"{'mechanisms' if k == 0 else '':<19} t = {e['time_s']:.3f} s  {what}")
        if len(mechanisms) > 8:
            print(f"{'':<19} ... {len(mechanisms) - 8} more")
    if not out["impact_admissible"]:
        print(f"                    the impact model gives c_v = {out['impact_model_cv']:.4f} < 0 "
              "for this geometry (inadmissible): impacts computed as perfectly plastic; see "
              "--restitution")


def _print_stepper(out: dict, rig: dict) -> None:
    """The rigid chain's lines: its contacts and how it was integrated (``rig``, its
    stepper's diagnostics)."""
    print(f"model               rigid: chain of rigid voussoirs ({out['assembly']['name']}), "
          "plastic contacts, "
          + ("no sliding" if out["friction_coefficient"] is None
             else f"Coulomb friction mu = {out['friction_coefficient']:g}"))
    if rig.get("below_onset"):
        print(f"integration         none: the ground acceleration stays below the onset of "
              f"hinging both ways, so the chain stays at rest ({out['end_time_s']:.2f} s)")
    elif rig["solver"] == "events":
        ev = rig["events"]
        print(f"integrator          from event to event: {ev['closures']} closures, "
              f"{ev['openings']} openings, {len(ev['handovers_s'])} hand-overs to time steps; "
              f"{out['end_time_s']:.2f} s simulated ({rig['wall_s']:.2f} s wall)")
    else:
        print(f"time step           {rig['time_step_s']:.3g} s, {out['end_time_s']:.2f} s "
              f"simulated ({rig['wall_s']:.1f} s wall)")


def _print_mechanism_verdict(out: dict) -> None:
    """The four-link model's outcome, verdict and impacts, with the outcome it computed where
    the verdict differs."""
    computed = out["computed_outcome"]
    when = (f" in half cycle {out['collapse_half_cycle']} at t = {out['collapse_time_s']:.3f} s"
            if out["collapse_half_cycle"] else f" ({out['final_state']})")
    if out["outcome"] == computed:
        print(f"outcome             {out['outcome']}{when}")
    elif not out["impact_described"]:
        print(f"outcome             {out['outcome']}: the model computed {computed}{when}, "
              "but only through an impact its law does not describe (see --impact, --restitution)")
    else:
        print(f"outcome             {out['outcome']}: the model computed {computed}{when}, "
              "but the run ended before that could be shown (see --t-end)")
    if out["verdict"]:
        print(f"verdict             {out['verdict']}")
    _print_impacts(out["impact_times_s"])


def _print_block_verdict(out: dict, criterion: str) -> None:
    """A block model's outcome, onset and impacts; ``criterion`` prefixes the collapse rule."""
    if out["collapse_half_cycle"]:
        what = (f"collapse in half cycle {out['collapse_half_cycle']} at t = "
                f"{out['collapse_time_s']:.3f} s ({criterion}crown fallen by t or a block "
                "below the springings)")
    else:
        what = f"{out['outcome']}: {out['verdict']}"
    print(f"outcome             {what}")
    if out["onset_time_s"] is not None:
        print(f"hinging from        {out['onset_time_s']:.3f} s")
    _print_impacts(out["impact_times_s"])


def _print_impacts(times: list) -> None:
    if times:
        more = f" ... ({len(times)} in all)" if len(times) > 6 else ""
        print(f"impacts [s]         {', '.join(f'{t:.3f}' for t in times[:6])}{more}")


def _print_energy(out: dict) -> None:
    """A block model's energy balance: the rigid chain's against its largest energy, with its
    contacts' dissipation, or the DEM's against the input work, with its damping's."""
    if "energy_scale_J" in out:
        if out["energy_scale_J"] > 0.0:
            print(f"energy balance      residual {out['energy_error']:.1e} of "
                  f"{out['energy_scale_J']:.4g} J (the largest of the input work, the kinetic and "
                  "potential energy and the ground's kinetic energy); input work "
                  f"{out['input_work_J']:.4g} J")
            print(f"dissipated          at the contacts {out['dissipated_contacts_J']:.4g} J: "
                  f"impacts {out['dissipated_impacts_J']:.4g} J, friction "
                  f"{out['dissipated_friction_J']:.4g} J")
        else:
            print("energy balance      nothing moved relative to the ground: no work, no "
                  "dissipation")
    elif "dissipated_damping_J" in out:
        print(f"energy balance      {out['energy_error']:.1e} of the input work; dissipated: "
              f"damping {out['dissipated_damping_J']:.4g} J, friction "
              f"{out['dissipated_friction_J']:.4g} J")
    if out.get("energy_warning"):
        print(f"warning             {out['energy_warning']}")


__all__ = ["print_text", "register", "run"]
