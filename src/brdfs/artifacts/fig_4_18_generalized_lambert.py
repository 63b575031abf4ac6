"""Figure 4.18: generalized Lambertian spheres d = 1, 0.75, 0.5, 0.25, direct illumination only.

f = C min(ξ(m), ξ(m_clip)) (eqs. 4.58/4.59, C = 1/max albedo); gray; top: one point light at the
eye (d = 1 shows the 'full moon', a disk of almost constant radiance); bottom: two point lights.
Each panel has its own display scale (the light at the eye is farther away). Direct lighting
(``max_depth = 1``: one scattering event) from delta point lights, each rendered alone (no light
sampling, so no noise but the jitter's), jittered pixel samples (box filter), and a dim gray
background (not a light) against which the unlit halves show.

The two lights of the bottom panel stand far enough in front, and the spheres far enough apart,
that no sphere shadows a neighbour (each sphere is lit as it would be alone): a point light at
distance D casts a shadow cone, and from :data:`TWO_LIGHTS` the spheres' spacing
:data:`SPACING` keeps every neighbour out of it (checked by a test, rendering each sphere alone).
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

NAME = "fig_4_18_generalized_lambert"
CAMERA = {"eye": (0.0, -12.0, 1.0), "target": (0.0, 0.0, 1.0), "fov_deg": 17.6}    # the outer spheres in frame
#: Distance between the spheres' centres (radius 1), and the two point lights of the bottom panel
#: (left-front-high and right-front, the relative intensities of the other figures' two lights).
SPACING = 2.6
TWO_LIGHTS = [((-4.0, -12.0, 6.0), 1.0), ((5.0, -10.0, 5.0), 0.6)]
#: The light at the eye (a delta point light: nothing there for the camera rays to hit).
LIGHT_AT_EYE = CAMERA["eye"]
#: Jittered samples per pixel: direct light from delta point lights, each rendered alone, has no
#: sampling noise; the samples antialias the edges and the terminator.
DIRECT_SPP = 16
#: Radiance of the background camera rays see (not a light): the unlit halves stand out against it.
BACKGROUND = 0.02


def panels(cfg: dict) -> list:
    ds = cfg[rf.SECTION]["generalized_lambertian"]["d"]
    objects = []
    for x, d in zip(rf.row(len(ds), 0.5 * SPACING * (len(ds) - 1)), ds):
        objects.append((f"d={d:g}", rf.sphere(x, 0.0, 1.0), {"model": "generalized_lambertian", "d": d}))
    labels = tuple(label for label, _, _ in objects)
    light_at_eye = [(LIGHT_AT_EYE, 1.0)]
    return [rf.Panel("point light at the eye", objects, light_at_eye, CAMERA, sky=False, channels="rgb",
                     background=BACKGROUND, reference=labels, aspect=3.0, max_depth=1, point_lights=True, spp=DIRECT_SPP),
            rf.Panel("two point lights", objects, TWO_LIGHTS, CAMERA, sky=False, channels="rgb",
                     background=BACKGROUND, reference=labels, aspect=3.0, max_depth=1, point_lights=True,
                     spp=DIRECT_SPP)]


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg), shared_scale=False)


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.18: generalized Lambertian spheres d = "
                   + ", ".join(f"{d:g}" for d in df["d"].dropna().unique()) + " (direct only)", columns=1)
