"""The timing rule of the benchmarks: the best of a few runs (``time.perf_counter``), after one
warm-up run where the first call pays for compilation or caches (Dr.Jit kernels, tables)."""
from __future__ import annotations

import time

import numpy as np


def best_time(fn, repeats: int = 3, warm_up: bool = True, clock=time.perf_counter) -> float:
    """Seconds of the fastest of ``repeats`` calls of ``fn()`` by ``clock`` (wall time by default;
    ``time.process_time`` for CPU time)."""
    if warm_up:
        fn()
    best = np.inf
    for _ in range(repeats):
        start = clock()
        fn()
        best = min(best, clock() - start)
    return best
