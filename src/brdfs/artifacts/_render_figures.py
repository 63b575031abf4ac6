"""Shared parts of the rendered figures (2.8, 3.8–3.13, 4.9, 4.11, 4.16–4.18): presets, panels, plots.

A figure is a list of panels; a panel is a scene (objects with materials from the config section
``renders``, geometry of :mod:`brdfs.render.mitsuba.scenes`), point lights (small spherical
emitters), an optional constant daylight S and a camera. Mitsuba renders each panel with the
package's plugins and the path tracer ``brdfs_path`` in the variant ``renders.variant``.

* **Preset** (``renders.preset``: ``preview`` or ``final``): the smallest panel size, samples per
  pixel (``spp``, or a figure's own ``figure_spp`` entry: the noisy figures get more, the quiet
  ones fewer; a list gives each panel its own, :func:`panel_setups`) and the number of independent
  passes they are split into (≥ 8; the noise figures of :mod:`brdfs.render.mitsuba.metrics` are
  taken over them). A panel is at least ``min_width``
  columns and ``min_height`` rows, at its aspect ratio; its PNG shows it at native resolution.
* **Launches** (:func:`render_panel`): a panel's samples are a map of samples per pixel and pass, the
  same in every pass; the pixels of one count are one wavefront of all passes (:func:`_launch_counts`),
  a pixel's pass one sequence of Mitsuba's stratified sampler ``renders.sampler`` (multijitter: it
  stratifies each pass of each pixel alone, and the passes stay independent; measured on Fig. 3.9 at
  64 spp: multijitter p95 0.070, independent 0.078 at equal time; ldsampler takes only powers of 4),
  with ``mi.render``'s rays and box filter (one pass and one count give ``mi.render``'s image to the bit).
  Dr.Jit traces the integrator per launch and compiles its kernel once per count. A launch holds at
  most :data:`MAX_LANES` samples and a count the sampler takes exactly (:func:`launches`). The map is
  uniform, or larger in crop windows around the objects (``crop_spp``), or chosen per pixel from an
  independent pilot (``adaptive``, :func:`adaptive_counts`).
* **Caustics** (``renders.caustics``): off, the paths diffuse → metal → light are not traced
  (:mod:`brdfs.render.mitsuba.integrator`); a figure listed in ``renders.<preset>.clamp`` has its indirect
  light clamped (Figs. 3.10, 3.11: their sparkles; 3.9, 4.11, 4.16: metal → metal light), the bias reported per object.
* **Timing**: each panel's measured wall and CPU seconds ride in ``df.attrs["timing"]`` to
  :func:`write_renders` (``timing.json`` beside the EXR files; the report's and docs' pages show them).
* **Colour** (section 3.8, :mod:`brdfs.render.mitsuba.spectral`): a spectral panel carries eight
  wavelengths as three colour groups along each path (a metal's ``eta``/``k`` and ``eta_g``/``k_g``,
  the integrator's ``colour_groups``); the eight channels go to XYZ and sRGB through colour-science.
  An ``rgb`` panel (eq. 3.31) is its plugins' r, g, b.
* **Rows**: one per (panel, object): the mean luminance Y of the object's pixels and its standard
  error over the passes, the scene's parameters, and the panel's noise figures ``p95_relative_se``,
  ``fireflies``, ``object_pixels``, the object's own ``object_p95_relative_se``,
  ``object_fireflies``, ``object_sparkles``, ``object_noise_pixels`` (:func:`~brdfs.render.mitsuba.metrics.object_noise`),
  with ``spp`` (an adaptive panel's mean over the film), ``object_spp``, ``passes``, ``preset``, ``variant``,
  ``caustics`` (the integrator's setting, ``renders.caustics``; moot where ``max_depth`` = 1) and
  ``clamp`` with each object's ``clamp_bias`` and ``clamp_bias_err`` (``renders.<preset>.clamp.<figure>``:
  the integrator's clamp of indirect light; the bias is the light it took, measured in the same passes). The
  display images (8-bit sRGB) ride along in ``df.attrs["images"]`` to ``plot``.
* **Linear radiance** (``df.attrs["radiance"]``): each panel's mean over its passes in linear sRGB
  (float32, the values the PNG is scaled and encoded from), written by :func:`write_renders` as
  OpenEXR ``results/renders/<figure>/panel_<k>.exr`` (``k`` the CSV's ``panel``).

All panels of a figure share one display scale (from the reference objects of its first panel,
section 3.6) unless a figure asks otherwise, and the same seeds (common random numbers).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import contextlib
import json
import textwrap
import time
from dataclasses import dataclass, field

import numpy as np

from brdfs.render import spectrum
from brdfs.render.mitsuba import metrics
from brdfs.render.mitsuba import scenes as msc
from brdfs.render.mitsuba.spectral import WAVELENGTH_PASSES, metal_constants, pass_channels

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

SECTION = "renders"
PRESETS = ("preview", "final")
SPECTRAL = len(spectrum.WAVELENGTHS_NM)
#: Material keys that are not model parameters.
MATERIAL_KEYS = ("metal", "model", "pumped", "label", "diffuse", "rgb", "a_s", "strategy", "mis_density", "count")


@dataclass
class Panel:
    title: str
    objects: list            # (label, shape parts, material spec)
    lights: list             # (position, relative intensity)
    camera: dict             # eye, target, fov_deg
    sky: bool = True
    channels: str = "spectral"         # or "rgb" (eq. 3.31)
    background: float | None = None    # radiance camera rays see where they miss (None: the sky)
    reference: tuple = ("floor",)
    aspect: float = 4.0 / 3.0          # width / height
    max_depth: int = -1                # -1: paths end by Russian roulette; 1: direct lighting only
    point_lights: bool = False         # delta point emitters, one render per light, summed (noise-free direct)
    spp: int | None = None             # samples per pixel of a noise-free panel (else the preset's)
    extra: dict = field(default_factory=dict)


def settings(cfg: dict) -> dict:
    """The preset's settings (``renders.preset``) with the variant: min_width, min_height, spp, passes."""
    section = cfg[SECTION]
    preset = section["preset"]
    if preset not in PRESETS:
        raise ValueError(f"renders.preset = {preset!r}: must be one of {PRESETS}")
    setup = {"preset": preset, "variant": section["variant"], "sampler": section["sampler"],
             "caustics": section["caustics"], "figure_spp": {}, **section[preset]}
    setup["figure_clamp"] = setup.pop("clamp", None) or {}
    if setup["passes"] < metrics.MIN_PASSES or setup["spp"] % setup["passes"]:
        raise ValueError(f"renders.{preset}: spp = {setup['spp']} must be a multiple of passes = "
                         f"{setup['passes']} >= {metrics.MIN_PASSES}")
    for name, spp in setup["figure_spp"].items():
        if any(value % setup["passes"] for value in np.atleast_1d(spp)):
            raise ValueError(f"renders.{preset}.figure_spp.{name} = {spp}: must be a multiple of passes = {setup['passes']}"
                             + (" (each entry)" if isinstance(spp, list) else ""))
    # the preset's crop_spp is per figure (figure_crop_spp); a panel's own is figure_setup's crop_spp
    setup["figure_crop_spp"], setup["crop_spp"] = setup.pop("crop_spp", None) or {}, 0
    for name, spp in setup["figure_crop_spp"].items():
        if not isinstance(spp, int) or spp < 0 or spp % setup["passes"]:
            raise ValueError(f"renders.{preset}.crop_spp.{name} = {spp!r}: must be a whole multiple of passes = "
                             f"{setup['passes']}, >= 0")
    setup["figure_object_spp"] = setup.pop("object_spp", None) or {}
    for name, per_object in setup["figure_object_spp"].items():
        for label, spp in per_object.items():
            if not isinstance(spp, int) or spp < setup["passes"] or spp % setup["passes"]:
                raise ValueError(f"renders.{preset}.object_spp.{name}.{label} = {spp!r}: must be a whole multiple of "
                                 f"passes = {setup['passes']}, >= passes")
    setup["figure_adaptive"] = setup.pop("adaptive", None) or {}
    for name, target in setup["figure_adaptive"].items():
        if not isinstance(target, (int, float)) or not 0.0 < target < 1.0:
            raise ValueError(f"renders.{preset}.adaptive.{name} = {target!r}: must be a relative standard error in (0, 1)")
    if setup["figure_adaptive"]:
        for key in ("adaptive_pilot", "adaptive_max"):
            value = setup.get(key)
            if not isinstance(value, int) or value < setup["passes"] or value % setup["passes"]:
                raise ValueError(f"renders.{preset}.{key} = {value!r}: must be a whole multiple of passes = {setup['passes']}")
    return setup


#: A preset's per-figure settings (``renders.<preset>.<setting>.<figure>``) that spend samples.
SAMPLING_SETTINGS = ("figure_spp", "crop_spp", "object_spp", "adaptive")


@dataclass(frozen=True)
class FigureFacts:
    """What the configuration checks need of a rendered figure, read from its ``panels(cfg)``."""

    labels: tuple[str, ...]        # its objects' labels (the CSV's ``object`` column), every panel's, in order
    panels: int                    # how many panels
    own_spp: bool                  # every panel renders at its own spp (noise-free): the preset's sampling is moot
    direct_only: bool              # every panel is direct light only (max_depth 1): a clamp has nothing to cut

    def ignores(self, setting: str) -> str | None:
        """Why the figure's panels would ignore preset setting ``setting`` (None: they use it)."""
        if setting in SAMPLING_SETTINGS and self.own_spp:
            return "its panels render at their own samples per pixel (noise-free), not the preset's"
        if setting == "clamp" and self.direct_only:
            return "its panels render direct light only (max_depth 1): there is no indirect light to clamp"
        return None


def figure_facts(name: str, cfg: dict) -> FigureFacts:
    """:class:`FigureFacts` of rendered figure ``name`` with ``cfg`` (imports its module, no renderer)."""
    import importlib

    panels = importlib.import_module(f"brdfs.artifacts.{name}").panels(cfg)
    labels = tuple(dict.fromkeys(label for panel in panels for label, _, _ in panel.objects))
    return FigureFacts(labels, len(panels), all(p.spp is not None for p in panels),
                       all(p.max_depth == 1 for p in panels))


def figure_setup(setup: dict, name: str) -> dict:
    """The preset's settings for figure ``name``: its ``figure_spp`` entry, if any, as ``spp`` (an
    integer, or a list with one entry per panel, :func:`panel_setups`)."""
    return {**setup, "spp": setup["figure_spp"].get(name, setup["spp"]), "crop_spp": int(setup["figure_crop_spp"].get(name, 0)),
            "object_spp": dict(setup["figure_object_spp"].get(name, {})),
            "adaptive": float(setup["figure_adaptive"].get(name, 0.0)),
            "clamp": float(setup["figure_clamp"].get(name, 0.0))}


def panel_setups(setup: dict, name: str, count: int) -> list[dict]:
    """The settings of each of a figure's ``count`` panels: a per-panel ``figure_spp`` list gives
    each panel its own samples per pixel (where the panels' noise differs, as Fig. 2.8's by 4x)."""
    spp = setup["spp"]
    if not isinstance(spp, (list, tuple)):
        return [setup] * count
    if len(spp) != count:
        raise ValueError(f"renders.{setup['preset']}.figure_spp.{name} = {list(spp)}: needs one entry per panel, "
                         f"{count} panels")
    return [{**setup, "spp": int(value)} for value in spp]


def panel_size(setup: dict, aspect: float) -> tuple[int, int]:
    """(width, height) at ``aspect``, at least min_width × min_height."""
    height = max(setup["min_height"], int(np.ceil(setup["min_width"] / aspect)))
    return int(round(height * aspect)), int(height)


# --- materials -> BSDF dictionaries ---------------------------------------------------------------

def _texture(values):
    return {"type": "srgb", "color": [float(v) for v in values], "unbounded": True}


def bsdf(spec: dict, groups=None) -> dict:
    """The plugin dictionary of a config material entry (see :mod:`brdfs.render.scenes`) for the
    colour groups ``groups`` (a tuple of wavelength-index triples, spectral: a metal gets ``eta``,
    ``k`` of the first and ``eta_g``, ``k_g`` of group g) or r, g, b (``None``)."""
    spec = dict(spec)
    params = {k: float(v) for k, v in spec.items() if k not in MATERIAL_KEYS}
    if "diffuse" in spec:
        return {"type": "brdfs_lambert", "reflectance": _texture([spec["diffuse"]] * 3)}
    if "rgb" in spec:          # eq. 3.31: ρ_d/π (r, g, b) + a_s · the new model, Fresnel 1
        if groups is not None:
            raise ValueError(f"plastic {spec!r}: eq. 3.31 is an r, g, b model; the panel is spectral")
        return {"type": "brdfs_phong_cosmin", "n": float(spec["n"]), "specular": _texture([spec["a_s"]] * 3),
                "diffuse_reflectance": _texture(spec["rgb"])}
    if "model" not in spec:
        raise ValueError(f"material entry {spec!r} has none of the keys diffuse, rgb, metal, model")
    out = {"type": f"brdfs_{spec['model']}", **params}
    if int(spec.get("pumped", 0)):
        out["pumping"] = "g1"
    for key in ("strategy", "mis_density"):
        if key in spec:
            out[key] = spec[key]
    if spec.get("count"):
        out["count"] = True           # the patch plugins count samples, tries and evaluations
    if "metal" in spec:
        if groups is None:
            raise ValueError(f"metal {spec!r}: metals are rendered at the {SPECTRAL} wavelengths")
        for g, channels in enumerate(groups):
            eta, k = metal_constants(spec["metal"], channels)
            suffix = f"_{g}" if g else ""
            out["eta" + suffix], out["k" + suffix] = _texture(eta), _texture(k)
    return out


# --- rendering -------------------------------------------------------------------------------------

def _mitsuba(variant: str):
    from brdfs.render.mitsuba import integrator, register_plugins, use_variant

    mi = use_variant(variant)
    register_plugins()
    integrator.register()
    return mi


def _scene(panel: Panel, cfg: dict, groups):
    section = cfg[SECTION]
    objects = tuple(msc.SceneObject(label, parts, bsdf(spec, groups)) for label, parts, spec in panel.objects)
    lights = tuple(msc.Light(tuple(pos), section["light_intensity"] * scale) for pos, scale in panel.lights)
    sky = float(section["sky_radiance"]) if panel.sky else None
    return msc.Scene(objects, lights, sky=sky, background_visible=panel.background is None,
                     point_lights=panel.point_lights)


def _integrator(panel: Panel, count: bool = False, caustics: bool = True, colour_groups: int = 1,
                clamp: float = 0.0) -> dict:
    out = {"type": "brdfs_path", "max_depth": panel.max_depth, "count_rays": bool(count), "caustics": bool(caustics),
           "colour_groups": int(colour_groups), "clamp": float(clamp)}
    if panel.background is not None:
        out.update(hide_emitters=True, background=float(panel.background))
    return out


@dataclass(frozen=True)
class RenderedPanel:
    """Per-pass channel images (P, H, W, C), the ID buffer (H, W) and {id: label}; with counting,
    the rays and the plugins' (samples, tries, evaluations) of all its passes."""

    passes: np.ndarray
    ids: np.ndarray
    labels: dict
    spp: int
    costs: dict = field(default_factory=dict)
    rays: int | None = None
    cos_v: np.ndarray | None = None
    lost: np.ndarray | None = None       # (P, H, W, C): the light the clamp took, per pass (clamp > 0)
    crop_spp: int = 0                    # more samples per pixel in the crop window (render_panel)
    windows: tuple = ()                  # the crop windows (x, y, width, height), one per object but the floor
    samples: np.ndarray | None = None    # (H, W) samples per pixel over all passes (render_panel's map)
    target: float = 0.0                  # the adaptive sampling's per-pixel relative SE target (0: uniform)

    @property
    def radiance(self):
        return self.passes.mean(axis=0)

    def luminance_passes(self, channels: int):
        return self.passes @ spectrum.luminance_weights(channels)


#: Most samples (lanes) in one ``mi.render`` launch: W·H·spp of a preview pass fits easily.
MAX_LANES = 1 << 24


def sampler_takes(sampler: str, spp: int) -> bool:
    """Whether Mitsuba's ``sampler`` renders exactly ``spp`` samples per pixel (the stratified ones
    round other counts up, with a warning): multijitter x·⌈n/x⌉ = n for x = ⌊√n⌋, stratified a
    square, ldsampler a power of 4."""
    root = int(np.sqrt(spp))
    if sampler == "multijitter":
        return root * -(-spp // root) == spp
    if sampler == "stratified":
        return root * root == spp
    if sampler == "ldsampler":
        return spp & (spp - 1) == 0 and (spp.bit_length() - 1) % 2 == 0
    return True


def launches(width: int, height: int, spp: int, sampler: str = "independent") -> list[int]:
    """Samples per pixel of each ``mi.render`` launch of one pass: at most :data:`MAX_LANES`
    samples each, each a count the sampler takes exactly (:func:`sampler_takes`), largest first."""
    per_launch = max(MAX_LANES // (width * height), 1)
    out = []
    while spp > 0:
        chunk = min(spp, per_launch)
        while not sampler_takes(sampler, chunk):
            chunk -= 1
        out.append(chunk)
        spp -= chunk
    return out


def render_panel(panel: Panel, cfg: dict, setup: dict, width: int, height: int, count: bool = False) -> RenderedPanel:
    """Render ``panel``: ``passes`` independently seeded passes of ``spp / passes`` samples per pixel.

    A panel's samples are a map of samples per pixel and pass (:func:`_panel_counts`), the same in every
    pass, rendered by :func:`_render_counts`: all passes of all pixels with the same count in one
    wavefront (:func:`_launch_counts`), where a pixel's pass is one sequence of Mitsuba's stratified
    sampler ``renders.sampler`` (multijitter stratifies each pass of each pixel alone) and the passes stay
    independent. Dr.Jit traces the integrator per launch and compiles its kernel once per count (the
    kernel cache). A spectral panel's eight wavelengths ride along one path as three colour groups
    (:data:`~brdfs.render.mitsuba.spectral.WAVELENGTH_PASSES`): the image carries the first, the
    integrator's ``c<g>_*`` AOVs the others.

    Spending samples where the noise is (the map; either, not both):

    * ``setup["crop_spp"]`` > 0: the pixels of a crop window around each object but the floor
      (:func:`crop_windows` of the objects seen by the pixels' centres, :func:`center_ids`) get
      ``crop_spp / passes`` more samples in each pass, one stratified set with the film's;
    * ``setup["object_spp"]``, {object label: samples per pixel}: each listed object's own window (its
      pixels' bounding box, :data:`CROP_MARGIN` wider, :func:`object_windows`) gets that many samples in
      all, ``spp / passes`` a pass elsewhere, the largest count where windows overlap
      (:func:`object_window_samples`): samples spent on the objects that need them;
    * ``setup["adaptive"]`` > 0, a relative standard error: each pixel's count from an independent pilot
      (:func:`adaptive_counts`).

    The 8-pass noise estimate holds pixel by pixel: every pass of a pixel has the same samples.
    """
    mi = _mitsuba(setup["variant"])
    cam = panel.camera
    camera = msc.Camera(tuple(cam["eye"]), tuple(cam["target"]), width, height, cam.get("fov_deg", 30.0))
    groups = WAVELENGTH_PASSES if panel.channels == "spectral" else None
    passes = setup["passes"]
    spp = max((setup["spp"] if panel.spp is None else panel.spp) // passes, 1)
    crop_spp = int(setup.get("crop_spp", 0)) // passes if panel.spp is None else 0
    target = float(setup.get("adaptive", 0.0)) if panel.spp is None else 0.0
    object_spp = {label: count // passes for label, count in setup.get("object_spp", {}).items()} if panel.spp is None else {}
    if sum(map(bool, (target > 0, crop_spp, object_spp))) > 1:
        raise ValueError(f"renders: panel {panel.title!r}: adaptive sampling, crop_spp and object_spp exclude each other")
    out = np.zeros((passes, height, width, SPECTRAL if groups else 3))
    clamp = float(setup.get("clamp", 0.0))
    integrator = _integrator(panel, count, setup["caustics"], len(groups) if groups else 1, clamp)
    lost = np.zeros_like(out) if clamp > 0 else None
    # point lights: one scene per light (an emitter sample then picks no light at random), the same samples
    light_sets = [[light] for light in panel.lights] if panel.point_lights else [panel.lights]
    counts = windows = None
    with one_thread():   # the same bytes in every run (one_thread)
        for lights in light_sets:
            part = Panel(**{**panel.__dict__, "lights": lights})
            scene = msc.load(_scene(part, cfg, groups), camera, integrator, setup["sampler"])
            if counts is None:
                counts, windows = _panel_counts(mi, scene, setup, cfg["seed"], groups, spp, crop_spp, target, object_spp)
                # the ID and cos θ_V AOVs averaged over every sample of the first scene (all passes): a
                # pixel's ID is an object's only where all its samples hit that object
                ids, cos_v, ids_sq = _render_counts(mi, scene, setup["sampler"], counts, passes, cfg["seed"], 0, groups, out, lost)
                labels = msc.object_labels(scene)
            else:
                _render_counts(mi, scene, setup["sampler"], counts, passes, cfg["seed"], 0, groups, out, lost)
    samples = counts * passes
    costs = _plugin_costs(scene) if count else {}
    rays = int(np.asarray(scene.integrator().rays)[0]) if count else None
    return RenderedPanel(out, pure_ids(ids, ids_sq, samples), labels, int(round(samples.mean())) if target else spp * passes,
                         costs, rays, cos_v, lost, crop_spp * passes if windows else 0, tuple(windows), samples, target)


def _panel_counts(mi, scene, setup: dict, seed: int, groups, spp: int, crop_spp: int, target: float,
                  object_spp: dict | None = None):
    """A panel's (H, W) samples per pixel and pass and its crop windows (:func:`render_panel`)."""
    width, height = scene.sensors()[0].film().crop_size()
    if target > 0:
        return adaptive_counts(mi, scene, setup, seed, groups, target), []
    if object_spp:
        windows = object_windows(center_ids(mi, scene), msc.object_labels(scene), object_spp)
        return object_window_samples((height, width), windows, spp), [w[:4] for w in windows]
    windows = crop_windows(center_ids(mi, scene), msc.object_labels(scene)) if crop_spp else []
    return window_samples((height, width), windows, spp, crop_spp), windows


def center_ids(mi, scene) -> np.ndarray:
    """The (H, W) object ID (:func:`~brdfs.render.mitsuba.integrator.scene_bsdfs` index + 1, 0: nothing)
    that the ray through each pixel's centre meets first (the crop windows' objects, before any sample)."""
    import drjit as dr

    from brdfs.render.mitsuba.integrator import object_index

    sensor = scene.sensors()[0]
    width, height = sensor.film().crop_size()
    pixel = dr.arange(mi.UInt32, width * height)
    row = pixel // width
    position = (mi.Vector2f(mi.Float(pixel - row * width), mi.Float(row)) + 0.5) / mi.ScalarVector2f(width, height)
    ray, _ = sensor.sample_ray(0.0, 0.0, position, mi.Point2f(0.5))
    ids = object_index(scene, scene.ray_intersect(ray))
    return np.asarray(ids).reshape(height, width)


#: Pixels around the crop window's objects (their mixed edge pixels, the floor's contact shadows).
CROP_MARGIN = 4


def crop_windows(ids: np.ndarray, labels: dict, skip=("floor",), margin: int = CROP_MARGIN) -> list[tuple]:
    """Windows (x, y, width, height) around the objects whose label does not start with one of
    ``skip`` (the floor: large and quiet): per object the smallest holding its pixels, ``margin``
    pixels wider (clipped to the film), and overlapping windows merged into their bounding box
    (:func:`merge_windows`), so that every window pixel gets the same samples."""
    height, width = ids.shape
    out = []
    for k, label in sorted(labels.items()):
        if label == "light" or label.startswith(tuple(skip)):
            continue
        rows, cols = np.nonzero(ids == k)
        if rows.size == 0:
            continue
        y0, x0 = max(rows.min() - margin, 0), max(cols.min() - margin, 0)
        y1, x1 = min(rows.max() + margin + 1, height), min(cols.max() + margin + 1, width)
        out.append((int(x0), int(y0), int(x1 - x0), int(y1 - y0)))
    return merge_windows(out)


def object_windows(ids: np.ndarray, labels: dict, counts: dict, margin: int = CROP_MARGIN) -> list[tuple]:
    """(x, y, width, height, count) per object of ``counts`` ({label: samples per pixel and pass}) that the
    pixels' centres see: its own window as :func:`crop_windows` makes it (not merged with others)."""
    out = []
    for k, label in sorted(labels.items()):
        if label in counts:
            out += [(*window, int(counts[label])) for window in crop_windows(ids, {k: label}, skip=(), margin=margin)]
    return out


def object_window_samples(shape, windows, spp_full: int) -> np.ndarray:
    """(H, W) samples per pixel and pass: ``spp_full``, and in each window (x, y, width, height, count) the
    largest of the counts of the windows over the pixel and ``spp_full``."""
    out = np.full(shape, int(spp_full))
    for x, y, w, h, count in windows:
        np.maximum(out[y:y + h, x:x + w], int(count), out=out[y:y + h, x:x + w])
    return out


def merge_windows(windows) -> list[tuple]:
    """``windows`` (x, y, width, height) with every overlapping pair replaced by its bounding box, until
    none overlap (sorted by y, then x)."""
    boxes = [(x, y, x + w, y + h) for x, y, w, h in windows]
    merged = True
    while merged:
        merged = False
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                a, b = boxes[i], boxes[j]
                if a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]:
                    boxes[i] = (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))
                    del boxes[j]
                    merged = True
                    break
            if merged:
                break
    return sorted(((x0, y0, x1 - x0, y1 - y0) for x0, y0, x1, y1 in boxes), key=lambda b: (b[1], b[0]))


def window_samples(shape, windows, spp_full: int, spp_crop: int) -> np.ndarray:
    """(H, W) samples per pixel: ``spp_full`` plus ``spp_crop`` in each window over it (overlaps add)."""
    out = np.full(shape, int(spp_full))
    for x, y, w, h in windows:
        out[y:y + h, x:x + w] += int(spp_crop)
    return out


@contextlib.contextmanager
def one_thread():
    """Dr.Jit's thread pool at one thread for the block: every pixel's samples are then added up in
    one order. With several threads a pixel whose samples span more than two of Dr.Jit's work blocks
    (30 samples per pass of Fig. 4.16) receives its partial sums in the order the threads race, and
    luminance_err moved by up to 1e-8 relative between two runs. The workflow runs its jobs side by
    side, one thread each (the rule's ``threads``), so the renders lose no wall time in ``make all``."""
    import drjit as dr

    threads = dr.thread_count()
    dr.set_thread_count(1)
    try:
        yield
    finally:
        dr.set_thread_count(threads)


def panel_channels(image: np.ndarray, groups) -> np.ndarray:
    """The panel's channels of one launch's image: r, g, b (``groups`` None), or the eight wavelengths
    from the colour groups (group 0 in channels 0–2, group g ≥ 1 in the AOVs ``c<g>_*`` after ``id``
    and ``cos_v``, channels 5 + 3(g − 1) …)."""
    if groups is None:
        return image[..., :3]
    out = np.zeros(image.shape[:-1] + (SPECTRAL,))
    for g, group in enumerate(groups):
        first = 0 if g == 0 else 5 + 3 * (g - 1)
        for k, wavelength in enumerate(pass_channels(group)):
            out[..., wavelength] = image[..., first + k]
    return out


def clamped_channels(image: np.ndarray, groups) -> np.ndarray:
    """The light the integrator's clamp took (AOVs ``k<g>_*``, after the ``c<g>_*``), in the panel's channels."""
    first = 5 + 3 * (len(groups) - 1 if groups else 0)
    if groups is None:
        return image[..., first:first + 3]
    out = np.zeros(image.shape[:-1] + (SPECTRAL,))
    for g, group in enumerate(groups):
        for k, wavelength in enumerate(pass_channels(group)):
            out[..., wavelength] = image[..., first + 3 * g + k]
    return out


#: The ID of a pixel whose samples hit more than one object (or an object and the background).
MIXED_ID = -1.0


def pure_ids(mean_id: np.ndarray, mean_id_sq: np.ndarray, samples: int) -> np.ndarray:
    """The object ID of each pixel from the means of ``id`` and ``id²`` over its ``samples`` samples:
    round(mean) where every sample hit the same object (variance 0; one sample of N elsewhere gives
    at least (1 − 1/N)/N), else :data:`MIXED_ID`."""
    variance = mean_id_sq - mean_id ** 2
    pure = (variance < 0.25 / samples) & (np.abs(mean_id - np.round(mean_id)) < 1e-3)
    return np.where(pure, np.round(mean_id), MIXED_ID)


def pass_seed(seed: int, pass_index: int, launch: int = 0) -> int:
    """Mitsuba's 32-bit seed of launch ``launch`` of pass ``pass_index`` (the same in every
    panel: common random numbers)."""
    return (int(seed) * 1009 + pass_index * 65537 + launch) % 2 ** 32


# --- adaptive sampling: samples per pixel from an independent pilot ------------------------------------

#: The first launch index (:func:`pass_seed`) of an adaptive panel's pilot: apart from the result's launches.
PILOT_LAUNCH = 1 << 20
#: Pixels of the box filter that smooths the pilot's relative variances (the map must not follow its noise).
PILOT_SMOOTHING = 5


def count_ladder(sampler: str, low: int, high: int, ratio: float) -> np.ndarray:
    """Samples per pixel and pass the adaptive map uses: from ``low`` to ``high``, each a count the
    sampler takes exactly (:func:`sampler_takes`), each step at least ``ratio`` × the last (a level is a
    launch)."""
    out = [low]
    for n in range(low + 1, high + 1):
        if sampler_takes(sampler, n) and (n >= ratio * out[-1] or n == high):
            out.append(n)
    return np.asarray(out)


def pixel_counts(relative_variance: np.ndarray, pilot_spp: int, passes: int, target: float, ladder) -> np.ndarray:
    """(H, W) samples per pixel and pass that bring each pixel's relative standard error over ``passes``
    passes to ``target``, from its relative variance of one pass of ``pilot_spp`` samples (variance as
    1/spp), rounded up to the ``ladder`` (its first and last entries bound it)."""
    ladder = np.asarray(ladder)
    need = relative_variance * pilot_spp / (passes * target ** 2)
    return ladder[np.minimum(np.searchsorted(ladder, need), ladder.size - 1)]


def pilot_relative_variance(passes: np.ndarray) -> np.ndarray:
    """Per pixel, the pilot's variance of a pass's luminance over its (P, H, W) ``passes``, relative to the
    square of its mean, or of :data:`~brdfs.render.mitsuba.metrics.DARK_FRACTION` × the 99th percentile
    where darker (the noise figures leave those pixels out), box-filtered over :data:`PILOT_SMOOTHING` px."""
    from scipy import ndimage

    mean = passes.mean(axis=0)
    floor = metrics.DARK_FRACTION * np.percentile(mean, 99.0)
    relative = passes.var(axis=0, ddof=1) / np.maximum(mean, floor) ** 2
    return ndimage.uniform_filter(relative, size=PILOT_SMOOTHING, mode="nearest")


def adaptive_counts(mi, scene, setup: dict, seed: int, groups, target: float) -> np.ndarray:
    """The (H, W) samples per pixel and pass of an adaptive panel: a pilot of ``passes`` passes of
    ``adaptive_pilot / passes`` samples (seeded apart from every pass of the result, :data:`PILOT_LAUNCH`,
    so the map is independent of the result and its pass-wise noise estimate stays unbiased),
    :func:`pilot_relative_variance`, :func:`pixel_counts` on :func:`count_ladder` from 1 to
    ``adaptive_max / passes``."""
    passes = setup["passes"]
    width, height = scene.sensors()[0].film().crop_size()
    per_pass = setup["adaptive_pilot"] // passes
    pilot = np.zeros((passes, height, width, SPECTRAL if groups else 3))
    _render_counts(mi, scene, setup["sampler"], np.full((height, width), per_pass), passes, seed, PILOT_LAUNCH, groups,
                   pilot, None)
    y = pilot @ spectrum.luminance_weights(pilot.shape[-1])
    ladder = count_ladder(setup["sampler"], 1, setup["adaptive_max"] // passes, setup.get("adaptive_ratio", 1.3))
    return pixel_counts(pilot_relative_variance(y), per_pass, passes, target, ladder)


def _render_counts(mi, scene, sampler: str, counts: np.ndarray, passes: int, seed: int, first_launch: int, groups, out,
                   lost):
    """Add ``counts[i, j]`` samples per pass at pixel (i, j), in each of ``passes`` passes, to ``out``
    (P, H, W, C: each pass's mean; ``lost``: the clamp's, if any): the pixels of one count in one wavefront
    (split at :data:`MAX_LANES`, and a count the sampler does not take into ones it takes,
    :func:`launches`), launch k seeded ``pass_seed(seed, 0, first_launch + k)``. A pass of a pixel is one
    sequence of the sampler, as Mitsuba's ``mi.render`` gives a pixel its samples (same rays, the film's
    box filter: with one pass and one count, ``mi.render``'s image). Returns the (H, W) means of the AOVs
    ``id``, ``cos_v`` and ``id_sq`` over all samples."""
    height, width = counts.shape
    flat = counts.ravel()
    aovs = np.zeros((height * width, 3))
    # (P, H·W, C) views: a pass's pixels by flat index, a slice where they run on (a uniform map's chunks);
    # indexing (rows, cols) of out itself cost ~10 % of Fig. 2.8's job (the same sums, in the same order)
    if not out.flags.c_contiguous or not (lost is None or lost.flags.c_contiguous):
        raise ValueError("_render_counts: out and lost must be C-contiguous (their flat views are written)")
    out_flat = out.reshape(passes, height * width, out.shape[-1])
    lost_flat = None if lost is None else lost.reshape(passes, height * width, lost.shape[-1])
    launch = first_launch
    for count in np.unique(flat[flat > 0]):
        pixels = np.flatnonzero(flat == count)
        step = max(MAX_LANES // (int(count) * passes), 1)
        for start in range(0, pixels.size, step):
            chunk = pixels[start:start + step]
            where = slice(chunk[0], chunk[-1] + 1) if chunk[-1] - chunk[0] + 1 == chunk.size else chunk
            for part in launches(1, 1, int(count), sampler):
                image = _launch_counts(mi, scene, chunk, part, passes, pass_seed(seed, 0, launch), width, height)
                launch += 1
                weight = part / count
                for p in range(passes):
                    pass_image = image[:, :, p].T          # (pixels, channels), a view
                    out_flat[p, where] += weight * panel_channels(pass_image, groups)
                    if lost is not None:
                        lost_flat[p, where] += weight * clamped_channels(pass_image, groups)
                # (pixels, passes, 3) with the strides the pixel-major image's fancy index gave (axis 2 outermost),
                # so that the mean adds the passes in the same order (the same bytes)
                aovs[chunk] += weight * np.moveaxis(image[[3, 4, -1]], 0, -1).mean(axis=1)
    return tuple(a.reshape(height, width) for a in aovs.T)


def _launch_counts(mi, scene, pixels: np.ndarray, count: int, passes: int, seed: int, width: int, height: int) -> np.ndarray:
    """One wavefront of ``count`` samples in each of ``passes`` passes at the flat ``pixels``: lanes ordered
    (pixel, pass, sample), sequences of ``count`` lanes (Mitsuba's ``render_sample``: position, ray, the
    integrator's ``sample``), each sample added into its (pixel, pass) in the same kernel (one thread:
    in lane order); returns (channels, pixels, passes) means, channels r, g, b then the AOVs (channel-major:
    stacking them pixel-major cost ~1 CPU-s of Fig. 2.8's job)."""
    import drjit as dr

    sensor = scene.sensors()[0]
    lanes = pixels.size * passes * count
    sampler = sensor.sampler().clone()
    sampler.set_sample_count(count)
    if sampler.sample_count() != count:
        raise ValueError(f"renders: {sampler.class_name()} takes {sampler.sample_count()} samples, not {count}")
    sampler.set_samples_per_wavefront(count)
    sampler.seed(seed, lanes)
    sequence = dr.arange(mi.UInt32, lanes) // count
    pixel = dr.gather(mi.UInt32, mi.UInt32(pixels.astype(np.uint32)), sequence // passes)
    row = pixel // width
    position = mi.Vector2f(mi.Float(pixel - row * width), mi.Float(row)) + sampler.next_2d()
    ray, weight = sensor.sample_ray_differential(0.0, 0.0, position / mi.ScalarVector2f(width, height), mi.Point2f(0.5))
    radiance, _, aovs = scene.integrator().sample(scene, sampler, ray, None, True)
    channels = [radiance[c] * weight[c] for c in range(3)] + list(aovs)
    sums = [dr.zeros(mi.Float, pixels.size * passes) for _ in channels]
    for total, channel in zip(sums, channels):
        dr.scatter_reduce(dr.ReduceOp.Add, total, channel, sequence)
    dr.eval(sums)
    return np.stack([np.asarray(v) for v in sums]).reshape(len(channels), pixels.size, passes) / count


def _plugin_costs(scene) -> dict:
    """{label: (samples, tries, evaluations)} of the plugins that count (``count = True``)."""
    out = {}
    for shape in scene.shapes():
        b = shape.bsdf()
        if getattr(b, "count", False):
            out[b.id()] = tuple(int(v) for v in np.asarray(b.costs))
    return out


def _describe(spec: dict) -> dict:
    """Material columns of a row (docs/contract.md names): model, metal, parameters, pumping."""
    keys = ("metal", "model", "n", "s", "b", "ratio", "d", "a_s", "diffuse", "strategy", "mis_density")
    out = {k: spec.get(k) for k in keys}
    if "rgb" in spec:          # eq. 3.31: Lambert r, g, b + a_s · phong_cosmin
        out["model"] = "phong_cosmin"
        out["rgb"] = " ".join(f"{c:g}" for c in spec["rgb"])
    elif "diffuse" in spec:
        out["model"] = "lambert"
    level = int(spec.get("pumped", 0))
    out["pumping"], out["level"] = ("g1" if level else "none"), level
    return out


def _count_columns(rendered: RenderedPanel, label: str, count: bool) -> dict:
    if not count:
        return {}
    samples, tries, evaluations = rendered.costs.get(label, (np.nan, np.nan, np.nan))
    return {"rays": rendered.rays, "plugin_samples": samples, "plugin_tries": tries,
            "plugin_evaluations": evaluations}


def _object_noise_columns(noise) -> dict:
    """An object's own noise figures (:func:`brdfs.render.mitsuba.metrics.object_noise`; None: no object pixels)."""
    if noise is None:
        return {"object_p95_relative_se": float("nan"), "object_fireflies": 0, "object_sparkles": 0,
                "object_noise_pixels": 0}
    return {"object_p95_relative_se": noise.p95_relative_se, "object_fireflies": noise.fireflies,
            "object_sparkles": noise.sparkles, "object_noise_pixels": noise.object_pixels}


def _clamp_columns(lost: np.ndarray | None, y: np.ndarray, sel: np.ndarray) -> dict:
    """``clamp_bias``: the object's relative bias from the clamp, −(light taken) / (light kept + taken)
    over its pixels (measured in the same passes: the integrator's ``k<g>_*`` AOVs), and its standard
    error over the passes; 0 without a clamp."""
    if lost is None:
        return {"clamp_bias": 0.0, "clamp_bias_err": 0.0}
    taken, kept = lost[:, sel].mean(axis=1), y[:, sel].mean(axis=1)
    bias = -taken / (kept + taken)
    return {"clamp_bias": float(-taken.mean() / (kept + taken).mean()),
            "clamp_bias_err": float(bias.std(ddof=1) / np.sqrt(bias.size))}


def object_rows(rendered: RenderedPanel, y: np.ndarray, noise: dict, lost: np.ndarray | None = None) -> list[dict]:
    """Per object: pixels, mean Y over its pixels and the standard error of that mean over passes
    (``y``: the (P, H, W) luminance passes), the object's own noise figures (``noise``:
    :func:`~brdfs.render.mitsuba.metrics.panel_noise`'s per object) and the clamp's bias (``lost``: the
    (P, H, W) luminance the clamp took, :func:`_clamp_columns`); ``object_spp``: the fewest samples per
    pixel of its pixels (``spp``, plus ``crop_spp`` inside the crop windows)."""
    rows = []
    samples = rendered.samples
    for k, label in sorted(rendered.labels.items()):
        sel = rendered.ids == k
        if label == "light" or not sel.any():
            continue
        per_pass = y[:, sel].mean(axis=1)
        rows.append({"object": label, "pixels": int(sel.sum()), "object_spp": int(samples[sel].min()),
                     "luminance": float(per_pass.mean()),
                     "luminance_err": float(per_pass.std(ddof=1) / np.sqrt(per_pass.size)),
                     **_object_noise_columns(noise.get(k)), **_clamp_columns(lost, y, sel)})
    return rows


def compute_panels(cfg: dict, name: str, panels: list[Panel], shared_scale: bool = True,
                   post=None, count: bool = False) -> pd.DataFrame:
    """Render ``panels``; rows per (panel, object), display images in ``df.attrs``.

    ``shared_scale``: one display scale for all panels (from the first panel's reference objects),
    else one per panel. ``post(panel, rendered) -> RenderedPanel`` may add a noise-free term (3.8).
    ``count``: columns ``rays`` (the panel's) and ``plugin_samples``, ``plugin_tries``,
    ``plugin_evaluations`` (per object whose plugin counts), over all passes.
    """
    import pandas as pd

    setups = panel_setups(figure_setup(settings(cfg), name), name, len(panels))
    rows, images, id_buffers, radiance, scale, seconds = [], [], [], [], None, []
    for k, (panel, setup) in enumerate(zip(panels, setups)):
        width, height = panel_size(setup, panel.aspect)
        wall, cpu = time.perf_counter(), time.process_time()
        rendered = render_panel(panel, cfg, setup, width, height, count)
        seconds.append({"panel": k, "title": panel.title, "wall_s": round(time.perf_counter() - wall, 3),
                        "cpu_s": round(time.process_time() - cpu, 3)})
        if post is not None:
            rendered = post(panel, rendered)
        channels = SPECTRAL if panel.channels == "spectral" else 3
        rgb = spectrum.linear_rgb(rendered.radiance)
        radiance.append(rgb.astype(np.float32))
        if scale is None or not shared_scale:
            ref = [i for i, label in rendered.labels.items() if label in panel.reference]
            scale = spectrum.display_scale(rgb, np.isin(rendered.ids, ref))
        images.append((panel.title, spectrum.to_display(rgb, scale)))
        id_buffers.append((rendered.ids, rendered.labels))
        y = rendered.luminance_passes(channels)
        noise, per_object = metrics.panel_noise(y, rendered.ids)
        specs = {label: spec for label, _, spec in panel.objects}
        lost = None if rendered.lost is None else rendered.lost @ spectrum.luminance_weights(channels)
        for row in object_rows(rendered, y, per_object, lost):
            rows.append({"figure": name, "panel": k, "panel_title": panel.title, **row,
                         **_describe(specs.get(row["object"], {})),
                         "width": width, "height": height, "spp": rendered.spp,
                         "crop_spp": rendered.crop_spp, "crop_windows": len(rendered.windows), "passes": setup["passes"],
                         "max_depth": panel.max_depth, "preset": setup["preset"], "variant": setup["variant"],
                         "caustics": bool(setup["caustics"]), "clamp": float(setup.get("clamp", 0.0)),
                         "point_lights": len(panel.lights),
                         "sky_radiance": cfg[SECTION]["sky_radiance"] if panel.sky else 0.0,
                         "p95_relative_se": noise.p95_relative_se, "fireflies": noise.fireflies,
                         "object_pixels": noise.object_pixels, "display_scale": scale, **panel.extra,
                         **_count_columns(rendered, row["object"], count)})
    df = pd.DataFrame(rows)
    df.attrs["images"] = SharedList(images)
    df.attrs["ids"] = SharedList(id_buffers)
    df.attrs[RADIANCE] = SharedList(radiance)
    df.attrs[TIMING] = SharedList(seconds)
    return df


class SharedList(list):
    """A list in ``df.attrs`` that pandas shares with the frames derived from ``df`` instead of deep-copying
    it: pandas deep-copies ``attrs`` into every frame or column it derives (``__finalize__``), and a
    figure's images, ID buffers and radiance (tens of MB) were copied on every column read (0.7 CPU-s
    of Fig. 2.8's job). They are results, never changed in place."""

    def __deepcopy__(self, memo):
        return self


#: ``df.attrs`` key of the panels' linear radiance: a list of (H, W, 3) float32 linear sRGB, panel by panel.
RADIANCE = "radiance"
#: ``df.attrs`` key of the panels' measured render seconds (wall and process CPU, a list of dicts:
#: panel, title, wall_s, cpu_s); written by :func:`write_renders` to :data:`TIMING_FILE`, never to
#: the CSV or PNG (which stay byte-identical).
TIMING = "timing"
#: The JSON file of a figure's measured render seconds per panel, beside its EXR files (the report's
#: and the docs' figure pages show it: :func:`brdfs.pipeline.report.render_seconds`).
TIMING_FILE = "timing.json"


def exr_name(panel: int) -> str:
    """The OpenEXR file of panel ``panel`` (the CSV's ``panel``) in its figure's renders directory."""
    return f"panel_{panel}.exr"


def write_renders(df: pd.DataFrame, directory) -> list:
    """Write each panel's linear radiance (``df.attrs["radiance"]``) as a 32-bit float RGB OpenEXR
    file :func:`exr_name` in ``directory`` (created; other ``panel_*.exr`` files there removed), by
    Mitsuba's own writer (``mi.Bitmap(...).write``), each atomically; the same image gives the same
    bytes for one variant and machine; the panels' measured seconds (``df.attrs["timing"]``, if
    any) go to :data:`TIMING_FILE` beside them.  Returns the EXR paths."""
    import os
    from pathlib import Path

    radiance = df.attrs.get(RADIANCE)
    if not radiance:
        raise ValueError(f"{directory}: no linear radiance passed from compute (df.attrs[{RADIANCE!r}])")
    mi = _mitsuba(str(df["variant"].iloc[0]))
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = []
    for k, rgb in enumerate(radiance):
        path = directory / exr_name(k)
        tmp = path.with_name(f".{path.name}.tmp.exr")
        mi.Bitmap(np.ascontiguousarray(rgb, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(str(tmp))
        os.replace(tmp, path)
        paths.append(path)
    for stale in set(directory.glob("panel_*.exr")) - set(paths):
        stale.unlink()
    if df.attrs.get(TIMING):
        path = directory / TIMING_FILE
        tmp = path.with_name(f".{path.name}.tmp")
        tmp.write_text(json.dumps({"figure": str(df["figure"].iloc[0]), "panels": df.attrs[TIMING]}, indent=1),
                       encoding="utf-8")
        os.replace(tmp, path)
    return paths


def object_crop(image: np.ndarray, ids: np.ndarray, labels: dict, label: str, margin: int = 6,
                side: str | None = None) -> np.ndarray:
    """The pixels of ``image`` in the bounding box of ``label``'s ID (plus ``margin``), native
    resolution; ``side = "right"`` keeps the right half of the box (a silhouette's rim)."""
    k = next(i for i, name in labels.items() if name == label)
    rows, cols = np.nonzero(ids == k)
    r0, r1 = max(rows.min() - margin, 0), min(rows.max() + margin + 1, ids.shape[0])
    c0, c1 = max(cols.min() - margin, 0), min(cols.max() + margin + 1, ids.shape[1])
    if side == "right":
        c0 = (c0 + c1) // 2
    return image[r0:r1, c0:c1]


def project(camera: dict, width: int, height: int, points) -> np.ndarray:
    """Continuous (column, row) image coordinates of world ``points`` (N, 3) in a ``width`` × ``height``
    panel seen by ``camera`` (eye, target, vertical ``fov_deg``, up +z: Mitsuba's ``look_at`` and
    ``perspective`` with ``fov_axis = "y"``); pixel (i, j) covers [j, j + 1) × [i, i + 1)."""
    eye, target = np.asarray(camera["eye"], float), np.asarray(camera["target"], float)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    rel = np.atleast_2d(np.asarray(points, float)) - eye
    depth = rel @ forward
    focal = 0.5 * height / np.tan(np.radians(camera.get("fov_deg", 30.0)) / 2.0)
    return np.stack([0.5 * width + focal * (rel @ right) / depth, 0.5 * height - focal * (rel @ up) / depth], axis=-1)


def framed_camera(camera: dict, points, aspect: float, fill: float = 0.92, rounds: int = 4) -> dict:
    """``camera`` moved along its own viewing direction (its field of view kept) and shifted sideways,
    so that the projections of ``points`` (N, 3: the objects to show) are centred and fill ``fill``
    of the picture's width or height, whichever they reach first (``aspect`` = width / height)."""
    points = np.asarray(points, float)
    height = 1000.0
    width = aspect * height
    eye, target = np.asarray(camera["eye"], float), np.asarray(camera["target"], float)
    back = (eye - target) / np.linalg.norm(eye - target)
    target = 0.5 * (points.min(axis=0) + points.max(axis=0))
    focal = 0.5 * height / np.tan(np.radians(camera.get("fov_deg", 30.0)) / 2.0)

    def extent(distance, centre):
        pixels = project({**camera, "eye": centre + distance * back, "target": centre}, width, height, points)
        return max(np.abs(pixels[:, 0] - width / 2).max() / (width / 2), np.abs(pixels[:, 1] - height / 2).max() / (height / 2))

    distance = float(np.linalg.norm(eye - np.asarray(camera["target"], float)))
    for _ in range(rounds):
        lo, hi = 1e-3 + np.linalg.norm(points - target, axis=1).max(), 1e3
        for _ in range(60):                  # bisection: the extent shrinks as the camera backs off
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if extent(mid, target) > fill else (lo, mid)
        distance = hi
        cam = {**camera, "eye": target + distance * back, "target": target}
        pixels = project(cam, width, height, points)
        offset = 0.5 * (pixels.min(axis=0) + pixels.max(axis=0)) - (width / 2, height / 2)
        forward = -back
        right = np.cross(forward, (0.0, 0.0, 1.0))
        right /= np.linalg.norm(right)
        up = np.cross(right, forward)
        target = target + (offset[0] * right - offset[1] * up) * distance / focal
    return {**camera, "eye": tuple(float(v) for v in target + distance * back), "target": tuple(float(v) for v in target)}


def object_points(objects, skip=("floor",)) -> np.ndarray:
    """The vertices (and sphere centres ± radius) of ``objects`` (label, parts, spec) but those labelled ``skip``."""
    out = []
    for label, parts, _ in objects:
        if label in skip:
            continue
        for part in parts:
            if "vertices" in part:
                out.append(np.asarray(part["vertices"], float))
            elif part.get("type") == "sphere":
                out.append(np.asarray(part["center"]) + part["radius"] * np.vstack([np.eye(3), -np.eye(3)]))
    return np.concatenate(out)


def draw_polylines(image: np.ndarray, lines, colour=(255, 255, 255), width: int = 1) -> np.ndarray:
    """A copy of ``image`` (H, W, 3 uint8) with the polylines ``lines`` (each (N, 2) column, row) drawn."""
    from PIL import Image, ImageDraw

    out = Image.fromarray(np.ascontiguousarray(image[..., :3]))
    draw = ImageDraw.Draw(out)
    for line in lines:
        if len(line) > 1:
            draw.line([tuple(map(float, p)) for p in line], fill=tuple(colour), width=width)
    return np.asarray(out)


def sphere_meridians(camera: dict, center, radius: float, count: int = 12, steps: int = 48) -> list[np.ndarray]:
    """World polylines of ``count`` meridians (great circles through the poles) of a sphere, each cut
    to its stretches on the hemisphere facing ``camera``'s eye."""
    center, eye = np.asarray(center, float), np.asarray(camera["eye"], float)
    polar = np.linspace(0.0, np.pi, steps)
    out = []
    for phi in np.linspace(0.0, 2.0 * np.pi, count, endpoint=False):
        normal = np.stack([np.cos(phi) * np.sin(polar), np.sin(phi) * np.sin(polar), np.cos(polar)], axis=-1)
        points = center + radius * normal
        facing = np.einsum("ij,ij->i", normal, eye - points) > 0.0
        for run in np.split(np.arange(steps), np.flatnonzero(np.diff(facing.astype(int))) + 1):
            if facing[run[0]] and run.size > 1:
                out.append(points[run])
    return out


# --- the PNG at native resolution ---------------------------------------------------------------------

TITLE_PX = 22
GAP_PX = 8


def plot_panels(df: pd.DataFrame, path, title: str, columns: int | None = None) -> None:
    """The panels in a grid (``columns`` per row), each at its native resolution (one render pixel is
    one PNG pixel: the images are placed with ``figimage``, never resampled), each under its title."""
    import matplotlib
    import matplotlib.pyplot as plt

    from brdfs.pipeline import plotting

    images = df.attrs.get("images")
    if not images:
        raise ValueError(f"{path}: no rendered images passed from compute (df.attrs['images'])")
    columns = columns or len(images)
    grid = [images[i:i + columns] for i in range(0, len(images), columns)]
    cell_w = max(img.shape[1] for _, img in images) + GAP_PX
    row_h = [max(img.shape[0] for _, img in row) + TITLE_PX for row in grid]     # each row as tall as it needs
    width, height = columns * cell_w + GAP_PX, sum(row_h) + TITLE_PX + GAP_PX
    dpi = plotting.DPI
    fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    fig.text(0.5, 1.0 - 4.0 / height, title, ha="center", va="top", fontsize=9)
    for r, row in enumerate(grid):
        for c, (panel_title, img) in enumerate(row):
            x0 = GAP_PX + c * cell_w
            top = TITLE_PX + sum(row_h[:r]) + TITLE_PX          # pixels from the top to the image's top
            fig.figimage(img, xo=x0, yo=height - top - img.shape[0], origin="upper", resize=False)
            wrapped = textwrap.shorten(panel_title, width=max(img.shape[1] // 6, 20), placeholder=" ...")
            fig.text((x0 + img.shape[1] / 2) / width, 1.0 - (top - 4) / height, wrapped,
                     ha="center", va="bottom", fontsize=7)
    with matplotlib.rc_context({"savefig.bbox": None}):
        fig.savefig(path, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)


# --- geometry shared by the scenes -----------------------------------------------------------------

def row(count, half_width):
    """x of ``count`` objects spread evenly over [−half_width, half_width] (a single one at −half_width)."""
    return [-half_width + 2 * half_width * k / max(count - 1, 1) for k in range(count)]


def floor(size=4.0):
    return msc.floor(size)


def sphere(x, y, r):
    return msc.sphere((x, y, r), r)


def tank(x, y, scale=1.0):
    """The tank: box hull, capped cylinder turret, barrel (:func:`brdfs.render.mitsuba.scenes.tank`)."""
    return msc.tank(x, y, scale)


THREE_LIGHTS = [((-4.0, -5.0, 6.0), 1.0), ((5.0, -3.0, 5.0), 0.6), ((0.0, 4.0, 7.0), 0.5)]
TWO_LIGHTS = [((-4.0, -5.0, 6.0), 1.0), ((5.0, -3.0, 5.0), 0.6)]
STREET_CAMERA = {"eye": (0.0, -7.0, 3.2), "target": (0.0, 0.0, 0.5), "fov_deg": 34.0}
