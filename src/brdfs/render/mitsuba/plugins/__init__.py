"""The package's BRDFs as Mitsuba 3 BSDF plugins, written in Dr.Jit (they run in the JIT variants).

Names a scene can load after :func:`register_plugins` (``mi.load_dict({"type": "brdfs_phong_cosmin", "n": 20})``):

=========================  ==================================================================================
``brdfs_lambert``          ρ/π; ``reflectance``
``brdfs_phong``            reciprocal Phong (eq. 2.6); ``n``, ``C``; ``pumping = "g1"`` / ``"g2"`` (eqs. 2.20/2.21)
``brdfs_phong_cosmin``     the new model (eq. 3.10); ``n``, ``C``; ``eta``, ``k``: its metal (eq. 3.29)
``brdfs_blinn``            reciprocal Blinn (eq. 1.34); ``n``, ``C``
``brdfs_blinn_cosmin``     corrected Blinn (eq. 3.34); ``n``, ``C``
``brdfs_ward``             Ward (eq. 2.8); ``m``, ``C``
``brdfs_cook_torrance``    Cook–Torrance (eq. 2.9); ``m``, ``C``, ``G`` (``torrance_sparrow``, ``smith``, ``none``)
``brdfs_ggx``              GGX with Smith's G2; ``alpha``, ``G2``, ``ior_re``, ``ior_im``
``brdfs_beckmann``         Beckmann with Smith's G2; ``alpha``, ``G2``, ``ior_re``, ``ior_im``
``brdfs_<patch model>``    the patch models of chapter 4 (:mod:`.patch`, where present)
``brdfs_model``            any registered model by ``model`` (its name) and its parameters, through numpy:
                           slower, wavefront mode only (:mod:`.generic`)
=========================  ==================================================================================

Every plugin also takes ``specular`` (the lobe's weight; Lambert's is ``reflectance``),
``diffuse_reflectance`` (adds ρ_d/π, one-sample MIS over the two lobes), ``eta`` and ``k`` (a metal:
the lobe times the conductor Fresnel at the model's angle: Θ_min for the Phong family, L·H for the
microfacet models, θ' for the patch models; refused beside ``ior_re``) and ``strategy`` (the model's
own sampler by default, or ``"cosine"``).
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:   # what _modules() imports by name, named here for the workflow's code provenance
    from brdfs.render.mitsuba.plugins import _common, generic, lambert, microfacet, patch, phong  # noqa: F401

#: The modules holding plugins, each with a ``PLUGINS`` dict (model name -> class).
PLUGIN_MODULES = ("lambert", "phong", "microfacet", "patch", "generic")
#: The prefix of every registered name.
PREFIX = "brdfs_"

_REGISTERED: dict[str, tuple[str, ...]] = {}


def _modules():
    """The plugin modules, (re)imported against the current variant: a module's classes subclass the
    ``mi.BSDF`` of the variant it was imported under."""
    import mitsuba as mi

    common = importlib.import_module(f"{__name__}._common")
    stale = getattr(common, "VARIANT", None) != mi.variant()
    if stale:
        common = importlib.reload(common)
        common.VARIANT = mi.variant()
    found = []
    for name in PLUGIN_MODULES:
        try:
            module = importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            continue                          # a plugin module not (yet) written
        found.append(importlib.reload(module) if stale else module)
    return found


def plugin_classes() -> dict:
    """Registered name (``brdfs_<model>``) -> plugin class, for the current variant."""
    classes = {}
    for module in _modules():
        for model_name, cls in module.PLUGINS.items():
            classes[PREFIX + model_name] = cls
    return classes


def register_plugins() -> tuple[str, ...]:
    """Register every plugin with Mitsuba under ``brdfs_<model name>`` for the current variant
    (idempotent; set the variant first, :func:`brdfs.render.mitsuba.use_variant`).  Returns the names."""
    import mitsuba as mi

    if mi.variant() is None:
        raise RuntimeError("register_plugins: no Mitsuba variant set; call brdfs.render.mitsuba.use_variant(...) first")
    if mi.variant() not in _REGISTERED:
        classes = plugin_classes()
        for name, cls in classes.items():
            mi.register_bsdf(name, lambda props, cls=cls: cls(props))
        _REGISTERED[mi.variant()] = tuple(classes)
    return _REGISTERED[mi.variant()]
