"""Chi-square tests of every model's importance sampler (issue 14): results/checks/sampling_chi2.csv.

Each row is one test (:func:`brdfs.numerics.chi2.chi2_test`) of ``model.sample`` against ``model.pdf``
at one incidence angle; ``passed`` is p ≥ the Šidák level of the family of tests in the file.  The
reduced set (default) tests every model in ``MODELS`` at the narrowest parameter of the thesis's range
(n = 512, m = 0.005, s = 512, …) at 45° and 89.99°, plus the cosine baseline; ``sampling.full``
runs every strategy over the parameter range at six incidence angles up to 89.99°.  Each model
declares its parameter sets (``chi2_cases``, narrowest first, else its ``examples``) and how it is
built from them (``chi2_example``): a model added to ``MODELS`` is tested without an edit here.
"""
from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

from brdfs.numerics.chi2 import chi2_test, sidak_level
from brdfs.physics.models import MODELS
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import check

NAME = "sampling_chi2"
SECTION = "sampling"

REDUCED_THETAS = (45.0, 89.99)
FULL_THETAS = (0.0, 30.0, 60.0, 80.0, 89.0, 89.99)


def parameters(name: str) -> tuple[dict, ...]:
    """The parameter sets the model ``name`` is tested at, narrowest first: its declared
    :meth:`~brdfs.physics.models.base.BRDF.chi2_parameters` (``chi2_cases``, else its examples)."""
    plist = MODELS[name].chi2_parameters()
    if not plist:
        raise ValueError(f"sampling_chi2: the model {name!r} declares neither chi2_cases nor examples")
    return plist


def build(name, params):
    """The model ``name`` at ``params``, as the model builds its test cases (``chi2_example``)."""
    return MODELS[name].chi2_example(params)


def cases(full: bool):
    """(name, params, strategy, theta_deg) of the tests: every model of ``MODELS``, its cases from itself."""
    out = []
    for name in MODELS:
        plist = parameters(name) if full else parameters(name)[:1]
        for params in plist:
            strategies = build(name, params).strategies
            chosen = strategies if full else strategies[:1]
            for strategy in chosen:
                for theta in (FULL_THETAS if full else REDUCED_THETAS):
                    out.append((name, params, strategy, theta))
    if not full:   # the cosine baseline, once (it does not depend on the model)
        out += [("phong", {"n": 20}, "cosine", t) for t in REDUCED_THETAS]
    return out


#: Processes running the full-size tests (``sampling.full: true``, minutes; run that alone, e.g.
#: ``snakemake --cores 2 results/checks/sampling_chi2.csv``).  The default run (4 s) is one process:
#: a two-thread job waits until both cores are free, which in the whole rebuild left it for last,
#: alone on one core's worth of work (the rule declares one thread).
FULL_WORKERS = 2


def _run(job):
    name, params, strategy, theta, n, seed, n_r, n_phi = job
    return chi2_test(build(name, params), theta, strategy, n_samples=n, seed=seed, n_radial=n_r, n_phi=n_phi,
                     n_pilot=max(n // 4, 5000))


@check(NAME, config=(SECTION,), resources={"runtime": 2, "threads": 1}, chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``model, parameters, strategy, theta_deg, n_samples, statistic, dof, p_value, sidak_level,
    pdf_mass, accepted_fraction, weight_error, passed``."""
    sec = cfg[SECTION]
    full = bool(sec["full"])
    n = sec["full_n_samples"] if full else sec["n_samples"]
    n_r = sec["full_radial_bins"] if full else sec["radial_bins"]
    n_phi = sec["full_phi_bins"] if full else sec["phi_bins"]
    todo = cases(full)
    level = sidak_level(len(todo), sec["significance"])
    jobs = [(name, params, strategy, theta, n, [cfg["seed"], k], n_r, n_phi) for k, (name, params, strategy, theta)
            in enumerate(todo)]
    # Each test has its own seed, so the pool's scheduling cannot change a number.
    if full:
        with ProcessPoolExecutor(max_workers=FULL_WORKERS) as pool:
            results = list(pool.map(_run, jobs))
    else:
        results = [_run(job) for job in jobs]
    rows = []
    for (name, params, strategy, theta, *_), r in zip(jobs, results):
        rows.append({"model": name, "parameters": " ".join(f"{a}={b:g}" for a, b in params.items()),
                     "strategy": strategy, "theta_deg": theta, "n_samples": n, "statistic": r.statistic,
                     "dof": r.dof, "p_value": r.p_value, "sidak_level": level, "pdf_mass": r.pdf_mass,
                     "accepted_fraction": r.accepted_fraction, "weight_error": r.weight_error,
                     "passed": bool(r.p_value >= level and r.dof >= 1)})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path) -> None:
    fig, ax = plotting.new_axes("test", "p-value", "Sampler chi-square tests (Sidak level dashed)")
    x = np.arange(len(df))
    for passed, marker in ((True, "o"), (False, "x")):
        sel = df["passed"] == passed
        if sel.any():
            ax.plot(x[sel], df["p_value"][sel], marker, linestyle="none",
                    label="passed" if passed else "failed")
    ax.axhline(float(df["sidak_level"].iloc[0]), linestyle="--", color="k")
    ax.set_yscale("log")
    ax.set_ylim(min(float(df["sidak_level"].iloc[0]) / 10, max(df["p_value"].min(), 1e-300)), 1.5)
    ax.legend(loc="lower left")
    plotting.savefig(fig, path)
