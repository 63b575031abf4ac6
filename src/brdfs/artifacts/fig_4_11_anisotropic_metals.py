"""Figure 4.11: anisotropic metals with the elliptical patch model (eqs. 4.32-4.36).

Each sphere's major axis u (``u_angle_deg`` = 0: Mitsuba's dp/du) runs along its parallels (the
tangent z × N), so highlights stretch around the sphere, and the grooves of the brushed metal run
along v = N × u, the meridians: a highlight on brushed metal stretches across the grooves.
Fresnel of the measured complex index at θ' (eq. 4.53); three point lights plus homogeneous
daylight, Monte Carlo paths, directions by the model's own 0/1 accept/reject sampling in the ellipse.

Below the render, the same image cropped to the spheres (native resolution) with the groove
direction drawn on them: the meridians of each sphere's visible half, projected by the panel's
camera (:func:`~brdfs.artifacts._render_figures.project`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_4_11_anisotropic_metals"
#: Chemical symbols in the panel title (the names are in the CSV), so that it fits the panel's width.
#: Centre height and radius of the spheres (scene units), and the y of their row.
SPHERE_RADIUS, SPHERE_Y = 0.6, -0.6
#: Colour of the drawn grooves (dark: the spheres are bright metals under daylight).
GROOVE_COLOUR = (25, 25, 25)
SYMBOL = {"gold": "Au", "silver": "Ag", "copper": "Cu", "aluminium": "Al", "chromium": "Cr", "platinum": "Pt"}


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    entries = section["anisotropic"]
    objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]})]
    for x, e in zip(rf.row(len(entries), 2.1), entries):
        objects.append((f"{e['metal']} b={e['b']:g} B/A={e['ratio']:g}", rf.sphere(x, SPHERE_Y, SPHERE_RADIUS),
                        {"metal": e["metal"], "model": "patch_elliptical", "b": e["b"], "ratio": e["ratio"]}))
    title = "(b, B/A): " + ", ".join(f"{SYMBOL.get(e['metal'], e['metal'])} ({e['b']:g}, {e['ratio']:g})" for e in entries)
    return [rf.Panel(title, objects, rf.THREE_LIGHTS, rf.STREET_CAMERA, aspect=1.6)]


def groove_overlay(panel, image: np.ndarray) -> np.ndarray:
    """``image`` (the panel's display image) with each sphere's grooves (its meridians, along v) drawn,
    cropped to the rows of the spheres (a few pixels' margin)."""
    height, width = image.shape[:2]
    lines, rows = [], []
    for _, parts, _ in panel.objects:
        part = parts[0]
        if part.get("type") != "sphere":
            continue
        for meridian in rf.sphere_meridians(panel.camera, part["center"], part["radius"]):
            pixels = rf.project(panel.camera, width, height, meridian)
            lines.append(pixels)
            rows.extend(pixels[:, 1])
    top, bottom = max(int(min(rows)) - 8, 0), min(int(np.ceil(max(rows))) + 8, height)
    return rf.draw_polylines(image, lines, GROOVE_COLOUR)[top:bottom]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    the_panels = panels(cfg)
    df = rf.compute_panels(cfg, NAME, the_panels)
    _, image = df.attrs["images"][0]
    df.attrs["images"] = rf.SharedList(df.attrs["images"] + [
        ("groove direction: along the drawn meridians (the highlights stretch across them)",
         groove_overlay(the_panels[0], image))])
    return df


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.11: anisotropic metals (elliptical patch model)", columns=1)
