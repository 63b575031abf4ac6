"""Albedo tables of the reciprocal Blinn model (n = 20) pumped 0 ... K times with g1 and g2 (eqs. 2.20, 2.21).

One piecewise Chebyshev interpolant in cos θ per level, its error measured at off-node points
(:func:`brdfs.numerics.pumping.tabulate_albedo`; nodes by the polar-azimuth reduction
:func:`brdfs.numerics.pumping.pumped_albedo`); each level's table builds the next level's model.
Figures 2.4 and 2.6 read them.
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _pumping_figures as shared
from brdfs.pipeline.registry import table


@table("extra_pumping_albedo_blinn", config=("pumping",), chapter=2)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Table nodes: columns model, n, C, pumping, level, piece, x_lo, x_hi, node, cos_theta, albedo, albedo_err, model_rtol."""
    return shared.albedo_tables("blinn", cfg)


def plot(df: pd.DataFrame, path) -> None:
    """The table nodes per level."""
    shared.plot_tables(df, path)
