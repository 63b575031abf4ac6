"""Figure 3.12: plastic spheres on a plastic plate, eq. 3.31 with (a_s, n) of section 3.8.

r, g, b channels as eq. 3.31 prescribes (Fresnel = 1); diffuse colours of one hue with different
lightness and saturation; two point lights plus homogeneous daylight, Monte Carlo paths.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_3_12_plastics"


def panels(cfg: dict) -> list:
    p = cfg[rf.SECTION]["plastics"]
    objects = [("floor", rf.floor(), dict(p["plate"]))]
    spheres = p["spheres"]
    for x, spec in zip(rf.row(len(spheres), 2.1), spheres):
        objects.append((f"sphere a_s={spec['a_s']:g} n={spec['n']:g}", rf.sphere(x, -0.6, 0.6), dict(spec)))
    title = "(a_s, n) = " + ", ".join(f"({s['a_s']:g}, {s['n']:g})" for s in spheres)
    return [rf.Panel(title, objects, rf.TWO_LIGHTS, rf.STREET_CAMERA, channels="rgb", aspect=1.6)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.12: plastic spheres on a plastic plate (eq. 3.31)")
