"""How the rigid chain's kernels are fed: a model packed once, stepping loops without reference
counting (the kernels' packed arguments: tests/test_kernel_arity.py).

Oracles: object identity (a model's derived forms are built once), and numba's compile options
(the stepping loops are compiled without reference counting, the step's cost measured in
docs/notes/measurements.md, "The rigid chain's step without reference counting"). The loops'
numbers are held elsewhere: step by step against the full solve,
``test_step_with_the_kept_factor_is_the_full_solve_to_the_tolerance`` (tests/rigid/test_chain.py),
and bit for bit by the digests (tests/test_digest.py).
"""

from __future__ import annotations

import math

from archquake.geometry import Arch

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def test_model_derived_forms_are_built_once():
    """A `RigidModel`'s packed arrays and its event-integrator layout are built once and kept on
    it; the verdict path finds the same objects, and the model remembers its arch."""
    from archquake.blocks.criteria import BlockCriteria
    from archquake.rigid.events import EventModel
    from archquake.rigid.verdict import _packed, rigid_model

    model = rigid_model(OPPENHEIM)
    assert model.arch == OPPENHEIM  # an equal arch (the models are memoised on the arch)
    assert model.chain is model.chain
    assert EventModel.of(model) is EventModel.of(model)
    assert _packed(model, BlockCriteria()) is _packed(model, BlockCriteria())  # hashed by identity
    assert _packed(model, BlockCriteria()).chain is model.chain


def test_stepping_loops_are_compiled_without_reference_counting():
    """The recorded stepper's and the verdict's loops allocate nothing and are compiled with
    numba's reference counting off: with it, each step took and dropped a reference to every
    array of the packed tuples it passes on."""
    import archquake.rigid._step_kernels as RK
    import archquake.rigid._verdict_kernels as VK

    for loop in (RK._steps, VK._verdict_steps):
        assert loop.targetoptions.get("_nrt") is False, loop.py_func.__name__


def test_one_loaded_assembly_and_one_onset_for_threads_asking_at_once():
    """The studies of one loaded arch run side by side (the assessment's sections in threads)
    share one assembly, one model and one packing, so the onset bisection (a second of
    projections) runs once; it starts from the equivalent static analysis the assembly
    records, and gives the plain bisection's numbers. Oracles: object identity, a count of
    the bisections, and `onset_g` on a fresh model."""
    import threading

    from archquake.blocks.assembly import VOUSSOIRS, dem_assembly
    from archquake.blocks.criteria import BlockCriteria
    from archquake.geometry.loads import Fill, Loads
    from archquake.ida.batch import rigid_body
    from archquake.limit.loaded import loaded_collapse, seismic_case
    from archquake.rigid.events import EventModel
    from archquake.rigid.model import RigidModel
    from archquake.rigid.verdict import _packed, rigid_model

    # an arch and loads of this test alone: nothing of them is memoised yet
    arch = Arch(5.0, 0.6, math.pi, 15, density=1750.0)
    loads = Loads(fill=Fill(depth=0.9, density=1800.0))
    calls = []
    bisect = EventModel._bisect

    def counted(self, sgn, *args):
        calls.append(sgn)
        return bisect(self, sgn, *args)

    packed: list = []

    def study() -> None:
        packed.append(_packed(rigid_model(rigid_body(Arch(5.0, 0.6, math.pi, 15, density=1750.0),
                                                     loads)), BlockCriteria()))

    EventModel._bisect = counted
    try:
        threads = [threading.Thread(target=study) for _ in range(3)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        EventModel._bisect = bisect
    assert packed[0] is packed[1] is packed[2]
    assert calls == [1.0, -1.0]  # one onset: lambda_+ and lambda_-, once
    body = rigid_body(arch, loads)
    assert body is dem_assembly(arch, VOUSSOIRS, loads=loads)
    lam = loaded_collapse(seismic_case(arch, loads)).multiplier
    assert body.meta["collapse_multiplier"] == lam
    plain = EventModel.build(RigidModel.build(dem_assembly(arch, VOUSSOIRS, loads=loads)))
    assert (packed[0].safe_pos, packed[0].safe_neg) == plain.onset_g
