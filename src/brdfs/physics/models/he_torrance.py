"""He–Torrance–Sillion–Greenberg (1991) BRDF: directional-diffuse and specular terms.

The thesis does not list the model's formulas (Sec. 1.2.4: "its constituent formulae will not be
listed"); equation numbers below are those of the original paper [1]_, as restated in Westin's
reference code ``heBRDF`` and in ``bbm`` [2]_.  Lengths ``sigma0_um`` (rms height σ0),
``tau_um`` (autocorrelation length τ) and ``lambda_um`` (wavelength λ) are in micrometres.

    f = f_sp + f_dd (+ f_ud = 0 for the thesis's metals)                      (eq. 69)
    f_dd = F(cos β) G S D / (π cos θ_i cos θ_r)                               (eq. 71)
    f_sp = ρ_s δ(V − R) / cos θ_r,  ρ_s = F(cos θ_i) e^{−g_s} S₁(θ_i)²        (eqs. 70, 73, 74)

Known errata, handled here:

* Eq. 25 as printed lacks the factor exp(−c²) in Smith's Λ; it is included (Pacanowski–Holzschuch
  erratum, Westin's code).
* The exponent of D (eq. 78) uses the scattering vector in wave-vector units:
  h = (π τ / λ)² |L_xy + V_xy|² (Westin's reading; with unit vectors the albedo is 51 at 0°).
* G (eq. 76) is written in its reduced form (|L + V|² / (cos θ_i + cos θ_r))², identical to the printed
  polarisation-frame form but without its 0/0 at retro-reflection.
* F is the unpolarised *power* reflectance (not squared again), at the half angle β for f_dd and at θ_i
  for ρ_s.

What a model value means.  ``f(L, V)`` is the part of the BRDF that has a density: f_dd for
``term='dd'`` and ``term='total'``, zero for ``term='specular'``.  The specular term is a Dirac delta at the
mirror direction; it has no value at a point, only an albedo, ``ρ_s``, given in closed form by
:meth:`HeTorrance.delta_albedo` (zero for ``term='dd'``), which :func:`brdfs.numerics.albedo.albedo` adds to the
integral of the density.

The density's azimuthal integral in closed form.  With F ≡ 1 (no index given), every factor of f_dd but
G and D depends on the polar angles alone, and G and each term of D's series are a polynomial and a
Gaussian in 1 + cos φ: the series integrates over φ term by term in Kummer functions
(:func:`azimuthal_directional_diffuse`, declared as :meth:`HeTorrance.scattering_azimuth_kernel`), so the
albedo is a 1-D integral over θ_V (issue 41: 273–651 kernel values per albedo of the thesis's surface
at rtol 1e-10, against 17k–52k BRDF values integrated in two dimensions; ``benchmarks/bench_he_torrance.py``).

References
----------
.. [1] X. D. He, K. E. Torrance, F. X. Sillion, D. P. Greenberg, "A Comprehensive Physical Model for
   Light Reflection", Computer Graphics 25(4) (SIGGRAPH '91), 175–186.
.. [2] ``bsdfbenchmark/bbm``: ``include/bsdfmodel/he.h`` and the bug-fixed copy of S. Westin's
   ``heBRDF`` in ``unittest/he/bin/he_westin.cpp``.
"""
from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import erfc, gammaln

from brdfs.physics.distributions import kummer_half_integers
from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.core.estimate import Estimate
from brdfs.physics.lobes import ScatteringLobe
from brdfs.physics.models.base import BRDF, check_positive, linear_range, log_range, non_negative, positive, register
from brdfs.physics import sampling

TERMS = ("dd", "specular", "total")
#: Relative truncation error the series is summed to (far below the engine's 1e-10).
SERIES_RTOL = 1e-14
SERIES_BLOCK = 12
#: Bound of the relative rounding error of one closed-form evaluation (a few ulps times the largest
#: condition number met, that of exp(−h/m) with h ≤ (2πτ/λ)² ~ 400).
EVAL_RTOL = 1e-12
_EPS = np.finfo(float).eps


def shadowing(cos_t, sin_t, sigma0, tau):
    """Smith's shadowing S₁(θ) for a Gaussian surface (eqs. 24–25 with the exp(−c²) erratum).

    c = τ cot θ / (2σ0),  Λ = ½ (e^{−c²}/(√π c) − erfc c),  S₁ = (1 − ½ erfc c) / (1 + Λ);  S₁(0) = 1.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        c = tau * cos_t / (2.0 * sigma0 * sin_t)
        lam = 0.5 * (np.exp(-c * c) / (np.sqrt(np.pi) * c) - erfc(c))
        s1 = (1.0 - 0.5 * erfc(c)) / (1.0 + lam)
    return np.where(sin_t == 0, 1.0, np.where(cos_t == 0, 0.0, s1))


def effective_roughness(cos_i, sin_i, cos_r, sin_r, sigma0, tau):
    """σ = σ0 / √(1 + z0²/σ0²) (eqs. 80–83), with the fixed point of eq. 80 in closed form.

    K(θ) = tan θ erfc(τ cot θ / (2σ0)); with x = z0/σ0, eq. 80 reads x e^{x²/2} = f0,
    f0 = (K_i + K_r)/√(8π), so x² = W₀(f0²) (principal Lambert W).
    """
    def k(cos_t, sin_t):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(sin_t == 0, 0.0, sin_t / cos_t * erfc(tau * cos_t / (2.0 * sigma0 * sin_t)))

    f0 = (k(cos_i, sin_i) + k(cos_r, sin_r)) / np.sqrt(8.0 * np.pi)
    return sigma0 / np.sqrt(1.0 + lambert_w(f0 * f0))


def lambert_w(x):
    """Principal Lambert W of x ≥ 0 (+inf at +inf); below 1e-8 by its series x − x² + 3x³/2
    (relative error < 3e-24).

    Above, Winitzki's approximation W ≈ ℓ (1 − ln(1 + ℓ)/(2 + ℓ)), ℓ = ln(1 + x) (relative error
    < 2e-2 on (0, ∞)), refined by two steps of Fritsch, Shafer and Crowley's fourth-order iteration
    (z = ln(x/w) − w, q = 2(1 + w)(1 + w + 2z/3), w ← w (1 + z (q − z) / ((1 + w)(q − 2z)))):
    2e-2 → 2e-7 → rounding.  Real arithmetic, ten times cheaper than :func:`scipy.special.lambertw`
    (complex); within 4 ulps of it from 1e-8 to 1e300 (tested)."""
    x = np.asarray(x, float)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ell = np.log1p(x)
        w = ell * (1.0 - np.log1p(ell) / (2.0 + ell))
        for _ in range(2):
            z = np.log(x / w) - w
            q = 2.0 * (1.0 + w) * (1.0 + w + (2.0 / 3.0) * z)
            w = w * (1.0 + z * (q - z) / ((1.0 + w) * (q - 2.0 * z)))
        series = x * (1.0 - x * (1.0 - 1.5 * x))
    return np.where(x < 1e-8, series, np.where(x == np.inf, np.inf, w))


def kirchhoff_series(g, h, factor=None):
    """T(g, h) = Σ_{m≥1} e^{−g} g^m / (m! m) e^{−h/m} (eq. 78) and a rigorous bound of its truncation.

    Summed in log space, in blocks of :data:`SERIES_BLOCK` terms, each point until its tail is below
    :data:`SERIES_RTOL` of its partial sum.  The bound: the term ratio t_{m+1}/t_m = g m/(m+1)² e^{h/(m(m+1))}
    decreases in m, so with q = g/(M+1) e^{h/(M(M+1))} < 1 the terms beyond M sum to at most t_M q/(1 − q).
    (The fixed count M(g) = ⌈g + 12√g + 30⌉ of the specification is never exceeded for g ≤ 100, h ≤ 1000;
    tested.)  g = 0 gives T = 0.

    ``factor(m, rows)``, if given, multiplies the m-th term of the points ``rows`` (of the flattened
    broadcast shape) by a factor in [0, 1], shape (rows.size, m.size): the sum of
    :func:`azimuthal_directional_diffuse`.  The bound above stays a bound (it bounds the unfactored tail),
    and the sum still stops at :data:`SERIES_RTOL` of its own (factored) partial sum.

    Returns
    -------
    (T, tail) : arrays of the broadcast shape of g and h
    """
    g, h = np.broadcast_arrays(np.asarray(g, float), np.asarray(h, float))
    shape, g, h = g.shape, g.ravel(), h.ravel()
    with np.errstate(divide="ignore"):
        log_g = np.log(g)
    total, tail = np.zeros(g.size), np.zeros(g.size)
    # T(g, +inf) = 0 exactly; a NaN or an infinite g has no sum (NaN, tail +inf), and neither would end the loop
    undefined = np.isnan(h) | ~np.isfinite(g)
    total[undefined], tail[undefined] = np.nan, np.inf
    active, last = np.flatnonzero(~undefined & (h < np.inf)), 0
    if active.size == 0:
        return total.reshape(shape), tail.reshape(shape)
    lg, ga, ha = log_g[active], g[active], h[active]
    while True:
        m = np.arange(last + 1.0, last + SERIES_BLOCK + 1.0)
        log_t = np.multiply.outer(lg, m)          # m ln g − ln(m! m) − h/m − g, in place
        log_t -= np.multiply.outer(ha, 1.0 / m)
        log_t -= _log_factorial_times(last, m)
        log_t -= ga[:, None]
        log_last = log_t[:, -1].copy()
        terms = np.exp(log_t, out=log_t)
        if factor is not None:
            live = terms.any(axis=-1)           # blocks that underflow whole (m ≪ g) need no factor
            if live.any():
                terms[live] *= factor(m, active[live])
        total[active] += terms.sum(axis=-1)
        last = int(m[-1])
        log_q = lg - np.log(last + 1.0) + ha / (last * (last + 1.0))
        with np.errstate(over="ignore", divide="ignore"):
            bound = np.where(log_q < 0, np.exp(log_last + log_q) / -np.expm1(np.minimum(log_q, 0.0)), np.inf)
        tail[active] = bound
        going = ~((bound <= SERIES_RTOL * total[active]) | np.isnan(bound))
        if not going.any():
            return total.reshape(shape), tail.reshape(shape)
        active = active[going]
        lg, ga, ha = log_g[active], g[active], h[active]


#: ln(m! m) for m = 1 … 4096, the terms' constant part (:func:`kirchhoff_series`).
_LOG_FACTORIAL_TIMES = gammaln(np.arange(2.0, 4098.0)) + np.log(np.arange(1.0, 4097.0))


def _log_factorial_times(last, m):
    """ln(m! m) of the block ``m`` = last + 1, …: from the table while it lasts."""
    if last + m.size <= _LOG_FACTORIAL_TIMES.size:
        return _LOG_FACTORIAL_TIMES[last:last + m.size]
    return gammaln(m + 1.0) + np.log(m)


def specular_albedo(cos_i, sin_i, sigma0, tau, lam, fresnel):
    """ρ_s = F(cos θ_i) e^{−g_s} S₁(θ_i)², g_s = (4π σ(θ_i, θ_i) cos θ_i / λ)² (eqs. 73–74).

    The albedo contribution of the specular delta (its directional-hemispherical reflectance).
    """
    sigma = effective_roughness(cos_i, sin_i, cos_i, sin_i, sigma0, tau)
    g_s = (4.0 * np.pi * sigma * cos_i / lam) ** 2
    return fresnel(cos_i) * np.exp(-g_s) * shadowing(cos_i, sin_i, sigma0, tau) ** 2


def directional_diffuse(L, V, sigma0, tau, lam, fresnel):
    """f_dd = F(cos β) G S D / (π cos θ_i cos θ_r) (eq. 71) and the bound of the series' truncation.

    With v = L + V (dimensionless scattering vector, eq. 84): cos β = |v|/2, G = (|v|²/v_z)² (eq. 76),
    S = S₁(θ_i) S₁(θ_r) (eq. 24), g = (2πσ/λ)² v_z² (eq. 79), h = (πτ/λ)² v_xy² (eq. 78, wave-vector
    units) and D = π²τ²/(4λ²) T(g, h) (eq. 78).  Directions at the horizon give 0 (there σ → 0, T → 0).
    """
    cos_i, cos_r = L[..., 2], V[..., 2]
    sin_i, sin_r = np.hypot(L[..., 0], L[..., 1]), np.hypot(V[..., 0], V[..., 1])
    v_xy2 = (L[..., 0] + V[..., 0]) ** 2 + (L[..., 1] + V[..., 1]) ** 2
    v_z = cos_i + cos_r
    v2 = v_xy2 + v_z * v_z
    sigma = effective_roughness(cos_i, sin_i, cos_r, sin_r, sigma0, tau)
    g = (2.0 * np.pi * sigma * v_z / lam) ** 2
    h = (np.pi * tau / lam) ** 2 * v_xy2
    series, tail = kirchhoff_series(g, h)
    d_factor = (np.pi * tau / (2.0 * lam)) ** 2
    inside = (cos_i > 0) & (cos_r > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        geometry = (v2 / v_z) ** 2
        shadow = shadowing(cos_i, sin_i, sigma0, tau) * shadowing(cos_r, sin_r, sigma0, tau)
        common = np.where(inside, fresnel(np.sqrt(v2) / 2.0) * geometry * shadow * d_factor
                          / (np.pi * cos_i * cos_r), 0.0)
    return common * series, common * tail


#: Relative rounding of one value of :func:`azimuthal_directional_diffuse`, in ulps, beyond its exponent's:
#: the Kummer functions' own bound (≤ 244 ulps, 120 Horner steps), the positive sums over the three of
#: them and over m, σ (Lambert W, erfc) and the shadowing (a few ulps each).
AZIMUTHAL_ROUNDING_ULPS = 320.0


def azimuthal_directional_diffuse(mu_l, s_l, mu_v, s_v, sigma0, tau, lam):
    """∫₀^{2π} f_dd cos θ_V sin θ_V dφ (F ≡ 1) in closed form at polar angles (θ_L, θ_V), and a bound
    of its error (the series' truncation and the rounding): the albedo a_dd(θ_L) = ∫₀^{π/2} … dθ_V.

    With u = 1 + cos φ (φ the azimuth of V from L's plane's far side, so u = 0 at the mirror azimuth),
    d = sin θ_L − sin θ_V and b = 2 sin θ_L sin θ_V, the two φ-dependent parts of f_dd (eq. 71) are
    linear in u: |L + V|² = p + b u with p = v_z² + d² (v_z = cos θ_L + cos θ_V), and
    h = (πτ/λ)² |L_xy + V_xy|² = κ (d² + b u), κ = (πτ/λ)²; σ, g and S depend on θ_L, θ_V only.  So
    with G = (|L + V|²/v_z)² (eq. 76) and T = Σ_m w_m e^{−h/m} (eq. 78), w_m = e^{−g} g^m/(m! m),

        ∫₀^π G e^{−h/m} dφ = e^{−κd²/m} / v_z² ∫₀^π (p + b u)² e^{−(κb/m) u} dφ
                           = π e^{−κd²/m} / v_z² · [p² F₀ + 2pb F₁ + (3/2) b² F₂],

    F_k = ₁F₁(k + ½; k + 1; −2κb/m), from ∫₀^π u^k e^{−zu} dφ = 2^k B(k + ½, ½) ₁F₁(k + ½; k + 1; −2z)
    (the same integrals as the Beckmann distribution's ``azimuthal_integral``; every term positive, no
    cancellation).  Writing P = p² + 2pb + (3/2) b², the bracket over P is a factor in (0, 1] of each
    term of T(g, κd²) (:func:`kirchhoff_series` with ``factor``, whose truncation bound stays a bound):

        ∫₀^{2π} f_dd cos θ_V sin θ_V dφ = 2 sin θ_V S₁(θ_L) S₁(θ_V) (π²τ²/(4λ²)) P T̃ / (cos θ_L v_z²).

    F ≠ 1 (Fresnel at the half angle, which depends on φ) has no such form.  A direction on the horizon
    gives 0 (f_dd does, by the horizon convention).

    Returns
    -------
    (value, error) : arrays of the broadcast shape
    """
    mu_l, s_l, mu_v, s_v = np.broadcast_arrays(*(np.asarray(x, float) for x in (mu_l, s_l, mu_v, s_v)))
    v_z = mu_l + mu_v
    d = s_l - s_v
    p = v_z * v_z + d * d
    b = 2.0 * s_l * s_v
    big_p = p * p + 2.0 * p * b + 1.5 * b * b
    kappa = (np.pi * tau / lam) ** 2
    sigma = effective_roughness(mu_l, s_l, mu_v, s_v, sigma0, tau)
    g = (2.0 * np.pi * sigma * v_z / lam) ** 2
    h0 = kappa * d * d
    flat = [x.ravel() for x in (p, b, big_p)]

    def bracket(m, rows):
        pr, br, pp = (x[rows, None] for x in flat)
        x = np.multiply.outer(2.0 * kappa * br[:, 0], 1.0 / m)
        f0, f1, f2 = kummer_half_integers(x)[0]
        return (pr * pr * f0 + 2.0 * pr * br * f1 + 1.5 * br * br * f2) / pp

    series, tail = kirchhoff_series(g, h0, factor=bracket)
    inside = (mu_l > 0) & (mu_v > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(inside, 2.0 * s_v * shadowing(mu_l, s_l, sigma0, tau) * shadowing(mu_v, s_v, sigma0, tau)
                         * (np.pi * tau / (2.0 * lam)) ** 2 * big_p / (mu_l * v_z * v_z), 0.0)
    value = scale * series
    # exp(−h/m) carries (h/m) ulps of the rounding of h/m; the terms that matter have h/m ≲ 745
    rounding = (AZIMUTHAL_ROUNDING_ULPS + np.minimum(h0, 745.0)) * _EPS * np.abs(value)
    return value, scale * tail + rounding


def _no_density(mu_l, s_l, mu_v, s_v):
    """The azimuthal integral of term 'specular''s density, which is zero: (0, 0)."""
    zero = np.zeros(np.broadcast_shapes(*(np.shape(x) for x in (mu_l, s_l, mu_v, s_v))))
    return zero, zero


@register
@dataclass(frozen=True)
class HeTorrance(BRDF):
    """He–Torrance BRDF (eq. 69 without the uniform-diffuse term): ``term`` 'dd', 'specular' or 'total'.

    Parameters
    ----------
    sigma0_um, tau_um : float
        rms roughness σ0 and autocorrelation length τ [µm].
    lambda_um : float
        Wavelength λ [µm]; the thesis does not state it (0.55 by default, a choice).
    ior_re, ior_im : float or None
        Complex index n = ior_re + i ior_im of the metal; ``None`` (both) for F ≡ 1, as the
        thesis's albedo figures assume.
    term : str
        'dd' (directional diffuse, eq. 71), 'specular' (the mirror delta, eq. 70) or 'total'.

    Examples
    --------
    >>> from brdfs.physics.geometry import direction
    >>> f = HeTorrance(sigma0_um=0.1, tau_um=1.7)
    >>> round(float(f(direction(0.0), direction(0.0))), 5)
    7.31872
    """

    sigma0_um: float
    tau_um: float
    lambda_um: float = 0.55
    ior_re: float | None = None
    ior_im: float | None = None
    term: str = "total"
    name = "he_torrance"
    # --- what the model says about itself
    chapter = 3                  # Figure 3.3 and the albedo beside the new model (sec. 3.7)
    param_ranges = {"sigma0_um": positive(), "tau_um": positive(), "lambda_um": positive(),
                    "ior_re": positive(), "ior_im": non_negative()}
    param_choices = {"term": TERMS}
    #: the generic tests draw σ0 from 0.01 … 1 µm, τ from 0.5 … 10 µm, λ over the visible 0.38 … 0.78 µm,
    #: F = 1 (None) or n_re in 0.1 … 10 with k from 0 and 1e-3 … 10
    test_ranges = {"sigma0_um": log_range(1e-2, 1.0), "tau_um": log_range(0.5, 10.0),
                   "lambda_um": linear_range(0.38, 0.78), "ior_re": log_range(0.1, 10.0, none=True),
                   "ior_im": log_range(1e-3, 10.0, zero=True, none=True)}
    #: the thesis's surface (σ0 = 0.1 µm, τ = 1.7 µm); narrowest: τ = 4 µm (lobe width λ/(πτ))
    examples = {"typical": {"sigma0_um": 0.1, "tau_um": 1.7}, "narrowest": {"sigma0_um": 0.1, "tau_um": 4.0}}
    # conserves_energy = False: a physical-optics approximation, not constructed to keep a(θ) ≤ 1; with
    # F = 1 the thesis's surface (σ0 = 0.1 µm, τ = 1.7 µm) has a(80°) ≈ 1.04 (extra_he_torrance_albedo)
    conserves_energy = False
    accuracy_families = {"he_torrance_dd": ("tau_um", {"sigma0_um": 0.1, "term": "dd", "lambda_um": 0.55})}

    def __post_init__(self):
        for key in ("sigma0_um", "tau_um", "lambda_um"):
            check_positive(key, getattr(self, key))
        if self.term not in TERMS:
            raise ValueError(f"unknown He–Torrance term {self.term!r}; choose one of {TERMS}")
        if (self.ior_re is None) != (self.ior_im is None):
            raise ValueError(f"give both ior_re and ior_im or neither, got {self.ior_re!r}, {self.ior_im!r}")
        if self.ior_re is not None:
            check_positive("ior_re", self.ior_re)
            check_positive("ior_im", self.ior_im, allow_zero=True)

    def fresnel(self, cos_theta):
        """Unpolarised Fresnel reflectance (eq. 75), or 1 when no index is given."""
        if self.ior_re is None:
            return np.ones_like(np.asarray(cos_theta, float))
        return unpolarised_reflectance(cos_theta, self.ior_re, self.ior_im)

    @property
    def _lengths(self):
        return self.sigma0_um, self.tau_um, self.lambda_um

    def _eval(self, L, V, nl, nv):
        if self.term == "specular":
            return np.zeros(np.broadcast_shapes(nl.shape, nv.shape))
        return directional_diffuse(L, V, *self._lengths, self.fresnel)[0]

    def truncation_error(self, L, V):
        """Bound of the series' truncation error of ``f(L, V)`` (absolute, sr⁻¹)."""
        if self.term == "specular":
            return np.zeros(np.broadcast_shapes(L.shape, V.shape)[:-1])
        return directional_diffuse(np.asarray(L, float), np.asarray(V, float), *self._lengths, self.fresnel)[1]

    def scattering_azimuth_kernel(self):
        """The density's azimuthal integral in closed form (:func:`azimuthal_directional_diffuse`) where
        F ≡ 1 (no index given); None with a Fresnel term, whose half angle depends on the azimuth."""
        if self.ior_re is not None:
            return None
        if self.term == "specular":
            return _no_density
        return functools.partial(azimuthal_directional_diffuse, sigma0=self.sigma0_um, tau=self.tau_um,
                                 lam=self.lambda_um)

    def delta_albedo(self, theta_deg):
        """Albedo of the specular delta, ρ_s(θ_i) (eqs. 73–74): 0 for ``term='dd'``.

        Returns an :class:`Estimate` (rounding-level error, :data:`EVAL_RTOL`).
        """
        theta = np.asarray(theta_deg, float)
        if self.term == "dd":
            return Estimate(np.zeros(theta.shape), np.zeros(theta.shape))
        rho = specular_albedo(cos_incidence(theta), sin_incidence(theta), *self._lengths, self.fresnel)
        return Estimate(rho, EVAL_RTOL * rho)

    # --- sampling ---------------------------------------------------------------------------------
    #: ``"dd_mixture"`` (u of shape (…, 3)): no exact sampler of f_dd is known, so a proposal —
    #: with probability 1/2 (u₃ < 1/2) the cosine distribution, else a Gaussian on the base plane
    #: centred at −L_P (the specular direction's projection; f_dd is a sum of Gaussians in
    #: |L_P + V_P|, eq. 78) with the width of the dominant term, σ_p = λ/(πτ) √(max(g, 1)/2),
    #: g = (4π σ0 cos θ_L/λ)²; points outside the unit disk are rejected.  The pdf is the combined
    #: (one-sample MIS, balance) density cos θ_V (1/π + G(V_P))/2, positive wherever f_dd is, so
    #: the weights are bounded by 2π f_dd.  The Dirac specular term (``term='specular'``/``'total'``)
    #: is not sampled: ``sample`` draws the density part f(L, V) = f_dd only, and its estimator omits
    #: the specular albedo ρ_s = :meth:`delta_albedo` that a caller adds as a discrete term (as
    #: :func:`brdfs.numerics.albedo.albedo` does).
    strategies = ("dd_mixture", "cosine")
    chi2_cases = ({"sigma0_um": 0.1, "tau_um": 1.7}, {"sigma0_um": 0.18, "tau_um": 3.0})
    sample_dimensions = {"dd_mixture": 3}

    def _planar_width(self, L):
        g = (4.0 * np.pi * self.sigma0_um * L[..., 2] / self.lambda_um) ** 2
        return self.lambda_um / (np.pi * self.tau_um) * np.sqrt(np.maximum(g, 1.0) / 2.0)

    def _sample_direction(self, L, u, strategy):
        width = self._planar_width(L)
        radius = width * np.sqrt(-2.0 * np.log1p(-u[..., 0]))     # Box–Muller radius
        phi = 2.0 * np.pi * u[..., 1]
        gx, gy = -L[..., 0] + radius * np.cos(phi), -L[..., 1] + radius * np.sin(phi)
        cx, cy = sampling.uniform_in_circle(0.0, 0.0, 1.0, u[..., 0], u[..., 1])
        cosine = u[..., 2] < 0.5
        return sampling.disk_to_direction(np.where(cosine, cx, gx), np.where(cosine, cy, gy))

    def _pdf(self, L, V, strategy):
        width = self._planar_width(L)
        r2 = (L[..., 0] + V[..., 0]) ** 2 + (L[..., 1] + V[..., 1]) ** 2
        gauss = np.exp(-r2 / (2.0 * width * width)) / (2.0 * np.pi * width * width)
        return 0.5 * V[..., 2] * (1.0 / np.pi + gauss)

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        """A function of r = |L_xy + V_xy| of width λ/(πτ) (h = 1 for m = 1), with a horizon layer of N·V ~ 2σ0/τ."""
        return ScatteringLobe(self.lambda_um / (np.pi * self.tau_um), 2.0 * self.sigma0_um / self.tau_um)

    def scattering_radius_levels(self):
        """The radial scales of D, width × 2^k (:meth:`ScatteringLobe.radial_levels`): a sum of
        Gaussians in r = |L_xy + V_xy| (eq. 78), each changing fastest near its own scale."""
        return tuple(self.lobe.radial_levels())

    def mirror_albedo(self, theta_deg):
        """ρ_s(θ_i) of the surface's specular delta (eqs. 73–74), whichever ``term`` this model evaluates."""
        return dataclasses.replace(self, term="specular").delta_albedo(theta_deg)
