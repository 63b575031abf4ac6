"""Patch-based BRDFs of chapter 4: projected-disk geometry, weight profiles, albedos.

Everything here lives on the base plane (the unit disk onto which directions project):
V ↦ V_P, and cos θ_V dω_V = dx dy, so an albedo is an area integral over the disk.

* :func:`circle_intersection` — C(L'_P, R) ∩ unit disk in closed form (eqs. 4.9/4.10); the one
  place the lens geometry is computed (albedos and diagrams draw from it).
* :func:`basic_albedo`, :func:`basic_mean_albedo` — the basic BRDF (eq. 4.2), closed forms.
* :class:`ExponentialProfile` (eq. 4.44), :class:`GeneralizedLambertProfile` (eqs. 4.58/4.59) —
  profiles ξ(m) with their weight functions p(R) (eq. 4.41) and constants.
* :func:`mixture_albedo`, :func:`mixture_mean_albedo` — eqs. 4.22/4.23: one adaptive
  Gauss–Kronrod integral over R, breakpoints at the kinks R = 1 − d, 1, 1 + d.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from brdfs.physics.geometry import sin_incidence
from brdfs.core.gauss_kronrod import Estimate, NodeValues, integrate

_EPS = float(np.finfo(float).eps)     # a Python float: the one-value path stays on Python floats
#: Relative rounding bound of the closed forms of this module (sums of non-negative terms,
#: each a few correctly rounded operations away from its inputs).
CLOSED_FORM_RTOL = 64 * _EPS


class Lens(NamedTuple):
    """C(Q, R) ∩ unit disk for a centre Q at distance d from O (figure 4.4).

    Attributes
    ----------
    alpha : ndarray
        Half the angle the common chord subtends at O (0 when no chord bounds the region
        on the unit circle, π when the whole unit disk is inside).
    beta : ndarray
        Half the angle the chord subtends at Q, likewise.
    area : ndarray
        Area(C(Q, R)) = (α − cos α sin α) + R² (β − cos β sin β)  (eq. 4.9).
    area_error : ndarray
        Bound on the rounding error of ``area`` for exact d and R (:func:`_lens_rounding`).
    """

    alpha: np.ndarray
    beta: np.ndarray
    area: np.ndarray
    area_error: np.ndarray


def _segment(t):
    """t − sin t cos t = (x − sin x)/2 with x = 2t, by its Taylor series where it cancels."""
    x = 2.0 * np.asarray(t, float)
    small = np.abs(x) < 0.25
    if small.any():
        small &= x != 0.0                # at 0 both forms give 0 (a lens's special cases)
    # x − sin x = Σ_{k≥1} (−1)^(k+1) x^(2k+1)/(2k+1)!, truncated after x^15 (error < 1e-18 rel).
    if not small.any():                  # (the series of zeros would add nothing)
        return 0.5 * (x - np.sin(x))
    out = np.asarray(x - np.sin(x))
    if out.ndim == 0:
        return 0.5 * _segment_series(x)
    out[small] = _segment_series(x[small])     # only where taken: its powers cost per value
    return 0.5 * out


def _segment_series(x):
    """x − sin x by its Taylor series (:func:`_segment`), for |x| < 1/4: an array's terms in one pass (a
    row per term), summed in order as they were added one by one (``np.cumsum`` is sequential): the
    same bits as term by term, for a seventh of the numpy calls."""
    if np.ndim(x) == 0:        # a number's power is not the array loop's (an ulp apart): term by term
        return sum(sign * x ** power / factorial for sign, power, factorial in _SEGMENT_TERMS)
    x = np.asarray(x, float)
    terms = _SEGMENT_SIGNS * x.reshape(1, -1) ** _SEGMENT_POWERS / _SEGMENT_FACTORIALS
    return np.cumsum(terms, axis=0)[-1].reshape(x.shape)


def _factorial(n):
    return float(np.prod(np.arange(1, n + 1, dtype=float)))


#: The terms of :func:`_segment`'s series, (−1)^(k+1), 2k + 1 and (2k + 1)!, k = 1 … 7, computed once
#: (a single angle's albedo computed the factorials 28 times).
_SEGMENT_TERMS = tuple(((-1) ** (k + 1), 2 * k + 1, _factorial(2 * k + 1)) for k in range(1, 8))
_SEGMENT_SIGNS, _SEGMENT_POWERS, _SEGMENT_FACTORIALS = (np.array(column, float)[:, None]
                                                        for column in zip(*_SEGMENT_TERMS))


def _four_triangle_area(a, b, c):
    """4 × area of the triangle with sides a, b, c (arrays of one shape; Kahan's stable Heron
    formula); 0 if degenerate."""
    a, b, c = np.sort(np.array([a, b, c]), axis=0)[::-1]
    factors = (a + (b + c)), (c - (a - b)), (c + (a - b)), (a + (b - c))
    prod = factors[0] * factors[1] * factors[2] * factors[3]
    out = np.sqrt(np.maximum(prod, 0.0))
    tiny = prod < _UNDERFLOWING
    if tiny.any():
        # a sliver of a triangle (sides 1, 1, d < 1e-160: the lens of R = 1 next to the pole) whose
        # product underflowed to 0, a lens area of 0 and an exact sampler's pdf of 0: the factors' roots
        roots = np.sqrt(np.maximum(factors[0], 0.0)) * np.sqrt(np.maximum(factors[1], 0.0))
        roots = roots * np.sqrt(np.maximum(factors[2], 0.0)) * np.sqrt(np.maximum(factors[3], 0.0))
        out = np.where(tiny, roots, out)
    return out


def _four_triangle_area_of_one(a, b, c):
    """:func:`_four_triangle_area` of one triangle, on Python floats: the same operations in the same
    order (sums, products, correctly rounded square roots), the same bits."""
    a, b, c = sorted((a, b, c), reverse=True)
    factors = (a + (b + c)), (c - (a - b)), (c + (a - b)), (a + (b - c))
    prod = factors[0] * factors[1] * factors[2] * factors[3]
    if prod < _UNDERFLOWING:
        return (math.sqrt(max(factors[0], 0.0)) * math.sqrt(max(factors[1], 0.0))
                * math.sqrt(max(factors[2], 0.0)) * math.sqrt(max(factors[3], 0.0)))
    return math.sqrt(max(prod, 0.0))


#: Below this Heron's product is near or past underflow (:func:`_four_triangle_area`).
_UNDERFLOWING = 1e-280


def circle_intersection(d, R, cos_theta=None):
    """The common part of the unit disk and the disk of radius R centred at distance d.

    Eqs. 4.9/4.10, with the angles from the triangle O, Q, P (P a chord end):
    α = atan2(4Δ, 1 + d² − R²), β = atan2(4Δ, d² + R² − 1), Δ its area (stable Heron) —
    accurate to rounding even for nearly tangent circles, where arccos of eq. 4.10 is not.

    Parameters
    ----------
    d : array_like
        Distance of the centre from O, ``d >= 0``.
    R : array_like
        Radius, ``R > 0``.
    cos_theta : array_like, optional
        √(1 − d²) where the caller has it accurately (d = sin θ): then 1 − d = cos²θ/(1 + d) and
        d² + R² − 1 = (R − cos θ)(R + cos θ) keep their relative accuracy for d near 1, which 1 − d
        from a rounded d does not (R = 2e-7 at 89.9998°: 4e-11 off, from d's last bit).

    Returns
    -------
    Lens
        Angles, area and a bound on the area's rounding (:func:`_lens_rounding`), which grows
        with the cancellation in 1 + d² − R² of nearly tangent circles.

    Examples
    --------
    Two unit circles one radius apart overlap in 2π/3 − √3/2:

    >>> lens = float(circle_intersection(1.0, 1.0).area)
    >>> bool(abs(lens - (2 * np.pi / 3 - np.sqrt(3) / 2)) < CLOSED_FORM_RTOL)
    True
    """
    d, R = _same_shape(np.asarray(d, float), np.asarray(R, float))
    # 1 + d² − R² as d² + (1 − R)(1 + R): 1 − R is exact near R = 1 (Sterbenz), and
    # 1.0 + (d − R)(d + R) lost all of d² ≈ 3e-16 at d = sin 1e-6°, R = 1 (a 1.5e-9 error).
    d2, one_minus_r, one_plus_r = d * d, 1.0 - R, 1.0 + R
    product, gap = one_minus_r * one_plus_r, np.abs(one_minus_r)
    x_alpha = d2 + product
    alpha_abs = d2 + gap * one_plus_r
    # for d > 1/2, with cos θ known, the forms of :func:`_four_triangle_area_near_unit` (below, 1 − d
    # from cos²θ/(1 + d) is the worse one); each form only where it is taken (one value: one form)
    near = None if cos_theta is None else d > 0.5
    every = near is not None and bool(near.all())
    some = every or near is not None and bool(near.any())
    if not every:
        four_delta = _four_triangle_area(np.ones_like(d), R, d)
        x_beta = d2 - product                      # d² + (R − 1)(1 + R), to the bit
        beta_abs = alpha_abs
        y_rel = 16 * _EPS
    if some:
        mu = np.asarray(cos_theta, float)
        mu = mu if mu.shape == d.shape else np.broadcast_to(mu, d.shape)
        mu2 = mu * mu
        one_minus_d = mu2 / (1.0 + d)
        with np.errstate(divide="ignore", invalid="ignore"):  # R − (1 − d): inputs that carry 4 ε themselves
            near_y_rel = 16 * _EPS + 4 * _EPS * one_minus_d / np.abs(R - one_minus_d)
        near_forms = (_four_triangle_area_near_unit(one_minus_d, d, R), (R - mu) * (R + mu), R * R + mu2, near_y_rel)
        if every:
            four_delta, x_beta, beta_abs, y_rel = near_forms
        else:
            four_delta, x_beta, beta_abs, y_rel = (
                np.where(near & (one_minus_d > 0) if k == 3 else near, form, general)
                for k, (form, general) in enumerate(zip(near_forms, (four_delta, x_beta, beta_abs, y_rel))))
    # both angles (and below, both segments and their rounding) in one pass: rows α, β
    # rows of equal shape: atan2 of a broadcast operand may take another loop, not the same to the bit
    x, y = np.array([x_alpha, x_beta]), np.array([four_delta, four_delta])
    angles = np.arctan2(y, x)
    nested = d <= gap
    apart = d >= one_plus_r
    special = nested | apart
    any_special = bool(special.any())
    if any_special:
        inside = R <= 1.0
        angles = np.where(apart, 0.0, np.where(nested, np.array([np.where(inside, 0.0, np.pi),
                                                                  np.where(inside, np.pi, 0.0)]), angles))
    segments = _segment(angles)
    area = segments[0] + R * R * segments[1]
    if any_special and special.all():
        error = _EPS * area
    else:
        error = _lens_rounding(angles, R, y, y_rel, x, np.array([alpha_abs, beta_abs]), area, segments)
        if any_special:
            error = np.where(special, _EPS * area, error)
    return Lens(angles[0], angles[1], area, error)


def _same_shape(d, R):
    """``d`` and ``R`` broadcast to one shape (a number beside an array: filled, the cheaper way)."""
    if d.shape == R.shape:
        return d, R
    if R.ndim == 0:
        return d, np.full(d.shape, R)
    if d.ndim == 0:
        return np.full(R.shape, d), R
    return tuple(np.broadcast_arrays(d, R))


def _four_triangle_area_near_unit(u, d, R):
    """4Δ of the triangle with sides 1, R, d = 1 − u: √((R + u)(1 + R + d)(R − u)(d − (R − 1)))
    (Heron's product with the differences 1 − d = u and R − 1 formed exactly, Sterbenz)."""
    upper = R >= 0.5
    last = d - (R - 1.0) if upper.all() else np.where(upper, d - (R - 1.0), d + (1.0 - R))
    return np.sqrt(np.maximum((R + u) * (1.0 + R + d) * (R - u) * last, 0.0))


def _angle_rounding(y, y_rel, x, x_abs):
    """Bound on the error of atan2(y, x) when y carries ``y_rel`` relative (16 ε: Kahan's Heron
    formula) and x = d² ± (1 − R)(1 + R) carries 4 ε · x_abs (x_abs the sum of its terms' absolute
    values): |δ atan2| ≤ (|x| |δy| + |y| |δx|)/(x² + y²), plus atan2's own rounding.  The ratio
    x_abs / |x| is the condition number of the cancellation in x, which no rewriting removes."""
    with np.errstate(divide="ignore", invalid="ignore"):
        spread = (np.abs(x) * y_rel * y + y * (4 * _EPS) * x_abs) / (x * x + y * y)   # y 4 ε: exact either way
    return np.where(np.isfinite(spread), spread, 0.0) + _EPS * np.abs(np.arctan2(y, x))


def _lens_rounding(angles, R, y, y_rel, x, x_abs, area, segments):
    """Bound on the rounding of eq. 4.9's area for exact d and R: the angles' errors times
    d(t − sin t cos t)/dt = 2 sin²t, the segments' own rounding (t − sin t cos t is formed as
    (x − sin x)/2, x = 2t, with an absolute error of a few ε t), and the final sum.  Rows α and β:
    ``angles``, the atan2 denominators ``x`` with the sums of their terms' absolute values ``x_abs``,
    and ``segments`` (:func:`_segment` of the angles, as the area has them)."""
    (sin2_alpha, sin2_beta), (d_alpha, d_beta) = np.sin(angles) ** 2, _angle_rounding(y, y_rel, x, x_abs)
    rounding = _segment_rounding(angles, segments)
    propagated = 2 * sin2_alpha * d_alpha + 2 * R * R * sin2_beta * d_beta
    return propagated + rounding[0] + R * R * rounding[1] + 2 * _EPS * area


def _segment_rounding(t, segment):
    """Rounding of ``segment`` = :func:`_segment` (t): a few ε relative on its series (2t < 1/4), a
    few ε t beyond."""
    size = np.abs(t)
    return 4 * _EPS * np.where(size < 0.125, segment, size)          # 2 |t| < 1/4, exactly


def basic_constant(R):
    """c(R) = 1 / (π min(1, R²))  (eq. 4.7)."""
    R = np.asarray(R, float)
    return 1.0 / (np.pi * np.minimum(1.0, R * R))


def basic_albedo(theta_deg, R):
    """a_R(L) = Area(C(L'_P, R)) / Area(C(O, R))  (eq. 4.8), with |L'_P| = sin θ.

    Returns
    -------
    Estimate
        Value and rounding bound, broadcast over ``theta_deg`` and ``R``.
    """
    return basic_albedo_at(sin_incidence(theta_deg), R, _cos_incidence_near_grazing(theta_deg))


def _cos_incidence_near_grazing(theta_deg):
    """cos θ = sin(90° − θ): 90° − θ is exact near grazing, where cos of a rounded radian angle
    carries ε (π/2)/(π/2 − θ) relative (7e-8 at 90° − 3e-7°)."""
    return np.sin(np.radians(90.0 - np.asarray(theta_deg, float)))


def basic_mean_albedo(R):
    """(a_R)_mean of the basic BRDF (eq. 4.11) in closed form.

    a_mean = 2 ∫₀¹ a_R(d) d dd (eq. 4.11 with u = cos²θ_L) and ∫_{|Q|<1} Area(C(Q, R)) dQ is
    the overlap of two unit disks averaged over shifts |t| < R, so with U = R/2
    a_mean = 2 F(U) / (π min(1, R²)),  F(U) = 4U² arccos U + arcsin U − U(1 + 2U²)√(1 − U²).

    Returns
    -------
    Estimate
        Value and rounding bound (the terms of F cancel to O(U²) for small R).
    """
    U = 0.5 * np.asarray(R, float)
    root = np.sqrt((1.0 - U) * (1.0 + U))
    terms = (4 * U * U * np.arccos(U), np.arcsin(U), U * (1 + 2 * U * U) * root)
    scale = 2.0 * basic_constant(R)
    value = scale * (terms[0] + terms[1] - terms[2])
    return Estimate(value, CLOSED_FORM_RTOL * scale * sum(terms))


@dataclass(frozen=True)
class ExponentialProfile:
    """ξ(m) = exp(−s m)  (eq. 4.44), s ≥ 0.

    Decreasing, so C_max makes a(N) = 1 (eq. 4.45); its weight p(R) (eq. 4.47) has a Dirac
    part p_Diffuse = C_max π e^{−2s} at R = 2 (eq. 4.21), the diffuse part of Table 4.1.
    """

    s: float

    def __post_init__(self):
        if not (np.isfinite(self.s) and self.s >= 0):
            raise ValueError(f"exponential profile: s must be finite and >= 0, got {self.s!r}")

    @property
    def negligible(self) -> bool:
        """s so small that e^{−s m} rounds to 1 for every m ≤ 2 (s < 2⁻⁵⁶): the profile is s = 0's,
        to the bit, and s² would underflow in C_max and the CDF (s = 1e-300 gave C = NaN)."""
        return self.s < 2.0 ** -56

    def xi(self, m):
        """ξ(m) = e^{−s m}  (eq. 4.44)."""
        return np.exp(-self.s * np.asarray(m, float))

    def dxi(self, m):
        """ξ'(m) = −s e^{−s m}."""
        return -self.s * self.xi(m)

    @property
    def c_max(self) -> float:
        """C_max = s² / (2π (1 − (1 + s) e^{−s}))  (eq. 4.45); 1 − (1+s)e^{−s} = P(2, s), the
        regularised incomplete gamma function, free of cancellation; its s → 0 limit is 1/π."""
        if self.negligible:
            return 1.0 / np.pi
        from scipy.special import gammainc   # scipy only where it is used: the diagrams import this module

        return self.s**2 / (2.0 * np.pi * gammainc(2.0, self.s))

    #: p(R) = C π s e^{−sR} min(1, R²) is entire: no pole to grade toward (:attr:`GeneralizedLambertProfile.steep_layer`).
    steep_layer = None

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Where p(R) changes scale: multiples of its mode 2/s (kinks are added by the caller)."""
        return tuple(k / self.s for k in (1.0, 4.0, 16.0, 64.0) if self.s > 0 and k / self.s < 2.0)

    def cdf(self, R):
        """F(R) = ∫₀^R p  (eq. 4.27): P(3, sR)/P(2, s) for R ≤ 1, then + s²(e^{−s} − e^{−sR})/(2P(2, s));
        the jump p_Diffuse at R = 2 is not included (F(2⁻) = 1 − p_Diffuse)."""
        R = np.asarray(R, float)
        if self.negligible:
            return np.zeros_like(R)
        from scipy.special import gammainc

        s, norm = self.s, gammainc(2.0, self.s)
        inner = gammainc(3.0, s * np.minimum(R, 1.0)) / norm
        outer = s * s * (np.exp(-s) - np.exp(-s * np.maximum(R, 1.0))) / (2.0 * norm)
        return inner + outer


@dataclass(frozen=True)
class GeneralizedLambertProfile:
    """ξ(m) = min((1 − (m/2)²)^{−d/2}, ξ_max), ξ_max = ξ(m_clip)  (eqs. 4.58/4.59), 0 ≤ d ≤ 1.

    Increasing: the albedo is smallest at normal incidence and largest at grazing incidence,
    so C_max = 1/a^ξ(90°) needs an integration (:func:`generalized_lambert_c_max`).
    """

    d: float
    m_clip: float = 1.9

    def __post_init__(self):
        if not 0.0 <= float(self.d) <= 1.0:
            raise ValueError(f"generalized Lambertian: d must lie in [0, 1], got {self.d!r}")
        if not 0.0 < float(self.m_clip) < 2.0:
            raise ValueError(f"generalized Lambertian: m_clip must lie in (0, 2), got {self.m_clip!r}")

    def _unclipped(self, m):
        return _one_minus_quarter_square(m) ** (-0.5 * self.d)

    @property
    def xi_max(self) -> float:
        """ξ_max = ξ(m_clip), the f_max column of Table 4.3."""
        return float(self._unclipped(self.m_clip))

    def xi(self, m):
        """ξ(m) clipped at ξ_max  (eq. 4.59 without C_max)."""
        m = np.asarray(m, float)
        return np.where(m < self.m_clip, self._unclipped(np.minimum(m, self.m_clip)), self.xi_max)

    def dxi(self, m):
        """ξ'(m) = (d m / 4)(1 − m²/4)^{−d/2 − 1} below m_clip, 0 above."""
        m = np.asarray(m, float)
        mc = np.minimum(m, self.m_clip)
        slope = 0.25 * self.d * mc * _one_minus_quarter_square(mc) ** (-0.5 * self.d - 1.0)
        return np.where(m < self.m_clip, slope, 0.0)

    def disk_integral(self, rho):
        """∫₀^ρ ξ(r) r dr for ρ ≤ m_clip: (4/(2 − d)) (1 − (1 − ρ²/4)^{(2−d)/2})."""
        rho = np.asarray(rho, float)
        if np.any(rho > self.m_clip):
            raise ValueError(f"disk_integral is closed-form only up to m_clip = {self.m_clip}")
        w = _one_minus_quarter_square(rho)
        return 4.0 / (2.0 - self.d) * -np.expm1(0.5 * (2.0 - self.d) * np.log(w))

    @property
    def breakpoints(self) -> tuple[float, ...]:
        return (float(self.m_clip),)                 # a number (a 0-d array m_clip is not hashable)

    @property
    def steep_layer(self) -> tuple[float, float] | None:
        """(end, pole) = (m_clip, 2): p(R) ∝ R³ (1 − R²/4)^{−d/2−1} (eq. 4.41 with :meth:`dxi`) grows toward
        its pole R = 2 up to its end m_clip, 0 beyond (:data:`WEIGHT_LAYER_GRADING`); None for d = 0 (p = 0)."""
        return (float(self.m_clip), 2.0) if self.d > 0 else None


def _one_minus_quarter_square(m):
    """1 − m²/4 as (1 − m/2)(1 + m/2): 1 − m/2 is exact for m in [1, 2] (Sterbenz), so the product carries
    2 ε relative where 1 − 0.25 m² lost ε/(1 − m/2) to cancellation near m = 2."""
    half = 0.5 * np.asarray(m, float)
    return (1.0 - half) * (1.0 + half)


def weight(profile, R, C):
    """p(R) = −C ξ'(R) π min(1, R²)  (eq. 4.41), the continuous part of the weight."""
    R = np.asarray(R, float)
    return -C * profile.dxi(R) * np.pi * np.minimum(1.0, R * R)


def diffuse_weight(profile, C):
    """p_Diffuse = C π ξ(2), the Dirac part of p(R) at R = 2 (eqs. 4.21, 4.24)."""
    return float(C * np.pi * profile.xi(2.0))



def _per_profile(fn, profiles):
    """An integrand ``(x, element) -> values`` applying ``fn(profile, x_rows)`` profile by profile."""

    def integrand(x, elem):
        out = np.empty_like(x)
        for i in np.unique(elem):
            rows = elem == i
            out[rows] = fn(profiles[i], x[rows])
        return out

    return integrand


def exponential_disk_integral(s, rtol=1e-10, atol=1e-14) -> Estimate:
    """∫₀¹ ξ(r) r dr = ∫₀¹ e^{−s r} r dr per s, by adaptive quadrature: the normalisation behind
    eq. 4.45's C_max = 1/(2π ∫₀¹ ξ r dr) (the albedo at normal incidence is 1), integrated."""
    s = np.asarray(s, float)
    rows = np.arange(s.size)

    def xi_r(r, e):
        return np.exp(-s[e][:, None] * r) * r

    return integrate(xi_r, np.stack([0 * rows, 1 + 0 * rows], 1), rtol=rtol, atol=atol)


def weight_integral(profiles, lo, hi, rtol=1e-10, atol=1e-14) -> Estimate:
    """∫_lo^hi p(R) dR (eq. 4.41/4.47) of each profile's weight with its own C_max, by adaptive
    quadrature split at R = 1 and the profile's breakpoints inside (lo, hi)."""
    p = _per_profile(lambda profile, R: weight(profile, R, profile.c_max), profiles)
    if (lo, hi) == (0.0, 2.0):
        bp = [[0.0, *sorted({1.0, *profile.breakpoints}), 2.0] for profile in profiles]
        width = max(map(len, bp))
        limits = [b + [np.nan] * (width - len(b)) for b in bp]
    else:
        rows = np.arange(len(profiles))
        limits = np.stack([lo + 0 * rows, hi + 0 * rows], 1)
    return integrate(p, np.asarray(limits, float), rtol=rtol, atol=atol)

#: Cuts R = (1 − d)(1 + g) above the kink R = 1 − d of a_R(d) (below 1): near grazing incidence
#: (1 − d ≈ cos²θ / 2) a_R falls from 1 to about 1/2 within a few times 1 − d of that kink, a layer
#: that one Gauss–Kronrod interval [1 − d, 1] does not see; a weight p(R) that does not vanish at
#: R → 0 gives it full weight (a uniform mixture at 89.9°: 3.3e-6 off at a reported 2.4e-6).
LENS_LAYER_GRADING = 4.0 ** np.arange(0.0, 27.0)


#: Every level of :data:`LENS_KINK_GRADING` halves the interval next to a kink, whose error (a_R's
#: (R − R₀)^{3/2}) falls by 2^{5/2} a level: a tolerance looser than this one takes one level fewer per
#: factor 2^{5/2} (:func:`lens_kink_levels`).  At rtol 1e-6 the eight levels had made a single angle's first
#: evaluation 607 nodes where 376 met the tolerance in one round as well (patch_exponential, the mean over
#: 12 angles to 89°; generalized Lambertian 530 and 299, the uniform mixture 425 and 194).
KINK_GRADED_RTOL = 1e-10
#: ... but never fewer levels than this: the rough pass (:data:`ROUGH_RTOL`) starts on the same partition,
#: and with one level or none a generalized Lambertian's first evaluation missed even its 1e-4 at some
#: angles (3–4 rounds, 45 angles to 89.9°); with two, the first evaluation of each typical lens mixture met
#: rtol 1e-6 and looser at those angles (a narrower one may take another round: the numpy route of a
#: generalized Lambertian with d = 1 at 62.3°).
MIN_KINK_LEVELS = 2


def lens_kink_levels(rtol):
    """How many levels of :data:`LENS_KINK_GRADING` a single element's first partition takes at ``rtol``: all
    at :data:`KINK_GRADED_RTOL` and tighter (and at rtol 0), one fewer per factor 2^{5/2} looser, at least
    :data:`MIN_KINK_LEVELS` (2 from 1e-6 on): the driver refines further where a model needs it."""
    rtol, levels, bound = float(rtol), len(LENS_KINK_GRADING), KINK_GRADED_RTOL
    # (a ratio of logs put 1e-10 · 2^2.5 a level low; the slack keeps a float32 1e-10, 1.0000000134e-10, at 8)
    while rtol > bound * (1.0 + 1e-6) and levels > MIN_KINK_LEVELS:
        levels, bound = levels - 1, bound * 2.0 ** 2.5
    return levels


def _r_breakpoints(points, d, single_graded=False, steep_layer=None, rtol=KINK_GRADED_RTOL):
    """Per element: 0, the kinks 1 − d, 1, 1 + d of a_R(d) in R, the cuts of :data:`LENS_LAYER_GRADING`,
    the weight's ``points``, 2, and with a ``steep_layer`` (end, pole) the cuts of :func:`weight_layer_cuts`;
    with ``single_graded``, a single element's row graded further for ``rtol`` (:func:`_single_element_partition`)."""
    d = np.atleast_1d(np.asarray(d, float))
    if single_graded and d.size == 1:
        return _single_element_partition(points, float(d[0]), steep_layer, rtol)[None]
    bp = _lens_breakpoints(points, d)
    return bp if steep_layer is None else _with_weight_layer(bp, d, *steep_layer)


def _lens_breakpoints(points, d):
    """:func:`_r_breakpoints`' rows without the weight's layer (NaN-padded)."""
    fixed = np.array([0.0, 1.0, 2.0, *points])
    layer = (1.0 - d)[:, None] * (1.0 + LENS_LAYER_GRADING)
    pts = np.concatenate([np.broadcast_to(fixed, (d.size, fixed.size)),
                          np.stack([1.0 - d, 1.0 + d], axis=1), np.where(layer < 1.0, layer, np.nan)], axis=1)
    pts = np.where((pts >= 0.0) & (pts <= 2.0), pts, np.nan)
    pts = np.sort(pts, axis=1)
    duplicate = np.concatenate([np.zeros((d.size, 1), bool), np.diff(pts, axis=1) == 0], axis=1)
    return np.sort(np.where(duplicate, np.nan, pts), axis=1)   # NaN padding last


#: Cuts R_e − r (4^k − 1), k = 1 … 26, below the end R_e = min(1 + d, end) of the integrand's support, when
#: its weight grows as a power of 1/(pole − R) toward a pole at r = pole − R_e (a generalized Lambertian:
#: (2 − R)^{−d/2−1}, cut at end = m_clip; :attr:`GeneralizedLambertProfile.steep_layer`): the pieces lie
#: r 4^k from the pole, 3 times as wide, where the Gauss–Kronrod pair resolves the pole and K − G bounds G's
#: error.  Without them the interval ending at R_e, ≫ r wide, held a layer of width ~r that neither rule
#: sees and K − G underrated G's error: near m_clip → 2 at grazing the weight's (2 − R)^{−3/2} (d = 1) and
#: the lens's 1 − a_R ∝ (1 + d − R)^{3/2} make p (a_R − 1) ≈ const · (1 − (3/2)(1 − d)/(2 − R)), and the
#: interval [m_clip − 1/16, m_clip] at m_clip = 2 − 1e-6, 89.99° had |K − G| = 1.2e-8 for an error of 3.5e-8
#: (reported 2.45e-8).  1 + 4^26 r exceeds the range [0, 2] for every r ≥ ε.
WEIGHT_LAYER_GRADING = tuple(4.0 ** k - 1.0 for k in range(1, 27))
#: The cuts are made only where the interval ending at R_e is wider than this many r (the rows of m_clip
#: ≤ 1.9 never: 0.9 / 0.1): a layer that wide is resolved, and the partition keeps its bits.
WEIGHT_LAYER_TRIGGER = 16.0


def weight_layer_cuts(prev, r_end, r):
    """:data:`WEIGHT_LAYER_GRADING`'s cuts in (``prev``, ``r_end``) for a pole ``r`` beyond ``r_end`` (numbers:
    a single element's row), none unless that interval is wider than :data:`WEIGHT_LAYER_TRIGGER` r."""
    if not (r > 0.0 and r_end - prev > WEIGHT_LAYER_TRIGGER * r):
        return []
    return [cut for cut in (r_end - r * g for g in WEIGHT_LAYER_GRADING) if cut > prev]


def _with_weight_layer(bp, d, end, pole):
    """Rows ``bp`` (:func:`_lens_breakpoints`) with :func:`weight_layer_cuts` below each element's end
    min(1 + d, ``end``): the same cuts as a single element's, rows without them unchanged."""
    r_end = np.minimum(1.0 + d, end)
    r = pole - r_end
    prev = np.max(np.where(bp < r_end[:, None], bp, -np.inf), axis=1)      # the row's point below the end
    steep = (r > 0.0) & (r_end - prev > WEIGHT_LAYER_TRIGGER * r)
    if not steep.any():
        return bp
    cuts = r_end[steep, None] - r[steep, None] * np.array(WEIGHT_LAYER_GRADING)
    layer = np.full((d.size, cuts.shape[1]), np.nan)
    layer[steep] = np.where(cuts > prev[steep, None], cuts, np.nan)
    rows = np.sort(np.concatenate([bp, layer], axis=1), axis=1)           # NaN padding last
    return rows[:, np.isfinite(rows).any(axis=0)]


#: A single element's first partition is graded by halves toward the lens's kinks, R = 1 − d from above
#: and R = 1 + d from below (where a_R(d) starts as (R − R₀)^{3/2}): cuts R₀ ± w 2^(−k), w the width of the
#: interval next to the kink.  The driver bisected those two intervals level by level, one round a level
#: (a uniform mixture at 40°, rtol 1e-10: 8 rounds of 4 intervals).
LENS_KINK_GRADING = tuple(2.0 ** -k for k in range(1, 9))
#: Cuts of a single element's first partition below each of the weight's ``points`` (the profile's
#: breakpoints), by halves: a generalized Lambertian's p(R) steepens toward its clip m_clip = 1.9, 0.1 from
#: its singularity at R = 2, and the interval below m_clip took one or two more rounds at 1e-10.
WEIGHT_POINT_GRADING = (0.5, 0.25, 0.125, 0.0625)
_LAYERS = tuple((1.0 + LENS_LAYER_GRADING).tolist())


def _single_element_partition(points, d, steep_layer=None, rtol=KINK_GRADED_RTOL):
    """The first partition of one element at |L'_P| = ``d``, on Python floats: the points of
    :func:`_r_breakpoints`, graded toward the lens's kinks (:data:`LENS_KINK_GRADING`, as many levels as
    ``rtol`` takes: :func:`lens_kink_levels`) and toward the
    weight's ``points`` from below (:data:`WEIGHT_POINT_GRADING`), so that one evaluation meets the
    tolerance (a round of a single element costs more than its nodes; a batch's elements share their
    rounds and keep :func:`_r_breakpoints`'s partition, to the bit)."""
    lo, hi = 1.0 - d, 1.0 + d
    row = sorted({p for p in (0.0, 1.0, 2.0, *points, lo, hi, *(lo * g for g in _LAYERS if lo * g < 1.0))
                  if 0.0 <= p <= 2.0})
    if steep_layer is not None:          # the weight's layer, then graded toward as the row's own points
        end, pole = steep_layer
        r_end = min(hi, end)
        row = sorted({*row, *weight_layer_cuts(max(p for p in row if p < r_end), r_end, pole - r_end)})
    cuts = set(row)
    inside = [p for p in points if 0.0 < p <= 2.0]       # the points _r_breakpoints keeps (a point past 2: none)
    if lo < hi:
        above = [p for p in row if p > lo]
        below = [p for p in row if p < hi]
        grading = LENS_KINK_GRADING[:lens_kink_levels(rtol)]
        if above:
            cuts.update(lo + (above[0] - lo) * g for g in grading)
        if below:
            cuts.update(hi - (hi - below[-1]) * g for g in grading)
    for point in inside:                 # the weight's own features, graded toward from below
        before = [p for p in row if p < point]
        if before:
            cuts.update(point - (point - before[-1]) * g for g in WEIGHT_POINT_GRADING)
    return np.array(sorted(cuts))


class LensMixture(NamedTuple):
    """What the albedo of a mixture of basic BRDFs, a^p(L) = ∫₀² p(R) a_R(L) dR + p_Diffuse (eqs. 4.22, 4.24),
    takes from its model: the arguments of :func:`weighted_mixture_albedo` that are the model's facts (a route,
    numpy's or a compiled one, integrates the lens areas a_R and calls ``weight`` on its nodes).

    Attributes
    ----------
    weight : callable
        p(R), vectorised, on [0, 2].
    p_diffuse : float
        The Dirac weight at R = 2.
    points : tuple of float
        Where p is not smooth (a profile's breakpoints, a mixture's ``weight_points``).
    covered : float or None
        p_Diffuse + ∫₁² p in closed form (:func:`covered_weight`), or None.
    steep_layer : tuple of float or None
        (end, pole) of a weight that grows toward a pole (:func:`weight_layer_cuts`), or None.
    """

    weight: object
    p_diffuse: float
    points: tuple = ()
    covered: float | None = None
    steep_layer: tuple | None = None


def profile_mixture(profile, C) -> LensMixture:
    """The :class:`LensMixture` of a profile's weight p(R) (eq. 4.41) at constant ``C``, with its Dirac part
    (eq. 4.24), breakpoints, covered weight and steep layer."""
    return LensMixture(lambda R: weight(profile, R, C), diffuse_weight(profile, C), profile.breakpoints,
                       covered_weight(profile, C), profile.steep_layer)


def lens_mixture_albedo(mixture, theta_deg, rtol=1e-10, atol=1e-14, single_graded=False):
    """:func:`weighted_mixture_albedo` of a :class:`LensMixture`."""
    return weighted_mixture_albedo(mixture.weight, mixture.p_diffuse, theta_deg, rtol, atol, mixture.points,
                                   single_graded, mixture.covered, mixture.steep_layer)


def _mixture_integral(profile, C, per_element, d, rtol, atol):
    """:func:`_weighted_mixture_integral` of a profile's weight p(R) (eq. 4.41) and Dirac part (eq. 4.24):
    its :func:`profile_mixture`."""
    mixture = profile_mixture(profile, C)
    return _weighted_mixture_integral(mixture.weight, mixture.p_diffuse, per_element, d, rtol, atol, mixture.points,
                                      covered=mixture.covered, steep_layer=mixture.steep_layer)


def covered_weight(profile, C):
    """p_Diffuse + ∫₁² p(R) dR = C π ξ(1) in closed form (p = −C π ξ' for R ≥ 1, eq. 4.41; p_Diffuse = C π ξ(2),
    eq. 4.24): the weight of patches that would cover the unit disk.  A profile's albedo integrates
    p (g − 1) on [1, 2] and adds this, where ∫ p g cancelled p_Diffuse: a generalized Lambertian's p_Diffuse
    = C π ξ_max is ~1000 C at m_clip = 2 − 1e-6, and its p(R), steep at m_clip on the scale 2 − m_clip, took
    the rounding of the nodes R (relative (d/2 + 1) ε R/(2 − R)) into that cancellation, past the error."""
    return float(C * np.pi * profile.xi(1.0))


#: The rough pass's tolerance in :func:`_weighted_mixture_integral`: it sizes the sum the target is relative to.
ROUGH_RTOL = 1e-4


def _weighted_mixture_integral(p, p_diffuse, per_element, d, rtol, atol, points=(), single_graded=False,
                               covered=None, steep_layer=None):
    """∫₀² p(R) g(R, element) dR + p_Diffuse for g = ``per_element`` (an :class:`Estimate`),
    one element per |L'_P| = ``d`` (whose kinks 1 ∓ d split the range, with the weight's ``points``).
    With ``covered`` = p_Diffuse + ∫₁² p in closed form (:func:`covered_weight`): ∫₀² p (g − [R ≥ 1]) dR + covered
    (g − 1 is exact, Sterbenz, for g in [1/2, 2]; its rounding below 1/2 is ε/2, within the final term).
    ``steep_layer``: (end, pole) of a weight that grows toward a pole (:func:`weight_layer_cuts`)."""

    def integrand(x, elem):
        g = per_element(x, elem)
        w = p(x)
        value = g.value if covered is None else g.value - (x >= 1.0)
        return NodeValues(w * value, w * value, w * g.error)

    kept = []                     # the rough pass's first evaluation: (nodes, elements, values)

    def rough_integrand(x, elem):
        out = integrand(x, elem)
        if not kept:
            kept.append((x, elem, out))
        return out

    def final_integrand(x, elem):
        if kept:                  # the second pass starts on the same intervals: their values again
            x0, elem0, out = kept.pop()
            if x.shape == x0.shape and np.array_equal(x, x0) and np.array_equal(elem, elem0):
                return out
        return integrand(x, elem)

    bp = _r_breakpoints(points, d, single_graded, steep_layer, rtol)
    # The tolerance is relative to the albedo, not to the integral: with a generalized Lambertian
    # profile the integral is negative and larger than the sum (d = 1: −1.5 + 2.26), so rtol on it
    # left the albedo up to 1.8 rtol off.  A rough pass sizes the sum.
    rough, rough_rounds = integrate(rough_integrand, bp, rtol=ROUGH_RTOL, atol=atol, return_rounds=True)
    constant = p_diffuse if covered is None else covered
    target = np.maximum(0.5 * rtol * np.abs(rough.value + constant), atol)
    # The second pass starts from the rough pass's first evaluation; where the rough pass stopped there
    # (nothing was split) with every error within a quarter of the target, the second stops there too
    # (2 Σ|K − G| ≤ error ≤ target / 4 is within its budget, :func:`.gauss_kronrod._budget`) and its sums
    # are the same: the rough answer is the final one, to the bit, without the second pass's round.
    est = rough if rough_rounds == 0 and np.all(rough.error <= 0.25 * target) else \
        integrate(final_integrand, bp, rtol=0.0, atol=target)
    rounding = abs(p_diffuse) if covered is None else abs(covered) + abs(p_diffuse)   # ≥ ∫₁²|p| (p of one sign)
    return Estimate(est.value + constant, est.error + CLOSED_FORM_RTOL * rounding)


def mixture_albedo(profile, theta_deg, C=None, rtol=1e-10, atol=1e-14, single_graded=False):
    """a^p(L) = ∫₀² p(R) a_R(L) dR + p_Diffuse  (eqs. 4.22, 4.24), vectorised over θ.

    Parameters
    ----------
    profile : ExponentialProfile or GeneralizedLambertProfile
        The profile ξ; p(R) from eq. 4.41.
    theta_deg : array_like
        Incidence angles in [0°, 90°].
    C : float, optional
        The BRDF's constant; default the profile's ``c_max``.
    single_graded : bool
        A single angle starts from a graded partition (:func:`_single_element_partition`: fewer
        rounds, other bits); the models' own routes ask for it, a batch is never graded.

    Returns
    -------
    Estimate
        Albedo and error, shape of ``theta_deg``.
    """
    C = profile.c_max if C is None else float(C)
    return lens_mixture_albedo(profile_mixture(profile, C), theta_deg, rtol, atol, single_graded)


def weighted_mixture_albedo(p, p_diffuse, theta_deg, rtol=1e-10, atol=1e-14, points=(), single_graded=False,
                            covered=None, steep_layer=None):
    """a^p(L) = ∫₀² p(R) a_R(L) dR + p_Diffuse  (eqs. 4.22, 4.24) of any weight: ``p`` a vectorised
    callable p(R) on [0, 2] (smooth between the kinks 1, 1 ∓ |L'_P| of a_R and its own ``points``: a weight not
    smooth between them gives an unreliable error estimate), ``p_diffuse`` the Dirac weight at R = 2, whose a_2 = 1.  The error adds each lens area's rounding
    bound, weighted by |p|, to the quadrature's.  ``single_graded``: as :func:`mixture_albedo`; ``covered``: p_Diffuse
    + ∫₁² p in closed form, as :func:`_weighted_mixture_integral` takes it; ``steep_layer``: (end, pole) of a
    weight that grows toward a pole (:func:`weight_layer_cuts`).

    Returns
    -------
    Estimate
        Albedo and error, shape of ``theta_deg``.
    """
    theta = np.asarray(theta_deg, float)
    d = np.atleast_1d(sin_incidence(theta)).ravel()
    mu = np.atleast_1d(_cos_incidence_near_grazing(theta)).ravel()
    est = _weighted_mixture_integral(p, p_diffuse, lambda R, e: basic_albedo_at(d[e][:, None], R, mu[e][:, None]),
                                     d, rtol, atol, points, single_graded, covered, steep_layer)
    return Estimate(est.value.reshape(theta.shape), est.error.reshape(theta.shape))


def basic_albedo_at(d, R, cos_theta=None):
    """a_R at |L'_P| = d (eq. 4.8), as an :class:`Estimate` (R > 0); ``cos_theta`` = √(1 − d²) where
    known accurately (:func:`circle_intersection`).

    The error is the lens's rounding bound (:attr:`Lens.area_error`, which grows with the
    cancellation in 1 + d² − R² where the circles are nearly tangent), plus the input's own
    rounding (2 ε relative in d = sin θ, or in cos θ, which moves d by 2 ε cos²θ/d) times
    |∂ area/∂d| = 2 sin α (the chord), plus c(R)'s rounding."""
    if np.size(d) == 1 and np.size(R) == 1 and (cos_theta is None or np.size(cos_theta) == 1):
        shape = (1,) * max(np.ndim(d), np.ndim(R), np.ndim(cos_theta))     # their broadcast: every size is 1
        value, error = _basic_albedo_of_one(float(np.ravel(d)[0]), float(np.ravel(R)[0]),
                                            None if cos_theta is None else float(np.ravel(cos_theta)[0]))
        return Estimate(np.full(shape, value), np.full(shape, error))
    lens = circle_intersection(d, R, cos_theta)
    c = basic_constant(R)
    value = lens.area * c
    d = np.asarray(d, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        moved = d if cos_theta is None else np.minimum(d, np.asarray(cos_theta, float) ** 2 / d)
    from_input = np.abs(np.sin(lens.alpha)) * (4 * _EPS) * moved      # 2 |sin α| · 2 ε: scalings by powers of 2
    return Estimate(value, c * (lens.area_error + from_input) + 3 * _EPS * value)


def _basic_albedo_of_one(d, R, mu=None):
    """(value, error) of :func:`basic_albedo_at` for one (d, R) on Python floats: a single angle's closed
    form, where numpy's ~80 calls on 1-element arrays cost 4/5 of the call.  The same operations in the
    same order as :func:`circle_intersection`, :func:`_lens_rounding` and :func:`basic_albedo_at`, the
    transcendental ones by numpy once on both angles (a libm ulp could differ), give the same bits
    (``tests/physics/test_patch.py`` holds the two paths together)."""
    d2, one_minus_r, one_plus_r = d * d, 1.0 - R, 1.0 + R
    product, gap = one_minus_r * one_plus_r, abs(one_minus_r)
    x_alpha, alpha_abs = d2 + product, d2 + gap * one_plus_r
    if mu is not None and d > 0.5:                       # the forms of _four_triangle_area_near_unit
        mu2 = mu * mu
        u = mu2 / (1.0 + d)
        last = d - (R - 1.0) if R >= 0.5 else d + (1.0 - R)
        four_delta = math.sqrt(max((R + u) * (1.0 + R + d) * (R - u) * last, 0.0))
        x_beta, beta_abs = (R - mu) * (R + mu), R * R + mu2
        y_rel = 16 * _EPS + (4 * _EPS * u / abs(R - u) if R != u else math.inf)
    else:
        four_delta = _four_triangle_area_of_one(1.0, R, d)
        x_beta, beta_abs, y_rel = d2 - product, alpha_abs, 16 * _EPS
    raw = np.arctan2(np.array([four_delta, four_delta]), np.array([x_alpha, x_beta]))
    angles = raw
    special = d <= gap or d >= one_plus_r
    if d >= one_plus_r:
        angles = np.zeros(2)
    elif special:
        angles = np.array([0.0, np.pi] if R <= 1.0 else [np.pi, 0.0])
    seg_alpha, seg_beta = _segment(angles).tolist()
    area = seg_alpha + R * R * seg_beta
    sin_alpha, sin_beta = np.sin(angles).tolist()
    if special:
        area_error = _EPS * area
    else:
        d_alpha, d_beta = (_spread(y_rel, x, x_abs, four_delta) + _EPS * abs(t)
                           for x, x_abs, t in zip((x_alpha, x_beta), (alpha_abs, beta_abs), raw.tolist()))
        alpha, beta = angles.tolist()
        rounding = [4 * _EPS * (seg if abs(t) < 0.125 else abs(t)) for t, seg in ((alpha, seg_alpha), (beta, seg_beta))]
        propagated = 2 * (sin_alpha * sin_alpha) * d_alpha + 2 * R * R * (sin_beta * sin_beta) * d_beta
        area_error = propagated + rounding[0] + R * R * rounding[1] + 2 * _EPS * area
    area_of_patch = np.pi * min(1.0, R * R)
    c = 1.0 / area_of_patch if area_of_patch else math.inf
    value = area * c
    moved = d if mu is None else min(d, mu * mu / d if d else math.inf)
    from_input = abs(sin_alpha) * (4 * _EPS) * moved
    return value, c * (area_error + from_input) + 3 * _EPS * value


def _spread(y_rel, x, x_abs, y):
    """:func:`_angle_rounding`'s first term for one row, on Python floats (0 where not finite)."""
    denominator = x * x + y * y
    spread = (abs(x) * y_rel * y + y * (4 * _EPS) * x_abs) / denominator if denominator else math.nan
    return spread if math.isfinite(spread) else 0.0


def mixture_mean_albedo(profile, C=None, rtol=1e-10, atol=1e-14):
    """a^p_mean = ∫₀² p(R) (a_R)_mean dR + p_Diffuse  (eqs. 4.23, 4.24), as a scalar Estimate."""
    C = profile.c_max if C is None else float(C)
    est = _mixture_integral(profile, C, lambda R, e: basic_mean_albedo(R), np.array([0.0]), rtol, atol)
    return est[0]


def generalized_lambert_c_max(profile, rtol=1e-10, atol=1e-14):
    """C_max = 1 / a^ξ(90°) of the clipped profile (Table 4.3): the albedo of ξ is largest at
    grazing incidence (see the thesis below eq. 4.59; checked in the tests).

    Summed as ∫₀² p a_R dR + p_Diffuse, without :func:`covered_weight`: C is the model's constant, and the
    stored truths of the sweep and the regression baselines were computed with these bits (the covered sum
    moves C by ~1e-11 relative, within its error).  Near m_clip → 2 this sum's error is not to be trusted
    (the albedo's is: it takes the covered sum for whatever C)."""
    a90 = weighted_mixture_albedo(lambda R: weight(profile, R, 1.0), diffuse_weight(profile, 1.0), 90.0, rtol, atol,
                                  profile.breakpoints)
    return Estimate(1.0 / a90.value, a90.error / a90.value**2)


def centred_ellipse_area(b, ratio):
    """Area(E(O, v, b)): the ellipse with semi-axes b/ratio (along u) and b (along v), centred at O,
    cut by the unit disk — the denominator of eqs. 4.35/4.36.

    With a = b/ratio: πab if a ≤ 1, π if b ≥ 1, otherwise (in polar coordinates, the ellipse
    leaves the disk at sin²φ₀ = (1 − a⁻²)/(b⁻² − a⁻²))  2φ₀ + ab (π − 2 atan((a/b) tan φ₀)).
    """
    b, ratio = np.broadcast_arrays(np.asarray(b, float), np.asarray(ratio, float))
    a = b / ratio
    with np.errstate(divide="ignore", invalid="ignore"):
        phi0 = np.arcsin(np.sqrt((1.0 - a**-2) / (b**-2 - a**-2)))
        clipped = 2.0 * phi0 + a * b * (np.pi - 2.0 * np.arctan(np.tan(phi0) / ratio))
    return np.where(a <= 1.0, np.pi * a * b, np.where(b >= 1.0, np.pi, clipped))


def elliptical_constant(b, ratio):
    """c(b) = 1 / Area(E(O, v, b))  (eq. 4.36: 1/(abπ) while the ellipse fits in the disk)."""
    return 1.0 / centred_ellipse_area(b, ratio)


def limit_small_patch_albedo(theta_deg):
    """lim_{R→0} a_R(θ) (eq. 4.8): 1 for θ < 90°, 1/2 at θ = 90°.

    For θ < 90° the disk of radius R → 0 around L'_P lies inside the unit disk; at θ = 90° its
    centre is on the unit circle, which cuts it in half as R → 0.  The exponential profile's
    p(R) concentrates at R → 0 as s → ∞ (F(R) → 1 for every R > 0, eq. 4.27), so this is also
    lim_{s→∞} a^p(θ), and the mean albedo tends to 1 (Table 4.2).
    """
    theta = np.asarray(theta_deg, float)
    return np.where(theta < 90.0, 1.0, 0.5)


def inverse_cdf(profile, r, iterations=64):
    """F⁻¹(r) of the exponential weight (eq. 4.27; Figure 4.13), by bisection on the closed-form F.

    F rises continuously to 1 − p_Diffuse at R = 2⁻ and jumps to 1 there (the Dirac part), so
    F⁻¹(r) = 2 for r ≥ 1 − p_Diffuse.

    Returns
    -------
    Estimate
        R with its error: the final bracket plus the rounding of F divided by the slope p(R).
    """
    r = np.asarray(r, float)
    if np.any((r < 0) | (r > 1)):
        raise ValueError(f"inverse_cdf: r must lie in [0, 1], got {r[(r < 0) | (r > 1)][:5]!r}")
    lo, hi = np.zeros_like(r), np.full_like(r, 2.0)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        below = profile.cdf(mid) < r
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    R = 0.5 * (lo + hi)
    slope = weight(profile, R, profile.c_max)
    with np.errstate(divide="ignore", invalid="ignore"):
        err = 0.5 * (hi - lo) + np.where(r > 0, CLOSED_FORM_RTOL * r / slope, 0.0)
    at_top = r >= 1.0 - diffuse_weight(profile, profile.c_max)
    return Estimate(np.where(at_top, 2.0, np.where(r > 0, R, 0.0)), np.where(at_top | (r == 0), 0.0, err))
