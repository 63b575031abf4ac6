"""Figure 2.4: Albedo and reflected radiance of the reciprocal Blinn model and its pumped-up versions.

Albedo (from the level tables) and radiance at the mirror direction of the reciprocal Blinn
model (n = 20) pumped 0 ... K times with g1 (eq. 2.20).
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _pumping_figures as shared
from brdfs.pipeline.registry import figure

TABLE = "extra_pumping_albedo_blinn"


@figure("fig_2_4_blinn_pumping", deps=(TABLE,), config=("pumping",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Rows of albedo and of radiance per level (see :func:`shared.curves`)."""
    return shared.curves(cfg, deps[TABLE], "g1")


def plot(df: pd.DataFrame, path) -> None:
    """Albedo and radiance / C against incidence angle, one curve per level."""
    shared.plot_curves(df, path, "Fig. 2.4: Albedo and reflected radiance of the reciprocal Blinn model and its pumped-up versions")
