"""The albedo toward grazing incidence, 80°–89.9999°, on log–log axes against cos θ_L, with the
asymptotic law of each model (Sec. 2.2.1; laws derived in :mod:`brdfs.numerics.grazing`)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _albedo_curves as albedo_curves
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.numerics.grazing import approach_angles, asymptotic_law


@figure("extra_grazing_divergence", deps=("fig_3_4_albedo_with_new_model",), config=("grazing",), chapter=3)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Albedo curves with the law's exponent, constant (and its error) and value at each angle.

    Returns
    -------
    pandas.DataFrame
        Curve columns (:func:`brdfs.artifacts._albedo_curves.curves`) plus ``law_exponent, law_constant,
        law_constant_err, law_albedo, law``: a ~ law_constant cos^(−law_exponent) θ_L.
    """
    g = cfg["grazing"]
    theta = approach_angles(max(g["approach_from"], -1.0), g["approach_to"], g["per_decade"])
    # The curves Figure 3.4 has (on a grid that contains these angles) are taken from its table;
    # the others are integrated to the figure's own tolerance.  The laws' constants (1-D integrals,
    # printed to 6 digits in the legend) keep the default tolerance.
    tol = {**cfg["tolerance"], "rtol": g["divergence_rtol"]}
    df = albedo_curves.curves(g["divergence_models"], theta, tol, known=deps["fig_3_4_albedo_with_new_model"])
    laws = []
    for spec in g["divergence_models"]:
        law = asymptotic_law(albedo_curves.build(spec), cfg["tolerance"]["rtol"])
        laws.append({"label": albedo_curves.label(albedo_curves.build(spec)),
                     "law_exponent": law.exponent if law else np.nan,
                     "law_constant": float(law.constant.value) if law else np.nan,
                     "law_constant_err": float(law.constant.error) if law else np.nan,
                     "law": law.derivation if law else "none derived"})
    df = df.merge(pd.DataFrame(laws), on="label", how="left")
    return df.assign(law_albedo=df["law_constant"] * df["cos_theta"] ** -df["law_exponent"])


def plot(df: pd.DataFrame, path) -> None:
    """Computed points (markers) and laws (lines), log–log against cos θ_L; the legend beside the axes."""
    fig, ax = plotting.new_axes("cos θ_L (log)", "albedo a(θ_L) (log)")
    fig.set_size_inches(7.0, 5.0)
    for name, g in df.groupby("label", sort=False):
        dots, = ax.loglog(g["cos_theta"], g["albedo"], ".", ms=3, label=f"{name}")
        law = g["law"].iloc[0]
        ax.loglog(g["cos_theta"], g["law_albedo"], "-", lw=0.8, color=dots.get_color(),
                  label=f"   law: {law}, constant {g['law_constant'].iloc[0]:.6g}")
    ax.axhline(1.0, color="k", lw=0.6, ls=":")
    ax.invert_xaxis()
    ax.set_title("Albedo toward grazing incidence, 80°–89.9999° (points: engine; lines: laws)", fontsize=9)
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    plotting.savefig(fig, path)
