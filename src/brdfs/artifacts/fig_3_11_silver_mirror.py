"""Fig. 3.11: gold and copper objects on a silver near-mirror: see the caption (workflow/report/captions/fig_3_11_silver_mirror.rst) for the substituted scene."""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.render import shapes  # noqa: F401  (scene shapes)
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_3_11_silver_mirror"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    return ms.mirror_scene(cfg, s['new_model_metals']['fig_3_11'], 'head, sphere, pyramid, plate: ' + ms.describe(s['new_model_metals']['fig_3_11']))


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.11: gold and copper objects on a silver near-mirror (n = 5000)")
