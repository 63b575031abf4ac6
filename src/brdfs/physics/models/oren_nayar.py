"""Oren–Nayar, the qualitative model (beyond the thesis): rough Lambertian facets.

M. Oren and S. K. Nayar, "Generalization of Lambert's reflectance model", SIGGRAPH 1994, eq. 30
(the "qualitative model", without its interreflection term)::

    f = (ρ/π) (A + B max(0, cos(φ_L − φ_V)) sin α tan β),
    A = 1 − 0.5 σ² / (σ² + 0.33),   B = 0.45 σ² / (σ² + 0.09),
    α = max(θ_L, θ_V),   β = min(θ_L, θ_V),

σ the standard deviation of the facets' slope angle (radians).  σ = 0 is Lambert's ρ/π.  Its kinks,
declared for the integrators: the half-planes cos(φ_L − φ_V) = 0 (φ_V = ±90° with L in the plane
φ = 0), where max(0, ·) switches, and θ_V = θ_L (N·V = N·L), where α and β swap.

Its albedo is elementary: ∫₀^{2π} max(0, cos Δφ) dΔφ = 2, and sin α tan β cos θ_V sin θ_V is
sin θ sin²θ_V below θ_V = θ (α = θ, β = θ_V) and tan θ sin²θ_V cos θ_V above it, so

    a(θ) = ρ A + (2ρB/π) [sin θ (θ/2 − sin 2θ/4) + tan θ (1 − sin³θ)/3]

(:meth:`OrenNayar.exact_albedo`; tan θ (1 − sin³θ) = sin θ cos θ (1 + sin θ + sin²θ)/(1 + sin θ), which
stays exact to rounding up to θ = 90°, where it vanishes).  :meth:`OrenNayar.albedo_estimate` answers
with it; the engine's two-dimensional route, which honours the declared kinks, integrates a user's
model of the same shape (the tests hold the two together).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from brdfs.core.estimate import Estimate
from brdfs.physics.lobes import HALF, PowerCosine
from brdfs.physics.models.base import BRDF, DrawRange, Interval, register


def oren_nayar_coefficients(sigma):
    """(A, B) of the qualitative model: A = 1 − 0.5σ²/(σ² + 0.33), B = 0.45σ²/(σ² + 0.09)."""
    s2 = np.asarray(sigma, float) ** 2
    return 1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)


def cos_relative_azimuth(L, V):
    """cos(φ_L − φ_V) from the horizontal parts of L and V; 0 where either is vertical (there the
    factor it multiplies, sin α tan β, vanishes with β = 0)."""
    L, V = np.broadcast_arrays(np.asarray(L, float), np.asarray(V, float))
    horizontal = np.hypot(L[..., 0], L[..., 1]) * np.hypot(V[..., 0], V[..., 1])
    dot = L[..., 0] * V[..., 0] + L[..., 1] * V[..., 1]
    return np.where(horizontal > 0, dot / np.where(horizontal > 0, horizontal, 1.0), 0.0)


@register
@dataclass(frozen=True)
class OrenNayar(BRDF):
    """Qualitative Oren–Nayar, f = (ρ/π)(A + B max(0, cos(φ_L − φ_V)) sin α tan β) (Oren & Nayar 1994, eq. 30)."""

    rho: float = 1.0
    sigma: float = 0.0
    name = "oren_nayar"
    # --- what the model says about itself
    chapter = None               # beyond the thesis (Oren & Nayar 1994)
    param_ranges = {"rho": Interval(0.0, 1.0), "sigma": Interval(0.0, np.pi / 2)}
    #: σ = 0 (Lambert) drawn on its own as well
    test_ranges = {"sigma": DrawRange(0.0, np.pi / 2, zero=True)}
    examples = {"typical": {"rho": 1.0, "sigma": 0.3}, "narrowest": {"rho": 1.0, "sigma": np.pi / 2}}
    # conserves_energy = False: with ρ = 1 the albedo exceeds 1 toward grazing incidence for
    # moderate roughness (σ = 0.3: a(89°) = 1.00409, a(90°) = 1.00536, engine and disk agreeing to
    # 1e-10); the qualitative model is not normalised
    conserves_energy = False
    reciprocal = True            # α, β and cos(φ_L − φ_V) are symmetric in L and V
    strategies = ("cosine",)     # a Lambertian base: cosine sampling
    chi2_cases = ({"rho": 1.0, "sigma": np.pi / 2}, {"rho": 1.0, "sigma": 0.3})
    #: Its rows of the accuracy map, if config.yaml lists values of σ for them (none by default).
    accuracy_families = {"oren_nayar": ("sigma", {"rho": 1.0})}

    def __post_init__(self):
        for key in ("rho", "sigma"):
            if not self.param_ranges[key].contains(getattr(self, key)):
                raise ValueError(f"oren_nayar: {key} must lie in {tuple(self.param_ranges[key][:2])}, "
                                 f"got {getattr(self, key)!r}")

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return PowerCosine(0.0, HALF)          # Lambertian: the half-vector frame covers the hemisphere

    def _eval(self, L, V, nl, nv):
        A, B = oren_nayar_coefficients(self.sigma)
        lambert = np.full(np.broadcast_shapes(nl.shape, nv.shape), self.rho / np.pi)
        if B == 0.0:                 # σ = 0: Lambert, bit for bit
            return lambert
        # sines from the horizontal parts, not from the cosines: next to the pole cos θ rounds to 1 and
        # √(1 − cos²θ) lost every digit of sin θ (θ_L = 1e-6°: tan β 15 % off, the albedo 4e-10)
        sin_l, sin_v = np.hypot(L[..., 0], L[..., 1]), np.hypot(V[..., 0], V[..., 1])
        l_steeper = nl >= nv                                                # α = max θ, β = min θ
        sin_alpha = np.where(l_steeper, sin_v, sin_l)
        tan_beta = np.where(l_steeper, sin_l / nl, sin_v / nv)
        rough = B * np.maximum(cos_relative_azimuth(L, V), 0.0) * sin_alpha * tan_beta
        return lambert * (A + rough)

    def nv_levels(self, nl):
        """N·V = N·L, where α = max(θ_L, θ_V) and β = min(θ_L, θ_V) swap; none at σ = 0 (B = 0: Lambert)."""
        return (nl,) if self.sigma > 0 else ()

    def azimuth_levels(self, nl):
        """cos(φ_L − φ_V) = 0: the half-planes φ_V = ±90° (L in the plane φ = 0); none at σ = 0."""
        return (0.5 * np.pi, 1.5 * np.pi) if self.sigma > 0 else ()

    def exact_albedo(self, theta_deg):
        """a(θ) = ρA + (2ρB/π)[sin θ (θ/2 − sin 2θ/4) + tan θ (1 − sin³θ)/3] (module docstring); a(0) = ρA."""
        return self._albedo_parts(theta_deg)[0]

    def albedo_estimate(self, theta_deg, rtol, atol):
        """The closed form of :meth:`exact_albedo`, with a bound of its rounding."""
        value, bound = self._albedo_parts(theta_deg)
        return Estimate(value, bound)

    def _albedo_parts(self, theta_deg):
        """a(θ) and a bound of its rounding: every part is a sum of non-negative terms, each good to a
        few ulps of itself, except θ/2 − sin 2θ/4, which cancels near θ = 0 to ulps of θ/2 (bounded by
        16 ε of the sum of the terms' magnitudes)."""
        A, B = oren_nayar_coefficients(self.sigma)
        theta = np.radians(np.asarray(theta_deg, float))
        s, c = np.sin(theta), np.cos(theta)
        below = s * (0.5 * theta - 0.25 * np.sin(2.0 * theta))
        above = s * c * (1.0 + s + s * s) / (3.0 * (1.0 + s))
        value = self.rho * (A + 2.0 * B / np.pi * (below + above))
        magnitude = self.rho * (A + 2.0 * B / np.pi * (s * (0.5 * theta + 0.25) + above))
        return value, 16.0 * np.finfo(float).eps * magnitude
