"""brdfs — recomputing Neumann (2001), *Constructions of Bidirectional Reflection Distribution Functions*.

Public API: :func:`albedo`, :func:`albedo_table`, :func:`model`, :data:`MODELS`, :class:`Estimate`;
:data:`__version__`.

The names are imported on first use (a module ``__getattr__``), so that ``import brdfs.physics``
loads the physics layer alone, not the numerics behind :func:`albedo`.
"""
from __future__ import annotations

import importlib

#: The package's version: the one place it is written (pyproject.toml reads it, ``brdfs --version``
#: prints it; ``CITATION.cff`` and ``CHANGELOG.md`` carry it with the release date, a test holds them).
__version__ = "0.2.0"
#: The release date of :data:`__version__` (ISO 8601).
__release_date__ = "2026-12-06"

#: Public name -> the module that defines it.
_HOMES = {
    "albedo": "brdfs.numerics.albedo",
    "albedo_table": "brdfs.numerics.albedo",
    "Estimate": "brdfs.core.estimate",
    "model": "brdfs.numerics.tables",     # builds the tables a model needs (brdfs.physics.models.model: none)
    "MODELS": "brdfs.physics.models",
    "ALBEDO_METHODS": "brdfs.numerics.albedo",
    "NotConvergedWarning": "brdfs.numerics.albedo",
    "NotConvergedError": "brdfs.numerics.albedo",
    "ArgumentError": "brdfs.numerics.arguments",
}

__all__ = ["albedo", "albedo_table", "model", "MODELS", "Estimate", "ALBEDO_METHODS", "NotConvergedWarning",
           "NotConvergedError", "ArgumentError"]


def __getattr__(name):
    try:
        home = _HOMES[name]
    except KeyError:
        raise AttributeError(f"module 'brdfs' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
