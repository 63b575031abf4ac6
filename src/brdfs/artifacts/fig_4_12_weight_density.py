"""Figure 4.12: the weight p(R) of the exponential profile (eq. 4.47) for several s (open choice,
``patch.fig_s``); ``p_diffuse`` is its Dirac part at R = 2 (eq. 4.21)."""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, grid

NAME = "fig_4_12_weight_density"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``s, R, p, p_err, p_diffuse``."""
    R = grid(0.0, 2.0, cfg[SECTION]["R_step"])
    frames = []
    for s in cfg[SECTION]["fig_s"]:
        profile = patch.ExponentialProfile(s)
        p = patch.weight(profile, R, profile.c_max)
        frames.append(pd.DataFrame({"model": "patch_exponential", "s": s, "R": R, "p": p,
                                    "p_err": patch.CLOSED_FORM_RTOL * p,
                                    "p_diffuse": patch.diffuse_weight(profile, profile.c_max)}))
    return pd.concat(frames, ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    fig, ax = plotting.new_axes("R", "p(R)", "Fig. 4.12: weight p(R), eq. 4.47 (s: open choice)")
    for s, group in df.groupby("s"):
        ax.plot(group["R"], group["p"], label=f"s = {s:g}")
    ax.set_yscale("log")
    ax.set_ylim(1e-4, None)
    plotting.savefig(fig, path)
