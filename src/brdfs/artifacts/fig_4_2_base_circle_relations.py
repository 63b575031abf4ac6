"""Figure 4.2: possible relations of the circle C(L'_P, R) to the base circle.

Four cases on the base plane (config ``diagrams.fig_4_2``, choices): R < 1 inside, R < 1 cut by
the base circle, R > 1 cut, R > 1 covering the base circle. The shaded common part is the lens
of :func:`brdfs.physics.patch_geometry.circle_intersection` (its α, β give the boundary arcs);
its area over Area(C(O, R)) is the basic BRDF's albedo (eq. 4.8, ``basic_albedo_at``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics.patch_geometry import basic_albedo_at, circle_intersection
from brdfs.pipeline.registry import figure

NAME = "fig_4_2_base_circle_relations"


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``case, d, R, alpha_rad, beta_rad, area, albedo, albedo_err`` per case."""
    rows = []
    for i, case in enumerate(cfg[dg.SECTION]["fig_4_2"]["cases"]):
        d, R = float(case["d"]), float(case["R"])
        lens = circle_intersection(d, R)
        a = basic_albedo_at(d, R)
        rows.append({"case": i + 1, "d": d, "R": R, "alpha_rad": float(lens.alpha), "beta_rad": float(lens.beta),
                     "area": float(lens.area), "albedo": float(a.value), "albedo_err": float(a.error)})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path) -> None:
    fig, axes = dg.new_canvas(3.0 * len(df), 3.4, ncols=len(df))
    t = np.linspace(0, 2 * np.pi, 300)
    for ax, row in zip(axes, df.itertuples()):
        poly = dg.lens_polygon(row.d, row.R)
        ax.fill(poly[:, 0], poly[:, 1], color="tab:blue", alpha=0.35, lw=0)
        ax.plot(np.cos(t), np.sin(t), "k", lw=1.0)
        ax.plot(row.d + row.R * np.cos(t), row.R * np.sin(t), "tab:blue", lw=1.0)
        ax.plot([0, row.d], [0, 0], "k.", ms=4)
        # O below its dot, L'_P above left of its dot: there the circles are farthest from the dots.
        ax.text(0.0, -0.06, "O", fontsize=8, ha="center", va="top")
        ax.text(row.d - 0.02, 0.06, "L'$_P$", fontsize=8, ha="right", va="bottom")
        reach = max(1.0, row.R) + 0.12   # each panel framed to its circles (the scales differ)
        ax.set_xlim(min(-1.0, row.d - row.R) - 0.12, max(1.0, row.d + row.R) + 0.12), ax.set_ylim(-reach, reach)
        ax.set_title(f"d = {row.d:g}, R = {row.R:g}\narea {row.area:.3f}, a = {row.albedo:.3f}", fontsize=8)
    fig.suptitle("Fig. 4.2: relations of C(L'$_P$, R) to the base circle", fontsize=9)
    dg.save(fig, path)
