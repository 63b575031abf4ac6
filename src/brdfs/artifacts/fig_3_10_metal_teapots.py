"""Fig. 3.10: gold, silver and copper teapots (Newell's, tessellated: :mod:`brdfs.render.mitsuba.geometry`) with
the new model on a diffuse plane; the caption (workflow/report/captions/fig_3_10_metal_teapots.rst) states the choices.

The middle teapot stands behind the others, so that with its high n it mirrors them (as the
thesis's does); the camera keeps CAMERA's direction and field of view and is moved so that the
teapots fill the frame, every spout and handle in it (:func:`~brdfs.artifacts._render_figures.framed_camera`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import dataclasses


from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_3_10_metal_teapots"
#: The camera's direction and field of view (its distance and target: framed on the teapots).
CAMERA = {"eye": (0.0, -6.2, 2.8), "target": (0.0, 0.0, 0.4), "fov_deg": 36.0}
ASPECT = 1.6


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    entries = s["new_model_metals"]["fig_3_10"]
    return [dataclasses.replace(p, camera=rf.framed_camera(CAMERA, rf.object_points(p.objects), ASPECT), aspect=ASPECT)
            for p in ms.row_of_objects(cfg, entries, "teapots: " + ms.describe(entries), ms.three_teapots())]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.10: gold, silver and copper teapots (new model)")
