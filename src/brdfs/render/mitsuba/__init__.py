"""Mitsuba 3 as the package's renderer: the variant (:mod:`.variant`), the BRDFs as BSDF plugins
(:mod:`.plugins`), the integrator, scenes, metrics and spectral colour.

A user's own scene::

    import mitsuba as mi
    from brdfs.render.mitsuba import use_variant, register_plugins
    use_variant("llvm_ad_rgb")
    register_plugins()
    bsdf = mi.load_dict({"type": "brdfs_phong_cosmin", "n": 20})

Importing this package imports no Mitsuba; :func:`use_variant` does.
"""
from __future__ import annotations

from brdfs.render.mitsuba.variant import MISSING_LLVM, MissingLLVM, use_variant


def register_plugins():
    """Register the package's plugins for the current variant (:func:`.plugins.register_plugins`)."""
    from brdfs.render.mitsuba.plugins import register_plugins as register
    return register()


__all__ = ["use_variant", "register_plugins", "MissingLLVM", "MISSING_LLVM"]
