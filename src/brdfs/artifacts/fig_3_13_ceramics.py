"""Figure 3.13: two ceramic objects, eq. 3.31 with a dominant diffuse part, n = 100 and 20.

Two Utah teapots (Newell's patches, tessellated: :mod:`brdfs.render.mitsuba.geometry`); r, g, b
channels, two point lights plus homogeneous daylight, Monte Carlo paths. The teapots stand close,
staggered in depth; the camera keeps CAMERA's direction and field of view and is moved so that they
fill the frame, spouts and handles in it (:func:`~brdfs.artifacts._render_figures.framed_camera`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.render.mitsuba import scenes as msc
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_3_13_ceramics"
#: The camera's direction and field of view (its distance and target: framed on the teapots).
CAMERA = {"eye": (0.0, -5.2, 2.6), "target": (0.0, 0.0, 0.4), "fov_deg": 34.0}
ASPECT = 1.6
#: Half the spread of the teapots along x, and their alternate offset in depth (scene units).
HALF_SPREAD, STAGGER = 0.75, 0.4


def panels(cfg: dict) -> list:
    c = cfg[rf.SECTION]["ceramics"]
    objects = [("floor", rf.floor(), dict(c["plate"]))]
    count = len(c["objects"])
    for k, (x, spec) in enumerate(zip(rf.row(count, HALF_SPREAD * max(count - 1, 1)), c["objects"])):
        y = STAGGER * (-1) ** (k + 1) if count > 1 else 0.0
        objects.append((f"teapot {k + 1} n={spec['n']:g}", msc.teapot(x, y, 1.0), dict(spec)))
    title = "ceramics, n = " + ", ".join(f"{s['n']:g}" for s in c["objects"])
    camera = rf.framed_camera(CAMERA, rf.object_points(objects), ASPECT)
    return [rf.Panel(title, objects, rf.TWO_LIGHTS, camera, channels="rgb", aspect=ASPECT)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.13: ceramic teapots (eq. 3.31)")
