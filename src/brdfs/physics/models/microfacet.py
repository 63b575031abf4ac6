"""Beckmann-lobe models: Ward (eqs. 2.8, 3.35), corrected Ward (eq. 3.36), Cook–Torrance (eqs. 2.9, 2.10)."""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy.special import gamma

from brdfs.core.gauss_kronrod import Estimate, NodeValues, integrate
from brdfs.physics.lobes import HALF, MicrofacetLobe
from brdfs.physics.distributions import Beckmann, half_vector_parts, half_vector_tan2
from brdfs.physics.fresnel import cos_theta_half, unpolarised_reflectance
from brdfs.physics.masking import ThesisSmith, g_smith_beckmann
from brdfs.physics.models.base import BRDF, CT_M_MAX, M_MIN, GrazingLaw, Interval, check_positive, exact, log_range, positive, register
from brdfs.physics import sampling


def beckmann_exponential(L, V, m):
    """(exp(−tan²δ/m²), cos δ) of the half vector of L and V (:class:`Beckmann` weight)."""
    tan2, cos_d = half_vector_tan2(L, V)
    return Beckmann(m).slope_weight(tan2), cos_d


@dataclass(frozen=True)
class _BeckmannFamily(BRDF):
    m: float
    C: float = 1.0
    #: the generic tests draw m from 0.005 … 10 (Table 3.2's narrowest is 0.005), C from 1e-3 … 1e3
    test_ranges = {"m": log_range(M_MIN, 10.0), "C": log_range(1e-3, 1e3)}

    def __post_init__(self):
        check_positive("m", self.m)
        check_positive("C", self.C)

    #: A metal of a microfacet model reads F at the facet's angle of incidence, L·H.
    fresnel_cosine = staticmethod(cos_theta_half)

    @property
    def distribution(self) -> Beckmann:
        """The Beckmann distribution of slopes with roughness α = m."""
        return Beckmann(self.m)

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return MicrofacetLobe(self.distribution)

    @property
    def azimuth_weight_form(self):
        """Ward and corrected Ward: C e^(−tan²δ/m²)/(4π m²) · 4 · sin δ dδ/dt
        (:meth:`Beckmann.solid_angle_per_t`) = C cos³δ/(8π): (C, 3, 8π), where the azimuth has a closed form."""
        return None if self.closed_form_azimuth is None else (self.C, 3, 8 * np.pi)

    # --- sampling: Beckmann normals with the half-vector Jacobian ------------------------------
    #: ``"beckmann"``: H from :meth:`Beckmann.sample_normal` (density D(H) N·H), V = 2 (L·H) H − L,
    #: pdf(V) = D(H) (N·H) / (4 V·H).  H with L·H ≤ 0 or V below the horizon is rejected (mass < 1).
    strategies = ("beckmann", "cosine")
    chi2_cases = ({"m": 0.005}, {"m": 0.1}, {"m": 0.5})

    def _sample_direction(self, L, u, strategy):
        return sampling.reflect_half_vectors(L, self.distribution.sample_normal(u[..., 0], u[..., 1]))

    def _pdf(self, L, V, strategy):
        _, cos_d = half_vector_tan2(L, V)
        _, jacobian = sampling.half_vector_jacobian(L, V)
        return self.distribution.normal_pdf(cos_d) * jacobian


@register
@dataclass(frozen=True)
class Ward(_BeckmannFamily):
    """Isotropic Ward, f = C/(4π m²) · exp(−tan²δ/m²) / √(N·L N·V) (eq. 2.8 / 3.35)."""

    name = "ward"
    # --- what the model says about itself
    chapter = 2                  # eq. 2.8 (and eq. 3.35)
    param_ranges = {"m": Interval(M_MIN, np.inf), "C": positive()}
    examples = {"typical": {"m": 0.1}, "narrowest": {"m": 0.005}}     # m = 0.005 … 0.4: Table 3.2
    # conserves_energy = False: a(θ) ~ K/√(cos θ) diverges at grazing incidence (sec. 2.2.1, :func:`ward_constant`)
    conserves_energy = False
    accuracy_families = {"ward": ("m", {})}
    diverges_at_grazing = True   # a(θ) √cos θ → K (grazing_law)
    sqrt_at_horizon = True
    closed_form_azimuth = (HALF, "sqrt(nv/nl)")

    def _eval(self, L, V, nl, nv):
        e, _ = beckmann_exponential(L, V, self.m)
        f = self.C / (4 * np.pi * self.m ** 2) * e / np.sqrt(nl * nv)
        return np.where((nl > 0) & (nv > 0), f, np.inf)        # the horizon: e > 0, 1/√(N·L N·V) → ∞

    def grazing_law(self):
        """Diverges: a(μ) √μ → K (:func:`ward_constant`)."""
        return GrazingLaw(0.5, ward_constant(self.m, self.C), "K U(7/4,1/4,1/m^2) / sqrt(cos)")


@register
@dataclass(frozen=True)
class WardCosmin(_BeckmannFamily):
    """Corrected Ward, f = C/(4π m²) · exp(−tan²δ/m²) / max(N·L, N·V) (eq. 3.36)."""

    name = "ward_cosmin"
    chapter = 3                  # eq. 3.36
    param_ranges = {"m": Interval(M_MIN, np.inf), "C": positive()}
    examples = {"typical": {"m": 0.1}, "narrowest": {"m": 0.005}}     # m = 0.005 … 0.4: Table 3.2
    conserves_energy = True      # Table 3.2: C_max = 1/max a ≥ 1, so max a ≤ 1 at the default C = 1
    accuracy_families = {"ward_cosmin": ("m", {})}
    closed_form_azimuth = (HALF, "nv/max")

    def _eval(self, L, V, nl, nv):
        e, _ = beckmann_exponential(L, V, self.m)
        return self.C / (4 * np.pi * self.m ** 2) * e / np.maximum(nl, nv)

    def nv_levels(self, nl):
        return (nl,)

    def grazing_law(self):
        """Finite: a(90°) = C Γ(3/2) U(3/2, 1/2, 1/m²)/(π m²) (:func:`ward_cosmin_limit`)."""
        return GrazingLaw(0.0, ward_cosmin_limit(self.m, self.C), "a(90) = U(3/2,1/2,1/m^2)/(pi m^2)")

    def exact_albedo(self, theta_deg):
        """a(90°) (:func:`ward_cosmin_limit`) and a(0) = C × :func:`ward_cosmin_normal_incidence`."""
        theta = np.asarray(theta_deg, float)
        out = np.where(theta == 90.0, ward_cosmin_limit(self.m, self.C).value, np.nan)
        if np.any(theta == 0.0):
            out = np.where(theta == 0.0, self.C * ward_cosmin_normal_incidence(self.m).value, out)
        return out


def ward_cosmin_normal_incidence(m) -> Estimate:
    """a(0) of eq. 3.36 with C = 1 as a 1-D integral: with L = N, t = tan(θ_V/2) and x = t²/m²,
    a(0) = ∫₀^(1/m²) e^(−x) (1 − m²x) / (1 + m²x)³ dx = 1 − 4m² + O(m⁴), so C_max → 1 as m → 0.
    The range is cut at x = 60 (e^(−60) ≈ 1e-26) where 1/m² is larger; ``scipy.integrate.quad`` to
    1e-13 relative, its own error estimate as the error."""
    from scipy.integrate import quad  # here: scipy.integrate costs a job ~0.2 s to import

    upper = min(1 / m ** 2, 60.0)
    val, err = quad(lambda x: np.exp(-x) * (1 - m * m * x) / (1 + m * m * x) ** 3, 0, upper,
                    epsabs=0, epsrel=1e-13, limit=200)
    return Estimate(val, err)


#: The cosine at which Cook–Torrance evaluates the limit of G / (N·L N·V) on the horizon.
_HORIZON_COS = 1e-150


def g_torrance_sparrow(nh, nl, nv, lh):
    """G = min{1, 2 NH NV / VH, 2 NH NL / LH} (eq. 2.10; V·H = L·H)."""
    return np.minimum(1.0, np.minimum(2 * nh * nv / lh, 2 * nh * nl / lh))


GEOMETRY_FACTORS = ("torrance_sparrow", "smith", "none")
#: The values of a = cot θ_V/m at which the polar route cuts the turn of the thesis's G*(N·V) of
#: roughness m (:meth:`CookTorrance.nv_levels`) ...
SMITH_TURN_SCALES = (1 / 16, 1 / 4, 1.0, 4.0, 16.0)
#: ... and their grading toward a = 1/m (θ_V = 45°) by this ratio (:func:`smith_turn_scales`).
SMITH_TURN_GRADING = 4.0


def smith_turn_scales(m):
    """a = cot θ_V/m of the breakpoints of the thesis's G* of roughness m > 1: :data:`SMITH_TURN_SCALES` and
    a = 1/16 · 4^(−k) down to 1/m.  G*(a) = √(π/2) a (1 − √(π/2) a + …) below its turn: in
    θ_V the terms aᵏ ∝ (m θ_V)^(−k) fall from 16/m to 1 over log₄(m) octave pairs, which one Gauss–Kronrod
    interval neither integrates nor sees (m = 1e6 at 0°: 1.4× the error it reported, with the turn cut)."""
    low = SMITH_TURN_SCALES[0]
    graded = []
    while low * m > 1.0:
        low /= SMITH_TURN_GRADING
        graded.append(low)
    return (*graded, *SMITH_TURN_SCALES)


@register
@dataclass(frozen=True)
class CookTorrance(_BeckmannFamily):
    """Cook–Torrance with F = 1 (eq. 2.9):
    f = exp(−tan²δ/m²) / (4π m² cos⁴δ) · G / (N·L N·V), G from eq. 2.10 by default.

    ``G`` selects the geometry factor: ``"torrance_sparrow"`` (eq. 2.10, as printed),
    ``"smith"`` (eq. 1.38) or ``"none"`` (G = 1).
    """

    G: str = "torrance_sparrow"
    name = "cook_torrance"
    # --- what the model says about itself
    chapter = 2                  # eqs. 2.9, 2.10
    param_ranges = {"m": Interval(M_MIN, CT_M_MAX), "C": positive()}
    param_choices = {"G": GEOMETRY_FACTORS}
    examples = {"typical": {"m": 0.1}, "narrowest": {"m": 0.005}}
    # conserves_energy = False: with G = 1 the albedo diverges like 1/cos θ (sec. 2.2.1,
    # :meth:`grazing_law`); the thesis prints values above 1 at grazing angles (sec. 3.7.3)
    conserves_energy = False
    accuracy_families = {"cook_torrance_ts": ("m", {"G": "torrance_sparrow"}),
                         "cook_torrance_smith": ("m", {"G": "smith"}),
                         "cook_torrance_none": ("m", {"G": "none"})}

    def __post_init__(self):
        super().__post_init__()
        if self.G not in GEOMETRY_FACTORS:
            raise ValueError(f"unknown geometry factor G={self.G!r}; choose one of {GEOMETRY_FACTORS}")

    def _eval(self, L, V, nl, nv):
        tan2, nh, h_norm = half_vector_parts(L, V)
        d = self.C * self.distribution.slope_weight(tan2) / (4 * np.pi * self.m ** 2 * nh ** 4)
        f = d * self._geometry(nl, nv, nh, 0.5 * h_norm) / (nl * nv)
        horizon = (nl == 0) | (nv == 0)
        if not horizon.any():
            return f
        # on the horizon G / (N·L N·V) is 0/0: its limit, with the zero cosine replaced by 1e-150 (G of
        # eq. 2.10 and Smith's G* are linear in it there, to rounding; G = 1 diverges)
        nl_h, nv_h = np.where(nl == 0, _HORIZON_COS, nl), np.where(nv == 0, _HORIZON_COS, nv)
        limit = np.inf if self.G == "none" else d * self._geometry(nl_h, nv_h, nh, 0.5 * h_norm) / (nl_h * nv_h)
        return np.where(horizon, limit, f)

    def _geometry(self, nl, nv, nh, lh):
        if self.G == "torrance_sparrow":
            return g_torrance_sparrow(nh, nl, nv, lh)
        if self.G == "smith":
            return g_smith_beckmann(nl, nv, self.m)
        return 1.0

    def grazing_law(self):
        """G = 1: diverges, a(μ) μ → C m/(2√π); G of eq. 2.10: a(90°) = C (G → 2 NH NL/LH);
        Smith's G: no closed form (the limit integrand is :meth:`grazing_limit_model`)."""
        if self.G == "none":
            return GrazingLaw(1.0, exact(self.C * self.m / (2 * np.sqrt(np.pi))), "m/(2 sqrt(pi) cos)")
        if self.G == "torrance_sparrow":
            return GrazingLaw(0.0, exact(self.C), "a(90) = 1 (G of eq. 2.10 -> 2 NH NL/LH)")
        return None

    def grazing_limit_model(self):
        """At N·L = 0 the BRDF is 0/0 with Smith's G and with eq. 2.10's; a(90°) integrates
        :class:`SmithGrazingLimit` or :class:`TorranceSparrowGrazingLimit`."""
        if self.G == "smith":
            return SmithGrazingLimit(self.m, self.C)
        if self.G == "torrance_sparrow":
            return TorranceSparrowGrazingLimit(self.m, self.C)
        return self

    @property
    def diverges_at_grazing(self):
        """G = 1: a(μ) μ → C m/(2√π) (:meth:`grazing_law`)."""
        return self.G == "none"

    @property
    def closed_form_azimuth(self):
        """G of eq. 2.10 and G = 1 are piecewise linear in L·H and N·V: closed forms; Smith's is not."""
        return {"torrance_sparrow": (HALF, "G/nl"), "none": (HALF, "1/nl")}.get(self.G)

    @property
    def azimuth_weight_form(self):
        """C e^(−tan²δ/m²)/(4π m² cos⁴δ) · 4 · sin δ dδ/dt · cos δ = C/(8π) (the kernel keeps L·H/cos δ):
        (C, 0, 8π), where the azimuth has a closed form."""
        return None if self.closed_form_azimuth is None else (self.C, 0, 8 * np.pi)

    def half_vector_factors(self):
        """Smith's G: f = D(H) · C G*(N·L) G*(N·V)/(4 N·L N·V) with D the Beckmann density
        (:mod:`brdfs.numerics.integrate.polar`); eq. 2.10's G depends on L·H: None."""
        if self.G != "smith":
            return None
        return self.distribution, self._smith_over_4_nl_nv

    @property
    def _smith_over_4_nl_nv(self) -> ThesisSmith:
        """C G*(N·L) G*(N·V)/(4 N·L N·V), the thesis's G* of roughness m: the declared form
        (:class:`~brdfs.physics.masking.ThesisSmith`), called as ``_smith_over_4_nl_nv(nl, nv)``.  A
        subclass that overrides it with a method declares no form: the polar route evaluates its method."""
        return self._thesis_masking

    @cached_property                 # a frozen model's masking: built once (the polar route asks per call)
    def _thesis_masking(self):
        return ThesisSmith(self.m, self.C)

    @property
    def kink_at_normal(self):
        """G* of eq. 1.38 behaves like 1 − c √(1 − N·V): a cone-shaped kink at V = N."""
        return self.G == "smith"

    @property
    def torrance_sparrow_switches(self):
        """G of eq. 2.10 is a min of three terms: its switches are kinks of the integrand."""
        return self.G == "torrance_sparrow"

    def nv_levels(self, nl):
        """N·V = N·L: where eq. 2.10's minimum switches between its masking and shadowing terms.  Smith's
        G: where G*(N·V) turns (:data:`SMITH_TURN_SCALES`)."""
        if self.G == "smith":
            return self._smith_turn_levels
        return (nl,) if self.G == "torrance_sparrow" else ()

    @cached_property
    def _smith_turn_levels(self):
        """N·V = cos θ with cot θ = a m (a in :data:`SMITH_TURN_SCALES`), where h = a²/2 in the thesis's G*
        (eq. 1.38): G* ≈ √(π/2) a for a ≪ 1, 1 − 1/(√(2π) a) for a ≫ 1.  For m ≪ 1 the levels are
        N·V ≈ a m, next to the horizon; for m ≫ 1, θ_V ≈ 1/(a m), next to the pole, where G* alone
        carries ~1/m of the albedo: between two breakpoints 0 and π/4 the rule missed it whole and
        reported it converged (m = 1e4 at 0°: 8.35370e-13 ± 1.1e-16 against 8.35229e-13).  None for
        m ≤ 1, where the turn spreads over the hemisphere and the adaptive rule resolves it (the sweep's
        independent truths, m ≤ 1, hold it without; the levels would cost 1.5–2.5× the evaluations)."""
        if self.m <= 1.0:
            return ()
        return tuple(float(1.0 / np.sqrt(1.0 + 1.0 / (a * self.m) ** 2)) for a in smith_turn_scales(self.m))

    def lh_levels(self, nl, cos_delta):
        """Where the shadowing (LH = 2 NH NL) and masking (LH (4 NH² − 1) = 2 NH NL) terms of eq. 2.10 reach 1."""
        if self.G != "torrance_sparrow":
            return ()
        with np.errstate(divide="ignore"):
            masking = 2 * cos_delta * nl / (4 * cos_delta ** 2 - 1)
        return (2 * cos_delta * nl, np.where(4 * cos_delta ** 2 > 1, masking, np.inf))


@dataclass(frozen=True)
class CookTorranceFresnel(CookTorrance):
    """Cook–Torrance of eq. 2.9 times the unpolarised Fresnel reflectance F(L·H) (eqs. 1.41–1.43) of a
    real or complex index ``ior_re + i ior_im`` (Figure 3.3 reads Cook–Torrance's "n = 5" so).

    Not registered: no table or sweep draws it.  F breaks the closed forms of :class:`CookTorrance`
    (its azimuthal kernel and grazing law assume F = 1), so they are withdrawn."""

    ior_re: float = field(kw_only=True)
    ior_im: float = field(kw_only=True, default=0.0)
    name = "cook_torrance_fresnel"
    closed_form_azimuth = None
    half_vector_factors = BRDF.half_vector_factors
    grazing_law = BRDF.grazing_law
    grazing_limit_model = BRDF.grazing_limit_model
    exact_albedo = BRDF.exact_albedo

    def _eval(self, L, V, nl, nv):
        return super()._eval(L, V, nl, nv) * unpolarised_reflectance(self.fresnel_cosine(L, V), self.ior_re,
                                                                    self.ior_im)


# --- closed forms at grazing incidence (Sec. 2.2.1) ------------------------------------------

#: u = v² beyond which exp(−u²) = exp(−v⁴) < 1e-35: the truncation of the 1-D integrals in v.
_V_MAX = 3.0
_EPS = np.finfo(float).eps


def _v_integral(fn):
    """∫₀^∞ fn(u) e^(−u²) du over u = v², v ∈ [0, 3], by the engine's Gauss–Kronrod driver."""
    def integrand(v, elem):
        u = v * v
        g = fn(u) * np.exp(-u * u) * 2 * v
        return NodeValues(g, g, None)

    est = integrate(integrand, np.array([[0.0, 0.5, 1.0, 1.5, 2.0, _V_MAX]]), rtol=1e-13, atol=1e-300)
    tail = 1e-35 * abs(float(est.value[0]))  # e^(−81) relative, beyond v = 3
    return Estimate(float(est.value[0]), float(est.error[0]) + tail + 8 * _EPS * abs(float(est.value[0])))


def ward_constant(m, C=1.0):
    """K_Ward = lim √μ a(μ) for Ward (eq. 2.8).

    √μ a = ∫ C e^(−tan²δ/m²)/(4π m²) √(N·V) dω_V → (L horizontal, dω_V = 4 L·H dω_H,
    N·V = sin 2δ cos φ, L·H = sin δ cos φ)::

        K = C/(π m²) · ∫cos^{3/2}φ dφ · ∫ e^(−tan²δ/m²) √(sin 2δ) sin²δ dδ
          = C/(π m²) · √π Γ(5/4)/Γ(7/4) · √2 m^{7/2} ∫₀^∞ u^{5/2} (1 + m²u²)^{−5/2} e^{−u²} du
          = C Γ(5/4) U(7/4, 1/4, 1/m²) / (√(2π) m²)   (tan δ = m u; the limit by dominated convergence).
    """
    inner = _v_integral(lambda u: u ** 2.5 * (1 + (m * u) ** 2) ** -2.5)
    scale = C / (np.pi * m * m) * np.sqrt(np.pi) * gamma(1.25) / gamma(1.75) * np.sqrt(2.0) * m ** 3.5
    return Estimate(scale * inner.value, scale * inner.error + 4 * _EPS * scale * inner.value)


def ward_cosmin_limit(m, C=1.0):
    """a(90°) of the corrected Ward (eq. 3.36).

    f = D/N·V at N·L = 0, so::

        a = C/(4π m²) ∫ e^(−tan²δ/m²) 4 L·H dω_H = 2C/(π m²) ∫ e^(−tan²δ/m²) sin²δ dδ
          = 2C m/π ∫₀^∞ u² (1 + m²u²)^(−2) e^(−u²) du = C Γ(3/2) U(3/2, 1/2, 1/m²)/(π m²).
    """
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

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return MicrofacetLobe(Beckmann(self.m))

    def _eval(self, L, V, nl, nv):
        e, nh = beckmann_exponential(L, V, self.m)
        d = self.C * e / (4 * np.pi * self.m ** 2 * nh ** 4)
        return d * np.sqrt(np.pi / 2) / self.m * g_smith_beckmann(np.ones_like(nv), nv, self.m) / nv

    def half_vector_factors(self):
        """f_lim = D(H) · C √(π/2) G*(N·V)/(4 m N·V), D the Beckmann density: the polar route."""
        return Beckmann(self.m), self._limit_masking

    def _limit_masking(self, nl, nv):
        return self.C * np.sqrt(np.pi / 2) / self.m * g_smith_beckmann(np.ones_like(nv), nv, self.m) / (4 * nv)


@dataclass(frozen=True)
class TorranceSparrowGrazingLimit(BRDF):
    """The integrand of lim a(θ_L), θ_L → 90°, of Cook–Torrance with G of eq. 2.10.

    At N·L → 0 the shadowing term of eq. 2.10 is the least, G → 2 N·H N·L / L·H, so
    G/(N·L N·V) → 2 N·H / (L·H N·V) and f_lim = C D · 2 N·H / (4π m² cos⁴δ L·H N·V); its albedo is
    C (:meth:`CookTorrance.grazing_law`)."""

    m: float
    C: float = 1.0
    name = "cook_torrance_ts_grazing_limit"

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return MicrofacetLobe(Beckmann(self.m))

    def _eval(self, L, V, nl, nv):
        tan2, nh, h_norm = half_vector_parts(L, V)
        d = self.C * Beckmann(self.m).slope_weight(tan2) / (4 * np.pi * self.m ** 2 * nh ** 4)
        return d * 2 * nh / (0.5 * h_norm * nv)
