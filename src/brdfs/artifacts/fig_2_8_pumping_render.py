"""Figure 2.8: metals with the reciprocal Phong model (top) and pumped once (bottom), n = 20 and 5000.

Reciprocal Phong (eq. 2.6, c = (n+2)/2π) times the metal's Fresnel reflectance at Θ_min, and the
same divided once by its albedo (g1, eq. 2.20; albedo table of brdfs.numerics.pumping); point
lights plus homogeneous daylight, Monte Carlo paths. One display scale for the four panels. The
thesis's scene: a golden tank with aluminium, silver, copper and golden pyramids.

The argument of the figure is where the angle of viewing is large (section 2.3: the unpumped
n = 5000 surfaces stay dark there under daylight), so below the panels are (left) the silver
pyramid of each panel cropped at native resolution, side by side, and (right) its *viewing-angle
profile*: the mean luminance Y of the pyramid's pixels in bins of the viewing angle θ_V (the
integrator's cos θ_V AOV), per panel, with its standard error over the independently seeded
passes. A flat face is seen at one θ_V (within the perspective's few degrees), so the profile has
a point per visible face: the front faces near 8° and 11°, the side faces near 75° and 87°; the
pixels on the edges between faces, mixtures of two, fill no bin. The CSV carries the profile as rows with
``theta_v_deg`` (the bin's mean θ_V), ``theta_v_lo_deg``, ``theta_v_hi_deg``, ``pixels``,
``luminance``, ``luminance_err``.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.render.mitsuba import scenes as msc
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
            for x, metal in zip(rf.row(len(p["pyramids"]), 2.1), p["pyramids"]):
                objects.append((f"{metal} pyramid", msc.pyramid((x, -1.5, 0.0), PYRAMID_HALF_BASE, PYRAMID_HEIGHT),
                                {**spec, "metal": metal}))
            out.append(rf.Panel(f"{row}, n = {n:g}", objects, rf.TWO_LIGHTS, rf.STREET_CAMERA,
                                aspect=1.6))
    return out


#: Half the base and the height of the pyramids (scene units; the tank behind them stays in view).
PYRAMID_HALF_BASE, PYRAMID_HEIGHT = 0.45, 0.95
#: The object that is cropped and profiled beside the panels (the argument of the figure).
PROFILED_OBJECT = "silver pyramid"
#: Bins of the viewing angle θ_V of the profile (degrees).
PROFILE_EDGES_DEG = tuple(float(x) for x in range(0, 95, 5))
#: Fewest pixels a profile bin needs to be reported, as a share of the object's pixels: a face's
#: bins pass, the edges between faces (pixels mixing two θ_V) do not.
MIN_BIN_SHARE = 0.02
#: Size of the profile chart in the PNG (pixels).
CHART_PX = (640, 400)


def viewing_angle_profile(rendered, channels: int, label: str = PROFILED_OBJECT) -> list[dict]:
    """Rows of the viewing-angle profile of ``label`` in one rendered panel: per θ_V bin holding at
    least :data:`MIN_BIN_SHARE` of its pixels, the pixels, mean Y and its standard error over the passes."""
    k = next(i for i, name in rendered.labels.items() if name == label)
    mask = rendered.ids == k
    theta = np.degrees(np.arccos(np.clip(rendered.cos_v, 0.0, 1.0)))
    y = rendered.luminance_passes(channels)                       # (passes, H, W)
    rows = []
    for lo, hi in zip(PROFILE_EDGES_DEG[:-1], PROFILE_EDGES_DEG[1:]):
        sel = mask & (theta >= lo) & (theta < hi)
        if sel.sum() < max(MIN_BIN_SHARE * mask.sum(), 4):
            continue
        per_pass = y[:, sel].mean(axis=1)
        rows.append({"object": label, "theta_v_deg": float(np.mean(theta[sel])), "theta_v_lo_deg": lo,
                     "theta_v_hi_deg": hi, "pixels": int(sel.sum()), "luminance": float(per_pass.mean()),
                     "luminance_err": float(per_pass.std(ddof=1) / np.sqrt(per_pass.size))})
    return rows


def profiled_crops(df: pd.DataFrame) -> np.ndarray:
    """PROFILED_OBJECT in every panel, at native resolution, side by side (one image)."""
    crops = [rf.object_crop(image, ids, labels, PROFILED_OBJECT)
             for (_, image), (ids, labels) in zip(df.attrs["images"], df.attrs["ids"]) if PROFILED_OBJECT in labels.values()]
    height, gap = max(c.shape[0] for c in crops), 6
    out = np.full((height, sum(c.shape[1] for c in crops) + gap * (len(crops) - 1), 3), 255, np.uint8)
    x = 0
    for crop in crops:
        out[:crop.shape[0], x:x + crop.shape[1]] = crop[..., :3]
        x += crop.shape[1] + gap
    return out


def profile_chart(profile: pd.DataFrame, titles: list[str]) -> np.ndarray:
    """The viewing-angle profiles as an RGB image of CHART_PX pixels: Y against θ_V, one curve per panel, ±2 SE."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    dpi = 100
    fig = Figure(figsize=(CHART_PX[0] / dpi, CHART_PX[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes([0.11, 0.13, 0.86, 0.8])
    # markers only: between the faces' viewing angles there is nothing to draw a line through
    styles = ["C0o", "C0s", "C3o", "C3s"]
    for k, title in enumerate(titles):
        part = profile[profile["panel"] == k].sort_values("theta_v_deg")
        if part.empty:
            continue
        ax.errorbar(part["theta_v_deg"], part["luminance"], yerr=2 * part["luminance_err"],
                    fmt=styles[k % len(styles)], ms=5, mfc="none" if k % 2 else None, capsize=2, lw=1.2,
                    label=title)
    ax.set_xlabel("viewing angle θ_V on the silver pyramid's faces (deg)", fontsize=8)
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
    profiles = []

    def keep_profile(panel, rendered):
        profiles.append(viewing_angle_profile(rendered, rf.SPECTRAL))
        return rendered

    the_panels = panels(cfg)
    df = rf.compute_panels(cfg, NAME, the_panels, post=keep_profile)
    # a profile row carries the silver pyramid's material and the panel's scene columns
    per_panel = df[df["object"] == PROFILED_OBJECT].set_index("panel")
    columns = [c for c in per_panel.columns if c not in ("object", "pixels", "luminance", "luminance_err")]
    rows = [{**per_panel.loc[k, columns].to_dict(), "panel": k, **row}
            for k, panel_rows in enumerate(profiles) for row in panel_rows]
    profile = pd.DataFrame(rows)
    images, ids = df.attrs["images"], df.attrs["ids"]
    out = pd.concat([df, profile], ignore_index=True)
    out.attrs["ids"] = ids
    out.attrs[rf.RADIANCE] = df.attrs[rf.RADIANCE]
    out.attrs["images"] = images
    crops = profiled_crops(out)
    out.attrs["images"] = images + [("the silver pyramid, native resolution", crops),
                                    ("viewing-angle profile of the silver pyramid",
                                     profile_chart(profile, [title for title, _ in images]))]
    return out


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 2.8: metals, reciprocal Phong (top) and pumped once (bottom); "
                   "the silver pyramid below", columns=len(set(df["n"].dropna())))
