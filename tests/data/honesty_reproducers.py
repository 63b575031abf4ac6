"""Truths of the honesty reproducers (issue 24), by a route that imports nothing from brdfs.

``tests/numerics/test_honesty_families.py`` and ``tests/numerics/test_disk_honesty.py`` hold these
numbers as literals; this script recomputes them (``python tests/data/honesty_reproducers.py``,
about a minute on one core).  The BRDFs are written here again from the thesis's equations, and the
integrals are nested ``scipy.integrate.quad`` calls with every kink as a breakpoint (epsrel 1e-14,
limit 500, epsabs 1e-300), or closed forms evaluated by mpmath at 50 digits:

* basic patch model (eq. 4.8): the lens area of two circles, arccos form, in mpmath;
* Cook–Torrance (eq. 2.9 with G of eq. 2.10, Smith's G* of eq. 1.38, or G = 1): half-vector
  coordinates, outer variable s = tan²δ/m² (the Beckmann weight becomes e^(−s)), inner azimuth of H
  split where N·V = 0, N·V = N·L and the three terms of eq. 2.10 meet (all linear in cos φ), outer
  split where those levels reach φ = 0 or π (roots by brentq on a dense scan) and, for Smith's G,
  at the circle through N;
* the new model phong_cosmin (eq. 3.10): mirror coordinates, outer variable α (angle to R), inner φ
  split at N·V = 0 and N·V = N·L, outer split at α = 2θ, π/2 − θ and at multiples of 1/√n.
"""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import erfc

EPSREL = 1e-14
LIMIT = 500


def _quad(fn, a, b, points=(), epsabs=1e-300):
    pts = sorted(p for p in set(points) if a < p < b)
    edges = [a, *pts, b]
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        total += quad(fn, lo, hi, epsabs=epsabs, epsrel=EPSREL, limit=LIMIT)[0]
    return total


# --- basic patch model -----------------------------------------------------------------------------

def patch_basic_truth(theta_deg, R):
    """a_R(θ) = Area(C(L'_P, R) ∩ unit disk) / (π min(1, R²)) (eqs. 4.7–4.9), d = sin θ, in mpmath."""
    mp.mp.dps = 50
    d = mp.sin(mp.mpf(theta_deg) * mp.pi / 180)
    R = mp.mpf(R)
    if d <= abs(1 - R):
        area = mp.pi * min(R, 1) ** 2
    elif d >= 1 + R:
        area = mp.mpf(0)
    else:
        a = mp.acos((d * d + 1 - R * R) / (2 * d))
        b = mp.acos((d * d + R * R - 1) / (2 * d * R))
        area = a + R * R * b - mp.sqrt((-d + 1 + R) * (d + 1 - R) * (d - 1 + R) * (d + 1 + R)) / 2
    return float(area / (mp.pi * min(1, R * R)))


# --- Cook–Torrance in half-vector coordinates -------------------------------------------------------

def _g_star(x, m):
    """Smith's G* as eq. 1.38 prints it: h = x²/(2m²(1 − x²)), g = √(πh)(2 − erfc √h), G* = g/(g + 1)."""
    if x >= 1.0:
        return 1.0
    h = x * x / (2 * m * m * (1 - x * x))
    g = math.sqrt(math.pi * h) * (2 - erfc(math.sqrt(h)))
    return g / (g + 1)


class _HalfFrame:
    """H = (sin δ cos φ, sin δ sin φ, cos δ), L = (sin θ, 0, cos θ): L·H = a + b cos φ and
    N·V = 2 (L·H) cos δ − μ = c + e cos φ."""

    def __init__(self, theta_deg):
        th = math.radians(theta_deg)
        self.mu, self.st = math.cos(th), math.sin(th)

    def coefficients(self, delta):
        cd, sd = math.cos(delta), math.sin(delta)
        a, b = self.mu * cd, self.st * sd
        return cd, a, b, 2 * a * cd - self.mu, 2 * b * cd


def _levels_x(frame, delta, G):
    """cos φ of every kink on the circle of radius δ: N·V = 0, and for eq. 2.10 N·V = N·L,
    L·H = 2 N·H N·L and L·H = 2 N·H N·V."""
    cd, a, b, c, e = frame.coefficients(delta)
    out = [(-c / e) if e else np.nan]
    if G == "torrance_sparrow":
        mu = frame.mu
        out.append((mu - c) / e if e else np.nan)
        out.append((2 * cd * mu - a) / b if b else np.nan)
        den = 2 * cd * e - b               # 2 cd (c + e x) = a + b x
        out.append((a - 2 * cd * c) / den if den else np.nan)
    return out


def cook_torrance_truth(m, G, theta_deg):
    """a(θ) = ∫ f cos θ_V dω_V of f = e^(−tan²δ/m²)/(4π m² cos⁴δ) · G/(N·L N·V) (eq. 2.9).

    With dω_V = 4 (L·H) dω_H and s = tan²δ/m² the integrand is e^(−s) G (L·H) / (2π N·L cos δ) ds dφ,
    φ over [0, 2π] (twice [0, π])."""
    frame = _HalfFrame(theta_deg)
    mu = frame.mu
    delta_max = 0.5 * (0.5 * math.pi + math.radians(theta_deg))

    def geometry(cd, lh, nv):
        if G == "none":
            return 1.0
        if G == "smith":
            return _g_star(mu, m) * _g_star(nv, m)
        return min(1.0, 2 * cd * nv / lh, 2 * cd * mu / lh)

    def inner(s):
        delta = math.atan(m * math.sqrt(s))
        cd, a, b, c, e = frame.coefficients(delta)
        xs = _levels_x(frame, delta, G)
        x_h = xs[0]
        phi_h = math.pi if not (x_h > -1) else (0.0 if x_h >= 1 else math.acos(x_h))
        if phi_h == 0.0:
            return 0.0
        cuts = [math.acos(x) for x in xs[1:] if -1 < x < 1]
        if G == "smith":
            cuts += [phi_h * 10.0 ** -k for k in range(1, 8)]

        def g(phi):
            cp = math.cos(phi)
            lh, nv = a + b * cp, c + e * cp
            if nv <= 0 or lh <= 0:
                return 0.0
            return geometry(cd, lh, nv) * lh / (2 * math.pi * mu * cd)

        return 2 * _quad(g, 0.0, phi_h, cuts) * math.exp(-s)

    s_max = (math.tan(delta_max) / m) ** 2 if delta_max < 0.5 * math.pi else math.inf
    s_top = min(s_max, 750.0)
    points = _outer_kinks_ct(frame, G, delta_max, m, s_top)
    if G == "smith":
        s_n = (math.tan(0.5 * math.radians(theta_deg)) / m) ** 2
        points += [s_n * (1 + k) for k in (-1e-3, -1e-6, 0.0, 1e-6, 1e-3)]
    points += [k for k in (0.5, 1, 2, 4, 8, 16, 32, 64, 128, 256) if k < s_top]
    return _quad(inner, 0.0, s_top, points)


def _outer_kinks_ct(frame, G, delta_max, m, s_top):
    """s where a level of :func:`_levels_x` reaches cos φ = ±1 (the φ-integral has a kink there)."""
    deltas = np.concatenate([np.linspace(0, delta_max, 4001)[1:-1],
                             delta_max * (1 - np.geomspace(1e-12, 1e-1, 400))])
    deltas = np.unique(deltas)

    def gaps(d):
        return [x - 1 for x in _levels_x(frame, d, G)] + [x + 1 for x in _levels_x(frame, d, G)]

    vals = np.array([gaps(d) for d in deltas])
    out = []
    for j in range(vals.shape[1]):
        col = vals[:, j]
        for i in np.nonzero(np.isfinite(col[:-1]) & np.isfinite(col[1:]) & (np.sign(col[:-1]) != np.sign(col[1:])))[0]:
            root = brentq(lambda d: gaps(d)[j], deltas[i], deltas[i + 1], xtol=1e-300, rtol=1e-15)
            s = (math.tan(root) / m) ** 2
            if s < s_top:
                out.append(s)
    return out


# --- the new model (eq. 3.10) in mirror coordinates ------------------------------------------------

def phong_cosmin_truth(n, theta_deg, C=None):
    """a(θ) of f = C cos^n α / max(N·L, N·V), C = (n + 2)/(2π) (eq. 3.10), α the angle of V to R.

    V = cos α R + sin α (cos φ i + sin φ j): N·V = μ cos α + sin θ sin α cos φ, dω_V = sin α dα dφ."""
    C = (n + 2) / (2 * math.pi) if C is None else C
    th = math.radians(theta_deg)
    mu, st = math.cos(th), math.sin(th)
    alpha_max = 0.5 * math.pi + th

    def inner(alpha):
        ca, sa = math.cos(alpha), math.sin(alpha)
        A, B = mu * ca, st * sa
        x_h = -A / B if B else (-1.0 if A > 0 else 1.0)
        phi_h = math.pi if x_h <= -1 else (0.0 if x_h >= 1 else math.acos(x_h))
        if phi_h == 0.0:
            return 0.0
        x_k = (mu - A) / B if B else np.nan
        cuts = [math.acos(x_k)] if -1 < x_k < 1 else []

        def g(phi):
            nv = A + B * math.cos(phi)
            return nv / max(mu, nv) if nv > 0 else 0.0

        return 2 * _quad(g, 0.0, phi_h, cuts) * C * ca ** n * sa if ca > 0 else 0.0

    width = 1.0 / math.sqrt(max(n, 1.0))
    points = [2 * th, 0.5 * math.pi - th] + [width * k for k in (0.25, 0.5, 1, 2, 4, 8, 16)]
    return _quad(inner, 0.0, min(alpha_max, 0.5 * math.pi), points)


REPRODUCERS = {
    "patch_basic R=1 theta=1e-6": lambda: patch_basic_truth(1e-6, 1.0),
    "patch_basic R=1-1e-12 theta=1e-7": lambda: patch_basic_truth(1e-7, 1.0 - 1e-12),
    "cook_torrance smith m=0.1 theta=26.25": lambda: cook_torrance_truth(0.1, "smith", 26.25),
    "cook_torrance smith m=0.1 theta=26.20": lambda: cook_torrance_truth(0.1, "smith", 26.20),
    "cook_torrance smith m=1 theta=85.75": lambda: cook_torrance_truth(1.0, "smith", 85.75),
    "cook_torrance ts m=0.005 theta=90-1e-9": lambda: cook_torrance_truth(0.005, "torrance_sparrow", 90 - 1e-9),
    "cook_torrance none m=0.005 theta=87.745827": lambda: cook_torrance_truth(0.005, "none", 87.745827),
    "cook_torrance ts m=1 theta=85": lambda: cook_torrance_truth(1.0, "torrance_sparrow", 85.0),
    "phong_cosmin n=7.3 theta=90-1e-9": lambda: phong_cosmin_truth(7.3, 90 - 1e-9),
    "phong_cosmin n=1e4 theta=90-1e-9": lambda: phong_cosmin_truth(1e4, 90 - 1e-9),
    "phong_cosmin n=1 theta=67.5": lambda: phong_cosmin_truth(1.0, 67.5),
    "phong_cosmin n=1 theta=76": lambda: phong_cosmin_truth(1.0, 76.0),
    "phong_cosmin n=1e4 theta=1e-6": lambda: phong_cosmin_truth(1e4, 1e-6),
}




# --- 30-digit 1-D reductions (mpmath) for the hardest cells ---------------------------------------
# Where G·(L·H) and N·V / max(N·L, N·V) are piecewise linear in cos φ, the inner φ-integral is
# closed-form on each piece: ∫ (p + q cos φ) dφ = p φ + q sin φ.  Only the outer integral remains.

def _piecewise_linear_phi(terms, x_h, extra_x):
    """∫₀^φ_h min_k (p_k + q_k cos φ) dφ, φ_h = arccos x_h, split at the crossings ``extra_x``."""
    phi_h = mp.pi if x_h <= -1 else (mp.mpf(0) if x_h >= 1 else mp.acos(x_h))
    cuts = sorted({mp.mpf(0), phi_h, *[mp.acos(x) for x in extra_x if -1 < x < 1 and mp.acos(x) < phi_h]})
    total = mp.mpf(0)
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        mid = mp.cos((lo + hi) / 2)
        p, q = min(terms, key=lambda pq: pq[0] + pq[1] * mid)
        total += p * (hi - lo) + q * (mp.sin(hi) - mp.sin(lo))
    return total


def cook_torrance_truth_mp(m, G, theta_deg, dps=30):
    """:func:`cook_torrance_truth` for G of eq. 2.10 or G = 1 at ``dps`` digits: G·(L·H) is
    min(L·H, 2 cos δ N·V, 2 cos δ N·L) (eq. 2.10) or L·H, linear in cos φ on each piece."""
    mp.mp.dps = dps
    m = mp.mpf(m)
    th = mp.mpf(theta_deg) * mp.pi / 180
    mu, st = mp.cos(th), mp.sin(th)
    delta_max = (mp.pi / 2 + th) / 2

    def inner(s):
        delta = mp.atan(m * mp.sqrt(s))
        cd, sd = mp.cos(delta), mp.sin(delta)
        a, b = mu * cd, st * sd
        c, e = 2 * a * cd - mu, 2 * b * cd
        x_h = -c / e if e else mp.mpf(-2)
        terms = [(a, b)]
        if G == "torrance_sparrow":
            terms += [(2 * cd * c, 2 * cd * e), (2 * cd * mu, mp.mpf(0))]
        crossings = []
        for i in range(len(terms)):
            for j in range(i + 1, len(terms)):
                dq = terms[i][1] - terms[j][1]
                if dq:
                    crossings.append((terms[j][0] - terms[i][0]) / dq)
        return 2 * _piecewise_linear_phi(terms, x_h, crossings) * mp.exp(-s) / (2 * mp.pi * mu * cd)

    s_max = (mp.tan(delta_max) / m) ** 2 if delta_max < mp.pi / 2 else mp.inf
    s_top = min(s_max, mp.mpf(200))
    points = [mp.mpf(p) for p in _outer_kinks_ct(_HalfFrame(float(theta_deg)), G, float(delta_max), float(m), float(s_top))]
    points = sorted({mp.mpf(0), *[p for p in points if 0 < p < s_top],
                     *[mp.mpf(k) for k in (0.5, 1, 2, 4, 8, 16, 32, 64, 128) if k < s_top], s_top})
    return float(mp.quad(inner, points))


def phong_cosmin_truth_mp(n, theta_deg, dps=30):
    """:func:`phong_cosmin_truth` at ``dps`` digits: N·V / max(N·L, N·V) is 1 where N·V > N·L and
    N·V / N·L below, linear in cos φ on each piece."""
    mp.mp.dps = dps
    n = mp.mpf(n)
    C = (n + 2) / (2 * mp.pi)
    th = mp.mpf(theta_deg) * mp.pi / 180
    mu, st = mp.cos(th), mp.sin(th)

    def inner(alpha):
        ca, sa = mp.cos(alpha), mp.sin(alpha)
        A, B = mu * ca, st * sa
        x_h = -A / B if B else mp.mpf(-2)
        terms = [(mp.mpf(1), mp.mpf(0)), (A / mu, B / mu)]
        crossings = [(mu - A) / B] if B else []
        return 2 * _piecewise_linear_phi(terms, x_h, crossings) * C * ca ** n * sa

    width = 1 / mp.sqrt(max(n, 1))
    top = mp.pi / 2
    points = sorted({mp.mpf(0), top, *[p for p in (2 * th, mp.pi / 2 - th) if 0 < p < top],
                     *[width * k for k in (0.25, 0.5, 1, 2, 4, 8, 16) if width * k < top]})
    return float(mp.quad(inner, points))


def oren_nayar_truth_mp(rho, sigma, theta_deg, dps=50):
    """Qualitative Oren–Nayar (Oren & Nayar 1994, eq. 30): the azimuth integrates to
    ∫ max(0, cos Δφ) dΔφ = 2, so a = ρA + (2ρB/π)[sin θ (θ/2 − sin 2θ/4) + tan θ (1 − sin³θ)/3]
    (θ_V below θ: α = θ, β = θ_V; above: α = θ_V, β = θ), in mpmath at ``dps`` digits."""
    mp.mp.dps = dps
    s2 = mp.mpf(sigma) ** 2
    A, B = 1 - s2 / 2 / (s2 + mp.mpf("0.33")), mp.mpf("0.45") * s2 / (s2 + mp.mpf("0.09"))
    t = mp.mpf(theta_deg) * mp.pi / 180
    below = mp.sin(t) * (t / 2 - mp.sin(2 * t) / 4)
    above = mp.tan(t) * (1 - mp.sin(t) ** 3) / 3
    return float(mp.mpf(rho) * A + 2 * mp.mpf(rho) * B / mp.pi * (below + above))


def ggx_truth(alpha, theta_deg):
    """GGX with the height-correlated Smith G2 and F = 1 (Walter et al. 2007; Heitz 2014), by the
    sweep's third route (``sweep/third_route.py``, nested quadrature in the half-vector frame, and the
    BRDF rewritten in ``sweep/independent.py``; neither imports brdfs)."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from sweep import independent as ind
    from sweep.third_route import Integrand, hemisphere_albedo
    ks = tuple(np.geomspace(0.1, 1e4, 26))
    f = ind.smith_microfacet("ggx", alpha, "height_correlated")
    nv = lambda nl: tuple(k * alpha for k in (1 / 16, 1 / 4, 1.0, 4.0) if k * alpha < 1)
    return hemisphere_albedo(Integrand(f, "half", [float(np.arctan(alpha * k)) for k in ks], nv_levels=nv),
                             theta_deg).value


REPRODUCERS_MP = {
    "oren_nayar rho=0.988493 sigma=1.311723 theta=89.7": lambda: oren_nayar_truth_mp(0.988493, 1.311723, 89.7),
    "oren_nayar rho=0.988493 sigma=1.311723 theta=89.791779": lambda: oren_nayar_truth_mp(0.988493, 1.311723, 89.791779),
    "cook_torrance ts m=0.005 theta=90-1e-9": lambda: cook_torrance_truth_mp(0.005, "torrance_sparrow", 90 - 1e-9),
    "cook_torrance none m=0.005 theta=87.745827": lambda: cook_torrance_truth_mp(0.005, "none", 87.745827),
    "cook_torrance ts m=1 theta=85": lambda: cook_torrance_truth_mp(1.0, "torrance_sparrow", 85.0),
    "phong_cosmin n=7.3 theta=90-1e-9": lambda: phong_cosmin_truth_mp(7.3, 90 - 1e-9),
    "phong_cosmin n=1e4 theta=90-1e-9": lambda: phong_cosmin_truth_mp(1e4, 90 - 1e-9),
    "phong_cosmin n=1 theta=67.5": lambda: phong_cosmin_truth_mp(1.0, 67.5),
    "phong_cosmin n=1 theta=76": lambda: phong_cosmin_truth_mp(1.0, 76.0),
    "phong_cosmin n=1e4 theta=1e-6": lambda: phong_cosmin_truth_mp(1e4, 1e-6),
}


REPRODUCERS_THIRD_ROUTE = {
    "ggx height_correlated alpha=0.700492 theta=90-1e-7": lambda: ggx_truth(0.700492, 90 - 1e-7),
    "ggx height_correlated alpha=0.700492 theta=90-1e-8": lambda: ggx_truth(0.700492, 90 - 1e-8),
    "ggx height_correlated alpha=0.700492 theta=90-1e-9": lambda: ggx_truth(0.700492, 90 - 1e-9),
}


if __name__ == "__main__":
    for name, fn in REPRODUCERS_THIRD_ROUTE.items():
        print(f"sweep   {name:45s} {fn()!r}", flush=True)
    for name, fn in REPRODUCERS.items():
        print(f"quad    {name:45s} {fn()!r}", flush=True)
    for name, fn in REPRODUCERS_MP.items():
        print(f"mpmath  {name:45s} {fn()!r}", flush=True)
