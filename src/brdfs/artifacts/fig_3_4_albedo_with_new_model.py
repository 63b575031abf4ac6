"""Figure 3.4: the curves of Figure 2.1 and the new model ``phong_cosmin`` (n = 150), F = 1 (Sec. 3.2.4)."""

from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _albedo_curves as albedo_curves
from brdfs.pipeline.registry import figure
from brdfs.numerics.grazing import incidence_grid


@figure("fig_3_4_albedo_with_new_model", deps=("fig_2_1_albedo_classical",), config=("grazing",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The curves, columns as Figure 2.1's; the curves Figure 2.1 already has are taken from its table."""
    g = cfg["grazing"]
    theta = incidence_grid(g["theta_step_deg"], g["approach_from"], g["approach_to"], g["per_decade"])
    return albedo_curves.curves(g["fig_3_4_models"], theta, cfg["tolerance"], known=deps["fig_2_1_albedo_classical"])


def plot(df: pd.DataFrame, path) -> None:
    """Figure 3.4, with a log panel showing the approach to 90°."""
    albedo_curves.plot_curves(df, path, albedo_curves.figure_title("3.4", df))
