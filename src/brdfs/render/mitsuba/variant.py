"""Choosing a Mitsuba 3 variant, with the system library its JIT variants need.

Mitsuba's ``llvm_*`` variants compile their kernels with LLVM at run time and find the library
through ``DRJIT_LIBLLVM_PATH``; Mitsuba 3.9.1 / Dr.Jit 1.5.0 need LLVM 19 (LLVM 15 fails).  Debian
ships it as ``libllvm19``.  :func:`use_variant` points ``DRJIT_LIBLLVM_PATH`` at Debian's copy when
it is unset, and where there is none says in one line what to run.
"""
from __future__ import annotations

import os
from pathlib import Path

#: Where Debian's libllvm19 puts the library (the package's own path, then llvm-19's link).
DEBIAN_LIBLLVM_PATHS = ("/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/llvm-19/lib/libLLVM.so",
                        "/usr/lib/aarch64-linux-gnu/libLLVM-19.so")
#: The one line a machine without LLVM 19 gets.
MISSING_LLVM = ("Mitsuba's llvm variants need Debian's libllvm19: run `make llvm` "
                "(apt-get install libllvm19)")


class MissingLLVM(RuntimeError):
    """An ``llvm_*`` variant was asked for on a machine without LLVM 19."""


def find_libllvm(candidates=DEBIAN_LIBLLVM_PATHS) -> str | None:
    """``DRJIT_LIBLLVM_PATH`` if set, else the first of ``candidates`` that exists, else None."""
    configured = os.environ.get("DRJIT_LIBLLVM_PATH")
    if configured:
        return configured
    return next((path for path in candidates if Path(path).exists()), None)


def use_variant(name: str = "llvm_ad_rgb", candidates=DEBIAN_LIBLLVM_PATHS):
    """Set Mitsuba's variant ``name`` (e.g. ``"llvm_ad_rgb"``, ``"llvm_ad_mono"``,
    ``"llvm_ad_spectral"``, ``"scalar_rgb"``) and return the ``mitsuba`` module.

    For an ``llvm_*`` variant, ``DRJIT_LIBLLVM_PATH`` is set to Debian's libllvm19 when unset (it must
    be set before Dr.Jit first initialises its LLVM backend); :class:`MissingLLVM` (one line:
    :data:`MISSING_LLVM`) where the library is not found.  An unknown variant raises ``ValueError``
    naming it and the variants this Mitsuba build has.
    """
    if name.startswith("llvm_"):
        path = find_libllvm(candidates)
        if path is None or not Path(path).exists():
            raise MissingLLVM(MISSING_LLVM)
        os.environ["DRJIT_LIBLLVM_PATH"] = path
    import mitsuba as mi

    if name not in mi.variants():
        raise ValueError(f"variant = {name!r}: not a variant of this Mitsuba build; choose one of {mi.variants()}")
    if mi.variant() != name:
        mi.set_variant(name)
    return mi
