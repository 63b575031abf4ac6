"""Mean albedo (eq. 1.20 / 3.37) of the cosine-lobe models as a two-dimensional integral.

A = (1/π) ∫∫ f(L, V) cos θ_L cos θ_V dω_L dω_V.  For f = w(β) g with the lobe weight
w(β) = C cos^n β and g = 1 or 1/max(N·L, N·V), the four-dimensional integral reduces to two
dimensions — the lobe angle β and one polar angle — because the remaining azimuth integrates
in closed form:

* mirror frame (Phong, eq. 2.6; new model, eq. 3.10).  V at angle α from R(L), azimuth φ:
  N·V = a + b cos φ with a = cos α cos θ, b = sin α sin θ, and
  A = 2 ∫ w(α) sin α dα ∫₀^{π/2} sin θ M(α, θ) dθ,
  M = cos θ · J(a, b) (Phong) or J(a, b) − J(a − cos θ, b) (new model: min(N·L, N·V)),
  J(a, b) = ∫₀^{2π} [a + b cos φ]₊ dφ.
* half frame (Blinn, corrected Blinn, eq. 3.34).  dω_L dω_V = 4 (L·H) dω_H dω_L; with L at
  angle α from H and N at angle δ from H, N·L, N·V = p ± q cos ψ, p = cos δ cos α, q = sin δ sin α:
  A = 2 ∫ w(δ) sin δ dδ ∫₀^{π/2} 4 cos α sin α P(δ, α) dα,
  P = ∫₀^{2π} [p² − q² cos²ψ]₊ dψ (Blinn) or ∫₀^{2π} [p − q |cos ψ|]₊ dψ (min(N·L, N·V)).

The outer variable is the lobe's cumulative weight t, for which w sin β dβ/dt = C/(n+1); the
inner integrand has one kink (θ = π/2 − α and π/2 − α/2, or α = π/2 − δ), given as breakpoints.
Independent of the albedo engine's hemisphere coordinates; the tests compare the two.
"""
from __future__ import annotations

import contextlib

import numpy as np

from brdfs.core.gauss_kronrod import NodeValues, integrate
from brdfs.physics.lobes import MIRROR


#: The context of a caller that already ignores numpy's divide and invalid errors (``quiet=True``).
QUIET = contextlib.nullcontext()


def mean_albedo_lobe(n, C, frame, cosmin, rtol=1e-10, atol=1e-14):
    """A for w = C cos^n β in ``frame`` (:data:`~brdfs.physics.lobes.MIRROR` or ``HALF``), g = 1/max(N·L, N·V) if ``cosmin``.

    ``n`` and ``C`` are arrays (one integral per entry); returns an :class:`Estimate`.
    """
    n, C = (np.atleast_1d(np.asarray(x, float)) for x in (n, C))
    inner = _mirror_inner if frame is MIRROR else _half_inner

    def outer(t, elem):
        y = np.log1p(-t) / (n[elem, None] + 1)          # log cos β, as in lobes.PowerCosine
        beta = np.arctan2(np.sqrt(np.maximum(-np.expm1(y) * (1 + np.exp(y)), 0.0)), np.exp(y))
        est = _inner_integrals(inner, beta.ravel(), cosmin, rtol / 10, atol)
        weight = (2 * C / (n + 1))[elem, None]
        value = weight * est.value.reshape(t.shape)
        return NodeValues(value, value, weight * est.error.reshape(t.shape))

    bp = np.tile([0.0, 1.0], (n.size, 1))
    return integrate(outer, bp, rtol=rtol, atol=atol)


def _inner_integrals(inner, beta, cosmin, rtol, atol):
    # half frame: α = π/2 − δ; mirror frame: θ = π/2 − α and π/2 − α/2 (ascending)
    kinks = [np.pi / 2 - beta] if inner is _half_inner else [np.pi / 2 - beta, np.pi / 2 - beta / 2]
    bp = np.column_stack([np.zeros_like(beta), *kinks, np.full_like(beta, np.pi / 2)])
    return integrate(lambda x, e: inner(beta[e, None], x, cosmin), bp, rtol=rtol, atol=atol)


def _mirror_inner(alpha, theta, cosmin):
    """sin θ · M(α, θ)."""
    a, b = np.cos(alpha) * np.cos(theta), np.sin(alpha) * np.sin(theta)
    m = positive_part_azimuth(a, b) - positive_part_azimuth(a - np.cos(theta), b) if cosmin \
        else np.cos(theta) * positive_part_azimuth(a, b)
    return np.sin(theta) * m


def positive_part_azimuth(a, b, quiet=False):
    """J(a, b) = ∫₀^{2π} [a + b cos φ]₊ dφ for b ≥ 0.  ``quiet``: the caller already ignores numpy's
    divide and invalid errors (a kernel of :mod:`.azimuthal`, which enters one ``np.errstate`` per
    round for all of its parts: each costs a single-angle call ~1 µs)."""
    with QUIET if quiet else np.errstate(divide="ignore", invalid="ignore"):
        phi0 = np.arccos(np.minimum(np.maximum(-a / b, -1.0), 1.0))     # np.clip, without its dispatch cost
    # the sine of the rounded angle, not √(1 − x²): J is stationary in φ₀ (a + b cos φ₀ = 0), so an
    # angle off by δ costs O(δ²) only while both terms see the same angle
    partial = 2 * (a * phi0 + b * np.sin(phi0))
    return np.where(a >= b, 2 * np.pi * a, np.where(a <= -b, 0.0, partial))


def _half_inner(delta, alpha, cosmin):
    """4 cos α sin α · P(δ, α)."""
    p, q = np.cos(delta) * np.cos(alpha), np.sin(delta) * np.sin(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        psi0 = np.arccos(np.clip(p / q, 0.0, 1.0))
    if cosmin:
        whole = 2 * np.pi * p - 4 * q
        partial = 4 * (p * (np.pi / 2 - psi0) - q * (1 - np.sin(psi0)))
    else:
        whole = 2 * np.pi * (p * p - q * q / 2)
        partial = 2 * (p * p - q * q / 2) * (np.pi - 2 * psi0) + q * q * np.sin(2 * psi0)
    return 4 * np.cos(alpha) * np.sin(alpha) * np.where(q <= p, whole, partial)
