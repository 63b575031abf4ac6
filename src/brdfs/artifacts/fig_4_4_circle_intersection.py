"""Figure 4.4: the intersection of two circles, Area(C(L'_P, R)) = t1 + t2 (eqs. 4.9/4.10).

Drawn from :func:`brdfs.physics.patch_geometry.circle_intersection`: the base circle (radius 1,
centre O), the circle of radius R around Q = L'_P at distance d, the common chord, the angles α
(at O) and β (at Q) and the two circular segments t1 = α − cos α sin α and
t2 = R²(β − cos β sin β). d and R are choices (config ``diagrams.fig_4_4``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics.patch_geometry import circle_intersection
from brdfs.pipeline.registry import figure

NAME = "fig_4_4_circle_intersection"


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``quantity, value``: d, R, alpha, beta, t1, t2, area, chord end P = (P_x, P_y)."""
    c = cfg[dg.SECTION]["fig_4_4"]
    d, R = float(c["d"]), float(c["R"])
    lens = circle_intersection(d, R)
    alpha, beta = float(lens.alpha), float(lens.beta)
    t1 = alpha - np.cos(alpha) * np.sin(alpha)
    t2 = R * R * (beta - np.cos(beta) * np.sin(beta))
    return dg.frame({"d": d, "R": R, "alpha_rad": alpha, "beta_rad": beta, "t1": t1, "t2": t2,
                     "area": float(lens.area), **dg.vec("P", [np.cos(alpha), np.sin(alpha)])})


def plot(df: pd.DataFrame, path) -> None:

    v = dg.values(df)
    d, R, alpha, beta = v["d"], v["R"], v["alpha_rad"], v["beta_rad"]
    P = dg.get(v, "P", 2)
    Pm = P * [1, -1]
    fig, (ax,) = dg.new_canvas(5.6, 4.2)
    t = np.linspace(0, 2 * np.pi, 300)
    ax.plot(np.cos(t), np.sin(t), "k", lw=1.0)
    ax.plot(d + R * np.cos(t), R * np.sin(t), "k", lw=1.0)
    phi = np.linspace(-alpha, alpha, 100)
    ax.fill(np.cos(phi), np.sin(phi), color="tab:orange", alpha=0.35, lw=0, label=f"t1 = {v['t1']:.4f}")
    psi = np.linspace(np.pi - beta, np.pi + beta, 100)
    ax.fill(d + R * np.cos(psi), R * np.sin(psi), color="tab:blue", alpha=0.35, lw=0, label=f"t2 = {v['t2']:.4f}")
    ax.plot([P[0], Pm[0]], [P[1], Pm[1]], "k--", lw=0.8)
    for end in (P, Pm):
        ax.plot([0, end[0]], [0, end[1]], color="0.4", lw=0.8)
        ax.plot([d, end[0]], [0, end[1]], color="0.4", lw=0.8)
    ax.plot([0, d], [0, 0], color="0.4", lw=0.8)
    ax.plot([0, d], [0, 0], "k.", ms=5)
    ax.text(-0.03, -0.05, "O", ha="right", va="top")
    ax.text(d - 0.03, -0.04, "Q", ha="right", va="top")  # left of the chord and below O–Q
    ax.text(d / 2, 0.03, "d", ha="center")
    ax.text(P[0] + 0.03, P[1] + 0.03, "P")
    dg.arc(ax, (0, 0), 0.22, 0, alpha, "α")
    dg.arc(ax, (d, 0), 0.16, np.pi - beta, np.pi, "β", label_radius=0.27)
    ax.text(d + R * np.cos(np.pi / 3), R * np.sin(np.pi / 3) + 0.04, "R")
    ax.plot([d, d + R * np.cos(np.pi / 3)], [0, R * np.sin(np.pi / 3)], color="0.4", lw=0.8, ls=":")
    ax.set_title(f"Fig. 4.4: the lens of C(Q = L'$_P$, R) and the unit disk (d = {d:g}, R = {R:g})", fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8,
              title=f"area = t1 + t2 = {v['area']:.4f}", title_fontsize=8)
    ax.set_xlim(-1.15, max(1.15, d + R + 0.1)), ax.set_ylim(-1.15, 1.15)
    dg.save(fig, path)
