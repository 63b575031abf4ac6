"""Figure 4.3: the basic BRDF (eq. 4.2) for R = 0.2, in the plane of incidence.

f*(R, L, V) = c(R) = 1/(π min(1, R²)) where |V_P − L'_P| ≤ R. θ_V is signed: positive on the
mirror side. The incidence angles are an open choice (config ``patch.fig_4_3_theta_deg``).
"""

from __future__ import annotations

import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION, plane_of_incidence
from brdfs.physics.models import model

NAME = "fig_4_3_basic_brdf"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The basic BRDF along the plane of incidence: ``R, theta_deg, theta_v_deg, brdf, brdf_err``."""
    section = cfg[SECTION]
    brdf = model("patch_basic", R=section["fig_4_3_R"])
    frames = [plane_of_incidence(brdf, theta, section["theta_v_step_deg"]) for theta in section["fig_4_3_theta_deg"]]
    df = pd.concat(frames, ignore_index=True)
    df.insert(0, "R", brdf.R)
    df["brdf_err"] = patch.CLOSED_FORM_RTOL * df["brdf"]
    return df


def plot(df: pd.DataFrame, path) -> None:
    """f against signed θ_V, one curve per θ_L."""
    fig, ax = plotting.new_axes(
        "theta_V [deg] (positive: mirror side)", "f_r*",
        f"Fig. 4.3: basic BRDF, R = {df['R'].iloc[0]:g} (theta_L: open choice)",
    )
    for theta, group in df.groupby("theta_deg"):
        ax.plot(group["theta_v_deg"], group["brdf"], label=f"theta_L = {theta:g} deg")
    ax.set_xlim(-90, 90)
    plotting.savefig(fig, path)
