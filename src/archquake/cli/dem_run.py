"""``archquake run --model dem``: one distinct-element time history (the paper's UDEC model).

The output is ``BlockResult.to_dict()``: the four-link run's keys
(`archquake.outcome.RESULT_KEYS`: outcome, collapse_half_cycle, collapse_time_s,
onset_time_s, impact_times_s, peak_rotation_rad, ...) followed by the DEM's own.
"""

from __future__ import annotations

import argparse

from archquake.cli.common import (
    check_range,
    comma_numbers,
    ranged,
    refuse_unless,
)
from archquake.errors import InvalidParameterError
from archquake.ground.base import motion_label
from archquake.ranges import (
    DAMPING_FREQUENCY_RANGE_HZ,
    DAMPING_RATIO_RANGE_PERCENT,
    DEM_T_END_MAX_S,
    FRICTION_RANGE,
    RAYLEIGH_ALPHA_RANGE,
    RAYLEIGH_BETA_RANGE,
    STIFFNESS_RANGE,
)

#: The paper's joint stiffness, Pa/m, and Rayleigh (alpha 1/s, beta s).
DEFAULT_STIFFNESS = 1e12
DEFAULT_RAYLEIGH = (6.28e-5, 1.59e-4)


def block_duration(args, arch, motion, flag: str, why: str) -> float:
    """The run's length for a block model (the DEM, the rigid chain), s: ``--t-end`` or the
    default (end of the excitation + 5 sqrt(R/g)); over ``ranges.DEM_T_END_MAX_S`` it is refused
    in one line naming the option, ``flag`` the model's option and ``why`` its cost."""
    from archquake.dem.run import default_dem_duration

    duration = args.t_end if args.t_end is not None else default_dem_duration(arch, motion)
    if duration > DEM_T_END_MAX_S:
        from archquake.cli.common import excitation_option

        given = ("--t-end" if args.t_end is not None
                 else "the default --t-end (end of the excitation + 5 sqrt(R/g))")
        change = ("a shorter --t-end" if args.t_end is not None
                  else f"a shorter {excitation_option(args)}, or a --t-end")
        raise InvalidParameterError(
            f"{given} is {duration:g} s; with {flag} it must be <= {DEM_T_END_MAX_S:g} s "
            f"({why}): give {change}")
    return duration


def _pair(text: str) -> tuple[float, float]:
    a, b = comma_numbers(text, 2, "two numbers A,B")
    return a, b


def refuse_dem_options(args: argparse.Namespace, *, friction_too: bool = True) -> None:
    """The DEM's options are an error unless ``--model dem`` (never silently ignored); with it,
    ``--dem-assembly`` defaults to every voussoir. ``friction_too=False`` leaves ``--friction``
    to the caller (``--model rigid``: the rigid chain's Coulomb joints)."""
    given = {"--dem-assembly": args.dem_assembly, "--stiffness": args.stiffness,
             "--friction": args.friction if friction_too else None, "--damping": args.damping,
             "--rayleigh": args.rayleigh}
    from archquake import models

    refuse_unless(given, models.spec(args.model).deformable,
                  "to the distinct-element model (--friction also to --model rigid): add "
                  "--model dem, or leave it out")
    if args.dem_assembly is None:  # None until here, so that giving it is seen
        args.dem_assembly = "voussoirs"


def add_dem_arguments(parser: argparse.ArgumentParser) -> None:
    """The distinct-element options of ``archquake run`` (used with ``--model dem``)."""
    grp = parser.add_argument_group("distinct-element model (with --model dem; --t-end sets the "
                                    "simulated time, default end of excitation + 5 sqrt(R/g), "
                                    "rerun with 10 then 20 sqrt(R/g) while the arch still moves; "
                                    "--history writes the DEM's rotation, energies and base motion)")
    grp.add_argument("--dem-assembly", choices=("voussoirs", "hinges"), default=None,
                     help="DEM blocks: every voussoir (default) or the arch cut only at the "
                          "four-link model's hinges (the paper's three-voussoir arch)")
    grp.add_argument("--stiffness", type=ranged(*STIFFNESS_RANGE, "Pa/m"), metavar="PA_PER_M",
                     help=f"joint normal and shear stiffness, Pa/m ({STIFFNESS_RANGE[0]:g} to "
                          f"{STIFFNESS_RANGE[1]:g}; default {DEFAULT_STIFFNESS:g}, the paper's)")
    grp.add_argument("--friction", type=ranged(*FRICTION_RANGE), metavar="MU",
                     help=f"joint friction coefficient tan(friction angle) ({FRICTION_RANGE[0]:g} "
                          f"to {FRICTION_RANGE[1]:g}; default: no sliding)")
    damp = grp.add_mutually_exclusive_group()
    damp.add_argument("--damping", type=_pair, metavar="F_MIN,XI_MIN",
                      help="Rayleigh damping as UDEC's minimum: frequency in Hz, damping ratio in "
                           "percent (default 0.1,0.01, the paper's; Figure 10: 0.05,0.001); the "
                           f"resulting beta must be <= {RAYLEIGH_BETA_RANGE[1]:g} s")
    damp.add_argument("--rayleigh", type=_pair, metavar="ALPHA,BETA",
                      help=f"Rayleigh coefficients: alpha in 1/s (0 to {RAYLEIGH_ALPHA_RANGE[1]:g}), "
                           f"beta in s (0 to {RAYLEIGH_BETA_RANGE[1]:g}) (default 6.28e-5,1.59e-4)")


def settings_from_args(args: argparse.Namespace, duration: float):
    """The DemSettings the options ask for."""
    from archquake.dem import ContactLaw, DemSettings

    stiffness = DEFAULT_STIFFNESS if args.stiffness is None else args.stiffness
    check_range("--stiffness", stiffness, *STIFFNESS_RANGE, "Pa/m")
    if args.friction is not None:
        check_range("--friction", args.friction, *FRICTION_RANGE)
    law = ContactLaw(normal_stiffness=stiffness) if args.friction is None else ContactLaw(
        normal_stiffness=stiffness, friction=args.friction)
    damping = DEFAULT_RAYLEIGH
    if args.damping is not None:
        f_min, xi_percent = args.damping
        check_range("--damping F_MIN", f_min, *DAMPING_FREQUENCY_RANGE_HZ, "Hz")
        check_range("--damping XI_MIN", xi_percent, *DAMPING_RATIO_RANGE_PERCENT, "%")
        damping = DemSettings.rayleigh_from_minimum(f_min, xi_percent / 100.0)
        low, high = RAYLEIGH_BETA_RANGE
        if damping[1] > high:
            raise InvalidParameterError(
                f"--damping {f_min:g},{xi_percent:g} gives beta = {damping[1]:.3g} s, above "
                f"{high:g} s (the explicit time step would vanish): raise F_MIN or lower XI_MIN")
        check_range("--damping (alpha = XI_MIN 2 pi F_MIN)", damping[0], *RAYLEIGH_ALPHA_RANGE, "1/s")
    elif args.rayleigh is not None:
        alpha, beta = args.rayleigh
        check_range("--rayleigh ALPHA", alpha, *RAYLEIGH_ALPHA_RANGE, "1/s")
        check_range("--rayleigh BETA", beta, *RAYLEIGH_BETA_RANGE, "s")
        damping = (alpha, beta)
    return DemSettings(contact=law, damping=damping, duration=duration)


def run(args: argparse.Namespace, arch, motion, options) -> int:
    """Run the DEM for ``arch`` under ``motion`` with ``options``
    (`archquake.models.RunOptions`, its loads carried by the assembly ``--dem-assembly``
    builds) and print/plot/animate as the options say."""
    from dataclasses import replace

    from archquake import models
    from archquake.compare import dem_assembly

    duration = block_duration(args, arch, motion, "--model dem",
                              "the explicit DEM needs millions of steps")
    settings = settings_from_args(args, duration)  # its contact law holds --friction
    assembly = dem_assembly(arch, args.dem_assembly, loads=options.loads)
    result = models.run(models.Model.DEM, assembly, motion,
                        options=replace(options, loads=None, friction=None, dem=settings))
    return emit_block_run(args, arch, motion, result, result.to_dict(),
                          lambda out: _print_text(out, result))


def emit_block_run(args: argparse.Namespace, arch, motion, result, out: dict,
                   print_text, label: str | None = None, history=None) -> int:
    """The output of a block-model run (the DEM, or the rigid chain read by the DEM's own
    post-processing, ``result`` a `BlockResult`): the ``--plot``,
    ``--animate`` and ``--history`` files, then ``out`` (the run's ``to_dict()``, completed with
    the arch and the excitation) as JSON with ``--json``, else ``print_text(out)`` and the files
    written. ``history``: the run whose ``to_csv`` writes ``--history`` (default ``result``).
    Returns the exit status."""
    if args.plot:
        from archquake.plotting.compare import save_dem_rotation

        if label is None:
            save_dem_rotation(result, args.plot)
        else:
            save_dem_rotation(result, args.plot, label=label)
    if args.animate:
        from archquake.plotting.dem import animate_dem

        animate_dem(result, args.animate, fps=15)
    if args.history:
        (result if history is None else history).to_csv(args.history)
    out["arch"] = arch.describe()
    out["excitation"] = motion.to_dict()
    if args.json:
        from archquake.cli.common import print_json

        print_json(out)
        return 0
    print_text(out)
    print_loads(out["assembly"])
    for what, path in (("plot", args.plot), ("animation", args.animate), ("history", args.history)):
        if path:
            print(f"{what}: {path}")
    return 0


def print_loads(assembly: dict) -> None:
    """The text lines of what a block model's arch carries (nothing for a bare arch)."""
    masses = assembly.get("masses")
    if masses is None:
        return
    held = masses["held_by_backing"]
    print(f"carried mass        {masses['carried_mass_kg']:.6g} kg on "
          f"{masses['masonry_mass_kg']:.6g} kg of masonry (fill columns and moving loads, at "
          "their centroids)"
          + (f"; voussoirs {', '.join(map(str, held))} held by the backing" if held else ""))
    print(f"passive pressure    {masses['passive_pressure']}")


def _print_text(out: dict, result) -> None:
    s = out["settings"]
    print(f"excitation          {motion_label(out['excitation'])}")
    print(f"model               distinct elements: {out['assembly']['name']}, "
          f"k = {s['contact']['normal_stiffness_Pa_m']:.3g} Pa/m, Rayleigh alpha = "
          f"{s['rayleigh_alpha_1_s']:.3g} 1/s, beta = {s['rayleigh_beta_s']:.3g} s")
    print(f"time step           {result.time_step:.3g} s, {result.n_steps} steps, "
          f"{out['end_time_s']:.2f} s simulated")
    print_block_verdict(out, "DEM criterion: ")
    peaks = out["peak_rotation_rad"]
    if peaks:
        print(f"peak rotation [rad] {', '.join(f'{p:.4f}' for p in peaks[:6])}"
              + (" ..." if len(peaks) > 6 else ""))
    print(f"energy balance      {out['energy_error']:.1e} of the input work; dissipated: damping "
          f"{out['dissipated_damping_J']:.4g} J, friction {out['dissipated_friction_J']:.4g} J")


def print_block_verdict(out: dict, criterion: str = "") -> None:
    """The outcome, onset and impact lines of a block model's text output (the DEM's, or the
    rigid chain's read by the DEM's post-processing); ``criterion`` prefixes the collapse rule."""
    if out["collapse_half_cycle"]:
        what = (f"collapse in half cycle {out['collapse_half_cycle']} at t = "
                f"{out['collapse_time_s']:.3f} s ({criterion}crown fallen by t or a block "
                "below the springings)")
    else:
        what = f"{out['outcome']}: {out['verdict']}"
    print(f"outcome             {what}")
    if out["onset_time_s"] is not None:
        print(f"hinging from        {out['onset_time_s']:.3f} s")
    imp = out["impact_times_s"]
    if imp:
        more = f" ... ({len(imp)} in all)" if len(imp) > 6 else ""
        print(f"impacts [s]         {', '.join(f'{t:.3f}' for t in imp[:6])}{more}")
