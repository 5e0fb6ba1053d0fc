"""The default case function: build the arch and the motion, run the case's model, summarise.

``evaluate_case`` is what `archquake.sweeps.run_sweep` maps when no other function is
injected. It is pure (the same case always gives the same summary) and importable by worker
processes and Dask workers (a plain module-level function).

Models:

- ``fourlink``: `archquake.mechanism.simulate` (the four-link rocking mechanism with
  impacts), summarised by ``result.to_dict(include_history=False)``;
- ``dem``: `archquake.dem.simulate_dem` on the arch with every voussoir a block, the
  paper's contact stiffness and damping (``DemSettings()``), for ``t_end_s`` (default: until a
  verdict, the end of the excitation + 5, then 10, then 20 sqrt(R/g) while the arch still moves,
  `archquake.compare.dem_to_verdict`), summarised by ``result.to_dict()``.
  ``restitution`` and ``impact`` do not apply to it (a case giving one is refused);
- ``rigid``: the chain of rigid blocks (hinges moving, the DEM's rigid limit). Without
  ``t_end_s``: its verdict (`archquake.rigid.rigid_verdict`: the step scaled with the
  arch, the half-step guard, stopped at collapse or proven rest, within the end of the
  excitation + 60 sqrt(R/g)), summarised by `rigid_summary` (no impact times or peak
  rotation per half cycle: the verdict path records no history). With ``t_end_s``:
  `archquake.rigid.simulate_rigid` for that time, summarised by ``RigidRun.to_dict()``
  without its joint forces. ``restitution`` and ``impact`` are refused as for the DEM (its
  impacts follow from the blocks' plastic contacts).

All summaries start with the same keys (`archquake.outcome.RESULT_KEYS`: outcome,
collapse_half_cycle, collapse_time_s, impact_times_s, peak_rotation_rad, ...), so a store
holding both models has one column per quantity.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from functools import lru_cache
from typing import Any

from archquake.errors import InvalidParameterError, ModelUnavailableError
from archquake.sweeps.cases import ArchSpec, Case, Model

#: Where each model's simulate function lives, as (module, function).
MODEL_FUNCTIONS: dict[Model, tuple[str, str]] = {
    Model.FOURLINK: ("archquake.mechanism", "simulate"),
    Model.DEM: ("archquake.dem", "simulate_dem"),
    Model.RIGID: ("archquake.rigid", "simulate_rigid"),
}


def model_function(model: Model | str) -> Callable[..., Any]:
    """The simulate function of ``model``, or a one-line error if this build lacks it."""
    model = Model(getattr(model, "value", model))
    module_name, name = MODEL_FUNCTIONS[model]
    try:
        return getattr(importlib.import_module(module_name), name)
    except (ImportError, AttributeError):
        raise ModelUnavailableError(
            f"model {model.value!r} needs {module_name}.{name}, which this build of archquake "
            "does not provide"
        ) from None


def evaluate_case(case: Case) -> dict[str, Any]:
    """Run ``case`` with its model and return the result's JSON-able summary.

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
    simulate = model_function(case.model)
    motion = case.excitation.build(g=case.options.g)
    if not case.options.guard and case.model is not Model.RIGID:
        raise InvalidParameterError("guard applies to model rigid only (its verdict path's "
                                    "half-step rerun)")
    if case.model is Model.FOURLINK:
        from archquake.mechanism import SolverOptions

        # no time history is kept (the store holds summaries), which also saves its memory
        result = simulate(prepared_mechanism(case.arch, case.options.impact, case.loads), motion,
                          restitution=case.options.restitution,
                          t_end=case.options.t_end_s, options=SolverOptions(output_interval=0.0),
                          g=case.options.g)
        return result.to_dict(include_history=False)
    # the block models' impacts follow from their contacts: no coefficient of restitution
    from archquake.compare import default_dem_duration
    from archquake.dem import DemSettings

    who = "the DEM's" if case.model is Model.DEM else "the rigid chain's"
    for key in ("restitution", "impact"):
        if getattr(case.options, key) is not None:
            raise InvalidParameterError(f"{key} applies to model fourlink only; {who} impacts "
                                        "follow from its contacts")
    arch = case.arch.build()
    body: Any = arch  # the arch, or its blocks carrying the loads
    if case.loads is not None:
        from archquake.blocks.assembly import build_arch_assembly

        body = build_arch_assembly(arch, loads=case.loads)
    if case.model is Model.RIGID:
        if case.options.t_end_s is None:  # to a verdict, on the verdict path
            from archquake.rigid import rigid_verdict

            return rigid_summary(rigid_verdict(body, motion, g=case.options.g,
                                               guard=case.options.guard))
        run = simulate(body, motion, duration=case.options.t_end_s, g=case.options.g)
        return run.to_dict(joint_forces=False)  # a store holds no histories' forces
    if case.options.t_end_s is None:  # run until a verdict (rest or collapse), or the cap
        from archquake.compare import dem_to_verdict

        return dem_to_verdict(body, motion, g=case.options.g, radius=arch.radius).to_dict()
    duration = case.options.t_end_s or default_dem_duration(arch, motion, g=case.options.g)
    result = simulate(body, motion, DemSettings(duration=duration), g=case.options.g)
    return result.to_dict()


#: The ``evaluator`` key of a summary of the rigid chain's verdict path.
RIGID_VERDICT_EVALUATOR = "rigid verdict (compiled, guarded)"


def rigid_summary(verdict) -> dict[str, Any]:
    """The stored summary of a `RigidVerdict`: its ``to_dict()``
    (outcome, collapse half cycle and time in s, largest rotation in rad, the step in s, the
    guard's rerun, ...) under the model's sweep name ``rigid``, with ``evaluator``."""
    return {**verdict.to_dict(), "model": Model.RIGID.value,
            "evaluator": RIGID_VERDICT_EVALUATOR}


@lru_cache(maxsize=256)
def prepared_mechanism(arch: ArchSpec, impact: str | None = None, loads=None):
    """The arch's mechanism from the equivalent static analysis, packed for the kernels with
    its impact solution under ``impact`` (None: "paper"), its links carrying ``loads``. A pure
    function of the arch, the law and the loads, memoised per process: a sweep usually runs
    many excitations on each arch, and this limit analysis (and the chain law's impact) costs
    more than a case."""
    from archquake.mechanism import PreparedMechanism

    return PreparedMechanism.build(arch.build(), impact, loads=loads)


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


__all__ = ["MODEL_FUNCTIONS", "RIGID_VERDICT_EVALUATOR", "ModelUnavailableError", "evaluate_case",
           "mechanism_limits", "model_function", "prepared_mechanism", "rigid_summary"]
