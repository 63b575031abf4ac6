"""Figure 2.8: metals with the reciprocal Phong model (top) and pumped once (bottom), n = 20 and 5000.

Reciprocal Phong (eq. 2.6, c = (n+2)/2π) times the metal's Fresnel reflectance at Θ_min, and the
same divided once by its albedo (g1, eq. 2.20; albedo table of brdfs.numerics.pumping); point
lights plus homogeneous daylight, Monte Carlo paths. One display scale for the four panels. The
thesis's scene: a golden tank with aluminium, silver, copper and golden pyramids.

All four panels have the same samples per pixel, seeds and passes (common random numbers).

The argument of the figure is where the angle of viewing is large (section 2.3: the unpumped
n = 5000 surfaces stay dark there under daylight). Below the panels: (left, top) the silver pyramid
of each panel cropped at native resolution, each labelled with its panel; (left, bottom) the *limb
render*: a silver sphere of each panel's material alone under the daylight S (no point lights, no
floor, a black background), four spheres in one small scene; (right) the sphere's *limb profile*: the mean luminance Y
of its pixels in bins of the viewing angle θ_V (the integrator's cos θ_V AOV) from the centre
(θ_V = 0) across the limb (θ_V → 90°), per material, with its standard error over the independently
seeded passes. A convex sphere under a constant sky shows S times its directional albedo at θ_V, so
the profile is the albedo curve the pumping flattens. Only the pixels within ``LIMB_WEDGE_DEG`` of
the vertical through each sphere's centre are binned, where the reflections look up or down into
the sky rather than sideways at the neighbouring spheres. The CSV carries the profile as rows with
``theta_v_deg`` (the bin's mean θ_V), ``theta_v_lo_deg``, ``theta_v_hi_deg``, ``pixels``,
``luminance``, ``luminance_err``, their ``panel`` the panel whose material the sphere has.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import time

import numpy as np

from brdfs.artifacts import _render_figures as rf
from brdfs.render import spectrum
from brdfs.render.mitsuba import scenes as msc
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_2_8_pumping_render"


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    p = section["pumping"]
    out = []
    for pumped, row in ((0, "reciprocal Phong"), (1, "pumped once (g1)")):
        for n in p["n"]:
            spec = {"model": "phong", "n": n, "pumped": pumped}
            objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]}),
                       ("tank", rf.tank(0.0, 1.2), {**spec, "metal": p["tank"]})]
            for x, metal in zip(rf.row(len(p["pyramids"]), 2.1), p["pyramids"]):
                objects.append((f"{metal} pyramid", msc.pyramid((x, -1.5, 0.0), PYRAMID_HALF_BASE, PYRAMID_HEIGHT),
                                {**spec, "metal": metal}))
            out.append(rf.Panel(f"{row}, n = {n:g}", objects, rf.TWO_LIGHTS, rf.STREET_CAMERA,
                                aspect=1.6))
    return out


#: Half the base and the height of the pyramids (scene units; the tank behind them stays in view).
PYRAMID_HALF_BASE, PYRAMID_HEIGHT = 0.45, 0.95
#: The object that is cropped beside the panels.
PROFILED_OBJECT = "silver pyramid"
#: The metal of the limb spheres, and the label of their rows.
LIMB_METAL = "silver"
LIMB_OBJECT = "silver sphere, daylight only"
#: The limb render: sphere radius and spacing (scene units), its aspect (its width: the preset's
#: min_width, at least LIMB_MIN_WIDTH pixels), the camera.
LIMB_RADIUS, LIMB_SPACING, LIMB_ASPECT, LIMB_MIN_WIDTH = 0.85, 2.3, 640 / 150, 192
LIMB_CAMERA = {"eye": (0.0, -40.0, 0.0), "target": (0.0, 0.0, 0.0), "fov_deg": 2.95}
#: Samples per pixel of the limb render: a profile bin averages hundreds of pixels, so few suffice.
LIMB_SPP = 16
#: Half-width of the wedge about each sphere's vertical whose pixels the limb profile bins (degrees).
LIMB_WEDGE_DEG = 30.0
#: Bins of the viewing angle θ_V of the profile (degrees).
PROFILE_EDGES_DEG = tuple(float(x) for x in range(0, 91, 3))
#: Fewest pixels a profile bin needs to be reported.
MIN_BIN_PIXELS = 8
#: Size of the profile chart in the PNG (pixels).
CHART_PX = (640, 400)


def limb_panel(cfg: dict, the_panels: list) -> rf.Panel:
    """The silver sphere of each panel's material (Phong n, pumping) in a row, under the daylight only."""
    objects = []
    xs = [LIMB_SPACING * (k - (len(the_panels) - 1) / 2) for k in range(len(the_panels))]
    for k, (x, panel) in enumerate(zip(xs, the_panels)):
        spec = next(spec for label, _, spec in panel.objects if label == PROFILED_OBJECT)
        objects.append((f"{LIMB_OBJECT} {k}", msc.sphere((x, 0.0, 0.0), LIMB_RADIUS), {**spec, "metal": LIMB_METAL}))
    # camera rays that miss see black (the sky still lights the spheres): the silhouettes stand out
    return rf.Panel("limb", objects, [], LIMB_CAMERA, aspect=LIMB_ASPECT, reference=(), background=0.0,
                    spp=LIMB_SPP)


def limb_profile(rendered, panel: rf.Panel, channels: int) -> list[dict]:
    """Rows of the limb profile of each sphere of the limb render: per θ_V bin with at least
    :data:`MIN_BIN_PIXELS` pure pixels inside the vertical wedge, the pixels, mean Y and its
    standard error over the passes; ``panel`` the index of the sphere (its main panel)."""
    height, width = rendered.ids.shape
    theta = np.degrees(np.arccos(np.clip(rendered.cos_v, 0.0, 1.0)))
    y = rendered.luminance_passes(channels)
    rows_px, cols_px = np.mgrid[0:height, 0:width] + 0.5
    out = []
    for k, (label, parts, _) in enumerate(panel.objects):
        ident = next(i for i, name in rendered.labels.items() if name == label)
        col, row = rf.project(panel.camera, width, height, [parts[0]["center"]])[0]
        off_vertical = np.degrees(np.arctan2(np.abs(cols_px - col), np.abs(rows_px - row)))
        mask = (rendered.ids == ident) & (off_vertical <= LIMB_WEDGE_DEG)
        for lo, hi in zip(PROFILE_EDGES_DEG[:-1], PROFILE_EDGES_DEG[1:]):
            sel = mask & (theta >= lo) & (theta < hi)
            if sel.sum() < MIN_BIN_PIXELS:
                continue
            per_pass = y[:, sel].mean(axis=1)
            out.append({"panel": k, "object": LIMB_OBJECT, "theta_v_deg": float(np.mean(theta[sel])),
                        "theta_v_lo_deg": lo, "theta_v_hi_deg": hi, "pixels": int(sel.sum()),
                        "luminance": float(per_pass.mean()),
                        "luminance_err": float(per_pass.std(ddof=1) / np.sqrt(per_pass.size))})
    return out


def short_title(title: str) -> str:
    """'reciprocal Phong, n = 20' -> 'Phong n=20'; 'pumped once (g1), n = 5000' -> 'g1 n=5000'."""
    return title.replace("reciprocal Phong", "Phong").replace("pumped once (g1)", "g1").replace(", n = ", ", n = ")


def labelled_strip(images: list[np.ndarray], labels: list[str], width: int, gap: int = 6) -> np.ndarray:
    """``images`` side by side at native resolution on white, each under its label, ``width`` wide."""
    from PIL import Image, ImageDraw, ImageFont

    font = ImageFont.load_default(size=11)
    label_px = 15
    height = max(img.shape[0] for img in images) + label_px
    out = Image.new("RGB", (max(width, sum(i.shape[1] for i in images) + gap * (len(images) - 1)), height), "white")
    draw = ImageDraw.Draw(out)
    x = 0
    for img, label in zip(images, labels):
        out.paste(Image.fromarray(np.ascontiguousarray(img[..., :3])), (x, label_px))
        draw.text((x + img.shape[1] / 2, 1), label, fill="black", font=font, anchor="ma")
        x += img.shape[1] + gap
    return np.asarray(out)


def bottom_left_cell(crops_and_titles: list, limb_image: np.ndarray, limb_panel_: rf.Panel, titles: list[str]) -> np.ndarray:
    """The pyramid crops (labelled) above the limb render (each sphere labelled), one image."""
    width = limb_image.shape[1]
    crops = labelled_strip([c for c, _ in crops_and_titles], [short_title(t) for _, t in crops_and_titles], width)
    height, width = limb_image.shape[:2]
    spheres = []
    for label, parts, _ in limb_panel_.objects:
        col, _ = rf.project(limb_panel_.camera, width, height, [parts[0]["center"]])[0]
        spheres.append(limb_image[:, max(int(col) - width // 8, 0):int(col) + width // 8])
    limb = labelled_strip(spheres, [short_title(t) for t in titles], width, gap=0)
    out = np.full((crops.shape[0] + 10 + limb.shape[0], max(crops.shape[1], limb.shape[1]), 3), 255, np.uint8)
    out[:crops.shape[0], :crops.shape[1]] = crops
    out[crops.shape[0] + 10:, :limb.shape[1]] = limb
    return out


def profile_chart(profile: pd.DataFrame, titles: list[str]) -> np.ndarray:
    """The limb profiles as an RGB image of CHART_PX pixels: Y against θ_V, one curve per panel's material, ±2 SE."""
    import matplotlib

    from brdfs.pipeline import plotting

    # the project's style, whatever this process imported before (a job alone has not imported
    # plotting yet when compute draws this; one forked from make all's pre-loaded parent has)
    with matplotlib.rc_context(plotting.STYLE):
        return _profile_chart(profile, titles)


def _profile_chart(profile: pd.DataFrame, titles: list[str]) -> np.ndarray:
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    dpi = 100
    fig = Figure(figsize=(CHART_PX[0] / dpi, CHART_PX[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes([0.11, 0.13, 0.86, 0.8])
    styles = ["C0o-", "C0s--", "C3o-", "C3s--"]
    for k, title in enumerate(titles):
        part = profile[profile["panel"] == k].sort_values("theta_v_deg")
        if part.empty:
            continue
        ax.errorbar(part["theta_v_deg"], part["luminance"], yerr=2 * part["luminance_err"],
                    fmt=styles[k % len(styles)], ms=3, mfc="none" if k % 2 else None, capsize=2, lw=1.2,
                    label=title)
    ax.set_xlabel("viewing angle θ_V across the silver sphere's limb (deg)", fontsize=8)
    ax.set_ylabel("mean luminance Y (±2 SE)", fontsize=8)
    ax.set_xlim(0, 90)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    with matplotlib.rc_context({"savefig.bbox": None}):
        fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    import pandas as pd

    the_panels = panels(cfg)
    df = rf.compute_panels(cfg, NAME, the_panels)
    setup = rf.figure_setup(rf.settings(cfg), NAME)
    limb = limb_panel(cfg, the_panels)
    limb_width = max(setup["min_width"], LIMB_MIN_WIDTH)
    limb_size = (limb_width, int(round(limb_width / LIMB_ASPECT)))
    wall, cpu = time.perf_counter(), time.process_time()
    rendered = rf.render_panel(limb, cfg, setup, *limb_size)
    limb_seconds = {"panel": "limb", "title": limb.title, "wall_s": round(time.perf_counter() - wall, 3),
                    "cpu_s": round(time.process_time() - cpu, 3)}
    profile_rows = limb_profile(rendered, limb, rf.SPECTRAL)
    # a profile row carries its panel's silver pyramid's material and scene columns, the limb render's size
    per_panel = df[df["object"] == PROFILED_OBJECT].set_index("panel")
    columns = [c for c in per_panel.columns if c not in ("object", "pixels", "luminance", "luminance_err")
               and not c.startswith(("object_", "p95", "fireflies"))]
    of_panel = {panel: per_panel.loc[panel, columns].to_dict() for panel in {row["panel"] for row in profile_rows}}
    rows = [{**of_panel[row["panel"]], "width": limb_size[0], "height": limb_size[1], "spp": rendered.spp,
             "point_lights": 0, "max_depth": limb.max_depth, **row} for row in profile_rows]
    profile = pd.DataFrame(rows)
    images, ids = df.attrs["images"], df.attrs["ids"]
    out = pd.concat([df, profile], ignore_index=True)
    out.attrs["ids"] = ids
    out.attrs[rf.RADIANCE] = df.attrs[rf.RADIANCE]
    out.attrs[rf.TIMING] = rf.SharedList(df.attrs[rf.TIMING] + [limb_seconds])
    titles = [title for title, _ in images]
    crops = [(rf.object_crop(image, panel_ids, labels, PROFILED_OBJECT), title)
             for (title, image), (panel_ids, labels) in zip(images, ids)]
    scale = df["display_scale"].iloc[0]
    limb_image = spectrum.to_display(spectrum.linear_rgb(rendered.radiance), scale)
    out.attrs["images"] = rf.SharedList(images + [("the silver pyramid (native resolution); a silver sphere under daylight",
                                     bottom_left_cell(crops, limb_image, limb, titles)),
                                    ("limb profile of the silver sphere under daylight",
                                     profile_chart(profile, titles))])
    return out


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 2.8: metals, reciprocal Phong (top) and pumped once (bottom); "
                   "the silver pyramid and a sphere's limb below", columns=len(set(df["n"].dropna())))
