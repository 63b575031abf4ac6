"""Figure 4.10: elliptical (anisotropic) basic BRDFs (eqs. 4.32, 4.34, 4.36) over the projected disk.

For a fixed L, f(L, V) as a function of V_P = (x, y): c(b) inside the ellipse around L'_P
(clipped by the unit disk), 0 outside. Ellipses (b, B/A, axis angle) and θ_L are open choices
(``patch.fig_4_10_ellipses``, ``patch.fig_4_10_theta_deg``).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._patch_common import SECTION
from brdfs.physics.geometry import light_direction
from brdfs.physics.models import model

NAME = "fig_4_10_elliptical_brdf"


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``b, ratio, u_angle_deg, theta_deg, x, y, brdf, brdf_err`` on the points of a grid inside the disk."""
    section = cfg[SECTION]
    axis = np.linspace(-1.0, 1.0, section["fig_4_10_grid"])
    x, y = (c.ravel() for c in np.meshgrid(axis, axis))
    inside = x * x + y * y < 1.0
    x, y = x[inside], y[inside]
    V = np.stack([x, y, np.sqrt(1.0 - x * x - y * y)], axis=-1)
    L = light_direction(section["fig_4_10_theta_deg"])
    frames = []
    for ellipse in section["fig_4_10_ellipses"]:
        f = model("patch_elliptical", **ellipse)(L, V)
        frames.append(pd.DataFrame({**ellipse, "theta_deg": section["fig_4_10_theta_deg"], "x": x, "y": y,
                                    "brdf": f, "brdf_err": patch.CLOSED_FORM_RTOL * f}))
    return pd.concat(frames, ignore_index=True).assign(model="patch_elliptical")


def plot(df: pd.DataFrame, path) -> None:
    """One panel per ellipse: f over the projected disk; the y axis is shared and labelled once, so
    that no label stands over a neighbouring panel."""
    groups = list(df.groupby(["b", "ratio", "u_angle_deg"], sort=False))
    fig = plotting.plt.figure(figsize=(3.6 * len(groups), 3.8))
    axes = np.atleast_1d(fig.subplots(1, len(groups), sharey=True))
    for ax, ((b, ratio, angle), group) in zip(axes, groups):
        ax.scatter(group["x"], group["y"], c=group["brdf"], s=2, marker="s", cmap="viridis")
        ax.add_patch(plotting.plt.Circle((0, 0), 1.0, fill=False, color="k", lw=0.8))
        ax.set(aspect="equal", xlim=(-1.05, 1.05), ylim=(-1.05, 1.05), xlabel="x = V_P,x")
        ax.set_title(f"b = {b:g}, B/A = {ratio:g}, u at {angle:g} deg", fontsize=8)
    axes[0].set_ylabel("y = V_P,y")
    fig.suptitle(f"Fig. 4.10: elliptical basic BRDFs, theta_L = {df['theta_deg'].iloc[0]:g} deg (all: open choices)")
    plotting.savefig(fig, path)
