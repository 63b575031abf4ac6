"""Figure 2.1: albedo of Phong (n = 150), He–Torrance (σ0 = 0.1 µm, τ = 1.7 µm), Cook–Torrance
(m = 0.1) and Ward (m = 0.1), F = 1, on 0°–90° with points clustered toward 90° (Sec. 2.2)."""

from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _albedo_curves as albedo_curves
from brdfs.pipeline.registry import figure
from brdfs.numerics.grazing import incidence_grid


@figure("fig_2_1_albedo_classical", config=("grazing",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The curves: columns ``model, G, n, m, sigma0_um, tau_um, term, C, label, theta_deg, cos_theta, albedo, albedo_err``."""
    g = cfg["grazing"]
    theta = incidence_grid(g["theta_step_deg"], g["approach_from"], g["approach_to"], g["per_decade"])
    return albedo_curves.curves(g["fig_2_1_models"], theta, cfg["tolerance"])


def plot(df: pd.DataFrame, path) -> None:
    """Figure 2.1, with a log panel showing the approach to 90°."""
    albedo_curves.plot_curves(df, path, albedo_curves.figure_title("2.1", df))
