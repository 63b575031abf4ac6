"""BRDF models by the names of the published-values file (data/published_values.csv).

Each model module registers its own classes (:func:`register`); this package imports every
module under it, the thesis's families first (in the order of its chapters, which is the order of
:data:`MODELS`), then any other module found here — a new model family is one new file.
"""
from __future__ import annotations

import importlib
import pkgutil
from typing import TYPE_CHECKING

from brdfs.physics.models.base import BRDF, MODELS, register

if TYPE_CHECKING:   # what _import_model_modules() imports by name, named here for the workflow's code provenance
    from brdfs.physics.models import (blinn, he_torrance, metal, microfacet, oren_nayar, patch, phong,  # noqa: F401
                                      pumped, smith_microfacet)
from brdfs.physics.models.phong import phong_constant

#: The thesis's families in chapter order (chapters 2–4), then today's Smith microfacet models.
_ORDERED = ("phong", "blinn", "microfacet", "he_torrance", "patch", "smith_microfacet")


def _import_model_modules():
    found = sorted(m.name for m in pkgutil.iter_modules(__path__) if m.name != "base")
    for name in [*_ORDERED, *(m for m in found if m not in _ORDERED)]:
        importlib.import_module(f"{__name__}.{name}")


_import_model_modules()


def model(name: str, **params) -> BRDF:
    """Build a model from its published name, e.g. ``model("ward", m=0.1)``.

    The physics layer computes no table: a model that needs one (Kulla–Conty's compensated
    microfacet models, :meth:`BRDF.table_requests`) raises :class:`brdfs.physics.tables.MissingTable`
    here unless its table is passed; the front door :func:`brdfs.model`
    (:func:`brdfs.numerics.tables.build`) tabulates it and builds the model with it."""
    try:
        cls = MODELS[name]
    except KeyError:
        raise ValueError(f"unknown model {name!r}; known models: {sorted(MODELS)}") from None
    try:
        return cls(**params)
    except TypeError as exc:
        raise ValueError(f"bad parameters {params!r} for model {name!r}: {exc}") from None


def __getattr__(name):
    """The model classes by their class names (``from brdfs.physics.models import Phong``)."""
    for cls in MODELS.values():
        if cls.__name__ == name:
            return cls
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["BRDF", "MODELS", "model", "register", "phong_constant", *[c.__name__ for c in MODELS.values()]]
