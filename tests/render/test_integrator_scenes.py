"""Noise figures, scenes and figure plumbing of the Mitsuba renders (metrics.py, scenes.py,
artifacts/_render_figures.py), and the old numpy tracer as an independent oracle of the new path."""
from __future__ import annotations

import numpy as np
import pytest

from brdfs.render.mitsuba import metrics


def test_object_pixels_need_the_same_id_within_two_pixels_and_one_percent_of_the_p99():
    ids = np.zeros((12, 12))
    ids[:, 6:] = 1.0
    ids[0, 11] = 2.0                              # a stray ID near a corner
    y = np.ones((12, 12))
    y[10, 10] = 1e-3                              # dark: below 1 % of the 99th percentile
    mask = metrics.object_pixels(ids, y)
    assert not mask[:, :6].any()                  # background (ID 0) is never an object pixel
    assert not mask[:, 6:8].any() and mask[5, 8]  # columns within 2 px of the ID edge are out
    assert not mask[0:3, 9:].any()                # within 2 px of the stray ID
    assert not mask[10, 10] and mask[9, 9]


def test_relative_standard_error_is_the_std_over_passes_over_root_passes_over_the_mean():
    passes = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0])[:, None, None] * np.ones((8, 2, 2))
    expected = np.std(np.arange(1, 9), ddof=1) / np.sqrt(8) / 4.5
    assert np.allclose(metrics.relative_standard_error(passes), expected, rtol=1e-14)
    with pytest.raises(ValueError, match="1 pass"):
        metrics.relative_standard_error(passes[:1])


def test_a_firefly_exceeds_ten_times_the_median_of_its_five_by_five_neighbourhood():
    y = np.ones((9, 9))
    y[4, 4] = 10.5
    y[1, 1] = 9.5                                 # bright but not a firefly
    mask = np.ones((9, 9), bool)
    found = metrics.fireflies(y, mask)
    assert found[4, 4] and found.sum() == 1
    assert metrics.fireflies(y, np.zeros((9, 9), bool)).sum() == 0    # only object pixels count


def test_a_pass_three_times_its_pixels_median_pass_and_its_neighbourhood_is_a_sparkle():
    """A 3.5x sparkle in one pass counts (the 10x rule of the panel's ``fireflies`` misses it); a 2.5x
    one does not; nor does a steady highlight (every pass 4x its neighbours: so is its own median),
    until one of its passes is 3.5x that median."""
    passes = np.ones((8, 9, 9))
    passes[3, 4, 4] = 3.5                          # sparkle: 3.5 x its own median (1) and its neighbours'
    passes[5, 1, 7] = 2.5                          # too faint
    passes[:, 7, 1] = 4.0                          # a steady highlight, 4 x its neighbours
    mask = np.ones((9, 9), bool)
    found = metrics.sparkles(passes, mask)
    assert found[4, 4] == 1 and found.sum() == 1
    assert metrics.fireflies(passes.mean(axis=0), mask).sum() == 0            # the panel's 10x rule
    passes[:, 7, 1] = [14.0] + [4.0] * 7           # 3.5 x the highlight's own median: a sparkle
    assert metrics.sparkles(passes, mask)[7, 1] == 1
    assert metrics.sparkles(passes, np.zeros((9, 9), bool)).sum() == 0       # only object pixels count


def test_each_object_gets_its_own_p95_and_fireflies_not_the_panels():
    """A large quiet floor beside a small noisy sphere: the panel's p95 is the floor's, the sphere's
    own p95 is its pixels' (as computed directly) and its sparkles are its own."""
    rng = np.random.default_rng(3)
    ids = np.ones((40, 40))
    ids[5:15, 5:15] = 2.0                                        # the sphere: 100 px of 1600
    passes = 1.0 + 0.01 * rng.standard_normal((8, 40, 40))
    passes[:, 5:15, 5:15] = rng.gamma(0.5, 2.0, (8, 10, 10))    # heavy noise, mean 1
    passes[0, 9, 9] = 50.0
    noise = metrics.object_noise(passes, ids)
    mask = metrics.object_pixels(ids, passes.mean(axis=0))
    rse = metrics.relative_standard_error(passes)
    sphere = mask & (ids == 2)
    assert noise[2].object_pixels == sphere.sum() == 36         # 6 x 6: 2 px in from its edge
    assert noise[2].p95_relative_se == np.percentile(rse[sphere], 95.0) > 0.2
    assert noise[1].p95_relative_se < 0.01
    assert metrics.noise_figures(passes, ids).p95_relative_se < 0.01          # the panel's: the floor's
    assert noise[2].fireflies >= 1 and noise[1].fireflies == 0
    assert noise[2].sparkles >= noise[2].fireflies


def test_noise_figures_of_a_noiseless_panel_are_zero_noise_and_every_interior_pixel():
    ids = np.ones((10, 10))
    figures = metrics.noise_figures(np.full((8, 10, 10), 0.3), ids)
    assert figures.p95_relative_se == 0.0 and figures.fireflies == 0 and figures.object_pixels == 100
    assert metrics.object_noise(np.full((8, 10, 10), 0.3), ids) == {1: metrics.ObjectNoise(0.0, 0, 0, 100)}


def test_the_pyramid_is_five_vertices_with_outward_faces():
    from brdfs.render.mitsuba import scenes

    (part,) = scenes.pyramid((0.0, 0.0, 0.0), 1.0, 1.5)
    v = np.asarray(part["vertices"])
    assert v.shape == (5, 3)
    centroid = v.mean(axis=0)
    for a, b, c in part["faces"]:
        normal = np.cross(v[b] - v[a], v[c] - v[a])
        assert normal @ ((v[a] + v[b] + v[c]) / 3 - centroid) > 0


def test_a_panel_is_at_least_the_presets_size_at_its_aspect():
    from brdfs.artifacts import _render_figures as rf

    setup = {"min_width": 640, "min_height": 400}
    for aspect in (1.0, 4 / 3, 1.6, 3.0):
        w, h = rf.panel_size(setup, aspect)
        assert w >= 640 and h >= 400 and abs(w / h - aspect) < 0.01


def test_the_png_shows_the_render_pixels_unscaled(tmp_path):
    import matplotlib.image
    import pandas as pd

    from brdfs.artifacts import _render_figures as rf

    rng = np.random.default_rng(1)
    img = rng.integers(0, 256, (40, 64, 3), dtype=np.uint8)
    df = pd.DataFrame({"x": [0]})
    df.attrs["images"] = [("panel", img)]
    rf.plot_panels(df, tmp_path / "p.png", "title")
    png = (matplotlib.image.imread(tmp_path / "p.png")[..., :3] * 255).round().astype(np.uint8)
    top, left = 2 * rf.TITLE_PX, rf.GAP_PX
    assert np.array_equal(png[top:top + 40, left:left + 64], img)


@pytest.fixture(scope="module")
def mi(mitsuba):
    from brdfs.render.mitsuba import integrator

    integrator.register()
    return mitsuba


def _sphere_on_floor(mi, spp, seed, width=24, height=16):
    from brdfs.render.mitsuba import scenes

    objects = (scenes.SceneObject("floor", scenes.floor(4.0), {"type": "brdfs_lambert"}),
               scenes.SceneObject("ball", scenes.sphere((0.0, 0.0, 1.0), 1.0), {"type": "brdfs_phong_cosmin", "n": 20.0}))
    scene = scenes.Scene(objects, (scenes.Light((-3.0, -4.0, 6.0), 40.0),), sky=0.5)
    camera = scenes.Camera((0.0, -7.0, 2.5), (0.0, 0.0, 0.8), width, height, 34.0)
    return np.asarray(mi.render(scenes.load(scene, camera, {"type": "brdfs_path"}), spp=spp, seed=seed))


def test_renders_are_byte_identical_for_the_same_seed_and_differ_for_another(mi):
    a, b, c = (_sphere_on_floor(mi, 8, seed) for seed in (3, 3, 4))
    assert a.tobytes() == b.tobytes()
    assert a.tobytes() != c.tobytes()


def test_the_id_buffer_names_each_object(mi):
    image = _sphere_on_floor(mi, 4, 0)
    ids = set(np.unique(image[..., 3]))
    assert {1.0, 2.0} <= ids                       # floor and ball both in view, integer where uniform


@pytest.mark.parametrize("sampler", ["independent", "multijitter", "stratified", "ldsampler"])
def test_a_pass_is_split_into_launches_of_counts_the_sampler_renders_exactly(sampler):
    """Mitsuba's stratified samplers round other sample counts up: every launch's count is one the
    sampler takes, no launch exceeds MAX_LANES samples, and the launches add up to the pass's spp."""
    from brdfs.artifacts import _render_figures as rf

    for spp in (1, 2, 13, 105, 555):
        chunks = rf.launches(640, 400, spp, sampler)
        assert sum(chunks) == spp and all(rf.sampler_takes(sampler, c) for c in chunks), (spp, chunks)
        assert max(chunks) * 640 * 400 <= rf.MAX_LANES
    assert not rf.sampler_takes("multijitter", 13) and rf.sampler_takes("multijitter", 12)
    assert not rf.sampler_takes("ldsampler", 8) and rf.sampler_takes("ldsampler", 16)


def test_a_figures_spp_entry_overrides_the_presets_and_must_be_a_multiple_of_passes():
    from brdfs.artifacts import _render_figures as rf

    cfg = {"renders": {"preset": "preview", "variant": "llvm_ad_rgb", "sampler": "multijitter", "caustics": False,
                       "preview": {"min_width": 64, "min_height": 40, "spp": 64, "passes": 8,
                                   "figure_spp": {"fig_2_8_pumping_render": 104}}}}
    setup = rf.settings(cfg)
    assert rf.figure_setup(setup, "fig_2_8_pumping_render")["spp"] == 104
    assert rf.figure_setup(setup, "fig_3_9_metals_new_model")["spp"] == 64
    cfg["renders"]["preview"]["figure_spp"]["fig_2_8_pumping_render"] = 100
    with pytest.raises(ValueError, match="figure_spp.fig_2_8_pumping_render = 100"):
        rf.settings(cfg)


def test_a_per_panel_spp_list_gives_each_panel_its_own_and_needs_one_entry_per_panel():
    from brdfs.artifacts import _render_figures as rf

    cfg = {"renders": {"preset": "preview", "variant": "llvm_ad_rgb", "sampler": "multijitter", "caustics": False,
                       "preview": {"min_width": 64, "min_height": 40, "spp": 64, "passes": 8,
                                   "figure_spp": {"fig_2_8_pumping_render": [64, 32, 48, 8]}}}}
    setup = rf.figure_setup(rf.settings(cfg), "fig_2_8_pumping_render")
    assert [s["spp"] for s in rf.panel_setups(setup, "fig_2_8_pumping_render", 4)] == [64, 32, 48, 8]
    with pytest.raises(ValueError, match=r"figure_spp.fig_2_8_pumping_render = \[64, 32, 48, 8\]: needs one entry per panel, 2"):
        rf.panel_setups(setup, "fig_2_8_pumping_render", 2)
    cfg["renders"]["preview"]["figure_spp"]["fig_2_8_pumping_render"] = [64, 30, 48, 8]
    with pytest.raises(ValueError, match="must be a multiple of passes = 8 \\(each entry\\)"):
        rf.settings(cfg)


def test_a_pixel_whose_samples_hit_two_objects_has_no_object_id_even_where_their_mean_is_an_integer():
    """Half the samples on object 3 and half on object 5 average to 4, another object's ID: the
    variance mean(id²) − mean(id)² tells them apart, down to one sample of N."""
    from brdfs.artifacts import _render_figures as rf

    n = 64
    mean = np.array([4.0, 4.0, 2.0, 0.0, (63 * 2 + 3) / n, 0.5])
    mean_sq = np.array([(9 + 25) / 2, 16.0, 4.0, 0.0, (63 * 4 + 9) / n, 0.5])
    assert rf.pure_ids(mean, mean_sq, n).tolist() == [rf.MIXED_ID, 4.0, 2.0, 0.0, rf.MIXED_ID, rf.MIXED_ID]


def test_a_pixel_inside_overlapping_crop_windows_gets_the_samples_of_each_window_and_one_outside_the_films():
    from brdfs.artifacts import _render_figures as rf

    windows = [(6, 3, 5, 4), (9, 5, 3, 3)]                 # x, y, width, height; overlapping at (9..10, 5..6)
    samples = rf.window_samples((10, 12), windows, 8, 24)
    assert samples[5, 9] == 56 and samples[4, 7] == 32 and samples[0, 0] == 8 and samples[7, 11] == 32
    inside = np.zeros((10, 12), bool)
    inside[3:7, 6:11] = inside[5:8, 9:12] = True
    assert np.all(samples[~inside] == 8)


def test_each_object_but_the_floor_gets_a_crop_window_with_its_margin_and_overlapping_ones_merge():
    from brdfs.artifacts import _render_figures as rf

    ids = np.full((40, 60), 1.0)                           # 1: the floor, everywhere
    ids[10:15, 20:26] = 2.0
    ids[22:30, 40:44] = 3.0
    ids[0, 0] = 4.0                                        # a light sphere: not an object
    labels = {1: "floor", 2: "ball", 3: "tank", 4: "light", 5: "hidden"}
    assert rf.crop_windows(ids, labels, margin=2) == [(18, 8, 10, 9), (38, 20, 8, 12)]
    assert rf.crop_windows(ids, labels, margin=50) == [(0, 0, 60, 40)]      # clipped to the film, merged
    # overlapping windows become their bounding box (no pixel sampled twice), then it may meet a third
    assert rf.merge_windows([(0, 0, 4, 4), (3, 3, 4, 4), (8, 0, 2, 2), (6, 6, 2, 2)]) == [(0, 0, 8, 8), (8, 0, 2, 2)]
    assert rf.merge_windows([(0, 0, 4, 4), (4, 0, 4, 4)]) == [(0, 0, 4, 4), (4, 0, 4, 4)]     # touching: kept
    assert rf.crop_windows(np.ones((4, 4)), {1: "floor"}) == []


def test_each_listed_object_gets_its_own_count_in_its_own_window_and_the_larger_count_where_windows_overlap():
    from brdfs.artifacts import _render_figures as rf

    ids = np.full((40, 60), 1.0)                           # 1: the floor, everywhere
    ids[10:15, 20:26] = 2.0                                # ball: window (18, 8, 10, 9) at margin 2
    ids[14:20, 27:31] = 3.0                                # tank: window (25, 12, 8, 10), overlapping the ball's
    ids[30:34, 50:54] = 4.0                                # cube: not listed, film samples only
    labels = {1: "floor", 2: "ball", 3: "tank", 4: "cube", 5: "hidden"}
    windows = rf.object_windows(ids, labels, {"ball": 3, "tank": 5, "hidden": 9}, margin=2)
    assert windows == [(18, 8, 10, 9, 3), (25, 12, 8, 10, 5)]          # unseen "hidden": no window
    samples = rf.object_window_samples(ids.shape, windows, 2)
    assert samples[8, 18] == 3 and samples[12, 26] == 5 and samples[21, 32] == 5     # the overlap: the larger
    assert samples[31, 51] == 2 and samples[0, 0] == 2 and samples[7, 18] == 2       # the cube, the floor: film
    assert rf.object_window_samples(ids.shape, [(0, 0, 4, 4, 1)], 2)[0, 0] == 2      # never below the film
    assert (samples > 2).sum() == 10 * 9 + 8 * 10 - 3 * 5      # the two windows' pixels, the overlap (3 x 5) once


def _lit_ball(mi, width=24, height=16, sampler="independent"):
    from brdfs.render.mitsuba import scenes

    objects = (scenes.SceneObject("floor", scenes.floor(4.0), {"type": "brdfs_lambert"}),
               scenes.SceneObject("ball", scenes.sphere((0.0, 0.0, 1.0), 1.0), {"type": "brdfs_phong_cosmin", "n": 20.0}))
    return scenes.load(scenes.Scene(objects, (scenes.Light((-3.0, -4.0, 6.0), 40.0),), sky=0.5),
                       scenes.Camera((0.0, -7.0, 2.5), (0.0, 0.0, 0.8), width, height, 34.0), {"type": "brdfs_path"}, sampler)


def test_one_pass_of_a_uniform_sample_map_is_mitsubas_own_render_to_the_bit(mi):
    """The sample-map launches (every pass of every pixel of one count in one wavefront) give a pixel
    the samples ``mi.render`` gives it: the same positions, rays, random sequences and box filter."""
    from brdfs.artifacts import _render_figures as rf

    scene = _lit_ball(mi, sampler="multijitter")
    for count in (1, 6):
        reference = np.asarray(mi.render(scene, spp=count, seed=rf.pass_seed(3, 0)))
        out = np.zeros((1, 16, 24, 3))
        ids, cos_v, _ = rf._render_counts(mi, scene, "multijitter", np.full((16, 24), count), 1, 3, 0, None, out, None)
        assert np.array_equal(out[0], reference[..., :3]) and np.array_equal(ids, reference[..., 3])
        assert np.array_equal(cos_v, reference[..., 4])


def test_a_sample_map_is_the_uniform_render_in_expectation_and_a_pixels_noise_falls_as_one_over_root_its_samples(mi):
    """16 passes of a map of 2 samples per pass (8 on the ball's left half, 4 on its right half) against
    16 passes of 32 spp by ``mi.render``: each pixel's mean agrees with the reference within its noise
    (z over every pixel), and the pass-to-pass standard deviation against the all-2 map's falls as
    sqrt(2 / n) (independent sampler; per-pixel median within 20 %)."""
    from brdfs.artifacts import _render_figures as rf

    scene = _lit_ball(mi)
    passes = 16
    counts = np.full((16, 24), 2)
    counts[3:12, 7:12] = 8
    counts[3:12, 12:17] = 4
    low = np.zeros((passes, 16, 24, 3))
    rf._render_counts(mi, scene, "independent", np.full((16, 24), 2), passes, 1, 0, None, low, None)
    mapped = np.zeros_like(low)
    rf._render_counts(mi, scene, "independent", counts, passes, 1, 0, None, mapped, None)
    reference = np.stack([np.asarray(mi.render(scene, spp=32, seed=rf.pass_seed(2, p)))[..., :3] for p in range(passes)])
    se = np.sqrt(mapped.var(axis=0, ddof=1) / passes + reference.var(axis=0, ddof=1) / passes) + 1e-12
    z = (mapped.mean(axis=0) - reference.mean(axis=0)) / se
    assert abs(z.mean()) < 4.0 / np.sqrt(z.size) * 1.5 and np.mean(np.abs(z) > 3.5) < 0.02
    noisy = low.std(axis=0) > 0
    for n in (8, 4):
        sel = (counts == n)[..., None] & noisy
        ratio = np.median(mapped.std(axis=0)[sel] / low.std(axis=0)[sel])
        assert abs(ratio - np.sqrt(2 / n)) < 0.2 * np.sqrt(2 / n), (n, ratio)


def test_a_figures_crop_spp_reaches_its_panels_and_must_be_a_multiple_of_passes():
    from brdfs.artifacts import _render_figures as rf

    cfg = {"renders": {"preset": "preview", "variant": "llvm_ad_rgb", "sampler": "multijitter", "caustics": False,
                       "preview": {"min_width": 64, "min_height": 40, "spp": 64, "passes": 8,
                                   "crop_spp": {"fig_3_9_metals_new_model": 160}}}}
    setup = rf.settings(cfg)
    assert setup["crop_spp"] == 0
    assert rf.figure_setup(setup, "fig_3_9_metals_new_model")["crop_spp"] == 160
    assert rf.figure_setup(setup, "fig_4_11_anisotropic_metals")["crop_spp"] == 0
    cfg["renders"]["preview"]["crop_spp"]["fig_3_9_metals_new_model"] = 20
    with pytest.raises(ValueError, match="crop_spp.fig_3_9_metals_new_model = 20"):
        rf.settings(cfg)


def test_the_adaptive_ladder_holds_counts_the_sampler_takes_and_a_pixel_gets_the_first_that_reaches_its_target():
    from brdfs.artifacts import _render_figures as rf

    ladder = rf.count_ladder("multijitter", 1, 120, 1.3)
    assert ladder[0] == 1 and ladder[-1] == 120
    assert all(rf.sampler_takes("multijitter", int(n)) for n in ladder)
    assert np.all(ladder[1:-1] >= 1.3 * ladder[:-2])                     # each step at least the ratio
    # relative variance v of one pass of 2 samples, 8 passes, target t: needs v * 2 / (8 t^2) samples per pass
    variance = np.array([[0.0, 8 * 0.05 ** 2 / 2 * 3.5, 1e9]])
    assert rf.pixel_counts(variance, 2, 8, 0.05, ladder).tolist() == [[1, 4, 120]]
    assert rf.pixel_counts(variance * 4, 2, 8, 0.1, ladder).tolist() == [[1, 4, 120]]   # v / t^2 is what counts


def test_the_pilots_relative_variance_is_smoothed_and_dark_pixels_count_against_the_panels_brightness():
    """A single noisy pixel spreads over the 5 x 5 box (the map must not follow the pilot's noise); a pixel
    darker than 1 % of the 99th percentile is measured against that level, not its own mean."""
    from brdfs.artifacts import _render_figures as rf

    rng = np.random.default_rng(1)
    passes = np.ones((8, 20, 20)) + 0.01 * rng.standard_normal((8, 20, 20))
    passes[:, 10, 10] = np.where(np.arange(8) % 2, 1.5, 0.5)             # relative variance 0.286
    out = rf.pilot_relative_variance(passes)
    window = passes[:, 8:13, 8:13]
    assert np.isclose(out[10, 10], (window.var(axis=0, ddof=1) / window.mean(axis=0) ** 2).mean(), rtol=1e-9)
    assert out[10, 10] == pytest.approx(0.286 / 25, rel=0.02) and out[0, 0] < 2e-4
    dark = np.ones((8, 20, 20))
    dark[:, :5, :5] = 1e-6 * np.where(np.arange(8) % 2, 2.0, 0.0)[:, None, None]    # 1e-6 +- 1e-6
    assert rf.pilot_relative_variance(dark)[0, 0] == pytest.approx(8 / 7 * 1e-12 / 0.01 ** 2, rel=1e-6)


def test_a_count_the_sampler_does_not_take_is_rendered_as_counts_it_takes_and_stays_unbiased(mi):
    """Multijitter takes 6 samples per pass, not 7 (``sampler_takes``): a map of 7 renders as 6 + 1 in two
    launches, weighted 6/7 and 1/7, and agrees with ``mi.render`` at 32 spp pixel by pixel within its noise."""
    from brdfs.artifacts import _render_figures as rf

    scene = _lit_ball(mi, sampler="multijitter")
    assert rf.launches(1, 1, 7, "multijitter") == [6, 1]
    passes = 8
    mapped = np.zeros((passes, 16, 24, 3))
    rf._render_counts(mi, scene, "multijitter", np.full((16, 24), 7), passes, 1, 0, None, mapped, None)
    reference = np.stack([np.asarray(mi.render(scene, spp=32, seed=rf.pass_seed(2, p)))[..., :3] for p in range(passes)])
    se = np.sqrt(mapped.var(axis=0, ddof=1) / passes + reference.var(axis=0, ddof=1) / passes) + 1e-12
    z = (mapped.mean(axis=0) - reference.mean(axis=0)) / se
    assert abs(z.mean()) < 4.0 / np.sqrt(z.size) * 1.5 and np.mean(np.abs(z) > 3.5) < 0.02
