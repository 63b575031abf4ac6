"""Figure 2.5: Controlled pumping-up of the reciprocal Phong model.

Albedo (from the level tables) and radiance at the mirror direction of the reciprocal Phong
model (n = 20) pumped 0 ... K times with g2 (eq. 2.21).
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _pumping_figures as shared
from brdfs.pipeline.registry import figure

TABLE = "extra_pumping_albedo_phong"


@figure("fig_2_5_phong_controlled_pumping", deps=(TABLE,), config=("pumping",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Rows of albedo and radiance per level, and the distance of each level to eq. 2.22."""
    curves = shared.curves(cfg, deps[TABLE], "g2")
    return pd.concat([curves, shared.distance_to_new_model(cfg, curves)], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Albedo and radiance / C against incidence angle, one curve per level."""
    shared.plot_curves(df, path, "Fig. 2.5: Controlled pumping-up of the reciprocal Phong model "
                       "(Phong's a(θ) ≥ cos θ, so g2 = g1: the same curves as Fig. 2.3)")
