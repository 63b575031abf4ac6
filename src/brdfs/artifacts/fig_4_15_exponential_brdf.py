"""Figure 4.15: the BRDF with the exponential weight, f = C_max e^{−s m} (eq. 4.46), in the
plane of incidence; s and θ_L are open choices (``patch.fig_s``, ``patch.fig_4_15_theta_deg``)."""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, plane_of_incidence
from brdfs.physics.models import model

NAME = "fig_4_15_exponential_brdf"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``s, theta_deg, theta_v_deg, brdf, brdf_err``."""
    section = cfg[SECTION]
    frames = []
    for s in section["fig_s"]:
        brdf = model("patch_exponential", s=s)
        for theta in section["fig_4_15_theta_deg"]:
            frames.append(plane_of_incidence(brdf, theta, section["theta_v_step_deg"]).assign(s=s))
    df = pd.concat(frames, ignore_index=True)
    df["brdf_err"] = patch.CLOSED_FORM_RTOL * df["brdf"]
    return df.assign(model="patch_exponential")[["model", "s", "theta_deg", "theta_v_deg", "brdf", "brdf_err"]]


def plot(df: pd.DataFrame, path) -> None:
    """One panel per θ_L, f/C_max against θ_V (log scale) per s."""
    thetas = sorted(df["theta_deg"].unique())
    fig = plotting.plt.figure(figsize=(4.8 * len(thetas), 4.0))
    for ax, theta in zip(fig.subplots(1, len(thetas)), thetas):
        for s, group in df[df["theta_deg"] == theta].groupby("s"):
            ax.plot(group["theta_v_deg"], group["brdf"] / group["brdf"].max(), label=f"s = {s:g}")
        ax.set(yscale="log", ylim=(1e-4, 1.5), xlim=(-90, 90), xlabel="theta_V [deg] (positive: mirror side)",
               ylabel="f / max f", title=f"theta_L = {theta:g} deg")
    fig.suptitle("Fig. 4.15: BRDF with exponential weight (s, theta_L: open choices)")
    plotting.savefig(fig, path)
