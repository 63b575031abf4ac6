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

E(μ) the single-scattering albedo of the same model with F = 1 (so F_ms = 1 for F = 1).  A
compensated model receives E when it is built, as a Chebyshev table with a measured error (the
field ``energy``, an :class:`brdfs.physics.tables.AlbedoTable`): it names the table it needs
(:meth:`_SmithMicrofacet.table_requests`) and the factory above the physics layer computes it
(:func:`brdfs.numerics.tables.build`, the engine's albedo tabulated by
:func:`brdfs.numerics.pumping.tabulate_albedo`).  Built without it, it raises
:class:`brdfs.physics.tables.MissingTable`: nothing here integrates.  E_avg is integrated from the
interpolant exactly (:func:`brdfs.physics.tables.cosine_weighted_average`); then
∫ f_ms μ_V dω_V = 1 − E_table(μ_L) and the compensated albedo for F = 1 is
E(μ_L) + 1 − E_table(μ_L) = 1 up to the table's error.  f_ms is symmetric in L and V by construction.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar

import numpy as np

from brdfs.core.estimate import Estimate
from brdfs.physics.lobes import MicrofacetLobe
from brdfs.physics.distributions import GGX, Beckmann, half_vector_tan2
from brdfs.physics.sampling import REJECTED
from brdfs.physics.fresnel import cos_theta_half, unpolarised_reflectance
from brdfs.physics.geometry import cos_incidence
from brdfs.physics.masking import G2_FORMS, SmithG2
from brdfs.physics.models.base import ALPHA_MAX, ALPHA_MIN, BRDF, Interval, check_positive, exact, log_range, non_negative, positive, register, table_field
from brdfs.physics.tables import AlbedoTable, MissingTable, TableRequest, cosine_weighted_average

COMPENSATIONS = ("none", "kulla_conty")

#: Accuracy of the E(μ) tables of the Kulla–Conty term: Chebyshev interpolation to 1e-6 relative
#: (checked at the midpoints between nodes) on engine values at 1e-7.
E_TABLE_RTOL = 1.0e-6
E_ENGINE_RTOL = 1.0e-7


def energy_table_edges(alpha, factors):
    """Pieces of [0, 1] in μ for the E table: 0, the multiples ``factors`` × α inside (0, 1), and 1.
    E(μ) turns steeply, and not like a polynomial, on the scale μ ~ α toward μ = 0, so the factors are
    the distribution's (:attr:`_SmithMicrofacet.energy_edge_factors`)."""
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
    #: E(μ) of the single-scattering model with F = 1 and this G2: the table a compensated model is
    #: built with (:meth:`table_requests`); None without compensation.
    energy: AlbedoTable | None = table_field()
    distribution_type: ClassVar[type] = GGX
    #: Multiples of α at which the E table is split (:func:`energy_table_edges`).
    energy_edge_factors: ClassVar[tuple[float, ...]] = (0.1, 1.0, 10.0)
    #: Whether single scattering integrates in the distribution's own CDF (:attr:`lobe`) rather
    #: than the tangent coordinate.
    single_scattering_in_own_cdf: ClassVar[bool] = False

    # --- what the model says about itself
    chapter = None               # today's practice, beyond the thesis (issue 18)
    param_ranges = {"alpha": Interval(ALPHA_MIN, ALPHA_MAX), "ior_re": positive(), "ior_im": non_negative()}
    param_choices = {"G2": G2_FORMS, "compensation": COMPENSATIONS}
    #: α = 0.3 ≈ the Blinn-matched roughness of n = 20; α = 0.01, the narrowest the engine is held to
    examples = {"typical": {"alpha": 0.3}, "narrowest": {"alpha": 0.01}}
    #: the generic tests draw α from 0.01 … 1, F = 1 (None) or n_re in 0.1 … 10, k from 0 and 1e-3 … 10
    test_ranges = {"alpha": log_range(1e-2, 1.0), "ior_re": log_range(0.1, 10.0, none=True),
                   "ior_im": log_range(1e-3, 10.0, zero=True)}
    #: energy property: n_re ≥ 1 (k ≥ 0); below 1 with k = 0 the Fresnel factor has the kink of total
    #: internal reflection inside the lobe, which costs the engine ~7e6 evaluations (3 s) per draw
    energy_test_ranges = {"ior_re": log_range(1.0, 10.0, none=True)}
    #: Single scattering loses the energy of the paths that hit the surface again (E ≤ 1); with
    #: Kulla–Conty's term the albedo is F_ms-weighted 1 (1 for F = 1) within the table's error.
    conserves_energy = True

    @classmethod
    def energy_request(cls, alpha, G2="height_correlated") -> TableRequest:
        """The E table of roughness ``alpha`` and ``G2``: single scattering with F = 1, pieces
        :func:`energy_table_edges`, Chebyshev degree 4 and up to :data:`E_TABLE_RTOL` on engine
        values at :data:`E_ENGINE_RTOL`."""
        alpha = float(alpha)
        return TableRequest(cls(alpha=alpha, G2=G2), energy_table_edges(alpha, cls.energy_edge_factors),
                            degree=4, target_rtol=E_TABLE_RTOL, engine_rtol=E_ENGINE_RTOL)

    @classmethod
    def table_requests(cls, **params):
        """``{"energy": E table}`` for ``compensation='kulla_conty'`` (:meth:`energy_request`), else none."""
        if params.get("compensation", "none") != "kulla_conty":
            return {}
        return {"energy": cls.energy_request(params["alpha"], params.get("G2", "height_correlated"))}

    def __post_init__(self):
        check_positive("alpha", self.alpha)
        if self.G2 not in G2_FORMS:
            raise ValueError(f"G2 must be one of {G2_FORMS}, got {self.G2!r}")
        if self.compensation not in COMPENSATIONS:
            raise ValueError(f"compensation must be one of {COMPENSATIONS}, got {self.compensation!r}")
        if self.ior_re is not None:
            check_positive("ior_re", self.ior_re)
            check_positive("ior_im", self.ior_im, allow_zero=True)
        elif self.ior_im != 0.0:
            raise ValueError(f"ior_im = {self.ior_im!r} given without ior_re (the index's real part)")
        if self.compensation == "kulla_conty":
            if self.energy is None:
                raise MissingTable(
                    f"{self.name} with compensation='kulla_conty' needs its E table (field 'energy'), which "
                    f"the physics layer does not compute: build it with brdfs.model({self.name!r}, ...) "
                    f"(brdfs.numerics.tables.build), which tabulates it")
            object.__setattr__(self, "_energy_average", cosine_weighted_average(self.energy))

    # --- shape ---------------------------------------------------------------------------------
    @cached_property                 # a frozen model's distribution: built once (the polar route asks per call)
    def distribution(self):
        return self.distribution_type(self.alpha)

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        """Half-vector lobe coordinates: Beckmann's own CDF for the Beckmann single scattering; the
        tangent coordinate t = tan δ/(α + tan δ) (:class:`TangentCoordinate`) for GGX and for every
        compensated model (f_ms spreads over the whole hemisphere, and Beckmann's t = 1 − exp(−tan²δ/α²)
        rounds to 1 beyond tan δ ≈ 6α, where that part of the integrand would be lost)."""
        if self.single_scattering_in_own_cdf and self.compensation == "none":
            return MicrofacetLobe(self.distribution)
        return MicrofacetLobe(TangentCoordinate(self.alpha))

    def nv_levels(self, nl):
        """No kinks, but a scale: λ(μ_V) = Λ μ_V turns on μ_V ~ α (√(μ² + α² (1 − μ²)) for GGX, whose
        branch points at μ_V = ±iα/√(1 − α²) sit next to the horizon for small α).  The levels α/16, α/4,
        α, 4α (those below 1) split the engine's fixed azimuthal rule there."""
        return tuple(k * self.alpha for k in (1 / 16, 1 / 4, 1.0, 4.0) if k * self.alpha < 1.0)

    # --- the BRDF ------------------------------------------------------------------------------
    #: Where F is read, by ``ior_re`` and by a renderer's metal (``eta``/``k``) alike: L·H.
    fresnel_cosine = staticmethod(cos_theta_half)

    def fresnel(self, cos_theta):
        """F(cos θ): 1 (``ior_re`` None) or the unpolarised conductor reflectance (eqs. 1.41–1.43)."""
        if self.ior_re is None:
            return np.ones_like(np.asarray(cos_theta, float))
        return unpolarised_reflectance(cos_theta, self.ior_re, self.ior_im)

    @property
    def g2_over_4_nl_nv(self) -> SmithG2:
        """G2 / (4 N·L N·V), finite at the horizon (module docstring): the declared form
        (:class:`~brdfs.physics.masking.SmithG2`, λ of :attr:`distribution`, this G2), called as
        ``g2_over_4_nl_nv(nl, nv)``.  A subclass that overrides it with a method of its own declares no
        form: the polar route evaluates its method (on numpy)."""
        return self._g2_masking

    @cached_property                 # a frozen model's masking: built once (the polar route asks per call)
    def _g2_masking(self):
        return SmithG2(self.distribution, self.G2)

    def half_vector_factors(self):
        """F = 1 and no compensation: f = D(H) · G2/(4 N·L N·V), the masking a function of the polar
        angles only (:mod:`brdfs.numerics.integrate.polar`).  F(L·H) or f_ms break the form: None."""
        if self.ior_re is not None or self.compensation != "none":
            return None
        return self.distribution, self.g2_over_4_nl_nv

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
        d = self.distribution.D(cos_d, tan2)
        if self.ior_re is None:
            return d * self.g2_over_4_nl_nv(nl, nv)
        return self.fresnel(self.fresnel_cosine(L, V)) * d * self.g2_over_4_nl_nv(nl, nv)

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
        """(E table, E_avg) of the single-scattering model with F = 1 and this G2: the table the model
        was built with and its cosine-weighted average (:func:`cosine_weighted_average`)."""
        if self.energy is None:
            raise MissingTable(f"{self.name} without compensation has no E table")
        return self.energy, self._energy_average

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

    @property
    def has_evaluation_error(self):
        return self.compensation == "kulla_conty" or super().has_evaluation_error

    def evaluation_error(self, theta_deg, albedo):
        """The E table's share of the compensated albedo's error.  With Ẽ the table (|Ẽ − E| ≤ ε) and
        Ẽ_avg its exact cosine-weighted average, ∫ f̃_ms μ_V dω_V = F̃_ms (1 − Ẽ(μ_L)) exactly (module
        docstring), against F_ms (1 − E(μ_L)) for the exact E:
        |Δ| ≤ F_ms ε + (1 − Ẽ_L + ε) |ΔF_ms|, |ΔF_ms| ≤ ε F_avg² (1 − F_avg) / (1 − F_avg (1 − Ẽ_avg + ε))²
        (dF_ms/dE_avg, zero for F = 1)."""
        out = super().evaluation_error(theta_deg, albedo)
        if self.compensation != "kulla_conty":
            return out
        table, e_avg = self.energy_table()
        eps = table.error
        one_minus_el = np.clip(1.0 - table(cos_incidence(np.asarray(theta_deg, float))), 0.0, 1.0)
        f_avg = self.fresnel_average()
        d_fms = eps * f_avg ** 2 * (1.0 - f_avg) / max(1.0 - f_avg * (1.0 - e_avg.value + eps), 1e-300) ** 2
        return out + self.fresnel_ms() * eps + (one_minus_el + eps) * d_fms

    def table_error(self):
        """Absolute error bound of the E table (interpolation + engine); 0 without compensation."""
        return self.energy_table()[0].error if self.compensation == "kulla_conty" else 0.0

    # --- sampling (visible normals) ------------------------------------------------------------
    def _ms_probability(self, nl):
        """Probability of the cosine lobe in the mixture sampler: 1 − E(μ_L) with compensation, else 0."""
        if self.compensation == "none":
            return np.zeros(np.shape(nl))
        return np.clip(1.0 - self.energy_table()[0](nl), 0.0, 1.0)

    #: ``"visible_normals"``: V reflected about a visible normal (mixed with the cosine lobe with
    #: probability 1 − E(μ_L) when compensated); ``"cosine"``: the protocol's baseline.
    strategies = ("visible_normals", "cosine")
    chi2_cases = ({"alpha": 0.01}, {"alpha": 0.3}, {"alpha": 1.0})

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
        # a visible normal may reflect L below the horizon: that sample is rejected (BRDF.sample's marker)
        V_ss = np.where(V_ss[..., 2:] > 0, V_ss, REJECTED)
        r, phi = np.sqrt(u_ms), 2.0 * np.pi * u1
        V_ms = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u_ms, 0.0))], -1)
        return np.where(cosine[..., None], V_ms, V_ss)


@register
@dataclass(frozen=True)
class GGXMicrofacet(_SmithMicrofacet):
    """GGX (Trowbridge–Reitz) microfacet conductor, f = F D G2 / (4 N·L N·V) (Walter et al. 2007, eq. 20)
    with GGX's D (their eq. 33) and Smith's G2 (Heitz 2014) (:class:`brdfs.physics.distributions.GGX`)."""

    name = "ggx"
    distribution_type = GGX
    #: GGX's tails make E − E(0) fall off like a fractional power toward μ = 0 (E(0) = 1 for the
    #: height-correlated G2): edges α·10^-k (k = 1 … 4) and α/3, α, 3α, 10α, geometric toward 0.
    energy_edge_factors = (1e-4, 1e-3, 1e-2, 0.1, 1 / 3, 1.0, 3.0, 10.0)

    def exact_albedo(self, theta_deg):
        """α = 1, F = 1, no compensation, θ = 0: E(1) = 1 − ln 2 (:func:`ggx_alpha1_normal_albedo`)."""
        theta = np.asarray(theta_deg, float)
        known = self.alpha == 1.0 and self.ior_re is None and self.compensation == "none"
        return np.where((theta == 0.0) & known, ggx_alpha1_normal_albedo().value, np.nan)


@register
@dataclass(frozen=True)
class BeckmannMicrofacet(_SmithMicrofacet):
    """Beckmann microfacet conductor, f = F D G2 / (4 N·L N·V) (Walter et al. 2007, eq. 20) with
    Beckmann's D (their eq. 25) and Smith's G2 (Heitz 2014) (:class:`brdfs.physics.distributions.Beckmann`)."""

    name = "beckmann"
    distribution_type = Beckmann
    #: Beckmann's E is smooth near μ = 0 (Gaussian tails): α/10, α, 10α suffice (fewer engine calls
    #: for the same checked accuracy).
    energy_edge_factors = (0.1, 1.0, 10.0)
    #: Single scattering integrates in Beckmann's own CDF (:attr:`lobe`).
    single_scattering_in_own_cdf = True


SMITH_MODELS = {cls.name: cls for cls in (GGXMicrofacet, BeckmannMicrofacet)}


def ggx_alpha1_normal_albedo() -> Estimate:
    """E(μ = 1) of GGX with α = 1, F = 1: 1 − ln 2, for both G2 forms.

    With α = 1, D(H) = 1/π for every H above the horizon.  At L = N, Λ(L) = 0, so both G2 forms are
    G1(V) = 2 μ_V / (1 + μ_V) (Λ = (1/μ − 1)/2).  With dω_V = 4 (V·H) dω_H, V·H = cos δ and
    μ_V = cos 2δ: E = ∫ D G1 / 4 · 4 cos δ dω_H = 2 ∫₀^{π/4} G1(cos 2δ) cos δ sin δ dδ
    = ½ ∫₀¹ G1(u) du = ∫₀¹ u / (1 + u) du = 1 − ln 2 ≈ 0.306853.
    """
    return exact(1.0 - np.log(2.0))
