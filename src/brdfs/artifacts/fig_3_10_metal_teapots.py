"""Fig. 3.10: gold, silver and copper objects: see the caption (workflow/report/captions/fig_3_10_metal_teapots.rst) for the substituted scene."""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.render import shapes  # noqa: F401  (scene shapes)
from brdfs.pipeline.registry import figure

NAME = "fig_3_10_metal_teapots"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    return ms.row_of_objects(cfg, s['new_model_metals']['fig_3_10'], ms.describe(s['new_model_metals']['fig_3_10']), ms.three_teapots())


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3}, batch="renders_chapters_2_3")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.10: gold, silver and copper objects (new model)")
