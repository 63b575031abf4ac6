"""Readings of the printed divergence numbers of Secs. 3.7.2 (Ward) and 3.7.3 (Cook–Torrance),
and their comparison ``grazing_divergence``.

The readings are fixed in config.yaml (``grazing.readings``) before any is compared with the
print: the exact albedo integral (the engine) and the discretisations a program of the time
plausibly used (midpoint (θ_V, φ_V) grids, Monte Carlo with three samplers and several N), for
each geometry factor (eq. 2.10 as printed, Smith eq. 1.38, G = 1) and, for Cook–Torrance, each
constant of D G/(N·L N·V) (eq. 2.9, the original Cook–Torrance paper, eqs. 1.35–1.36).  All are
reported; the comparison then names those, if any, that reproduce a print.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.numerics.albedo import albedo
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.numerics.albedo import monte_carlo_albedo
from brdfs.numerics.grazing import NORMALISATION_FACTORS
from brdfs.physics.models import model

ARTIFACT = "grazing_divergence"
#: The reading the thesis's own formulas prescribe: eq. 2.9 with G of eq. 2.10, integrated exactly.
AS_PRINTED = {"method": "exact", "G": "torrance_sparrow", "normalisation": "eq_2_9"}


def _models(r: dict) -> list[tuple]:
    """(model, G, normalisations, theta list) of every base model the readings integrate, with the
    (label, factor) of every constant the readings multiply it by: Ward's own (eq. 3.35, factor 1),
    Cook–Torrance's D G/(N·L N·V) constants (:data:`brdfs.numerics.grazing.NORMALISATION_FACTORS`)."""
    ward = (model("ward", m=r["ward_m"]), "", [("eq_3_35", 1.0)], r["ward_theta_deg"])
    ct_norms = [(n, NORMALISATION_FACTORS[n]) for n in r["normalisations"]]
    cts = [(model("cook_torrance", m=r["cook_torrance_m"], G=g), g, ct_norms, r["cook_torrance_theta_deg"])
           for g in r["geometry_factors"]]
    return [ward, *cts]


def _methods(r: dict, seed: int, key: tuple) -> list[tuple]:
    """(method, n_theta, n_phi, n_samples, sampler seed sequence) of every discretisation."""
    grids = [("grid", g["n_theta"], g["n_phi"], 0, None) for g in r["grids"]]
    mc = [(f"mc_{s}", 0, 0, n, np.random.SeedSequence([seed, *key, i, n]))
          for i, s in enumerate(r["mc_samplers"]) for n in r["mc_samples"]]
    return [("exact", 0, 0, 0, None), *grids, *mc]


def _evaluate(brdf, theta, method, n_theta, n_phi, n_samples, seq, tol):
    """(albedo, albedo_err, mc_stderr) of one reading."""
    if method == "exact":
        est = albedo(brdf, theta, rtol=tol["rtol"], atol=tol["atol"])
        return float(est.value), float(est.error), np.nan
    if method == "grid":
        est = albedo(brdf, theta, "midpoint_grid", n_theta=n_theta, n_phi=n_phi)
        return float(est.value), float(est.error), np.nan
    est = monte_carlo_albedo(brdf, theta, method.removeprefix("mc_"), n_samples, seq)
    return float(est.value), float(est.rounding), float(est.error)


@table("extra_divergence_readings", config=("grazing",), chapter=3)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Every reading at every printed angle.

    Returns
    -------
    pandas.DataFrame
        Columns ``model, G, normalisation, m, C, method, n_theta, n_phi, n_samples, seed,
        theta_deg, albedo, albedo_err, mc_stderr``. ``albedo_err`` bounds the error of computing
        the reading (quadrature error for ``exact``, rounding for a grid or a seeded Monte Carlo
        sum); ``mc_stderr`` is the Monte Carlo estimator's own standard error, its distance from
        the exact integral.  Normalisations other than eq. 2.9 are the eq. 2.9 values times
        their constant factor (:data:`brdfs.numerics.grazing.NORMALISATION_FACTORS`).
    """
    r = cfg["grazing"]["readings"]
    records = []
    for k, (brdf, g, norms, thetas) in enumerate(_models(r)):
        for j, theta in enumerate(thetas):
            for method, n_theta, n_phi, n_samples, seq in _methods(r, cfg["seed"], (k, j)):
                value, err, stderr = _evaluate(brdf, theta, method, n_theta, n_phi, n_samples, seq, cfg["tolerance"])
                base = {"model": brdf.name, "G": g, "m": brdf.m, "C": brdf.C, "method": method, "n_theta": n_theta,
                        "n_phi": n_phi, "n_samples": n_samples, "seed": cfg["seed"] if seq else 0, "theta_deg": theta}
                for name, factor in norms:
                    records.append(base | {"normalisation": name, "albedo": factor * value,
                                           "albedo_err": factor * err + 2 * np.finfo(float).eps * abs(factor * value),
                                           "mc_stderr": factor * stderr})
    columns = ["model", "G", "normalisation", "m", "C", "method", "n_theta", "n_phi", "n_samples", "seed",
               "theta_deg", "albedo", "albedo_err", "mc_stderr"]
    return pd.DataFrame.from_records(records)[columns]


def plot(df: pd.DataFrame, path) -> None:
    """Every reading against the angle, one panel per model, the prints marked."""
    fig, axes = plotting.plt.subplots(1, 2, figsize=(11, 4.6))
    prints = published.published_rows(ARTIFACT)
    for ax, name in zip(axes, ("ward", "cook_torrance")):
        sub = df[df["model"] == name]
        for key, g in sub.groupby(["G", "normalisation", "method", "n_theta", "n_samples"], sort=False):
            style = "-" if key[2] == "exact" else ":"
            ax.loglog(90.0 - g["theta_deg"], g["albedo"], style, marker=".", lw=0.8, alpha=0.6)
        p = prints[prints["model"] == name]
        angles = [float(q.removeprefix("albedo_at_").removesuffix("deg")) for q in p["quantity"]]
        ax.loglog(90.0 - np.array(angles), p["published"].astype(float), "k*", ms=12, label="printed")
        ax.invert_xaxis()
        ax.set(title=f"{name}: {sub.groupby(['G', 'normalisation', 'method', 'n_theta', 'n_samples']).ngroups} readings",
               xlabel="90° − θ_L [deg]", ylabel="albedo")
    fig.suptitle("Readings of the printed divergence numbers (solid: exact; dotted: grids, Monte Carlo)", fontsize=10)
    plotting.savefig(fig, path)


READING_KEY = ["G", "normalisation", "method", "n_theta", "n_phi", "n_samples"]


def reading_name(key: tuple) -> str:
    """A reading as text, e.g. ``G=none, eq_2_9, mc_cosine N=100000``."""
    g, norm, method, n_theta, n_phi, n_samples = key
    detail = {"grid": f" {n_theta}x{n_phi}", "exact": ""}.get(method, f" N={n_samples}")
    return f"{'G=' + g + ', ' if g else ''}{norm}, {method}{detail}"


def _angle(quantity: str) -> float:
    return float(quantity.removeprefix("albedo_at_").removesuffix("deg"))


def _hits(readings: pd.DataFrame, prints: pd.DataFrame) -> pd.DataFrame:
    """For every reading of the model, at every printed angle, whether it reproduces the print."""
    printed = {_angle(q): p for q, p in zip(prints["quantity"], prints["published"])}
    sub = readings[readings["theta_deg"].isin(printed)].copy()
    sub["hit"] = [published.rounds_to(printed[t], v) for t, v in zip(sub["theta_deg"], sub["albedo"])]
    return sub


def _model_fact(row, readings: pd.DataFrame, theta: float, computed: float) -> str:
    """What bounds, laws and the Monte Carlo spread say about the print."""
    at = readings[readings["theta_deg"] == theta]
    printed = float(row.published)
    if row.model == "ward":
        mc = at[at["method"].isin(["mc_uniform", "mc_cosine"]) & (at["n_samples"] <= 100_000)]["mc_stderr"]
        return (f"the print is {printed - computed:+.3f} ({printed / computed - 1:+.1%}) from it, less than the "
                f"standard error ({mc.min():.2f}-{mc.max():.2f}) of Monte Carlo estimates with 1e4-1e5 uniform or "
                f"cosine samples, the integration the thesis says it used (Sec. 3.9); the other two prints reproduce")
    exact = at[at["method"] == "exact"]
    g1 = exact[(exact["G"] == "none") & (exact["normalisation"] == "eq_2_9")]["albedo"].iloc[0]
    mu, k = np.sin(np.radians(90.0 - theta)), float(at["m"].iloc[0]) / (2 * np.sqrt(np.pi))
    return (f"with G of eq. 2.10 the albedo is at most 2 at every incidence (G <= 2 N.H N.L / L.H gives "
            f"a <= 2 int D N.H dw_H), so no integration of eqs. 2.9-2.10 can print it, and it tends to 1; "
            f"with G = 1 it is {g1:.4g} ~ m/(2 sqrt(pi) cos theta_L) = {k / mu:.4g}, "
            f"while print x cos theta_L = {printed * mu:.3g} against m/(2 sqrt(pi)) = {k:.3g}")


def _explain(row, hits: pd.DataFrame, computed: float) -> dict:
    """Reason, verdict, closest reading and Monte Carlo z-score for a print the formula does not reproduce."""
    theta = _angle(row.quantity)
    all_hit = hits.groupby(READING_KEY, sort=False)["hit"].all()
    consistent = [k for k, ok in all_hit.items() if ok]
    here = hits[hits["theta_deg"] == theta]
    printed = float(row.published)
    closest = here.loc[(here["albedo"] - printed).abs().idxmin()]
    out = {"evidence": get_artifact("extra_divergence_readings").csv, "family_size": str(all_hit.size),
           "reading": reading_name(tuple(closest[k] for k in READING_KEY)), "value_under_reading": float(closest["albedo"])}
    as_printed = here
    if row.model == "cook_torrance":
        as_printed = here[(here["G"] == AS_PRINTED["G"]) & (here["normalisation"] == AS_PRINTED["normalisation"])]
    mc = monte_carlo_z(as_printed, printed, computed)
    lone = "; ".join(f"{reading_name(tuple(r[k] for k in READING_KEY))} gives {r['albedo']:.4g}"
                     for _, r in here[here["hit"]].head(3).iterrows())
    out["reason"] = (
        f"the formula as printed, integrated to 1e-10, gives {computed:.5g}; "
        f"{_model_fact(row, hits, theta, computed)}; "
        f"{len(consistent)} of {all_hit.size} readings fixed in advance reproduce all prints of this model"
        + (f", {int(here['hit'].sum())} this one alone ({lone})" if here["hit"].any() else ", none this one")
        + f"; {mc['text']}"
    )
    out["z_score"] = mc["z"]
    if mc["within"]:
        out |= {"reading_verdict": "within Monte Carlo error", "reading": mc["reading"],
                "value_under_reading": computed}
    return out


def monte_carlo_z(at: pd.DataFrame, printed: float, exact: float) -> dict:
    """The print's z-score against a Monte Carlo estimate with the smallest declared sample count.

    The thesis says it integrated numerically "(Monte-Carlo)" (Sec. 3.9) and states no sample count
    or sampler, so the standard deviation is that of the most efficient declared sampler (the
    strictest test) at the smallest declared count N_min (``grazing.readings.mc_samples``, ≥ 1e3):
    σ_N = σ₁/√N_min, σ₁ = its standard error × √N at the largest N. The variance counts as finite
    when σ₁ from the two largest N agree within 25 %; |z| ≤ 3 is within Monte Carlo error."""
    mc = at[at["method"].str.startswith("mc_")]
    counts = sorted(mc["n_samples"].unique())
    rows = []
    for method, part in mc.groupby("method", sort=False):
        by_n = part.set_index("n_samples")["mc_stderr"]
        sigma = by_n[counts[-1]] * np.sqrt(counts[-1])
        finite = abs(sigma / (by_n[counts[-2]] * np.sqrt(counts[-2])) - 1) <= 0.25
        rows.append((sigma, method, finite))
    sigma, method, finite = min(rows)
    sigma_n = sigma / np.sqrt(counts[0])
    z = (printed - exact) / sigma_n
    within = bool(finite and abs(z) <= readings.MC_Z_MAX and counts[0] >= 1000)
    text = (f"against {method.removeprefix('mc_')} Monte Carlo with N = {counts[0]:,} (sigma = {sigma_n:.3g}, "
            f"per-sample sigma {sigma:.3g} {'stable' if finite else 'unstable'} between N = {counts[-2]:,} and "
            f"{counts[-1]:,}) the print is z = {z:+.2f}")
    return {"z": float(z), "within": within, "text": text,
            "reading": f"{method.removeprefix('mc_')} Monte Carlo, N = {counts[0]:,} (the smallest declared count)"}


@comparison(ARTIFACT, tables=("extra_divergence_readings",))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Computed = eq. 3.35 (Ward) or eqs. 2.9-2.10 (Cook–Torrance) integrated exactly; readings where it differs."""
    readings = tables["extra_divergence_readings"].fillna({"G": ""})
    prints = published.published_rows(ARTIFACT)
    records = []
    for row in prints.itertuples(index=False):
        mine = readings[readings["model"] == row.model]
        exact = mine[(mine["method"] == "exact") & (mine["theta_deg"] == _angle(row.quantity))]
        if row.model == "cook_torrance":
            exact = exact[(exact["G"] == AS_PRINTED["G"]) & (exact["normalisation"] == AS_PRINTED["normalisation"])]
        value, err = float(exact["albedo"].iloc[0]), float(exact["albedo_err"].iloc[0])
        record = {"model": row.model, "param_value": row.param_value, "quantity": row.quantity,
                  "computed": value, "computed_err": err}
        if published.verdict(row.published, value, err) == published.DIFFERS:
            record |= _explain(row, _hits(mine, prints[prints["model"] == row.model]), value)
        records.append(record)
    return pd.DataFrame.from_records(records)
