"""Work against precision of the albedo methods on hard problems (``extra_work_precision``).

Every run goes through the albedo front door, :func:`brdfs.albedo` with a ``method``, so that cost
is counted the same way for all of them: BRDF evaluations (deterministic, unlike wall time on a
shared machine; ``make benchmark`` measures the same runs in seconds).  Accuracy is the true error
against a reference: the closed form where the model has one at that angle
(``model.exact_albedo``), else the engine at ``reference_rtol``, whose own error is reported
beside it and is cross-checked against the independent projected-disk route in the tests and in
the accuracy map.

A case names a model, its parameters and an incidence angle; ``theta_deg: max`` asks for the
angle of the model's largest albedo (corrected Blinn n = 2 has it inside, near 41°).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs import albedo, model
from brdfs.numerics.quantities import max_albedo

#: Methods in the chart: the front door's method, and the option that varies along a curve.
SETTINGS = {"engine": "rtol", "product_grid": "n", "dblquad": "epsrel", "monte_carlo": "n_samples"}


def case_model(case: dict):
    """The BRDF of a case: every key but ``theta_deg`` and ``label`` is a model parameter."""
    params = {k: v for k, v in case.items() if k not in ("model", "theta_deg", "label")}
    return model(case["model"], **params)


def case_angle(case: dict, brdf) -> float:
    """The case's incidence angle; ``max``: where the albedo is largest (:func:`max_albedo`)."""
    if case["theta_deg"] == "max":
        return float(max_albedo([brdf], rtol=1e-10)[1][0])
    return float(case["theta_deg"])


def reference(brdf, theta_deg: float, reference_rtol: float) -> tuple[float, float, str]:
    """(value, error, kind) of the reference: the closed form if there is one, else the engine."""
    exact = float(brdf.exact_albedo(theta_deg))
    if np.isfinite(exact):
        return exact, 4 * np.finfo(float).eps * abs(exact), "closed_form"
    est = albedo(brdf, theta_deg, rtol=reference_rtol, atol=1e-16)
    return float(est.value), float(est.error), "engine"


def runs(sec: dict, seed: int):
    """(method, sampler, setting, options) of every run of the chart, in a fixed order."""
    out = [("engine", "", r, {"rtol": r}) for r in sec["engine_rtol"]]
    out += [("product_grid", "", n, {"n": int(n)}) for n in sec["grid_n"]]
    out += [("dblquad", "", e, {"epsrel": e}) for e in sec["dblquad_epsrel"]]
    out += [("monte_carlo", s, n, {"sampler": s, "n_samples": int(n)})
            for s in sec["mc_samplers"] for n in sec["mc_samples"]]
    return out


def planned_runs(sec: dict, seed: int):
    """Every run of the chart in a fixed order, with its case's model, angle and reference:
    ``(case_label, brdf, theta, (ref, ref_err, ref_kind), method, sampler, setting, options)``.
    The artifact counts their evaluations; ``make benchmark`` times the same runs."""
    for k, case in enumerate(sec["cases"]):
        brdf = case_model(case)
        theta = case_angle(case, brdf)
        ref = reference(brdf, theta, sec["reference_rtol"])
        for j, (method, sampler, setting, options) in enumerate(runs(sec, seed)):
            if method == "monte_carlo":
                options = {**options, "seed": [seed, k, j]}
            yield case["label"], brdf, theta, ref, method, sampler, setting, options


def work_precision(sec: dict, seed: int) -> pd.DataFrame:
    """One row per (case, method, sampler, setting): value, reported error, true error, evaluations."""
    rows = []
    for label, brdf, theta, (ref, ref_err, ref_kind), method, sampler, setting, options in planned_runs(sec, seed):
        # coarse settings miss the tolerance on purpose: the status column records it, no warning
        est = albedo(brdf, theta, method, warn=False, **options)
        value, err = float(est.value), float(est.error)
        rows.append({"case": label, "model": brdf.name, "theta_deg": theta, "method": method,
                     "sampler": sampler, "setting": float(setting), "evaluations": int(est.evaluations),
                     "status": str(est.status), "albedo": value, "albedo_err": err,
                     "reference": ref, "reference_err": ref_err, "reference_kind": ref_kind,
                     "true_error": abs(value - ref),
                     "dishonest": bool(abs(value - ref) > err + ref_err)})
    return pd.DataFrame(rows)
