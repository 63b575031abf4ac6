"""Figure 4.7: sampling the basic BRDF when the circles do not intersect (section 4.2.4, special case):
C(V'_P, R) lies inside the unit disk, so uniform points in it are exact samples (albedo 1).
R and θ are open choices (the thesis's figure is a sketch): R = 0.3 at θ = 30°."""

from __future__ import annotations

import pandas as pd

from brdfs.artifacts._sampling_figures import SECTION, plot_points, sample_points
from brdfs.pipeline.registry import figure

NAME = "fig_4_7_sampling_circles_apart"
R, THETA_DEG = 0.3, 30.0


@figure(NAME, config=(SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``model, R, theta_deg, strategy, x, y, accepted, weight, centre_x, centre_y, lens_alpha_rad, lens_area, albedo``."""
    return sample_points(THETA_DEG, R, ("exact",), cfg[SECTION]["figure_points"], [cfg["seed"], 47])


def plot(df: pd.DataFrame, path) -> None:
    plot_points(df, path, "Fig. 4.7: sampling when the circles do not intersect")
