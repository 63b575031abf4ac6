"""Accuracy against cost of albedo integration methods, on albedos with closed forms.

Cost is counted in BRDF evaluations (deterministic, unlike wall time on a shared machine);
accuracy is the true error against the closed form, beside each method's own error estimate:

* ``engine`` — the lobe-following adaptive Gauss–Kronrod of :mod:`brdfs.numerics.integrate.hemisphere`;
* ``product_grid`` — an N × N Gauss–Legendre grid in (cos θ_V, φ_V), error |Q_N − Q_{N/2}|;
* ``dblquad`` — ``scipy.integrate.dblquad`` over (θ_V, φ_V) with its own error estimate;
* ``monte_carlo`` — cosine-weighted sampling of V, error = standard deviation / √N.

The cases and their closed forms:

* ``phong_normal_incidence`` — reciprocal Phong, c = (n+2)/2π, θ = 0: a = 1 (eq. 3.6);
* ``new_model_at_90`` — the new model at θ = 90°: a = (n+2)/(2(n+1)) (eq. 3.27);
* ``ward_cosmin_at_90`` — corrected Ward at θ = 90°: Γ(3/2) U(3/2, 1/2, 1/m²)/(π m²)
  (:func:`brdfs.numerics.grazing.ward_cosmin_limit`).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.integrate import IntegrationWarning, dblquad

from brdfs.numerics.albedo import DEFAULT_ATOL
from brdfs.physics.geometry import light_direction
from brdfs.numerics.grazing import monte_carlo_albedo, ward_cosmin_limit
from brdfs.numerics.integrate.hemisphere import albedo_many
from brdfs.physics.models import model
from brdfs.numerics.quantities import grazing_albedo_new_model


@dataclass(frozen=True)
class Case:
    model: str
    parameter: str
    theta_deg: float

    def exact(self, value):
        if self.model == "phong":
            return 1.0                                            # eq. 3.6
        if self.model == "phong_cosmin":
            return float(grazing_albedo_new_model(value))        # eq. 3.27
        return float(ward_cosmin_limit(value).value)


CASES = {
    "phong_normal_incidence": Case("phong", "n", 0.0),
    "new_model_at_90": Case("phong_cosmin", "n", 90.0),
    "ward_cosmin_at_90": Case("ward_cosmin", "m", 90.0),
}
METHODS = ("engine", "product_grid", "dblquad", "monte_carlo")


class CountingBRDF:
    """A BRDF that counts the directions it is evaluated at (attributes pass through)."""

    def __init__(self, brdf):
        self.brdf = brdf
        self.count = 0

    def __getattr__(self, name):
        return getattr(self.brdf, name)

    def __call__(self, L, V):
        V = np.asarray(V, float)
        self.count += V.size // 3
        return self.brdf(L, V)


def engine(brdf, theta_deg, rtol):
    counted = CountingBRDF(brdf)
    est = albedo_many([counted], [theta_deg], rtol=rtol, atol=DEFAULT_ATOL)
    return float(est.value[0]), float(est.error[0]), counted.count


def product_grid(brdf, theta_deg, n):
    """N × N Gauss–Legendre in (u = cos θ_V, φ_V ∈ [0, π]), doubled by symmetry."""
    counted = CountingBRDF(brdf)
    value = _grid_sum(counted, theta_deg, n)
    coarse = _grid_sum(brdf, theta_deg, n // 2) if n >= 2 else np.nan
    return value, abs(value - coarse), counted.count


def _grid_sum(brdf, theta_deg, n):
    x, w = np.polynomial.legendre.leggauss(n)
    u, wu = 0.5 * (x + 1), 0.5 * w
    phi, wphi = 0.5 * np.pi * (x + 1), 0.5 * np.pi * w
    U, P = np.meshgrid(u, phi, indexing="ij")
    s = np.sqrt((1 - U) * (1 + U))
    V = np.stack([s * np.cos(P), s * np.sin(P), U], -1)
    f = brdf(light_direction(theta_deg), V)
    return float(2 * np.einsum("i,j,ij->", wu, wphi, f * U))


def scipy_dblquad(brdf, theta_deg, epsrel):
    counted = CountingBRDF(brdf)
    L = light_direction(theta_deg)

    def integrand(phi, theta):
        st = np.sin(theta)
        return float(counted(L, np.array([st * np.cos(phi), st * np.sin(phi), np.cos(theta)]))) * np.cos(theta) * st

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        value, err = dblquad(integrand, 0.0, np.pi / 2, 0.0, np.pi, epsabs=0.0, epsrel=epsrel)
    return 2 * value, 2 * err, counted.count


def monte_carlo(brdf, theta_deg, n, seed_sequence):
    """Cosine-weighted sampling of V (:func:`brdfs.numerics.grazing.monte_carlo_albedo`); error = standard error."""
    est, stderr = monte_carlo_albedo(brdf, theta_deg, "cosine", n, seed_sequence)
    return float(est.value), float(stderr), n


def accuracy_cost(cases, engine_rtol, grid_n, dblquad_epsrel, mc_samples, seed):
    """One row per (case, method, setting): value, error estimate, true error, evaluations."""
    rows = []
    for k, spec in enumerate(cases):
        case = CASES[spec["case"]]
        value = float(spec[case.parameter])
        brdf = model(case.model, **{case.parameter: value})
        exact = case.exact(value)
        runs = ([("engine", r, engine(brdf, case.theta_deg, r)) for r in engine_rtol]
                + [("product_grid", n, product_grid(brdf, case.theta_deg, n)) for n in grid_n]
                + [("dblquad", e, scipy_dblquad(brdf, case.theta_deg, e)) for e in dblquad_epsrel])
        runs += [("monte_carlo", n, monte_carlo(brdf, case.theta_deg, n, [seed, k, n])) for n in mc_samples]
        for method, setting, (v, err, count) in runs:
            rows.append({"case": spec["case"], "model": case.model, "parameter": case.parameter,
                         "parameter_value": value, "theta_deg": case.theta_deg, "method": method,
                         "setting": float(setting), "evaluations": int(count), "albedo": v, "albedo_err": err,
                         "exact": exact, "true_error": abs(v - exact)})
    return rows
