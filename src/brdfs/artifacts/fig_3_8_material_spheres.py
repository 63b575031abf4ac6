"""Figure 3.8: the material editor — a diffuse gray reference sphere and golden spheres n = 2, 8, 16.

Spheres of the new model for metals (eq. 3.29, gold's measured complex index at eight
wavelengths) beside a Lambert gray sphere, under two point lights and homogeneous daylight
(section 3.6, eq. 3.32); the display scale puts the gray sphere's median at 0.5 (section 3.6).
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

NAME = "fig_3_8_material_spheres"


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    objects = [("gray", rf.sphere(-3.3, 0.0, 1.0), {"diffuse": section["diffuse_reflectance"]})]
    for k, n in enumerate(section["material_spheres"]["gold_n"]):
        objects.append((f"gold n={n:g}", rf.sphere(-1.1 + 2.2 * k, 0.0, 1.0),
                        {"metal": "gold", "model": "phong_cosmin", "n": n}))
    camera = {"eye": (0.0, -14.0, 1.0), "target": (0.0, 0.0, 1.0), "fov_deg": 12.0}
    return [rf.Panel("gray (Lambert) and gold n = " + ", ".join(f"{n:g}" for n in section["material_spheres"]["gold_n"]),
                     objects, rf.TWO_LIGHTS, camera, background=0.08, reference=("gray",), aspect=3.0)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2}, batch="renders_chapters_2_3")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.8: gray reference sphere and gold spheres (new model)")
