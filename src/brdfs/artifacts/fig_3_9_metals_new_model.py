"""Fig. 3.9: a silver 'tank' and metal spheres: see the caption (workflow/report/captions/fig_3_9_metals_new_model.rst) for the substituted scene."""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_3_9_metals_new_model"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    return ms.tank_and_spheres(cfg, s['new_model_metals']['fig_3_9'], 'phong_cosmin', 'tank ' + ms.describe(s['new_model_metals']['fig_3_9'][:1]) + '; spheres ' + ms.describe(s['new_model_metals']['fig_3_9'][1:]))


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.9: a silver 'tank' and metal spheres (new model)")
