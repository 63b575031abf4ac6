"""Fig. 4.17: cube, cylinder and sphere with the exponential patch model: see the caption (workflow/report/captions/fig_4_17_patch_shapes.rst) for the substituted scene.

The camera stands back from the street camera of the other metal scenes and the panel is wider
(aspect 1.6), so that the cube's front corner, the cylinder's lid and the sphere are all in frame.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import dataclasses


from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.render.mitsuba import scenes as msc
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_4_17_patch_shapes"
CAMERA = {"eye": (0.0, -7.6, 3.0), "target": (0.0, 0.0, 0.55), "fov_deg": 34.0}


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]["patch_exponential"]
    entries = ms.with_sampler(section["fig_4_17"], section["sampler"])
    shapes = [("cube", msc.box((-2.0, -0.3, 0.6), (0.6, 0.6, 0.6))),
              ("cylinder", msc.capped_cylinder((0.0, 0.5, 0.0), 0.6, 1.3)),
              ("sphere", rf.sphere(2.0, -0.3, 0.7))]
    title = "cube, cylinder, sphere: " + ms.describe(entries, "patch_exponential")
    return [dataclasses.replace(p, camera=CAMERA, aspect=1.6)
            for p in ms.row_of_objects(cfg, entries, title, shapes, model="patch_exponential")]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.17: cube, cylinder, sphere (exponential patch model)")
