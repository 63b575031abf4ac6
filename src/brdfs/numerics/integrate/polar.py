"""Albedo of a microfacet model whose masking depends on the polar angles only: one dimension, in θ_V.

A model declares ``half_vector_factors() = (distribution, S)`` when its BRDF is

    f(L, V) = D(H) S(N·L, N·V)                                            (1)

with D the distribution of microfacet normals (a function of the half vector's tilt δ alone) and S
anything of the two polar angles: Smith's G2/(4 N·L N·V) of the GGX and Beckmann models
(Walter et al. 2007, eq. 20; RTR4 eq. 9.34, F = 1), Cook–Torrance with the thesis's Smith G
(eq. 2.9 with eq. 1.38).  Then, with V at polar angle θ_V and azimuth φ about N (L at φ = 0),

    a(θ_L) = ∫₀^{π/2} 2 sin θ_V cos θ_V S(cos θ_L, cos θ_V) Φ(θ_V) dθ_V,   Φ = ∫₀^π D dφ,

and Φ is known in closed form: h = L + V has h_z = cos θ_L + cos θ_V and
|h_xy|² = sin²θ_L + sin²θ_V + 2 sin θ_L sin θ_V cos φ, so

    tan²δ = |h_xy|²/h_z² = q + b (1 + cos φ),  q = tan²((θ_L − θ_V)/2),  b = 2 sin θ_L sin θ_V / h_z²,

both formed without cancellation (q is the tilt at the mirror azimuth φ = π), and the distribution
integrates D over φ (``azimuthal_integral(q, b)``: rational for GGX, Kummer functions for Beckmann).
Every V with θ_V < π/2 lies above the horizon for every φ, so no cut in φ is needed.

The radial integrand is smooth in θ_V (in cos θ_V it would carry √(1 − cos θ_V) through sin θ_V);
its scales are the lobe around the mirror angle θ_V = θ_L, of width 2 arctan α, and the Smith term's
turn at cos θ_V ~ α (the model's ``nv_levels``): both become breakpoints.  Near grazing incidence a
third scale appears, cos θ_V ~ cos θ_L = μ_L: S is symmetric in its two cosines (reciprocity), so
it turns in μ_V where it turns in μ_L.  Smith's height-correlated G2/(4 μ_L μ_V) =
1/(4 (μ_L μ_V + μ_V λ(μ_L) + μ_L λ(μ_V))) ≈ 1/(4 λ(0) (μ_L + μ_V)) for μ_L, μ_V ≪ α (λ(0) = α/2
for GGX) makes the integrand ≈ c μ_V/(μ_V + μ_L) toward the horizon: a layer of width μ_L in μ_V
whose μ_L/μ_V tail takes c μ_L ln(α/μ_L) from the albedo, most of 1 − a.  At θ_L = 90° − 1e-9°
(GGX, α = 0.3, μ_L = 1.7e-11) the nearest node of the interval that ends at the mirror angle lay
3e-4 rad, 10⁷ layer widths, from it: the first pass missed half of 1 − a and Σ|K − G| saw nothing
(the sweep's GGX cells, 2–4× under-reported at every rtol).
Levels μ_V = μ_L · 8^k between μ_L and α (:data:`GRAZING_GRADING`) make every piece an eightfold
range of μ_V, on which the rule resolves the layer and its tail.  The adaptive
Gauss–Kronrod driver reports the Gauss sum with SAFETY Σ|K − G| plus the kernel's rounding bound.
``evaluations`` counts the kernel's nodes.  Shares no code with :mod:`.hemisphere` or :mod:`.disk`:
the tests check it against both and against nested ``scipy.integrate.quad``.

A single angle of a distribution and masking that :mod:`.polar_compiled` knows (GGX and Beckmann with
Smith's masking, Cook–Torrance with the thesis's Smith G, by the factors the model declares) runs
compiled where numba is available
(:func:`brdfs.core.compiled.available`): breakpoints, integrand and driver in one call, a replica of
the numpy path below, which stays the reference and the fallback.
"""
from __future__ import annotations

import functools

import numpy as np

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import FILL_CHEAP, Estimate, NodeValues, estimate_of_one, integrate, number_of_one
from brdfs.numerics.integrate.grouping import first_of_model, indices_by_model

_EPS = np.finfo(float).eps
#: Multiples of the lobe's width 2 arctan α on either side of the mirror angle, cut as breakpoints.
#: Beyond 4 widths Beckmann's tail still carries e^(−16) ~ 1e-7 of the lobe: left to one interval
#: [0, θ_L − 4 w] that it reaches only at its end, the Gauss rule missed it whole and Kronrod half
#: (Cook–Torrance with Smith's G, m = 0.005, 90° − 1e-5: 1.02× under-reported at rtol 1e-4); at
#: 16 widths it is e^(−256).
LOBE_WIDTHS = (0.25, 1.0, 4.0, 16.0)
#: Ratio of the graded levels μ_V = μ_L · r^k (k ≥ 1, below α) toward the horizon (module docstring).
GRAZING_GRADING = 8.0
#: Relative rounding of S (Smith's Λ: square roots, erfc and exp of a few rounded cosines), in ulps.
S_ROUNDING = 32.0


def supports(model) -> bool:
    """Whether ``model`` factors as eq. (1): it declares ``half_vector_factors()`` (None by default)."""
    return model.half_vector_factors() is not None


def albedo_many(models, theta_deg, rtol=1e-10, atol=1e-14) -> Estimate:
    """Albedo of ``models[i]`` at ``theta_deg[i]`` (every model :func:`supports`), in one adaptive run."""
    models = list(models)
    theta_deg = np.asarray(theta_deg, float).ravel()
    if len(models) != theta_deg.size:
        raise ValueError("albedo_many needs one model per angle")
    if len(models) == 1:
        return _albedo_one(models[0], theta_deg, rtol, atol)
    bad = [m for m in models if not supports(m)]
    if bad:
        raise ValueError(f"the polar route needs a model that declares half_vector_factors, got {bad[0].name!r}")
    theta_l = np.radians(theta_deg)
    groups = indices_by_model(models)
    if len(groups) == 1:                         # one model (a single angle, a curve): no masks
        factors = models[0].half_vector_factors()

        def integrand(theta_v, elem):
            value, rounding = radial_integrand(*factors, theta_l[elem, None], theta_v)
            return NodeValues(value, value, rounding)
    else:
        index = first_of_model(models)
        by_first = {members[0]: models[members[0]].half_vector_factors() for members in groups}

        def integrand(theta_v, elem):
            value, rounding = np.empty_like(theta_v), np.empty_like(theta_v)
            for k in np.unique(index[elem]):
                rows = index[elem] == k
                value[rows], rounding[rows] = radial_integrand(*by_first[k], theta_l[elem[rows], None], theta_v[rows])
            return NodeValues(value, value, rounding)

    return integrate(integrand, breakpoints(models, theta_l, groups), rtol=rtol, atol=atol, fill=FILL_CHEAP)


def _albedo_one(brdf, theta_deg, rtol, atol) -> Estimate:
    """:func:`albedo_many` of one element (a single angle): the same breakpoints, integrand and driver,
    without the batch's grouping (:func:`_breakpoints_of_one`), θ_L, cos θ_L and sin θ_L as numbers
    (computed once, by the arrays' own cos and sin, where the batch gathers them per node: IEEE
    operations with a number or with a column of copies give the same bits).  Compiled where
    :func:`_compiled_kernel` knows the factors (:func:`_albedo_one_compiled`)."""
    factors = brdf.half_vector_factors()
    if factors is None:
        raise ValueError(f"the polar route needs a model that declares half_vector_factors, got {brdf.name!r}")
    theta_l = np.radians(theta_deg)
    t, mu_l, s_l = theta_l.item(), np.cos(theta_l).item(), np.sin(theta_l).item()
    kernel = _compiled_kernel(*factors)
    if kernel is not None:
        return _albedo_one_compiled(brdf, kernel, t, mu_l, s_l, rtol, atol)

    def integrand(theta_v, elem):
        value, rounding = radial_integrand(*factors, t, theta_v, mu_l, s_l)
        return NodeValues(value, value, rounding)

    return integrate(integrand, _breakpoints_of_one(brdf, factors[0], t, mu_l), rtol=rtol, atol=atol,
                     fill=FILL_CHEAP)


def _compiled_kernel(distribution, S):
    """The compiled kernel's codes of these factors (:func:`.polar_compiled.kernel_of`), or None: numba
    missing or switched off (:func:`brdfs.core.compiled.available`), or factors it does not know."""
    if not compiled.available():
        return None
    return _polar_compiled().kernel_of(distribution, S)


def _polar_compiled():
    """:mod:`.polar_compiled`, imported on the first use (:func:`brdfs.core.compiled.module`)."""
    return compiled.module("brdfs.numerics.integrate.polar_compiled")


def _albedo_one_compiled(brdf, kernel, theta_l, mu_l, s_l, rtol, atol) -> Estimate:
    """:func:`_albedo_one` in one compiled call (:func:`.polar_compiled.albedo_one`): the same breakpoints'
    candidates (the lobe's offsets and the levels' angles from the same caches), integrand and driver."""
    alpha = kernel[1]
    value, error, evaluations, status = _polar_compiled().albedo_one(
        *kernel, theta_l, mu_l, s_l, _lobe_offsets_of(alpha), _compiled_level_angles(brdf, alpha, mu_l),
        number_of_one(rtol), number_of_one(atol), FILL_CHEAP)
    return estimate_of_one(value, error, int(evaluations), compiled.status_name(status))


_NO_LEVELS = np.empty(0)
_NO_LEVELS.flags.writeable = False


def _level_angles_of_one(brdf, mu_l):
    """The polar angles of the model's ``nv_levels`` at one μ_L, one read-only row (the cached row of
    constant levels, as :func:`_breakpoints_of_one` takes them)."""
    levels = brdf.nv_levels(np.array([mu_l]))
    if not levels:
        return _NO_LEVELS
    if all(isinstance(c, float) for c in levels):
        return _constant_level_angles(tuple(levels))
    angles = np.ascontiguousarray(_level_angles(levels, 1)[0], float)
    angles.flags.writeable = False
    return angles


def _compiled_level_angles(brdf, alpha, mu_l):
    """The angles of the levels of :func:`_breakpoints_of_one` at one μ_L, as numpy computes them (the
    compiled call sorts them in with the lobe's): the model's ``nv_levels`` (:func:`_level_angles_of_one`)
    and, near grazing incidence, the graded ones (:func:`_grazing_levels`: numpy's arccos, which the C
    library's rounds differently by an ulp now and then)."""
    levels = _level_angles_of_one(brdf, mu_l)
    if not (mu_l > 0 and GRAZING_GRADING * mu_l < alpha):
        return levels
    graded = _grazing_levels(np.array([mu_l]), alpha)
    return np.concatenate([levels, *graded]) if graded else levels


def radial_integrand(distribution, S, theta_l, theta_v, mu_l=None, s_l=None):
    """2 sin θ_V cos θ_V S Φ at polar angles θ_V (module docstring; an array, the driver's nodes), with
    its rounding bound.  ``mu_l``, ``s_l``: cos θ_L and sin θ_L where the caller has them (a single
    angle's, as numbers)."""
    if mu_l is None:
        mu_l, s_l = np.cos(theta_l), np.sin(theta_l)
    mu_v, s_v = np.cos(theta_v), np.sin(theta_v)
    h_z = mu_l + mu_v
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        q = np.tan(0.5 * (theta_l - theta_v)) ** 2
        b = 2.0 * s_l * s_v / (h_z * h_z)
        phi, phi_err = distribution.azimuthal_integral(q, b)
        weight = 2.0 * s_v * mu_v * S(mu_l, mu_v)
        value = weight * phi
    value[phi == 0] = 0.0                        # D vanishes (e^−q/α² underflows): zero, not 0·∞
    rounding = np.abs(weight) * phi_err + S_ROUNDING * _EPS * np.abs(value)
    rounding[~np.isfinite(rounding)] = 0.0       # (in place, both new arrays: np.where's values, in fewer µs)
    return value, rounding


#: The mirror angle and its offsets in lobe widths, s · k for s = ±1 and k in :data:`LOBE_WIDTHS`.
_LOBE_OFFSETS = np.array([0.0] + [s * k for k in LOBE_WIDTHS for s in (-1.0, 1.0)])


def breakpoints(models, theta_l, groups=None):
    """Per element, ascending and NaN-padded: 0, π/2, the mirror angle θ_L and θ_L ± k · 2 arctan α
    (:data:`LOBE_WIDTHS`), the polar angles of the model's ``nv_levels`` (the Smith term's scale) and,
    near grazing incidence, of μ_V = μ_L · 8^k below α (:func:`_grazing_levels`).  ``groups``: the
    element indices of each model object (:func:`.grouping.indices_by_model`), if known."""
    if len(models) == 1:
        return _breakpoints_of_one(models[0], models[0].half_vector_factors()[0], theta_l[0].item(),
                                   np.cos(theta_l)[0].item())
    parts = []                                   # (element indices, candidates) of each model
    for members in groups or indices_by_model(models):
        idx = np.array(members)
        brdf = models[members[0]]
        distribution, _ = brdf.half_vector_factors()
        t = theta_l[idx]
        mu = np.cos(t)
        cand = [t[:, None] + _lobe_offsets(distribution.alpha)]
        levels = brdf.nv_levels(mu)
        if levels:
            cand.append(_level_angles(levels, t.size))
        graded = _grazing_levels(mu, distribution.alpha)
        if graded:
            cand.append(np.stack(graded, 1))
        cand = np.concatenate(cand, 1) if len(cand) > 1 else cand[0]
        parts.append((idx, np.where((cand > 0) & (cand < 0.5 * np.pi), cand, 0.0)))
    return _ascending_distinct(parts, len(models))


def _breakpoints_of_one(brdf, distribution, theta_l, mu_l):
    """:func:`breakpoints` of one element (θ_L and cos θ_L as numbers), as one row: the same candidates
    by the same arithmetic (a number plus the cached offsets, IEEE sums as the array's), kept and
    ordered as Python floats."""
    cand = [theta_l + offset for offset in _lobe_offsets_listed(float(distribution.alpha))]
    levels = brdf.nv_levels(np.array([mu_l]))
    if levels:
        cand += (_constant_level_angles_listed(tuple(levels)) if all(isinstance(c, float) for c in levels)
                 else _level_angles(levels, 1)[0].tolist())
    if mu_l > 0 and GRAZING_GRADING * mu_l < distribution.alpha:          # S's layer at the horizon
        cand += [float(level[0]) for level in _grazing_levels(np.array([mu_l]), distribution.alpha)]
    return np.array([sorted({0.0, _HALF_PI, *(c for c in cand if 0.0 < c < _HALF_PI)})])


_HALF_PI = 0.5 * np.pi


def _lobe_offsets(alpha):
    """The lobe's breakpoints about the mirror angle, :data:`_LOBE_OFFSETS` times its width 2 arctan α
    (read only: kept for the next call of the same α, keyed by α as a Python float, so that a 0-d array
    or a float32 α is cached by its value and computed in double precision)."""
    return _lobe_offsets_of(float(alpha))


@functools.lru_cache(maxsize=256)
def _lobe_offsets_of(alpha: float):
    offsets = _LOBE_OFFSETS * (2.0 * np.arctan(alpha))
    offsets.flags.writeable = False
    return offsets


@functools.lru_cache(maxsize=256)
def _lobe_offsets_listed(alpha: float):
    """:func:`_lobe_offsets_of` as a tuple of Python floats (a single angle's breakpoints)."""
    return tuple(_lobe_offsets_of(alpha).tolist())


@functools.lru_cache(maxsize=256)
def _constant_level_angles_listed(levels):
    """:func:`_constant_level_angles` as a tuple of Python floats (a single angle's breakpoints)."""
    return tuple(_constant_level_angles(levels).tolist())


@functools.lru_cache(maxsize=256)
def _constant_level_angles(levels):
    """The polar angles of constant levels μ_V = c (a tuple of floats), one row (read only)."""
    angles = np.arccos(np.clip(np.array(levels), 0.0, 1.0))
    angles.flags.writeable = False
    return angles


def _level_angles(levels, size):
    """The polar angles of the levels μ_V = c (numbers, or arrays over the ``size`` elements), one
    column per level."""
    if all(isinstance(c, float) for c in levels):      # constants (GGX, Beckmann: multiples of α)
        return np.broadcast_to(_constant_level_angles(tuple(levels)), (size, len(levels)))
    return np.stack([np.broadcast_to(np.arccos(np.clip(c, 0.0, 1.0)), (size,)) for c in levels], 1)


def _ascending_distinct(parts, size):
    """Rows of breakpoints, each with 0 and π/2, ascending, without repeats, NaN-padded to the
    longest (``parts``: (element indices, candidate rows))."""
    width = 2 + max(cand.shape[1] for _, cand in parts)
    out = np.full((size, width), np.nan)
    for idx, cand in parts:
        out[idx, :2] = 0.0, 0.5 * np.pi
        out[idx, 2:2 + cand.shape[1]] = cand
    out.sort(axis=1)
    repeated = np.zeros(out.shape, bool)
    repeated[:, 1:] = out[:, 1:] == out[:, :-1]
    out[repeated] = np.nan
    out.sort(axis=1)
    return out[:, :int((~np.isnan(out)).sum(axis=1).max())]


def _grazing_levels(mu_l, alpha):
    """Polar angles of μ_V = μ_L · r^k, k ≥ 1, r = :data:`GRAZING_GRADING`, while below α (0 where
    not: dropped by :func:`breakpoints`), one array per k: S's layer of width μ_L at the horizon
    (module docstring).  None (an empty list) at μ_L = 0 (θ_L = 90°: no layer) or μ_L ≥ α/r."""
    if mu_l.size == 1 and not (mu_l[0] > 0 and GRAZING_GRADING * mu_l[0] < alpha):    # one element, no layer
        return []
    positive = mu_l[mu_l > 0]
    if positive.size == 0 or GRAZING_GRADING * positive.min() >= alpha:    # every level at or above α
        return []
    count = int(np.ceil(np.log(alpha / np.min(positive)) / np.log(GRAZING_GRADING))) - 1
    levels = mu_l[:, None] * GRAZING_GRADING ** np.arange(1, max(count, 0) + 1)
    return list(np.where((levels > 0) & (levels < alpha), np.arccos(np.minimum(levels, 1.0)), 0.0).T)
