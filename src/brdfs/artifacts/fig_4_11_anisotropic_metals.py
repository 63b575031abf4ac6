"""Figure 4.11: anisotropic metals with the elliptical patch model (eqs. 4.32-4.36).

Each sphere's major axis u (``u_angle_deg`` = 0: Mitsuba's dp/du) runs along its parallels (the
tangent z × N), so highlights stretch around the sphere, and the grooves of the brushed metal run
along v = N × u, the meridians: a highlight on brushed metal stretches across the grooves.
Fresnel of the measured complex index at θ' (eq. 4.53); three point lights plus homogeneous
daylight, Monte Carlo paths, directions by the model's own 0/1 accept/reject sampling in the ellipse.
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

NAME = "fig_4_11_anisotropic_metals"
#: Chemical symbols in the panel title (the names are in the CSV), so that it fits the panel's width.
SYMBOL = {"gold": "Au", "silver": "Ag", "copper": "Cu", "aluminium": "Al", "chromium": "Cr", "platinum": "Pt"}


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    entries = section["anisotropic"]
    objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]})]
    for x, e in zip(rf.row(len(entries), 2.1), entries):
        objects.append((f"{e['metal']} b={e['b']:g} B/A={e['ratio']:g}", rf.sphere(x, -0.6, 0.6),
                        {"metal": e["metal"], "model": "patch_elliptical", "b": e["b"], "ratio": e["ratio"]}))
    title = "(b, B/A): " + ", ".join(f"{SYMBOL.get(e['metal'], e['metal'])} ({e['b']:g}, {e['ratio']:g})" for e in entries)
    return [rf.Panel(title, objects, rf.THREE_LIGHTS, rf.STREET_CAMERA, aspect=1.6)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.11: anisotropic metals (elliptical patch model)")
