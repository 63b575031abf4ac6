"""Fresnel reflectance of a smooth interface from air into a (complex) index.

The thesis writes the complex index as ``n - i k`` (eq. 1.39): ``n`` is the
real part (here ``ior_re``) and ``k`` the extinction coefficient (``ior_im``).

References
----------
.. [1] L. Neumann, "Constructions of BRDFs", thesis, 2001, Sec. 1, eqs. 1.39-1.43.
.. [2] M. Born and E. Wolf, "Principles of Optics", 7th ed., Sec. 1.5.2 and 14.2
   (Fresnel formulae; reflection on a metal).
.. [3] M. Pharr, W. Jakob, G. Humphreys, "Physically Based Rendering", 4th ed.,
   Sec. 9.5 ("FrComplex"): the same unpolarised reflectance with ``eta = n + i k``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

#: Unit roundoff of binary64.
UNIT_ROUNDOFF = np.finfo(float).eps / 2


def _gamma(count: int) -> float:
    """Higham's gamma_n = n u / (1 - n u): bound of ``count`` accumulated roundings."""
    return count * UNIT_ROUNDOFF / (1 - count * UNIT_ROUNDOFF)


def normal_incidence_reflectance(ior_re: ArrayLike, ior_im: ArrayLike) -> np.ndarray:
    """Reflectance at normal incidence, ``a0 = rho`` (eq. 1.40).

    ``a0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2)``.

    Parameters
    ----------
    ior_re : array_like
        Real part ``n`` of the refractive index, ``> 0``.
    ior_im : array_like
        Extinction coefficient ``k``, ``>= 0``.

    Returns
    -------
    numpy.ndarray
        The fraction of the incident energy reflected, in ``[0, 1)``.

    Examples
    --------
    >>> float(normal_incidence_reflectance(1.5, 0.0))
    0.04
    """
    n, k = np.asarray(ior_re, dtype=float), np.asarray(ior_im, dtype=float)
    k2 = k * k
    return ((n - 1) ** 2 + k2) / ((n + 1) ** 2 + k2)  # eq. 1.40


def normal_incidence_reflectance_err(ior_re: ArrayLike, ior_im: ArrayLike) -> np.ndarray:
    """Bound of the floating-point error of :func:`normal_incidence_reflectance`.

    The bound covers both the rounding of the inputs to binary64 (the truth is
    eq. 1.40 at the decimal inputs) and the arithmetic: each of the two sums of
    squares carries at most four roundings and the division one more, so the
    arithmetic error is at most ``gamma_9 a0``; an input rounding of relative
    size ``u`` moves ``a0`` by at most ``u (|n da0/dn| + |k da0/dk|)``, with
    ``da0/dn = -4 (1 - n^2 + k^2) / D^2``, ``da0/dk = 8 n k / D^2`` and
    ``D = (n + 1)^2 + k^2``. That term is counted twice (``gamma_2``) to cover
    the second-order terms.

    Parameters
    ----------
    ior_re, ior_im : array_like
        As for :func:`normal_incidence_reflectance`.

    Returns
    -------
    numpy.ndarray
        An absolute error bound, about ``1e-16``.
    """
    n, k = np.asarray(ior_re, dtype=float), np.asarray(ior_im, dtype=float)
    denominator = (n + 1) ** 2 + k * k
    sensitivity = (np.abs(n * 4 * (1 - n * n + k * k)) + np.abs(k * 8 * n * k)) / denominator**2
    return _gamma(9) * normal_incidence_reflectance(n, k) + _gamma(2) * sensitivity


def unpolarised_reflectance(cos_theta: ArrayLike, ior_re: ArrayLike, ior_im: ArrayLike = 0.0) -> np.ndarray:
    """Unpolarised Fresnel reflectance ``F = (F_par + F_perp) / 2`` (eqs. 1.41-1.43).

    The thesis prints the amplitude ratios of eqs. 1.41-1.42 squared; for a
    complex index the reflectances are their squared moduli ``|r|^2``. With
    ``eta = n + i k`` (the sign of ``k`` does not change ``|r|^2``) and
    ``w = eta cos(theta_t) = sqrt(eta^2 - sin^2 theta)`` (the principal root,
    the transmitted wave decaying into the metal), the standard form (the module's references 2 and 3) is::

        r_perp = (cos theta - w) / (cos theta + w)                 # eq. 1.41
        r_par  = (eta^2 cos theta - w) / (eta^2 cos theta + w)     # eq. 1.42
        F      = (|r_perp|^2 + |r_par|^2) / 2                      # eq. 1.43

    Parameters
    ----------
    cos_theta : array_like
        Cosine of the angle of incidence, in ``[0, 1]``.
    ior_re : array_like
        Real part ``n`` of the refractive index, ``> 0``.
    ior_im : array_like, optional
        Extinction coefficient ``k``, ``>= 0``; 0 for a dielectric.

    Returns
    -------
    numpy.ndarray
        The reflectance, ``a0`` of eq. 1.40 at normal incidence and 1 at grazing.

    Examples
    --------
    >>> round(float(unpolarised_reflectance(1.0, 1.5)), 15), float(unpolarised_reflectance(0.0, 0.93, 6.33))
    (0.04, 1.0)
    """
    cos_theta = np.clip(np.asarray(cos_theta, dtype=float), 0.0, 1.0)
    eta2 = (np.asarray(ior_re, dtype=float) + 1j * np.asarray(ior_im, dtype=float)) ** 2
    w = np.sqrt(eta2 - (1.0 - cos_theta**2))
    r_perp = (cos_theta - w) / (cos_theta + w)  # eq. 1.41
    r_par = (eta2 * cos_theta - w) / (eta2 * cos_theta + w)  # eq. 1.42
    return (np.abs(r_perp) ** 2 + np.abs(r_par) ** 2) / 2  # eq. 1.43


# --- the angle at which a model's Fresnel factor is read (eqs. 3.29, 4.53/4.54; L·H) ----------------

def cos_theta_min(L: ArrayLike, V: ArrayLike) -> np.ndarray:
    """cos Θ_min = max(N·L, N·V), in ``[0, 1]``: the angle of the new model's metals (eq. 3.29).

    Θ_min = min(Θ_L, Θ_V) is symmetric in L and V, so ``f · F(Θ_min)`` stays reciprocal; N = (0, 0, 1).

    >>> float(cos_theta_min(np.array([0.6, 0.0, 0.8]), np.array([0.0, 0.0, 1.0])))
    1.0
    """
    L, V = np.asarray(L, float), np.asarray(V, float)
    return np.clip(np.maximum(L[..., 2], V[..., 2]), 0.0, 1.0)


def cos_theta_half(L: ArrayLike, V: ArrayLike) -> np.ndarray:
    """cos of the angle between L and the half vector H = (L + V)/|L + V|, L·H = V·H, in ``[0, 1]``:
    where a microfacet model reads F (the facet's own angle of incidence; Cook & Torrance 1982,
    Walter et al. 2007, eq. 20), formed as L·(L + V)/|L + V| (0 where L + V = 0).

    >>> round(float(cos_theta_half(np.array([0.6, 0.0, 0.8]), np.array([-0.6, 0.0, 0.8]))), 12)
    0.8
    """
    L, V = np.asarray(L, float), np.asarray(V, float)
    h = L + V
    norm = np.linalg.norm(h, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos = np.sum(L * h, axis=-1) / norm
    return np.clip(np.where(norm > 0, cos, 0.0), 0.0, 1.0)


def cos_theta_prime(L: ArrayLike, V: ArrayLike) -> np.ndarray:
    """cos θ' with sin θ' = |L_P − V_P| / 2 (eqs. 4.52/4.53): the incidence angle of the mirror pair
    with the same L_P − V_P, where the patch models' metals read F (eq. 4.54).

    >>> float(cos_theta_prime(np.array([0.6, 0.0, 0.8]), np.array([-0.6, 0.0, 0.8])))
    0.8
    """
    L, V = np.asarray(L, float), np.asarray(V, float)
    half = 0.5 * np.hypot(L[..., 0] - V[..., 0], L[..., 1] - V[..., 1])
    return np.sqrt(np.clip(1.0 - half * half, 0.0, 1.0))

