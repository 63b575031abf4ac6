"""The azimuthal integral of the isotropic Ward BRDF in the half-vector frame, in closed form.

    W(p, q, a, b) = ∫₀^π (p + q cos φ) √[a + b cos φ]₊ dφ = p W₀(a, b) + q W₁(a, b),     b ≥ 0,   (1)
    W₀ = ∫₀^π √[a + b cos φ]₊ dφ,       W₁ = ∫₀^π cos φ √[a + b cos φ]₊ dφ,

with N·V = a + b cos φ and L·H = p + q cos φ (:mod:`.azimuthal`, kernel ``"sqrt(nv/nl)"``).
Both moments are computed to a few ulps *relative to themselves*, so W carries an absolute
error of a few ulps of |p| W₀ + |q| W₁, the conditioning of the sum (1) itself: that is relative
to |W| whenever p W₀ and q W₁ do not cancel, and never worse than relative to the scale
S = (|p| + |q|) √(|a| + b) π.

Reduction (x = cos φ; every step below is an identity, checked against 40-digit quadrature).
R_D is Carlson's symmetric integral (DLMF 19.16.5)

    R_D(x, y, z) = 3/2 ∫₀^∞ [(t + x)(t + y)]^{-1/2} (t + z)^{-3/2} dt,                           (2)

homogeneous of degree −3/2, with R_D(0, y, y) = 3π / (4 y^{3/2}) and y R_D(0, c, y) → 3/√c,
y R_D(0, y, c) → 0 as y → 0.

1. W₁ by parts.  d(sin φ √(a + b cos φ)) = cos φ √(…) dφ − (b sin²φ / 2√(…)) dφ, and the boundary
   term vanishes at φ = 0, at φ = π and where a + b cos φ = 0, so

       W₁ = (b/2) ∫ sin²φ / √(a + b cos φ) dφ  ≥ 0                                              (3)

   over the lit arc.  W₀ and W₁ both have positive integrands: no cancellation is inherent in
   either, and the formulas below keep it that way except (5b), which is replaced by (6).

2. The cut.  The cubic (1 − x)(1 + x)(a + b x) under x = cos φ has roots −1, 1 and −a/b; the lit
   arc runs between two adjacent roots, so both moments are *complete* elliptic integrals.
   Write α = a + b (the value of N·V at φ = 0) and ψ = φ/2, a + b cos φ = α − 2b sin²ψ:

   * a ≤ −b: the circle lies below the horizon, W₀ = W₁ = 0 exactly (also a = b = 0).
   * a ≥ b (whole circle lit): with k² = 2b/α, k′² = β/α, β = a − b,
     W₀ = 2√α E(k) and W₁ = 2√α (E − 2 I₁), I₁ = ∫₀^{π/2} sin²ψ √(1 − k² sin²ψ) dψ.
   * |a| < b (cap φ ∈ [0, φ_h], cos φ_h = −a/b): put sin ψ = κ sin θ with κ² = α/(2b), so that
     a + b cos φ = α cos²θ and dφ = 2κ cos θ dθ / √(1 − κ² sin²θ); then
     W₀ = 2√α κ ∫₀^{π/2} cos²θ / Δ dθ and, from (3), W₁ = (4bκ³/√α) I₁(κ), Δ = √(1 − κ² sin²θ).
     No division by b survives: κ′² = γ/(2b), γ = b − a.

3. Carlson forms without subtraction.  DLMF 19.25.1 gives K − E = (k²/3) R_D(0, k′², 1),
   E − k′²K = (k² k′²/3) R_D(0, 1, k′²), E = (k′²/3) [R_D(0, k′², 1) + R_D(0, 1, k′²)].  Hence
   ∫ cos²θ / Δ = (E − k′²K)/k² = (k′²/3) R_D(0, 1, k′²) and I₁ = [k′²K + (2k² − 1) E]/(3k²)
   = (2/3)E − (E − k′²K)/(3k²) = (k′²/9) [2 R_D(0, k′², 1) + R_D(0, 1, k′²)]: sums of positive
   terms.  Scaling the arguments by α (or 2b) with homogeneity, and writing for s ≥ 0, c > 0

       T(s, c) = s R_D(0, c, s)  (the large one, → 3/√c as s → 0),
       t(s, c) = s R_D(0, s, c)  (the small one, → 0 as s → 0, like s log(1/s)),              (4)

   the moments are, with α = a + b:

       a ≥ b,  T = T(β, α), t = t(β, α), β = a − b:
           W₀ = (2α/3) (T + t),                                                               (5a)
           W₁ = (2α/9) (T − t);                                                               (5b)
       |a| < b,  T = T(γ, 2b), t = t(γ, 2b), γ = b − a:
           W₀ = (2α/3) T,                                                                     (5c)
           W₁ = (2α/9) (T + 2t).                                                              (5d)

   At a = b (the circle touches the horizon at φ = π) both sides give T = 3/√(2b), t = 0:
   W₀ = 2√(2b), W₁ = (2/3)√(2b), so the two cases join continuously (with the logarithmic
   slope ∂W/∂a ~ log|a − b| of a touching circle, carried by t).  Near a = b, β and γ are exact
   (Sterbenz), near a = −b α is exact: the tiny cap keeps W = O(α) to a few ulps relative.
   T and t are replaced by their limits when s ≤ 10⁻²⁰⁰ c (relative change ≤ 10⁻¹⁹⁰), which
   keeps R_D(0, c, s) ~ 3/(s√c) from overflowing and gives a = b exactly its limit.

4. Far from the horizon.  (5b) subtracts: T − t = O(k²) (T + t) as b/a → 0 (the loss is
   (T + t)/(T − t) ≈ 2.6 at a = 2b, ≈ 4 at a = 3b, ≈ 25 at a = 20b).  There the moment comes
   instead from (3) as a hypergeometric series: with ψ = φ/2,
   W₁ = (4b/√α) ∫₀^{π/2} sin²ψ cos²ψ (1 − k² sin²ψ)^{-1/2} dψ = (π b / 4√α) F(1/2, 3/2; 3; k²),
   and Gauss's quadratic transformation F(A, B; 2B; z) = (1 − z/2)^{-A} F(A/2, A/2 + 1/2; B + 1/2;
   (z/(2 − z))²) (DLMF 15.8.13; here A = 1/2, B = 3/2), with 1 − k²/2 = a/α and k²/(2 − k²) = b/a,
   gives

       W₁ = (π b / 4√a) G((b/a)²),     G(z) = F(1/4, 3/4; 2; z) = Σₙ gₙ zⁿ,
       g₀ = 1,  gₙ₊₁ = gₙ (n + 1/4)(n + 3/4) / ((n + 2)(n + 1)),                              (6)

   a series of positive terms, used where a ≥ 2b (z ≤ 1/4, 26 terms: truncation < 10⁻¹⁹).  It is
   exact at b = 0 (W₁ = 0, and (5a) gives W₀ = π√a) and divides by a, never by b.  The switch at
   a = 2b bounds the loss of (5b) by 2.6; the two branches agree there to a few ulps.

Rounding-error bound (absolute, first order in the unit roundoff u = ε/2).  scipy's R_D
(Carlson's duplication algorithm) is taken to err by ≤ 4ε relatively (measured ≤ 2.6ε over
2·10⁴ complete-integral arguments against mpmath at 40 digits); perturbing its arguments by u
each changes it by ≤ 1.5u (homogeneity of degree −3/2, all partial derivatives negative).
Counting the roundings of α, β, γ, the products and the sums term by term gives the constants in
:func:`sqrt_positive_part_moments`; (6) adds Horner's Σ (2n + 2) gₙ zⁿ u over G (a constant
evaluated at z = 1/4, where this ratio is largest).  The bound on W adds ε (|p W₀| + |q W₁|)
for (1).  Against mpmath (2·10⁴ random (a, b) biased to the joins, seven (p, q)): errors ≤ 3.8ε
of |p| W₀ + |q| W₁, never above the bound (at most 0.36 of it), median bound/error ≈ 20.
"""
from __future__ import annotations

import numpy as np
from scipy.special import elliprd

_EPS = np.finfo(float).eps
_U = _EPS / 2
#: Relative error allowed for scipy.special.elliprd on complete arguments (measured ≤ 2.6 ε).
_RD_REL = 4.0 * _EPS
#: Below s = _LIMIT_RATIO · c, T(s, c) and t(s, c) of eq. (4) take their s → 0 limits.
_LIMIT_RATIO = 1e-200
#: Series (6) for W₁ where a ≥ _SERIES_SWITCH · b, i.e. z = (b/a)² ≤ 1/_SERIES_SWITCH².
_SERIES_SWITCH = 2.0


def _series_coefficients(z_max: float, tail: float = 1e-3 * _U):
    """gₙ of eq. (6) up to the first n whose remaining tail gₙ z_maxⁿ/(1 − z_max) < ``tail``, and
    the Horner rounding constant Σ (2n + 2) gₙ z_maxⁿ / G(z_max) (the ratio grows with z)."""
    g = [1.0]
    while g[-1] * z_max ** (len(g) - 1) / (1.0 - z_max) >= tail:
        n = len(g) - 1
        g.append(g[-1] * (n + 0.25) * (n + 0.75) / ((n + 2.0) * (n + 1.0)))
    g = np.array(g[:-1])
    terms = g * z_max ** np.arange(g.size)
    return g, float((2.0 * np.arange(g.size) + 2.0) @ terms / terms.sum())


_G_COEFFS, _HORNER_REL = _series_coefficients(1.0 / _SERIES_SWITCH ** 2)
#: Relative bound of eq. (6): Horner, z's 3u through zG'/G ≤ 0.03, b/√a, the two products, π/4.
_SERIES_REL = (_HORNER_REL + 6.0) * _U + 1e-3 * _U


def sqrt_positive_part_moment(p, q, a, b):
    """W(p, q, a, b) = ∫₀^π (p + q cos φ) √[a + b cos φ]₊ dφ (eq. 1) and an absolute bound on its
    rounding error, elementwise over the broadcast of the four arrays (b ≥ 0, else ValueError).

    Returns ``(value, bound)``; the bound is |p| e₀ + |q| e₁ + ε (|p W₀| + |q W₁|) with e₀, e₁ of
    :func:`sqrt_positive_part_moments`.  NaN in, NaN out.
    """
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    w0, w1, e0, e1 = sqrt_positive_part_moments(a, b)
    pw0, qw1 = p * w0, q * w1
    value = pw0 + qw1
    bound = np.abs(p) * e0 + np.abs(q) * e1 + _EPS * (np.abs(pw0) + np.abs(qw1))
    return value, bound


def sqrt_positive_part_moments(a, b):
    """(W₀, W₁, e₀, e₁): the two moments of eq. (1) and absolute bounds on their rounding errors,
    broadcast over ``a`` and ``b`` (b ≥ 0).  Zero below the horizon (a ≤ −b), eqs. (5a, 6) when
    the whole circle is lit (a ≥ b; (5b) instead of (6) for b ≤ a < 2b), eqs. (5c, 5d) for a cap."""
    a, b = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    if np.any(b < 0):
        raise ValueError("b must be non-negative")
    shape, a, b = a.shape, a.ravel(), b.ravel()
    out = np.zeros((4, a.size))
    lit = np.flatnonzero(a > -b)
    if lit.size:
        out[:, lit] = _lit_moments(a[lit], b[lit])
    out[:, np.isnan(a) | np.isnan(b)] = np.nan
    return tuple(row.reshape(shape) for row in out)


def _lit_moments(a, b):
    """Eqs. (5a–d, 6) for a > −b, b ≥ 0 (1-D arrays): rows W₀, W₁, e₀, e₁."""
    alpha = a + b
    full = a >= b
    s = np.where(full, a - b, b - a)              # β = a − b or γ = b − a, exact near a = b
    c = np.where(full, alpha, 2.0 * b)
    big, small = _scaled_rd_pair(s, c)
    w0 = 2.0 * alpha * np.where(full, big + small, big) / 3.0            # (5a), (5c)
    w1 = 2.0 * alpha * np.where(full, big - small, big + 2.0 * small) / 9.0   # (5b), (5d)
    e0 = (_RD_REL + 8.0 * _U) * w0
    e1 = np.where(full, (_RD_REL + 4.0 * _U) * 2.0 * alpha * (big + small) / 9.0 + 4.0 * _U * np.abs(w1),
                  (_RD_REL + 8.0 * _U) * w1)
    far = a >= _SERIES_SWITCH * b
    if np.any(far):
        w1[far], e1[far] = _far_moment(a[far], b[far])
    return w0, w1, e0, e1


def _scaled_rd_pair(s, c):
    """T(s, c) = s R_D(0, c, s) and t(s, c) = s R_D(0, s, c) of eq. (4), s ≥ 0, c > 0; their s → 0
    limits 3/√c and 0 where s ≤ 10⁻²⁰⁰ c (s = 0 at a touching circle)."""
    limit = s <= _LIMIT_RATIO * c
    s_safe = np.where(limit, c, s)
    big = np.where(limit, 3.0 / np.sqrt(c), s_safe * elliprd(0.0, c, s_safe))
    small = np.where(limit, 0.0, s_safe * elliprd(0.0, s_safe, c))
    return big, small


def _far_moment(a, b):
    """W₁ = (π b / 4√a) G((b/a)²) of eq. (6) for a ≥ 2b, and its rounding bound."""
    r = b / a
    z = r * r
    g = np.full_like(z, _G_COEFFS[-1])
    for coeff in _G_COEFFS[-2::-1]:         # Horner in place: the same roundings, no temporaries
        g *= z
        g += coeff
    w1 = (b / np.sqrt(a)) * g * (np.pi / 4.0)
    return w1, _SERIES_REL * w1
