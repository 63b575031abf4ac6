"""Microfacet conductors of today's practice: GGX and Beckmann with Smith's masking-shadowing, and
Kulla–Conty's multiple-scattering compensation (the modern answer to the thesis's energy question).

Single scattering (Walter et al. 2007, eq. 20; RTR4 eq. 9.34)::

    f_ss(L, V) = F(L·H) D(H) G2(L, V) / (4 N·L N·V)

with Smith's G2 either ``separable``, G2 = G1(L) G1(V), or ``height_correlated``,
G2 = 1 / (1 + Λ(L) + Λ(V)) (Heitz 2014; RTR4 eq. 9.31), Λ exact for both distributions
(:mod:`brdfs.physics.distributions`).  Written with λ(μ) = Λ(μ) μ (finite at the horizon), the
quotient G2 / (4 N·L N·V) is 1 / (4 (μ_L μ_V + μ_V λ(μ_L) + μ_L λ(μ_V))) (height-correlated) or
1 / (4 (μ_L + λ(μ_L)) (μ_V + λ(μ_V))) (separable): no 0/0 at grazing angles.

Multiple scattering (Kulla & Conty 2017, "Revisiting physically based shading at Imageworks",
SIGGRAPH course, Sec. "Multiple scattering"; Kelemen & Szirmay-Kalos 2001)::

    f_ms(L, V) = F_ms (1 − E(μ_L)) (1 − E(μ_V)) / (π (1 − E_avg)),   E_avg = 2 ∫₀¹ E(μ) μ dμ,
    F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg)),                    F_avg = 2 ∫₀¹ F(μ) μ dμ,

E(μ) the single-scattering albedo of the same model with F = 1 (so F_ms = 1 for F = 1).  E is
computed here by the engine (:func:`brdfs.numerics.albedo.albedo`) and tabulated as a Chebyshev
interpolant with a measured error (:func:`brdfs.numerics.pumping.tabulate_albedo`), E_avg
integrated from the interpolant exactly; then ∫ f_ms μ_V dω_V = 1 − E_table(μ_L) and the
compensated albedo for F = 1 is E(μ_L) + 1 − E_table(μ_L) = 1 up to the table's error.
f_ms is symmetric in L and V by construction.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from brdfs.core.estimate import Estimate
from brdfs.physics.lobes import MicrofacetLobe
from brdfs.physics.distributions import GGX, Beckmann, half_vector_tan2
from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.models.base import BRDF, check_positive, exact

G2_FORMS = ("separable", "height_correlated")
COMPENSATIONS = ("none", "kulla_conty")

#: Accuracy of the E(μ) tables of the Kulla–Conty term: Chebyshev interpolation to 1e-6 relative
#: (checked at the midpoints between nodes) on engine values at 1e-7.
E_TABLE_RTOL = 1.0e-6
E_ENGINE_RTOL = 1.0e-7


def energy_table_edges(alpha, name="ggx"):
    """Pieces of [0, 1] in μ for the E table: E(μ) turns steeply, and not like a polynomial, on the
    scale μ ~ α toward μ = 0 (E(0) = 1 for the height-correlated G2; GGX's tails make E − E(0) fall
    off like a fractional power), so the GGX edges are α·10^-k (k = 1 … 4) and α/3, α, 3α, 10α (those
    inside (0, 1)): geometric toward 0.  Beckmann's E is smooth there (its tails are Gaussian): α/10, α,
    10α suffice (fewer engine calls for the same checked accuracy)."""
    factors = (1e-4, 1e-3, 1e-2, 0.1, 1 / 3, 1.0, 3.0, 10.0) if name == "ggx" else (0.1, 1.0, 10.0)
    inner = [k * alpha for k in factors if 0 < k * alpha < 1]
    return tuple([0.0, *inner, 1.0])


@dataclass(frozen=True)
class TangentCoordinate:
    """Radial coordinate t = tan δ / (α + tan δ) of the half vector, for :class:`MicrofacetLobe`.

    GGX's own CDF t = tan²δ/(α² + tan²δ) leaves 1 − t ~ α² cos²δ: near the horizon at small α it
    falls below 1e-8 and t carries only 1e-8 of relative precision there (the engine stalls at
    α = 0.01).  Here 1 − t = α/(α + tan δ) ~ α cos δ, and GGX's radial weight per unit t is the
    bounded 2t(1 − t)/((1 − t)² + t²)² (peak at t ~ 1/2, zero at both ends).

    >>> c = TangentCoordinate(0.1)
    >>> round(float(c.cdf(c.tan_of_cdf(0.3))), 14)
    0.3
    """

    alpha: float
    #: A rational function of t: a few ulps.
    rounding = 8.0

    def cdf(self, tan_delta):
        tan_delta = np.asarray(tan_delta, float)
        with np.errstate(invalid="ignore"):
            return np.where(np.isinf(tan_delta), 1.0, tan_delta / (self.alpha + tan_delta))

    def tan_of_cdf(self, t):
        t = np.asarray(t, float)
        with np.errstate(divide="ignore"):
            return self.alpha * t / (1.0 - t)

    def solid_angle_per_t(self, t, cos_delta):
        """sin δ dδ/dt = tan δ cos³δ · α/(1 − t)² = α² t cos³δ / (1 − t)³."""
        return self.alpha ** 2 * t * cos_delta ** 3 / (1.0 - t) ** 3


@dataclass(frozen=True)
class _SmithMicrofacet(BRDF):
    """f = F D G2 / (4 N·L N·V) (+ Kulla–Conty's f_ms); F = 1 unless ``ior_re`` is given."""

    alpha: float
    G2: str = "height_correlated"
    compensation: str = "none"
    ior_re: float | None = None
    ior_im: float = 0.0
    distribution_type: ClassVar[type] = GGX

    def __post_init__(self):
        check_positive("alpha", self.alpha)
        if self.G2 not in G2_FORMS:
            raise ValueError(f"G2 must be one of {G2_FORMS}, got {self.G2!r}")
        if self.compensation not in COMPENSATIONS:
            raise ValueError(f"compensation must be one of {COMPENSATIONS}, got {self.compensation!r}")
        if self.ior_re is not None:
            check_positive("ior_re", self.ior_re)
            check_positive("ior_im", self.ior_im, allow_zero=True)
        if self.compensation == "kulla_conty":
            self.energy_table()     # built (or fetched from the cache) now, not inside an integration

    # --- shape ---------------------------------------------------------------------------------
    @property
    def distribution(self):
        return self.distribution_type(self.alpha)

    @property
    def lobe(self):
        """Half-vector lobe coordinates: Beckmann's own CDF for the Beckmann single scattering; the
        tangent coordinate t = tan δ/(α + tan δ) (:class:`TangentCoordinate`) for GGX and for every
        compensated model (f_ms spreads over the whole hemisphere, and Beckmann's t = 1 − exp(−tan²δ/α²)
        rounds to 1 beyond tan δ ≈ 6α, where that part of the integrand would be lost)."""
        if self.name == "beckmann" and self.compensation == "none":
            return MicrofacetLobe(self.distribution)
        return MicrofacetLobe(TangentCoordinate(self.alpha))

    def nv_levels(self, nl):
        """No kinks, but a scale: λ(μ_V) = Λ μ_V turns on μ_V ~ α (√(μ² + α² (1 − μ²)) for GGX, whose
        branch points at μ_V = ±iα/√(1 − α²) sit next to the horizon for small α).  The levels α/16, α/4,
        α, 4α (those below 1) split the engine's fixed azimuthal rule there."""
        return tuple(k * self.alpha for k in (1 / 16, 1 / 4, 1.0, 4.0) if k * self.alpha < 1.0)

    # --- the BRDF ------------------------------------------------------------------------------
    def fresnel(self, cos_theta):
        """F(cos θ): 1 (``ior_re`` None) or the unpolarised conductor reflectance (eqs. 1.41–1.43)."""
        if self.ior_re is None:
            return np.ones_like(np.asarray(cos_theta, float))
        return unpolarised_reflectance(cos_theta, self.ior_re, self.ior_im)

    def g2_over_4_nl_nv(self, nl, nv):
        """G2 / (4 N·L N·V), finite at the horizon (module docstring)."""
        lam = self.distribution.smith_lambda_cos
        if self.G2 == "height_correlated":
            return 1.0 / (4.0 * (nl * nv + nv * lam(nl) + nl * lam(nv)))
        return 1.0 / (4.0 * (nl + lam(nl)) * (nv + lam(nv)))

    def masking_shadowing(self, nl, nv):
        """Smith's G2(L, V) (separable G1 G1 or height-correlated 1/(1 + Λ_L + Λ_V)); 0 at the horizon."""
        lam = self.distribution.smith_lambda
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.G2 == "height_correlated":
                return 1.0 / (1.0 + lam(nl) + lam(nv))
            return 1.0 / ((1.0 + lam(nl)) * (1.0 + lam(nv)))

    def single_scattering(self, L, V, nl, nv):
        """f_ss = F(L·H) D(H) G2 / (4 N·L N·V)."""
        tan2, cos_d = half_vector_tan2(L, V)
        d = self.distribution.D(cos_d)
        if self.ior_re is None:
            return d * self.g2_over_4_nl_nv(nl, nv)
        h = np.asarray(L, float) + np.asarray(V, float)
        cos_lh = np.sum(np.asarray(L, float) * h, axis=-1) / np.linalg.norm(h, axis=-1)
        return self.fresnel(cos_lh) * d * self.g2_over_4_nl_nv(nl, nv)

    def multiple_scattering(self, nl, nv):
        """Kulla–Conty f_ms(μ_L, μ_V) (module docstring); zero without compensation."""
        if self.compensation == "none":
            return np.zeros(np.broadcast_shapes(np.shape(nl), np.shape(nv)))
        table, e_avg = self.energy_table()
        return self.fresnel_ms() * (1.0 - table(nl)) * (1.0 - table(nv)) / (np.pi * (1.0 - e_avg.value))

    def multiple_scattering_error(self, nl, nv):
        """Bound on |f_ms − f_ms(exact E)| from the E table's error ε (E_L, E_V and E_avg each off by ≤ ε):
        F_ms ε ((1 − E_L) + (1 − E_V)) / (π (1 − E_avg)) + f_ms ε / (1 − E_avg) (F_ms's own dependence on
        E_avg neglected: it is 1 for F = 1)."""
        if self.compensation == "none":
            return np.zeros(np.broadcast_shapes(np.shape(nl), np.shape(nv)))
        table, e_avg = self.energy_table()
        eps, rest = table.error, 1.0 - e_avg.value
        first = self.fresnel_ms() * eps * ((1.0 - table(nl)) + (1.0 - table(nv))) / (np.pi * rest)
        return first + self.multiple_scattering(nl, nv) * eps / rest

    def _eval(self, L, V, nl, nv):
        f = self.single_scattering(L, V, nl, nv)
        if self.compensation == "kulla_conty":
            f = f + self.multiple_scattering(nl, nv)
        return f

    # --- the energy tables -------------------------------------------------------------------
    def energy_table(self):
        """(E table, E_avg) of the single-scattering model with F = 1 and this G2 (cached per α)."""
        return energy_table(self.name, float(self.alpha), self.G2)

    def fresnel_average(self):
        """F_avg = 2 ∫₀¹ F(μ) μ dμ (64-point Gauss–Legendre; F is smooth)."""
        if self.ior_re is None:
            return 1.0
        x, w = np.polynomial.legendre.leggauss(64)
        mu = 0.5 * (x + 1)
        return float(np.sum(w * self.fresnel(mu) * mu))

    def fresnel_ms(self):
        """F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg)) (Kulla & Conty 2017); 1 for F = 1."""
        if self.ior_re is None:
            return 1.0
        f_avg = self.fresnel_average()
        e_avg = self.energy_table()[1].value
        return f_avg ** 2 * e_avg / (1.0 - f_avg * (1.0 - e_avg))

    def table_error(self):
        """Absolute error bound of the E table (interpolation + engine); 0 without compensation."""
        return self.energy_table()[0].error if self.compensation == "kulla_conty" else 0.0

    # --- closed forms ------------------------------------------------------------------------
    def exact_albedo(self, theta_deg):
        """GGX, α = 1, F = 1, no compensation, θ = 0: E(1) = 1 − ln 2 (:func:`ggx_alpha1_normal_albedo`)."""
        theta = np.asarray(theta_deg, float)
        known = (self.name == "ggx" and self.alpha == 1.0 and self.ior_re is None
                 and self.compensation == "none")
        return np.where((theta == 0.0) & known, ggx_alpha1_normal_albedo().value, np.nan)

    # --- sampling (visible normals) ------------------------------------------------------------
    def _ms_probability(self, nl):
        """Probability of the cosine lobe in the mixture sampler: 1 − E(μ_L) with compensation, else 0."""
        if self.compensation == "none":
            return np.zeros(np.shape(nl))
        return np.clip(1.0 - self.energy_table()[0](nl), 0.0, 1.0)

    #: ``"visible_normals"``: V reflected about a visible normal (mixed with the cosine lobe with
    #: probability 1 − E(μ_L) when compensated); ``"cosine"``: the protocol's baseline.
    strategies = ("visible_normals", "cosine")

    def _pdf(self, L, V, strategy):
        """Density of the visible-normal sampler: D_L(H) / (4 L·H) (visible normals seen from L,
        reflected), mixed with cos θ_V / π with weight 1 − E(μ_L) when compensated."""
        L, V = np.asarray(L, float), np.asarray(V, float)
        h = L + V
        norm = np.linalg.norm(h, axis=-1, keepdims=True)
        with np.errstate(divide="ignore", invalid="ignore"):
            H = h / norm
            lh = np.sum(L * H, axis=-1)
            p_ss = self.distribution.visible_normal_pdf(L, H) / (4.0 * lh)
        p_ss = np.where((V[..., 2] > 0) & (lh > 0) & (norm[..., 0] > 0), p_ss, 0.0)
        p_ms = self._ms_probability(L[..., 2])
        return (1.0 - p_ms) * p_ss + p_ms * np.where(V[..., 2] > 0, V[..., 2] / np.pi, 0.0)

    def _sample_direction(self, L, u, strategy):
        """V = reflection of L about a visible normal H (Heitz 2018 / Heitz & d'Eon 2014); with
        compensation, a cosine-distributed V with probability 1 − E(μ_L) (u₀ reused by rescaling)."""
        L = np.asarray(L, float)
        u = np.asarray(u, float)
        shape = np.broadcast_shapes(L.shape[:-1], u.shape[:-1])
        L = np.broadcast_to(L, shape + (3,))
        u0, u1 = np.broadcast_to(u[..., 0], shape), np.broadcast_to(u[..., 1], shape)
        p_ms = np.broadcast_to(self._ms_probability(L[..., 2]), shape)
        cosine = u0 < p_ms
        with np.errstate(divide="ignore", invalid="ignore"):
            u_ss = np.where(cosine, 0.5, (u0 - p_ms) / (1.0 - p_ms))
            u_ms = np.where(cosine, u0 / p_ms, 0.5)
        H = self.distribution.sample_visible_normal(L, np.clip(u_ss, 0.0, 1.0), u1)
        V_ss = 2.0 * np.sum(L * H, axis=-1, keepdims=True) * H - L
        r, phi = np.sqrt(u_ms), 2.0 * np.pi * u1
        V_ms = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u_ms, 0.0))], -1)
        return np.where(cosine[..., None], V_ms, V_ss)


@dataclass(frozen=True)
class GGXMicrofacet(_SmithMicrofacet):
    """GGX (Trowbridge–Reitz) microfacet conductor with Smith's G2 (:class:`brdfs.physics.distributions.GGX`)."""

    name = "ggx"
    distribution_type = GGX


@dataclass(frozen=True)
class BeckmannMicrofacet(_SmithMicrofacet):
    """Beckmann microfacet conductor with Smith's G2 (:class:`brdfs.physics.distributions.Beckmann`)."""

    name = "beckmann"
    distribution_type = Beckmann


SMITH_MODELS = {cls.name: cls for cls in (GGXMicrofacet, BeckmannMicrofacet)}


#: E tables by (model name, α, G2): computed once per process, or read from the table artifact
#: ``extra_microfacet_albedo`` (:func:`seed_energy_tables`) so that the figures do not recompute them.
_ENERGY_TABLES: dict[tuple, tuple] = {}


def energy_table(name: str, alpha: float, G2: str):
    """The single-scattering albedo E(μ) (F = 1) of model ``name`` as a Chebyshev table in μ with its
    error bound, and E_avg = 2 ∫₀¹ E(μ) μ dμ integrated from the table exactly (Gauss–Legendre of
    degree above the interpolant's), its error 2 ∫ err μ dμ = the table's error bound.  Cached per
    (name, α, G2).

    Returns
    -------
    (AlbedoTable, Estimate)
    """
    from brdfs.numerics.pumping import tabulate_albedo

    key = (name, float(alpha), G2)
    if key not in _ENERGY_TABLES:
        single = SMITH_MODELS[name](alpha=alpha, G2=G2)
        table = tabulate_albedo(single, energy_table_edges(alpha, name), degree=4, target_rtol=E_TABLE_RTOL,
                                engine_rtol=E_ENGINE_RTOL)
        _ENERGY_TABLES[key] = (table, cosine_weighted_average(table))
    return _ENERGY_TABLES[key]


def energy_table_frame(name: str, alpha: float, G2: str):
    """The E table's nodes as tidy rows (``mu`` = node, ``albedo``, ``albedo_err`` = the table's bound,
    with ``piece, x_lo, x_hi, node``), for :func:`seed_energy_tables`."""
    table = energy_table(name, alpha, G2)[0]
    rows = table.to_frame().rename(columns={"cos_theta": "mu"}).drop(columns=["model_rtol"])
    return rows.assign(model=name, G2=G2, alpha=float(alpha))


def seed_energy_tables(frame) -> int:
    """Put the E tables stored by :func:`energy_table_frame` (rows with a ``piece``) into the cache;
    returns how many."""
    from brdfs.numerics.pumping import AlbedoTable

    nodes = frame.dropna(subset=["piece"])
    count = 0
    for (name, alpha, G2), g in nodes.groupby(["model", "alpha", "G2"]):
        table = AlbedoTable.from_frame(g.rename(columns={"mu": "cos_theta"}).assign(
            model_rtol=0.0, piece=g["piece"].astype(int), node=g["node"].astype(int)))
        _ENERGY_TABLES[(name, float(alpha), G2)] = (table, cosine_weighted_average(table))
        count += 1
    return count


def cosine_weighted_average(table) -> Estimate:
    """2 ∫₀¹ table(μ) μ dμ, exact for the piecewise polynomial (Gauss–Legendre, 2·(D+1) nodes a piece)."""
    degree = table.values.shape[1] - 1
    x, w = np.polynomial.legendre.leggauss(degree + 2)
    total = 0.0
    for lo, hi in zip(table.edges[:-1], table.edges[1:]):
        mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x
        total += 0.5 * (hi - lo) * np.sum(w * table(mu) * mu)
    return Estimate(2.0 * total, table.error + 64 * np.finfo(float).eps)


def ggx_alpha1_normal_albedo() -> Estimate:
    """E(μ = 1) of GGX with α = 1, F = 1: 1 − ln 2, for both G2 forms.

    With α = 1, D(H) = 1/π for every H above the horizon.  At L = N, Λ(L) = 0, so both G2 forms are
    G1(V) = 2 μ_V / (1 + μ_V) (Λ = (1/μ − 1)/2).  With dω_V = 4 (V·H) dω_H, V·H = cos δ and
    μ_V = cos 2δ: E = ∫ D G1 / 4 · 4 cos δ dω_H = 2 ∫₀^{π/4} G1(cos 2δ) cos δ sin δ dδ
    = ½ ∫₀¹ G1(u) du = ∫₀¹ u / (1 + u) du = 1 − ln 2 ≈ 0.306853.
    """
    return exact(1.0 - np.log(2.0))
