"""Changes of variables that follow a lobe: the radial angle β of a frame as a function of t.

t is the cumulative distribution of the lobe's own radial weight (the variable importance
sampling draws uniformly), so a narrow lobe (n = 512, m = 0.005) becomes a smooth integrand on
[0, 1].  ``sin β dβ/dt`` — the solid-angle element per unit t — is returned in closed form so that
no ratio of two underflowing numbers is ever formed.

Frames (:class:`Frame`, compared by identity, never by name): :data:`MIRROR` — β = α, the angle
between V and R (Phong family, eq. 3.5); :data:`HALF` — β = δ, the angle between H and N (Blinn,
Ward, Cook–Torrance), where dω_V = 4 (V·H) dω_H; :data:`SCATTERING` — the horizontal scattering
vector r = |L_xy + V_xy| (Kirchhoff lobes, He–Torrance), integrated by
:mod:`brdfs.numerics.integrate.scattering`.  A model without a lobe (the patch models of chapter 4,
whose albedo is their own) declares ``lobe = None``.
"""
from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np


class Frame(enum.Enum):
    """The pole of a lobe's coordinates: which direction the radial angle β is measured from."""

    #: β = α, the angle between V and the mirror direction R (dω_V = sin α dα dφ).
    MIRROR = "mirror"
    #: β = δ, the angle between the half vector H and N (dω_V = 4 (L·H) dω_H).
    HALF = "half"
    #: r = |L_xy + V_xy|, the horizontal scattering vector (and N·V).
    SCATTERING = "scattering"

    def __repr__(self):
        return f"Frame.{self.name}"


MIRROR, HALF, SCATTERING = Frame.MIRROR, Frame.HALF, Frame.SCATTERING


@dataclass(frozen=True)
class PowerCosine:
    """Radial weight cos^n β sin β (eq. 3.19/3.20): t = 1 − cos^(n+1) β."""

    n: float
    frame: Frame

    @property
    def reaches_hemisphere(self):
        """Whether t ∈ [0, 1] (β ∈ [0, π/2]) covers every V above the horizon: about N·H yes (N·H > 0
        whenever N·L, N·V > 0); about R no, it stops at R·V = 0 (β = π/2 < π/2 + θ)."""
        return self.frame is not Frame.MIRROR

    @property
    def rounding(self):
        """Relative rounding error of the weight, in ulps: cos β carries ~1 ulp, cos^n β n of them."""
        return self.n + 1.0

    def angle(self, t):
        """(cos β, sin β) at t, computed without cancellation for small β."""
        y = np.log1p(-t) / (self.n + 1.0)
        c = np.exp(y)
        s = np.sqrt(np.maximum(-np.expm1(y) * (1.0 + c), 0.0))
        return c, s

    def weight_per_t_form(self, C=1.0):
        """C cos^n β sin β dβ per unit t = C/(n+1), as the form (c, k, d) of c cos^k β / d: (C, 0, n+1)
        (the radial weight of the closed-form azimuth, :attr:`brdfs.physics.models.base.BRDF.azimuth_weight_form`)."""
        return (C, 0, self.n + 1.0)

    def solid_angle_per_t(self, t, cos_b, sin_b):
        """sin β dβ/dt = 1 / ((n+1) cos^n β)."""
        return 1.0 / ((self.n + 1.0) * (1.0 - t)) * cos_b

    def t_of(self, beta):
        # np.minimum(np.maximum(...)), not np.clip (twice its cost on a single angle's few values);
        # cos β ≥ cos(π/2) = 6.1e-17 > 0 in floats, so the log never divides by zero
        beta = np.minimum(np.maximum(beta, 0.0), np.pi / 2)
        return -np.expm1((self.n + 1.0) * np.log(np.cos(beta)))


@dataclass(frozen=True)
class MicrofacetLobe:
    """Radial weight of a microfacet distribution in the half-vector frame (eqs. 2.8/2.9): t is the
    distribution's own radial CDF (:meth:`brdfs.physics.distributions.Beckmann.cdf`)."""

    distribution: object
    frame: Frame = HALF
    #: δ ∈ [0, π/2] covers every V above the horizon (:attr:`PowerCosine.reaches_hemisphere`).
    reaches_hemisphere = True

    @property
    def rounding(self):
        return self.distribution.rounding

    def angle(self, t):
        tan_b = self.distribution.tan_of_cdf(t)
        c = 1.0 / np.sqrt(1.0 + tan_b * tan_b)
        return c, tan_b * c

    def solid_angle_per_t(self, t, cos_b, sin_b):
        return self.distribution.solid_angle_per_t(t, cos_b)

    def t_of(self, beta):
        return self.distribution.cdf(np.tan(np.minimum(np.maximum(beta, 0.0), np.pi / 2)))


@dataclass(frozen=True)
class ScatteringLobe:
    """A lobe in r = |L_xy + V_xy| of radial scale ``width``, with a boundary layer of thickness
    ``horizon_scale`` in N·V at the horizon."""

    width: float
    horizon_scale: float
    frame: Frame = SCATTERING
    #: r ∈ [0, 2] covers every V above the horizon (:attr:`PowerCosine.reaches_hemisphere`).
    reaches_hemisphere = True

    def radial_levels(self):
        """width × 2^k below 2 (the largest r), ascending: the scales of a Gaussian mixture in r."""
        levels = self.width * 2.0 ** np.arange(-1, 64)
        return levels[levels < 2.0]

    def nv_levels(self):
        """horizon_scale × 4^k (k = 1 … −5), ascending: the boundary layer and its logarithmic end."""
        return self.horizon_scale * 4.0 ** np.arange(-5, 2)
