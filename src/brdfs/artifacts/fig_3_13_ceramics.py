"""Figure 3.13: two ceramic objects, eq. 3.31 with a dominant diffuse part, n = 100 and 20.

Two Utah teapots (Newell's patches, tessellated: :mod:`brdfs.render.mitsuba.geometry`); r, g, b
channels, two point lights plus homogeneous daylight, Monte Carlo paths. The camera is closer than
the street camera of the sphere scenes and the panel wider (aspect 1.6): the teapots fill the frame,
spouts and handles in it.
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.render.mitsuba import scenes as msc
from brdfs.pipeline.registry import figure

NAME = "fig_3_13_ceramics"
CAMERA = {"eye": (0.0, -5.2, 2.2), "target": (0.0, 0.0, 0.4), "fov_deg": 34.0}


def panels(cfg: dict) -> list:
    c = cfg[rf.SECTION]["ceramics"]
    objects = [("floor", rf.floor(), dict(c["plate"]))]
    for k, (x, spec) in enumerate(zip(rf.row(len(c["objects"]), 1.3), c["objects"])):
        objects.append((f"teapot {k + 1} n={spec['n']:g}", msc.teapot(x, 0.0, 1.0), dict(spec)))
    title = "ceramics, n = " + ", ".join(f"{s['n']:g}" for s in c["objects"])
    return [rf.Panel(title, objects, rf.TWO_LIGHTS, CAMERA, channels="rgb", aspect=1.6)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.13: ceramic teapots (eq. 3.31)")
