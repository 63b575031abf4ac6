"""Fig. 4.16: metals with the exponential patch model: see the caption (workflow/report/captions/fig_4_16_patch_metals.rst) for the substituted scene."""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import _render_metal_scenes as ms
from brdfs.artifacts.fig_4_11_anisotropic_metals import SYMBOL
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_4_16_patch_metals"


def panels(cfg: dict) -> list:
    s = cfg[rf.SECTION]
    entries = ms.with_sampler(s["patch_exponential"]["fig_4_16"], s["patch_exponential"]["sampler"])
    tank, plate, spheres = entries[0], entries[1], entries[2:]
    title = (f"tank {_short(tank)} s={tank['s']:g}, plate {_short(plate)} s={plate['s']:g}, spheres s = "
             + ", ".join(f"{e['s']:g} ({_short(e)})" for e in spheres))
    return ms.tank_and_spheres(cfg, [tank] + spheres, "patch_exponential", title, base=plate)


def _short(entry):
    return SYMBOL.get(entry["metal"], entry["metal"])


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.16: metals with the exponential patch model")
