"""The Dormand-Prince 5(4) tableau (Dormand & Prince 1980; Hairer, Norsett & Wanner, *Solving
Ordinary Differential Equations I*, Table 5.2): the one set of coefficients every embedded
Runge-Kutta step of the package reads (the four-link model's, :mod:`archquake.mechanism._kernels`,
and the rigid chain's event integrator, :mod:`archquake.rigid._event_kernels`).

``C`` nodes, ``A`` stage weights, ``B`` the fifth-order solution's weights (first same as
last: ``B`` is the seventh stage's row), ``E`` the error estimate's weights, the difference
between the fifth- and fourth-order solutions (``E7`` weighs the derivative at the new point).
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
