"""The albedo at grazing incidence: asymptotic laws (Sec. 2.2.1) and discretised readings (Secs. 3.7.2–3.7.3).

Asymptotic laws, μ = cos θ_L → 0 (derivations in the docstrings):

* Ward (eq. 2.8): a(μ) √μ → K_Ward, a one-dimensional integral (a confluent hypergeometric U);
  the albedo diverges like μ^(−1/2).
* Cook–Torrance (eq. 2.9) with G = 1: a(μ) μ → m / (2√π) exactly; diverges like 1/μ.
* Cook–Torrance with G as printed (eq. 2.10): G ≤ 2 N·H N·L / L·H bounds the albedo by 2 at
  every incidence, and a(90°) = 1: no divergence.
* Phong (eq. 2.6), the new model (eq. 3.10), corrected Ward (eq. 3.36): finite limits in closed
  form; Blinn, corrected Blinn and Cook–Torrance with Smith's G (eq. 1.38): finite limits
  evaluated as albedo integrals at θ = 90°.

Readings: the albedo as a program of 2001 could have computed it — a midpoint rule on a
(θ_V, φ_V) grid, or Monte Carlo with uniform, cosine or Beckmann half-vector sampling.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import beta, gamma

from brdfs.numerics.albedo import albedo
from brdfs.physics.geometry import light_direction
from brdfs.numerics.integrate.gauss_kronrod import Estimate, integrate
from brdfs.numerics.integrate.lobes import Beckmann
from brdfs.physics.models import BRDF
from brdfs.physics.models.microfacet import beckmann_exponential, g_smith_beckmann

_EPS = np.finfo(float).eps
#: u = v² beyond which exp(−u²) = exp(−v⁴) < 1e-35: the truncation of the 1-D integrals in v.
_V_MAX = 3.0

#: D·G/(N·L N·V) constants relative to eq. 2.9's 1/(4π m² cos⁴δ): the original Cook–Torrance
#: paper (D = 1/(π m² cos⁴δ), f = D G/(π N·L N·V)) and eqs. 1.35–1.36 as printed (D = π/(4 m² cos⁴δ)).
NORMALISATION_FACTORS = {"eq_2_9": 1.0, "cook_torrance_original": 4.0 / np.pi, "eq_1_36": np.pi ** 2}


def approach_angles(exponent_from, exponent_to, per_decade):
    """Incidence angles 90° − 10^(−x) for x from ``exponent_from`` to ``exponent_to``, ``per_decade`` a decade."""
    count = int(round((exponent_to - exponent_from) * per_decade)) + 1
    return 90.0 - 10.0 ** -np.linspace(exponent_from, exponent_to, count)


def incidence_grid(step_deg, exponent_from, exponent_to, per_decade):
    """A uniform grid on [0°, 90°) joined with :func:`approach_angles` (sorted, unique)."""
    uniform = np.arange(0.0, 90.0, step_deg)
    return np.unique(np.concatenate([uniform, approach_angles(exponent_from, exponent_to, per_decade)]))


@dataclass(frozen=True)
class Law:
    """a(θ) ~ constant · (cos θ_L)^(−exponent) as cos θ_L → 0; exponent 0 is a finite limit a(90°)."""

    exponent: float
    constant: Estimate
    derivation: str

    def __call__(self, mu):
        return self.constant.value * np.asarray(mu, float) ** -self.exponent


def _v_integral(fn):
    """∫₀^∞ fn(u) e^(−u²) du over u = v², v ∈ [0, 3], by the engine's Gauss–Kronrod driver."""
    def integrand(v, elem):
        u = v * v
        g = fn(u) * np.exp(-u * u) * 2 * v
        return g, g, None

    est = integrate(integrand, np.array([[0.0, 0.5, 1.0, 1.5, 2.0, _V_MAX]]), rtol=1e-13, atol=1e-300)
    tail = 1e-35 * abs(float(est.value[0]))  # e^(−81) relative, beyond v = 3
    return Estimate(float(est.value[0]), float(est.error[0]) + tail + 8 * _EPS * abs(float(est.value[0])))


def ward_constant(m, C=1.0):
    """K_Ward = lim √μ a(μ) for Ward (eq. 2.8).

    √μ a = ∫ C e^(−tan²δ/m²)/(4π m²) √(N·V) dω_V → (L horizontal, dω_V = 4 L·H dω_H,
    N·V = sin 2δ cos φ, L·H = sin δ cos φ):
    K = C/(π m²) · ∫cos^{3/2}φ dφ · ∫ e^(−tan²δ/m²) √(sin 2δ) sin²δ dδ
      = C/(π m²) · √π Γ(5/4)/Γ(7/4) · √2 m^{7/2} ∫₀^∞ u^{5/2} (1 + m²u²)^{−5/2} e^{−u²} du
      = C Γ(5/4) U(7/4, 1/4, 1/m²) / (√(2π) m²)   (tan δ = m u; the limit by dominated convergence).
    """
    inner = _v_integral(lambda u: u ** 2.5 * (1 + (m * u) ** 2) ** -2.5)
    scale = C / (np.pi * m * m) * np.sqrt(np.pi) * gamma(1.25) / gamma(1.75) * np.sqrt(2.0) * m ** 3.5
    return Estimate(scale * inner.value, scale * inner.error + 4 * _EPS * scale * inner.value)


def ward_cosmin_limit(m, C=1.0):
    """a(90°) of the corrected Ward (eq. 3.36): f = D/N·V at N·L = 0, so
    a = C/(4π m²) ∫ e^(−tan²δ/m²) 4 L·H dω_H = 2C/(π m²) ∫ e^(−tan²δ/m²) sin²δ dδ
      = 2C m/π ∫₀^∞ u² (1 + m²u²)^(−2) e^(−u²) du = C Γ(3/2) U(3/2, 1/2, 1/m²)/(π m²)."""
    inner = _v_integral(lambda u: u * u * (1 + (m * u) ** 2) ** -2.0)
    scale = 2 * C * m / np.pi
    return Estimate(scale * inner.value, scale * inner.error + 4 * _EPS * scale * inner.value)


@dataclass(frozen=True)
class SmithGrazingLimit(BRDF):
    """The integrand of lim a(θ_L), θ_L → 90°, of Cook–Torrance with Smith's G (eq. 1.38).

    G*(x) ~ √(π/2) x/m as x → 0, so G/(N·L N·V) → √(π/2)/m · G*(N·V)/N·V and
    a(90°) = ∫ f_lim cos θ_V dω_V with f_lim = D √(π/2) G*(N·V) / (4π m³ cos⁴δ N·V) at N·L = 0.
    """

    m: float
    C: float = 1.0
    name = "cook_torrance_smith_grazing_limit"

    @property
    def lobe(self):
        return Beckmann(self.m)

    def _eval(self, L, V, nl, nv):
        e, nh = beckmann_exponential(L, V, self.m)
        d = self.C * e / (4 * np.pi * self.m ** 2 * nh ** 4)
        return d * np.sqrt(np.pi / 2) / self.m * g_smith_beckmann(np.ones_like(nv), nv, self.m) / nv


def asymptotic_law(model, tol=None):
    """The law of a(θ_L) as cos θ_L → 0 for ``model`` (see the module docstring), or None."""
    name, p = model.name, model.params
    exact = lambda v: Estimate(float(v), 4 * _EPS * abs(float(v)))
    if name == "ward":
        return Law(0.5, ward_constant(p["m"], p["C"]), "K U(7/4,1/4,1/m^2) / sqrt(cos)")
    if name == "cook_torrance" and p["G"] == "none":
        return Law(1.0, exact(p["C"] * p["m"] / (2 * np.sqrt(np.pi))), "m/(2 sqrt(pi) cos)")
    if name == "cook_torrance" and p["G"] == "torrance_sparrow":
        return Law(0.0, exact(p["C"]), "a(90) = 1 (G of eq. 2.10 -> 2 NH NL/LH)")
    if name == "phong":
        return Law(0.0, exact(p["C"] * beta(1.5, (p["n"] + 1) / 2)), "a(90) = c B(3/2,(n+1)/2)")
    if name == "phong_cosmin":
        return Law(0.0, exact(p["C"] * np.pi / (p["n"] + 1)), "a(90) = c pi/(n+1)")
    if name == "ward_cosmin":
        return Law(0.0, ward_cosmin_limit(p["m"], p["C"]), "a(90) = U(3/2,1/2,1/m^2)/(pi m^2)")
    if name == "cook_torrance" and p["G"] == "smith":
        limit = albedo(SmithGrazingLimit(p["m"], p["C"]), 90.0, tol)
        return Law(0.0, Estimate(float(limit.value), float(limit.error)), "a(90) as the limit integral")
    limit = albedo(model, 90.0, tol)
    if np.isfinite(limit.value):
        return Law(0.0, Estimate(float(limit.value), float(limit.error)), "a(90) by the engine at 90 deg")
    return None


# --- readings: discretisations a program of the time could have used -------------------------


def grid_albedo(model, theta_deg, n_theta, n_phi):
    """Midpoint rule on n_θ × n_φ cells of (θ_V, φ_V): Σ f cos θ_V sin θ_V Δθ Δφ; with a rounding bound."""
    L = light_direction(theta_deg)
    d_theta, d_phi = 0.5 * np.pi / n_theta, 2 * np.pi / n_phi
    phi = (np.arange(n_phi) + 0.5) * d_phi
    total = bound = 0.0
    for tv in (np.arange(n_theta) + 0.5) * d_theta:
        V = np.stack([np.sin(tv) * np.cos(phi), np.sin(tv) * np.sin(phi), np.full_like(phi, np.cos(tv))], -1)
        row = model(L, V) * np.cos(tv) * np.sin(tv) * d_theta * d_phi
        total += row.sum()
        bound += np.abs(row).sum()
    return Estimate(total, 4 * _EPS * (np.log2(n_theta * n_phi) + 2) * bound)


def _sample(sampler, model, L, rng, n):
    """Directions V drawn by ``sampler`` and their weights f cos θ_V / p(V)."""
    u1, u2 = rng.random(n), rng.random(n)
    phi = 2 * np.pi * u2
    if sampler == "beckmann_half_vector":
        tan_d = model.m * np.sqrt(-np.log1p(-u1))                # Ward (1992): tan²δ = −m² ln(1 − u)
        cos_d = 1 / np.sqrt(1 + tan_d ** 2)
        H = np.stack([tan_d * cos_d * np.cos(phi), tan_d * cos_d * np.sin(phi), cos_d], -1)
        lh = H @ L
        V = 2 * lh[:, None] * H - L
        p_h = np.exp(-tan_d ** 2 / model.m ** 2) / (np.pi * model.m ** 2 * cos_d ** 3)
        with np.errstate(divide="ignore", invalid="ignore"):
            w = model(L, V) * V[:, 2] * 4 * lh / p_h
        return np.where((V[:, 2] > 0) & (lh > 0), w, 0.0)
    cos_v = u1 if sampler == "uniform" else np.sqrt(1 - u1)
    sin_v = np.sqrt((1 - cos_v) * (1 + cos_v))
    V = np.stack([sin_v * np.cos(phi), sin_v * np.sin(phi), cos_v], -1)
    density = 1 / (2 * np.pi) if sampler == "uniform" else cos_v / np.pi
    return model(L, V) * cos_v / density


def monte_carlo_albedo(model, theta_deg, sampler, n_samples, seed_sequence):
    """Monte Carlo albedo with ``n_samples`` drawn by ``sampler`` (``uniform``, ``cosine``,
    ``beckmann_half_vector``); returns (Estimate with a rounding bound, statistical standard error)."""
    rng = np.random.default_rng(seed_sequence)
    L = light_direction(theta_deg)
    w = np.concatenate([_sample(sampler, model, L, rng, k) for k in _chunks(n_samples)])
    mean = w.mean()
    stderr = w.std(ddof=1) / np.sqrt(w.size) if w.size > 1 else np.inf
    return Estimate(mean, 4 * _EPS * (np.log2(w.size) + 2) * np.abs(w).mean()), stderr


def _chunks(n, size=250_000):
    return [size] * (n // size) + ([n % size] if n % size else [])
