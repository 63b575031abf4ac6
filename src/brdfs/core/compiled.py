"""Whether the compiled single-angle routes run: numba importable, and not switched off.

A single albedo call spends most of its time in numpy's per-call overhead (a few hundred ufunc
calls on arrays of a few hundred nodes), which a curve shares among its angles.  The routes that
have a compiled replica of their single-element path (:mod:`.gauss_kronrod_compiled` and a kernel)
take it when :func:`available` says so; the numpy path stays the reference and the fallback, and
the tests hold the two together (:func:`numpy_only`).

The environment variable ``BRDFS_COMPILED=0`` switches the compiled routes off for a process
(read once, at the first call); without numba (the optional extra ``fast``) they are off.
"""
from __future__ import annotations

import contextlib
import importlib.util
import os

from brdfs.core.estimate import BUDGET_EXHAUSTED, CONVERGED, STALLED

#: The statuses of :mod:`.gauss_kronrod_compiled`'s codes (0, 1, 2), as :class:`.Estimate` names them.
STATUS_NAMES = (CONVERGED, STALLED, BUDGET_EXHAUSTED)
#: The variable that switches the compiled routes off (``0``, ``false``, ``no`` or ``off``).
ENVIRONMENT_SWITCH = "BRDFS_COMPILED"

_state = {"available": None, "suspended": 0}


def available() -> bool:
    """Whether the compiled routes run now: numba importable, the environment does not switch them
    off, and no :func:`numpy_only` block is open."""
    if _state["suspended"]:
        return False
    known = _state["available"]
    if known is None:
        known = _state["available"] = _numba_present() and not _switched_off(os.environ.get(ENVIRONMENT_SWITCH))
    return known


def _numba_present() -> bool:
    return importlib.util.find_spec("numba") is not None


def _switched_off(setting) -> bool:
    return setting is not None and setting.strip().lower() in ("0", "false", "no", "off")


@contextlib.contextmanager
def numpy_only():
    """Inside the block every route takes its numpy path (the reference the compiled routes are
    held to)."""
    _state["suspended"] += 1
    try:
        yield
    finally:
        _state["suspended"] -= 1


def status_name(code: int) -> str:
    """The :class:`.Estimate` status of a compiled driver's status ``code``."""
    return STATUS_NAMES[code]
