"""Figure 4.14: albedo of the exponential mixture (eq. 4.22: adaptive integral over R of p(R)
times the closed-form a_R) for several s (open choice, ``patch.fig_s``)."""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, grid, tolerances

NAME = "fig_4_14_exponential_albedo"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``s, theta_deg, albedo, albedo_err``."""
    theta = grid(0.0, 90.0, cfg[SECTION]["theta_step_deg"])
    frames = []
    for s in cfg[SECTION]["fig_s"]:
        a = patch.mixture_albedo(patch.ExponentialProfile(s), theta, **tolerances(cfg))
        frames.append(pd.DataFrame({"model": "patch_exponential", "s": s, "theta_deg": theta,
                                    "albedo": a.value, "albedo_err": a.error}))
    return pd.concat(frames, ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    fig, ax = plotting.new_axes("theta [deg]", "albedo", "Fig. 4.14: albedo of f = C_max exp(-s m) (s: open choice)")
    for s, group in df.groupby("s"):
        ax.plot(group["theta_deg"], group["albedo"], label=f"s = {s:g}")
    ax.set_ylim(0, 1.05)
    plotting.savefig(fig, path)
