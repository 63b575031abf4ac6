"""Figure 4.1: geometry of the BRDF definition of chapter 4 — L, V, their mirrors L', V' across N
and the projections L_P, V_P, L'_P, V'_P onto the base plane; m(L, V) = |V_P − L'_P| (eq. 4.1).

Vectors from :mod:`brdfs.physics.geometry` (``direction``, ``mirror``) and m from
:func:`brdfs.physics.models.patch.projected_distance`; the directions are choices (config
``diagrams.fig_4_1``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics import geometry as geo
from brdfs.physics.models.patch import projected_distance
from brdfs.pipeline.registry import figure

NAME = "fig_4_1_brdf_geometry"
#: Where the projections' labels sit relative to their feet (clear of the m segment and the drops).
FOOT_OFFSETS = {"L": (0.02, -0.1), "V": (-0.17, 0.03), "Lm": (0.05, 0.02), "Vm": (0.03, -0.1)}
#: Where the vectors' labels sit relative to their tips (V' would sit on the dome's outline).
TIP_OFFSETS = {"Vm": (-0.11, -0.09)}


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    c = cfg[dg.SECTION]["fig_4_1"]
    L, V = dg.light_and_view(c)
    out = {**dg.vec("L", L), **dg.vec("V", V), **dg.vec("Lm", geo.mirror(L)), **dg.vec("Vm", geo.mirror(V)),
           "m": float(projected_distance(L, V))}
    return dg.frame(out)


def plot(df: pd.DataFrame, path) -> None:
    v = dg.values(df)
    fig, ax = dg.hemisphere_canvas()
    O = np.zeros(2)
    dg.arrow(ax, O, dg.project([0, 0, 1]), "N")
    style = {"L": ("tab:orange", "L"), "V": ("tab:blue", "V"), "Lm": ("tab:orange", "L'"), "Vm": ("tab:blue", "V'")}
    feet = {}
    for key, (col, label) in style.items():
        p = dg.get(v, key)
        ls = "-" if key in ("L", "V") else (0, (4, 2))
        ax.plot(*np.stack([O, dg.project(p)]).T, color=col, lw=1.2, ls=ls)
        tip = dg.project(p)
        where = tip + TIP_OFFSETS.get(key, 0.09 * tip / np.linalg.norm(tip))
        ax.text(*where, label, color=col, ha="center", va="center")
        feet[key] = dg.drop_to_base(ax, p, f"{label}$_P$", col, label_offset=FOOT_OFFSETS[key])
        ax.plot(*feet[key], "o", color=col, ms=3)
    ax.plot(*np.stack([feet["V"], feet["Lm"]]).T, "k", lw=1.6)
    mid = 0.5 * (feet["V"] + feet["Lm"])
    ax.text(*(mid + [-0.03, 0.04]), "m", fontsize=9, ha="right", va="bottom")
    ax.text(0.0, -0.62, f"m = |V$_P$ − L'$_P$| = {v['m']:.3f}", fontsize=8, ha="center")
    ax.set_xlim(-1.3, 1.4), ax.set_ylim(-0.7, 1.15)
    ax.set_title("Fig. 4.1: L, V, their mirrors and projections", fontsize=9)
    dg.save(fig, path)
