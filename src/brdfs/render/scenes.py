"""Materials from config entries, and rendering a scene into display pixels plus statistics.

Material entries (one dict per object):

* ``{metal: gold, model: phong_cosmin, n: 20}`` — eq. 3.29: the package's model × Fresnel of the
  metal's measured complex index at the eight wavelengths, at the angle the model declares
  (``fresnel_cosine``: Θ_min for the Phong-type models, L·H for the microfacet models, θ' of
  eq. 4.53 for the patch models, eq. 4.54); ``pumped: 1`` divides the model by its albedo once (eq. 2.20,
  :class:`brdfs.physics.models.pumped.Pumped`, built with its table by the model factory
  :mod:`brdfs.numerics.tables`);
* ``{rgb: [r, g, b], a_s: 0.04, n: 169}`` — the plastic of eq. 3.31 (r, g, b channels);
* ``{diffuse: 0.5}`` — Lambert, flat spectrum;
* ``{model: generalized_lambertian, d: 0.5}`` — any package model with F = 1 (gray).
"""
from __future__ import annotations

import functools

import numpy as np

from brdfs.numerics import tables
from brdfs.physics import optical_constants
from brdfs.render import materials, spectrum

SPECTRAL = len(spectrum.WAVELENGTHS_NM)
#: Accuracy of the albedo table a pumped model divides by (a render needs no more).
PUMPING_TABLE_RTOL = 1e-6


def complex_indices(metal: str) -> np.ndarray:
    """n + ik of ``metal`` at the eight wavelengths (``complex_index`` of the spectral module)."""
    ior = np.asarray(optical_constants.complex_index(metal, spectrum.WAVELENGTHS_NM), complex)
    return ior.real + 1j * np.abs(ior.imag)


@functools.lru_cache(maxsize=None)
def pumped(base, levels: int):
    """``base`` divided ``levels`` times by its albedo (g1, eq. 2.20), from albedo tables."""
    for _ in range(levels):
        base = tables.pump(base, "g1", target_rtol=PUMPING_TABLE_RTOL, engine_rtol=1e-8)
    return base


def _model(spec: dict):
    params = {k: v for k, v in spec.items() if k not in ("metal", "model", "pumped", "label", "channels")}
    return pumped(tables.build(spec["model"], **params), int(spec.get("pumped", 0)))


def make_material(spec: dict, channels: int = SPECTRAL):
    """A :class:`~brdfs.render.materials.Material` from a config entry (module docstring)."""
    spec = dict(spec)
    label = spec.pop("label", "")
    if "diffuse" in spec:
        return materials.lambert(np.full(channels, float(spec["diffuse"])), label=label or "diffuse")
    if "rgb" in spec:
        if channels != 3:
            raise ValueError(f"plastic {spec!r}: eq. 3.31 is an r, g, b model, the scene has {channels} channels")
        model = tables.build("phong_cosmin", n=spec["n"])
        return materials.plastic(spec["rgb"], spec["a_s"], model, label=label or "plastic")
    if "metal" in spec:
        if channels != SPECTRAL:
            raise ValueError(f"metal {spec!r}: metals are rendered at the {SPECTRAL} wavelengths")
        return materials.specular(_model(spec), channels, ior=complex_indices(spec["metal"]),
                                  label=label or spec["metal"])
    if "model" in spec:
        return materials.specular(_model(spec), channels, label=label or spec["model"])
    raise ValueError(f"material entry {spec!r} has none of the keys diffuse, rgb, metal, model")
