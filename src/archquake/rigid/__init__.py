"""The rigid-block chain: rigid voussoirs with unilateral, plastic, no-slip (or Coulomb) joint
contacts and any number of open hinges, the rigid limit of the distinct-element model.

`model` packs an arch (or any block assembly, `archquake.blocks`'s
description) and holds the tolerances every integrator reads; two integrators read it: the
Moreau-Jean time stepper (`steps`) and the event integrator
(`events`); `forces` recovers the joint forces of a
run; `simulate_rigid` (`run`) drives either to a verdict.
"""

from archquake.rigid.model import DEFAULT_TIME_STEP, RigidModel
from archquake.rigid.run import RigidRun, simulate_rigid
from archquake.rigid.verdict import RigidVerdict, rigid_verdict, rigid_verdicts

__all__ = ["DEFAULT_TIME_STEP", "RigidModel", "RigidRun", "RigidVerdict", "rigid_verdict",
           "rigid_verdicts", "simulate_rigid"]
