"""Fig. 4.16: metals with the exponential patch model: see the caption (workflow/report/captions/fig_4_16_patch_metals.rst) for the substituted scene."""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.render import shapes  # noqa: F401  (scene shapes)
from brdfs.pipeline.registry import figure

NAME = "fig_4_16_patch_metals"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    return ms.tank_and_spheres(cfg, s['patch_exponential']['fig_4_16'][:1] + s['patch_exponential']['fig_4_16'][2:], 'patch_exponential', 'tank, plate, spheres: ' + ms.describe(s['patch_exponential']['fig_4_16'], 'patch_exponential'), base=s['patch_exponential']['fig_4_16'][1])


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3}, batch="renders_chapter_4")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.16: metals with the exponential patch model")
