"""Figure 4.13: F⁻¹(r) of the exponential weight (eq. 4.27), by bisection on its closed-form F,
for several s (open choice, ``patch.fig_s``); F⁻¹(r) = 2 above 1 − p_Diffuse."""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, grid

NAME = "fig_4_13_inverse_cdf"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``s, r, R, R_err``."""
    r = grid(0.0, 1.0, cfg[SECTION]["r_step"])
    frames = []
    for s in cfg[SECTION]["fig_s"]:
        R = patch.inverse_cdf(patch.ExponentialProfile(s), r)
        frames.append(pd.DataFrame({"model": "patch_exponential", "s": s, "r": r, "R": R.value, "R_err": R.error}))
    return pd.concat(frames, ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    fig, ax = plotting.new_axes("r", "R = F^-1(r)", "Fig. 4.13: inverse distribution of p(R) (s: open choice)")
    for s, group in df.groupby("s"):
        ax.plot(group["r"], group["R"], label=f"s = {s:g}")
    plotting.savefig(fig, path)
