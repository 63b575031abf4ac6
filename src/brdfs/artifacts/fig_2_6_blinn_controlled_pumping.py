"""Figure 2.6: Controlled pumping-up of the reciprocal Blinn model.

Albedo (from the level tables) and radiance at the mirror direction of the reciprocal Blinn
model (n = 20) pumped 0 ... K times with g2 (eq. 2.21).
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _pumping_figures as shared
from brdfs.pipeline.registry import figure

TABLE = "extra_pumping_albedo_blinn"


@figure("fig_2_6_blinn_controlled_pumping", deps=(TABLE,), config=("pumping",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Rows of albedo and of radiance per level (see :func:`shared.curves`)."""
    return shared.curves(cfg, deps[TABLE], "g2")


def plot(df: pd.DataFrame, path) -> None:
    """Albedo and radiance / C against incidence angle, one curve per level."""
    shared.plot_curves(df, path, "Fig. 2.6: Controlled pumping-up of the reciprocal Blinn model")
