"""Figure 2.8: metals with the reciprocal Phong model (top) and pumped once (bottom), n = 20 and 5000.

Reciprocal Phong (eq. 2.6, c = (n+2)/2π) times the metal's Fresnel reflectance at Θ_min, and the
same divided once by its albedo (g1, eq. 2.20; albedo table of brdfs.numerics.pumping); point
lights plus homogeneous daylight, Monte Carlo paths. One display scale for the four panels.

The argument of the figure is at the grazing rims (section 2.3: the unpumped n = 5000 surfaces
stay dark "where the angle of viewing is large"), so below the panels are (left) the right half
of the silver sphere of each panel cropped at native resolution, side by side, and (right) its
*rim-radiance profile*: the mean luminance Y of the sphere's right-half pixels in bins of the
viewing angle θ_V (the integrator's cos θ_V AOV), per panel, with its standard error over the
independently seeded passes. The CSV carries the profile as rows with ``theta_v_deg`` (bin centre),
``theta_v_lo_deg``, ``theta_v_hi_deg``, ``pixels``, ``luminance``, ``luminance_err``.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

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
            for x, metal in zip(rf.row(len(p["spheres"]), 2.1), p["spheres"]):
                objects.append((f"{metal} sphere", rf.sphere(x, -1.4, 0.55), {**spec, "metal": metal}))
            out.append(rf.Panel(f"{row}, n = {n:g}", objects, rf.TWO_LIGHTS, rf.STREET_CAMERA,
                                aspect=1.6))
    return out


#: The object whose grazing rim is cropped and profiled beside the panels (the argument of the figure).
RIM_OBJECT = "silver sphere"
#: Bins of the viewing angle θ_V of the rim profile (degrees): coarse inside, fine toward the rim.
PROFILE_EDGES_DEG = (0.0, 15.0, 30.0, 45.0, 55.0, 65.0, 72.0, 78.0, 83.0, 87.0, 90.0)
#: Fewest pixels a profile bin needs to be reported.
MIN_BIN_PIXELS = 4
#: Size of the profile chart in the PNG (pixels).
CHART_PX = (640, 400)


def _right_half(ids: np.ndarray, k: int) -> np.ndarray:
    """Pixels of object ``k`` (its ID over every sample) right of its bounding box's middle."""
    mask = ids == k
    cols = np.nonzero(mask)[1]
    middle = 0.5 * (cols.min() + cols.max())
    return mask & (np.arange(ids.shape[1])[None, :] > middle)


def rim_profile(rendered, channels: int, label: str = RIM_OBJECT) -> list[dict]:
    """Rows of the rim profile of ``label`` in one rendered panel: per θ_V bin (of its right half), the
    pixels, mean Y and its standard error over the passes."""
    k = next(i for i, name in rendered.labels.items() if name == label)
    half = _right_half(rendered.ids, k)
    theta = np.degrees(np.arccos(np.clip(rendered.cos_v, 0.0, 1.0)))
    y = rendered.luminance_passes(channels)                       # (passes, H, W)
    rows = []
    for lo, hi in zip(PROFILE_EDGES_DEG[:-1], PROFILE_EDGES_DEG[1:]):
        sel = half & (theta >= lo) & (theta < hi)
        if sel.sum() < MIN_BIN_PIXELS:
            continue
        per_pass = y[:, sel].mean(axis=1)
        rows.append({"object": label, "theta_v_deg": float(np.mean(theta[sel])), "theta_v_lo_deg": lo,
                     "theta_v_hi_deg": hi, "pixels": int(sel.sum()), "luminance": float(per_pass.mean()),
                     "luminance_err": float(per_pass.std(ddof=1) / np.sqrt(per_pass.size))})
    return rows


def rim_crops(df: pd.DataFrame) -> np.ndarray:
    """The right half of RIM_OBJECT in every panel, at native resolution, side by side (one image)."""
    crops = [rf.object_crop(image, ids, labels, RIM_OBJECT, side="right")
             for (_, image), (ids, labels) in zip(df.attrs["images"], df.attrs["ids"]) if RIM_OBJECT in labels.values()]
    height, gap = max(c.shape[0] for c in crops), 6
    out = np.full((height, sum(c.shape[1] for c in crops) + gap * (len(crops) - 1), 3), 255, np.uint8)
    x = 0
    for crop in crops:
        out[:crop.shape[0], x:x + crop.shape[1]] = crop[..., :3]
        x += crop.shape[1] + gap
    return out


def profile_chart(profile: pd.DataFrame, titles: list[str]) -> np.ndarray:
    """The rim profiles as an RGB image of CHART_PX pixels: Y against θ_V, one curve per panel, ±2 SE."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    dpi = 100
    fig = Figure(figsize=(CHART_PX[0] / dpi, CHART_PX[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes([0.11, 0.13, 0.86, 0.8])
    styles = ["C0-", "C0--", "C3-", "C3--"]
    for k, title in enumerate(titles):
        part = profile[profile["panel"] == k].sort_values("theta_v_deg")
        if part.empty:
            continue
        ax.errorbar(part["theta_v_deg"], part["luminance"], yerr=2 * part["luminance_err"],
                    fmt=styles[k % len(styles)] + "o", ms=3, capsize=2, lw=1.2, label=title)
    ax.set_xlabel("viewing angle θ_V on the silver sphere (deg), right half", fontsize=8)
    ax.set_ylabel("mean luminance Y (±2 SE)", fontsize=8)
    ax.set_xlim(0, 90)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    with matplotlib.rc_context({"savefig.bbox": None}):
        fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 3}, batch="renders_chapters_2_3")
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    profiles = []

    def keep_profile(panel, rendered):
        profiles.append(rim_profile(rendered, rf.SPECTRAL))
        return rendered

    the_panels = panels(cfg)
    df = rf.compute_panels(cfg, NAME, the_panels, post=keep_profile)
    # a profile row carries the silver sphere's material and the panel's scene columns
    per_panel = df[df["object"] == RIM_OBJECT].set_index("panel")
    columns = [c for c in per_panel.columns if c not in ("object", "pixels", "luminance", "luminance_err")]
    rows = [{**per_panel.loc[k, columns].to_dict(), "panel": k, **row}
            for k, panel_rows in enumerate(profiles) for row in panel_rows]
    profile = pd.DataFrame(rows)
    images, ids = df.attrs["images"], df.attrs["ids"]
    out = pd.concat([df, profile], ignore_index=True)
    out.attrs["ids"] = ids
    out.attrs["images"] = images
    crops = rim_crops(out)
    out.attrs["images"] = images + [("rim crops (right halves)", crops),
                                    ("rim-radiance profile of the silver sphere",
                                     profile_chart(profile, [title for title, _ in images]))]
    return out


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 2.8: metals, reciprocal Phong (top) and pumped once (bottom); "
                   "the silver sphere's rim below", columns=len(set(df["n"].dropna())))
