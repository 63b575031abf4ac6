"""Fig. 4.17: cube, cylinder and sphere with the exponential patch model: see the caption (workflow/report/captions/fig_4_17_patch_shapes.rst) for the substituted scene."""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.render.mitsuba import scenes as msc
from brdfs.pipeline.registry import figure

NAME = "fig_4_17_patch_shapes"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    return ms.row_of_objects(cfg, s['patch_exponential']['fig_4_17'], 'cube, cylinder, sphere: ' + ms.describe(s['patch_exponential']['fig_4_17'], 'patch_exponential'), [('cube', msc.box((-2.0, -0.3, 0.6), (0.6, 0.6, 0.6))), ('cylinder', msc.capped_cylinder((0.0, 0.5, 0.0), 0.6, 1.3)), ('sphere', rf.sphere(2.0, -0.3, 0.7))], model='patch_exponential')


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3}, batch="renders_chapter_4")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.17: cube, cylinder and sphere with the exponential patch model")
