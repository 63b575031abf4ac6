"""Figure 3.2: ratio of the p-model (eq. 3.12) and the Phong BRDF (eq. 3.5) against viewing angle.

The ratio is 1 / max(cos θ_L, cos θ_V)^p wherever (R·V) > 0; it is evaluated from the two
models (V in the plane of incidence, on the side of R), and a test checks the closed form.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.artifacts._pumping_figures import ROUNDING_RTOL
from brdfs.physics.geometry import direction, light_direction
from brdfs.physics.models import model


@figure("fig_3_2_p_model_ratio", config=("p_model_ratio",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Columns p, n, theta_deg (θ_L), theta_v_deg, ratio, ratio_err."""
    section = cfg["p_model_ratio"]
    theta_v = np.arange(0.0, 90.0 - 1e-9, section["theta_v_step_deg"])
    V = direction(theta_v, 180.0)
    phong = model("phong", n=section["n"])
    rows = []
    for theta in section["theta_l_deg"]:
        L = np.broadcast_to(light_direction(np.array(theta)), V.shape)
        for p in section["p"]:
            ratio = model("p_model", n=section["n"], p=p)(L, V) / phong(L, V)
            rows.append(pd.DataFrame({"model": "p_model", "p": float(p), "n": float(section["n"]),
                                      "theta_deg": float(theta), "theta_v_deg": theta_v,
                                      "ratio": ratio, "ratio_err": ROUNDING_RTOL * ratio}))
    return pd.concat(rows, ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """One panel per θ_L, one curve per p."""
    thetas = sorted(df["theta_deg"].unique())
    fig, axes = plotting.plt.subplots(1, len(thetas), figsize=(5 * len(thetas), 4.2), sharey=True)
    for ax, theta in zip(np.atleast_1d(axes), thetas):
        for p, g in df[df["theta_deg"] == theta].groupby("p"):
            ax.plot(g["theta_v_deg"], g["ratio"], label=f"p = {p:g}")
        ax.set(xlabel="viewing angle θ_V [deg]", ylabel="f_p-model / f_Phong", title=f"θ_L = {theta:g}°", ylim=(0, 6))
    fig.suptitle(f"Figure 3.2: ratio of the p-model and the Phong BRDFs (n = {df['n'].iloc[0]:g})", fontsize=10)
    plotting.savefig(fig, path)
