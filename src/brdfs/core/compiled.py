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
import functools
import hashlib
import importlib.util
import os
import re
import sys
import threading
from pathlib import Path

from brdfs.core.estimate import BUDGET_EXHAUSTED, CONVERGED, STALLED

#: The statuses of :mod:`.gauss_kronrod_compiled`'s codes (0, 1, 2), as :class:`~brdfs.core.estimate.Estimate` names them.
STATUS_NAMES = (CONVERGED, STALLED, BUDGET_EXHAUSTED)
#: The variable that switches the compiled routes off (``0``, ``false``, ``no`` or ``off``).
ENVIRONMENT_SWITCH = "BRDFS_COMPILED"

_state = {"available": None}
#: The :func:`numpy_only` blocks open in each thread.
_suspended = threading.local()


def available() -> bool:
    """Whether the compiled routes run now: numba importable, the environment does not switch them
    off, and no :func:`numpy_only` block is open in this thread."""
    if getattr(_suspended, "depth", 0):
        return False
    known = _state["available"]
    if known is None:
        known = _state["available"] = _numba_present() and not _switched_off(os.environ.get(ENVIRONMENT_SWITCH))
    return known


def _numba_present() -> bool:
    """Whether numba imports (found but broken, e.g. built for another numpy: the numpy routes run)."""
    if importlib.util.find_spec("numba") is None:
        return False
    try:
        import numba  # noqa: F401
    except Exception:                  # noqa: BLE001 — any failure of a broken install means "not available"
        return False
    return True


def _switched_off(setting) -> bool:
    return setting is not None and setting.strip().lower() in ("0", "false", "no", "off")


@contextlib.contextmanager
def numpy_only():
    """Inside the block every route of this thread takes its numpy path (the reference the compiled
    routes are held to); other threads are not affected."""
    _suspended.depth = getattr(_suspended, "depth", 0) + 1
    try:
        yield
    finally:
        _suspended.depth -= 1


@functools.cache
def module(name: str):
    """The compiled module ``name``, imported at its first use (it imports numba: choosing a route must
    not), then kept (an import statement per call costs a single angle half a µs)."""
    return importlib.import_module(name)


def status_name(code: int) -> str:
    """The :class:`~brdfs.core.estimate.Estimate` status of a compiled driver's status ``code``."""
    return STATUS_NAMES[code]


def drop_stale_cache(module) -> bool:
    """Remove ``module``'s entries from numba's cache when a brdfs module it depends on has changed;
    whether it removed them.  Called by every compiled module at the end of its import.

    numba keys a cached function on its own source file only.  A compiled function keeps the machine
    code of the compiled functions it calls (the driver of :mod:`.gauss_kronrod_compiled`) and the
    values of the constants it reads (``SAFETY``, a route's grading) as they were when it was compiled:
    after one of those changes, the cache would go on answering with the old ones.  The fingerprint is
    the sources of every brdfs module ``module`` imports, directly or not; it is kept beside the cache."""
    dispatchers = [value for value in vars(module).values()       # its own (not one it imported)
                   if hasattr(getattr(value, "_cache", None), "_cache_path")
                   and getattr(getattr(value, "py_func", None), "__module__", None) == module.__name__]
    if not dispatchers:
        return False
    cache = Path(dispatchers[0]._cache._cache_path)
    stem = Path(module.__file__).stem
    stamp = cache / f"{stem}.{sys.implementation.cache_tag}.depends"
    fingerprint = _fingerprint(module.__name__)
    try:
        if stamp.read_text() == fingerprint:
            return False
    except OSError:
        pass
    for entry in cache.glob(f"{stem}.*.nb[ic]"):
        with contextlib.suppress(OSError):
            entry.unlink()
    with contextlib.suppress(OSError):
        cache.mkdir(parents=True, exist_ok=True)
        stamp.write_text(fingerprint)
    return True


def _fingerprint(name: str) -> str:
    """A hash of the sources of ``name`` and of every brdfs module it imports, directly or not."""
    digest = hashlib.sha256()
    for module_name in sorted(brdfs_imports(name)):
        digest.update(module_name.encode())
        digest.update(_source(module_name).read_bytes())
    return digest.hexdigest()


def brdfs_imports(name: str) -> set[str]:
    """``name`` and the brdfs modules it imports, directly or not (read from the sources: ``import
    brdfs.…`` and ``from brdfs.… import …`` statements, a name imported from a package counted where it
    is a module itself)."""
    seen, todo = set(), [name]
    while todo:
        current = todo.pop()
        if current in seen:
            continue
        seen.add(current)
        for statement in _IMPORT.finditer(_source(current).read_text()):
            module, names = statement.group("module") or statement.group("plain"), statement.group("names")
            if _is_brdfs_module(module):
                todo.append(module)
            for imported in _NAME.findall(names or ""):
                if _is_brdfs_module(f"{module}.{imported}"):
                    todo.append(f"{module}.{imported}")
    return seen


#: ``import brdfs.x`` or ``from brdfs.x import a, b as c, (…)`` at the start of a line (indented too).
_IMPORT = re.compile(r"^[ \t]*(?:import[ \t]+(?P<plain>brdfs[\w.]*)|from[ \t]+(?P<module>brdfs[\w.]*)[ \t]+import[ \t]+"
                     r"(?P<names>\([^)]*\)|[^\n]*))", re.M)
_NAME = re.compile(r"\b(\w+)\b(?:\s+as\s+\w+)?")


#: The directory of the brdfs package: module names map to files under it without importing them.
_PACKAGE = Path(__file__).resolve().parent.parent


def _source(name: str) -> Path | None:
    """The source file of the brdfs module ``name`` (None where it is not a module, e.g. a function)."""
    parts = name.split(".")[1:]
    base = _PACKAGE.joinpath(*parts)
    for candidate in (base.with_suffix(".py") if parts else None, base / "__init__.py"):
        if candidate is not None and candidate.is_file():
            return candidate
    return None


def _is_brdfs_module(name: str) -> bool:
    return name.split(".")[0] == "brdfs" and _source(name) is not None
