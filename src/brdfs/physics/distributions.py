"""Microfacet distributions: the normal distribution D, its radial CDF and sampling, Smith's Λ and G1.

One type per distribution, apart from the models that use it (as pbrt-v4 keeps
``TrowbridgeReitzDistribution`` apart from ``ConductorBxDF``): Ward, corrected Ward and Cook–Torrance
(eqs. 2.8, 2.9, 3.35, 3.36) share :class:`Beckmann`; the Smith microfacet models
(:mod:`brdfs.physics.models.smith_microfacet`) use :class:`Beckmann` and :class:`GGX` (Trowbridge–Reitz)
with the same interface, plus visible-normal sampling for both; the lobe coordinates of the integration engine
(:mod:`brdfs.physics.lobes`) and the grazing analysis (:mod:`brdfs.numerics.grazing`)
use its CDF, its sampling and its Smith functions.

Conventions.  δ is the angle between the microfacet normal H and N, ``tan2`` = tan²δ.  ``D`` is
normalised so that ∫ D(H) (N·H) dω_H = 1 (the projected microfacet area per unit macro area).
The *radial weight* is the part of D·cos δ·sin δ dδ that importance sampling draws: for Beckmann
t = 1 − exp(−tan²δ/α²) is uniform.

References
----------
Beckmann & Spizzichino (1963); Walter et al. (2007), "Microfacet models for refraction through
rough surfaces", eqs. 25–27 (Beckmann D, Λ, G1); Heitz (2014), "Understanding the
masking-shadowing function" (projected area, visible normals, Λ of both distributions);
Heitz & d'Eon (2014) and Heitz (2018), "Sampling the GGX distribution of visible normals".
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from fractions import Fraction
from functools import lru_cache
from math import factorial, lgamma, sqrt

from scipy.special import erfc, erfcx, i0e, ndtri

from brdfs.physics.parameters import check_positive


def half_vector_tan2(L, V):
    """(tan²δ, cos δ) of the half vector of L and V, from h = L + V without cancellation."""
    return half_vector_parts(L, V)[:2]


def half_vector_parts(L, V):
    """(tan²δ, cos δ, |L + V|) of unit vectors L, V; L·H = V·H = |L + V|/2."""
    h = np.asarray(L, float) + np.asarray(V, float)
    hz2 = h[..., 2] ** 2
    hxy2 = h[..., 0] ** 2 + h[..., 1] ** 2
    h2 = hz2 + hxy2
    with np.errstate(divide="ignore", invalid="ignore"):
        return hxy2 / hz2, np.sqrt(hz2 / h2), np.sqrt(h2)


# --- Smith masking on the sphere and visible normals (both distributions) ----------------------

def _frame_angle(w):
    """cos θ and the azimuth (cos φ, sin φ) of directions w (…, 3); φ = 0 where w ∥ N."""
    w = np.asarray(w, float)
    r = np.hypot(w[..., 0], w[..., 1])
    safe = np.where(r > 0, r, 1.0)
    return w[..., 2] / np.linalg.norm(w, axis=-1), np.where(r > 0, w[..., 0] / safe, 1.0), np.where(r > 0, w[..., 1] / safe, 0.0)


class _SmithVisibleNormals:
    """Smith's Λ on the whole sphere and the distribution of visible normals (Heitz 2014;
    Heitz & d'Eon 2014), shared by :class:`Beckmann` and :class:`GGX`.

    For a direction w below the horizon (a ray leaving the microsurface in a random walk, seen
    from the surface), Λ(w) = −1 − Λ(−w) (Heitz et al. 2016), so that (1 + Λ(w)) cos θ_w
    is still the projected area ∫⟨w·H⟩⁺ D(H) dω_H of the microsurface seen from w (its value for the
    lower hemisphere of directions).
    """

    def smith_lambda_signed(self, cos_theta):
        """Λ(w) on the whole sphere: :meth:`smith_lambda` above the horizon, −1 − Λ(−w) below."""
        c = np.asarray(cos_theta, float)
        up = self.smith_lambda(np.where(c > 0, c, 1.0))
        down = -1.0 - self.smith_lambda(np.where(c < 0, -c, 1.0))
        return np.where(c > 0, up, np.where(c < 0, down, np.inf))

    def projected_area(self, cos_theta):
        """(1 + Λ(w)) cos θ_w = ∫⟨w·H⟩⁺ D(H) dω_H (Heitz 2014), any direction."""
        c = np.asarray(cos_theta, float)
        with np.errstate(invalid="ignore"):
            area = (1.0 + self.smith_lambda_signed(c)) * c
        return np.where(c == 0, self._grazing_area(), area)

    def _grazing_area(self):
        """Projected area at θ = 90°: lim Λ(θ) cos θ."""
        raise NotImplementedError

    def visible_normal_pdf(self, w, H):
        """D_w(H) = ⟨w·H⟩⁺ D(H) / ((1 + Λ(w)) cos θ_w) per solid angle of H (Heitz 2014, the distribution of visible normals);
        = G1(w) max(0, w·H) D(H) / cos θ_w above the horizon."""
        w, H = np.asarray(w, float), np.asarray(H, float)
        wh = np.sum(w * H, axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            pdf = np.maximum(wh, 0.0) * self.D(H[..., 2]) / self.projected_area(w[..., 2])
        return np.where(wh > 0, pdf, 0.0)


_TWO_SQRT_PI = 2.0 * np.sqrt(np.pi)


def _beckmann_visible_slope_log_cdf(x, cos_t, sin_t):
    """log ∫_{−∞}^x (cos θ − s sin θ) e^{−s²}/√π ds (unnormalised), the marginal of the visible slopes
    of the α = 1 Beckmann surface seen from θ in the x–z plane; scaled to avoid underflow."""
    neg = x < 0
    xn = np.where(neg, x, 0.0)
    xp = np.where(neg, 0.0, x)
    with np.errstate(divide="ignore", invalid="ignore"):
        low = -xn * xn + np.log(0.5 * (cos_t * erfcx(-xn) + sin_t / np.sqrt(np.pi)))
        high = np.log(0.5 * (cos_t * erfc(-xp) + sin_t * np.exp(-xp * xp) / np.sqrt(np.pi)))
    return np.where(neg, low, high)


def _safeguarded_newton(x, lo, hi, target, cos_t, sin_t, iterations):
    """Solve log F(x) = target (:func:`_beckmann_visible_slope_log_cdf`) in the bracket [lo, hi] by Newton's
    method, a bisection step wherever Newton leaves the bracket; iterates only the unconverged entries."""
    x, lo, hi = (np.array(np.broadcast_to(v, np.broadcast_shapes(x.shape, lo.shape, hi.shape, target.shape)),
                          float).ravel() for v in (x, lo, hi))
    shape = np.broadcast_shapes(target.shape, cos_t.shape)
    target, cos_t, sin_t = (np.broadcast_to(v, shape).ravel() for v in (target, cos_t, sin_t))
    active = np.arange(x.size)
    for _ in range(iterations):
        if active.size == 0:
            break
        xa, c, s = x[active], cos_t[active], sin_t[active]
        log_f = _beckmann_visible_slope_log_cdf(xa, c, s)
        g = log_f - target[active]
        lo[active] = np.where(g < 0, xa, lo[active])
        hi[active] = np.where(g < 0, hi[active], xa)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            log_density = np.log(np.maximum(c - xa * s, 0.0)) - xa * xa - 0.5 * np.log(np.pi)
            step = g / np.exp(log_density - log_f)
        newton = xa - step
        ok = np.isfinite(newton) & (newton > lo[active]) & (newton < hi[active])
        x[active] = np.where(ok, newton, 0.5 * (lo[active] + hi[active]))
        moved = np.where(ok, np.abs(step), hi[active] - lo[active])
        active = active[moved > 1e-14 * np.maximum(1.0, np.abs(x[active]))]
    return x.reshape(shape)


@dataclass(frozen=True)
class Beckmann(_SmithVisibleNormals):
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

    def D(self, cos_delta, tan2=None):
        """D(δ) = exp(−tan²δ/α²) / (π α² cos⁴δ); zero below the horizon.

        ``tan2``: tan²δ where the caller has it without cancellation (:func:`half_vector_tan2`).
        From cos δ alone, 1 − cos δ ≈ δ²/2 carries a relative rounding of ε/(1 − cos δ), which
        exp(−tan²δ/α²) multiplies by tan²δ/α²: 2e4 ulps at α = 0.01 (Beckmann–Smith albedo 2.4e-13
        above 1 at 60°).
        """
        c = np.asarray(cos_delta, float)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tan2 = (1.0 - c) * (1.0 + c) / (c * c) if tan2 is None else np.asarray(tan2, float)
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

    def azimuthal_integral(self, q, b):
        """∫₀^π D dφ where tan²δ = q + b (1 + cos φ) (q, b ≥ 0), and a bound on its rounding.

        With x = tan²δ, D = e^(−x/α²) (1 + x)²/(π α²); writing u = 1 + cos φ and p = 1 + q,
        (1 + x)² = p² + 2 p b u + b² u², every term positive, and
        ∫₀^π u^k e^(−z u) dφ = 2^k B(k + ½, ½) ₁F₁(k + ½; k + 1; −2z), z = b/α², so
        ∫₀^π D dφ = e^(−q/α²)/α² · [p² F₀ + 2 p b F₁ + (3/2) b² F₂],  F_k = ₁F₁(k + ½; k + 1; −2b/α²)
        (:func:`kummer_half_integers`).  The exponential carries 2q/α² ulps (the rounding of q and of α²), as
        :attr:`rounding` says of the weight.
        """
        a2 = self.alpha ** 2
        x = 2.0 * b / a2
        p = 1.0 + q
        (f0, f1, f2), (e0, e1, e2) = kummer_half_integers(x)
        exponent = q / a2                        # 2q/α² below is 2 · this, exactly (a power of two)
        scale = np.exp(-exponent) / a2
        weights = (p * p, 2 * p * b, 1.5 * b * b)          # of F_k and of their bounds alike
        value = scale * (weights[0] * f0 + weights[1] * f1 + weights[2] * f2)
        rounding = scale * (weights[0] * e0 + weights[1] * e1 + weights[2] * e2) + (2 * exponent + 16) * _EPS * value
        return value, rounding

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
        """Exact Λ(θ) = (erf(a) − 1)/2 + exp(−a²)/(2a√π), a = 1/(α tan θ) (Heitz 2014, eq. 72);
        0 at normal incidence.

        Evaluated as e^(−a²)/2 · (1/(a√π) − erfcx(a)) with the scaled erfcx, so that Λ keeps its
        relative accuracy where it falls below the rounding of 1 (large a): the two terms of the
        printed form cancel there.
        """
        c = np.asarray(cos_theta, float)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            a = c / (self.alpha * np.sqrt(np.maximum((1.0 - c) * (1.0 + c), 0.0)))
            lam = 0.5 * np.exp(-a * a) * (1.0 / (a * np.sqrt(np.pi)) - erfcx(a))
        return np.where(c >= 1.0, 0.0, np.where(c > 0, lam, np.inf))

    def smith_g1(self, cos_theta):
        """Exact Smith masking G1 = 1/(1 + Λ) of a Beckmann surface."""
        return 1.0 / (1.0 + self.smith_lambda(cos_theta))

    def smith_lambda_cos(self, cos_theta):
        """λ(μ) = Λ(θ) cos θ = α sin θ e^{−a²}/(2√π) − cos θ erfc(a)/2, a = cot θ/α: finite at the
        horizon (α/(2√π)), 0 at normal incidence; G1 = μ/(μ + λ(μ))."""
        if type(cos_theta) is float and type(self.alpha) is float:          # one number: the same bits
            return self._smith_lambda_cos_of_one(cos_theta)
        c = np.minimum(np.maximum(cos_theta, 0.0), 1.0)      # np.clip's values, without its wrapper's cost
        s = np.sqrt((1.0 - c) * (1.0 + c))
        with np.errstate(divide="ignore", invalid="ignore"):
            alpha_s = self.alpha * s
            a = c / alpha_s
            lam = alpha_s * np.exp(-a * a) / _TWO_SQRT_PI - 0.5 * c * erfc(a)
        return np.where(s > 0, lam, 0.0)

    def _smith_lambda_cos_of_one(self, cos_theta: float) -> float:
        """:meth:`smith_lambda_cos` of one Python float, by the same operations on numbers (IEEE
        arithmetic and sqrt as numpy's; exp and erfc by the same ufuncs), without the arrays' cost."""
        c = min(max(cos_theta, 0.0), 1.0)
        s = sqrt((1.0 - c) * (1.0 + c))
        alpha_s = self.alpha * s
        if not alpha_s > 0:                      # the pole, or α s below the smallest float: λ = 0
            return 0.0
        a = c / alpha_s
        return float(alpha_s * np.exp(-a * a) / _TWO_SQRT_PI - 0.5 * c * erfc(a))

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

    # --- visible normals (Heitz & d'Eon 2014) ------------------------------------------------
    def _grazing_area(self):
        return self.alpha / (2.0 * np.sqrt(np.pi))

    def sample_visible_normal(self, w, u1, u2, iterations=100):
        """Normals H with density :meth:`visible_normal_pdf` (w, H), any direction w off the horizon.

        Method (Heitz & d'Eon 2014, "Importance sampling microfacet-based BSDFs using the distribution
        of visible normals", Sec. 4 and appendix; Jakob's numerical inversion in Mitsuba): stretch w
        to the α = 1 surface, draw the slope x̃ along w's azimuth from its visible marginal
        ∝ (cos θ − x̃ sin θ)⁺ e^{−x̃²} by Newton's method on the log-CDF safeguarded by bisection
        (to 1e-14; at most 100 steps, each halving the bracket of width ≤ 60 if Newton leaves it), the slope ỹ across it from e^{−ỹ²} (independent), rotate by φ,
        unstretch by α and take H ∝ (−x, −y, 1).
        """
        w = np.asarray(w, float)
        a = self.alpha
        ws = np.stack([a * w[..., 0], a * w[..., 1], w[..., 2]], -1)
        cos_t, cos_p, sin_p = _frame_angle(ws)
        sin_t = np.sqrt(np.maximum((1.0 - cos_t) * (1.0 + cos_t), 0.0))
        with np.errstate(divide="ignore"):
            cot = np.where(sin_t > 0, cos_t / np.where(sin_t > 0, sin_t, 1.0), np.inf)
        hi = np.minimum(cot, 30.0)
        lo = np.minimum(hi, 0.0) - 30.0
        u1 = np.clip(np.asarray(u1, float), 1e-300, 1.0)
        target = np.log(u1) + _beckmann_visible_slope_log_cdf(hi, cos_t, sin_t)
        x1 = _safeguarded_newton(np.where(np.isfinite(cot), np.minimum(0.0, hi - 1.0), 0.0), lo, hi, target,
                                 cos_t, sin_t, iterations)
        y1 = ndtri(np.clip(np.asarray(u2, float), 1e-300, 1.0 - 1e-16)) / np.sqrt(2.0)
        x = a * (cos_p * x1 - sin_p * y1)
        y = a * (sin_p * x1 + cos_p * y1)
        H = np.stack([-x, -y, np.ones_like(x)], -1)
        return H / np.linalg.norm(H, axis=-1, keepdims=True)


@dataclass(frozen=True)
class GGX(_SmithVisibleNormals):
    """Trowbridge–Reitz (GGX) distribution, D = α² / (π cos⁴δ (α² + tan²δ)²) (Walter et al. 2007, eq. 33).

    >>> d = GGX(0.3)
    >>> round(float(d.cdf(d.tan_of_cdf(0.25))), 12)
    0.25
    >>> [round(float(GGX(1.0).D(c)) * np.pi, 14) for c in (0.3, 0.9)]     # α = 1: D = 1/π, uniform
    [1.0, 1.0]
    """

    alpha: float
    name = "ggx"

    def __post_init__(self):
        check_positive("alpha", self.alpha)

    def slope_weight(self, tan2):
        """(1 + tan²δ/α²)⁻², the GGX weight (1 at δ = 0)."""
        return (1.0 + np.asarray(tan2, float) / self.alpha ** 2) ** -2

    def D(self, cos_delta, tan2=None):
        """D(δ) = α² / (π (α² cos²δ + sin²δ)²) = α² / (π cos⁴δ (α² + tan²δ)²); zero below the horizon.

        ``tan2``: tan²δ where the caller has it without cancellation (:func:`half_vector_tan2`);
        sin²δ = (1 − c)(1 + c) from cos δ alone is off by ε relative to 1, i.e. ε/α² relative to α².
        """
        c = np.asarray(cos_delta, float)
        a2 = self.alpha ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            if tan2 is None:
                d = a2 / (np.pi * (a2 * c * c + (1.0 - c) * (1.0 + c)) ** 2)
            else:
                d = a2 / (np.pi * c ** 4 * (a2 + np.asarray(tan2, float)) ** 2)
        return np.where(c > 0, d, 0.0)

    def cdf(self, tan_delta):
        """t(δ) = 2π ∫₀^δ D cos δ' sin δ' dδ' = tan²δ / (α² + tan²δ)."""
        t2 = np.asarray(tan_delta, float) ** 2
        with np.errstate(invalid="ignore"):
            return np.where(np.isinf(t2), 1.0, t2 / (self.alpha ** 2 + t2))

    def tan_of_cdf(self, t):
        """tan δ = α √(t / (1 − t)) (Walter et al. 2007, eq. 35)."""
        t = np.asarray(t, float)
        with np.errstate(divide="ignore"):
            return self.alpha * np.sqrt(t / (1.0 - t))

    def solid_angle_per_t(self, t, cos_delta):
        """sin δ dδ/dt = 1/(2π D cos δ) = α² cos³δ / (2 (1 − t)²)."""
        return self.alpha ** 2 * cos_delta ** 3 / (2.0 * (1.0 - t) ** 2)

    #: Rational in cos δ: a few ulps (no exponential, no power of a rounded dot product).
    rounding = 8.0

    def azimuthal_integral(self, q, b):
        """∫₀^π D dφ where tan²δ = q + b (1 + cos φ) (q, b ≥ 0), and a bound on its rounding.

        D = α² (1 + x)²/(π (α² + x)²) = (α²/π) (1 + k/(c + b cos φ))², x = tan²δ, k = 1 − α²,
        c = α² + q + b; with ∫₀^π dφ/(c + b cos φ) = π/r and ∫₀^π dφ/(c + b cos φ)² = π c/r³,
        r = √((c − b)(c + b)) (Gradshteyn–Ryzhik 3.613.2, 3.661.4):
        ∫₀^π D dφ = α² [1 + 2k/r + k² c/r³].  c − b = α² + q is formed without cancellation.
        """
        a2 = self.alpha ** 2
        k = 1.0 - a2
        near = a2 + q
        far = near + 2.0 * b                     # a2 + q + 2b, c: the same sums as written out
        r = np.sqrt(near * far)
        c = near + b
        second, third = 2.0 * k / r, k * k * c / r ** 3
        total = 1.0 + second + third
        # the bound's sum of magnitudes is the sum itself where k ≥ 0 (α ≤ 1: every term ≥ 0)
        magnitudes = total if k >= 0 else 1.0 + np.abs(second) + third
        return a2 * total, 16 * _EPS * a2 * magnitudes

    def sample_normal(self, u1, u2):
        """Microfacet normals H with density D(H) (N·H) from uniform (u1, u2); shape (..., 3)."""
        t = np.asarray(u1, float)
        cos_d = np.sqrt((1.0 - t) / (1.0 - t + self.alpha ** 2 * t))
        sin_d = np.sqrt(np.maximum(self.alpha ** 2 * t / (1.0 - t + self.alpha ** 2 * t), 0.0))
        phi = 2.0 * np.pi * np.asarray(u2, float)
        return np.stack([sin_d * np.cos(phi), sin_d * np.sin(phi), cos_d], -1)

    def normal_pdf(self, cos_delta):
        """Density of :meth:`sample_normal` per solid angle of H: D(H) (N·H)."""
        return self.D(cos_delta) * np.asarray(cos_delta, float)

    def smith_lambda(self, cos_theta):
        """Exact Λ(θ) = (−1 + √(1 + α² tan²θ))/2 (Walter et al. 2007, eq. 34 context; Heitz 2014)."""
        c = np.asarray(cos_theta, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            tan2 = (1.0 - c) * (1.0 + c) / (c * c)
            x = self.alpha ** 2 * tan2
            lam = 0.5 * x / (1.0 + np.sqrt(1.0 + x))          # (√(1+x) − 1)/2 without cancellation
        return np.where(c >= 1.0, 0.0, np.where(c > 0, lam, np.inf))

    def smith_g1(self, cos_theta):
        """Exact Smith masking G1 = 1/(1 + Λ) = 2/(1 + √(1 + α² tan²θ)) of a GGX surface."""
        return 1.0 / (1.0 + self.smith_lambda(cos_theta))

    def smith_lambda_cos(self, cos_theta):
        """λ(μ) = Λ(θ) cos θ = (√(μ² + α² sin²θ) − μ)/2 = α² sin²θ / (2 (√(μ² + α² sin²θ) + μ)):
        finite at the horizon (α/2); G1 = μ/(μ + λ(μ))."""
        if type(cos_theta) is float and type(self.alpha) is float:          # one number: the same bits
            c = min(max(cos_theta, 0.0), 1.0)                               # (IEEE arithmetic, sqrt rounded alike)
            s2 = (1.0 - c) * (1.0 + c)
            a2 = self.alpha ** 2
            root = sqrt(c * c + a2 * s2) + c
            if root > 0:                                                    # else the arrays' 0/0
                return 0.5 * a2 * s2 / root
        c = np.minimum(np.maximum(cos_theta, 0.0), 1.0)      # np.clip's values, without its wrapper's cost
        s2 = (1.0 - c) * (1.0 + c)
        a2 = self.alpha ** 2
        return 0.5 * a2 * s2 / (np.sqrt(c * c + a2 * s2) + c)

    def _grazing_area(self):
        return self.alpha / 2.0

    def sample_visible_normal(self, w, u1, u2):
        """Normals H with density :meth:`visible_normal_pdf` (w, H) for any direction w (…, 3) off the
        horizon, by Heitz (2018), "Sampling the GGX distribution of visible normals", JCGT 7(4),
        listing 1: a uniform point of the projected, stretched hemisphere, lifted and unstretched.
        Below the horizon the projection is the half disk minus the half ellipse (s < 1/2)."""
        w = np.asarray(w, float)
        a = self.alpha
        vh = np.stack([a * w[..., 0], a * w[..., 1], w[..., 2]], -1)
        vh = vh / np.linalg.norm(vh, axis=-1, keepdims=True)
        lensq = vh[..., 0] ** 2 + vh[..., 1] ** 2
        inv = np.where(lensq > 0, 1.0 / np.sqrt(np.where(lensq > 0, lensq, 1.0)), 0.0)
        t1_vec = np.where((lensq > 0)[..., None], np.stack([-vh[..., 1] * inv, vh[..., 0] * inv, 0 * inv], -1),
                          np.array([1.0, 0.0, 0.0]))
        t2_vec = np.cross(vh, t1_vec)
        r, phi = np.sqrt(np.asarray(u1, float)), 2.0 * np.pi * np.asarray(u2, float)
        t1, t2 = r * np.cos(phi), r * np.sin(phi)
        s = 0.5 * (1.0 + vh[..., 2])
        t2 = (1.0 - s) * np.sqrt(np.maximum(1.0 - t1 * t1, 0.0)) + s * t2
        nh = (t1[..., None] * t1_vec + t2[..., None] * t2_vec
              + np.sqrt(np.maximum(1.0 - t1 * t1 - t2 * t2, 0.0))[..., None] * vh)
        ne = np.stack([a * nh[..., 0], a * nh[..., 1], np.maximum(nh[..., 2], 0.0)], -1)
        return ne / np.linalg.norm(ne, axis=-1, keepdims=True)


# --- the azimuthal integral of the Beckmann distribution ---------------------------------------

_EPS = np.finfo(float).eps
#: Where F underflows to 0 at a finite x, its true value is below the smallest subnormal.
_TINY = float(np.finfo(float).smallest_subnormal)
#: x below which :func:`kummer_half_integers` sums the convergent series, above it the asymptotic one.
_KUMMER_SWITCH = 40.0
_KUMMER_SERIES_TERMS = 120
_KUMMER_ASYMPTOTIC_TERMS = 40
#: Columns (values of x) per block of the powers' table: (terms × block) doubles stay in cache.
_KUMMER_BLOCK = 1024


def _rounded_coefficients(rows, count):
    """Float rows of the exact rational coefficients ``rows[k](n)`` for n < ``count``, each rounded once."""
    return np.array([[float(row(n)) for n in range(count)] for row in rows])


@lru_cache(maxsize=None, typed=True)
def _pochhammer(a, n):
    """(a)_n exactly, from (a)_(n-1): the tables' rows take n products each, not n² (import time).
    Cached by type too: an int ``a`` and an equal Fraction are separate entries."""
    return Fraction(1) if n == 0 else _pochhammer(a, n - 1) * (a + n - 1)


#: The series' coefficients (½)_n / ((k + 1)_n n!) of k = 1, 2 (rows), n < 120, each rounded once.
_SERIES = _rounded_coefficients(
    [lambda n, k=k: _pochhammer(Fraction(1, 2), n) / (_pochhammer(k + 1, n) * factorial(n)) for k in (1, 2)],
    _KUMMER_SERIES_TERMS)
#: The asymptotic series' coefficients (k + ½)_s (½)_s / s! of k = 0, 1, 2 (rows), s ≤ 40 and the
#: first omitted one (s = 41), each rounded once.
_ASYMPTOTIC = _rounded_coefficients(
    [lambda s, k=k: _pochhammer(Fraction(2 * k + 1, 2), s) * _pochhammer(Fraction(1, 2), s) / factorial(s)
     for k in range(3)], _KUMMER_ASYMPTOTIC_TERMS + 2)
#: The asymptotic prefactor's log Γ(k + 1) − log Γ(½) and exponent k + ½ (columns over k = 0, 1, 2).
_ASYMPTOTIC_LOG_SCALE = np.array([[lgamma(k + 1) - lgamma(0.5)] for k in range(3)])
_ASYMPTOTIC_POWER = np.array([[k + 0.5] for k in range(3)])
_TWICE_ASYMPTOTIC_POWER = 2 * _ASYMPTOTIC_POWER


def _powers(y, count):
    """Rows y⁰ … y^(count − 1) of the values y (1-D): by doubling, yᵐ = y^(m−1) y and the rows m … 2m − 1
    the rows 0 … m − 1 times yᵐ, so that yⁿ takes n − 1 multiplications (each a rounding) in 2 log₂ count
    numpy operations."""
    out = np.empty((count, y.size))
    out[0] = 1.0
    multiply = np.multiply                       # (out passed by position: the keyword costs a parse per call)
    m = 1
    while m < count:
        k = min(m, count - m)
        multiply(out[m - 1], y, out[m])
        if k > 1:
            multiply(out[1:k], out[m], out[m + 1:m + k])
        m *= 2
    return out


def kummer_half_integers(x):
    """(F, bound), each of shape (3,) + x.shape: row k is F = ₁F₁(k + ½; k + 1; −x) for x ≥ 0, k = 0, 1, 2,
    with an absolute rounding bound.

    x < 40: k = 0 is e^(−x/2) I₀(x/2) (``scipy.special.i0e``); k ≥ 1 the positive series
    e^(−x) Σ_{n<T} aₙ xⁿ, aₙ = (½)_n/((k + 1)_n n!) (Kummer's transformation, DLMF 13.2.39), with
    T = min(120, ⌈x + 10√x + 25⌉) terms for the largest x of the call (the Poisson-like terms beyond are
    below 1e-17 of the sum); the difference forms with I₁ lose ~x^k digits there.  x ≥ 40: the
    asymptotic series Γ(k + 1)/Γ(½) x^(−k−½) Σ_{s≤40} (k + ½)_s (½)_s/(s! x^s) (DLMF 13.7.2; positive
    terms, the first omitted one added to the bound, the subdominant e^(−x) part below 1e-17).

    Both series are sums of positive terms c_n yⁿ (y = x, or 1/x), evaluated as one matrix product of
    the coefficients (each rounded once from its exact rational) with a table of powers
    (:func:`_powers`: yⁿ after n − 1 roundings).  Term n is then within (n + 1) ε (plus n ε from the
    rounding of 1/x) of its exact value, a sum of T positive terms adds at most (T − 1) ε of itself in any
    order, and e^(−x) its own ulp and a product's: the series' bound (2T + 4) ε |F| holds with room.  The
    asymptotic series' terms carry 2s + 1 ε each, but its first terms dominate (term 1 is at most
    5/(4 · 40) of term 0 = 1, exact): its sum is within (40 + 2) ε; the prefactor
    exp(log Γ(k + 1) − log Γ(½) − (k + ½) ln x) within 2 (k + ½) |ln x| ε (the rounding of ln x and of the
    exponent, times the exponential's derivative) and an ulp of exp; bound (48 + 2 (k + ½) |ln x|) ε |F|
    plus the first omitted term (the former 88 ε, without ln x, was exceeded at x = 1e200: 183 ε).
    Checked against mpmath to within the bound for x in [0, 1e200] (``tests/numerics/test_polar_route.py``).
    """
    x = np.asarray(x, float)
    flat = x.ravel()
    small = flat < _KUMMER_SWITCH
    if flat.size == 0:
        out = np.empty((6, 0))
    elif small.all():
        out = _series(flat)
    elif not small.any():
        out = _asymptotic(flat)
    else:
        out = np.empty((6, flat.size))
        out[:, small] = _series(flat[small])
        large = ~small
        out[:, large] = _asymptotic(flat[large])
    return out[:3].reshape((3,) + x.shape), out[3:].reshape((3,) + x.shape)


def _series(xs):
    """:func:`kummer_half_integers` for x < 40 (1-D): rows F₀, F₁, F₂ and their bounds, (6, xs.size)."""
    out = np.empty((6, xs.size))
    value, bound = out[:3], out[3:]
    value[0] = i0e(0.5 * xs)
    bound[0] = 8 * _EPS * value[0]
    top = xs.max()
    terms = int(min(_KUMMER_SERIES_TERMS, np.ceil(top + 10 * np.sqrt(top) + 25)))
    coefficients = _SERIES[:, :terms]
    for s in range(0, xs.size, _KUMMER_BLOCK):
        block = xs[s:s + _KUMMER_BLOCK]
        value[1:, s:s + _KUMMER_BLOCK] = np.exp(-block) * (coefficients @ _powers(block, terms))
    bound[1:] = (2 * terms + 4) * _EPS * value[1:]
    return out


def _asymptotic(xl):
    """:func:`kummer_half_integers` for x ≥ 40 (1-D): rows F₀, F₁, F₂ and their bounds, (6, xl.size)."""
    out = np.empty((6, xl.size))
    value, bound = out[:3], out[3:]
    n = _KUMMER_ASYMPTOTIC_TERMS
    y = 1.0 / xl                                 # x ≥ 40 (or NaN): no division by zero
    for s in range(0, xl.size, _KUMMER_BLOCK):
        powers = _powers(y[s:s + _KUMMER_BLOCK], n + 2)
        total = _ASYMPTOTIC[:, :n + 1] @ powers[:n + 1]
        omitted = _ASYMPTOTIC[:, n + 1:] * powers[n + 1]
        log_x = np.log(xl[s:s + _KUMMER_BLOCK])
        high = np.exp(_ASYMPTOTIC_LOG_SCALE - _ASYMPTOTIC_POWER * log_x) * total
        value[:, s:s + _KUMMER_BLOCK] = high
        rounding = n + 8 + _TWICE_ASYMPTOTIC_POWER * np.abs(log_x)
        with np.errstate(invalid="ignore"):          # x = ∞: F = 0 exactly, 0 · ∞ in the bound
            relative = high * (rounding * _EPS + omitted / total)
        bound[:, s:s + _KUMMER_BLOCK] = np.where(high > 0, relative, np.where(np.isinf(log_x), 0.0, _TINY))
    return out

