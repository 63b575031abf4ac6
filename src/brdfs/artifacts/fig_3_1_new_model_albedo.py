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
    at60 = df[df["theta_deg"] == 60.0].set_index("n")["albedo"]
    gaps = ", ".join(f"{1 - a:.3g}" for a in at60)
    ax.set_title(f"Fig. 3.1: albedo of the new model for different n (choice: n = "
                 f"{', '.join(f'{n:g}' for n in at60.index)})\nc = (n+2)/2π; 1 − a(60°) = {gaps}", fontsize=8)
    plotting.savefig(fig, path)
