"""Figure 4.8: sampling the basic BRDF when the circles intersect (section 4.2.4, general case):
exact samples fill the lens C(V'_P, R) ∩ unit disk uniformly (weight a_R), the 0/1 accept/reject
sampler (the thesis's "Russian roulette", strategy ``russian_roulette``; Fig. 4.9's accept/reject)
draws in C_min and rejects the points outside the other circle (weight 1 or 0).
R and θ are open choices: R = 0.5 at θ = 60°."""

from __future__ import annotations

import pandas as pd

from brdfs.artifacts._sampling_figures import SECTION, plot_points, sample_points
from brdfs.pipeline.registry import figure

NAME = "fig_4_8_sampling_circles_intersect"
R, THETA_DEG = 0.5, 60.0


@figure(NAME, config=(SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """As Figure 4.7, for the exact and the accept/reject ("Russian roulette") samplers."""
    return sample_points(THETA_DEG, R, ("exact", "russian_roulette"), cfg[SECTION]["figure_points"],
                         [cfg["seed"], 48])


def plot(df: pd.DataFrame, path) -> None:
    plot_points(df, path, "Fig. 4.8: sampling when the circles intersect")
