"""Directional albedo a(L) (eq. 1.18), its maximum over L, and the mean albedo (eq. 1.20 / 3.37)."""
from __future__ import annotations

import numpy as np

from brdfs.numerics.integrate.gauss_kronrod import Estimate, integrate
from brdfs.numerics.integrate.hemisphere import albedo_many
from brdfs.numerics.integrate.scattering import FRAME as SCATTERING_FRAME
from brdfs.numerics.integrate.scattering import albedo_scattering

DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-14


def _check_angles(theta_deg):
    theta = np.asarray(theta_deg, float)
    bad = ~((theta >= 0) & (theta <= 90))
    if bad.any():
        raise ValueError(f"incidence angles must lie in [0, 90] degrees, got {theta[bad][:5]!r}")
    return theta


def _albedo_pairs(models, theta, rtol, atol):
    """Albedo of ``models[i]`` at ``theta[i]``: the density integrated in the frame its lobe asks for
    (Kirchhoff lobes in the scattering-vector frame, :mod:`.integrate.scattering`; the others around R
    or N, :mod:`.integrate.hemisphere`), plus the closed-form albedo of a Dirac part, for a model that
    has one (``model.delta_albedo(theta)``, e.g. He–Torrance's specular term)."""
    value, error = np.zeros(theta.size), np.zeros(theta.size)
    kirchhoff = np.array([m.lobe.frame == SCATTERING_FRAME for m in models], bool)
    for chosen, scheme in ((kirchhoff, albedo_scattering), (~kirchhoff, albedo_many)):
        if chosen.any():
            est = scheme([m for m, c in zip(models, chosen) if c], theta[chosen], rtol=rtol, atol=atol)
            value[chosen], error[chosen] = est.value, est.error
    for i, m in enumerate(models):
        if hasattr(m, "delta_albedo"):
            delta = m.delta_albedo(theta[i])
            value[i] += delta.value
            error[i] += delta.error
    return Estimate(value, error)


def albedo(model, theta_deg, tol=None, atol=DEFAULT_ATOL):
    """a(θ) = ∫ f(L, V) cos θ_V dω_V  (eq. 1.18), vectorised over ``theta_deg``.

    Returns an :class:`Estimate` whose ``value`` and ``error`` have the shape of ``theta_deg``.
    """
    theta = _check_angles(theta_deg)
    flat = theta.ravel()
    est = _albedo_pairs([model] * flat.size, flat, rtol=tol or DEFAULT_RTOL, atol=atol)
    return Estimate(est.value.reshape(theta.shape), est.error.reshape(theta.shape))


def albedo_table(models, theta_deg, tol=None, atol=DEFAULT_ATOL):
    """Albedo of several models on a common grid: arrays of shape (len(models), len(theta))."""
    theta = _check_angles(np.atleast_1d(theta_deg)).ravel()
    pairs = [(m, t) for m in models for t in theta]
    est = _albedo_pairs([p[0] for p in pairs], np.array([p[1] for p in pairs]), rtol=tol or DEFAULT_RTOL, atol=atol)
    shape = (len(models), theta.size)
    return Estimate(est.value.reshape(shape), est.error.reshape(shape))
