"""Microfacet distributions: the normal distribution D, its radial CDF and sampling, Smith's Λ and G1.

One type per distribution, apart from the models that use it (as pbrt-v4 keeps
``TrowbridgeReitzDistribution`` apart from ``ConductorBxDF``): Ward, corrected Ward and Cook–Torrance
(eqs. 2.8, 2.9, 3.35, 3.36) share :class:`Beckmann`; the lobe coordinates of the integration engine
(:mod:`brdfs.numerics.integrate.lobes`) and the grazing analysis (:mod:`brdfs.numerics.grazing`)
use its CDF, its sampling and its Smith functions.

Conventions.  δ is the angle between the microfacet normal H and N, ``tan2`` = tan²δ.  ``D`` is
normalised so that ∫ D(H) (N·H) dω_H = 1 (the projected microfacet area per unit macro area).
The *radial weight* is the part of D·cos δ·sin δ dδ that importance sampling draws: for Beckmann
t = 1 − exp(−tan²δ/α²) is uniform.

References
----------
Beckmann & Spizzichino (1963); Walter et al. (2007), "Microfacet models for refraction through
rough surfaces", eqs. 25–27 (Beckmann D, Λ, G1); Heitz (2014), "Understanding the
masking-shadowing function", eq. 72 (Beckmann Λ).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import erf, erfc

from brdfs.physics.models.base import check_positive


def half_vector_tan2(L, V):
    """(tan²δ, cos δ) of the half vector of L and V, from h = L + V without cancellation."""
    h = np.asarray(L, float) + np.asarray(V, float)
    hz2 = h[..., 2] ** 2
    hxy2 = h[..., 0] ** 2 + h[..., 1] ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        return hxy2 / hz2, np.sqrt(hz2 / (hz2 + hxy2))


@dataclass(frozen=True)
class Beckmann:
    """Beckmann distribution, D = exp(−tan²δ/α²) / (π α² cos⁴δ), roughness α (the thesis's m).

    >>> d = Beckmann(0.3)
    >>> round(float(d.cdf(d.tan_of_cdf(0.25))), 12)
    0.25
    >>> float(d.smith_g1(1.0))
    1.0
    """

    alpha: float
    name = "beckmann"

    def __post_init__(self):
        check_positive("alpha", self.alpha)

    # --- the distribution ----------------------------------------------------------------------
    def slope_weight(self, tan2):
        """exp(−tan²δ/α²), the unnormalised Beckmann weight of eqs. 2.8/2.9 (1 at δ = 0)."""
        return np.exp(-np.asarray(tan2, float) / self.alpha ** 2)

    def D(self, cos_delta):
        """D(δ) = exp(−tan²δ/α²) / (π α² cos⁴δ); zero below the horizon."""
        c = np.asarray(cos_delta, float)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tan2 = (1.0 - c) * (1.0 + c) / (c * c)
            d = self.slope_weight(tan2) / (np.pi * self.alpha ** 2 * c ** 4)
        return np.where(c > 0, d, 0.0)

    # --- radial CDF and sampling ---------------------------------------------------------------
    def cdf(self, tan_delta):
        """t(δ) = ∫₀^δ D cos δ' dω / 2π = 1 − exp(−tan²δ/α²)."""
        return -np.expm1(-(np.asarray(tan_delta, float) / self.alpha) ** 2)

    def tan_of_cdf(self, t):
        """tan δ at the CDF value t: α √(−ln(1 − t)) (Ward 1992; Walter et al. 2007, eq. 28)."""
        return self.alpha * np.sqrt(-np.log1p(-np.asarray(t, float)))

    def solid_angle_per_t(self, t, cos_delta):
        """sin δ dδ/dt = α² cos³δ / (2 (1 − t)), the solid angle of H per unit of the CDF (over 2π)."""
        return self.alpha ** 2 * cos_delta ** 3 / (2.0 * (1.0 - t))

    #: Relative rounding of the weight in ulps: exp(−x) carries x ulps of the rounding of x, and
    #: the weight matters up to x ≈ ln(1/ε) ≈ 36.
    rounding = 40.0

    def sample_normal(self, u1, u2):
        """Microfacet normals H with density D(H) (N·H) from uniform (u1, u2); shape (..., 3)."""
        tan_d = self.tan_of_cdf(u1)
        cos_d = 1.0 / np.sqrt(1.0 + tan_d * tan_d)
        phi = 2.0 * np.pi * np.asarray(u2, float)
        sin_d = tan_d * cos_d
        return np.stack([sin_d * np.cos(phi), sin_d * np.sin(phi), cos_d], -1)

    def normal_pdf(self, cos_delta):
        """Density of :meth:`sample_normal` per solid angle of H: D(H) (N·H)."""
        return self.D(cos_delta) * np.asarray(cos_delta, float)

    # --- Smith masking -------------------------------------------------------------------------
    def smith_lambda(self, cos_theta):
        """Exact Λ(θ) = (erf(a) − 1)/2 + exp(−a²)/(2a√π), a = 1/(α tan θ) (Walter et al. 2007, eq. 27 context;
        Heitz 2014, eq. 72); 0 at normal incidence."""
        c = np.asarray(cos_theta, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            a = c / (self.alpha * np.sqrt(np.maximum((1.0 - c) * (1.0 + c), 0.0)))
            lam = 0.5 * (erf(a) - 1.0) + np.exp(-a * a) / (2.0 * a * np.sqrt(np.pi))
        return np.where(c >= 1.0, 0.0, np.where(c > 0, lam, np.inf))

    def smith_g1(self, cos_theta):
        """Exact Smith masking G1 = 1/(1 + Λ) of a Beckmann surface."""
        return 1.0 / (1.0 + self.smith_lambda(cos_theta))

    def smith_g1_thesis(self, cos_theta):
        """G*(x) as the thesis prints it (eq. 1.38): with h = x²/(2α²(1 − x²)),
        G* = g/(g + 1), g = √(πh) (2 − erfc √h).

        Not the exact Smith G1 of a Beckmann surface of the same α (at α = 0.3, cos θ = 0.3 it gives
        0.691 against 0.980): kept as a named variant, for Cook–Torrance with ``G='smith'``.
        """
        x = np.asarray(cos_theta, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            h = x * x / (2 * self.alpha ** 2 * (1 - x * x))
            g = np.sqrt(np.pi * h) * (2 - erfc(np.sqrt(h)))
        return np.where(x >= 1.0, 1.0, g / (g + 1))
