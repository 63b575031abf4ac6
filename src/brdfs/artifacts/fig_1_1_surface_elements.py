"""Figure 1.1: geometrical relation between two small surface elements (eqs. 1.2–1.4).

A schematic (no package geometry): elements A1 and A2 at distance r, their normals at the
incidence angles Θ1, Θ2 to the connecting line, and the solid angles ω1 (of A2 seen from A1) and
ω2 (of A1 seen from A2), ω1 = A2 cos Θ2 / r², ω2 = A1 cos Θ1 / r² (eq. 1.2 with the division the
print lost), so that ω1 A1 cos Θ1 = ω2 A2 cos Θ2 (eq. 1.3). The drawn sizes and angles are
choices (config ``diagrams.fig_1_1``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.pipeline.registry import figure

NAME = "fig_1_1_surface_elements"


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    c = cfg[dg.SECTION]["fig_1_1"]
    r, A1, A2 = float(c["r"]), float(c["a1"]), float(c["a2"])
    t1, t2 = np.radians(c["theta1_deg"]), np.radians(c["theta2_deg"])
    # A1 at the origin, A2 at (r, 0); normals turned from the connecting line by Θ1, Θ2.
    n1 = np.array([np.cos(t1), np.sin(t1)])
    n2 = np.array([-np.cos(t2), np.sin(t2)])
    w1, w2 = A2 * np.cos(t2) / r**2, A1 * np.cos(t1) / r**2
    return dg.frame({"r": r, "A1": A1, "A2": A2, "theta1_deg": c["theta1_deg"], "theta2_deg": c["theta2_deg"],
                     **dg.vec("N1", n1), **dg.vec("N2", n2), "omega1_sr": w1, "omega2_sr": w2,
                     "omega1_A1_cos1": w1 * A1 * np.cos(t1), "omega2_A2_cos2": w2 * A2 * np.cos(t2)})


def plot(df: pd.DataFrame, path) -> None:
    v = dg.values(df)
    r = v["r"]
    P1, P2 = np.zeros(2), np.array([r, 0.0])
    fig, (ax,) = dg.new_canvas(6.0, 3.2)
    for P, n, A, name, other in ((P1, dg.get(v, "N1", 2), v["A1"], "1", P2), (P2, dg.get(v, "N2", 2), v["A2"], "2", P1)):
        tangent = np.array([-n[1], n[0]])
        ends = np.stack([P - tangent * A / 2, P + tangent * A / 2])
        ax.plot(*ends.T, "k", lw=3)
        ax.fill(*np.vstack([other, ends]).T, color="tab:blue", alpha=0.12, lw=0)  # the solid angle seen from `other`
        dg.arrow(ax, P, P + 0.9 * n, f"N{name}", gap=0.12)
        start, stop = sorted([dg.angle_of(n), dg.angle_of(other - P)])
        if stop - start > np.pi:
            start, stop = stop, start + 2 * np.pi
        dg.arc(ax, P, 0.45, start, stop, f"Θ{name}", label_radius=0.6, fontsize=9)
        ax.text(*(P + ([-0.45, -0.45] if name == "1" else [0.15, -0.45])), f"A{name}", fontsize=10)
    ax.plot(*np.stack([P1, P2]).T, color="0.4", lw=0.8, ls="--")
    ax.text(r / 2, -0.15, "r", ha="center")
    ax.text(r * 0.5, 0.22, "ω1 (A2 seen from A1)", ha="center", color="tab:blue", fontsize=8)
    ax.text(r * 0.08, -0.3, "ω2 (A1 seen from A2)", color="tab:blue", fontsize=8)
    ax.text(r / 2, -0.72, f"ω1·A1·cos Θ1 = ω2·A2·cos Θ2 = {v['omega1_A1_cos1']:.4f}", fontsize=8, ha="center")
    ax.set_xlim(-0.6, r + 0.8), ax.set_ylim(-0.8, 1.2)
    ax.set_title("Fig. 1.1: two small surface elements", fontsize=9)
    dg.save(fig, path)
