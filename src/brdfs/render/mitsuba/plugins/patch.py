"""The patch models of chapter 4 as Mitsuba plugins (Dr.Jit), twins of :mod:`brdfs.physics.models.patch`:

=================================  ===========================================================================
``brdfs_patch_basic``              f*(R) = C [m ≤ R], C = c(R) = 1/(π min(1, R²)) (eqs. 4.2, 4.7); ``R``, ``C``
``brdfs_patch_exponential``        f = C e^{−s m}, C = C_max (eqs. 4.44–4.46); ``s``, ``C``
``brdfs_patch_elliptical``         f = C [|(B/A z·u, z·v)| ≤ b] (eqs. 4.32–4.36); ``b``, ``ratio``, ``u_angle_deg``, ``C``
``brdfs_generalized_lambertian``   f = C min((1 − m²/4)^{−d/2}, ξ(m_clip)) (eqs. 4.58/4.59); ``d``, ``m_clip``, ``C``
=================================  ===========================================================================

m = |(L + V)_P| is the distance on the base plane of V_P from V'_P = −L_P (eq. 4.1); the constants
(C by default, W, the exponential profile's F) are read from the numpy model, the one home of every
number of a model.  Every plugin takes, as :class:`~brdfs.render.mitsuba.plugins._common.ModelBSDF`
does, ``specular`` (a texture, default 1), ``eta`` and ``k`` (a metal: the lobe times the conductor
Fresnel at θ', sin θ' = |L_P − V_P|/2, eqs. 4.52–4.54, as the numpy model's ``fresnel_cosine``),
``diffuse_reflectance`` (a Lambertian lobe beside it, one-sample MIS) and ``strategy``.

Strategies (section 4.2.4; Figure 4.9 renders metal spheres with the first three):

* ``"cosine"``: V from cos θ/π, weight π f (one BRDF evaluation);
* ``"accept_reject"`` (the model's ``"russian_roulette"``; the thesis calls this 0/1 sampling
  "Russian roulette", eqs. 4.18/4.19): a uniform point of C_min — C(V'_P, R) if R < 1, else the unit
  disk — kept if it lies in the other one too, else the sample is rejected (weight 0, no ray).  Kept
  points have pdf = cos θ_V / Area(C_min) and the constant weight C Area(C_min) (1 for the default C),
  no BRDF evaluation.  ``patch_exponential`` first draws R = F⁻¹(u) of its mixture (eq. 4.27; the
  model's ``radius_of_cdf``, tabulated, then Newton on the closed-form F in float64), then the same, with
  weight W = C/C_max; ``patch_elliptical`` uses the ellipse E(V'_P) in place of the circle (pdf
  cos θ_V / min(πab, π), weight C min(πab, π));
* ``"normal"`` (the model's ``"exact"``; the thesis's "normal importance sampling"): a uniform point
  of the lens C(V'_P, R) ∩ unit disk drawn as the thesis draws it, by repeating the accept/reject
  draw until a point is kept ("repeat ... until found").  pdf = cos θ_V / Area(lens) (eq. 4.9), weight
  C Area(lens) = a_R(L) (eq. 4.8; one albedo evaluation).  The loop is a ``dr.while_loop`` of at most
  :data:`MAX_TRIES` tries; the first try uses ``sample2``, the others a PCG32 stream seeded by a TEA
  hash of (sample1, sample2).  A try is kept with probability Area(lens)/Area(C_min) ≥
  :data:`MIN_ACCEPTANCE` (the lens of two unit circles one radius apart, over all R and |L_P| ≤ 1),
  so a lane is still rejected after :data:`MAX_TRIES` tries with probability ≤ (1 − 0.391)^64 < 2⁻⁴⁵:
  such a lane returns weight 0 (it is counted, see below), a relative bias below float32's 2⁻²⁴.
  For ``patch_exponential``, R = F⁻¹(sample1) first; the weight is then W a_R(L), the *conditional*
  weight given R: E[weight g(V)] = ∫ f g dA for every g, so the estimate is exact in expectation
  under any MIS weights that sum to one.  :meth:`PatchExponentialBSDF.pdf` is the marginal density
  of V, Q(m, d) cos θ_V with Q = ∫_m² q(R)/A(d, R) dR + p_Diffuse/π — the model's own ``exact``
  strategy (:meth:`brdfs.physics.models.patch.PatchExponential.exact_area_density`, closed pieces
  and Gauss–Legendre nodes on the general lenses, relative error ≤ 5e-5), twinned by
  :func:`exponential_exact_density`; the pdf serves MIS and the chi-square test, the weight stays
  the exact conditional one, so the quadrature's error cannot bias an image.  With
  ``diffuse_reflectance`` the one-sample mixture over the lobes weighs by f cos/pdf of the mixture.

Groove direction (``patch_elliptical``): the ellipse's major axis u = (cos φ_u, sin φ_u, 0) (φ_u =
``u_angle_deg`` from the shading frame's x = dp/du) is where the highlight stretches; a highlight on
brushed metal stretches *across* the grooves, so the grooves run along v = N × u (for φ_u = 0, along
the shading frame's y, ``si.sh_frame.t``).  The frame is Mitsuba's shading frame through
:func:`~brdfs.render.mitsuba.plugins._common.to_model` / ``from_model`` (the mutation
``FRAME_ROTATED_90`` turns it).

Costs (Figure 4.9's CSV: samples, BRDF evaluations, rays per pixel).  With ``count = true`` the
plugin adds, per call of :meth:`sample` on an active lane, to the UInt32 array ``costs`` =
[samples, tries, evaluations]: one sample; the points drawn (1 for cosine and accept/reject, the
tries of the loop for normal); the BRDF (or albedo) evaluations its weight needs (cosine 1,
accept/reject 0, normal 1), and to ``failures`` the lanes the normal loop gave up on.  Every active
lane of :meth:`~PatchBSDF.eval` and :meth:`~PatchBSDF.eval_pdf` — the evaluations next-event
estimation makes, one per light sample that reaches the surface — adds one evaluation too.
:meth:`PatchBSDF.cost_counts` reads them as a dict (:meth:`PatchBSDF.reset_costs` clears them).
Uniform numbers drawn = 2 × tries (+ 1 per sample for the mixture's R).  A ray is cast per sample
whose weight is not 0 (the integrator counts those).  Without ``count`` nothing is recorded; the
counters are UInt32 (they wrap at 2³²: read and reset them per pass).  Measured (benchmarks/
bench_patch_plugins.py): at s = 2 accept/reject rejects 0 % (θ = 0°) to 45 % (85°) of the samples,
23 % over a sphere seen head-on; the normal loop takes 1.0-2.0 tries (1.40 over the sphere).
"""
from __future__ import annotations

import math

import drjit as dr
import mitsuba as mi
import numpy as np
from scipy.special import gammainc

from brdfs.physics.models import model as numpy_model
from brdfs.physics.models.patch import _exact_pdf_nodes
from brdfs.render.mitsuba.plugins._common import (ModelBSDF, cosine_pdf, from_model, read_float,
                                                  sample_cosine, to_model)

#: Tries of the "normal" loop before a lane gives up (weight 0, counted in ``failures``).
MAX_TRIES = 64
#: The smallest probability that one try of the "normal" loop is kept: Area(lens)/Area(C_min) at
#: R = 1, |L_P| = 1, (2π/3 − √3/2)/π (tests/render/test_patch_plugins.py checks it on a grid).
MIN_ACCEPTANCE = (2.0 * np.pi / 3.0 - np.sqrt(3.0) / 2.0) / np.pi
#: Intervals of the table of the model's F⁻¹ (and its slope: a cubic Hermite start) that brackets R,
#: the safeguarded Newton steps on the closed-form F after it (float64), and the bound on the relative
#: error of R they reach (:func:`exponential_radius64`; tested on s ∈ [1e-2, MAX_S]).
CDF_TABLE = 256
NEWTON_STEPS = 2
RADIUS_RTOL = 2.0 ** -30
#: The largest s the plugin takes: above it the model's bisection table is off by more than RADIUS_RTOL
#: (1.8e-8 at s = 1e10), the bracket misses the root and the bound fails (first near s = 3e9).
MAX_S = 1e9
#: Terms of the series of P(3, x) below x = 1.
SERIES_TERMS = 14
#: The plugin's names of the strategies and the model's names they stand for.
MODEL_STRATEGY = {"cosine": "cosine", "accept_reject": "russian_roulette", "normal": "exact"}
#: The model's names accepted as aliases of the plugin's.
ALIASES = {"russian_roulette": "accept_reject", "exact": "normal"}


# --- geometry of the base plane (Dr.Jit twins of brdfs.physics.sampling / patch_geometry) -------------

def projected_distance(L, V):
    """m(L, V) = |(L + V)_P| (eq. 4.1)."""
    return dr.sqrt(dr.square(L.x + V.x) + dr.square(L.y + V.y))


def uniform_in_circle(cx, cy, radius, u):
    """Uniform points of C((cx, cy), radius): r = radius √u₀, φ = 2π u₁ (:func:`~brdfs.physics.sampling.uniform_in_circle`)."""
    r = radius * dr.sqrt(u.x)
    s, c = dr.sincos(dr.two_pi * u.y)
    return cx + r * c, cy + r * s


def disk_to_direction(x, y):
    """V = (x, y, √(1 − x² − y²)) (eq. 4.17) and whether (x, y) lies inside the unit disk."""
    r2 = x * x + y * y
    return mi.Vector3f(x, y, dr.safe_sqrt(1.0 - r2)), r2 < 1.0


#: 1/(2k + 3)! for k = 0 … 6: the series x³/3! − x⁵/5! + … of x − sin x (the products, not divisions, in the kernel).
_SEGMENT_SERIES = tuple(1.0 / math.factorial(2 * k + 3) for k in range(7))


def _segment(x, sin_x):
    """t − sin t cos t = (x − sin x)/2 (Float64) of x = 2t and its sine (given: the caller has it without
    a call of sin), by its series (Horner) where the difference cancels, |x| < 1/4 (as patch_geometry)."""
    x2 = x * x
    series = 0.0 * x
    for c in reversed(_SEGMENT_SERIES):
        series = c - x2 * series
    series = x * x2 * series
    return 0.5 * dr.select(dr.abs(x) < 0.25, series, x - sin_x)


def lens_area(d, R):
    """Area of C(Q, R) ∩ unit disk, |Q| = d (eqs. 4.9/4.10 with Kahan's Heron formula, as
    :func:`brdfs.physics.patch_geometry.circle_intersection`), computed in float64, returned as Float."""
    return mi.Float(lens_area64(d, R))


def lens_area64(d, R):
    """:func:`lens_area` in float64 (Float64)."""
    d, R = mi.Float64(d), mi.Float64(R)
    one = mi.Float64(1.0)
    a = dr.maximum(dr.maximum(one, R), d)
    c = dr.minimum(dr.minimum(one, R), d)
    b = dr.maximum(dr.minimum(one, R), dr.minimum(dr.maximum(one, R), d))
    prod = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c))
    four_delta = dr.sqrt(dr.maximum(prod, 0.0))
    cos_alpha, cos_beta = 1.0 + (d - R) * (d + R), d * d + (R - 1.0) * (R + 1.0)   # (4Δ, ·) ∝ (sin, cos)
    alpha, beta = dr.atan2(four_delta, cos_alpha), dr.atan2(four_delta, cos_beta)
    nested = d <= dr.abs(1.0 - R)
    apart = d >= 1.0 + R
    special = nested | apart                         # α, β ∈ {0, π}: sin 2α = sin 2β = 0
    half_turn = mi.Float64(math.pi)                  # (a select of two Python floats would be float32)
    alpha = dr.select(apart, 0.0, dr.select(nested, dr.select(R <= 1.0, 0.0, half_turn), alpha))
    beta = dr.select(apart, 0.0, dr.select(nested, dr.select(R <= 1.0, half_turn, 0.0), beta))
    return (_segment(2.0 * alpha, _sin_double(four_delta, cos_alpha, special))
            + R * R * _segment(2.0 * beta, _sin_double(four_delta, cos_beta, special)))


def _sin_double(y, x, special):
    """sin 2φ of φ = atan2(y, x), y ≥ 0: 2xy/(x² + y²), 0 where ``special`` or x = y = 0."""
    h = x * x + y * y
    return dr.select(special | (h == 0.0), 0.0, 2.0 * x * y / dr.select(h == 0.0, 1.0, h))


def fresnel_cosine_prime(L, V):
    """cos θ', sin θ' = |L_P − V_P|/2 (eqs. 4.52/4.53; :func:`brdfs.physics.fresnel.cos_theta_prime`)."""
    half2 = 0.25 * (dr.square(L.x - V.x) + dr.square(L.y - V.y))
    return dr.safe_sqrt(dr.clip(1.0 - half2, 0.0, 1.0))


def _rng_after(sample1, sample2):
    """A PCG32 stream per lane, seeded by a TEA hash of the bits of (sample1, sample2)."""
    bits = (dr.reinterpret_array(mi.UInt32, sample2.x) ^ dr.reinterpret_array(mi.UInt32, sample1),
            dr.reinterpret_array(mi.UInt32, sample2.y))
    v0, v1 = mi.sample_tea_32(bits[0], bits[1], 4)
    return mi.PCG32(initstate=mi.UInt64(v0), initseq=mi.UInt64(v1))


def c_min_point(cx, cy, R, u):
    """The accept/reject try (eqs. 4.18/4.19, :func:`brdfs.physics.sampling.russian_roulette_point`):
    a uniform point of C_min (C(V'_P, R) for R < 1, else the unit disk) and whether it lies in both."""
    small = R < 1.0
    x, y = uniform_in_circle(dr.select(small, cx, 0.0), dr.select(small, cy, 0.0), dr.minimum(R, 1.0), u)
    inside = (x * x + y * y < 1.0) & (dr.sqrt(dr.square(x - cx) + dr.square(y - cy)) <= R)
    return x, y, inside


def lens_point_by_rejection(cx, cy, R, sample1, sample2, active):
    """The thesis's "repeat ... until found" (section 4.2.4): accept/reject tries until one is kept,
    at most :data:`MAX_TRIES` (module docstring).  Returns (x, y, kept, tries)."""
    x, y, kept = c_min_point(cx, cy, R, sample2)
    tries = dr.select(active, mi.UInt32(1), mi.UInt32(0))
    rng = _rng_after(sample1, sample2)

    def pending(x, y, kept, tries, rng):
        return active & ~kept & (tries < MAX_TRIES)

    def another_try(x, y, kept, tries, rng):
        u = mi.Point2f(rng.next_float32(), rng.next_float32())
        x, y, kept = c_min_point(cx, cy, R, u)
        return x, y, kept, tries + 1, rng

    x, y, kept, tries, rng = dr.while_loop((x, y, kept, tries, rng), pending, another_try)
    return x, y, kept & active, tries


# --- the exponential mixture's F and F⁻¹ (eq. 4.27; ExponentialProfile.cdf, inverse_cdf) -------------

def _p3_series(x):
    """Σ_{k≥3} x^k/k! (Float64, :data:`SERIES_TERMS` terms by Horner's scheme): e^{−x} times it is
    P(3, x) below x = 1, where the closed form 1 − e^{−x}(1 + x + x²/2) cancels."""
    acc = 0.0 * x + 1.0
    for k in range(3 + SERIES_TERMS - 1, 3, -1):
        acc = 1.0 + acc * x * (1.0 / k)
    return x * x * x * (1.0 / 6.0) * acc


def exponential_cdf_and_density(R, s, norm, ends):
    """(F(R), p(R)/W = dF/dR) of the mixture (Float64, R ∈ [0, 2]; ``norm`` = P(2, s), ``ends`` =
    (P(3, s)/P(2, s), e^{−s}), the kernel's constants) with one exponential:
    F = P(3, sR)/P(2, s) for R ≤ 1, P(3, s)/P(2, s) + s²(e^{−s} − e^{−sR})/(2 P(2, s)) above;
    dF/dR = s³ min(R, 1)² e^{−sR}/(2 P(2, s))."""
    inner_end, e_s = ends
    x = s * dr.minimum(R, 1.0)
    E = dr.exp(-s * R)
    p3 = dr.select(x < 1.0, E * _p3_series(x), 1.0 - E * (1.0 + x + 0.5 * x * x))
    cdf = dr.select(R <= 1.0, p3 / norm, inner_end + s * s * (e_s - E) / (2.0 * norm))
    return cdf, s * s * s * dr.square(dr.minimum(R, 1.0)) * E / (2.0 * norm)


def _p3(x):
    """P(3, x) = 1 − e^{−x}(1 + x + x²/2), the regularised incomplete gamma function (Float64), by
    :func:`_p3_series` below x = 1."""
    e = dr.exp(-x)
    return dr.select(x < 1.0, e * _p3_series(x), 1.0 - e * (1.0 + x + 0.5 * x * x))


def exponential_cdf(R, s, norm):
    """F(R) = P(3, sR)/P(2, s) for R ≤ 1, + s²(e^{−s} − e^{−sR})/(2 P(2, s)) above (Float64; ``norm`` = P(2, s))."""
    return exponential_cdf_and_density(R, s, norm, (_p3(s) / norm, dr.exp(-s)))[0]


def radius_position(u, p_diffuse):
    """The table's coordinate N t of u < 1 − p_Diffuse: r = u/(1 − p_Diffuse) = 1 − (1 − t³)⁴ (Float64),
    t³ = r/((1 + q)(1 + q²)), q = (1 − r)^{1/4}, which keeps t's relative precision as r → 0."""
    r = u / (1.0 - p_diffuse)
    q = dr.sqrt(dr.sqrt(dr.maximum(1.0 - r, 0.0)))
    return CDF_TABLE * dr.cbrt(dr.maximum(r, 0.0) / ((1.0 + q) * (1.0 + q * q)))


def exponential_radius64(u, s, norm, p_diffuse, ends, table, slopes):
    """R = F⁻¹(u) (eq. 4.27) in float64, R = 2 (the Dirac p_Diffuse) for u ≥ 1 − p_Diffuse.

    ``table`` and ``slopes`` (Float64, :data:`CDF_TABLE` + 1 entries, :func:`radius_table`) hold the
    model's own F⁻¹ (``radius_of_cdf``) of the continuous part and its derivative in t at
    r = u/(1 − p_Diffuse) = 1 − (1 − t_i³)⁴, t_i = i/N: dense toward r = 0, where R ∝ r^{1/3} (then
    linear in t), and toward r = 1.  The cubic Hermite interpolant in t starts R (relative error
    ≤ 1e-3 over s ∈ [1e-2, 1e5], ≤ 4e-6 for s ≤ 6; its worst bins are the kink of p at R = 1 and
    the exponential tail of a narrow profile), and :data:`NEWTON_STEPS` Newton steps on the
    closed-form F refine it, kept inside the table's bracket (a step that leaves it bisects):
    |R − F⁻¹(u)| ≤ :data:`RADIUS_RTOL` R (tests/render/test_patch_plugins.py, at 10⁵ u per s)."""
    u = mi.Float64(u)
    position = radius_position(u, p_diffuse)
    i = mi.UInt32(dr.clip(dr.floor(position), 0, CDF_TABLE - 1))
    lo, hi = dr.gather(mi.Float64, table, i), dr.gather(mi.Float64, table, i + 1)
    dlo, dhi = dr.gather(mi.Float64, slopes, i), dr.gather(mi.Float64, slopes, i + 1)
    x = dr.clip(position - mi.Float64(i), 0.0, 1.0)
    y = 1.0 - x
    R = (y * y * ((1.0 + 2.0 * x) * lo + x * dlo / CDF_TABLE)
         + x * x * ((3.0 - 2.0 * x) * hi - y * dhi / CDF_TABLE))
    R = dr.clip(R, lo, hi)
    for _ in range(NEWTON_STEPS):
        cdf, density = exponential_cdf_and_density(R, s, norm, ends)
        excess = cdf - u
        lo, hi = dr.select(excess < 0, R, lo), dr.select(excess < 0, hi, R)
        newton = R - excess / dr.maximum(density, 1e-300)
        R = dr.select((newton >= lo) & (newton <= hi), newton, 0.5 * (lo + hi))
    return dr.select(u >= 1.0 - p_diffuse, 2.0, dr.select(u > 0.0, R, 0.0))


def radius_table(brdf, p_diffuse):
    """(R_i, dR/dt at t_i), i = 0 … :data:`CDF_TABLE`, of :func:`exponential_radius64` for the numpy
    model ``brdf`` (``patch_exponential``) whose Dirac at R = 2 weighs ``p_diffuse`` (zeros where it is
    all the weight): R_i = ``brdf.radius_of_cdf`` (bisection on the closed-form F),
    dR/dt = (dr/dt)(1 − p_Diffuse)/F'(R) = 12 t²(1 − t³)³(1 − p_Diffuse)/F'(R), its limit
    (24 P(2, s)(1 − p_Diffuse))^{1/3}/s at t = 0 and 0 at t = 1 (numpy, float64)."""
    t = np.linspace(0.0, 1.0, CDF_TABLE + 1)
    s = float(brdf.s)
    if p_diffuse >= 1.0 or s == 0.0:
        return np.zeros_like(t), np.zeros_like(t)
    norm = float(gammainc(2.0, s))
    r = 1.0 - (1.0 - t ** 3) ** 4
    R = np.where(r < 1.0, brdf.radius_of_cdf(np.minimum(r * (1.0 - p_diffuse), 1.0)), 2.0)
    R[-1] = 2.0
    density = s ** 3 * np.minimum(R, 1.0) ** 2 * np.exp(-s * R) / (2.0 * norm)
    with np.errstate(divide="ignore", invalid="ignore"):
        slopes = np.where(density > 0, 12.0 * t * t * (1.0 - t ** 3) ** 3 * (1.0 - p_diffuse) / density, 0.0)
    slopes[0] = (24.0 * norm * (1.0 - p_diffuse)) ** (1.0 / 3.0) / s
    slopes[-1] = 0.0
    return R, slopes


def exponential_exact_density(d, m, s, norm, p_diffuse):
    """Q(m, d) = ∫_m² q(R)/A(d, R) dR + p_Diffuse/π, the density per unit area of the base plane of the
    "normal" sampler of the mixture (Float64 in, Float64 out): the twin of
    :meth:`brdfs.physics.models.patch.PatchExponential.exact_area_density` — the same closed pieces
    and the same Gauss–Legendre nodes (``EXACT_PDF_NODES`` per piece, read from the model's module),
    summed by a ``dr.while_loop`` over the nodes of both pieces (one loop body to compile)."""
    d, m = mi.Float64(d), mi.Float64(m)
    scale = s * s / (2.0 * norm)
    inside = dr.select(m < 1.0 - d, scale * (dr.exp(-s * m) - dr.exp(-s * (1.0 - d))) / dr.pi, 0.0)
    covers = (1.0 - p_diffuse - exponential_cdf(dr.clip(dr.maximum(m, 1.0 + d), 0.0, 2.0), s, norm)) / dr.pi
    t, weights = _exact_pdf_nodes()
    count = len(t)
    smooth = mi.Float64(np.tile(t * t * (3.0 - 2.0 * t), 2))
    factor = mi.Float64(np.tile(weights * 6.0 * t * (1.0 - t), 2))
    ends = []                                        # (a, b, w_a, w_b) of [1 − d, 1] and [1, 1 + d]
    for lo, hi in ((1.0 - d, mi.Float64(1.0)), (mi.Float64(1.0), dr.minimum(1.0 + d, 2.0))):
        a = dr.maximum(lo, m)
        b = dr.maximum(hi, a)
        ends.append((a, b, dr.exp(-s * a), dr.exp(-s * b)))
    k = mi.UInt32(0)
    total = inside + covers + p_diffuse / dr.pi

    def pending(k, total):
        return k < 2 * count

    def add_node(k, total):
        first = k < count
        a, b, wa, wb = (dr.select(first, x, y) for x, y in zip(*ends))
        w = wa + (wb - wa) * dr.gather(mi.Float64, smooth, k)
        R = dr.clip(-dr.log(w) / s, a, b)
        area = lens_area64(d, R)
        h = dr.select(area > 0.0, dr.square(dr.minimum(R, 1.0)) / area, 0.0)
        return k + 1, total + scale * (wa - wb) * dr.gather(mi.Float64, factor, k) * h

    k, total = dr.while_loop((k, total), pending, add_node)
    return total


# --- the plugins -----------------------------------------------------------------------------------------

class PatchBSDF(ModelBSDF):
    """What the patch plugins share: parameters read into the numpy model (its constants), the
    strategy, θ' for metals, the costs counter, and :meth:`sample` with each strategy's own weight.

    Subclasses declare ``name`` (the model's), ``parameters`` (its parameter names) and implement
    :meth:`lobe_eval` and, per own strategy, :meth:`draw` and :meth:`own_pdf`.
    """

    strategies = ("cosine",)
    parameters: tuple[str, ...] = ()
    extra_parameters = {"count": ("boolean", "false", "count the samplers' tries and failures (the costs of "
                                                      "Figure 4.9)")}

    def __init__(self, props):
        if "strategy" in props:
            requested = props["strategy"]
            props["strategy"] = ALIASES.get(requested, requested)
        super().__init__(props)
        params = {name: read_float(props, name) for name in self.parameters if name in props}
        try:
            self.brdf = numpy_model(self.name, **params)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{props.plugin_name()}: {exc}") from None
        self.count = bool(props.get("count", False))
        self.costs = dr.zeros(mi.UInt32, 3)
        self.failures = dr.zeros(mi.UInt32, 1)
        self.C = dr.opaque(mi.Float, self.brdf.C)

    # --- the model's numbers -------------------------------------------------------------------------
    def fresnel_cosine(self, L, V):
        """θ' of eqs. 4.53/4.54, where the patch models' metals read F."""
        return fresnel_cosine_prime(L, V)

    def lobe_pdf(self, L, V, active):
        if self.strategy == "cosine":
            return cosine_pdf(V)
        return self.own_pdf(L, V, active)

    def draw(self, L, sample1, sample2, active):
        """(V, kept, tries, weight of the lobe without its factor or None for f cos/pdf, evaluations)."""
        V = sample_cosine(sample2)
        return V, active, mi.UInt32(1), None, 1

    # --- costs ------------------------------------------------------------------------------------------
    def _count(self, active, tries, evaluations, kept):
        if not self.count:
            return
        zero = dr.zeros(mi.UInt32, dr.width(active))
        per_lane = (1, tries, evaluations)
        for slot, value in enumerate(per_lane):
            dr.scatter_reduce(dr.ReduceOp.Add, self.costs, dr.select(active, mi.UInt32(value), 0), zero + slot)
        gave_up = active & ~kept & (mi.UInt32(tries) >= MAX_TRIES)
        dr.scatter_reduce(dr.ReduceOp.Add, self.failures, dr.select(gave_up, mi.UInt32(1), 0), zero)

    def eval(self, ctx, si, wo, active=True):
        self._count_evaluations(active, wo)
        return super().eval(ctx, si, wo, active)

    def eval_pdf(self, ctx, si, wo, active=True):
        self._count_evaluations(active, wo)
        return super().eval_pdf(ctx, si, wo, active)

    def _count_evaluations(self, active, wo):
        """One BRDF evaluation per active lane of :meth:`eval` / :meth:`eval_pdf` (next-event estimation)."""
        if not self.count:
            return
        lanes = dr.zeros(mi.UInt32, dr.width(wo))
        active = mi.Bool(active) & (lanes == 0)          # (broadcast to the lanes of wo)
        dr.scatter_reduce(dr.ReduceOp.Add, self.costs, dr.select(active, mi.UInt32(1), 0), lanes + 2)

    def cost_counts(self) -> dict:
        """``{"samples", "tries", "evaluations", "failures"}`` counted since the last :meth:`reset_costs`."""
        dr.eval(self.costs, self.failures)
        samples, tries, evaluations = (int(v) for v in self.costs.numpy())
        return {"samples": samples, "tries": tries, "evaluations": evaluations,
                "failures": int(self.failures.numpy()[0])}

    def reset_costs(self) -> None:
        self.costs = dr.zeros(mi.UInt32, 3)
        self.failures = dr.zeros(mi.UInt32, 1)

    # --- Mitsuba's sample --------------------------------------------------------------------------------
    def sample(self, ctx, si, sample1, sample2, active=True):
        wi_m = to_model(si.wi)
        active = mi.Bool(active) & (wi_m.z > 0) & (sample1 >= 0.0)    # (the width of the samples)
        u1 = mi.Float(sample1)
        diffuse = mi.Bool(False)
        if self.diffuse is not None:
            p_d = self._diffuse_probability(si, active)
            diffuse = sample1 < p_d
            u1 = dr.clip(dr.select(diffuse, 0.0, (sample1 - p_d) / dr.maximum(1.0 - p_d, 1e-30)), 0.0, 1.0 - 2 ** -24)
        lobe = active & ~diffuse
        if self.strategy == "cosine":
            V, kept, tries, lobe_weight, evaluations = PatchBSDF.draw(self, wi_m, u1, sample2, lobe)
        else:
            V, kept, tries, lobe_weight, evaluations = self.draw(wi_m, u1, sample2, lobe)
        self._count(lobe, tries, evaluations, kept)
        if self.diffuse is not None:
            V = dr.select(diffuse, sample_cosine(sample2), V)
            kept = dr.select(diffuse, True, kept)
            lobe_weight = None
        V = dr.normalize(V)
        # the lobe's weight is the exact conditional one, so bs.pdf may be the MIS density; only a mixture
        # with the diffuse lobe divides by the exact density (f cos / pdf below)
        mis_pdf = self._pdf(si, wi_m, V, active, mis=True)
        pdf = mis_pdf if self.diffuse is None else self._pdf(si, wi_m, V, active)
        ok = active & kept & (V.z > 0) & (pdf > 0)
        bs = dr.zeros(mi.BSDFSample3f)
        bs.wo = dr.select(ok, from_model(V), mi.Vector3f(0.0, 0.0, -1.0))
        bs.pdf = dr.select(ok, mis_pdf, 0.0)
        bs.eta = 1.0
        bs.sampled_type = dr.select(diffuse, mi.UInt32(int(mi.BSDFFlags.DiffuseReflection)),
                                    mi.UInt32(int(self.lobe_flag)))
        bs.sampled_component = dr.select(diffuse, mi.UInt32(1), mi.UInt32(0))
        if lobe_weight is None:
            weight = self._value(si, V, wi_m, ok) * V.z / dr.select(ok, pdf, 1.0)
        else:
            weight = self._specular_factor(si, V, wi_m, ok) * lobe_weight
        return bs, dr.select(ok, weight, 0.0)

    def describe(self):
        return {**self.brdf.params, "strategy": self.strategy}


class PatchBasicBSDF(PatchBSDF):
    """The basic patch BRDF f*(R) = C [m ≤ R] (eq. 4.2), C = c(R) (eq. 4.7) by default; strategies
    ``normal`` (default), ``accept_reject``, ``cosine`` (module docstring)."""

    name = "patch_basic"
    parameters = ("R", "C")
    strategies = ("normal", "accept_reject", "cosine")

    def __init__(self, props):
        super().__init__(props)
        self.R = dr.opaque(mi.Float, self.brdf.R)
        self.c_min_area = dr.opaque(mi.Float, np.pi * min(self.brdf.R, 1.0) ** 2)

    def lobe_eval(self, L, V, active):
        return dr.select(projected_distance(L, V) <= self.R, self.C, 0.0)

    def own_pdf(self, L, V, active):
        inside = projected_distance(L, V) <= self.R
        if self.strategy == "normal":
            area = lens_area(dr.sqrt(L.x * L.x + L.y * L.y), self.R)
        else:
            area = self.c_min_area
        return dr.select(inside, V.z / area, 0.0)

    def draw(self, L, sample1, sample2, active):
        cx, cy = -L.x, -L.y
        if self.strategy == "normal":
            x, y, kept, tries = lens_point_by_rejection(cx, cy, self.R, sample1, sample2, active)
            V, in_disk = disk_to_direction(x, y)
            weight = self.C * lens_area(dr.sqrt(L.x * L.x + L.y * L.y), self.R)
            return V, kept & in_disk, tries, weight, 1
        x, y, kept = c_min_point(cx, cy, self.R, sample2)
        V, in_disk = disk_to_direction(x, y)
        return V, kept & in_disk & active, mi.UInt32(1), self.C * self.c_min_area, 0


class PatchExponentialBSDF(PatchBSDF):
    """f = C e^{−s m} (eqs. 4.44/4.46), C = C_max (eq. 4.45) by default: a mixture of basic BRDFs,
    sampled by R = F⁻¹(u) and then the basic BRDF's strategy; ``accept_reject`` (default), ``normal``,
    ``cosine`` (module docstring)."""

    name = "patch_exponential"
    parameters = ("s", "C")
    strategies = ("accept_reject", "normal", "cosine")

    #: ``mis_density``: "exact" (default), the marginal density of ``normal`` sampling in the MIS
    #: weights; "lobe", f cos θ_V / W (the accept/reject density, of the same shape) instead.
    MIS_DENSITIES = ("exact", "lobe")
    extra_parameters = {**PatchBSDF.extra_parameters,
                        "mis_density": ("string", "exact", "``exact``: the marginal density of ``normal`` sampling "
                                                           "in the MIS weights; ``lobe``: f cos θ_V / W instead")}

    def __init__(self, props):
        mis_density = props.get("mis_density", "exact")
        super().__init__(props)
        if mis_density not in self.MIS_DENSITIES:
            raise ValueError(f"{props.plugin_name()}: mis_density = {mis_density!r}; choose one of {self.MIS_DENSITIES}")
        self.mis_density = mis_density
        s = float(self.brdf.s)
        if s > MAX_S:
            raise ValueError(f"{props.plugin_name()}: s = {s!r}: at most {MAX_S:g} (the radius sampler's error "
                             f"bound holds up to it; the lobe is then narrower than a float32 direction)")
        profile_c_max = self.brdf.C / self.brdf.total_weight
        self.s = dr.opaque(mi.Float, s)
        self.s64 = dr.opaque(mi.Float64, s)
        self.norm = dr.opaque(mi.Float64, float(gammainc(2.0, s)) if s > 0 else 1.0)
        p_diffuse = float(profile_c_max * np.pi * np.exp(-2.0 * s))
        self.p_diffuse = dr.opaque(mi.Float64, p_diffuse)
        self.W = dr.opaque(mi.Float, float(self.brdf.total_weight))
        self.cdf_ends = (dr.opaque(mi.Float64, float(gammainc(3.0, s) / gammainc(2.0, s)) if s > 0 else 0.0),
                         dr.opaque(mi.Float64, float(np.exp(-s))))
        self.radius_table, self.radius_slopes = (mi.Float64(a) for a in radius_table(self.brdf, p_diffuse))

    def lobe_eval(self, L, V, active):
        return self.C * dr.exp(-self.s * projected_distance(L, V))

    def own_pdf(self, L, V, active):
        """``accept_reject``: f cos θ_V / W (the model's ``russian_roulette`` pdf); ``normal``: Q(m, d) cos θ_V
        (the model's ``exact`` pdf, :func:`exponential_exact_density`; cos θ_V / π where s = 0)."""
        if self.strategy != "normal":
            return self.lobe_eval(L, V, active) * V.z / self.W
        if self.brdf.s == 0:
            return V.z / dr.pi
        d = dr.sqrt(mi.Float64(L.x * L.x + L.y * L.y))
        Q = exponential_exact_density(d, mi.Float64(projected_distance(L, V)), self.s64, self.norm, self.p_diffuse)
        return mi.Float(Q) * V.z

    def mis_lobe_pdf(self, L, V, active):
        """With ``mis_density = "lobe"`` and ``normal`` sampling: f cos θ_V / W, the accept/reject
        density, in place of the marginal Q(m, d) cos θ_V, whose Gauss–Legendre nodes cost twice the
        rest of a path (Fig. 4.16 at 240 spp: 114.7 CPU-s with them in ``sample``'s check, 50.9
        without, the same image).  :meth:`pdf` stays the exact density (the chi-square tests)."""
        if self.mis_density == "lobe" and self.strategy == "normal":
            return self.lobe_eval(L, V, active) * V.z / self.W
        return self.lobe_pdf(L, V, active)

    def radius(self, u):
        """R = F⁻¹(u) of the mixture's weight (eq. 4.27), Float (:func:`exponential_radius64`)."""
        return mi.Float(self.radius64(u))

    def radius64(self, u):
        """R = F⁻¹(u) in float64 (:func:`exponential_radius64`)."""
        return exponential_radius64(u, self.s64, self.norm, self.p_diffuse, self.cdf_ends, self.radius_table,
                                    self.radius_slopes)

    def draw(self, L, sample1, sample2, active):
        cx, cy = -L.x, -L.y
        R = self.radius(sample1)
        if self.strategy == "normal":
            x, y, kept, tries = lens_point_by_rejection(cx, cy, R, sample1, sample2, active)
            V, in_disk = disk_to_direction(x, y)
            a_R = lens_area(dr.sqrt(L.x * L.x + L.y * L.y), R) / (dr.pi * dr.minimum(R * R, 1.0))
            return V, kept & in_disk, tries, self.W * a_R, 1
        x, y, kept = c_min_point(cx, cy, R, sample2)
        V, in_disk = disk_to_direction(x, y)
        return V, kept & in_disk & active, mi.UInt32(1), mi.Float(self.W), 0


class PatchEllipticalBSDF(PatchBSDF):
    """f = C where the elliptic distance |(B/A z·u, z·v)| ≤ b, z = (L + V)_P (eqs. 4.32, 4.34, 4.36);
    ``accept_reject`` (default; section 4.5.4: points of a circle scaled to the ellipse), ``cosine``.
    The major axis u is at ``u_angle_deg`` from the shading frame's x; grooves run along v (module docstring)."""

    name = "patch_elliptical"
    parameters = ("b", "ratio", "u_angle_deg", "C")
    strategies = ("accept_reject", "cosine")

    def __init__(self, props):
        super().__init__(props)
        b, ratio = float(self.brdf.b), float(self.brdf.ratio)
        phi = np.radians(float(self.brdf.u_angle_deg))
        self.b = dr.opaque(mi.Float, b)
        self.ratio = dr.opaque(mi.Float, ratio)
        self.major = dr.opaque(mi.Float, b / ratio)
        self.cos_u, self.sin_u = dr.opaque(mi.Float, np.cos(phi)), dr.opaque(mi.Float, np.sin(phi))
        self.fits = np.pi * b * b / ratio <= np.pi
        self.domain_area = dr.opaque(mi.Float, min(np.pi * b * b / ratio, np.pi))

    def _inside(self, L, V):
        zx, zy = L.x + V.x, L.y + V.y
        along_u = self.cos_u * zx + self.sin_u * zy
        along_v = -self.sin_u * zx + self.cos_u * zy
        return dr.sqrt(dr.square(self.ratio * along_u) + dr.square(along_v)) <= self.b

    def lobe_eval(self, L, V, active):
        return dr.select(self._inside(L, V), self.C, 0.0)

    def own_pdf(self, L, V, active):
        return dr.select(self._inside(L, V), V.z / self.domain_area, 0.0)

    def draw(self, L, sample1, sample2, active):
        X, Y = uniform_in_circle(0.0, 0.0, 1.0, sample2)
        if self.fits:
            x = -L.x + self.major * X * self.cos_u - self.b * Y * self.sin_u
            y = -L.y + self.major * X * self.sin_u + self.b * Y * self.cos_u
        else:
            x, y = X, Y
        V, in_disk = disk_to_direction(x, y)
        kept = active & in_disk & self._inside(L, V) & (V.z > 0)
        return V, kept, mi.UInt32(1), self.C * self.domain_area, 0


class GeneralizedLambertianBSDF(PatchBSDF):
    """f = C min((1 − (m/2)²)^{−d/2}, ξ(m_clip)) (eqs. 4.58/4.59), C = 1/max a by default; sampled with
    the cosine distribution and the weight π f (section 4.7.4: its p(R) is negative, no mixture to sample)."""

    name = "generalized_lambertian"
    parameters = ("d", "m_clip", "C")
    strategies = ("cosine",)

    def __init__(self, props):
        super().__init__(props)
        d, m_clip = float(self.brdf.d), float(self.brdf.m_clip)
        self.half_d = dr.opaque(mi.Float, 0.5 * d)
        self.m_clip = dr.opaque(mi.Float, m_clip)
        self.xi_max = dr.opaque(mi.Float, float((1.0 - 0.25 * m_clip * m_clip) ** (-0.5 * d)))

    def lobe_eval(self, L, V, active):
        m = projected_distance(L, V)
        w = dr.maximum(1.0 - 0.25 * m * m, 1e-30)
        xi = dr.select(m < self.m_clip, dr.exp(-self.half_d * dr.log(w)), self.xi_max)
        return self.C * xi


PLUGINS = {cls.name: cls for cls in (PatchBasicBSDF, PatchExponentialBSDF, PatchEllipticalBSDF,
                                     GeneralizedLambertianBSDF)}
