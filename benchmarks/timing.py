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
