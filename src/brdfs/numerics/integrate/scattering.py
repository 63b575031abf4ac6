"""Albedo of Kirchhoff-type lobes: BRDFs that, for a fixed L, depend on V only through N·V and r = |L_xy + V_xy|.

r is the horizontal part of the (dimensionless) scattering vector L + V, zero at the mirror direction;
He–Torrance's distribution D is a function of r alone, and its other factors (shadowing, effective
roughness, G, Fresnel at the half angle) are functions of N·V and r.  In the engine's frames around R
or N (:mod:`.hemisphere`) such a lobe becomes elongated by 1/cos θ near grazing incidence; here the
coordinates follow its two variables instead.

Coordinates.  V = (sin θ_V cos φ, sin θ_V sin φ, cos θ_V) with L in the plane φ = 0, so that
cos θ_V dω_V = sin θ_V cos θ_V dθ_V dφ and r² = sin²θ + sin²θ_V + 2 sin θ sin θ_V cos φ.
On a circle of constant θ_V the integrand is a function of r alone, decreasing from φ = 0 to the
mirror side φ = π; it is split at the φ where r crosses the lobe's radial scales (width × 2^k), found
in closed form, and each piece gets a Gauss–Kronrod pair.  Across θ_V the integrand changes fast only
near the horizon (the shadowing and effective roughness, on the scale N·V ~ 2σ0/τ, with a logarithmic
end at N·V = 0) and where a circle first meets one of the radial scales (sin θ_V = sin θ ± r_k):
these are the breakpoints of the adaptive outer integration.  The integrand is symmetric in φ:
φ ∈ [0, π], doubled.

A model that declares ``scattering_azimuth_kernel()`` (He–Torrance with F ≡ 1: its Kirchhoff series
integrated over φ term by term in Kummer functions) gives the inner integral in closed form, with a bound
of its error: the albedo is then the 1-D integral over θ_V of that kernel, on the same breakpoints, each
kernel value counted as one evaluation (as the other closed-form routes count their nodes).
"""
from __future__ import annotations

import numpy as np

from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.numerics.integrate.grouping import first_of_model
from brdfs.core.gauss_kronrod import FILL_CHEAP, NodeValues, integrate
from brdfs.physics.models.base import count_evaluations

INNER_RTOL = 0.25          # inner integrals to a quarter of the target, so that the outer can meet it


def albedo_scattering(models, theta_deg, rtol=1e-10, atol=1e-14):
    """Albedo of ``models[i]`` at ``theta_deg[i]`` (the density part of the BRDF), in one adaptive run.

    Returns
    -------
    Estimate
        Value and absolute error per element.
    """
    theta_deg = np.asarray(theta_deg, float).ravel()
    models = list(models)
    if len(models) != len(theta_deg):
        raise ValueError("albedo_scattering needs one model per angle")
    index = first_of_model(models)
    mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    bp = _breakpoints([m.lobe for m in models], st)
    kernels = {k: models[k].scattering_azimuth_kernel() for k in np.unique(index)}

    def integrand(theta_v, elem):
        high, low, extra = (np.empty_like(theta_v) for _ in range(3))
        for k in np.unique(index[elem]):
            rows = index[elem] == k
            e = elem[rows]
            if kernels[k] is None:
                high[rows], low[rows], extra[rows] = _azimuthal(models[k], theta_v[rows], mu[e, None],
                                                                 st[e, None], INNER_RTOL * rtol, atol)
                continue
            t = theta_v[rows]
            high[rows], extra[rows] = kernels[k](mu[e, None], st[e, None], np.cos(t), np.sin(t))
            low[rows] = high[rows]
            count_evaluations(t.size)
        return NodeValues(high, low, extra)

    if all(kernel is not None for kernel in kernels.values()):
        return integrate(integrand, bp, rtol=rtol, atol=atol, fill=FILL_CHEAP)
    return integrate(integrand, bp, rtol=rtol, atol=atol, chunk=64)


def _breakpoints(lobes, st):
    """Per element, in θ_V: 0, π/2, the horizon levels and sin θ_V = sin θ ± r_k (NaN-padded rows)."""
    rows = []
    for lobe, s in zip(lobes, st):
        r = lobe.radial_levels()
        sines = np.concatenate([s - r, s + r])
        sines = sines[(sines > 0) & (sines < 1)]
        inner = np.concatenate([np.arccos(lobe.nv_levels()), np.arcsin(sines)])
        rows.append(np.unique(np.concatenate([[0.0, np.pi / 2], inner[(inner > 0) & (inner < np.pi / 2)]])))
    out = np.full((len(rows), max(len(r) for r in rows)), np.nan)
    for i, r in enumerate(rows):
        out[i, : r.size] = r
    return out


def _azimuthal(model, theta_v, mu, st, rtol, atol):
    """Inner φ-integral (doubled, times sin θ_V cos θ_V) at outer nodes θ_V (m, 21), adaptively:
    its value twice (the outer rule compares its own pair) and its error as the known extra error."""
    sv, cv = np.sin(theta_v).ravel(), np.cos(theta_v).ravel()
    mu, st = (np.broadcast_to(x, theta_v.shape).ravel() for x in (mu, st))
    levels = model.lobe.radial_levels()[::-1]
    cuts = np.stack([np.zeros_like(sv)] + [_phi_at_radius(rk, st, sv) for rk in levels] + [np.full_like(sv, np.pi)], -1)

    def integrand(phi, elem):
        s_v, c_v, s_i, c_i = (x[elem, None] for x in (sv, cv, st, mu))
        V = np.stack(np.broadcast_arrays(s_v * np.cos(phi), s_v * np.sin(phi), c_v), -1)
        L = np.stack(np.broadcast_arrays(s_i, 0.0 * s_i, c_i), -1)
        return model.unchecked(L, V)

    inner = integrate(integrand, cuts, rtol=rtol, atol=atol, chunk=4096)
    weight = 2 * sv * cv
    value, error = (weight * inner.value).reshape(theta_v.shape), (weight * inner.error).reshape(theta_v.shape)
    return value, value, error


def _phi_at_radius(r, st, sv):
    """φ in [0, π] where |L_xy + V_xy| = r on the circle θ_V: cos φ = (r² − sin²θ − sin²θ_V)/(2 sin θ sin θ_V)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        x = (r * r - st * st - sv * sv) / (2.0 * st * sv)
    x = np.where(st * sv > 0, x, np.where(r > st + sv, 2.0, -2.0))
    return np.arccos(np.clip(x, -1.0, 1.0))
