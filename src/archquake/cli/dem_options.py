"""The distinct-element options of ``archquake run`` (``--model dem``): the joints' stiffness
and friction, the Rayleigh damping, the assembly, and the run's length, in the CLI's units
(Pa/m, Hz and percent, 1/s and s), turned into `archquake.dem.DemSettings` here, at the edge."""

from __future__ import annotations

import argparse

from archquake.cli.common import (
    check_range,
    comma_numbers,
    ranged,
    refuse_unless,
)
from archquake.errors import InvalidParameterError
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


__all__ = ["DEFAULT_RAYLEIGH", "DEFAULT_STIFFNESS", "add_dem_arguments", "block_duration",
           "refuse_dem_options", "settings_from_args"]
