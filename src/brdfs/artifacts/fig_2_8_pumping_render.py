"""Figure 2.8: metals with the reciprocal Phong model (top) and pumped once (bottom), n = 20 and 5000.

Reciprocal Phong (eq. 2.6, c = (n+2)/2π) times the metal's Fresnel reflectance at Θ_min, and the
same divided once by its albedo (g1, eq. 2.20; albedo table of brdfs.numerics.pumping); point
lights plus homogeneous daylight, Monte Carlo paths. One display scale for the four panels; below
them, the right half of the silver sphere of each panel cropped at native resolution, where the
grazing rims show what pumping does.
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

NAME = "fig_2_8_pumping_render"


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    p = section["pumping"]
    out = []
    for pumped, row in ((0, "reciprocal Phong"), (1, "pumped once (g1)")):
        for n in p["n"]:
            spec = {"model": "phong", "n": n, "pumped": pumped}
            objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]}),
                       ("tank", rf.tank(0.0, 1.2), {**spec, "metal": p["tank"]})]
            for x, metal in zip(rf.row(len(p["spheres"]), 2.1), p["spheres"]):
                objects.append((f"{metal} sphere", rf.sphere(x, -1.4, 0.55), {**spec, "metal": metal}))
            out.append(rf.Panel(f"{row}, n = {n:g}", objects, rf.TWO_LIGHTS, rf.STREET_CAMERA,
                                aspect=1.6))
    return out


#: The object whose grazing rim is cropped beside the panels (the argument of the figure).
RIM_OBJECT = "silver sphere"


def rim_crops(df: pd.DataFrame) -> list:
    """(title, crop) of the right half of RIM_OBJECT in every panel, at native resolution."""
    out = []
    for (title, image), (ids, labels) in zip(df.attrs["images"], df.attrs["ids"]):
        if RIM_OBJECT in labels.values():
            out.append((f"rim crop: {title}", rf.object_crop(image, ids, labels, RIM_OBJECT, side="right")))
    return out


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3}, batch="renders_chapters_2_3")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    df = rf.compute_panels(cfg, NAME, panels(cfg))
    df.attrs["images"] = df.attrs["images"] + rim_crops(df)
    return df


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 2.8: metals, reciprocal Phong (top) and pumped once (bottom); "
                   "the silver sphere's rims cropped below", columns=len(set(df["n"].dropna())))
