"""The rendered figures (artifacts fig_2_8, fig_3_8 ... fig_4_18) on tiny images, through Mitsuba."""
from __future__ import annotations

import copy
import dataclasses
import importlib
import json
import re

import numpy as np
import pandas as pd
import pytest
import yaml

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import fig_4_18_generalized_lambert as fig_4_18
from brdfs.pipeline import registry
from brdfs.pipeline.config import CONFIG_YAML
from brdfs.pipeline.io import REPO_ROOT

#: Figures whose geometry differs (tank, bust and pyramid, cube and capped cylinder).
GEOMETRIES = ["fig_3_9_metals_new_model", "fig_3_11_silver_mirror", "fig_4_17_patch_shapes"]


@pytest.fixture(scope="module")
def mitsuba():
    from brdfs.render.mitsuba import MissingLLVM, use_variant
    try:
        return use_variant("llvm_ad_rgb")
    except MissingLLVM as exc:
        pytest.skip(str(exc))


@pytest.fixture(scope="module")
def tiny_cfg(mitsuba):
    cfg = yaml.safe_load(CONFIG_YAML.read_text())
    cfg["renders"]["preview"] = {"min_width": 48, "min_height": 30, "spp": 8, "passes": 8}
    return registry.config_subset(cfg, ["renders"])


@pytest.mark.parametrize("name", GEOMETRIES)
def test_every_figure_is_a_white_furnace_when_its_objects_are_white_lambert(name, tiny_cfg, tmp_path):
    """The figure's own scene (shapes, floor, camera), every material a Lambert of albedo 1, the point
    lights off, the sky S on: every object shows S (interreflections included: paths end by Russian
    roulette only), within 5 standard errors, and never above it by more."""
    cfg = copy.deepcopy(tiny_cfg)
    module = importlib.import_module(f"brdfs.artifacts.{name}")
    white = [dataclasses.replace(p, objects=[(label, parts, {"diffuse": 1.0}) for label, parts, _ in p.objects],
                                 lights=[], sky=True, background=None) for p in module.panels(cfg)[:1]]
    df = rf.compute_panels(cfg, name, white)
    S = cfg["renders"]["sky_radiance"]
    assert len(df) >= 2 and np.all(df["pixels"] > 0)
    assert np.all(np.abs(df["luminance"] - S) <= 5 * df["luminance_err"] + 2e-3 * S), df[["object", "luminance"]]
    rf.plot_panels(df, tmp_path / "x.png", name)
    assert (tmp_path / "x.png").stat().st_size > 1000


def test_pumping_brightens_every_object_of_figure_2_8(tiny_cfg):
    """Pumping divides f by g ≤ 1 with the same sampler and seeds: never darker (Sec. 2.3)."""
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["pumping"]["n"] = [20]
    df = registry.get_artifact("fig_2_8_pumping_render").compute(cfg, {})
    profile, df = df[df["theta_v_deg"].notna()], df[df["theta_v_deg"].isna()]
    plain = df[df["level"] == 0].set_index("object")
    pumped = df[df["level"] == 1].set_index("object")
    metals = [o for o in plain.index if o != "floor"]
    assert set(pumped["pumping"]) == {"g1"} and len(metals) >= 5
    assert np.all(pumped.loc[metals, "luminance"] >= plain.loc[metals, "luminance"]
                  - 5 * np.hypot(pumped.loc[metals, "luminance_err"], plain.loc[metals, "luminance_err"]))
    assert (pumped.loc[metals, "luminance"] > plain.loc[metals, "luminance"] * 1.01).any()
    assert len(df.attrs["images"]) == 4            # two panels, the silver pyramid's crops and profile
    # the limb profile (Y per θ_V bin of a silver sphere under daylight): pumped brighter near the limb
    outer = profile.loc[profile.groupby("level")["theta_v_deg"].idxmax()].set_index("level")
    assert set(outer.index) == {0, 1} and (profile["object"] == "silver sphere, daylight only").all()
    assert outer["theta_v_deg"].min() > 70.0
    assert outer.loc[1, "luminance"] > outer.loc[0, "luminance"] + 2 * np.hypot(*outer["luminance_err"])


def test_the_d_1_sphere_under_a_light_at_the_eye_is_a_full_moon(tiny_cfg):
    """Sec. 4.7.4: with the light at the eye, d = 1 gives almost constant radiance over the disk,
    flatter than d = 0.25 (rim-darkened like Lambert)."""
    cfg = copy.deepcopy(tiny_cfg)
    setup = rf.settings(cfg)
    panel = fig_4_18.panels(cfg)[0]
    spread = {}
    for label, parts, spec in panel.objects:
        center = np.asarray(parts[0]["center"])
        eye = tuple(center + (0.0, -100.0, 0.0))     # far: 1/r² is nearly constant over the disk
        single = dataclasses.replace(panel, objects=[(label, parts, spec)], lights=[(eye, 1.0)],
                                     camera={"eye": eye, "target": tuple(center), "fov_deg": 1.3}, aspect=1.0)
        rendered = rf.render_panel(single, cfg, setup, 24, 24)
        inside = rendered.ids == 1.0
        values = rendered.radiance[inside, 0]
        q25, q50, q75 = np.percentile(values, [25, 50, 75])
        spread[spec["d"]] = (q75 - q25) / q50   # the rim beyond m_clip (eq. 4.59) is ~10 % of the disk
    assert spread[1.0] < 1e-2 < 0.2 * spread[0.25], spread
    assert spread[1.0] < spread[0.75] < spread[0.5] < spread[0.25]


def test_the_preset_switch_rejects_unknown_values_in_one_line(tiny_cfg):
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["preset"] = "ultra"
    with pytest.raises(ValueError, match="renders.preset = 'ultra'"):
        rf.settings(cfg)
    cfg["renders"]["preset"] = "preview"
    cfg["renders"]["preview"]["passes"] = 4
    with pytest.raises(ValueError, match="passes = 4"):
        rf.settings(cfg)


def _written_bytes(cfg: dict, name: str, folder) -> tuple[bytes, bytes, bytes]:
    """The CSV, PNG and first panel's OpenEXR bytes of ``name`` written into ``folder``."""
    artifact = registry.get_artifact(name)
    folder.mkdir()
    df = artifact.compute(cfg, {})
    artifact.write(df, folder / "x.csv", folder / "x.png", folder / "renders")
    exr = folder / "renders" / rf.exr_name(0)
    return (folder / "x.csv").read_bytes(), (folder / "x.png").read_bytes(), exr.read_bytes()


def test_a_render_figure_written_twice_from_one_config_has_identical_csv_png_and_exr_bytes(tiny_cfg, tmp_path):
    """Byte determinism (issue 23): the passes' seeds come from the config's ``seed`` alone, so two
    runs agree byte for byte, the OpenEXR linear radiance included (issue 42: Mitsuba's writer, the
    same bytes for the same image on one variant and machine), and another ``seed`` gives another
    noise (the seed is really used). The crop windows' passes (``crop_spp``) are seeded alike."""
    cfg = copy.deepcopy(tiny_cfg)
    name = "fig_3_12_plastics"                 # an rgb figure: one pass per seed (the cheapest)
    preset = cfg["renders"][cfg["renders"]["preset"]]
    preset["crop_spp"] = {name: preset["passes"]}
    first = _written_bytes(cfg, name, tmp_path / "a")
    assert (pd.read_csv(tmp_path / "a" / "x.csv")["crop_windows"] > 0).all()
    assert _written_bytes(cfg, name, tmp_path / "b") == first
    cfg["seed"] = int(cfg["seed"]) + 1
    other = _written_bytes(cfg, name, tmp_path / "c")
    assert other[0] != first[0] and other[2] != first[2]


def test_each_panel_is_written_as_32_bit_float_openexr_of_its_linear_radiance(tiny_cfg, tmp_path, mitsuba):
    """results/renders/<figure>/panel_<k>.exr: one file per panel (the CSV's ``panel``), RGB float32,
    the panel's mean over its passes in linear sRGB exactly (the values the PNG is scaled from); a
    panel file left from an earlier run with more panels is removed."""
    mi = mitsuba
    cfg = copy.deepcopy(tiny_cfg)
    df = registry.get_artifact("fig_4_18_generalized_lambert").compute(cfg, {})
    (tmp_path / rf.exr_name(99)).write_bytes(b"stale")
    paths = rf.write_renders(df, tmp_path)
    assert [p.name for p in sorted(tmp_path.glob("*.exr"))] == sorted(rf.exr_name(k) for k in df["panel"].unique())
    timing = json.loads((tmp_path / rf.TIMING_FILE).read_text())      # measured seconds: beside, not in the CSV
    assert [p["panel"] for p in timing["panels"]] == sorted(df["panel"].unique())
    assert all(p["wall_s"] > 0 and p["cpu_s"] > 0 for p in timing["panels"])
    assert not {"wall_s", "cpu_s"} & set(df.columns)
    for k, path in enumerate(paths):
        bitmap = mi.Bitmap(str(path))
        assert bitmap.component_format() == mi.Struct.Type.Float32
        assert bitmap.pixel_format() == mi.Bitmap.PixelFormat.RGB
        image = np.asarray(bitmap)
        assert image.dtype == np.float32 and np.array_equal(image, df.attrs[rf.RADIANCE][k])
        assert image.shape[:2] == tuple(df[df["panel"] == k][["height", "width"]].iloc[0])
    assert registry.get_artifact("fig_4_18_generalized_lambert").renders == "results/renders/fig_4_18_generalized_lambert"
    assert registry.get_artifact("table_3_2_ward_cmax").renders is None


def _contract_render_columns() -> set:
    """The column names docs/contract.md lists for the renders (its "- Renders" item)."""
    (line,) = [line for line in (REPO_ROOT / "docs" / "contract.md").read_text().splitlines()
               if line.startswith("- Renders")]
    return set(re.findall(r"`([A-Za-z_0-9]+)`", line))


def test_a_render_csv_records_the_caustics_setting_and_names_only_contract_columns(tiny_cfg):
    """The ``caustics`` column is the integrator's setting (``renders.caustics``) as a bool, beside
    ``variant``, ``preset`` and ``passes``; every column is one docs/contract.md lists for renders."""
    cfg = copy.deepcopy(tiny_cfg)
    name = "fig_3_12_plastics"                 # the cheapest figure: one rgb panel
    listed = _contract_render_columns()
    for caustics in (False, True):
        cfg["renders"]["caustics"] = caustics
        df = registry.get_artifact(name).compute(cfg, {})
        assert df["caustics"].dtype == bool and (df["caustics"] == caustics).all()
        assert {"variant", "preset", "passes", "caustics"} <= set(df.columns)
        unlisted = {c for c in df.columns if c not in listed and not c.endswith("_per_pixel")}
        assert not unlisted, f"render columns missing from docs/contract.md: {sorted(unlisted)}"


def test_the_groove_lines_of_figure_4_11_fall_on_their_spheres(tiny_cfg):
    """The meridians drawn on Fig. 4.11 (camera projection of rf.project) land on the pixels Mitsuba
    rendered of their own sphere: each sphere's centre and most of its meridian points hit its ID."""
    from brdfs.artifacts import fig_4_11_anisotropic_metals as fig_4_11

    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["preview"] = {"min_width": 160, "min_height": 100, "spp": 8, "passes": 8}
    panel = fig_4_11.panels(cfg)[0]
    width, height = rf.panel_size(rf.settings(cfg), panel.aspect)
    rendered = rf.render_panel(panel, cfg, rf.settings(cfg), width, height)
    spheres = [(label, parts[0]) for label, parts, _ in panel.objects if parts[0]["type"] == "sphere"]
    assert len(spheres) == 4
    for label, part in spheres:
        k = next(i for i, name in rendered.labels.items() if name == label)
        col, row = rf.project(panel.camera, width, height, [part["center"]])[0]
        assert rendered.ids[int(row), int(col)] == k, label
        points = np.concatenate([rf.project(panel.camera, width, height, m)
                                 for m in rf.sphere_meridians(panel.camera, part["center"], part["radius"])])
        inside = (points[:, 0] >= 0) & (points[:, 0] < width) & (points[:, 1] >= 0) & (points[:, 1] < height)
        hits = rendered.ids[points[inside, 1].astype(int), points[inside, 0].astype(int)]
        assert inside.all() and np.mean(np.isin(hits, [k, rf.MIXED_ID])) > 0.97, label
    image = np.zeros((height, width, 3), np.uint8)
    overlay = fig_4_11.groove_overlay(panel, image)
    assert overlay.any() and overlay.shape[0] < height


def test_a_framed_camera_centres_its_points_and_fills_the_picture():
    """rf.framed_camera: the projected points are centred and reach the fill fraction on one axis,
    keeping the camera's viewing direction."""
    rng = np.random.default_rng(1)
    points = rng.uniform((-2.0, -0.5, 0.0), (2.0, 0.5, 0.8), size=(400, 3))
    camera = {"eye": (0.0, -6.0, 2.5), "target": (0.0, 0.0, 0.4), "fov_deg": 36.0}
    framed = rf.framed_camera(camera, points, 1.6, fill=0.9)
    pixels = rf.project(framed, 1600, 1000, points)
    half = np.array([800.0, 500.0])
    reach = np.abs(pixels - half).max(axis=0) / half
    assert np.isclose(reach.max(), 0.9, atol=2e-3)
    assert np.allclose(0.5 * (pixels.min(axis=0) + pixels.max(axis=0)), half, atol=2.0)
    before = np.subtract(camera["eye"], camera["target"])
    after = np.subtract(framed["eye"], framed["target"])
    assert np.allclose(before / np.linalg.norm(before), after / np.linalg.norm(after))


def test_no_sphere_of_figure_4_18_shadows_a_neighbour(tiny_cfg):
    """Fig. 4.18's two-light panel: each sphere has the luminance it has alone in the scene (direct
    light from delta lights, the same jittered samples: equal but for float rounding)."""
    cfg = copy.deepcopy(tiny_cfg)
    cfg["renders"]["preview"] = {"min_width": 120, "min_height": 40, "spp": 8, "passes": 8}
    setup = rf.settings(cfg)
    panel = dataclasses.replace(fig_4_18.panels(cfg)[1], spp=8)
    width, height = rf.panel_size(setup, panel.aspect)
    together = rf.compute_panels(cfg, fig_4_18.NAME, [panel], shared_scale=False).set_index("object")
    for label, parts, spec in panel.objects:
        alone = dataclasses.replace(panel, objects=[(label, parts, spec)])
        row = rf.compute_panels(cfg, fig_4_18.NAME, [alone]).set_index("object").loc[label]
        assert row["pixels"] == together.loc[label, "pixels"] and width > 0
        assert np.isclose(row["luminance"], together.loc[label, "luminance"], rtol=1e-4), label



def test_a_figures_clamp_reaches_its_integrator_and_its_taken_light_maps_to_the_panels_channels():
    """``renders.<preset>.clamp.<figure>`` (issue 42's caustic treatment) is that figure's integrator
    ``clamp`` in that preset (0 for the others); the light the clamp took (AOVs ``k<g>_*`` after the
    ``c<g>_*``) maps to the eight wavelengths as the image's groups do; each object's ``clamp_bias`` is
    −taken / (kept + taken)."""
    cfg = yaml.safe_load(CONFIG_YAML.read_text())
    cfg["renders"]["preview"]["clamp"] = {"fig_3_11_silver_mirror": 3.0}
    cfg["renders"]["final"]["clamp"] = {"fig_3_9_metals_new_model": 5.0}
    setup = rf.settings(cfg)
    assert rf.figure_setup(setup, "fig_3_11_silver_mirror")["clamp"] == 3.0
    assert rf.figure_setup(setup, "fig_3_9_metals_new_model")["clamp"] == 0.0
    cfg["renders"]["preset"] = "final"
    final = rf.settings(cfg)
    assert rf.figure_setup(final, "fig_3_11_silver_mirror")["clamp"] == 0.0
    assert rf.figure_setup(final, "fig_3_9_metals_new_model")["clamp"] == 5.0
    assert rf._integrator(rf.Panel("p", [], [], {}), clamp=4.0)["clamp"] == 4.0
    groups = rf.WAVELENGTH_PASSES
    colour = 3 * len(groups)
    image = np.zeros((2, 3, 3 + 2 + (colour - 3) + colour + 1))
    image[..., :3] = [1.0, 2.0, 3.0]
    image[..., 5:5 + colour - 3] = np.arange(4.0, colour + 1)          # c1_*, c2_*, ...
    image[..., 5 + colour - 3:-1] = 10.0 * np.arange(1.0, colour + 1)  # k0_*, k1_*, ...: 10 x the same order
    assert np.array_equal(rf.clamped_channels(image, groups), 10.0 * rf.panel_channels(image, groups))
    assert np.array_equal(rf.clamped_channels(image[..., :9], None), image[..., 5:8])
    kept, taken = np.ones((8, 2, 2)), np.full((8, 2, 2), 0.25)
    columns = rf._clamp_columns(taken, kept, np.ones((2, 2), bool))
    assert columns["clamp_bias"] == -0.2 and columns["clamp_bias_err"] == 0.0
    assert rf._clamp_columns(None, kept, np.ones((2, 2), bool)) == {"clamp_bias": 0.0, "clamp_bias_err": 0.0}


def test_an_adaptive_render_is_the_uniform_one_in_expectation_spends_its_samples_unevenly_and_repeats_to_the_bit(tiny_cfg):
    """``renders.<preset>.adaptive``: a pixel's samples from an independent pilot. Each object's mean
    luminance agrees with a uniform render's at more samples within their errors (|z| < 4), the map is
    uneven (the sky gets the fewest), ``object_spp`` is the fewest of an object's pixels, and a second
    run gives the same bytes (the pilot is seeded from the config too)."""
    cfg = copy.deepcopy(tiny_cfg)
    name = "fig_3_12_plastics"                 # the cheapest figure: one rgb panel
    preset = cfg["renders"][cfg["renders"]["preset"]]
    uniform = registry.get_artifact(name).compute({**cfg, "renders": {**cfg["renders"], "preview": {**preset, "spp": 32}}}, {})
    preset.update(adaptive={name: 0.05}, adaptive_pilot=8, adaptive_max=16)
    first = registry.get_artifact(name).compute(cfg, {})
    second = registry.get_artifact(name).compute(cfg, {})
    pd.testing.assert_frame_equal(first, second)
    assert np.array_equal(first.attrs[rf.RADIANCE][0], second.attrs[rf.RADIANCE][0])
    z = (first["luminance"] - uniform["luminance"]) / np.hypot(first["luminance_err"], uniform["luminance_err"])
    assert (z.abs() < 4.0).all(), z
    assert first["object_spp"].min() >= 8 and first["object_spp"].max() <= 16 and first["spp"].iloc[0] < 16
    assert first["object_spp"].nunique() > 1


def test_figure_4_9s_panel_titles_give_each_spheres_samples_where_they_differ_from_the_films():
    import pandas as pd

    from brdfs.artifacts.fig_4_9_sampling_efficiency import panel_costs

    rows = pd.DataFrame({"panel": [0] * 4, "object": ["gold s=10", "silver s=4", "copper s=15", "floor"],
                         "spp": 32, "object_spp": [96, 160, 96, 32], "rays_per_pixel": 160.0,
                         "plugin_evaluations_per_pixel": [1.0, 2.0, 3.0, float("nan")], "thesis_minutes": 51.0})
    assert panel_costs(rows) == ["32 spp (spheres 96/160/96), 160 rays/px, 6.0 plugin evals/px; thesis 50 spp, 51 min"]
    uniform = rows.assign(object_spp=32)
    assert panel_costs(uniform)[0].startswith("32 spp, 160 rays/px")


def test_each_presets_clamps_are_the_rules_choice_from_the_measured_noise_and_bias():
    """config.yaml's ``renders.<preset>.clamp`` of Figs. 3.9, 4.11 and 4.16 is what the declared rule
    picks from the committed measurements at that preset's samples (benchmarks/render_clamp_rule.py)."""
    import subprocess
    import sys

    run = subprocess.run([sys.executable, str(REPO_ROOT / "benchmarks" / "render_clamp_rule.py")],
                         capture_output=True, text=True, cwd=REPO_ROOT)
    assert run.returncode == 0 and run.stdout.count(" rule ") == 6, run.stdout + run.stderr
