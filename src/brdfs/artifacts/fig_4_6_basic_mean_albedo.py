"""Figure 4.6: mean albedo of the basic BRDF against R (closed form, see
:func:`brdfs.physics.patch_geometry.basic_mean_albedo`); the thesis: minimal at R = 1. The R grid is an open
choice (``patch.R_step``)."""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, grid

NAME = "fig_4_6_basic_mean_albedo"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``R, mean_albedo, mean_albedo_err`` on (0, 2]."""
    R = grid(0.0, 2.0, cfg[SECTION]["R_step"])[1:]
    mean = patch.basic_mean_albedo(R)
    return pd.DataFrame({"model": "patch_basic", "R": R, "mean_albedo": mean.value, "mean_albedo_err": mean.error})


def plot(df: pd.DataFrame, path) -> None:
    """The curve with its minimum marked."""
    lowest = df.loc[df["mean_albedo"].idxmin()]
    fig, ax = plotting.new_axes("R", "mean albedo", "Fig. 4.6: mean albedo of the basic BRDF (R grid: open choice)")
    ax.plot(df["R"], df["mean_albedo"], label="eq. 4.11, closed form")
    ax.plot([lowest["R"]], [lowest["mean_albedo"]], "o", label=f"minimum {lowest['mean_albedo']:.5f} at R = {lowest['R']:g}")
    plotting.savefig(fig, path)
