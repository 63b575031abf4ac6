"""Accuracy against cost of four albedo integration methods on albedos with closed forms
(:mod:`brdfs.artifacts._accuracy`): the lobe-following engine, a product Gauss grid, scipy's dblquad over
(θ_V, φ_V) and cosine-weighted Monte Carlo. Cost in BRDF evaluations, accuracy as true error."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.artifacts._accuracy import METHODS, accuracy_cost
from brdfs.pipeline.registry import figure

NAME = "extra_accuracy_cost"
SECTION = "accuracy_cost"
MARKERS = dict(zip(METHODS, "os^x"))


@figure(NAME, config=(SECTION,), batch=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``case, model, parameter, parameter_value, theta_deg, method, setting, evaluations, albedo,
    albedo_err, exact, true_error``."""
    sec = cfg[SECTION]
    return pd.DataFrame(accuracy_cost(sec["cases"], sec["engine_rtol"], sec["grid_n"], sec["dblquad_epsrel"],
                                      sec["mc_samples"], cfg["seed"]))


def plot(df: pd.DataFrame, path) -> None:
    """One panel per case: true error (solid) and the method's own estimate (dotted) against cost."""
    cases = list(dict.fromkeys(df["case"]))
    fig, axes = plotting.plt.subplots(1, len(cases), figsize=(5.2 * len(cases), 4.6), squeeze=False)
    floor = 1e-17
    for ax, case in zip(axes[0], cases):
        sub = df[df["case"] == case]
        first = sub.iloc[0]
        for method in METHODS:
            m = sub[sub["method"] == method].sort_values("evaluations")
            line, = ax.loglog(m["evaluations"], np.maximum(m["true_error"], floor), marker=MARKERS[method],
                              label=f"{method}: true error")
            ax.loglog(m["evaluations"], np.maximum(m["albedo_err"], floor), ":", color=line.get_color(),
                      label=f"{method}: own estimate")
        ax.set_title(f"{first['model']}, {first['parameter']} = {first['parameter_value']:g}, "
                     f"θ = {first['theta_deg']:g}° (exact {first['exact']:.10g})", fontsize=9)
        ax.set_xlabel("BRDF evaluations")
        ax.set_ylabel("albedo error (absolute)")
        ax.grid(True, which="major", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    for ax in axes[0]:
        for line in ax.get_lines():
            line.set_label("_" + line.get_label())  # one legend for the figure, below the panels
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=4, fontsize=7)
    fig.suptitle("Accuracy against cost of albedo integration methods (errors below 1e-17 drawn at 1e-17)")
    fig.tight_layout()
    plotting.savefig(fig, path)
