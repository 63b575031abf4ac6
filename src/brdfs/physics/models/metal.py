"""The new model for metals (eq. 3.29): Fresnel reflectance evaluated at Θ_min.

    f(L, V, λ) = (n+2)/(2π) · cos^n α / cos Θ_min · F(κ(λ), Θ_min),   cos Θ_min = max(N·L, N·V)

Θ_min = min(Θ_L, Θ_V) is a symmetric function of L and V, so the model stays reciprocal; since
F(Θ_min) ≤ 1 and the new model (eq. 3.10) conserves energy, so does this one. F varies with V
inside the albedo integral, so a(L) is *not* F(θ_L) times the new model's albedo: the engine
integrates this model directly. Its only kink besides the lobe is the one of max(N·L, N·V), at
N·V = N·L, which the new model already reports.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.models.base import BRDF
from brdfs.physics.models.phong import PhongCosmin


@dataclass(frozen=True)
class PhongCosminMetal(PhongCosmin):
    """eq. 3.29 with the complex index ``ior_re + i ior_im`` of one wavelength."""

    ior_re: float = field(kw_only=True)
    ior_im: float = field(kw_only=True, default=0.0)
    name = "phong_cosmin_metal"
    # The Fresnel factor voids the closed forms of the new model it extends.
    closed_form_azimuth = None
    limit_cos_power = None
    limit_albedo_90 = None
    grazing_law = BRDF.grazing_law
    exact_albedo = BRDF.exact_albedo

    def __post_init__(self):
        super().__post_init__()
        if not (np.isfinite(self.ior_re) and self.ior_re > 0):
            raise ValueError(f"ior_re must be positive, got {self.ior_re!r}")
        if not (np.isfinite(self.ior_im) and self.ior_im >= 0):
            raise ValueError(f"ior_im must be non-negative, got {self.ior_im!r}")

    def fresnel_at_theta_min(self, nl, nv):
        """F(κ, Θ_min) with cos Θ_min = max(N·L, N·V)  (eq. 3.29)."""
        return unpolarised_reflectance(np.maximum(nl, nv), self.ior_re, self.ior_im)

    def _eval(self, L, V, nl, nv):
        return super()._eval(L, V, nl, nv) * self.fresnel_at_theta_min(nl, nv)
