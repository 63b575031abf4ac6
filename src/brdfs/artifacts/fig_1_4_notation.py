"""Figure 1.4: the notations of §1.2.2 — L, V, N, H, R, their angles and projections.

The vectors come from :mod:`brdfs.physics.geometry` (``direction``, ``mirror``, ``half_vector``,
``r_dot_v``, ``n_dot_h``) for directions of L and V that are choices (config
``diagrams.fig_1_4``); the CSV holds them and the angles θ_L, θ_V, α = ∠(R, V), δ = ∠(N, H).
Every angle is drawn as an arc along its great circle (δ's too) and printed below with its value.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics import geometry as geo
from brdfs.physics.models.patch import projected_distance
from brdfs.pipeline.registry import figure

NAME = "fig_1_4_notation"
#: Label positions relative to an arrow's tip where "beyond the tip" would sit on another line
#: (H runs almost along N; V's tip is next to R's drop line) and relative to a projection's foot.
LABEL_OFFSETS = {"H": (-0.12, -0.03), "V": (-0.05, 0.05)}
FOOT_OFFSETS = {"L": (0.03, -0.13), "V": (0.03, -0.13), "R": (0.05, -0.03)}
#: Radius of the arc of δ = ∠(N, H) and its label's offset from the arc's end on N.
DELTA_RADIUS, DELTA_LABEL_OFFSET = 0.78, (0.07, 0.0)


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    c = cfg[dg.SECTION]["fig_1_4"]
    L, V = dg.light_and_view(c)
    R = geo.mirror(L)
    H = geo.half_vector(L, V)
    N = np.array([0.0, 0.0, 1.0])
    out = {**dg.vec("N", N), **dg.vec("L", L), **dg.vec("V", V), **dg.vec("R", R), **dg.vec("H", H)}
    out.update({"theta_l_deg": float(np.degrees(np.arccos(geo.dot(N, L)))),
                "theta_v_deg": float(np.degrees(np.arccos(geo.dot(N, V)))),
                "alpha_deg": float(np.degrees(np.arccos(np.clip(geo.r_dot_v(L, V), -1, 1)))),
                "delta_deg": float(np.degrees(np.arccos(np.clip(geo.n_dot_h(L, V), -1, 1)))),
                "projected_distance": float(projected_distance(L, V))})
    return dg.frame(out)


def plot(df: pd.DataFrame, path) -> None:
    v = dg.values(df)
    fig, ax = dg.hemisphere_canvas()
    O = np.zeros(2)
    colours = {"N": "k", "L": "tab:orange", "V": "tab:blue", "R": "tab:red", "H": "tab:green"}
    for name, col in colours.items():
        p = dg.get(v, name)
        dg.arrow(ax, O, dg.project(p), name, color=col, offset=LABEL_OFFSETS.get(name), gap=0.08)
        if name in "LVR":
            foot = dg.drop_to_base(ax, p, f"{name}$_p$", col, label_offset=FOOT_OFFSETS[name])
            ax.plot(*np.stack([O, foot]).T, color=col, lw=0.9, ls="--")
    N, L, V, R, H = (dg.get(v, k) for k in "NLVRH")
    dg.arc3(ax, N, L, 0.45, "θ$_L$", color="tab:orange", fontsize=8)
    dg.arc3(ax, N, V, 0.3, "θ$_V$", color="tab:blue", label_radius=0.42, fontsize=8)
    dg.arc3(ax, R, V, 0.55, "α", color="tab:red", label_radius=0.72, fontsize=8)
    dg.arc3(ax, L * [1, 1, 0], V * [1, 1, 0], 0.3, "φ", color="0.3", label_radius=0.5, fontsize=8)
    # δ = ∠(N, H): H leans mostly toward the viewer, so the arc is short in the projection; its label
    # sits just right of N at the arc's end (between N and H there is no room for it).
    dg.arc3(ax, N, H, DELTA_RADIUS, color="tab:green")
    dg.label(ax, dg.project(DELTA_RADIUS * N) + DELTA_LABEL_OFFSET, "δ", color="tab:green", fontsize=8)
    text = (f"θ$_L$ = {v['theta_l_deg']:.1f}°,  θ$_V$ = {v['theta_v_deg']:.1f}°,  "
            f"α = ∠(R, V) = {v['alpha_deg']:.1f}°,  δ = ∠(N, H) = {v['delta_deg']:.1f}°\n"
            f"|L'$_p$ − V$_p$| = |h − (N·h)N| = {v['projected_distance']:.3f}")
    ax.text(0.05, -0.58, text, fontsize=7.5, va="top", ha="center")
    ax.set_xlim(-1.3, 1.4), ax.set_ylim(-0.8, 1.2)
    ax.set_title("Fig. 1.4: notations", fontsize=9)
    dg.save(fig, path)
