"""Sharper truths where a family has them (session 5, issue 24's unjudged cells): closed forms, one-
dimensional mpmath integrals at 30+ digits, and the vectorised He–Torrance route.  :func:`sharp_truth`
returns a :class:`sweep.third_route.Truth` for a cell it knows a sharper route for, else None (the cell
keeps :func:`sweep.cells.truth`'s nested quadrature).

Nothing here imports :mod:`brdfs.numerics`.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from sweep import independent as ind
from sweep import patch_mp as pm
from sweep.ct_mp import cook_torrance_ts_albedo
from sweep.he_torrance import he_torrance_truth
from sweep.third_route import Truth, hemisphere_albedo, incidence


def kulla_conty_truth(params) -> Truth | None:
    """Kulla–Conty with the exact E and F = 1: a(θ) = 1, exactly.  With E(μ) the single-scattering albedo,
    f_ms = (1 − E(μ_L))(1 − E(μ_V))/(π(1 − E_avg)) and ∫ (1 − E(μ_V)) μ_V dω_V = 2π ∫₀¹ (1 − E) μ dμ =
    π (1 − E_avg), so a = E(μ_L) + (1 − E(μ_L)) = 1 whatever E is: the truth needs no E table at all, and
    the package's albedo (built with its E table Ẽ) is 1 + E(μ_L) − Ẽ(μ_L), which its reported error must cover."""
    if params.get("ior_re") is not None:
        return None                                 # F_ms ≠ 1: no closed form here
    return Truth(1.0, 0.0, "closed_form+independent", 0, ["Kulla-Conty, exact E, F = 1: a = E + (1 - E) = 1"])


def sharp_truth(family, params: dict, theta: float, model) -> Truth | None:
    """A sharper truth of the cell (family, params incl. the fixed ones, θ), or None."""
    name = family.model
    if name == "he_torrance":
        return he_torrance_truth(params["sigma0_um"], params["tau_um"], theta,
                                 params.get("lambda_um", 0.55), params.get("term", "total"))
    if params.get("compensation") == "kulla_conty":
        return kulla_conty_truth(params)
    if name in PATCH_ROUTES:
        return PATCH_ROUTES[name](params, model, theta)
    if name == "cook_torrance" and params.get("G") == "torrance_sparrow" and theta > MP_GRAZING_THETA:
        return cook_torrance_ts_albedo(params["m"], theta, dps=MP_DPS)
    if family.pumped is None and name in EXTENDED_F_RTOL:
        return extended_hemisphere_truth(family, params, theta, model)
    return None


#: Cook–Torrance (Torrance–Sparrow) beyond this angle by the 2-D mpmath route (:mod:`sweep.ct_mp`, ~25 CPU-s a
#: cell at :data:`MP_DPS` digits): where the double route's truths were suspect (issue 24's 78× cells).
MP_GRAZING_THETA = 89.99
MP_DPS = 25
#: Families whose rewrite the nested quadrature integrates in long double (:func:`extended_hemisphere_truth`),
#: by model, with the relative accuracy of one evaluation: 0 where every operation is numpy's (long double),
#: 1e-15 where a scipy special function (double only) enters (erfc in the thesis's Smith G*, erfcx in
#: Beckmann's Λ: ≤ 2 ulp each, two factors, each entering with a sensitivity below 1; the conductor's
#: complex Fresnel in double).  The pumped models (their table in double, ~15 s a cell in long double, and
#: already judged) keep the double route.
EXTENDED_F_RTOL = {"phong": 0.0, "phong_original": 0.0, "phong_cosmin": 0.0, "p_model": 0.0, "blinn": 0.0,
                   "blinn_original": 0.0, "blinn_cosmin": 0.0, "ward": 0.0, "ward_cosmin": 0.0,
                   "cook_torrance": 0.0, "ggx": 0.0, "beckmann": 1e-15}
#: The long-double route's tolerance (outer and inner), near its ε = 1.1e-19 × the integrand's condition.
EXTENDED_EPSREL = 1e-17


def extended_hemisphere_truth(family, params, theta, model) -> Truth:
    """The family's rewrite (:func:`sweep.cells._independent`) by the nested quadrature in long double
    (:func:`sweep.third_route.hemisphere_albedo` with ``extended=True``)."""
    from sweep.cells import _independent            # lazily: sweep.cells imports this module lazily too
    f_rtol = EXTENDED_F_RTOL[family.model]
    if params.get("G") == "smith" or params.get("ior_re") is not None:
        f_rtol = 1e-15
    integrand = dataclasses.replace(_independent(family, params, model), f_rtol=f_rtol)
    t = hemisphere_albedo(integrand, theta, epsrel=EXTENDED_EPSREL, extended=True)
    t.route += "+independent"
    return t


#: The patch models' 40-digit routes (:mod:`sweep.patch_mp`), by model: (params, model, θ) → Truth.
PATCH_ROUTES = {
    "patch_basic": lambda p, m, t: pm.basic_lens_albedo(p["R"], m.C, t),
    "patch_elliptical": lambda p, m, t: pm.elliptical_albedo(p["b"], p["ratio"], p["u_angle_deg"], m.C, t),
    "patch_exponential": lambda p, m, t: pm.radial_albedo(pm.exponential_phi(p["s"], m.C), (), t),
    "generalized_lambertian": lambda p, m, t: pm.radial_albedo(pm.generalized_lambert_phi(p["d"], m.m_clip, m.C),
                                                               (m.m_clip,), t),
    "patch_mixture": lambda p, m, t: pm.radial_albedo(pm.mixture_phi(p["weight"], p["p_diffuse"]),
                                                      (1.0, *(ind.box_ends(p["weight"]) or ())), t),
}


def he_torrance_pointwise(model, rng, n: int = 2000) -> float:
    """max |f_rewrite − f_model| / max |f_model| of He–Torrance's f_dd at random points of the projected
    disk, at five random incidence angles (the rewrite is written in the disk's coordinates)."""
    if model.ior_re is not None or model.term == "specular":
        raise ValueError(f"the He-Torrance rewrite has F = 1 and the density only, got {model!r}")
    worst = 0.0
    for theta in rng.uniform(0.0, 90.0, 5):
        cl, s = incidence(theta)
        psi = rng.uniform(0.0, np.pi, n)
        q = np.sqrt(cl * cl + (s * np.cos(psi)) ** 2)
        rmax = s * np.cos(psi) + q
        rho = rmax * np.sqrt(rng.uniform(0.0, 1.0, n))
        mine, _ = ind.he_torrance_disk(model.sigma0_um, model.tau_um, model.lambda_um, theta)(rho, psi, rmax - rho)
        x, y = -s + rho * np.cos(psi), rho * np.sin(psi)
        V = np.stack([x, y, np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))], -1)
        ref = model(np.broadcast_to([s, 0.0, cl], V.shape), V)
        worst = max(worst, float(np.max(np.abs(mine - ref)) / (np.max(np.abs(ref)) or 1.0)))
    return worst
