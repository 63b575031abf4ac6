"""The patch models' albedos (chapter 4) as one-dimensional integrals at 40 digits (mpmath), for truths
sharp to the rounding of a double.

On the projected disk in polar coordinates (ρ, ψ) about V'_P = −L_P (cos θ_V dω_V = ρ dρ dψ, m = ρ):

* a radial ξ(m) (basic, exponential, generalized Lambertian, mixture):
  a(θ) = 2 ∫₀^π Φ(ρ_max(ψ)) dψ, Φ(r) = ∫₀^r ξ(ρ) ρ dρ in closed form (below);
* the elliptical patch (ξ = C inside the ellipse ρ ≤ ρ_e(ψ), eq. 4.34): the ellipse and the unit disk are
  convex and both hold the centre, so their intersection is star-shaped about it and
  a(θ) = C/2 ∫₀^{2π} min(ρ_e(ψ), ρ_max(ψ))² dψ;

with ρ_max(ψ) = s cos ψ + q = cos²θ/(q − s cos ψ), q = √(cos²θ + s² cos²ψ), s = sin θ (the second form where
cos ψ < 0: no cancellation at grazing incidence).  The outer integral (tanh-sinh, ``mpmath.quad``) is cut
where ρ_max meets a kink radius or ρ_e, graded toward ψ = π/2 (ρ_max's √ layer of width cos θ) and
toward ψ = π (the chord 1 − s).  θ is the cell's double, converted exactly.  The truth is the double nearest
the 40-digit value; its error is the quadrature's estimate plus that rounding.

Nothing here imports the package (the model's constant C, a double, is passed in: the truth is the
albedo of the BRDF as the package evaluates it).
"""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np

from sweep.third_route import Truth

DPS = 40


def _frame(theta_deg):
    t = mp.radians(mp.mpf(float(theta_deg)))
    return mp.sin(t), mp.cos(t)


def rho_max(s, cl, psi):
    c = mp.cos(psi)
    q = mp.sqrt(cl * cl + (s * c) ** 2)
    return s * c + q if c >= 0 else cl * cl / (q - s * c)


def _kink_angles(s, k):
    """ψ in (0, π) where ρ_max(ψ) = k: cos ψ = (s² + k² − 1)/(2 s k)."""
    if s == 0 or k <= 0:
        return []
    c = (s * s + k * k - 1) / (2 * s * k)
    return [mp.acos(c)] if -1 < c < 1 else []


def _graded(s, cl, top):
    pts = []
    for centre in ((mp.pi / 2,) if top == 1 else (mp.pi / 2, 3 * mp.pi / 2)):
        if cl < 0.1:
            pts += [centre + sign * cl * mp.mpf(2) ** k for k in range(-8, 9) for sign in (-1, 1) if cl * 2 ** k < 0.5]
    if s > 0.5:
        w = mp.sqrt(2 * (1 - s)) if s < 1 else mp.mpf(0)
        for k in (0.25, 0.5, 1, 2, 4, 8, 16, 32, 64):
            if 0 < w * k < 1:
                pts.append(mp.pi - w * k)
                if top == 2:
                    pts.append(mp.pi + w * k)
    return pts


def _quad(f, points, lo, hi):
    pts = sorted({mp.mpf(lo), mp.mpf(hi), *[p for p in points if lo < p < hi]})
    return mp.quad(f, pts, error=True, maxdegree=10)


def _truth(value, err, route):
    v = float(value)
    return Truth(v, float(abs(mp.mpf(v) - value) + abs(err)), route, 0, [f"mp {mp.nstr(value, 25)}"])


def radial_albedo(phi, kinks, theta_deg) -> Truth:
    """a(θ) = 2 ∫₀^π Φ(ρ_max(ψ)) dψ for a radial ξ with ``phi`` = Φ (mpmath) and its kink radii."""
    with mp.workdps(DPS):
        s, cl = _frame(theta_deg)
        pts = [p for k in kinks for p in _kink_angles(s, mp.mpf(k))] + _graded(s, cl, 1)
        v, e = _quad(lambda psi: phi(rho_max(s, cl, psi)), pts, 0, mp.pi)
        return _truth(2 * v, 2 * e, "mp_1d/disk+independent")


def basic_phi(R, C):
    """Φ(r) = C min(r, R)²/2 (ξ = C for m ≤ R, eq. 4.1)."""
    R, C = mp.mpf(R), mp.mpf(C)
    return lambda r: C * min(r, R) ** 2 / 2


def exponential_phi(s_, C):
    """Φ(r) = C (1 − e^{−s r}(1 + s r))/s² (ξ = C e^{−s m})."""
    s_, C = mp.mpf(s_), mp.mpf(C)
    return lambda r: C * (1 - mp.exp(-s_ * r) * (1 + s_ * r)) / s_ ** 2


def generalized_lambert_phi(d, m_clip, C):
    """ξ = C min((1 − m²/4)^{−d/2}, ξ(m_clip)) (eqs. 4.58–4.59); with u = 1 − ρ²/4,
    Φ(r) = 2C (1 − u^{1−d/2})/(1 − d/2) for r ≤ m_clip, then + C ξ_cap (r² − m_clip²)/2."""
    d, mc, C = mp.mpf(d), mp.mpf(m_clip), mp.mpf(C)
    e = 1 - d / 2

    def inner(r):
        u = 1 - r * r / 4
        return 2 * C * (1 - u ** e) / e
    cap = (1 - mc * mc / 4) ** (-d / 2)
    return lambda r: inner(r) if r <= mc else inner(mc) + C * cap * (r * r - mc * mc) / 2


def mixture_phi(kind, p_diffuse):
    """Φ of :func:`sweep.independent.patch_mixture_xi` (times π): uniform: ξπ = 1/(2m) + p (m < 1),
    (2 − m)/2 + p (1 ≤ m ≤ 2); falling: ξπ = 1/m − 1 + ln(m)/2 + 1/4 + p (m < 1), (1 − m/2)² + p (m ≥ 1)."""
    p = mp.mpf(p_diffuse)
    if isinstance(kind, (list, tuple)):                # ["box", a, b]: ξπ = h (1/max(m, a) − 1/b) + p below b
        return _box_phi(mp.mpf(kind[1]), mp.mpf(kind[2]), p)
    if kind == "uniform":
        low = lambda r: r / 2
        high = lambda r: r * r / 2 - r ** 3 / 6
    else:
        low = lambda r: (r - r * r / 2 + r * r * mp.log(r) / 4) if r > 0 else mp.mpf(0)
        high = lambda r: r * r / 2 - r ** 3 / 3 + r ** 4 / 16

    def phi(r):
        r = min(r, mp.mpf(2))
        out = low(r) if r <= 1 else low(mp.mpf(1)) + high(r) - high(mp.mpf(1))
        return (out + p * r * r / 2) / mp.pi
    return phi


def _box_phi(a, b, p):
    """Φ (times π) of the box weight h = 1/(b − a) on [a, b] ⊂ (0, 1]: h (1/a − 1/b) r²/2 up to a, then
    + h ((r − a) − (r² − a²)/(2b)) up to b, constant beyond; plus p r²/2."""
    h = 1 / (b - a)

    def phi(r):
        r = min(r, mp.mpf(2))
        inner = h * (1 / a - 1 / b) * min(r, a) ** 2 / 2
        if r > a:
            top = min(r, b)
            inner += h * ((top - a) - (top * top - a * a) / (2 * b))
        return (inner + p * r * r / 2) / mp.pi
    return phi


def elliptical_albedo(b, ratio, u_angle_deg, C, theta_deg) -> Truth:
    """a(θ) = C/2 ∫₀^{2π} min(ρ_e, ρ_max)² dψ (module docstring), cut where ρ_e = ρ_max."""
    with mp.workdps(DPS):
        s, cl = _frame(theta_deg)
        b, ratio, C = mp.mpf(b), mp.mpf(ratio), mp.mpf(C)
        phi = mp.radians(mp.mpf(u_angle_deg))

        def rho_e(psi):
            cu = mp.cos(psi - phi)
            cv = mp.sin(psi - phi)
            return b / mp.sqrt((ratio * cu) ** 2 + cv * cv)

        def gap(psi):
            return rho_e(psi) - rho_max(s, cl, psi)
        grid = np.unique(np.concatenate([np.linspace(0, 2 * math.pi, 4001),
                                         [float(p) for p in _graded(s, cl, 2)]]))
        vals = [float(gap(mp.mpf(x))) for x in grid]
        roots = []
        for x0, x1, v0, v1 in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
            if v0 == 0:
                roots.append(mp.mpf(x0))
            elif v0 * v1 < 0:
                roots.append(mp.findroot(gap, (mp.mpf(x0), mp.mpf(x1)), solver="anderson"))
        pts = roots + _graded(s, cl, 2)
        v, e = _quad(lambda psi: min(rho_e(psi), rho_max(s, cl, psi)) ** 2, pts, 0, 2 * mp.pi)
        return _truth(C * v / 2, C * e / 2, "mp_1d/disk+independent")


def basic_lens_albedo(R, C, theta_deg) -> Truth:
    """The basic patch in closed form: C × the area of the lens of the unit disk and the disk of radius R
    about (−s, 0), A = acos((s² + 1 − R²)/(2s)) + R² acos((s² + R² − 1)/(2sR)) − ½√((−s+1+R)(s+1−R)(s−1+R)(s+1+R))
    (π min(1, R)² when one disk holds the other), at 40 digits."""
    with mp.workdps(DPS):
        s, _ = _frame(theta_deg)
        R, C = mp.mpf(R), mp.mpf(C)
        if s <= abs(1 - R):
            area = mp.pi * min(mp.mpf(1), R) ** 2
        elif s >= 1 + R:
            area = mp.mpf(0)
        else:
            area = (mp.acos((s * s + 1 - R * R) / (2 * s)) + R * R * mp.acos((s * s + R * R - 1) / (2 * s * R))
                    - mp.sqrt((-s + 1 + R) * (s + 1 - R) * (s - 1 + R) * (s + 1 + R)) / 2)
        return _truth(C * area, mp.mpf(10) ** (-DPS + 5), "closed_form_mp+independent")
