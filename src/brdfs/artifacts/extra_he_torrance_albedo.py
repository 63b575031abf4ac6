"""He–Torrance albedo (σ0 = 0.1 µm, τ = 1.7 µm, F = 1, the parameters of Figs. 2.1 and 3.4) with and
without the specular delta: which of the two is the thesis's "badly decreasing" curve.

The thesis does not say whether its He–Torrance albedo includes the specular term (a Monte Carlo
integration over the hemisphere would miss the delta).  Every term is computed through
:func:`brdfs.numerics.albedo.albedo`: 'dd' (directional diffuse), 'specular' (ρ_s, the delta's closed-form
albedo) and 'total' (their sum).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.numerics.albedo import albedo
from brdfs.core.estimate import Estimate
from brdfs.pipeline.registry import figure
from brdfs.physics.models.he_torrance import TERMS, HeTorrance


def incidence_grid(step_deg: float, extra_deg) -> np.ndarray:
    """A uniform grid on [0°, 90°] with step ``step_deg``, plus the angles ``extra_deg``."""
    uniform = np.linspace(0.0, 90.0, int(round(90.0 / step_deg)) + 1)
    return np.unique(np.concatenate([uniform, np.asarray(extra_deg, float)]))


@figure("extra_he_torrance_albedo", config=("he_torrance",), chapter=2)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Albedo of each term on the incidence grid.

    Returns
    -------
    pandas.DataFrame
        Columns ``model, sigma0_um, tau_um, lambda_um, ior_re, ior_im, term, theta_deg, albedo,
        albedo_err`` (``ior_re``, ``ior_im`` empty: F = 1).
    """
    section = cfg["he_torrance"]
    params = section["albedo"]
    theta = incidence_grid(params["theta_step_deg"], params["theta_extra_deg"])
    frames = []
    estimates = {}
    for term in TERMS:
        brdf = HeTorrance(sigma0_um=params["sigma0_um"], tau_um=params["tau_um"],
                          lambda_um=section["lambda_um"], term=term)
        if term == "total":
            # the total's density is the directional diffuse term: the engine's sum of the two, to the bit
            est = Estimate(estimates["dd"].value + estimates["specular"].value,
                           estimates["dd"].error + estimates["specular"].error)
        else:
            est = albedo(brdf, theta, rtol=cfg["tolerance"]["rtol"], atol=cfg["tolerance"]["atol"])
        estimates[term] = est
        frames.append(pd.DataFrame({
            "model": brdf.name, "sigma0_um": brdf.sigma0_um, "tau_um": brdf.tau_um, "lambda_um": brdf.lambda_um,
            "ior_re": "", "ior_im": "", "term": term, "theta_deg": theta, "albedo": est.value,
            "albedo_err": est.error}))
    return pd.concat(frames, ignore_index=True)


def overshoot(df: pd.DataFrame) -> str:
    """The runs of grid angles where the total albedo exceeds 1, each with its largest value (from the data)."""
    total = df[df["term"] == "total"].sort_values("theta_deg")
    above = (total["albedo"] > 1.0).to_numpy()
    run_id = np.cumsum(np.concatenate([[True], above[1:] != above[:-1]]))
    runs = [g for _, g in total[above].groupby(run_id[above])]
    if not runs:
        return "total albedo <= 1 everywhere"
    return "total > 1 on " + ", ".join(
        f"{g['theta_deg'].min():g}°–{g['theta_deg'].max():g}° (max {g['albedo'].max():.5f} at "
        f"{g.loc[g['albedo'].idxmax(), 'theta_deg']:g}°)" for g in runs)


def plot(df: pd.DataFrame, path) -> None:
    """The three curves with the line a = 1."""
    first = df.iloc[0]
    fig, ax = plotting.new_axes("incidence angle θ_L [deg]", "albedo a(θ_L)")
    names = {"dd": "directional diffuse only", "specular": "specular delta ρ_s", "total": "dd + specular"}
    for term, g in df.groupby("term", sort=False):
        ax.plot(g["theta_deg"], g["albedo"], label=names[term])
    ax.axhline(1.0, color="k", lw=0.6, ls=":")
    ax.set(xlim=(0, 90), ylim=(0, 1.1))
    ax.set_title(f"He–Torrance albedo (σ0 = {first['sigma0_um']:g} µm, τ = {first['tau_um']:g} µm, F = 1)", fontsize=10)
    ax.legend(loc="lower left")
    plotting.savefig(fig, path)
