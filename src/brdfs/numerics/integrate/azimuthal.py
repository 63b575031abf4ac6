"""Directional albedo of the cosine-lobe models with the azimuth integrated in closed form.

For the four cosine-power lobes — reciprocal Phong (eq. 2.6 / 3.5), the new model (eq. 3.10),
reciprocal Blinn (eq. 1.34 / 3.33) and corrected Blinn (eq. 3.34), any exponent n ≥ 0 and any
constant C — the albedo integral (eq. 1.18) in the lobe's own frame has an integrand that is a
polynomial of degree ≤ 2 in cos φ on pieces bounded by levels of N·V, so the azimuth integrates
in closed form and only a one-dimensional integral over the lobe variable t remains (as the mean
albedo does in :mod:`.mean`):

* mirror frame (Phong, new model): V at angle α from R, N·V = A + B cos φ with A = cos α cos θ,
  B = sin α sin θ;  a = C/(n+1) ∫₀^{t_max} M dt  with M = J(A, B) (Phong) or
  (J(A, B) − J(A − cos θ, B)) / cos θ (new model: N·V / max(N·L, N·V) = min(N·V, N·L)/N·L),
  J(a, b) = ∫₀^{2π} [a + b cos φ]₊ dφ.
* half frame (Blinn, corrected Blinn): H at angle δ from N, dω_V = 4 (L·H) dω_H,
  N·V = A + B cos φ with A = cos 2δ cos θ, B = sin 2δ sin θ, and L·H = P + Q cos φ with
  P = cos δ cos θ, Q = sin δ sin θ;  a = C/(n+1) ∫ 8 [I₂(φ_h)] dt (Blinn) or
  8 [I₁(φ_μ) + (I₂(φ_h) − I₂(φ_μ)) / cos θ] (corrected Blinn), I₁, I₂ the integrals of L·H and
  L·H · N·V from 0 to the azimuths φ_h (N·V = 0) and φ_μ (N·V = N·L).

The lobe variable t = 1 − cos^(n+1) β (:class:`.lobes.PowerCosine`) makes C cos^n β sin β dβ =
C/(n+1) dt.  The integrand in t has kinks where a level circle N·V = c (c = 0, cos θ) touches the
circle of radius β; these are breakpoints.  For the two max(N·L, N·V) models the difference
quotient loses ε / cos θ relative digits near grazing; that rounding is added to the error.

Independent of the engine's two-dimensional quadrature (:mod:`.hemisphere`); the tests compare them.
"""
from __future__ import annotations

import numpy as np

from brdfs.numerics.integrate.gauss_kronrod import Estimate, integrate
from brdfs.numerics.integrate.hemisphere import TAIL
from brdfs.numerics.integrate.lobes import PowerCosine
from brdfs.numerics.integrate.mean import positive_part_azimuth

#: Models whose azimuthal integral is closed-form here, with their frame and max(N·L, N·V) flag.
_EPS = np.finfo(float).eps


def supports(model) -> bool:
    """Whether :func:`albedo_azimuthal` applies to ``model``: its class declares
    ``closed_form_azimuth`` (frame, divided by max(N·L, N·V)) and its lobe is a cosine power."""
    return getattr(type(model), "closed_form_azimuth", None) is not None \
        and isinstance(getattr(model, "lobe", None), PowerCosine)


def albedo_azimuthal(model, theta_deg, rtol=1e-10, atol=1e-14) -> Estimate:
    """a(θ) (eq. 1.18) of a Phong / new-model / Blinn / corrected-Blinn ``model`` at ``theta_deg``.

    Returns an :class:`Estimate` of the shape of ``theta_deg``.

    Raises
    ------
    ValueError
        For a model :func:`supports` rejects, or an angle outside [0, 90] degrees.

    Examples
    --------
    The new model at grazing incidence, eq. 3.27: a(90°) = (n+2)/(2(n+1)) = 22/42 for n = 20.

    >>> from brdfs.physics.models import model
    >>> a = albedo_azimuthal(model("phong_cosmin", n=20), 90.0)
    >>> abs(float(a.value) - 22 / 42) <= float(a.error) < 1e-10
    True
    """
    theta_deg = np.asarray(theta_deg, float)
    est = albedo_many([model] * theta_deg.size, theta_deg.ravel(), rtol=rtol, atol=atol)
    return Estimate(est.value.reshape(theta_deg.shape), est.error.reshape(theta_deg.shape))


def albedo_many(models, theta_deg, rtol=1e-10, atol=1e-14) -> Estimate:
    """Albedo of ``models[i]`` at ``theta_deg[i]`` (as :func:`.hemisphere.albedo_many`), one adaptive
    run per model family, the exponents and constants varying per element."""
    models = list(models)
    theta_deg = np.asarray(theta_deg, float).ravel()
    if len(models) != theta_deg.size:
        raise ValueError("albedo_many needs one model per angle")
    bad = [m for m in models if not supports(m)]
    if bad:
        raise ValueError(f"albedo_azimuthal needs a model whose class declares closed_form_azimuth, "
                         f"got {getattr(bad[0], 'name', bad[0])!r}")
    outside = ~((theta_deg >= 0) & (theta_deg <= 90))
    if outside.any():
        raise ValueError(f"theta_deg must lie in [0, 90] degrees, got {theta_deg[outside][:5]!r}")
    value, error = np.zeros(theta_deg.size), np.zeros(theta_deg.size)
    status = np.full(theta_deg.size, "converged", dtype=object)
    nodes = 0
    names = np.array([m.name for m in models])
    for name in np.unique(names):
        chosen = names == name
        n = np.array([float(m.n) for m, c in zip(models, chosen) if c])
        C = np.array([float(m.C) for m, c in zip(models, chosen) if c])
        family = type(next(m for m, c in zip(models, chosen) if c)).closed_form_azimuth
        est = _family(family, n, C, theta_deg[chosen], rtol, atol)
        value[chosen], error[chosen], status[chosen] = est.value, est.error, est.status
        nodes += est.evaluations
    return Estimate(value, error, nodes, status.astype(str))


def _family(family, n, C, theta_deg, rtol, atol):
    """One adaptive run for elements of one model family ``(frame, cosmin)`` with exponents n and
    constants C."""
    frame, cosmin = family
    lobe = PowerCosine(n, frame)
    mu, st = np.sin(np.radians(90.0 - theta_deg)), np.sin(np.radians(theta_deg))
    bp = _breakpoints(lobe, np.radians(theta_deg), mu, cosmin)
    inner = _mirror if frame == "mirror" else _half
    scale = C / (n + 1.0)

    def integrand(t, elem):
        el_lobe = PowerCosine(n[elem, None], frame)
        cb, sb = el_lobe.angle(np.minimum(t, 1.0 - _EPS))
        value, rounding = inner(cb, sb, mu[elem, None], st[elem, None], cosmin)
        value = scale[elem, None] * np.where(t < 1.0, value, 0.0)
        rounding = scale[elem, None] * rounding + (n[elem, None] + 4) * _EPS * np.abs(value)
        return value, value, rounding

    return integrate(integrand, bp, rtol=rtol, atol=atol)


def _breakpoints(lobe, theta, mu, cosmin):
    """t of the radii where the level circles N·V = 0 (and N·V = cos θ) touch the lobe circle."""
    scale = 0.5 if lobe.frame == "half" else 1.0
    beta_max = scale * (np.pi / 2 + theta)
    cols = [np.zeros_like(theta), beta_max]
    for a in ([np.full_like(theta, np.pi / 2)] + ([np.arccos(np.clip(mu, -1, 1))] if cosmin else [])):
        cols += [scale * (a - theta), scale * (theta - a), scale * (a + theta)]
    beta = np.column_stack(cols)
    beta = np.where((beta > 0) & (beta < beta_max[:, None]), beta, beta_max[:, None])
    beta[:, 0] = 0.0
    n = np.broadcast_to(np.asarray(lobe.n, float), theta.shape)[:, None]
    t = PowerCosine(n, lobe.frame).t_of(beta)
    t_end = t.max(axis=1, keepdims=True)
    # Tail points, as in the 2-D engine (hemisphere.TAIL): a kink squeezed into 1 − t < 1e-3 can
    # hide from the first interval's Kronrod nodes (the new model, n = 128, at 67.5°: 1e-12 off
    # while 5e-14 was reported).
    tail = np.broadcast_to(1.0 - TAIL, (t.shape[0], TAIL.size))
    return np.sort(np.concatenate([t, np.minimum(tail, t_end)], axis=1), axis=1)


def _level_azimuth(a, b, c):
    """φ in [0, π] with a + b cos φ = c; the set a + b cos φ > c is [0, φ) (π: all, 0: none)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(b > 0, (c - a) / b, np.where(a > c, -1.0, 1.0))
    return np.arccos(np.clip(u, -1.0, 1.0))


def _mirror(cb, sb, mu, st, cosmin):
    """M(α) and its rounding bound: the φ-integral of [N·V]₊ (· 1/max(N·L, N·V))."""
    a, b = cb * mu, sb * st
    full = positive_part_azimuth(a, b)
    if not cosmin:
        return full, 4 * _EPS * np.abs(full)
    low = positive_part_azimuth(a - mu, b)
    with np.errstate(divide="ignore", invalid="ignore"):
        quotient = (full - low) / mu
        rounding = 8 * _EPS * (np.abs(full) + np.abs(low)) / mu
    grazing = 2 * _level_azimuth(a, b, 0.0)        # N·L = 0: N·V / max(0, N·V) = 1 where N·V > 0
    value = np.where(mu > 0, quotient, grazing)
    return value, np.where(mu > 0, rounding, 4 * _EPS * grazing)


def _half(cb, sb, mu, st, cosmin):
    """8 × the φ-integral over [0, π] of L·H [N·V]₊ (· 1/max(N·L, N·V)), with its rounding bound."""
    p, q = cb * mu, sb * st                                   # L·H = p + q cos φ
    a, b = (cb - sb) * (cb + sb) * mu, 2 * sb * cb * st       # N·V = a + b cos φ

    def i1(phi):
        return p * phi + q * np.sin(phi)

    def i2(phi):
        return p * a * phi + (p * b + q * a) * np.sin(phi) + q * b * (0.5 * phi + 0.25 * np.sin(2 * phi))

    phi_h = _level_azimuth(a, b, 0.0)
    above = i2(phi_h)
    if not cosmin:
        return 8 * above, 8 * 8 * _EPS * (np.abs(p * a) + np.abs(p * b + q * a) + np.abs(q * b)) * np.pi
    phi_mu = _level_azimuth(a, b, mu)
    with np.errstate(divide="ignore", invalid="ignore"):
        band = (above - i2(phi_mu)) / mu
        rounding = 16 * _EPS * (np.abs(p * a) + np.abs(p * b + q * a) + np.abs(q * b)) * np.pi / mu
    value = np.where(mu > 0, i1(phi_mu) + band, i1(phi_h))   # N·L = 0: the weight is 1 where N·V > 0
    return 8 * value, 8 * np.where(mu > 0, rounding + 4 * _EPS * np.abs(i1(phi_mu)), 4 * _EPS * np.abs(value))
