"""Single-scattering albedo E(μ) of GGX and Beckmann microfacet conductors (F = 1, Smith's separable and
height-correlated G2, exact Λ) over roughness α and μ = cos θ, and its cosine-weighted average
E_avg(α) = 2 ∫₀¹ E(μ) μ dμ, the two ingredients of Kulla–Conty's compensation.

E(μ) comes from the engine (:func:`brdfs.albedo`) at ``microfacet.table_rtol``; E_avg from the Chebyshev
E table the compensated models are built with (:func:`brdfs.artifacts._microfacet_energy.energy_table`), its error
the table's error bound.  Rows: ``quantity = E`` (one per μ), ``quantity = E_avg`` (``mu`` empty), and
``quantity = E_table_node``: the nodes of every Kulla–Conty E table (``piece, x_lo, x_hi, node``; ``mu`` the
node, ``albedo_err`` the table's bound) — those of ``average_alpha`` and those at the roughness matched to
the pumping tables' n (the figures' α), which the figures read instead of recomputing them.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.numerics.albedo import albedo
from brdfs.physics.models import model
from brdfs.artifacts import _microfacet_energy as mf
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import table

#: Panel titles per distribution.
TITLES = {"ggx": "GGX", "beckmann": "Beckmann"}
COLUMNS = ["model", "G2", "alpha", "quantity", "mu", "albedo", "albedo_err", "piece", "x_lo", "x_hi", "node"]


def figure_alphas(deps) -> list[float]:
    """α matched to the n of the pumping tables (Phong and Blinn), :mod:`brdfs.artifacts._microfacet_energy`."""
    return [float(mf.alpha_of_n(family, deps[name]["n"].iloc[0])) for family, name in mf.PUMPING_TABLES.items()]


@table("extra_microfacet_albedo", deps=tuple(mf.PUMPING_TABLES.values()), config=("microfacet",), chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Columns ``model, G2, alpha, quantity (E | E_avg | E_table_node), mu, albedo, albedo_err`` and, for the
    node rows, ``piece, x_lo, x_hi, node``."""
    c = cfg["microfacet"]
    mu = np.asarray(c["table_mu"], float)
    theta = np.degrees(np.arccos(np.clip(mu, 0.0, 1.0)))
    frames = []
    for name in ("ggx", "beckmann"):
        for G2 in c["table_G2"]:
            for alpha in c["table_alpha"]:
                est = albedo(model(name, alpha=float(alpha), G2=G2), theta, rtol=c["table_rtol"])
                frames.append(pd.DataFrame({"model": name, "G2": G2, "alpha": float(alpha), "quantity": "E",
                                            "mu": mu, "albedo": est.value, "albedo_err": est.error}))
        averaged = [(G2, float(a)) for G2 in c["average_G2"] for a in c["average_alpha"]]
        averaged += [("height_correlated", a) for a in figure_alphas(deps)]
        for G2, alpha in averaged:
            e_avg = mf.energy_table(name, alpha, G2)[1]
            frames.append(pd.DataFrame({"model": [name], "G2": [G2], "alpha": [alpha], "quantity": ["E_avg"],
                                        "mu": [np.nan], "albedo": [e_avg.value], "albedo_err": [e_avg.error]}))
            frames.append(mf.energy_table_frame(name, alpha, G2).assign(quantity="E_table_node"))
    return pd.concat(frames, ignore_index=True).reindex(columns=COLUMNS)


def plot(df: pd.DataFrame, path) -> None:
    """E(μ) per α (one panel per distribution), height-correlated solid, separable dashed; E_avg in the legend."""
    fig, axes = plotting.plt.subplots(1, 2, figsize=(10, 6.0), sharey=True)
    fig.subplots_adjust(bottom=0.38)
    averages = df[df["quantity"] == "E_avg"]
    for ax, name in zip(axes, ("ggx", "beckmann")):
        curves = df[(df["quantity"] == "E") & (df["model"] == name)]
        for (G2, alpha), g in curves.groupby(["G2", "alpha"], sort=True):
            avg = averages[(averages["model"] == name) & (averages["G2"] == G2) & (averages["alpha"] == alpha)]
            label = f"α = {alpha:g}, {G2}" + (f", E_avg = {avg['albedo'].iloc[0]:.4f}" if not avg.empty else "")
            ax.plot(g["mu"], g["albedo"], "-" if G2 == "height_correlated" else "--", marker=".", label=label)
        ax.set(xlabel="μ = cos θ", ylabel="single-scattering albedo E(μ), F = 1", title=TITLES[name])
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    fig.suptitle("Single-scattering albedo of microfacet conductors with Smith's G2 (engine)", fontsize=9)
    plotting.savefig(fig, path)
