"""Shared parts of the rendered figures (2.8, 3.8–3.13, 4.11, 4.16–4.18): settings, panels, plots.

A figure is a list of panels; a panel is a scene (objects with materials from the config section
``renders``), point lights, an optional homogeneous daylight S and a camera. ``compute`` renders
every panel and returns one row per (panel, object) with the scene's parameters and the mean
luminance Y of the object's pixels with its Monte Carlo standard error; the display images (8-bit
sRGB) ride along in ``df.attrs["images"]`` to ``plot``, which lays them out. All panels of a
figure share one display scale (from the reference objects of its first panel, section 3.6), so
brightness differences between panels (pumping, Fig. 2.8) stay visible, and all panels use the
same random numbers (common random numbers), so such differences are not Monte Carlo noise.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from brdfs.render import scenes, shapes, spectrum, tracer
from brdfs.pipeline import plotting

SECTION = "renders"


@dataclass
class Panel:
    title: str
    objects: list            # (label, shape, material spec)
    lights: list             # (position, relative intensity)
    camera: dict
    sky: bool = True
    channels: int = scenes.SPECTRAL
    background: float | None = None
    reference: tuple = ("floor",)
    aspect: float = 4.0 / 3.0          # width / height; the pixel count stays width × height of the settings
    extra: dict = field(default_factory=dict)


def settings(cfg: dict) -> dict:
    """Width, height, spp and depth of the selected quality (``renders.quality``)."""
    section = cfg[SECTION]
    quality = section["quality"]
    if quality not in ("draft", "high"):
        raise ValueError(f"renders.quality must be 'draft' or 'high', got {quality!r}")
    return {"quality": quality, **section[quality]}


def _scene(panel: Panel, cfg: dict):
    section = cfg[SECTION]
    objects = []
    for label, shape, spec in panel.objects:
        material = scenes.make_material({**spec, "label": label}, panel.channels)
        objects.append(tracer.SceneObject(shape, material, label))
    lights = [tracer.PointLight(tuple(pos), np.full(panel.channels, section["light_intensity"] * scale))
              for pos, scale in panel.lights]
    sky = np.full(panel.channels, float(section["sky_radiance"])) if panel.sky else None
    background = None if panel.background is None else np.full(panel.channels, panel.background)
    return tracer.Scene(objects, lights, sky=sky, background=background)


def _describe(spec: dict) -> dict:
    """Material columns of a row (docs/contract.md names): model, metal, parameters, pumping."""
    keys = ("metal", "model", "n", "s", "b", "ratio", "d", "a_s", "diffuse")
    out = {k: spec.get(k) for k in keys}
    if "rgb" in spec:          # eq. 3.31: Lambert r, g, b + a_s · phong_cosmin
        out["model"] = "phong_cosmin"
        out["rgb"] = " ".join(f"{c:g}" for c in spec["rgb"])
    elif "diffuse" in spec:
        out["model"] = "lambert"
    level = int(spec.get("pumped", 0))
    out["pumping"], out["level"] = ("g1" if level else "none"), level
    return out


def compute_panels(cfg: dict, name: str, panels: list[Panel], shared_scale: bool = True) -> pd.DataFrame:
    """Render ``panels``; rows per (panel, object), display images in ``df.attrs``.

    ``shared_scale``: one display scale for all panels (from the first panel's reference objects),
    else one per panel.
    """
    setup = settings(cfg)
    rows, images, scale = [], [], None
    for k, panel in enumerate(panels):
        scene = _scene(panel, cfg)
        cam = panel.camera
        pixels = setup["width"] * setup["height"]
        height = int(round(np.sqrt(pixels / panel.aspect)))
        width = int(round(height * panel.aspect))
        camera = tracer.Camera(tuple(cam["eye"]), tuple(cam["target"]), width, height, cam.get("fov_deg", 30.0))
        direct_only = not panel.sky
        image = tracer.render(scene, camera, spp=1 if direct_only else setup["spp"],
                              depth=1 if direct_only else setup["depth"], seed=cfg["seed"],   # common random numbers: panels differ by their materials only
                              stat_weights=spectrum.luminance_weights(panel.channels))
        rgb = spectrum.linear_rgb(image.radiance)
        if scale is None or not shared_scale:
            labels = [o.label for o in scene.objects]
            mask = np.isin(image.index, [labels.index(r) for r in panel.reference if r in labels])
            scale = spectrum.display_scale(rgb, mask)
        images.append((panel.title, spectrum.to_display(rgb, scale)))
        specs = {label: spec for label, _, spec in panel.objects}
        for row in tracer.object_statistics(image, scene):
            rows.append({"figure": name, "panel": k, "panel_title": panel.title, **row,
                         **_describe(specs.get(row["object"], {})),
                         "width": width, "height": height,
                         "spp": 1 if direct_only else setup["spp"], "depth": 1 if direct_only else setup["depth"],
                         "quality": setup["quality"], "point_lights": len(panel.lights),
                         "sky_radiance": cfg[SECTION]["sky_radiance"] if panel.sky else 0.0,
                         "display_scale": scale, **panel.extra})
    df = pd.DataFrame(rows).rename(columns={"radiance": "luminance", "radiance_err": "luminance_err"})
    df.attrs["images"] = images
    return df


def plot_panels(df: pd.DataFrame, path, title: str, columns: int | None = None) -> None:
    """The panels in a grid (``columns`` per row), each with its title; no axes."""
    import matplotlib.pyplot as plt

    images = df.attrs.get("images")
    if not images:
        raise ValueError(f"{path}: no rendered images passed from compute (df.attrs['images'])")
    columns = columns or len(images)
    rows = -(-len(images) // columns)
    h, w = images[0][1].shape[:2]
    fig, axes = plt.subplots(rows, columns, figsize=(3.2 * columns, 3.2 * rows * h / w + 0.5), squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (panel_title, img) in zip(axes.ravel(), images):
        ax.imshow(img, interpolation="nearest")
        ax.set_title(panel_title, fontsize=8)
    fig.suptitle(title, fontsize=9)
    plotting.savefig(fig, path)


# --- geometry shared by the scenes -----------------------------------------------------------------

def row(count, half_width):
    """x of ``count`` objects spread evenly over [−half_width, half_width] (a single one at −half_width)."""
    return [-half_width + 2 * half_width * k / max(count - 1, 1) for k in range(count)]


def floor(size=4.0):
    return shapes.Rectangle((0.0, 0.0, 0.0), (size, size))


def sphere(x, y, r):
    return shapes.Sphere((x, y, r), r)


def tank(x, y, scale=1.0):
    """The 'tank' substitute: a box hull with a cylinder turret (two shapes)."""
    hull = shapes.Box((x, y, 0.35 * scale), (0.9 * scale, 0.55 * scale, 0.35 * scale))
    turret = shapes.Cylinder((x, y, 0.7 * scale), 0.35 * scale, 0.3 * scale)
    return hull, turret


THREE_LIGHTS = [((-4.0, -5.0, 6.0), 1.0), ((5.0, -3.0, 5.0), 0.6), ((0.0, 4.0, 7.0), 0.5)]
TWO_LIGHTS = [((-4.0, -5.0, 6.0), 1.0), ((5.0, -3.0, 5.0), 0.6)]
STREET_CAMERA = {"eye": (0.0, -7.0, 3.2), "target": (0.0, 0.0, 0.5), "fov_deg": 34.0}
