"""BRDF models by the names of the published-values file (data/published_values.csv)."""
from __future__ import annotations

from brdfs.physics.models.base import BRDF
from brdfs.physics.models.blinn import Blinn, BlinnCosmin, BlinnOriginal
from brdfs.physics.models.he_torrance import HeTorrance
from brdfs.physics.models.microfacet import CookTorrance, Ward, WardCosmin
from brdfs.physics.models.phong import Phong, PhongCosmin, PhongOriginal, PModel, phong_constant

MODELS: dict[str, type[BRDF]] = {
    cls.name: cls
    for cls in (Phong, PhongOriginal, PhongCosmin, PModel, Blinn, BlinnOriginal, BlinnCosmin,
                Ward, WardCosmin, CookTorrance, HeTorrance)
}


def register(cls):
    """Add a model class (with a unique ``name``) to :data:`MODELS`; usable as a decorator."""
    MODELS[cls.name] = cls
    return cls


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


from brdfs.physics.models.patch import GeneralizedLambertian, PatchBasic, PatchElliptical, PatchExponential, PatchMixture  # noqa: E402

for _patch_model in (PatchBasic, PatchMixture, PatchExponential, PatchElliptical, GeneralizedLambertian):
    register(_patch_model)

__all__ = ["BRDF", "MODELS", "model", "register", "phong_constant", *[c.__name__ for c in MODELS.values()]]

from brdfs.physics.models.smith_microfacet import BeckmannMicrofacet, GGXMicrofacet  # noqa: E402

for _smith_model in (GGXMicrofacet, BeckmannMicrofacet):
    register(_smith_model)
