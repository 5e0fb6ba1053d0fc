"""One way to run any of the three models: their names and `run`.

The models, named as ``--model``, study files, sweep stores and JSON name them (`Model`):

- ``rigid`` (the default, `DEFAULT_MODEL`): the chain of rigid voussoirs
  (`archquake.rigid`): hinges open, migrate and close anywhere, impacts follow from plastic
  contacts;
- ``fourlink``: the paper's four-link mechanism (`archquake.mechanism`): hinges fixed
  between impacts, Eq. 4's coefficient of restitution;
- ``dem``: the distinct-element model (`archquake.dem`).

`run` is the one dispatch, like the ``method=`` of `scipy.integrate.solve_ivp` and its
table of methods: `MODELS` holds each model's runner and the options it takes; an option
given to a model that does not take it is refused in one line naming the option. Each model's
policy for running to a verdict lives in its own package (`archquake.rigid.run.rigid_to_verdict`,
`archquake.dem.run.dem_to_verdict`; the four-link model's inside `archquake.mechanism.simulate`).

Examples
--------
>>> import math
>>> from archquake import Arch, StepImpulse
>>> arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
>>> run(Model.FOURLINK, arch, StepImpulse.from_g(1.0, 0.27)).outcome.value  # Figure 4(c)
'collapse'
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass, fields
from enum import StrEnum
from functools import lru_cache
from typing import Any

from archquake._validate import require_gravity
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.geometry.spec import ArchSpec


class Model(StrEnum):
    """The model a run, a case or a study uses, named as ``--model`` names it: the chain of
    rigid voussoirs (``rigid``, the default: hinges open, migrate and close anywhere, impacts
    follow from plastic contacts), the paper's four-link mechanism with hinges fixed between
    impacts and Eq. 4's coefficient of restitution (``fourlink``), or the distinct-element
    model (``dem``)."""

    RIGID = "rigid"
    FOURLINK = "fourlink"
    DEM = "dem"


#: The model every command and API function uses unless told otherwise.
DEFAULT_MODEL = Model.RIGID

#: The words of earlier versions that still name one model, for one more release (with a
#: DeprecationWarning): ``rigid_chain`` (the rigid chain's verdicts) and ``analytical`` (the
#: four-link model).
DEPRECATED_WORDS = {"rigid_chain": Model.RIGID, "analytical": Model.FOURLINK}


def model_of(model: str | Model | None = None, hinges: str | None = None, *,
             model_name: str = "model", hinges_name: str = "hinges",
             stacklevel: int = 2) -> Model:
    """The `Model` a user names (``rigid``, ``fourlink`` or ``dem``; None: the default,
    rigid). The words of earlier versions (`DEPRECATED_WORDS`: ``rigid_chain``,
    ``analytical``) still name their model, with a DeprecationWarning.

    ``hinges`` is the retired ``--hinges fixed|moving`` (None when not given): any value is
    refused with the ``--model`` that replaces it. ``model_name`` and ``hinges_name`` are the
    option or key as the user typed it (``--model``, ``study.model``...). ``stacklevel``: the
    warning's, as `warnings.warn` takes it (2: the caller of `model_of`).

    Examples
    --------
    >>> model_of().value
    'rigid'
    >>> model_of("fourlink").value
    'fourlink'
    >>> model_of("dem", model_name="--model").value
    'dem'
    """
    if hinges is not None:
        now = {"moving": "rigid", "fixed": "fourlink"}.get(str(hinges))
        hint = (f"{model_name} {now}" if now is not None
                else f"{model_name} rigid (hinges moving) or {model_name} fourlink (hinges fixed)")
        raise InvalidParameterError(f"{hinges_name} is retired: use {hint}")
    if model is None:
        return DEFAULT_MODEL
    word = str(getattr(model, "value", model))
    if word in DEPRECATED_WORDS:
        now = DEPRECATED_WORDS[word]
        warnings.warn(f"{model_name} {word} is deprecated and will be removed in the next "
                      f"release: use {model_name} {now.value}", DeprecationWarning,
                      stacklevel=stacklevel)
        return now
    try:
        return Model(word)
    except ValueError:
        raise InvalidParameterError(f"{model_name} must be one of "
                                    f"{', '.join(m.value for m in Model)}, got {word!r}") from None


@dataclass(frozen=True)
class RunOptions:
    """What a run is told besides the arch and the motion (None: the model's default).

    Parameters
    ----------
    t_end : float, optional
        End of the run, s (> 0). None: run to a verdict, each model's own way (the
        four-link model to the end of the excitation + 60 sqrt(R/g); the rigid chain to the
        end of the excitation + 5 sqrt(R/g), then on while the arch moves up to + 60 sqrt(R/g);
        the DEM to + 5, 10, 20 sqrt(R/g) while the arch moves).
    g : float
        Gravity, m/s^2.
    loads : Loads, optional
        What the arch carries (`archquake.geometry.loads.Loads`): masses that move with it.
    restitution : float, optional
        ``fourlink``: a prescribed coefficient of restitution c_v in [0, 1].
    impact : {"paper", "chain", "mirror"}, optional
        ``fourlink``: the impact law (`archquake.mechanism.impact`).
    friction : float, optional
        ``rigid`` and ``dem``: Coulomb coefficient of every joint (None: no sliding).
    integrator : {"steps", "events"}, optional
        ``rigid``: Moreau-Jean time steps (default) or from contact event to contact event.
    time_step : float, optional
        ``rigid``: the stepper's step, s (default: the verdict's step, scaled with the
        voussoirs' thickness, to a verdict; ``archquake.rigid.DEFAULT_TIME_STEP`` otherwise).
    guard : bool
        ``rigid``: the half-step rerun of a verdict near a threshold (a run to a verdict at
        the verdict's step reads it; False is refused for the other models).
    dem : DemSettings, optional
        ``dem``: contact law, damping and thresholds (``duration`` is replaced by the run's);
        ``rigid``: its thresholds only (hinge opening, collapse criteria), so that the run is
        classified as the DEM's is.
    """

    t_end: float | None = None
    g: float = STANDARD_GRAVITY
    loads: Any = None
    restitution: float | None = None
    impact: str | None = None
    friction: float | None = None
    integrator: str | None = None
    time_step: float | None = None
    guard: bool = True
    dem: Any = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "g", require_gravity(self.g))
        if self.t_end is not None and not float(self.t_end) > 0.0:
            raise InvalidParameterError(f"t_end must be > 0 s, got {self.t_end!r}")
        if self.integrator not in (None, "steps", "events"):
            raise InvalidParameterError(
                f"integrator must be 'steps' or 'events', got {self.integrator!r}")
        if not isinstance(self.guard, bool):
            raise InvalidParameterError(f"guard must be true or false, got {self.guard!r}")

    def given(self) -> list[str]:
        """The names of the model options given (not None; ``guard`` when False)."""
        out = []
        for f in fields(self):
            if f.name in _SHARED:
                continue
            value = getattr(self, f.name)
            if value is not None and value is not True:
                out.append(f.name)
        return out


#: The options every model takes.
_SHARED = frozenset({"t_end", "g", "loads"})


@dataclass(frozen=True)
class ModelSpec:
    """One row of `MODELS`: how a model runs, what it takes and what it is.

    Attributes
    ----------
    model : Model
    label : str
        What the model is, in a few words (for errors).
    short : str
        Its name in a table's heading (``rigid``, ``four-link``, ``DEM``).
    kind : str
        Its name in a sentence (``rigid chain``, ``four-link mechanism``,
        ``distinct-element``).
    takes : frozenset of str
        The `RunOptions` fields it reads besides ``t_end``, ``g`` and ``loads``.
    blocks : bool
        A block model: every voussoir a body, its impacts from its contacts (the rigid chain,
        the DEM), rather than the four-link mechanism's links.
    deformable : bool
        Its contacts are deformable, with a stiffness and damping (the DEM), rather than rigid
        and plastic.
    batched : bool
        Its verdicts run many at once in one compiled, threaded call (no process pool):
        the four-link model's batch and the rigid chain's verdict path.
    runner : callable
        ``runner(arch, motion, options, to_verdict, progress)``.
    completes : callable
        ``completes(result, arch, out) -> dict``: the keys that complete ``out``, the result's
        ``to_dict()`` with the arch and the excitation, into `to_dict` (none by default).
    """

    model: Model
    label: str
    short: str
    kind: str
    takes: frozenset[str]
    blocks: bool
    deformable: bool
    batched: bool
    runner: Callable[..., Any]
    completes: Callable[..., dict] = lambda result, arch, out: {}

    def refuse(self, options: RunOptions) -> None:
        """Refuse, in one line naming it, the first option given that this model does not
        take, with the models that take it."""
        for name in options.given():
            if name not in self.takes:
                owners = " and ".join(m.value for m, spec in MODELS.items() if name in spec.takes)
                raise InvalidParameterError(f"{name} applies to model {owners} only, not to the "
                                            f"{self.label} ({self.model.value})")


@lru_cache(maxsize=256)
def prepared_mechanism(arch: ArchSpec, impact: str | None = None, loads=None):
    """The arch's mechanism from the equivalent static analysis, packed for the kernels with
    its impact solution under ``impact`` (None: "paper"), its links carrying ``loads``. A pure
    function of the arch, the law and the loads, memoised per process: a sweep usually runs
    many excitations on each arch, and this limit analysis (and the chain law's impact) costs
    more than a case."""
    from archquake.mechanism import PreparedMechanism

    return PreparedMechanism.build(arch.build(), impact, loads=loads)


def _built(arch):
    """An `ArchSpec` built (`ArchSpec.build`); anything else as it is."""
    return arch.build() if isinstance(arch, ArchSpec) else arch


def _run_fourlink(arch, motion, o: RunOptions, to_verdict: bool, progress) -> Any:
    from archquake.mechanism import PreparedMechanism, SolverOptions
    from archquake.mechanism.simulate import simulate

    prepared = (prepared_mechanism(arch, o.impact, o.loads) if isinstance(arch, ArchSpec)
                else PreparedMechanism.build(arch, o.impact, loads=o.loads))
    # a verdict keeps no time history, which also saves its memory
    solver = SolverOptions(output_interval=0.0) if to_verdict else SolverOptions()
    return simulate(prepared, motion, restitution=o.restitution, t_end=o.t_end,
                    options=solver, g=o.g)


def _run_rigid(arch, motion, o: RunOptions, to_verdict: bool, progress) -> Any:
    from archquake.blocks.assembly import loaded_body
    from archquake.rigid.model import DEFAULT_TIME_STEP
    from archquake.rigid.run import rigid_to_verdict, simulate_rigid

    solver = "events" if o.integrator == "events" else "direct"
    if solver == "events" and o.friction is not None:
        raise InvalidParameterError("integrator events has no sliding: leave friction unset, "
                                    "or use integrator steps")
    verdict_step = o.t_end is None and o.friction is None and solver == "direct" \
        and o.time_step is None
    if not o.guard and not verdict_step:
        raise InvalidParameterError("guard applies to a rigid run to a verdict at the verdict's "
                                    "step only (without t_end, friction, integrator events or "
                                    "time_step)")
    arch = _built(arch)
    body = loaded_body(arch, o.loads)
    criteria = None if o.dem is None else o.dem.criteria  # what the rigid chain reads of them
    if o.t_end is not None:  # a given end is run as given
        return simulate_rigid(body, motion, duration=o.t_end, friction=o.friction, g=o.g,
                              solver=solver, progress=progress, settings=criteria,
                              time_step=DEFAULT_TIME_STEP if o.time_step is None else o.time_step)
    if verdict_step and to_verdict:  # the compiled verdict path, no history
        from archquake.rigid.verdict import rigid_verdict

        return rigid_verdict(body, motion, g=o.g, guard=o.guard, settings=criteria)
    if verdict_step:  # the history, integrated once at the verdict's step, guarded
        from archquake.rigid.run import run_guarded

        return run_guarded(arch, motion, g=o.g, loads=o.loads, progress=progress,
                           guard=o.guard, settings=criteria)
    return rigid_to_verdict(arch, motion, friction=o.friction, g=o.g, solver=solver,
                            time_step=o.time_step, progress=progress, loads=o.loads,
                            settings=criteria)


def _run_dem(arch, motion, o: RunOptions, to_verdict: bool, progress) -> Any:
    from archquake.blocks.assembly import loaded_body
    from archquake.dem import DemSettings, simulate_dem
    from archquake.dem.run import dem_to_verdict

    settings = DemSettings() if o.dem is None else o.dem
    if o.friction is not None:
        from archquake.dem import ContactLaw

        law = settings.contact
        settings = settings.with_(contact=ContactLaw(normal_stiffness=law.normal_stiffness,
                                                     friction=o.friction))
    arch = _built(arch)
    body = loaded_body(arch, o.loads)
    if o.t_end is None:  # run until a verdict (rest or collapse), or the cap
        radius = getattr(arch, "radius", None)
        if radius is None:
            raise InvalidParameterError("give t_end: this block assembly has no radius to scale "
                                        "the default window by")
        return dem_to_verdict(body, motion, settings, radius=radius, g=o.g)
    return simulate_dem(body, motion, settings.with_(duration=o.t_end), g=o.g)


def _rigid_completes(result, arch, out: dict) -> dict:
    """The rigid chain's joint forces numbered as the arch's joints (those inside a backing
    are not recorded: `archquake.rigid.forces.on_arch_joints`)."""
    if not out.get("joint_forces"):
        return {}
    from archquake.rigid.forces import joint_numbers, on_arch_joints

    recorded = getattr(result, "run", result)  # a guarded run: the run it guards
    return {"joint_forces": on_arch_joints(out["joint_forces"], joint_numbers(recorded),
                                           arch.voussoirs + 1)}


def _fourlink_completes(result, arch, out: dict) -> dict:
    """The loads the four-link mechanism's links carry and their masses
    (`archquake.mechanism.prepared.link_masses`; nothing for a bare arch)."""
    from archquake.mechanism.prepared import link_masses

    masses = link_masses(result.mechanism)
    if masses is None:
        return {}
    return {"loads": result.mechanism.arch.loads.to_dict(), "masses": masses}


#: Each model's runner and the options it takes, like `scipy.integrate.solve_ivp`'s METHODS.
MODELS: dict[Model, ModelSpec] = {
    Model.RIGID: ModelSpec(Model.RIGID, "chain of rigid voussoirs", "rigid", "rigid chain",
                           frozenset({"friction", "integrator", "time_step", "guard", "dem"}),
                           blocks=True, deformable=False, batched=True, runner=_run_rigid,
                           completes=_rigid_completes),
    Model.FOURLINK: ModelSpec(Model.FOURLINK, "four-link mechanism", "four-link",
                              "four-link mechanism", frozenset({"restitution", "impact"}),
                              blocks=False, deformable=False, batched=True,
                              runner=_run_fourlink, completes=_fourlink_completes),
    Model.DEM: ModelSpec(Model.DEM, "distinct-element model", "DEM", "distinct-element",
                         frozenset({"friction", "dem"}), blocks=True, deformable=True,
                         batched=False, runner=_run_dem),
}


def spec(model: str | Model) -> ModelSpec:
    """The `MODELS` row of ``model`` (`model_of` reads the name)."""
    return MODELS[model_of(model)]


def takes(model: str | Model, option: str) -> bool:
    """Whether ``model`` takes the `RunOptions` field ``option`` (the shared ones, ``t_end``,
    ``g`` and ``loads``, every model takes).

    Examples
    --------
    >>> takes("fourlink", "restitution"), takes("rigid", "restitution")
    (True, False)
    """
    return option in _SHARED or option in MODELS[model_of(model)].takes


def run(model: str | Model, arch, motion, *, options: RunOptions | None = None,
        to_verdict: bool = False, progress: Callable[[int, int], None] | None = None) -> Any:
    """Run ``model`` on ``arch`` under ``motion``: the one way into the three models.

    Parameters
    ----------
    model : {"rigid", "fourlink", "dem"} or Model
        `Model` (`model_of`: the words of earlier versions warn and map).
    arch : Arch or ArchSpec
        The arch (a `archquake.mechanism.PreparedMechanism` for ``fourlink``, or a block
        `archquake.dem.Assembly` for ``rigid`` and ``dem``, is taken as it is; an `ArchSpec`'s
        four-link mechanism is memoised, `prepared_mechanism`).
    motion : GroundMotion
        Ground acceleration, m/s^2.
    options : RunOptions, optional
        Each model refuses, in one line naming it, an option it does not take.
    to_verdict : bool
        True: the verdict alone, no time history kept (sweeps, incremental dynamic analysis):
        the four-link model without its samples, the rigid chain's compiled verdict path
        (`archquake.rigid.rigid_verdict`, with its half-step guard; without ``t_end``,
        ``friction``, ``integrator="events"`` or ``time_step``), the DEM as it is. False (the
        default): the history; the rigid chain's, without those options, integrated once at
        the verdict's step under the same guard (`archquake.rigid.run.run_guarded`).
    progress : callable, optional
        ``progress(steps_done, steps_at_most)`` of the rigid chain's time stepper.

    Returns
    -------
    ModelResult
        `archquake.result.ModelResult` (``to_dict()`` starts with
        `archquake.outcome.RESULT_KEYS`): a `SimulationResult` (``fourlink``), a `RigidRun`
        (``rigid``; a `GuardedRun` at the verdict's step, a `RigidVerdict` for a verdict run)
        or a `archquake.blocks.BlockResult` (``dem``).

    Raises
    ------
    InvalidParameterError
        An unknown model, or an option the model does not take.
    """
    spec = MODELS[model_of(model, stacklevel=3)]  # a deprecated word: the caller's line
    o = RunOptions() if options is None else options
    if not isinstance(o, RunOptions):
        raise InvalidParameterError(f"options must be a RunOptions, got {type(o).__name__}")
    spec.refuse(o)
    return spec.runner(arch, motion, o, to_verdict, progress)


def summary(result: Any) -> dict:
    """A run's JSON summary without its histories, as a sweep store keeps it: ``to_dict()``,
    the four-link model's without its samples, the rigid chain's without its joint forces
    (a post-processing that costs more than the run), the rigid chain's verdict with
    ``evaluator`` (`RIGID_VERDICT_EVALUATOR`)."""
    # a class whose module is not imported cannot be the result's (a rigid run does not
    # import the four-link model to be summarised)
    fourlink = sys.modules.get("archquake.mechanism.simulate")
    rigid = sys.modules.get("archquake.rigid.run")
    if fourlink is not None and isinstance(result, fourlink.SimulationResult):
        return result.to_dict(include_history=False)
    if rigid is not None and isinstance(result, (rigid.RigidRun, rigid.GuardedRun)):
        return result.to_dict(joint_forces=False)
    verdict = sys.modules.get("archquake.rigid.verdict")
    if verdict is not None and isinstance(result, verdict.RigidVerdict):
        return {**result.to_dict(), "evaluator": RIGID_VERDICT_EVALUATOR}
    return dict(result.to_dict())


def to_dict(result: Any, arch, motion) -> dict:
    """A history run's JSON, as ``archquake run --json`` prints it: the result's ``to_dict()``
    (`archquake.outcome.RESULT_KEYS` first, then its model's own keys), the arch
    (``arch.describe()``) and the excitation (``motion.to_dict()``), then what its model adds
    (`ModelSpec.completes`): the rigid chain's joint forces numbered as the arch's joints, the
    four-link model's loads and the masses its links carry.

    Parameters
    ----------
    result : ModelResult
        What `run` returned for ``arch`` and ``motion`` (not ``to_verdict``).
    arch : Arch
        The arch the run was given (before any block assembly or mechanism was built from it).
    motion : GroundMotion

    Examples
    --------
    >>> import math
    >>> from archquake import Arch, StepImpulse
    >>> arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
    >>> motion = StepImpulse.from_g(1.0, 0.27)
    >>> out = to_dict(run(Model.FOURLINK, arch, motion), arch, motion)
    >>> out["model"], out["outcome"], out["excitation"] == motion.to_dict()
    ('fourlink', 'collapse', True)
    """
    out = result.to_dict()
    out["arch"] = arch.describe()
    out["excitation"] = motion.to_dict()
    out.update(spec(out["model"]).completes(result, arch, out))
    return out


#: The ``evaluator`` key of a summary of the rigid chain's verdict path.
RIGID_VERDICT_EVALUATOR = "rigid verdict (compiled, guarded)"


__all__ = ["DEFAULT_MODEL", "DEPRECATED_WORDS", "MODELS", "RIGID_VERDICT_EVALUATOR", "Model",
           "ModelSpec", "RunOptions", "model_of", "prepared_mechanism", "run", "spec", "summary", "takes",
           "to_dict"]
