"""The Dormand-Prince 5(4) tableau (Dormand & Prince 1980; Hairer, Norsett & Wanner, *Solving
Ordinary Differential Equations I*, Table 5.2): the one set of coefficients every embedded
Runge-Kutta step of the package reads (the four-link model's, `archquake.mechanism._kernels`,
and the rigid chain's event integrator, `archquake.rigid._event_kernels`).

``C`` nodes, ``A`` stage weights, ``B`` the fifth-order solution's weights (first same as
last: ``B`` is the seventh stage's row), ``E`` the error estimate's weights, the difference
between the fifth- and fourth-order solutions (``E7`` weighs the derivative at the new point).

Why there are two steps over this one tableau
---------------------------------------------
The four-link model (``mechanism._kernels.dopri_step``) and the rigid chain's event integrator
(``rigid._event_kernels.dopri_step``) each write their own step. One step for both was built
and measured, and kept out because it slowed both kernels by about 5 %:

* *The right-hand side as an argument* (a numba dispatcher passed to the step) cannot be cached:
  numba embeds the function's address in the caller (a "dynamic global") and refuses to write
  the caller to disk, so every process would compile the four-link kernel again (10-40 s).
* *A factory* ``make_step(rhs)``, a cached ``njit`` closure calling ``rhs(args, t, t_left, y,
  out) -> bool`` on a state array, caches (each model's step is its own cache entry, renewed
  when the right-hand side's code changes) and gives every number bit for bit (the sums kept in
  the tableau's order: the digests of tests/test_digest.py did not change). But the four-link
  step is scalar: its state (phi, phi') and six stages live in registers, and the generic step
  moves them through two-element work arrays threaded down to every call (the step, the event
  location, the requested states). The event integrator's right-hand side gains a tuple of
  twelve arguments (the work arrays among them) per evaluation.
* Measured (CPU time by ``time.process_time``, 4 pairs of processes alternating the two
  versions, the least of 7 x 300 calls, resp. 5 x 4 calls, in each; Oppenheim's arch, step
  1.0 g, t_p = 0.20 s, 4 s, the history of ``benchmarks/bench_history.py`` and
  ``bench_rigid_chain.py``): the four-link kernel 1.049 times as long (median of the pairs;
  1.069 with the step inlined by numba, ``inline="always"``), the event integrator 1.045
  (1.052 inlined). The step alone, in a loop of 400,000 steps of the four-link model: 1.018.
  The same code measured the same way (before and after an unrelated change) gave 1.00 to 1.08
  on the four-link kernel, so its excess is at the noise, but 0.99 to 1.00 on the event
  integrator, so its 4.5 to 6 % is not.

A shared step over arrays would pay for itself only if the four-link kernel kept its whole
state in arrays, which costs it more than the duplicated twelve lines of stage sums.
"""

from __future__ import annotations

C2, C3, C4, C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
A21 = 1.0 / 5.0
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = (9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0,
                           -5103.0 / 18656.0)
B1, B3, B4, B5, B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                          22.0 / 525.0, -1.0 / 40.0)
