"""Figure 3.1: albedo functions of the new model (eq. 3.10, c = (n+2)/2π) for different n."""
from __future__ import annotations

import pandas as pd

from brdfs.pipeline import plotting
from brdfs.artifacts import _new_model_figures as shared
from brdfs.pipeline.registry import figure


@figure("fig_3_1_new_model_albedo", config=("new_model_albedo",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """One albedo curve per n of ``fig_3_1_n``."""
    section = cfg["new_model_albedo"]
    return shared.albedo_curves(section["fig_3_1_n"], section["theta_step_deg"], cfg["tolerance"]["rtol"])


def plot(df: pd.DataFrame, path) -> None:
    """Albedo against incidence angle, one curve per n, with 1 − a(60°) per n in the caption."""
    fig, ax = plotting.plt.subplots()
    shared.plot_albedo(ax, df)
    ax.set_title("Figure 3.1: albedo of the new model for different n", fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    plotting.savefig(fig, path)
