"""The rendered figures (artifacts fig_2_8, fig_3_8 ... fig_4_18) on tiny images."""
from __future__ import annotations

import copy

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


@pytest.mark.parametrize("name", RENDERS)
def test_every_render_reports_each_object_with_a_finite_luminance_and_error(name, frames, tmp_path):
    df = frames[name]
    assert set(df["quality"]) == {"draft"}
    assert np.all(np.isfinite(df["luminance"])) and np.all(df["luminance"] >= 0)
    assert np.all(df["luminance_err"] >= 0)
    objects = df[df["object"] != "background"]
    assert len(objects) >= 2 and np.all(objects["pixels"] > 0)
    direct = df["spp"] == 1
    assert np.all(df.loc[direct, "luminance_err"] == 0)
    registry.get_artifact(name).plot(df, tmp_path / "x.png")
    assert (tmp_path / "x.png").stat().st_size > 1000


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
