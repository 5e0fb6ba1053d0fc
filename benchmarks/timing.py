"""The benchmarks' one timer: the best of ``repeat`` rounds of ``number`` calls, s per call.

Best-of, not mean: on shared cores the least time is the one least disturbed by other load.
"""

from __future__ import annotations

import math
import time


def best_of(fn, repeat: int = 7, number: int = 1) -> float:
    """Least wall time of one call of ``fn()``, s, over ``repeat`` rounds of ``number`` calls."""
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


#: The example bridge's ring on the command line (R 5 m, t 0.6 m, 15 voussoirs, 1800 kg/m^3).
BRIDGE_ARGS = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15",
               "--density", "1800"]


def best_process(argv: list[str], repeat: int = 3) -> float:
    """Best wall time, s, of ``archquake *argv`` as a whole process over ``repeat`` runs."""
    import subprocess
    import sys
    from pathlib import Path

    exe = str(Path(sys.executable).with_name("archquake"))
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([exe, *argv], check=True, capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best
