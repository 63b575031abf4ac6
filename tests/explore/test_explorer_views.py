"""The explorer's views are the package's numbers: the albedo curve is brdfs.albedo's with honest error
bounds, the lobe peaks where the model does, the sphere's pixels are the lighting formula's, the slice
is f in Rusinkiewicz's coordinates; the controls come from each model's declarations."""
from __future__ import annotations

import math
import zlib

import numpy as np
import pytest

import brdfs
from brdfs.explore import views
from brdfs.explore.views import BadRequest
from brdfs.physics.models import MODELS


def decode_png(data: bytes) -> np.ndarray:
    """The (h, w, 3) array of an unfiltered 8-bit RGB PNG as views.png writes it."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    w, h = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    start = data.index(b"IDAT") + 4
    length = int.from_bytes(data[start - 8:start - 4], "big")
    raw = np.frombuffer(zlib.decompress(data[start:start + length]), np.uint8).reshape(h, 1 + 3 * w)
    assert not raw[:, 0].any()
    return raw[:, 1:].reshape(h, w, 3)


def test_png_round_trips_an_image():
    rgb = np.random.default_rng(1).integers(0, 256, (7, 5, 3), dtype=np.uint8)
    assert np.array_equal(decode_png(views.png(rgb)), rgb)


@pytest.mark.parametrize("name", list(MODELS))
def test_every_declared_parameter_has_a_control_inside_its_range_starting_at_a_valid_value(name):
    entry = {m["name"]: m for m in views.model_catalogue(MODELS)}[name]
    cls = MODELS[name]
    assert [p["name"] for p in entry["params"]] == list(cls.param_ranges)
    assert [c["name"] for c in entry["choices"]] == list(cls.param_choices)
    for p in entry["params"]:
        interval = cls.param_ranges[p["name"]]
        lo, hi = p["slider"]
        assert lo < hi and interval.lo <= lo and hi <= interval.hi
        assert p["log"] == (lo > 0 and hi / lo >= 100)
        if p["default"] is not None:
            assert interval.contains(p["default"])
    for c in entry["choices"]:
        assert c["default"] in c["values"]
    # the page's defaults build the model
    brdfs.model(name, **views.model_arguments(MODELS, name, {}))


def test_slider_is_logarithmic_where_the_range_spans_decades_and_linear_otherwise():
    assert views.slider_span((0.0, math.inf, False, False), 20.0, [10000.0]) == (0.2, 100000.0, True)
    assert views.slider_span((0.0, 1.0, False, False), 0.5) == (0.0, 1.0, False)
    assert views.slider_span((0.0, 2.0, True, False), 0.5) == (0.0, 2.0, False)


@pytest.mark.parametrize("values, words", [
    ({"n": "-3"}, ["n=-3", "outside its range [0, 100000]"]),
    ({"n": "abc"}, ["n='abc'", "not a number"]),
    ({"n": "nan"}, ["n='nan'", "must be finite"]),
    ({"nope": "1"}, ["'nope'", "not a parameter", "n, C"]),
])
def test_a_bad_parameter_is_refused_in_one_line_naming_it(values, words):
    with pytest.raises(BadRequest) as err:
        views.model_arguments(MODELS, "phong", values)
    assert all(w in str(err.value) for w in words) and "\n" not in str(err.value)


def test_a_bad_choice_and_an_unknown_model_are_refused_naming_them():
    with pytest.raises(BadRequest, match="G='bogus': choose one of torrance_sparrow, smith, none"):
        views.model_arguments(MODELS, "cook_torrance", {"G": "bogus"})
    with pytest.raises(BadRequest, match="model='os.system': not a registered model"):
        views.model_arguments(MODELS, "os.system", {})


def test_albedo_curve_is_brdfs_albedo_with_honest_bounds_at_91_angles():
    model = brdfs.model("ggx", alpha=0.3)
    curve = views.albedo_curve(model)
    assert len(curve["theta"]) == 91 and curve["theta"][0] == 0 and curve["theta"][-1] == 90
    truth = brdfs.albedo(model, np.array(curve["theta"]), rtol=1e-12).value
    value, error = np.array(curve["value"]), np.array(curve["error"])
    assert np.all(np.abs(value - truth) <= error) and np.all(error <= 1e-6 * value + 1e-14)
    assert curve["counts"] == {"converged": 91}


def test_albedo_curve_of_a_model_diverging_at_grazing_says_so_at_90_degrees():
    curve = views.albedo_curve(brdfs.model("ward", m=0.1), n=10)
    assert curve["value"][-1] is None and curve["status"][-1] == "diverged"
    assert all(v is not None for v in curve["value"][:-1]) and curve["counts"]["diverged"] == 1


def test_lobe_of_phong_peaks_in_the_mirror_direction_and_is_symmetric_at_normal_incidence():
    for theta_l in (0.0, 30.0, 70.0):
        lobe = views.lobe(brdfs.model("phong", n=200), theta_l, n=361)
        assert lobe["theta_v"][int(np.argmax(lobe["f"]))] == pytest.approx(theta_l, abs=0.5)
        if theta_l:                                  # the light's side (θ_V < −5°) is dark
            assert max(v for v, t in zip(lobe["f"], lobe["theta_v"]) if t < -5) < 1e-6 * max(lobe["f"])
        else:
            assert lobe["f"] == pytest.approx(lobe["f"][::-1], rel=1e-12)


def test_sphere_pixels_are_the_light_by_evaluation_plus_the_sky_through_the_albedo():
    # Oren-Nayar with sigma = 0 is Lambert: radiance = E rho/pi cos(theta_L local) + S rho
    model = brdfs.model("oren_nayar", rho=0.6, sigma=0.0)
    curve = views.albedo_curve(model, n=19)
    size, theta_l = 64, 40.0
    rgb = decode_png(views.sphere(model, curve, theta_l, size))
    c = (np.arange(size) + 0.5) / size * 2 - 1
    for i, j in [(32, 32), (20, 10), (40, 50), (5, 30)]:
        x, y = c[j], -c[i]
        n = np.array([x, y, math.sqrt(1 - x * x - y * y)])
        light = np.array([-math.sin(math.radians(theta_l)), 0, math.cos(math.radians(theta_l))])
        radiance = views.LIGHT_IRRADIANCE * 0.6 / math.pi * max(n @ light, 0) + views.SKY_RADIANCE * 0.6
        expected = views._srgb(np.array(min(radiance, 1.0)))
        assert abs(int(rgb[i, j, 0]) - int(expected)) <= 1, (i, j)
    assert tuple(rgb[0, 0]) == (40, 44, 52)          # outside the sphere: the background


def test_half_difference_directions_are_rusinkiewiczs_at_phi_d_90():
    theta_h, theta_d, L, V = views.half_diff_directions(16)
    H = (L + V) / np.linalg.norm(L + V, axis=-1, keepdims=True)
    assert np.allclose(H, np.stack([np.sin(theta_h), 0 * theta_h, np.cos(theta_h)], -1))
    assert np.allclose(np.sum(L * H, -1), np.cos(theta_d))
    assert np.allclose(L[..., 1], np.sin(theta_d)) and np.allclose(np.linalg.norm(L, axis=-1), 1)
    assert theta_d[0, 0] > theta_d[-1, 0] and theta_h[0, 0] < theta_h[0, -1]   # θ_d up, θ_h right


def test_half_difference_slice_of_blinn_is_brightest_at_theta_h_zero():
    rgb = decode_png(views.half_diff_slice(brdfs.model("blinn", n=50), size=32))
    brightness = rgb.astype(int).sum(-1)
    assert np.all(np.argmax(brightness, axis=1)[4:-4] == 0)   # every θ_d row peaks in the θ_h = 0 column


def test_3d_lobe_in_the_plane_of_incidence_is_the_polar_lobe():
    model = brdfs.model("blinn", n=30)
    grid = views.lobe_3d(model, 40.0, n_theta=10, n_phi=4)        # φ_V = 0 (mirror side) and 180° (light side)
    polar = views.lobe(model, 40.0, n=181)                        # θ_V every degree, −90..90
    at = {round(t): v for t, v in zip(polar["theta_v"], polar["fcos"])}
    for i, t in enumerate(grid["theta_v"]):
        if float(t).is_integer():
            tiny = 1e-12 * max(polar["fcos"])            # cos(±90°) rounds to 0 or to 6e-17
            assert grid["fcos"][i][0] == pytest.approx(at[round(t)], rel=1e-12, abs=tiny)
            assert grid["fcos"][i][2] == pytest.approx(at[-round(t)], rel=1e-12, abs=tiny)
