"""BRDFs written again, from the thesis's and the papers' formulas, without the package's code.

Each function ``f(L, V, nl, nv, geo)`` takes directions (…, 3) with N = (0, 0, 1) and, where the
third route knows them exactly, the frame's coordinates in ``geo`` (``cos_axis`` = R·V in the
mirror frame or N·H in the half frame, ``lh`` = L·H, ``tan2`` = tan²δ); without them it computes
them from L and V.  Nothing here imports the package; :mod:`sweep.cells` holds them to the
package's models at random directions (``pointwise_agreement``).

References: Phong-type models eqs. 2.5, 2.6, 3.5, 3.10, 3.12 (c = (n+2)/2π, eq. 3.6); Blinn-type
eqs. 1.34, 2.5, 3.34; Ward eqs. 2.8, 3.35, 3.36; Cook–Torrance eqs. 2.9, 2.10 and the thesis's
Smith G* (eq. 1.38); GGX and Beckmann with Smith's exact Λ (Walter et al. 2007, eqs. 25–27, 33–34;
Heitz 2014, eqs. 72, 86); patch models eqs. 4.1, 4.2, 4.7, 4.21, 4.32–4.36, 4.44, 4.58–4.59.
"""
from __future__ import annotations

import numpy as np
from scipy.special import erfc, erfcx


def _double(special, x):
    """A scipy special function (double precision only) of x, also when x is long double (the third
    route's extended mode: the function's rounding is then its ``f_rtol``)."""
    x = np.asarray(x)
    return special(x.astype(float)) if x.dtype == np.longdouble else special(x)


def _rv(L, V, geo):
    if geo and "cos_axis" in geo and "lh" not in geo:
        return geo["cos_axis"]
    R = np.stack([-L[..., 0], -L[..., 1], L[..., 2]], -1)
    return np.sum(R * V, -1)


def _half(L, V, geo):
    """(N·H, L·H, tan²δ)."""
    if geo and "lh" in geo:
        return geo["cos_axis"], geo["lh"], geo["tan2"]
    h = L + V
    norm = np.linalg.norm(h, axis=-1)
    nh = h[..., 2] / norm
    lh = np.sum(L * h, -1) / norm
    tan2 = (h[..., 0] ** 2 + h[..., 1] ** 2) / h[..., 2] ** 2
    return nh, lh, tan2


def _pos_pow(x, n):
    return np.where(x > 0, np.maximum(x, 0.0) ** n, 0.0)


# --- Phong and Blinn types ------------------------------------------------------------------

def phong(n, C=None, divide="none", p=1.0):
    """c (R·V)^n / d, d = 1, cos θ_L (original), max(N·L, N·V) (new model) or its p-th power."""
    C = (n + 2.0) / (2.0 * np.pi) if C is None else C

    def f(L, V, nl, nv, geo=None):
        lobe = C * _pos_pow(_rv(L, V, geo), n)
        return lobe / _divisor(divide, nl, nv, p)
    return f


def blinn(n, C=1.0, divide="none"):
    """C (N·H)^n / d."""
    def f(L, V, nl, nv, geo=None):
        nh, _, _ = _half(L, V, geo)
        return C * _pos_pow(nh, n) / _divisor(divide, nl, nv, 1.0)
    return f


def _divisor(divide, nl, nv, p):
    if divide == "none":
        return 1.0
    if divide == "nl":
        return nl
    return np.maximum(nl, nv) ** p


# --- Beckmann lobes: Ward, corrected Ward, Cook–Torrance ---------------------------------------

def ward(m, C=1.0, corrected=False):
    """C e^(−tan²δ/m²)/(4π m²) / √(N·L N·V) (eq. 2.8), or / max(N·L, N·V) (eq. 3.36)."""
    def f(L, V, nl, nv, geo=None):
        _, _, tan2 = _half(L, V, geo)
        lobe = C * np.exp(-tan2 / (m * m)) / (4.0 * np.pi * m * m)
        return lobe / (np.maximum(nl, nv) if corrected else np.sqrt(nl * nv))
    return f


def g_star(x, m):
    """The thesis's Smith term (eq. 1.38): h = x²/(2m²(1 − x²)), g = √(πh)(2 − erfc √h), G* = g/(g + 1)."""
    x = np.asarray(x, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        h = x * x / (2.0 * m * m * (1.0 - x) * (1.0 + x))
        g = np.sqrt(np.pi * h) * (2.0 - _double(erfc, np.sqrt(h)))
        out = g / (g + 1.0)
    return np.where(x >= 1.0, 1.0, out)


def cook_torrance(m, G="torrance_sparrow", C=1.0):
    """e^(−tan²δ/m²)/(4π m² cos⁴δ) · G/(N·L N·V) (eq. 2.9, F = 1), G of eq. 2.10, eq. 1.38 or 1."""
    def f(L, V, nl, nv, geo=None):
        nh, lh, tan2 = _half(L, V, geo)
        d = C * np.exp(-tan2 / (m * m)) / (4.0 * np.pi * m * m * nh ** 4)
        if G == "torrance_sparrow":
            g = np.minimum(1.0, np.minimum(2.0 * nh * nv / lh, 2.0 * nh * nl / lh))
        elif G == "smith":
            g = g_star(nl, m) * g_star(nv, m)
        else:
            g = 1.0
        return d * g / (nl * nv)
    return f


def torrance_sparrow_lh_levels(nl, cos_delta):
    """L·H where eq. 2.10's shadowing (L·H = 2 N·H N·L) and masking (L·H (4 N·H² − 1) = 2 N·H N·L,
    with N·V = 2 L·H N·H − N·L) terms reach 1."""
    cos_delta = np.asarray(cos_delta, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        masking = 2.0 * cos_delta * nl / (4.0 * cos_delta ** 2 - 1.0)
    return (2.0 * cos_delta * nl, np.where(4.0 * cos_delta ** 2 > 1.0, masking, np.inf))


# --- Smith microfacet models (GGX, Beckmann) ----------------------------------------------------

def fresnel_conductor(cos_t, ior_re, ior_im):
    """Unpolarised Fresnel reflectance of a complex index η = n + ik: (R_s + R_p)/2 with
    t = √(η² − sin²θ), R_s = |(cos θ − t)/(cos θ + t)|², R_p = |(η² cos θ − t)/(η² cos θ + t)|²."""
    c = np.asarray(cos_t, complex)
    eta = complex(ior_re, ior_im)
    t = np.sqrt(eta * eta - (1.0 - c * c))
    rs = np.abs((c - t) / (c + t)) ** 2
    rp = np.abs((eta * eta * c - t) / (eta * eta * c + t)) ** 2
    return 0.5 * (rs + rp)


def ggx_lambda(mu, a):
    """Λ = (√(1 + α² tan²θ) − 1)/2 (Walter et al. 2007)."""
    mu = np.asarray(mu, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = a * a * (1.0 - mu) * (1.0 + mu) / (mu * mu)
        return 0.5 * x / (1.0 + np.sqrt(1.0 + x))


def beckmann_lambda(mu, a):
    """Λ = (erf(c) − 1)/2 + e^(−c²)/(2c√π), c = 1/(α tan θ) (Walter et al. 2007, eq. 27 context)."""
    mu = np.asarray(mu, float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        c = mu / (a * np.sqrt((1.0 - mu) * (1.0 + mu)))
        lam = 0.5 * np.exp(-c * c) * (1.0 / (c * np.sqrt(np.pi)) - _double(erfcx, c))
    return np.where(mu >= 1.0, 0.0, lam)


def smith_microfacet(distribution, alpha, G2="height_correlated", ior_re=None, ior_im=0.0, multiple=None):
    """F D G2 / (4 N·L N·V); ``multiple(nl, nv)`` adds a multiple-scattering term (Kulla–Conty)."""
    lam = ggx_lambda if distribution == "ggx" else beckmann_lambda

    def D(nh, tan2):
        if distribution == "ggx":
            a2 = alpha * alpha
            return a2 / (np.pi * (a2 * nh * nh + (1.0 - nh) * (1.0 + nh)) ** 2)
        return np.exp(-tan2 / (alpha * alpha)) / (np.pi * alpha * alpha * nh ** 4)

    def f(L, V, nl, nv, geo=None):
        nh, lh, tan2 = _half(L, V, geo)
        ll, lv = lam(nl, alpha), lam(nv, alpha)
        g2 = 1.0 / (1.0 + ll + lv) if G2 == "height_correlated" else 1.0 / ((1.0 + ll) * (1.0 + lv))
        F = 1.0 if ior_re is None else fresnel_conductor(lh, ior_re, ior_im)
        out = F * D(nh, tan2) * g2 / (4.0 * nl * nv)
        if multiple is not None:
            out = out + multiple(nl, nv)
        return out
    return f


# --- Oren–Nayar (qualitative model, Oren & Nayar 1994, eq. 30) --------------------------------------

def oren_nayar(rho, sigma):
    """(ρ/π)(A + B max(0, cos(φ_L − φ_V)) sin α tan β) from the polar angles and azimuths of L and V."""
    s2 = sigma * sigma
    A, B = 1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)

    def f(L, V, nl=None, nv=None, geo=None):
        theta_l = np.arccos(np.clip(L[..., 2], -1.0, 1.0))
        theta_v = np.arccos(np.clip(V[..., 2], -1.0, 1.0))
        dphi = np.arctan2(L[..., 1], L[..., 0]) - np.arctan2(V[..., 1], V[..., 0])
        alpha, beta = np.maximum(theta_l, theta_v), np.minimum(theta_l, theta_v)
        return rho / np.pi * (A + B * np.maximum(0.0, np.cos(dphi)) * np.sin(alpha) * np.tan(beta))
    return f


def oren_nayar_albedo(rho, sigma, theta_deg):
    """a(θ) of :func:`oren_nayar` in closed form.  The azimuth gives ∫ max(0, cos Δφ) dΔφ = 2, so
    a = ρA + (2ρB/π) ∫₀^{π/2} sin α tan β cos θ_V sin θ_V dθ_V, split at θ_V = θ:
    below, sin θ ∫₀^θ sin²θ_V dθ_V = sin θ (θ/2 − sin 2θ/4); above, tan θ ∫_θ^{π/2} sin²θ_V cos θ_V dθ_V
    = tan θ (1 − sin³θ)/3 = sin θ cos θ (1 + s + s²)/(3(1 + s)), s = sin θ (1 − s = cos²θ/(1 + s): no
    cancellation at grazing, and the limit at 90° is 0)."""
    s2 = sigma * sigma
    A, B = 1.0 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)
    t = np.radians(theta_deg)
    s, c = np.sin(t), np.sin(np.radians(90.0 - theta_deg))
    below = s * (0.5 * t - 0.25 * np.sin(2.0 * t))
    above = s * c * (1.0 + s + s * s) / (3.0 * (1.0 + s))
    return float(rho * A + 2.0 * rho * B / np.pi * (below + above))


# --- patch models on the projected disk: ξ(m) with m = |L_xy + V_xy| ---------------------------

def basic_constant(R):
    """c(R) = 1/(π min(1, R²)) (eq. 4.7)."""
    return 1.0 / (np.pi * min(1.0, R * R))


def patch_basic_xi(R, C=None):
    C = basic_constant(R) if C is None else C
    return lambda m: np.where(m <= R, C, 0.0)


def patch_exponential_xi(s, C):
    return lambda m: C * np.exp(-s * m)


def generalized_lambert_xi(d, m_clip, C):
    """C min((1 − (m/2)²)^(−d/2), ξ(m_clip)) (eqs. 4.58, 4.59)."""
    cap = (1.0 - (m_clip / 2.0) ** 2) ** (-d / 2.0)

    def xi(m):
        with np.errstate(invalid="ignore", divide="ignore"):
            return C * np.minimum((1.0 - (m / 2.0) ** 2) ** (-d / 2.0), cap)
    return xi


def box_ends(kind):
    """(a, b) of a box weight p = 1/(b − a) on [a, b] ⊂ (0, 1] given as ``["box", a, b]``, else None."""
    if isinstance(kind, (list, tuple)) and len(kind) == 3 and kind[0] == "box":
        a, b = float(kind[1]), float(kind[2])
        if not 0.0 < a < b <= 1.0:
            raise ValueError(f"a box weight in (0, 1], got {kind!r}")
        return a, b
    return None


def box_weight(kind):
    """p(R) of ``["box", a, b]``: 1/(b − a) on [a, b], 0 elsewhere."""
    a, b = box_ends(kind)
    return lambda R: np.where((np.asarray(R, float) >= a) & (np.asarray(R, float) <= b), 1.0 / (b - a), 0.0)


def patch_mixture_xi(kind, p_diffuse=0.0):
    """ξ(m) = ∫_m² p(R) c(R) dR + p_Diffuse c(2) (eq. 4.21) in closed form, c(R) = 1/(π min(1, R²)),
    for p(R) = 1/2 ('uniform'), p(R) = 1 − R/2 ('falling') and a box ``["box", a, b]`` (h = 1/(b − a)):
    uniform: (1/m − 1)/2 + 1/2 (m < 1), (2 − m)/2 (m ≥ 1); falling: (1/m − 1) + ln(m)/2 + 1/4 (m < 1),
    (1 − m/2)² (m ≥ 1); box: h (1/max(m, a) − 1/b) (m < b), 0 (m ≥ b); all over π."""
    box = box_ends(kind)
    if box is not None:
        a, b = box

        def xi_box(m):
            m = np.asarray(m, float)
            return np.where(m < b, (1.0 / np.maximum(m, a) - 1.0 / b) / (b - a), 0.0) / np.pi + p_diffuse / np.pi
        return xi_box

    def xi(m):
        m = np.minimum(np.asarray(m, float), 2.0)
        small = np.minimum(m, 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            if kind == "uniform":
                inner = np.where(m < 1.0, 0.5 * (1.0 / small - 1.0) + 0.5, 0.5 * (2.0 - m))
            else:
                inner = np.where(m < 1.0, (1.0 / small - 1.0) + 0.5 * np.log(small) + 0.25, (1.0 - 0.5 * m) ** 2)
        return inner / np.pi + p_diffuse / np.pi
    return xi


def ellipse_radius(b, ratio, u_angle_deg):
    """ρ_e(ψ): the radius along (cos ψ, sin ψ) of the ellipse |(ratio z·u, z·v)| = b (eq. 4.34)."""
    phi = np.radians(u_angle_deg)

    def rho(psi):
        cu = np.cos(psi) * np.cos(phi) + np.sin(psi) * np.sin(phi)
        cv = -np.cos(psi) * np.sin(phi) + np.sin(psi) * np.cos(phi)
        return b / np.hypot(ratio * cu, cv)
    return rho


# --- He–Torrance (1991), written again from /work/shared/he_torrance.md ---------------------------

def he_shadowing(cos_t, sin_t, sigma0, tau):
    """S₁(θ) = (1 − ½ erfc c)/(1 + Λ), Λ = ½ (e^{−c²}/(√π c) − erfc c), c = τ cot θ/(2σ0) (eqs. 24–25
    with the exp(−c²) erratum); S₁(0) = 1."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        c = tau * cos_t / (2.0 * sigma0 * sin_t)
        ec = erfc(c)
        lam = 0.5 * (np.exp(-c * c) / (np.sqrt(np.pi) * c) - ec)
        out = (1.0 - 0.5 * ec) / (1.0 + lam)
    return np.where(sin_t == 0, 1.0, out)


def he_sigma(cos_i, sin_i, cos_r, sin_r, sigma0, tau):
    """Effective roughness σ = σ0/√(1 + x²), x e^{x²/2} = f0 = (K_i + K_r)/√(8π), K = tan θ erfc(τ cot θ/(2σ0))
    (eqs. 80–83), x by Newton on ln x + x²/2 = ln f0 (Westin's iteration, not the Lambert W closed form),
    from x = f0 (f0 ≤ 1) or √(2 ln f0)."""
    def k(c, s):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(s == 0, 0.0, s / c * erfc(tau * c / (2.0 * sigma0 * s)))
    f0 = (k(cos_i, sin_i) + k(cos_r, sin_r)) / np.sqrt(8.0 * np.pi)
    x = np.where(f0 <= 1.0, f0, np.sqrt(2.0 * np.log(np.maximum(f0, 1.0))))
    tiny = f0 < 1e-6                   # x = f0 − f0³/2 + …: x² = f0² − f0⁴ (relative error < 1e-18)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        lf0 = np.log(f0)
        for _ in range(60):
            step = (np.log(x) + 0.5 * x * x - lf0) / (1.0 / x + x)
            x = np.where(tiny | (f0 == 0), x, x - step)
    x2 = np.where(tiny, f0 * f0 * (1.0 - f0 * f0), x * x)
    return sigma0 / np.sqrt(1.0 + x2)


#: Relative truncation of the Kirchhoff series of :func:`he_series` (its tail bound is below this).
HE_SERIES_RTOL = 1e-17
_HE_BLOCK = 24


def he_series(g, h):
    """(T, tail) of T(g, h) = Σ_{m≥1} e^{−g} g^m/(m! m) e^{−h/m} (eq. 78), summed in log space in blocks
    until the tail bound t_M q/(1 − q), q = g/(M+1) e^{h/(M(M+1))} < 1 (the term ratio decreases in m),
    is below :data:`HE_SERIES_RTOL` of the partial sum (or below 1e-300)."""
    from scipy.special import gammaln
    g, h = np.broadcast_arrays(np.asarray(g, float), np.asarray(h, float))
    shape, g, h = g.shape, g.ravel().copy(), h.ravel().copy()
    total, tail = np.zeros(g.size), np.zeros(g.size)
    live = np.nonzero(g > 0)[0]
    with np.errstate(divide="ignore"):
        lg = np.log(g)
    start = 1
    while live.size:
        m = np.arange(start, start + _HE_BLOCK, dtype=float)
        const = gammaln(m + 1.0) + np.log(m)
        lt = lg[live, None] * m - g[live, None] - const - h[live, None] / m
        total[live] += np.exp(lt).sum(-1)
        M = m[-1]
        lq = lg[live] - np.log(M + 1.0) + h[live] / (M * (M + 1.0))
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            bound = np.where(lq < 0, np.exp(lt[:, -1] + lq) / -np.expm1(np.minimum(lq, -1e-300)), np.inf)
        tail[live] = bound
        done = (bound <= HE_SERIES_RTOL * total[live]) | (bound <= 1e-300)
        live = live[~done]
        start += _HE_BLOCK
    return total.reshape(shape), tail.reshape(shape)


def he_torrance_disk(sigma0, tau, lam, theta_deg):
    """f_dd of He–Torrance (F = 1) on the projected disk, polar about −L_xy, for incidence θ:
    ``xi(rho, psi, to_edge)`` with ρ = |L_xy + V_xy| (so h = (πτ/λ)² ρ² exactly) and ``to_edge`` = ρ_max(ψ) − ρ
    (so cos²θ_V = (ρ_max − ρ)(ρ + |ρ_min|) without the cancellation of 1 − |V_xy|² at the horizon);
    returns (f_dd, its series' truncation bound).

    f_dd = G S D / (π cos θ_i cos θ_r), G = (|v|²/v_z)², v_z = cos θ_i + cos θ_r, |v|² = ρ² + v_z²,
    S = S₁(θ_i) S₁(θ_r), D = π²τ²/(4λ²) T(g, h), g = (2πσ v_z/λ)², σ the effective roughness (eqs. 71–84)."""
    t = np.radians(theta_deg)
    cl, s = float(np.sin(np.radians(90.0 - theta_deg))), float(np.sin(t))
    s1_i = he_shadowing(np.array(cl), np.array(s), sigma0, tau)

    def xi(rho, psi, to_edge):
        cp = np.cos(psi)
        q = np.sqrt(cl * cl + (s * cp) ** 2)                    # √(1 − s² sin² ψ)
        with np.errstate(divide="ignore", invalid="ignore"):
            rho_max = np.where(cp >= 0, s * cp + q, cl * cl / (q - s * cp))
            rho_min = np.where(cp >= 0, cl * cl / (q + s * cp), q - s * cp)     # |ρ_min|
        cos_r = np.sqrt(np.maximum(to_edge, 0.0) * (rho + rho_min))
        x, y = -s + rho * cp, rho * np.sin(psi)
        sin_r = np.minimum(np.hypot(x, y), 1.0)
        vz = cl + cos_r
        sig = he_sigma(np.full(rho.shape, cl), np.full(rho.shape, s), cos_r, sin_r, sigma0, tau)
        g = (2.0 * np.pi * sig * vz / lam) ** 2
        h = (np.pi * tau / lam) ** 2 * rho * rho
        T, tail = he_series(g, h)
        with np.errstate(divide="ignore", invalid="ignore"):
            common = ((rho * rho + vz * vz) / vz) ** 2 * s1_i * he_shadowing(cos_r, sin_r, sigma0, tau) \
                * (np.pi * tau / (2.0 * lam)) ** 2 / (np.pi * cl * cos_r)
        ok = (cos_r > 0) & (cl > 0) & np.isfinite(common)
        return np.where(ok, common * T, 0.0), np.where(ok, common * tail, 0.0)
    return xi


def he_specular_albedo(sigma0, tau, lam, theta_deg):
    """ρ_s = e^{−g_s} S₁(θ)², g_s = (4π σ(θ, θ) cos θ/λ)² (eqs. 73–74, F = 1): the specular delta's albedo."""
    cl, s = np.sin(np.radians(90.0 - theta_deg)), np.sin(np.radians(theta_deg))
    cl, s = np.array(cl), np.array(s)
    sig = he_sigma(cl, s, cl, s, sigma0, tau)
    return float(np.exp(-(4.0 * np.pi * sig * cl / lam) ** 2) * he_shadowing(cl, s, sigma0, tau) ** 2)
