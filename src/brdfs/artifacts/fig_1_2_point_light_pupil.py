"""Figure 1.2: response of a point light source toward the observer's pupil (Sec. 1.1.1).

A schematic (no package geometry): a point source at unit distance in direction L from a surface
element with normal N, the observer's pupil of area A2 in direction V; cos Θ_L = N·L gives the
irradiance E = P cos Θ_L (unit distance), cos Θ2 = N·V the pupil's view of the element; the
observed radiance f_r E does not depend on the observer's distance (eq. 1.9). Angles and
distances are choices (config ``diagrams.fig_1_2``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.pipeline.registry import figure

NAME = "fig_1_2_point_light_pupil"


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    c = cfg[dg.SECTION]["fig_1_2"]
    tl, tv = np.radians(c["theta_l_deg"]), np.radians(c["theta_v_deg"])
    L = np.array([-np.sin(tl), np.cos(tl)])
    V = np.array([np.sin(tv), np.cos(tv)])
    return dg.frame({"theta_l_deg": c["theta_l_deg"], "theta_v_deg": c["theta_v_deg"], **dg.vec("L", L),
                     **dg.vec("V", V), "observer_distance": c["observer_distance"],
                     "cos_theta_l": float(L[1]), "cos_theta_2": float(V[1])})


def plot(df: pd.DataFrame, path) -> None:
    v = dg.values(df)
    L, V, D = dg.get(v, "L", 2), dg.get(v, "V", 2), v["observer_distance"]
    fig, (ax,) = dg.new_canvas(5.6, 3.8)
    ax.plot([-1.4, 1.4], [0, 0], "k", lw=1.0)
    ax.plot([-0.25, 0.25], [0, 0], "k", lw=4)
    dg.arrow(ax, (0, 0), (0, 1.0), "N")
    src = L
    ax.plot(*src, "*", color="tab:orange", ms=14)
    ax.text(src[0] - 0.35, src[1] + 0.12, "point source P\n(unit distance)", fontsize=8, color="tab:orange")
    dg.arrow(ax, (0, 0), 0.88 * src, color="tab:orange")  # L points from the surface to the light
    eye = D * V
    pupil = np.array([-V[1], V[0]]) * 0.15
    ax.plot(*np.stack([eye - pupil, eye + pupil]).T, "tab:blue", lw=3)
    ax.text(eye[0] + 0.08, eye[1], "pupil A2", color="tab:blue", fontsize=8)
    ax.fill(*np.vstack([[0, 0], eye - pupil, eye + pupil]).T, color="tab:blue", alpha=0.12, lw=0)
    dg.arrow(ax, (0, 0), V, "V", color="tab:blue")
    ax.text(*(0.5 * L + [-0.22, -0.05]), "L", color="tab:orange")
    dg.arc(ax, (0, 0), 0.35, np.pi / 2, dg.angle_of(L), "Θ$_L$", label_radius=0.48, fontsize=8)
    dg.arc(ax, (0, 0), 0.45, dg.angle_of(V), np.pi / 2, "Θ$_2$", label_radius=0.58, fontsize=8)
    ax.text(0.0, -0.12, f"cos Θ$_L$ = N·L = {v['cos_theta_l']:.3f},  cos Θ$_2$ = N·V = {v['cos_theta_2']:.3f}",
            fontsize=8, ha="center", va="top")
    ax.set_xlim(-1.4, eye[0] + 0.6), ax.set_ylim(-0.35, max(eye[1], 1.1) + 0.3)
    ax.set_title("Fig. 1.2: a point light seen through the observer's pupil", fontsize=9)
    dg.save(fig, path)
