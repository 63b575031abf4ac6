"""Independent truths for the Smith-masked models: their BRDFs written again from the papers (scalar,
``math`` only, nothing of ``brdfs``) and integrated by nested ``scipy.integrate.quad`` over (θ_V, φ_V).

Used by ``test_polar_route.py`` (a few cells) and ``benchmarks/bench_polar_honesty.py`` (≥ 20 cells
per family).  The inner φ-integral gets breakpoints graded toward the mirror azimuth φ = π, the outer
θ_V-integral the mirror angle θ_L and θ_L ± k · 2 arctan α; the truth's error is the outer quad's
estimate plus the outer range times the largest inner estimate.
"""
from __future__ import annotations

import math

from scipy.integrate import quad


def _half_vector(theta_l, theta_v, phi):
    """(cos δ, tan²δ) of H ∝ L + V, L = (sin θ_L, 0, cos θ_L), V at (θ_V, φ)."""
    hx = math.sin(theta_l) + math.sin(theta_v) * math.cos(phi)
    hy = math.sin(theta_v) * math.sin(phi)
    hz = math.cos(theta_l) + math.cos(theta_v)
    tan2 = (hx * hx + hy * hy) / (hz * hz)
    return 1.0 / math.sqrt(1.0 + tan2), tan2


def ggx_d(alpha, cos_d, tan2):
    """Walter et al. 2007, eq. 33."""
    return alpha ** 2 / (math.pi * cos_d ** 4 * (alpha ** 2 + tan2) ** 2)


def beckmann_d(alpha, cos_d, tan2):
    """Walter et al. 2007, eq. 25."""
    return math.exp(-tan2 / alpha ** 2) / (math.pi * alpha ** 2 * cos_d ** 4)


def ggx_lambda(alpha, mu):
    """Walter et al. 2007 / Heitz 2014: (−1 + √(1 + α² tan²θ))/2."""
    if mu >= 1.0:
        return 0.0
    tan2 = (1.0 - mu * mu) / (mu * mu)
    return 0.5 * (math.sqrt(1.0 + alpha ** 2 * tan2) - 1.0)


def beckmann_lambda(alpha, mu):
    """Heitz 2014, eq. 72: (erf(a) − 1)/2 + e^(−a²)/(2a√π), a = 1/(α tan θ)."""
    if mu >= 1.0:
        return 0.0
    a = mu / (alpha * math.sqrt(1.0 - mu * mu))
    return 0.5 * (math.erf(a) - 1.0) + math.exp(-a * a) / (2.0 * a * math.sqrt(math.pi))


def smith_brdf(d, lam, g2):
    """f = D G2 / (4 μ_L μ_V), G2 height-correlated 1/(1 + Λ_L + Λ_V) or separable."""
    def f(alpha, theta_l, theta_v, phi):
        cos_d, tan2 = _half_vector(theta_l, theta_v, phi)
        mu_l, mu_v = math.cos(theta_l), math.cos(theta_v)
        ll, lv = lam(alpha, mu_l), lam(alpha, mu_v)
        g = 1.0 / (1.0 + ll + lv) if g2 == "height_correlated" else 1.0 / ((1.0 + ll) * (1.0 + lv))
        return d(alpha, cos_d, tan2) * g / (4.0 * mu_l * mu_v)
    return f


def thesis_smith_g(m, x):
    """G* of eq. 1.38: h = x²/(2m²(1 − x²)), g = √(πh)(2 − erfc √h), G* = g/(g + 1)."""
    if x >= 1.0:
        return 1.0
    h = x * x / (2.0 * m * m * (1.0 - x * x))
    g = math.sqrt(math.pi * h) * (2.0 - math.erfc(math.sqrt(h)))
    return g / (g + 1.0)


def cook_torrance_smith(m, theta_l, theta_v, phi):
    """Eq. 2.9 with F = 1 and G = G*(N·L) G*(N·V) (eq. 1.38)."""
    cos_d, tan2 = _half_vector(theta_l, theta_v, phi)
    mu_l, mu_v = math.cos(theta_l), math.cos(theta_v)
    d = math.exp(-tan2 / m ** 2) / (4.0 * math.pi * m ** 2 * cos_d ** 4)
    return d * thesis_smith_g(m, mu_l) * thesis_smith_g(m, mu_v) / (mu_l * mu_v)


#: family -> (BRDF(α, θ_L, θ_V, φ), the brdfs model name and parameters for a given α)
FAMILIES = {
    "ggx": (smith_brdf(ggx_d, ggx_lambda, "height_correlated"), lambda a: ("ggx", {"alpha": a})),
    "ggx_separable": (smith_brdf(ggx_d, ggx_lambda, "separable"), lambda a: ("ggx", {"alpha": a, "G2": "separable"})),
    "beckmann": (smith_brdf(beckmann_d, beckmann_lambda, "height_correlated"), lambda a: ("beckmann", {"alpha": a})),
    "cook_torrance_smith": (cook_torrance_smith, lambda a: ("cook_torrance", {"m": a, "G": "smith"})),
}


def nested_quad_albedo(brdf, alpha, theta_deg, epsrel=1e-12):
    """(a, error) of a(θ_L) = 2 ∫₀^{π/2} ∫₀^π f cos θ_V sin θ_V dφ dθ_V by nested quad."""
    theta_l = math.radians(theta_deg)
    width = 2.0 * math.atan(alpha)
    inner_errors = []

    def inner(theta_v):
        pts = sorted({math.pi - w for w in (1.0, 0.3, 0.1, 0.03, 0.01, 0.003, 1e-3, 3e-4, 1e-4) if w < math.pi})
        val, err = quad(lambda p: brdf(alpha, theta_l, theta_v, p), 0.0, math.pi, points=pts,
                        epsabs=0.0, epsrel=epsrel, limit=400)
        inner_errors.append(err * 2.0 * math.cos(theta_v) * math.sin(theta_v))
        return 2.0 * val * math.cos(theta_v) * math.sin(theta_v)

    pts = sorted({p for p in [theta_l] + [theta_l + s * k * width for k in (0.1, 0.25, 0.5, 1, 2, 4) for s in (-1, 1)]
                  if 0.0 < p < 0.5 * math.pi})
    val, err = quad(inner, 0.0, 0.5 * math.pi, points=pts or None, epsabs=0.0, epsrel=epsrel, limit=400)
    return val, err + 0.5 * math.pi * max(inner_errors)


def cook_torrance_smith_normal_incidence(m, epsrel=1e-13):
    """(a, error) of Cook–Torrance with Smith's G at θ_L = 0 (eq. 2.9, F = 1, C = 1, eq. 1.38): with L = N,
    δ = θ_V/2 and G*(N·L) = 1, a(0) = (1/(2m²)) ∫₀^{π/2} e^(−tan²δ/m²)/cos⁴δ G*(cos θ_V) sin θ_V dθ_V, by quad
    cut where G* turns (cot θ_V = a m, a = 4^k) and G* written with h = cot²θ_V/(2m²), exact next to the
    pole where 1 − cos²θ_V would cancel."""
    def integrand(t):
        if t <= 0.0:
            return 0.0
        delta = 0.5 * t
        h = (math.cos(t) / math.sin(t)) ** 2 / (2.0 * m * m)
        g = math.sqrt(math.pi * h) * (2.0 - math.erfc(math.sqrt(h)))
        return math.exp(-math.tan(delta) ** 2 / m ** 2) / math.cos(delta) ** 4 * g / (g + 1.0) * math.sin(t)

    cuts = sorted({math.atan(1.0 / (4.0 ** k * m)) for k in range(-12, 5)} | {0.0, 0.5 * math.pi})
    total, error = 0.0, 0.0
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        value, err = quad(integrand, lo, hi, epsabs=0.0, epsrel=epsrel, limit=200)
        total, error = total + value, error + err
    scale = 1.0 / (2.0 * m * m)
    return scale * total, scale * error + 4 * 2.0 ** -52 * scale * total
