"""The default case function: build the arch and the motion, run the case's model, summarise.

``evaluate_case`` is what `archquake.sweeps.run_sweep` maps when no other function is
injected. It is pure (the same case always gives the same summary) and importable by worker
processes and Dask workers (a plain module-level function). It runs the case's model through
`archquake.models.run` and keeps its `archquake.models.summary` (no histories):

- ``fourlink``: the four-link rocking mechanism with impacts, without its samples;
- ``dem``: the arch with every voussoir a block, the paper's contact stiffness and damping
  (``DemSettings()``), for ``t_end_s`` (default: until a verdict, at rest or collapsed, within
  the end of the excitation + 20 sqrt(R/g), `archquake.dem.run.dem_to_verdict`);
  ``restitution`` and ``impact`` do not apply to it (a case giving one is refused);
- ``rigid``: the chain of rigid blocks (hinges moving, the DEM's rigid limit). Without
  ``t_end_s``: its verdict (`archquake.rigid.rigid_verdict`: the step scaled with the
  arch, the half-step guard, stopped at collapse or proven rest, within the end of the
  excitation + 60 sqrt(R/g)), summarised by `rigid_summary` (no impact times or peak
  rotation per half cycle: the verdict path records no history). With ``t_end_s``:
  `archquake.rigid.simulate_rigid` for that time, without its joint forces. ``restitution``
  and ``impact`` are refused as for the DEM (its impacts follow from the blocks' plastic
  contacts).

All summaries start with the same keys (`archquake.outcome.RESULT_KEYS`: outcome,
collapse_half_cycle, collapse_time_s, impact_times_s, peak_rotation_rad, ...), so a store
holding both models has one column per quantity.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from archquake import models
from archquake.errors import InvalidParameterError, ModelUnavailableError
from archquake.models import (  # noqa: F401  (the IDA's batches read them here)
    RIGID_VERDICT_EVALUATOR,
    prepared_mechanism,
)
from archquake.sweeps.cases import ArchSpec, Case


def evaluate_case(case: Case) -> dict[str, Any]:
    """Run ``case`` with its model (`archquake.models.run`) and return the result's JSON-able
    summary (`archquake.models.summary`).

    Parameters
    ----------
    case : Case

    Returns
    -------
    dict
        ``result.to_dict()`` (no history): the keys of `archquake.outcome.RESULT_KEYS`
        (outcome, collapse half cycle, impact times in s, peak rotation per half cycle in
        rad, ...), then the model's own.

    Raises
    ------
    ArchquakeError
        When the model refuses the case (the sweep stores it as an ``error`` row).
    """
    o = case.options
    if o.step_fraction != 1.0:
        raise InvalidParameterError("step_fraction applies to the rigid chain's verdicts in "
                                    "batches (archquake.ida.batch.evaluate_rigid_cases)")
    motion = case.excitation.build(g=o.g)
    try:
        options = models.RunOptions(t_end=o.t_end_s, g=o.g, loads=case.loads,
                                    restitution=o.restitution, impact=o.impact, guard=o.guard)
    except InvalidParameterError as exc:  # in the case's words
        raise InvalidParameterError(str(exc).replace("t_end ", "t_end_s ")) from None
    result = models.run(case.model, case.arch, motion, options=options, to_verdict=True)
    return models.summary(result)


def rigid_summary(verdict) -> dict[str, Any]:
    """The stored summary of a `RigidVerdict` (`archquake.models.summary`): its ``to_dict()``
    (outcome, collapse half cycle and time in s, largest rotation in rad, the step in s, the
    guard's rerun, ...) with ``evaluator``."""
    return models.summary(verdict)


@lru_cache(maxsize=256)
def mechanism_limits(arch: ArchSpec, loads=None) -> tuple[float, float]:
    """The arch's equivalent static collapse acceleration (g) and the critical rotation of its
    four-hinge mechanism (rad: the crest of its potential), with no impact law: defined on any
    arch, symmetric or not (`prepared_mechanism` needs the mirror-image mechanism of a
    symmetric one for its impact). Memoised per process.

    Returns
    -------
    (float, float)
        collapse acceleration, g; critical rotation, rad.
    """
    from archquake.limit.analysis import hinges_of
    from archquake.mechanism.kinematics import G0, H0, PHI_CRIT
    from archquake.mechanism.prepared import pack_mechanism

    if loads is not None and not loads.empty:  # the links carrying the loads, loaded hinges
        from archquake.geometry.carrying import CarryingChain
        from archquake.geometry.hinges import HingeMechanism
        from archquake.limit.loaded import loaded_collapse, seismic_case

        built = arch.build()
        found = loaded_collapse(seismic_case(built, loads)).mechanism
        mech = HingeMechanism(CarryingChain(built, loads), found.joints, found.faces)
    else:
        mech = hinges_of(arch.build())
    if mech.load_direction < 0:
        mech = mech.mirrored()
    packed = pack_mechanism(mech)
    return float(packed[G0] / abs(packed[H0])), float(packed[PHI_CRIT])


__all__ = ["RIGID_VERDICT_EVALUATOR", "ModelUnavailableError", "evaluate_case",
           "mechanism_limits", "prepared_mechanism", "rigid_summary"]
