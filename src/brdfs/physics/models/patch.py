"""Patch-based BRDFs of chapter 4: functions of the distance m of L'_P and V_P on the base plane.

m(L, V) = |h − (N·h)N| with h = L + V (eq. 4.1) is symmetric in L and V, so every model here is
reciprocal (section 4.2.1).  The geometry, profiles and constants are in :mod:`brdfs.physics.patch_geometry`;
the albedos of these models come from there too (closed-form circle intersections, the verb
``albedo_estimate`` that the albedo engine takes), not from the generic hemisphere integration.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy.special import gammainc

from brdfs.physics import patch_geometry as patch
from brdfs.core.gauss_kronrod import Estimate, integrate
from brdfs.core.gauss_kronrod import KRONROD_WEIGHTS, nodes_on
from brdfs.physics import fresnel, sampling
from brdfs.physics.models.base import BRDF, ELLIPSE_B_MIN, RADIUS_MIN, Interval, check_positive, linear_range, log_range, non_negative, positive, register


def projected_distance(L, V):
    """m(L, V) = |V_P − L'_P| = |h − (N·h)N|, h = L + V  (eq. 4.1)."""
    return np.hypot(L[..., 0] + V[..., 0], L[..., 1] + V[..., 1])


def _check_radius(name, value):
    value = check_positive(name, value)
    if value > 2.0:
        raise ValueError(f"{name} must lie in (0, 2], got {value!r}")
    return value


def _default_constant(model, value):
    """Set the frozen field ``C`` to ``value`` unless given; reject a non-positive C."""
    if model.C is None:
        object.__setattr__(model, "C", float(value))
    check_positive("C", model.C)


def _mirrored_projection(L):
    """V'_P = −L_P, the centre of the patch on the base plane (eq. 4.16, with L and V exchanged)."""
    return -L[..., 0], -L[..., 1]


def _russian_roulette_mixture(L, u, R):
    """Section 4.4 with the Russian roulette of section 4.2.4: R = F⁻¹(u₃) given, a uniform point in
    C_min(V'_P, R), kept if it lies in the other circle too (eqs. 4.18, 4.19)."""
    cx, cy = _mirrored_projection(L)
    x, y, accepted, _ = sampling.russian_roulette_point(cx, cy, R, u[..., 0], u[..., 1])
    return np.where(accepted[..., None], sampling.disk_to_direction(x, y), sampling.REJECTED)


class _OnTheBasePlane:
    """What every patch model declares for its samplers and metals: its samplers draw points of the
    base plane (the chi-square test's disk chart), and a metal reads F at θ' (eqs. 4.53, 4.54)."""

    sampling_domain = "disk"
    fresnel_cosine = staticmethod(fresnel.cos_theta_prime)


class LensMixtureAlbedo:
    """The albedo of a mixture of basic BRDFs as its own route (eqs. 4.22, 4.24): one quadrature in R of the
    lens areas a_R, weighted by the model's p(R), which :meth:`lens_mixture` declares.  A single angle starts
    from a graded partition (:func:`patch_geometry._single_element_partition`).  A compiled route may answer
    a single angle of a model whose ``albedo_estimate`` is this one from the same :meth:`lens_mixture`."""

    def lens_mixture(self) -> patch.LensMixture:
        """p(R), p_Diffuse, the weight's points, covered weight and steep layer (:class:`~patch.LensMixture`)."""
        raise NotImplementedError

    def albedo_estimate(self, theta_deg, rtol, atol):
        """∫₀² p(R) a_R(L) dR + p_Diffuse over the basic patches' lens areas (eqs. 4.8, 4.22, 4.24): one
        quadrature in R of closed forms, split at the kinks of a_R and at the weight's points."""
        return patch.lens_mixture_albedo(self.lens_mixture(), theta_deg, rtol, atol, single_graded=True)


class _MixtureSampling(_OnTheBasePlane):
    """Sampling of a mixture of basic BRDFs, f = ∫ p(R) f*_R dR + p_Diffuse f*_2 (eq. 4.20).

    ``"russian_roulette"`` (sections 4.4 and 5.2.5; u of shape (…, 3)): R = F⁻¹(u₃) (eq. 4.27, the
    Dirac p_Diffuse at R = 2 as the step of F), then the Russian roulette of the basic BRDF at R.
    An accepted point has density Σ_R p(R) c(R) [m ≤ R] = f per unit area of the base plane, so
    pdf(V) = f(L, V) cos θ_V / W (W = ∫p + p_Diffuse, 1 for a normalised p) and weight = W: the
    sampler is exact up to its rejections, whose probability is 1 − a(L)/W.
    """

    sample_dimensions = {"russian_roulette": 3}
    strategies = ("russian_roulette", "cosine")
    #: Uniform numbers :meth:`basic_radius` consumes per sample.
    basic_radius_dimension = 1

    def basic_radius(self, u):
        """R of the basic BRDF f*_R a sample draws from (eq. 4.20): F⁻¹(u₀) (eq. 4.27)."""
        return self.radius_of_cdf(u[..., 0])

    def _sample_direction(self, L, u, strategy):
        return _russian_roulette_mixture(L, u, self.radius_of_cdf(u[..., 2]))

    def _pdf(self, L, V, strategy):
        return self.unchecked(L, V) * V[..., 2] / self.total_weight


@dataclass(frozen=True)
class PatchBasic(_OnTheBasePlane, BRDF):
    """Basic BRDF f*(R) = c(R) where m(L, V) ≤ R, else 0  (eq. 4.2); c(R) = 1/(π min(1, R²)) (eq. 4.7)."""

    R: float
    C: float | None = None
    name = "patch_basic"
    # --- what the model says about itself
    chapter = 4                  # eqs. 4.2, 4.7
    test_ranges = {"R": log_range(1e-2, 2.0), "C": log_range(1e-3, 1e3)}     # R = 0.2 and below: Figure 4.3
    param_ranges = {"R": Interval(RADIUS_MIN, 2.0), "C": positive()}
    examples = {"typical": {"R": 0.5}, "narrowest": {"R": 0.2}}     # R = 0.2: Figure 4.3
    conserves_energy = True      # c(R) = 1/(π min(1, R²)): a = lens area / patch area ≤ 1 (eq. 4.8)

    def __post_init__(self):
        _check_radius("R", self.R)
        _default_constant(self, patch.basic_constant(self.R))

    # --- the integrand's shape: a jump at m = R; no lobe (the albedo is the lens area, eq. 4.8)
    lobe = None

    def scattering_radius_levels(self):
        """The jump of f*(R) at m(L, V) = |L_xy + V_xy| = R (eq. 4.2)."""
        return (float(self.R),)

    def _eval(self, L, V, nl, nv):
        return np.where(projected_distance(L, V) <= self.R, self.C, 0.0)

    def albedo_estimate(self, theta_deg, rtol, atol):
        """Lens area over patch area (eq. 4.8), scaled by C/c(R)."""
        est = patch.basic_albedo(theta_deg, self.R)
        scale = self.C / float(patch.basic_constant(self.R))
        return Estimate(est.value * scale, est.error * scale)

    # --- sampling (section 4.2.4) ---------------------------------------------------------------
    #: ``"exact"`` ("normal importance sampling"): uniform points in C(V'_P, R) ∩ unit disk — a
    #: whole circle in the special cases (figure 4.7), the lens of two circles in the general case
    #: (figure 4.8) — so pdf = cos θ_V / Area(lens) and weight = a_R(L) (the albedo of eq. 4.8);
    #: mass 1.  ``"russian_roulette"`` (eqs. 4.18, 4.19): uniform in C_min, rejected outside the
    #: other circle, weight 1 (for the default C), pdf = f cos θ_V, mass a_R(L).
    strategies = ("exact", "russian_roulette", "cosine")
    chi2_cases = ({"R": 0.05}, {"R": 0.5}, {"R": 1.5})
    #: Uniform numbers :meth:`basic_radius` consumes per sample: none, R is the model's.
    basic_radius_dimension = 0

    def basic_radius(self, u):
        """R of the basic BRDF a sample draws from (section 4.2.4): the model's own, for every sample."""
        return np.full(np.shape(u)[:-1], self.R)

    def disk_boundaries(self):
        """The circle C(V'_P, R), where f*(R) jumps (eq. 4.2)."""
        return (float(self.R),), None

    def _sample_direction(self, L, u, strategy):
        cx, cy = _mirrored_projection(L)
        if strategy == "exact":
            x, y = sampling.uniform_in_lens(cx, cy, self.R, u[..., 0], u[..., 1])
            return sampling.disk_to_direction(x, y)
        x, y, accepted, _ = sampling.russian_roulette_point(cx, cy, self.R, u[..., 0], u[..., 1])
        return np.where(accepted[..., None], sampling.disk_to_direction(x, y), sampling.REJECTED)

    def _pdf(self, L, V, strategy):
        inside = projected_distance(L, V) <= self.R
        if strategy == "exact":
            area = sampling.lens_area(np.hypot(L[..., 0], L[..., 1]), self.R)
        else:
            area = np.pi * min(self.R, 1.0) ** 2
        return np.where(inside, V[..., 2] / area, 0.0)


@dataclass(frozen=True)
class PatchExponential(LensMixtureAlbedo, _MixtureSampling, BRDF):
    """f = C e^{−s m(L, V)}  (eqs. 4.44/4.46), C = C_max of eq. 4.45 by default."""

    s: float
    C: float | None = None
    name = "patch_exponential"
    # --- what the model says about itself
    chapter = 4                  # eqs. 4.44–4.46
    param_ranges = {"s": non_negative(), "C": positive()}
    test_ranges = {"s": log_range(1e-2, 1e3, zero=True), "C": log_range(1e-3, 1e3)}
    examples = {"typical": {"s": 4.0}, "narrowest": {"s": 512.0}}
    conserves_energy = True      # C_max of eq. 4.45 makes max a = a(N) = 1 (ξ decreasing)
    accuracy_families = {"patch_exponential": ("s", {})}

    def __post_init__(self):
        _default_constant(self, patch.ExponentialProfile(self.s).c_max)

    #: No lobe: the albedo is the mixture of lens areas (eqs. 4.22, 4.24); e^{−s m} has no kink.
    lobe = None

    def lens_mixture(self):
        """The exponential profile's weight p(R) (eq. 4.47) at C, with its Dirac part (eq. 4.24)."""
        return patch.profile_mixture(patch.ExponentialProfile(self.s), self.C)

    def _eval(self, L, V, nl, nv):
        return self.C * np.exp(-self.s * projected_distance(L, V))

    chi2_cases = ({"s": 512}, {"s": 10}, {"s": 1})

    @property
    def total_weight(self) -> float:
        """W = ∫p + p_Diffuse = C / C_max (p of eq. 4.41 scales with C)."""
        return self.C / patch.ExponentialProfile(self.s).c_max

    def radius_of_cdf(self, r):
        """R = F⁻¹(r) of the normalised weight (eq. 4.27, Figure 4.13: :func:`patch_geometry.inverse_cdf`)."""
        return patch.inverse_cdf(patch.ExponentialProfile(self.s), np.clip(r, 0.0, 1.0)).value

    # --- "exact" ("normal importance sampling" of section 4.2.4 for the mixture, section 4.4) -------
    #: R = F⁻¹(u₃) (eq. 4.27), then a uniform point of the lens C(V'_P, R) ∩ unit disk
    #: (:func:`sampling.uniform_in_lens`; the thesis's "repeat ... until found" draws the same
    #: point): mass 1, no rejection.  Its density per unit area of the base plane is
    #: Q(m, d) = ∫_m² q(R)/A(d, R) dR + p_Diffuse/π (:meth:`exact_area_density`); pdf = Q cos θ_V.
    strategies = ("russian_roulette", "exact", "cosine")
    sample_dimensions = {"russian_roulette": 3, "exact": 3}

    def _sample_direction(self, L, u, strategy):
        if strategy != "exact":
            return super()._sample_direction(L, u, strategy)
        cx, cy = _mirrored_projection(L)
        x, y = sampling.uniform_in_lens(cx, cy, self.radius_of_cdf(u[..., 2]), u[..., 0], u[..., 1])
        return sampling.disk_to_direction(x, y)

    def _pdf(self, L, V, strategy):
        if strategy != "exact":
            return super()._pdf(L, V, strategy)
        return self.exact_area_density(np.hypot(L[..., 0], L[..., 1]), projected_distance(L, V)) * V[..., 2]

    def exact_area_density(self, d, m):
        """Q(m, d) = ∫_m² q(R)/A(d, R) dR + p_Diffuse/π: the density per unit area of the base plane of
        the ``"exact"`` sampler at |L_P| = d, m = m(L, V) (eq. 4.1), q = F' (eq. 4.27) normalised,
        A(d, R) the lens area (eq. 4.9).

        The pieces where A is a closed form are closed: R ≤ 1 − d (the circle inside the disk,
        A = πR², q/A = s³e^{−sR}/(2π P(2, s))) and R ≥ 1 + d (A = π, ∫ q = ΔF).  Between them the lens
        is general; there ∫ runs over [1 − d, 1] and [1, 1 + d] (q has a kink at R = 1) in
        w = e^{−sR} (q dR ∝ R̂² dw, R̂ = min(R, 1), so that e^{−sR} needs no nodes), with
        w = w_a + (w_b − w_a)(3t² − 2t³) (which flattens A's (R − R_end)^{3/2} at the ends where
        the circles touch) and :data:`EXACT_PDF_NODES` Gauss–Legendre nodes in t per piece.
        Relative error against adaptive quadrature (scipy ``quad``, rtol 1e-12) at 480 random
        (s, d, m), s ∈ {0.5 … 512}: ≤ 5e-5 (tests/physics/test_patch_exact_density.py); the
        Dr.Jit twin (``brdfs_patch_exponential``, ``strategy = "normal"``) uses the same nodes.
        """
        d, m = np.broadcast_arrays(np.asarray(d, float), np.asarray(m, float))
        s = float(self.s)
        profile = patch.ExponentialProfile(s)
        p_diffuse = 1.0 - float(profile.cdf(2.0)) if not profile.negligible else 1.0
        if profile.negligible:                       # all the weight is the Dirac at R = 2: cosine
            return np.full(d.shape, 1.0 / np.pi)
        scale = s * s / (2.0 * gammainc(2.0, s))     # q(R) = s R̂² e^{−sR} · scale
        inside = np.where(m < 1.0 - d, scale * (np.exp(-s * m) - np.exp(-s * (1.0 - d))) / np.pi, 0.0)
        covers = (float(profile.cdf(2.0)) - profile.cdf(np.clip(np.maximum(m, 1.0 + d), 0.0, 2.0))) / np.pi
        total = inside + covers + p_diffuse / np.pi
        t, weights = _exact_pdf_nodes()
        smooth, slope = t * t * (3.0 - 2.0 * t), 6.0 * t * (1.0 - t)
        one = np.ones_like(d)
        for lo, hi in ((1.0 - d, one), (one, np.minimum(1.0 + d, 2.0))):
            a = np.maximum(lo, m)
            b = np.maximum(hi, a)
            wa, wb = np.exp(-s * a), np.exp(-s * b)
            w = wa[..., None] + (wb - wa)[..., None] * smooth
            R = np.clip(-np.log(w) / s, a[..., None], b[..., None])
            with np.errstate(divide="ignore", invalid="ignore"):
                h = np.minimum(R, 1.0) ** 2 / _lens_area(d[..., None], R)
            total = total + scale * (wa - wb) * np.sum(weights * slope * np.nan_to_num(h), axis=-1)
        return total


#: Gauss–Legendre nodes per piece of :meth:`PatchExponential.exact_area_density` (≤ 5e-5 relative;
#: 12 nodes give 5e-6 at 1.5× the cost).  The Dr.Jit twin reads them from here.
EXACT_PDF_NODES = 8


def _lens_area(d, R):
    """Area of C(Q, R) ∩ unit disk, |Q| = d, in the general case |1 − R| < d < 1 + R (eqs. 4.9/4.10):
    the angles of :func:`patch_geometry.circle_intersection` without its rounding bound, and the
    segment t − sin t cos t = (x − sin x)/2, x = 2t, by Horner's scheme of its series below x = 1/4
    (the density's quadrature evaluates it 16 times a direction)."""
    prod = (1.0 + d + R) * (d + R - 1.0) * (1.0 - d + R) * (1.0 + d - R)
    four_delta = np.sqrt(np.maximum(prod, 0.0))
    alpha = np.arctan2(four_delta, d * d + (1.0 - R) * (1.0 + R))
    beta = np.arctan2(four_delta, d * d + (R - 1.0) * (R + 1.0))
    return _segment(alpha) + R * R * _segment(beta)


def _segment(t):
    x = 2.0 * t
    x2 = x * x
    series = x * x2 * (1 / 6 - x2 * (1 / 120 - x2 * (1 / 5040 - x2 * (1 / 362880 - x2 / 39916800))))
    return 0.5 * np.where(x < 0.25, series, x - np.sin(x))


def _exact_pdf_nodes():
    """Gauss–Legendre nodes t ∈ [0, 1] and weights (summing to 1) of :data:`EXACT_PDF_NODES` points."""
    x, w = np.polynomial.legendre.leggauss(EXACT_PDF_NODES)
    return 0.5 * (x + 1.0), 0.5 * w


@dataclass(frozen=True)
class GeneralizedLambertian(LensMixtureAlbedo, _OnTheBasePlane, BRDF):
    """f = C min((1 − (m/2)²)^{−d/2}, ξ(m_clip))  (eqs. 4.58/4.59); C = 1/max albedo by default."""

    d: float
    m_clip: float = 1.9
    C: float | None = None
    name = "generalized_lambertian"
    # --- what the model says about itself
    chapter = 4                  # eqs. 4.58, 4.59 (Table 4.3)
    param_ranges = {"d": Interval(0.0, 1.0), "m_clip": Interval(RADIUS_MIN, 2.0, hi_open=True),
                    "C": positive()}
    #: m_clip to 2 − 1e-6, toward the end of its declared range (ξ_max ≈ 1000 at d = 1)
    test_ranges = {"m_clip": log_range(5e-2, 2.0 - 1e-6), "C": log_range(1e-3, 1e3)}
    examples = {"typical": {"d": 0.5}, "narrowest": {"d": 1.0}}
    conserves_energy = True      # C = 1/max a by default
    accuracy_families = {"generalized_lambertian": ("d", {})}

    def __post_init__(self):
        profile = patch.GeneralizedLambertProfile(self.d, self.m_clip)
        if self.C is None:
            _default_constant(self, patch.generalized_lambert_c_max(profile).value)
        check_positive("C", self.C)

    #: No lobe: the albedo is the mixture of lens areas (eqs. 4.22, 4.24).
    lobe = None

    def scattering_radius_levels(self):
        """The kink of min(ξ(m), ξ(m_clip)) at m = m_clip (eq. 4.59)."""
        return (float(self.m_clip),)

    def scattering_radius_steep_layer(self):
        """(m_clip, 2): ξ(m) = (1 − m²/4)^{−d/2} grows toward its pole m = 2 up to m_clip (the profile's own
        :attr:`~brdfs.physics.patch_geometry.GeneralizedLambertProfile.steep_layer`, that of p(R))."""
        return patch.GeneralizedLambertProfile(self.d, self.m_clip).steep_layer

    def _eval(self, L, V, nl, nv):
        return self.C * patch.GeneralizedLambertProfile(self.d, self.m_clip).xi(projected_distance(L, V))

    def lens_mixture(self):
        """The clipped profile's weight p(R) (eq. 4.41 with :meth:`~patch.GeneralizedLambertProfile.dxi`) at C,
        with its Dirac part (eq. 4.24)."""
        return patch.profile_mixture(patch.GeneralizedLambertProfile(self.d, self.m_clip), self.C)

    #: Its p(R) is negative (ξ increases), so it is no mixture to sample: the thesis samples it
    #: "with a cosine distribution ... and an appropriate multiplier correction factor for each
    #: ray" (section 4.7.4) — the cosine strategy, exact up to the weight f·π ≤ C ξ_max π.
    strategies = ("cosine",)
    chi2_cases = ({"d": 1.0}, {"d": 0.5})


def _checked_weight_points(points):
    """``weight_points`` as a sorted tuple of distinct floats in [0, 2], or one line naming the bad value."""
    if isinstance(points, (str, bytes)) or not np.iterable(points):
        raise ValueError(f"patch_mixture: weight_points must be a sequence of R in [0, 2], got {points!r}")
    out = set()
    for r in points:
        if isinstance(r, (bool, np.bool_)) or not isinstance(r, (int, float, np.integer, np.floating)):
            raise ValueError(f"patch_mixture: weight_points must hold real numbers R in [0, 2], got {r!r}")
        if not 0.0 <= float(r) <= 2.0:         # NaN fails too
            raise ValueError(f"patch_mixture: weight_points must lie in [0, 2], got {r!r}")
        out.add(float(r))
    return tuple(sorted(out))


@dataclass(frozen=True)
class BoxWeight:
    """p(R) = 1/(hi − lo) on [lo, hi], 0 elsewhere: a normalised weight (eq. 4.21) with a narrow peak, whose
    jumps at ``lo`` and ``hi`` a mixture declares (``weight_points=box.points``).  A frozen value: a
    mixture built with it compares and hashes by its ends."""

    lo: float
    hi: float

    def __post_init__(self):
        if not 0.0 <= self.lo < self.hi <= 2.0:
            raise ValueError(f"BoxWeight: needs 0 <= lo < hi <= 2, got lo={self.lo!r}, hi={self.hi!r}")

    def __call__(self, R):
        R = np.asarray(R, float)
        return np.where((R >= self.lo) & (R <= self.hi), 1.0 / (self.hi - self.lo), 0.0)

    @property
    def points(self) -> tuple[float, float]:
        """Where p is not smooth: its two jumps."""
        return (self.lo, self.hi)


#: The relative distance of a quadrature node R from the point it stands for, bounded: R = c + h t is rounded
#: in the product, the sum and the centre c itself, each by ε/2 of its size (|c|, |h t| ≤ |R| near R).
NODE_ROUNDING = 4 * float(np.finfo(float).eps)
#: A box of width 1e-5 at R = 0.37 (:attr:`PatchMixture.feature_examples`).
_NARROW_BOX = BoxWeight(0.37 - 5e-6, 0.37 + 5e-6)


def _uniform_weight(R):
    """p(R) = 1/2 on [0, 2]: a normalised weight (eq. 4.21), the example mixture."""
    return np.full(np.shape(R), 0.5)


def _falling_weight(R):
    """p(R) = (2 − R)/2 on [0, 2], normalised, weighted toward small patches: the narrower example."""
    return 1.0 - 0.5 * np.asarray(R, float)


@dataclass(frozen=True)
class PatchMixture(LensMixtureAlbedo, _MixtureSampling, BRDF):
    """Mixture of basic BRDFs f = ∫_m² p(R) c(R) dR + p_Diffuse c(2)  (eqs. 4.20, 4.21, 4.40). A weight
    that is not smooth between its declared ``weight_points`` and the built-in kinks (R = 1, 1 ∓ |L'_P|)
    gives an unreliable error estimate: declare its points.

    ``weight`` is the continuous part p(R) (a vectorised callable on [0, 2]), ``p_diffuse`` the
    Dirac weight at R = 2 (the ideal diffuse part). A mirror part (R = 0) is a Dirac in V and
    has no value to evaluate. The integrals in R (f itself, the albedo ∫ p(R) a_R(L) dR of
    eqs. 4.22/4.24, the table of F of eq. 4.27) are adaptive Gauss–Kronrod to ``rtol``, split at
    R = 1, at the lens's kinks and at ``weight_points``.

    ``weight_points``: the R in [0, 2] where p is not smooth — jumps, kinks, and the ends of a narrow
    peak.  p must be bounded: a pole, even an integrable one ((R − a)^(−q)), is not supported, declared
    or not (Gauss–Kronrod's K − G under-rates an endpoint singularity: q = 0.5 at a = 0.37 was 1.5e-8
    off at a reported 8.5e-10, "converged").  The quadrature sees p only at its nodes and judges its
    error by two rules on the same nodes, so a feature between two breakpoints that no node meets is
    neither integrated nor reported (a box of width 1e-5 at R = 0.37, undeclared: 0 ± 0 "converged" for
    an albedo of 1).  Declare a jump
    or a kink at its R, and a peak by its ends, where p has fallen below the tolerance, with its centre
    (a box: its two ends; a Gaussian of width σ: c − 8σ, c, c + 8σ): each piece between declared points
    is then as wide as the feature, where the Gauss–Kronrod pair resolves it.  The centre alone leaves a
    peak at the end of a piece much wider than the peak, which the nodes may miss (a Gaussian of
    σ = 1e-4 … 1e-6 at R = 0.37 declared by its centre alone: 0.5–1.0 off, "converged" at rtol 1e-10).
    With declared points, every route's error also bounds p's own rounding (:meth:`evaluation_error`): the
    nodes R carry a few ε R, which moves a feature of width w at R by ~ε R/w relative (a Gaussian of
    σ = 1e-6 at 0.37: 1.6e-11, 6× the quadrature's error at rtol 1e-10); a tolerance below it is
    reported ``stalled``.
    """

    weight: Callable[[np.ndarray], np.ndarray]
    p_diffuse: float = 0.0
    rtol: float = 1e-12
    #: Not ``tuple[float, ...]``: the front door checks a field typed float as one real number; this one is
    #: checked element by element in ``__post_init__`` (stored sorted, as a tuple of floats: hashable).
    weight_points: tuple = ()
    name = "patch_mixture"
    # --- what the model says about itself
    chapter = 4                  # eqs. 4.20, 4.21
    param_ranges = {"p_diffuse": non_negative(), "rtol": positive()}
    param_texts = {"weight": "a vectorised callable p(R) on [0, 2]",
                   "weight_points": "R in [0, 2] where p is not smooth (jumps, kinks, a peak's ends); "
                                    "a weight not smooth between them and R = 1, 1 ∓ |L'_P|, or unbounded (a pole), "
                                    "gives an unreliable error estimate"}
    #: rtol, the tolerance of the mixture's own integral (no physical parameter), held at its default
    test_ranges = {"p_diffuse": log_range(1e-3, 10.0, zero=True), "rtol": log_range(1e-12, 1e-12)}
    examples = {"typical": {"weight": _uniform_weight}, "narrowest": {"weight": _falling_weight}}
    #: Weights with features of their own, each with its declared ``weight_points``, beyond the examples
    #: (whose answers the front door's stored cells hold to the bit): the sweep's family
    #: ``patch_mixture_narrow_box`` covers them by the engine, the disk and ``auto``.  Undeclared, this box
    #: gave 0 ± 0 "converged" by every route for an albedo of 1 at 0° and 0.4606 at 90° − 1e-9.
    feature_examples = {"narrow_box": {"weight": _NARROW_BOX, "weight_points": _NARROW_BOX.points}}
    evaluation_error_source = "p's own rounding at the nodes, where its declared features are narrow"
    evaluation_error_remedy = "widen the weight's narrow features"
    # conserves_energy = False: a ≤ W = ∫p + p_Diffuse, which is 1 only for a normalised weight
    # (eq. 4.21); the model takes any weight and does not normalise it
    conserves_energy = False

    def __post_init__(self):
        if not callable(self.weight):
            raise ValueError(f"patch_mixture: weight must be a callable p(R), got {self.weight!r}")
        check_positive("p_diffuse", self.p_diffuse, allow_zero=True)
        check_positive("rtol", self.rtol)
        object.__setattr__(self, "weight_points", _checked_weight_points(self.weight_points))
        self._check_weight_is_finite()

    def _check_weight_is_finite(self):
        """p must be a real, bounded function: refused in one line where it is complex, or not finite at the
        ends or the midpoints of the table of F's pieces (a NaN weight otherwise gave NaN ± NaN after 63,756 evaluations)."""
        edges = self._table_edges()
        probe = np.concatenate([edges, 0.5 * (edges[:-1] + edges[1:])])
        given = np.asarray(self.weight(probe))
        if np.iscomplexobj(given):
            raise ValueError(f"patch_mixture: weight p(R) must be real, got values of type {given.dtype}")
        values = np.broadcast_to(given.astype(float), probe.shape)
        if not np.all(np.isfinite(values)):
            i = int(np.flatnonzero(~np.isfinite(values))[0])
            raise ValueError(f"patch_mixture: weight p(R) must be finite on [0, 2], got {float(values[i])!r} at R = {probe[i]:.6g}")

    #: No lobe: the albedo is the mixture of lens areas (eqs. 4.22, 4.24), its own route.
    lobe = None

    def scattering_radius_levels(self):
        """The kink of c(R) = 1/(π min(1, R²)) at m = 1, inherited by ∫_m² p(R) c(R) dR (eq. 4.21), and
        f's kinks at the weight's own points (f'(m) = −p(m) c(m) jumps where p does)."""
        return (1.0, *(r for r in self.weight_points if 0.0 < r < 2.0 and r != 1.0))

    @property
    def has_evaluation_error(self) -> bool:
        """Whether p's own rounding moves the albedo (:meth:`evaluation_error`): looked for only where points
        are declared (a weight without them keeps the answers it had, to the bit)."""
        return bool(self.weight_points) and self._weight_rounding() > 0.0

    def evaluation_error(self, theta_deg, albedo):
        """Bound of |a as evaluated − a| from p's own rounding, for every route.  f and the albedo evaluate p
        at quadrature nodes R that stand for points a few ε R away (:data:`NODE_ROUNDING`), which moves a
        feature of width w at R by ~ε R/w relative (a triangle of width 1e-5 at R = 0.37: 1.1e-11, where
        the quadrature's error was 1.2e-14).  Each route's error is ∫ δp(R) a_R dR with |δp| ≤ |p(R + δ) −
        p(R)|, δ = NODE_ROUNDING R (the disk's through f = ∫_m² p c dR, eq. 4.21: the same integral in the
        other order), so with a_R ≤ 1: ∫₀² |p(R + δ) − p(R)| dR, by a 21-point Kronrod rule on each piece
        of the table of F (split at the declared points), times 2 (:meth:`_weight_rounding`)."""
        return np.full(np.shape(theta_deg), self._weight_rounding())

    def _weight_rounding(self) -> float:
        """2 ∫₀² |p(R + δ) − p(R)| dR, δ = :data:`NODE_ROUNDING` R (:meth:`evaluation_error`); 0 for a weight
        constant between its declared points (a box), cached on the model."""
        cached = self.__dict__.get("_rounding_cache")
        if cached is None:
            edges = self._table_edges()
            x = nodes_on(edges[:-1], edges[1:])
            moved = np.abs(self.weight(x + NODE_ROUNDING * x) - self.weight(x))
            cached = float(2.0 * np.sum(0.5 * np.diff(edges) * (moved @ KRONROD_WEIGHTS)))
            if not np.isfinite(cached):
                raise ValueError(f"patch_mixture: weight is not finite on [0, 2] (p's rounding bound is {cached}); "
                                 "p must be a bounded function")
            object.__setattr__(self, "_rounding_cache", cached)
        return cached

    def lens_mixture(self):
        """The user's p(R) and p_Diffuse, split at ``weight_points`` (p not smooth between them: an unreliable
        error estimate).  Its albedo is one quadrature in R of closed forms (:class:`LensMixtureAlbedo`), where
        the disk integrates f, itself an integral in R, at every point (14 sweep cells took 1,400 s)."""
        return patch.LensMixture(self.weight, self.p_diffuse, self.weight_points)

    def _eval(self, L, V, nl, nv):
        m = np.minimum(projected_distance(L, V), 2.0)
        flat = m.ravel()
        # c(R) = 1/(πR²) below R = 1: cuts geometric from m, where one interval [m, 1] took the driver
        # ~log2(1/m) rounds of bisection per block (the disk's albedo of a mixture: 5.2 s at 2 angles, now 0.6 s)
        graded = flat[:, None] * self.GRADING
        columns = [np.stack([flat, np.maximum(flat, 1.0), np.full_like(flat, 2.0)], axis=1),
                   np.where((graded < 1.0) & (graded > flat[:, None]), graded, np.nan)]
        if self.weight_points:           # the weight's own features inside [m, 2] (none: the same bits)
            points = np.array(self.weight_points)[None, :]
            columns.append(np.where((points > flat[:, None]) & (points < 2.0), points, np.nan))
        bp = np.sort(np.concatenate(columns, axis=1), axis=1)
        # In blocks: one call over very many points would run into the driver's interval budget;
        # atol 1e-300: a tail that underflows (s = 512 far from the patch) must not be refined forever.
        inner = np.concatenate([
            integrate(lambda R, e: self.weight(R) * patch.basic_constant(R), bp[k:k + self.block],
                      rtol=self.rtol, atol=1e-300).value for k in range(0, max(len(bp), 1), self.block)])
        return inner[:flat.size].reshape(m.shape) + self.p_diffuse * patch.basic_constant(2.0)

    #: Points per call of the integration driver in ``_eval``.
    block = 2048
    #: Cuts R = m · 2^k of ``_eval``'s integral in R (those below 1): with 4^k the driver still bisected
    #: 1/R² pieces for 1e-12 (the disk's albedo of a 15-angle group: 34 s, with 2^k 23 s).
    GRADING = 2.0 ** np.arange(1.0, 54.0)

    #: The chi-square tests' mixtures: the exponential profile's weight, rebuilt generically
    #: (:meth:`chi2_example`), so that the sampler runs the tabulated F⁻¹.
    chi2_cases = ({"s": 512}, {"s": 10})

    @classmethod
    def chi2_example(cls, params):
        """The p(R) mixture with the exponential profile's weight (eqs. 4.41, 4.47) of ``params["s"]``:
        the same BRDF as ``patch_exponential``, built generically."""
        return cls.of_profile(patch.ExponentialProfile(params["s"]), rtol=1e-7)

    @classmethod
    def of_profile(cls, profile, rtol=1e-12):
        """The mixture of a profile's weight p(R) and Dirac p_Diffuse at C = C_max (eqs. 4.40, 4.41)."""
        return cls(weight=partial(patch.weight, profile, C=profile.c_max),
                   p_diffuse=patch.diffuse_weight(profile, profile.c_max), rtol=rtol)

    # --- F(R) and F⁻¹ (eq. 4.27) for sampling ---------------------------------------------------
    #: Intervals of the table of F (section 4.4: "stored in a sufficiently large one-dimensional array"),
    #: split further at ``weight_points``.
    cdf_table_size = 1024

    def _table_edges(self):
        """The edges of the table of F: :attr:`cdf_table_size` equal pieces of [0, 2], split at the weight's
        features (``weight_points``): every piece smooth, also the short ones of ``_pdf`` and F⁻¹."""
        edges = np.linspace(0.0, 2.0, self.cdf_table_size + 1)
        return np.unique(np.concatenate([edges, self.weight_points])) if self.weight_points else edges

    def _cdf_table(self):
        cached = self.__dict__.get("_cdf_cache")
        if cached is None:
            edges = self._table_edges()
            pieces = integrate(lambda R, e: self.weight(R), np.stack([edges[:-1], edges[1:]], 1),
                               rtol=self.rtol, atol=1e-15).value
            cached = (edges, np.concatenate([[0.0], np.cumsum(pieces)]))
            object.__setattr__(self, "_cdf_cache", cached)
        return cached

    def _density_table(self):
        """G_i = ∫_{R_i}^2 p(R) c(R) dR on the edges of the table of F (f = G(m) + p_Diffuse/π)."""
        cached = self.__dict__.get("_density_cache")
        if cached is None:
            edges, _ = self._cdf_table()
            pieces = integrate(lambda R, e: self.weight(R) * patch.basic_constant(R),
                               np.stack([edges[:-1], edges[1:]], 1), rtol=self.rtol, atol=1e-15).value
            cached = np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])
            object.__setattr__(self, "_density_cache", cached)
        return cached

    def _pdf(self, L, V, strategy):
        """f cos θ_V / W with f from the table: G(R_{i+1}) + ∫_m^{R_{i+1}} p c (a 21-point Kronrod rule on
        the short piece), the same numbers as ``_eval`` to its tolerance at a fraction of the cost."""
        edges, _ = self._cdf_table()
        table = self._density_table()
        m = np.minimum(projected_distance(L, V), 2.0)
        i = np.clip(np.searchsorted(edges, m, side="right") - 1, 0, edges.size - 2)
        hi = edges[i + 1]
        x = nodes_on(m, hi)
        piece = 0.5 * (hi - m) * ((self.weight(x) * patch.basic_constant(x)) @ KRONROD_WEIGHTS)
        f = self._with_diffuse(table[i + 1] + piece)
        return f * V[..., 2] / self.total_weight

    def _with_diffuse(self, continuous):
        """f from its continuous part: + p_Diffuse c(2) (eq. 4.21)."""
        return continuous + self.p_diffuse * patch.basic_constant(2.0)

    @property
    def total_weight(self) -> float:
        """W = ∫₀² p(R) dR + p_Diffuse (1 for a normalised weight, eq. 4.21)."""
        return float(self._cdf_table()[1][-1] + self.p_diffuse)

    def radius_of_cdf(self, r):
        """R = F⁻¹(r W): the table of F brackets R, three Newton steps on
        F(R) = F(R_i) + ∫_{R_i}^R p (a 21-point Kronrod rule on the short piece) refine it; R = 2
        (the Dirac p_Diffuse) above F(2⁻)."""
        edges, table = self._cdf_table()
        target = np.asarray(r, float) * self.total_weight
        i = np.clip(np.searchsorted(table, target, side="right") - 1, 0, edges.size - 2)
        lo, hi = edges[i], edges[i + 1]
        span = table[i + 1] - table[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            R = np.where(span > 0, lo + (hi - lo) * (target - table[i]) / span, lo)
        for _ in range(3):
            x = nodes_on(lo, R)
            partial = 0.5 * (R - lo) * (self.weight(x) @ KRONROD_WEIGHTS)
            slope = self.weight(R)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(slope > 0, (table[i] + partial - target) / slope, 0.0)
            R = np.clip(R - step, lo, hi)
        return np.where(target >= table[-1], 2.0, R)


@dataclass(frozen=True)
class PatchElliptical(_OnTheBasePlane, BRDF):
    """Anisotropic basic BRDF: c(b) where the elliptic distance ≤ b, else 0  (eqs. 4.32, 4.34, 4.36).

    m = √((B/A · z·u)² + (z·v)²) with z = V_P − L'_P, u = (cos φ_u, sin φ_u, 0) the major axis
    and v ⊥ u the minor axis; ``ratio`` = B/A ≤ 1, ``b`` the minor semi-axis in (0, 2].
    """

    b: float
    ratio: float
    u_angle_deg: float = 0.0
    C: float | None = None
    name = "patch_elliptical"
    # --- what the model says about itself
    chapter = 4                  # eqs. 4.32, 4.34, 4.36
    param_ranges = {"b": Interval(ELLIPSE_B_MIN, 2.0), "ratio": Interval(0.0, 1.0, lo_open=True),
                    "u_angle_deg": Interval(-np.inf, np.inf), "C": positive()}
    #: Figure 4.10's first ellipse; narrowest: Figure 4.11's copper (b = 0.08, B/A = 0.2)
    test_ranges = {"b": log_range(2e-2, 2.0), "ratio": log_range(5e-2, 1.0),
                   "u_angle_deg": linear_range(-180.0, 180.0), "C": log_range(1e-3, 1e3)}
    examples = {"typical": {"b": 0.3, "ratio": 0.5}, "narrowest": {"b": 0.08, "ratio": 0.2}}
    conserves_energy = True      # c(b) = 1/min(π a b, π) (eq. 4.36): a = area(E ∩ disk)/min(π a b, π) ≤ 1

    def __post_init__(self):
        _check_radius("b", self.b)
        if not 0.0 < float(self.ratio) <= 1.0:
            raise ValueError(f"patch_elliptical: ratio B/A must lie in (0, 1], got {self.ratio!r}")
        _default_constant(self, patch.elliptical_constant(self.b, self.ratio))

    # --- the integrand's shape: a jump on an ellipse, not symmetric about the plane of incidence
    lobe = None
    symmetric_about_incidence_plane = False

    def scattering_radius_kinks(self, cos_psi, sin_psi):
        """The jump on the ellipse |(ratio z·u, z·v)| = b (eq. 4.34) along z = r (cos ψ, sin ψ)."""
        phi = np.radians(self.u_angle_deg)
        along_u = cos_psi * np.cos(phi) + sin_psi * np.sin(phi)
        along_v = -cos_psi * np.sin(phi) + sin_psi * np.cos(phi)
        return [self.b / np.hypot(self.ratio * along_u, along_v)]

    def _eval(self, L, V, nl, nv):
        phi = np.radians(self.u_angle_deg)
        zx, zy = L[..., 0] + V[..., 0], L[..., 1] + V[..., 1]     # V_P − L'_P = (L + V)_P
        along_u = np.cos(phi) * zx + np.sin(phi) * zy
        along_v = -np.sin(phi) * zx + np.cos(phi) * zy
        return np.where(np.hypot(self.ratio * along_u, along_v) <= self.b, self.C, 0.0)

    # --- sampling (section 4.5.4: "points are generated inside a circle that has radius b, then a
    # scaling transformation is applied that transforms the circle to the ellipse") --------------
    #: ``"russian_roulette"``: the Russian roulette of eq. 4.18 with the ellipse E(V'_P) in place of
    #: the circle: uniform points in the smaller of E(V'_P) (area π a b, a = b/ratio) and the unit
    #: disk, kept if inside the other; pdf = cos θ_V / min(π a b, π) on E(V'_P) ∩ disk, mass
    #: Area(E(V'_P) ∩ disk) / min(π a b, π), weight C · min(π a b, π) (1 while the ellipse fits).
    strategies = ("russian_roulette", "cosine")
    chi2_cases = ({"b": 0.05, "ratio": 0.25}, {"b": 0.3, "ratio": 0.5})

    def disk_boundaries(self):
        """The ellipse E(V'_P) (semi-axes b and b/ratio about V'_P), where f jumps (eq. 4.32)."""
        return (float(self.b), float(self.b / self.ratio)), (float(self.b), float(self.ratio), float(np.radians(self.u_angle_deg)))

    def _domain_area(self):
        return min(np.pi * self.b * self.b / self.ratio, np.pi)

    def _sample_direction(self, L, u, strategy):
        cx, cy = _mirrored_projection(L)
        X, Y = sampling.uniform_in_circle(0.0, 0.0, 1.0, u[..., 0], u[..., 1])
        if np.pi * self.b * self.b / self.ratio <= np.pi:
            phi = np.radians(self.u_angle_deg)
            a = self.b / self.ratio
            x = cx + a * X * np.cos(phi) - self.b * Y * np.sin(phi)
            y = cy + a * X * np.sin(phi) + self.b * Y * np.cos(phi)
        else:
            x, y = X, Y
        V = sampling.disk_to_direction(x, y)
        inside = self._eval(L, V, L[..., 2], V[..., 2]) > 0
        return np.where((inside & (V[..., 2] > 0))[..., None], V, sampling.REJECTED)

    def _pdf(self, L, V, strategy):
        return np.where(self._eval(L, V, L[..., 2], V[..., 2]) > 0, V[..., 2] / self._domain_area(), 0.0)


# chapter 4's order: the basic patch model (4.2), the mixtures (4.3: general, exponential), the
# elliptical patch (4.4) and the generalized Lambertian (4.5)
for _patch_model in (PatchBasic, PatchMixture, PatchExponential, PatchElliptical, GeneralizedLambertian):
    register(_patch_model)
