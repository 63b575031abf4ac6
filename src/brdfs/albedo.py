"""Directional albedo a(L) (eq. 1.18), its maximum over L, and the mean albedo (eq. 1.20 / 3.37)."""
from __future__ import annotations

import numpy as np

from .integrate.gauss_kronrod import Estimate, integrate
from .integrate.hemisphere import albedo_many

DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-14


def _check_angles(theta_deg):
    theta = np.asarray(theta_deg, float)
    bad = ~((theta >= 0) & (theta <= 90))
    if bad.any():
        raise ValueError(f"incidence angles must lie in [0, 90] degrees, got {theta[bad][:5]!r}")
    return theta


def albedo(model, theta_deg, tol=None, atol=DEFAULT_ATOL):
    """a(θ) = ∫ f(L, V) cos θ_V dω_V  (eq. 1.18), vectorised over ``theta_deg``.

    Returns an :class:`Estimate` whose ``value`` and ``error`` have the shape of ``theta_deg``.
    """
    theta = _check_angles(theta_deg)
    flat = theta.ravel()
    est = albedo_many([model] * flat.size, flat, rtol=tol or DEFAULT_RTOL, atol=atol)
    return Estimate(est.value.reshape(theta.shape), est.error.reshape(theta.shape))


def albedo_table(models, theta_deg, tol=None, atol=DEFAULT_ATOL):
    """Albedo of several models on a common grid: arrays of shape (len(models), len(theta))."""
    theta = _check_angles(np.atleast_1d(theta_deg)).ravel()
    pairs = [(m, t) for m in models for t in theta]
    est = albedo_many([p[0] for p in pairs], [p[1] for p in pairs], rtol=tol or DEFAULT_RTOL, atol=atol)
    shape = (len(models), theta.size)
    return Estimate(est.value.reshape(shape), est.error.reshape(shape))
