"""The four-link kernels take the model packed once, in one compiled type.

Oracles: numba's own typing (``numba.typeof`` of the packed arguments, and the signatures each
dispatcher holds after the commands' workloads have run), and the settings array read back
through its named indices. Each check is exact: one type per argument, one signature per
kernel, whatever the ground motion (pulse, sine, record, a read-only record), the impact law
or a prescribed c_v. A second signature is a second compilation of the kernel (tens of
seconds on first use) and, for a literal constant, a second copy of its machine code.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest

import archquake.mechanism._kernels as K
from archquake.geometry import Arch
from archquake.ground import Record, SinePulse, StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.mechanism.prepared import KERNEL_TABLES

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def _record() -> Record:
    t = 0.01 * np.arange(101)
    return Record(4.9 * np.sin(2.0 * math.pi * t), 0.01, name="one cycle")


def test_every_motion_packs_to_one_type():
    """A step, a sine, a record and a read-only record: one `Excitation` type."""
    kind, params = _record().kernel_spec()
    frozen = params.copy()
    frozen.flags.writeable = False  # as a memory-mapped record's samples
    specs = [StepImpulse.from_g(1.0, 0.27).kernel_spec(), SinePulse.from_g(0.5, 0.4).kernel_spec(),
             (kind, params), (kind, frozen)]
    types = {numba.typeof(K.excitation(kind, params)) for kind, params in specs}
    types.add(numba.typeof(K.excitation(specs[2][0], specs[2][1], np.ones(101))))
    assert len(types) == 1


@pytest.mark.parametrize("restitution", [None, 0.6])
def test_every_impact_law_packs_to_one_table_type(restitution):
    """The paper's law (one row) and the chain law (its reachable set): one `Table` type."""
    types = {numba.typeof(PreparedMechanism.build(OPPENHEIM, law).kernel_table(restitution))
             for law in ("paper", "chain", "mirror")}
    assert len(types) == 1


def test_the_kernel_table_is_built_once_per_restitution_and_the_memo_is_bounded():
    """Oracle: object identity. The same table while memoised, a rebuilt (equal) one after
    `KERNEL_TABLES` other values of c_v have pushed it out."""
    prepared = PreparedMechanism.build(OPPENHEIM)
    first = prepared.kernel_table(None)
    assert prepared.kernel_table(None) is first
    for k in range(KERNEL_TABLES):
        prepared.kernel_table(0.1 + 0.05 * k)
    again = prepared.kernel_table(None)
    assert again is not first
    for a, b in zip(again, first, strict=True):
        np.testing.assert_array_equal(a, b)


def test_settings_read_back_by_their_indices():
    s = K.settings(9.81, 4.0, 1e-9, 1e-10, 1e-6, 200, dt_out=0.01, hist_limit=7,
                   initial_rate=0.3)
    assert s.shape == (K.N_SETTINGS,) and s.dtype == np.float64
    assert (s[K.S_G], s[K.S_T_END], s[K.S_RTOL], s[K.S_ATOL_PHI], s[K.S_REST_ROTATION],
            s[K.S_MAX_IMPACTS], s[K.S_DT_OUT], s[K.S_DT_LOCK], s[K.S_HIST_LIMIT],
            s[K.S_INITIAL_RATE]) == (9.81, 4.0, 1e-9, 1e-10, 1e-6, 200, 0.01, 0.01, 7, 0.3)
    assert K.settings(9.81, 4.0, 1e-9, 1e-10, 1e-6, 200, dt_out=0.01, dt_lock=0.1)[K.S_DT_LOCK] \
        == 0.1


def test_each_kernel_compiles_once_for_every_workload():
    """After histories (pulse, record, requested times, free rocking, the
    chain law, a prescribed c_v), a batch of pulses and a batch of records, every four-link,
    domains and IDA kernel holds one signature."""
    from archquake.domains.batch import evaluate_pulses
    from archquake.ida.batch import evaluate_cases
    from archquake.sweeps.cases import ArchSpec, Case, ExcitationKind, ExcitationSpec, Model
    from archquake.warm import dispatchers

    prepared = PreparedMechanism.build(OPPENHEIM)
    step = StepImpulse.from_g(1.0, 0.27)
    simulate(prepared, step)
    simulate(prepared, step, t_eval=[0.1, 0.5], options=SolverOptions(output_interval=-1.0))
    simulate(prepared, StepImpulse.from_g(0.0, 0.27), initial_rate=0.2, t_end=1.0)
    simulate(prepared, _record())
    simulate(PreparedMechanism.build(OPPENHEIM, "chain"), step, restitution=0.5)
    evaluate_pulses(OPPENHEIM, "step", [0.5, 1.0], [0.27, 0.27])
    spec = ExcitationSpec(ExcitationKind.RECORD, motion=_record(), scale=2.0)
    evaluate_cases([Case(ArchSpec(10.0, 0.15, 157.5, 7), spec, model=Model.FOURLINK)])
    modules = ("archquake.mechanism.", "archquake.domains.", "archquake.ida.")
    held = {f"{d.py_func.__module__}.{d.py_func.__name__}": [str(s) for s in d.signatures]
            for d in dispatchers() if d.py_func.__module__.startswith(modules)}
    assert held["archquake.mechanism._kernels.simulate_kernel_eval"]  # the histories ran
    assert held["archquake.ida._kernels.batch_kernel"]  # and the batches
    assert {name: sigs for name, sigs in held.items() if len(sigs) > 1} == {}
