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

from brdfs.numerics.albedo import albedo
from brdfs.physics.models import model


@dataclass(frozen=True)
class Case:
    """An albedo with a closed form (``exact_albedo`` of the model class) at one angle."""

    model: str
    parameter: str
    theta_deg: float

    def brdf(self, value):
        return model(self.model, **{self.parameter: value})


CASES = {
    "phong_normal_incidence": Case("phong", "n", 0.0),
    "new_model_at_90": Case("phong_cosmin", "n", 90.0),
    "ward_cosmin_at_90": Case("ward_cosmin", "m", 90.0),
}
METHODS = ("engine", "product_grid", "dblquad", "monte_carlo")


def _run(brdf, theta_deg, method, setting, seed_sequence):
    """(value, error, BRDF evaluations) of one method at one setting, through the albedo front door."""
    if method == "engine":
        est = albedo(brdf, theta_deg, rtol=setting)
    elif method == "product_grid":
        est = albedo(brdf, theta_deg, "product_grid", n=int(setting))
    elif method == "dblquad":
        est = albedo(brdf, theta_deg, "dblquad", epsrel=setting)
    else:
        est = albedo(brdf, theta_deg, "monte_carlo", n_samples=int(setting), seed=seed_sequence)
    return float(est.value), float(est.error), est.evaluations


def accuracy_cost(cases, engine_rtol, grid_n, dblquad_epsrel, mc_samples, seed):
    """One row per (case, method, setting): value, error estimate, true error, evaluations."""
    rows = []
    for k, spec in enumerate(cases):
        case = CASES[spec["case"]]
        value = float(spec[case.parameter])
        brdf = case.brdf(value)
        exact = float(brdf.exact_albedo(case.theta_deg))
        settings = ([("engine", r) for r in engine_rtol] + [("product_grid", n) for n in grid_n]
                    + [("dblquad", e) for e in dblquad_epsrel] + [("monte_carlo", n) for n in mc_samples])
        runs = [(method, s, _run(brdf, case.theta_deg, method, s, [seed, k, int(s)])) for method, s in settings]
        for method, setting, (v, err, count) in runs:
            rows.append({"case": spec["case"], "model": case.model, "parameter": case.parameter,
                         "parameter_value": value, "theta_deg": case.theta_deg, "method": method,
                         "setting": float(setting), "evaluations": int(count), "albedo": v, "albedo_err": err,
                         "exact": exact, "true_error": abs(v - exact)})
    return rows
