"""Patch-based BRDFs of chapter 4: functions of the distance m of L'_P and V_P on the base plane.

m(L, V) = |h − (N·h)N| with h = L + V (eq. 4.1) is symmetric in L and V, so every model here is
reciprocal (section 4.2.1).  The geometry, profiles and constants are in :mod:`brdfs.numerics.patch_geometry`;
the albedos of these models come from there too (closed-form circle intersections, the verb
``albedo_estimate`` that the albedo engine takes), not from the generic hemisphere integration.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from brdfs.numerics import patch_geometry as patch
from brdfs.numerics.integrate.gauss_kronrod import Estimate, integrate
from brdfs.physics.models.base import BRDF, check_positive


def projected_distance(L, V):
    """m(L, V) = |V_P − L'_P| = |h − (N·h)N|, h = L + V  (eq. 4.1)."""
    return np.hypot(L[..., 0] + V[..., 0], L[..., 1] + V[..., 1])


def _check_radius(name, value):
    value = check_positive(name, value)
    if value > 2.0:
        raise ValueError(f"{name} must lie in (0, 2], got {value!r}")
    return value


def _default_constant(model, value):
    """Set the frozen field ``C`` to ``value`` unless given; reject a non-positive C."""
    if model.C is None:
        object.__setattr__(model, "C", float(value))
    check_positive("C", model.C)


@dataclass(frozen=True)
class PatchBasic(BRDF):
    """Basic BRDF f*(R) = c(R) where m(L, V) ≤ R, else 0  (eq. 4.2); c(R) = 1/(π min(1, R²)) (eq. 4.7)."""

    R: float
    C: float | None = None
    name = "patch_basic"

    def __post_init__(self):
        _check_radius("R", self.R)
        _default_constant(self, patch.basic_constant(self.R))

    def _eval(self, L, V, nl, nv):
        return np.where(projected_distance(L, V) <= self.R, self.C, 0.0)

    def albedo_estimate(self, theta_deg, rtol, atol):
        """Lens area over patch area (eq. 4.8), scaled by C/c(R)."""
        est = patch.basic_albedo(theta_deg, self.R)
        scale = self.C / float(patch.basic_constant(self.R))
        return Estimate(est.value * scale, est.error * scale)


@dataclass(frozen=True)
class PatchExponential(BRDF):
    """f = C e^{−s m(L, V)}  (eqs. 4.44/4.46), C = C_max of eq. 4.45 by default."""

    s: float
    C: float | None = None
    name = "patch_exponential"

    def __post_init__(self):
        _default_constant(self, patch.ExponentialProfile(self.s).c_max)

    def albedo_estimate(self, theta_deg, rtol, atol):
        """∫ p(R) a_R(L) dR over the lens areas (eqs. 4.22, 4.24)."""
        return patch.mixture_albedo(patch.ExponentialProfile(self.s), theta_deg, self.C, rtol, atol)

    def _eval(self, L, V, nl, nv):
        return self.C * np.exp(-self.s * projected_distance(L, V))


@dataclass(frozen=True)
class GeneralizedLambertian(BRDF):
    """f = C min((1 − (m/2)²)^{−d/2}, ξ(m_clip))  (eqs. 4.58/4.59); C = 1/max albedo by default."""

    d: float
    m_clip: float = 1.9
    C: float | None = None
    name = "generalized_lambertian"

    def __post_init__(self):
        profile = patch.GeneralizedLambertProfile(self.d, self.m_clip)
        if self.C is None:
            _default_constant(self, patch.generalized_lambert_c_max(profile).value)
        check_positive("C", self.C)

    def _eval(self, L, V, nl, nv):
        return self.C * patch.GeneralizedLambertProfile(self.d, self.m_clip).xi(projected_distance(L, V))

    def albedo_estimate(self, theta_deg, rtol, atol):
        """∫ p(R) a_R(L) dR + p_Diffuse over the lens areas (eqs. 4.22, 4.24)."""
        return patch.mixture_albedo(patch.GeneralizedLambertProfile(self.d, self.m_clip), theta_deg, self.C, rtol, atol)


@dataclass(frozen=True)
class PatchMixture(BRDF):
    """Mixture of basic BRDFs f = ∫_m² p(R) c(R) dR + p_Diffuse c(2)  (eqs. 4.20, 4.21, 4.40).

    ``weight`` is the continuous part p(R) (a vectorised callable on [0, 2]), ``p_diffuse`` the
    Dirac weight at R = 2 (the ideal diffuse part). A mirror part (R = 0) is a Dirac in V and
    has no value to evaluate. The integral is adaptive Gauss–Kronrod to ``rtol``, split at R = 1.
    """

    weight: Callable[[np.ndarray], np.ndarray]
    p_diffuse: float = 0.0
    rtol: float = 1e-12
    name = "patch_mixture"

    def __post_init__(self):
        if not callable(self.weight):
            raise ValueError(f"patch_mixture: weight must be a callable p(R), got {self.weight!r}")
        check_positive("p_diffuse", self.p_diffuse, allow_zero=True)

    def _eval(self, L, V, nl, nv):
        m = np.minimum(projected_distance(L, V), 2.0)
        flat = m.ravel()
        bp = np.stack([flat, np.maximum(flat, 1.0), np.full_like(flat, 2.0)], axis=1)
        inner = integrate(lambda R, e: self.weight(R) * patch.basic_constant(R), bp, rtol=self.rtol, atol=0.0)
        return inner.value.reshape(m.shape) + self.p_diffuse * patch.basic_constant(2.0)


@dataclass(frozen=True)
class PatchElliptical(BRDF):
    """Anisotropic basic BRDF: c(b) where the elliptic distance ≤ b, else 0  (eqs. 4.32, 4.34, 4.36).

    m = √((B/A · z·u)² + (z·v)²) with z = V_P − L'_P, u = (cos φ_u, sin φ_u, 0) the major axis
    and v ⊥ u the minor axis; ``ratio`` = B/A ≤ 1, ``b`` the minor semi-axis in (0, 2].
    """

    b: float
    ratio: float
    u_angle_deg: float = 0.0
    C: float | None = None
    name = "patch_elliptical"

    def __post_init__(self):
        _check_radius("b", self.b)
        if not 0.0 < float(self.ratio) <= 1.0:
            raise ValueError(f"patch_elliptical: ratio B/A must lie in (0, 1], got {self.ratio!r}")
        _default_constant(self, patch.elliptical_constant(self.b, self.ratio))

    def _eval(self, L, V, nl, nv):
        phi = np.radians(self.u_angle_deg)
        zx, zy = L[..., 0] + V[..., 0], L[..., 1] + V[..., 1]     # V_P − L'_P = (L + V)_P
        along_u = np.cos(phi) * zx + np.sin(phi) * zy
        along_v = -np.sin(phi) * zx + np.cos(phi) * zy
        return np.where(np.hypot(self.ratio * along_u, along_v) <= self.b, self.C, 0.0)
