"""The rendered figures (artifacts fig_2_8, fig_3_8 ... fig_4_18) on tiny images."""
from __future__ import annotations

import copy
import dataclasses
import importlib

import numpy as np
import pytest
import yaml

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import fig_4_18_generalized_lambert as fig_4_18
from brdfs.render import tracer
from brdfs.pipeline import registry
from brdfs.pipeline.config import CONFIG_YAML

RENDERS = ["fig_2_8_pumping_render", "fig_3_8_material_spheres", "fig_3_9_metals_new_model",
           "fig_3_10_metal_teapots", "fig_3_11_silver_mirror", "fig_3_12_plastics", "fig_3_13_ceramics",
           "fig_4_11_anisotropic_metals", "fig_4_16_patch_metals", "fig_4_17_patch_shapes",
           "fig_4_18_generalized_lambert"]


@pytest.fixture(scope="module")
def tiny_cfg():
    cfg = yaml.safe_load(CONFIG_YAML.read_text())
    cfg["renders"]["draft"] = {"width": 24, "height": 18, "spp": 4, "depth": 2}
    return registry.config_subset(cfg, ["renders"])


@pytest.fixture(scope="module")
def frames(tiny_cfg):
    return {name: registry.get_artifact(name).compute(tiny_cfg, {}) for name in RENDERS}


def _sky_lit_panels(cfg, name):
    """The panels of a figure that the sky lights (a direct-only panel is lit by point lights alone)."""
    return [p for p in importlib.import_module(f"brdfs.artifacts.{name}").panels(cfg) if p.sky]


@pytest.fixture(scope="module")
def sky_only_frames(tiny_cfg):
    """The figures' sky-lit panels with their point lights switched off: the uniform sky S alone."""
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["light_intensity"] = 0.0
    return {name: rf.compute_panels(cfg, name, panels) for name in RENDERS if (panels := _sky_lit_panels(cfg, name))}


@pytest.mark.parametrize("name", RENDERS)
def test_every_figure_is_a_white_furnace_when_its_objects_are_white_lambert(name, tiny_cfg, tmp_path):
    """The figure's own scenes (shapes, floor, camera), every material a Lambert of albedo 1, the
    point lights off, the sky S on: a path that leaves carries throughput 1 (interreflections
    included), so every object shows S, short only by the paths still bouncing after 40 vertices
    (in the thin wedge where a sphere touches the floor: at most 1 % here) and never above it —
    the tracer's geometry, shading frames, ray offsets, escape to the sky and cosine sampling,
    figure by figure."""
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["draft"]["depth"] = 40
    module = importlib.import_module(f"brdfs.artifacts.{name}")
    white = [dataclasses.replace(p, objects=[(label, shape, {"diffuse": 1.0}) for label, shape, _ in p.objects],
                                 lights=[], sky=True, background=None) for p in module.panels(cfg)[:1]]
    df = rf.compute_panels(cfg, name, white)
    objects = df[df["object"] != "background"]
    S = cfg["renders"]["sky_radiance"]
    assert len(objects) >= 2 and np.all(objects["pixels"] > 0)
    assert np.all(objects["luminance"] <= S * (1 + 1e-12)), objects["luminance"].max() - S
    assert np.all(objects["luminance"] >= 0.99 * S), objects[["object", "luminance"]]
    rf.plot_panels(df, tmp_path / "x.png", name)
    assert (tmp_path / "x.png").stat().st_size > 1000


@pytest.mark.parametrize("name", [n for n in RENDERS if n != "fig_4_18_generalized_lambert"])   # direct-only
def test_under_the_sky_alone_no_object_of_a_figure_outshines_the_sky(name, sky_only_frames):
    """Every material of the figures conserves energy (the new model, pumped models, F ≤ 1, eq. 3.31's
    a_s + max(r, g, b) ≤ 1, the patch models' C_max), so under a uniform sky S alone no point
    reflects more than S (L = ∫ f L_in cos θ dω ≤ a · S ≤ S, bounce by bounce): every object's mean
    luminance ≤ S within 5 standard errors, and a lit object is not black."""
    df = sky_only_frames[name]
    objects = df[(df["object"] != "background") & (df["sky_radiance"] > 0)]
    assert len(objects) >= 2
    assert np.all(objects["luminance"] <= objects["sky_radiance"] + 5 * objects["luminance_err"])
    assert np.all(objects["luminance"] > 0) and np.all(objects["luminance_err"] > 0)


def test_pumping_brightens_every_object_of_figure_2_8(frames):
    """Pumping divides f by g ≤ 1 with the same proposal and random stream: never darker (Sec. 2.3)."""
    df = frames["fig_2_8_pumping_render"]
    objects = df[df["object"] != "background"]
    for n in objects["n"].dropna().unique():
        in_panels = objects[objects["panel_title"].str.endswith(f"n = {n:g}")]
        plain = in_panels[in_panels["panel"] < 2].set_index("object")["luminance"]
        pumped = in_panels[in_panels["panel"] >= 2].set_index("object")["luminance"]
        assert set(objects[objects["panel"] >= 2]["pumping"].dropna()) - {"none"} == {"g1"}
        assert len(plain) == len(pumped) >= 6
        assert np.all(pumped >= plain * (1 - 1e-12)), (n, plain, pumped)
        assert (pumped > plain * 1.01).any()


def test_the_d_1_sphere_under_a_light_at_the_eye_is_a_full_moon(tiny_cfg):
    """Sec. 4.7.4: with the light at the eye, d = 1 gives almost constant radiance over the disk,
    flatter than d = 0.25 (rim-darkened like Lambert)."""
    cfg = copy.deepcopy(tiny_cfg)
    panel = fig_4_18.panels(cfg)[0]
    spread = {}
    for label, shape, spec in panel.objects:
        eye = tuple(np.add(shape.center, (0.0, -1000.0, 0.0)))   # far: 1/r² is constant over the disk
        single = rf.Panel("", [(label, shape, spec)], [(eye, 1.0)], {"eye": eye, "target": shape.center},
                          sky=False, channels=3)
        scene = rf._scene(single, cfg)
        camera = tracer.Camera(eye, shape.center, 21, 21, fov_deg=0.13)
        image = tracer.render(scene, camera)
        values = image.radiance[image.index == 0, 0]
        q25, q50, q75 = np.percentile(values, [25, 50, 75])
        spread[spec["d"]] = (q75 - q25) / q50   # the rim beyond m_clip (eq. 4.59) is ~10 % of the disk
    assert spread[1.0] < 1e-3 < 0.1 * spread[0.25]
    assert spread[1.0] < spread[0.75] < spread[0.5] < spread[0.25]


def test_quality_switch_rejects_unknown_values(tiny_cfg):
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["quality"] = "ultra"
    with pytest.raises(ValueError, match="renders.quality"):
        rf.settings(cfg)
