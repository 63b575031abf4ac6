"""Derived quantities of the albedo: its maximum over incidence (maximal constants, Tables 1.1,
3.1, 3.2), the mean albedo (eq. 3.37, Table 3.3) and the limits n → ∞ (Tables 3.3 and 4.2)."""
from __future__ import annotations

import numpy as np

from brdfs.numerics.albedo import DEFAULT_ATOL, DEFAULT_RTOL, albedo_pairs
from brdfs.core.gauss_kronrod import Estimate, NodeValues, integrate
from brdfs.numerics.integrate.mean import mean_albedo_lobe
from brdfs.physics.lobes import PowerCosine
from brdfs.physics.models import MODELS
# the closed forms live on the models (re-exported here for their callers)

_GOLD = (np.sqrt(5.0) - 1.0) / 2.0


def max_albedo(models, rtol=None, grid_deg=2.0, xtol_deg=1e-5, theta_max_deg=90.0, grid_values=None):
    """max over θ ∈ [0°, theta_max_deg] of a(θ) for each model, and where it is attained.

    A grid of step ``grid_deg`` brackets the maximum; a golden-section search, run for all
    models at once, then shrinks each bracket to ``xtol_deg``.  The maximum need not lie at
    normal incidence (Table 1.1: corrected Blinn with small n).  At an interior maximum a
    bracket of 1e-5° moves a by ~a''·1e-14: the default resolves the value, not just the angle.
    ``grid_values`` (models × grid points), when the caller has the grid already, saves its
    recomputation; otherwise the grid is integrated at 1e-6, which locates the bracket (a wrong
    bracket would need two grid values within 1e-6 of each other across the maximum, and the
    golden section then works on values at ``rtol``).

    Returns
    -------
    (Estimate, ndarray)
        The maximal albedo with its error (albedo error plus the variation of a over the final
        bracket, which bounds the error of locating the maximum) and its angle in degrees.
    """
    rtol = rtol or DEFAULT_RTOL
    models = list(models)
    grid = np.append(np.arange(0.0, theta_max_deg, grid_deg), theta_max_deg)
    if grid_values is None:
        grid_values = albedo_pairs([m for m in models for _ in grid], np.tile(grid, len(models)), rtol=1e-6).value
    best = np.nanargmax(np.reshape(grid_values, (len(models), grid.size)), axis=1)
    lo = grid[np.maximum(best - 1, 0)]
    hi = grid[np.minimum(best + 1, grid.size - 1)]
    value = lambda th: albedo_pairs(models, th, rtol=rtol, atol=DEFAULT_ATOL).value
    x1, x2 = hi - _GOLD * (hi - lo), lo + _GOLD * (hi - lo)
    f1, f2 = value(x1), value(x2)
    while np.max(hi - lo) > xtol_deg:
        left = f1 >= f2                       # the maximum lies in [lo, x2], else in [x1, hi]
        hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
        new_x1 = np.where(left, hi - _GOLD * (hi - lo), x2)
        new_x2 = np.where(left, x1, lo + _GOLD * (hi - lo))
        f_new = value(np.where(left, new_x1, new_x2))
        f1, f2 = np.where(left, f_new, f2), np.where(left, f1, f_new)
        x1, x2 = new_x1, new_x2
    points = np.stack([0.5 * (lo + hi), lo, hi])           # (3, models): centre and bracket ends
    est = albedo_pairs(models * 3, points.ravel(), rtol=rtol, atol=DEFAULT_ATOL)
    values, errors = est.value.reshape(3, -1), est.error.reshape(3, -1)
    pick = np.argmax(values, axis=0)     # an end wins at a boundary maximum (θ = 0 exactly)
    cols = np.arange(len(models))
    bracket = values[pick, cols] - values[1:].min(axis=0)
    return Estimate(values[pick, cols], errors[pick, cols] + bracket), points[pick, cols]


def maximal_constant(models, rtol=None, **search):
    """C_max = 1 / max_θ a(θ) of models evaluated with C = 1 (Tables 1.1, 3.1, 3.2).

    Returns (Estimate of C_max, angle of the maximal albedo in degrees)."""
    amax, theta = max_albedo(models, rtol, **search)
    return Estimate(1.0 / amax.value, amax.error / amax.value ** 2), theta


def mean_albedo(models, rtol=None):
    """A = (1/π) ∫ a(L) cos θ_L dω_L  (eq. 1.20 / 3.37) for each model.

    The cosine-lobe models (reciprocal Phong, the new model, Blinn, corrected Blinn) take the
    two-dimensional reduction of :mod:`brdfs.numerics.integrate.mean`; any other model the nested
    integration of its albedo, :func:`mean_albedo_nested`.
    """
    rtol = rtol or DEFAULT_RTOL
    models = list(models)
    lobe_models = [_lobe_reduction(m) for m in models]
    if any(r is None for r in lobe_models):
        return mean_albedo_nested(models, rtol)
    value, error = np.empty(len(models)), np.empty(len(models))
    for key in set(lobe_models):
        idx = [i for i, r in enumerate(lobe_models) if r == key]
        est = mean_albedo_lobe([models[i].n for i in idx], [models[i].C for i in idx], *key,
                               rtol=rtol, atol=DEFAULT_ATOL)
        value[idx], error[idx] = est.value, est.error
    return Estimate(value, error)


def _lobe_reduction(brdf):
    """(frame, cosmin) of the models :func:`mean_albedo_lobe` covers, else None: a cosine-power lobe
    (:class:`~brdfs.physics.lobes.PowerCosine`) whose declared closed-form azimuth is the kernel g = 1
    (``"nv"``: reciprocal Phong, Blinn) or g = 1/max(N·L, N·V) (``"nv/max"``: the new model, corrected
    Blinn) — what the model says about its integrand, not its type or name (a pumped model or a metal
    declares no closed-form azimuth)."""
    declared = brdf.closed_form_azimuth
    if declared is None or not isinstance(brdf.lobe, PowerCosine) or declared[1] not in ("nv", "nv/max"):
        return None
    return declared[0], declared[1] == "nv/max"


def mean_albedo_nested(models, rtol=None):
    """A = ∫₀¹ a(θ(v)) 2v dv with v = cos θ_L, the albedo from the engine at every node.

    The variable v = cos θ (not cos²θ) keeps the integrand smooth at grazing incidence, where
    the albedo of the Phong family varies linearly in cos θ.  One nested adaptive integration
    for all models: the outer Gauss–Kronrod rule in v calls the albedo engine at all its nodes
    at once, and the inner albedo errors are carried as known errors of the integrand.
    """
    rtol = rtol or DEFAULT_RTOL
    models = list(models)

    def integrand(v, elem):
        theta = np.degrees(np.arctan2(np.sqrt((1.0 - v) * (1.0 + v)), v))
        inner = albedo_pairs([models[e] for e in np.repeat(elem, v.shape[1])], theta.ravel(),
                            rtol=rtol / 10, atol=DEFAULT_ATOL)
        a = inner.value.reshape(v.shape) * 2 * v
        return NodeValues(a, a, inner.error.reshape(v.shape) * 2 * v)

    bp = np.tile([0.0, 1.0], (len(models), 1))
    return integrate(integrand, bp, rtol=rtol, atol=DEFAULT_ATOL)


# Limits n → ∞ (the derivations are on the model classes, ``limit_cos_power`` and
# ``limit_albedo_90``).  With a(θ) = cos^k θ the mean albedo is ∫₀¹ u^(k/2) du = 2/(k+2).


def _model_class(model_name):
    try:
        return MODELS[model_name]
    except KeyError:
        raise ValueError(f"unknown model {model_name!r}") from None


def _limit_power(model_name):
    k = _model_class(model_name).limit_cos_power
    if k is None:
        raise ValueError(f"no derived n → ∞ limit for model {model_name!r}")
    return k


def limit_albedo(model_name, theta_deg):
    """lim_{n→∞} a(θ) for θ < 90°: cos^k θ with k = ``limit_cos_power`` of the model."""
    k = _limit_power(model_name)
    return np.cos(np.radians(np.asarray(theta_deg, float))) ** k


def limit_mean_albedo(model_name):
    """lim_{n→∞} A = 2 / (k + 2): Phong 2/3, new model 1, Blinn 1/2, corrected Blinn 2/3."""
    return 2.0 / (_limit_power(model_name) + 2.0)


def limit_albedo_90(model_name):
    """lim_{n→∞} a(90°), ``limit_albedo_90`` of the model (new model 1/2, reciprocal Phong 0)."""
    limit = _model_class(model_name).limit_albedo_90
    if limit is None:
        raise ValueError(f"no derived limit of a(90°) for model {model_name!r}")
    return limit
