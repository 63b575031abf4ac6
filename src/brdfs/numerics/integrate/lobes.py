"""Changes of variables that follow a lobe: the radial angle β of a frame as a function of t.

t is the cumulative distribution of the lobe's own radial weight (the variable importance
sampling draws uniformly), so a narrow lobe (n = 512, m = 0.005) becomes a smooth integrand on
[0, 1].  ``sin β dβ/dt`` — the solid-angle element per unit t — is returned in closed form so that
no ratio of two underflowing numbers is ever formed.

Frames: ``"mirror"`` — β = α, the angle between V and R (Phong family, eq. 3.5);
``"half"`` — β = δ, the angle between H and N (Blinn, Ward, Cook–Torrance), where
dω_V = 4 (V·H) dω_H.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PowerCosine:
    """Radial weight cos^n β sin β (eq. 3.19/3.20): t = 1 − cos^(n+1) β."""

    n: float
    frame: str

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

    def solid_angle_per_t(self, t, cos_b, sin_b):
        """sin β dβ/dt = 1 / ((n+1) cos^n β)."""
        return 1.0 / ((self.n + 1.0) * (1.0 - t)) * cos_b

    def t_of(self, beta):
        beta = np.clip(beta, 0.0, np.pi / 2)
        with np.errstate(divide="ignore"):
            return -np.expm1((self.n + 1.0) * np.log(np.cos(beta)))


@dataclass(frozen=True)
class Beckmann:
    """Radial weight exp(−tan²δ/m²) of eqs. 2.8/2.9: t = 1 − exp(−tan²δ/m²)."""

    m: float
    frame: str = "half"
    # exp(−x) carries x ulps of the rounding of x; the weight matters up to x ≈ ln(1/ε) ≈ 36.
    rounding = 40.0

    def angle(self, t):
        tan_b = self.m * np.sqrt(-np.log1p(-t))
        c = 1.0 / np.sqrt(1.0 + tan_b * tan_b)
        return c, tan_b * c

    def solid_angle_per_t(self, t, cos_b, sin_b):
        """sin δ dδ/dt = m² cos³δ / (2 (1 − t))."""
        return self.m ** 2 * cos_b ** 3 / (2.0 * (1.0 - t))

    def t_of(self, beta):
        beta = np.clip(beta, 0.0, np.pi / 2)
        return -np.expm1(-(np.tan(beta) / self.m) ** 2)
