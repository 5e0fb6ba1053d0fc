"""``archquake run`` (``--model rigid``, the default): one history of the chain of rigid
voussoirs.

The model is `archquake.rigid.simulate_rigid`, run through `archquake.models.run`: every
voussoir a rigid block, plastic no-slip corner contacts (or Coulomb joints with
``--friction``), hinges opening, migrating and closing anywhere. Its output is
``RigidRun.to_dict()``: the keys every model shares (`archquake.outcome.RESULT_KEYS`), then
the DEM post-processing's keys (the rigid run is read by the DEM's own code) and the rigid
stepper's.

Without ``--t-end``, ``--friction`` or ``--integrator events``, the chain is integrated once,
at the verdict's step (scaled with the arch, 1e-3 s on Oppenheim's arch), and rerun at half
the step only near a threshold, ``indeterminate`` where the two differ
(`archquake.rigid.run.run_guarded`); the guard is under ``guard`` in the JSON. With
``--friction`` or ``--integrator events`` the recorded run's verdict is printed, at 1e-4 s.
"""

from __future__ import annotations

import argparse

from archquake.cli.common import check_range
from archquake.errors import InvalidParameterError
from archquake.ranges import FRICTION_RANGE


def run(args: argparse.Namespace, arch, motion, options) -> int:
    """Run the rigid chain for ``arch`` under ``motion`` with ``options``
    (`archquake.models.RunOptions`); print, plot, animate as asked."""
    from archquake import models

    if args.friction is not None:
        check_range("--friction", args.friction, *FRICTION_RANGE)
    solver = "events" if getattr(args, "integrator", None) == "events" else "direct"
    if solver == "events" and args.friction is not None:
        raise InvalidParameterError(
            "--integrator events has no sliding: leave --friction out, or use --integrator steps")
    from archquake.cli.common import length_option, rigid_work
    from archquake.rigid.model import DEFAULT_TIME_STEP
    from archquake.rigid.run import rigid_window

    progress = None
    if args.t_end is not None:  # a given --t-end is run as given
        if solver == "direct":
            progress = rigid_work("run", arch, motion, args.t_end, DEFAULT_TIME_STEP)
    elif args.friction is None and solver == "direct":  # once, at the verdict's step
        from archquake.rigid.verdict import verdict_time_step

        # the run, and near a threshold the guard's rerun at half the step (twice the steps)
        progress = rigid_work("run", arch, motion, rigid_window(arch, motion)[1],
                              verdict_time_step(arch), passes=3, length=length_option(args))
    elif solver == "direct":
        progress = rigid_work("run", arch, motion, rigid_window(arch, motion)[1],
                              DEFAULT_TIME_STEP, length=length_option(args))
    result = models.run(models.Model.RIGID, arch, motion, options=options, progress=progress)
    from archquake.cli.dem_run import emit_block_run

    recorded = getattr(result, "run", result)  # the RigidRun of a guarded run
    out = result.to_dict()
    if out.get("joint_forces"):
        out["joint_forces"] = on_arch_joints(out["joint_forces"], joint_numbers(recorded),
                                             arch.voussoirs + 1)
    return emit_block_run(args, arch, motion, recorded, out, _print_text,
                          label="rigid chain", history=recorded)


def loaded_body(arch, loads):
    """What the rigid chain runs: ``arch`` itself, or its assembly carrying ``loads``."""
    if loads is None:
        return arch
    from archquake.blocks.assembly import build_arch_assembly

    return build_arch_assembly(arch, loads=loads)


def joint_numbers(run) -> list[int] | None:
    """The arch's joint number of each joint the run records, or None where they are all of
    them in order (the joints inside a backing are not recorded)."""
    asm = run.assembly
    cuts = asm.meta.get("cut_joints")
    numbers = [int(cuts[j.index]) for j in asm.joints] if cuts else None
    return None if numbers is None or numbers == list(range(len(numbers))) else numbers


def on_arch_joints(state: dict, numbers: list[int] | None, n_joints: int) -> dict:
    """A joint-force state or summary (`archquake.rigid.forces`) with its joints numbered
    as the arch's (``numbers`` from `joint_numbers`; the joints not recorded get None)."""
    if numbers is None:
        return state
    out = dict(state)
    for key in ("relative_eccentricity", "friction_demand"):
        if key in out:
            full: list = [None] * n_joints
            for j, v in zip(numbers, out[key], strict=True):
                full[j] = v
            out[key] = full
    if "face_joints" in out:
        out["face_joints"] = [numbers[j] for j in out["face_joints"]]
    if out.get("max_friction_demand_joint") is not None:
        out["max_friction_demand_joint"] = numbers[out["max_friction_demand_joint"]]
    return out


def _print_text(out: dict) -> None:
    from archquake.ground.base import motion_label

    rig = out["rigid"]
    print(f"excitation          {motion_label(out['excitation'])}")
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
    from archquake.cli.dem_run import print_block_verdict

    print_block_verdict(out)
    v = out.get("guard")
    if v is not None:
        print(f"verdict's step      {v['time_step_s']:.3g} s, "
              + (f"rerun at half the step: {v['outcome']}" if v["ran"]
                 else "not near a threshold (no rerun)"))
    events = out["mechanisms"]
    for k, e in enumerate(events[:10]):
        print(f"{'hinge sets' if k == 0 else '':<19} t = {e['time_s']:.3f} s  {e['kind']:<7} "
              f"{e['hinges'] or '(all joints closed)'}"
              + (f"  ({e['degrees_of_freedom']} dof)" if e["hinges"] else ""))
    if len(events) > 10:
        print(f"{'':<19} ... {len(events) - 10} more (--json lists them all)")
    peaks = out["peak_rotation_rad"]
    if peaks:
        print(f"peak rotation [rad] {', '.join(f'{p:.4f}' for p in peaks[:6])}"
              + (" ..." if len(peaks) > 6 else ""))
    jf = out.get("joint_forces")
    if jf and jf["max_friction_demand"] is not None:
        print(f"friction demand     max |V|/N = {jf['max_friction_demand']:.3f} at joint "
              f"{jf['max_friction_demand_joint']}, t = {jf['max_friction_demand_time_s']:.3f} s "
              f"({jf['indeterminate_samples']} indeterminate and {jf['impulsive_samples']} impact "
              f"samples of {jf['samples']} left out)")
    if out["energy_scale_J"] > 0.0:
        print(f"energy balance      residual {out['energy_error']:.1e} of {out['energy_scale_J']:.4g} J "
              f"(the largest of the input work, the kinetic and potential energy and the ground's "
              f"kinetic energy); input work "
              f"{out['input_work_J']:.4g} J")
        print(f"dissipated          at the contacts {out['dissipated_contacts_J']:.4g} J: impacts "
              f"{out['dissipated_impacts_J']:.4g} J, friction {out['dissipated_friction_J']:.4g} J")
    else:
        print("energy balance      nothing moved relative to the ground: no work, no dissipation")
    if out["energy_warning"]:
        print(f"warning             {out['energy_warning']}")


__all__ = ["run"]
