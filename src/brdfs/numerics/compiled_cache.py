"""Fill numba's cache with the compiled single-angle routes, once after set-up.

numba compiles a route on its first call in a process and keeps the machine code in its cache
(``__pycache__`` beside the sources, or the user's cache where those are read-only); later processes
load it in a fraction of a second.  ``make`` runs this module after installing (``make compiled``),
so that the first compilation — seconds per route — happens at set-up, not inside the first test
or pipeline job that asks for a single angle.  It knows no route: single-angle albedos of every
registered model's example, at a few angles and tolerances (:data:`ANGLES`, :data:`RTOLS`), reach every
compiled function there is.

    python -m brdfs.numerics.compiled_cache
"""
from __future__ import annotations

import sys
import time
import warnings


#: Angles and tolerances of the single calls that reach every compiled function: numba compiles a function
#: at its first call, and some are called only near grazing (graded levels) or at tight tolerances (the
#: tight first partition); filled at 30° alone, a fresh clone's test workers compiled those again (+20 s).
ANGLES = (0.0, 1e-6, 30.0, 89.9999, 90.0 - 1e-9)
RTOLS = (1e-6, 1e-10)


def fill() -> float | None:
    """Compile (or load) every compiled route; the seconds it took (None without numba, or switched off)."""
    from brdfs.core import compiled
    if not compiled.available():
        return None
    from brdfs.numerics.albedo import albedo
    from brdfs.physics.models import MODELS
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for cls in MODELS.values():
            for theta in ANGLES:
                for rtol in RTOLS:
                    albedo(cls.example(), theta, rtol=rtol, warn=False)
    return time.perf_counter() - start


def main() -> int:
    seconds = fill()
    print(f"compiled routes: numba's cache ready ({seconds:.1f} s)" if seconds is not None else
          "compiled routes: numba not installed or switched off (BRDFS_COMPILED=0); the numpy routes run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
