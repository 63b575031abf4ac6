"""The path tracer ``brdfs_path`` against closed forms, with the package's plugins (tiny images).

Each test is one of the checks ``make check-mutations`` runs under a deliberate fault
(``workflow/scripts/check_mutations.sh``): the fault's name is in the test's docstring.
"""
from __future__ import annotations

import numpy as np
import pytest

import brdfs
from brdfs.physics.models import MODELS

SPP = 64
PASSES = 8


@pytest.fixture(scope="module")
def mi(mitsuba):
    from brdfs.render.mitsuba import integrator

    integrator.register()
    return mitsuba


def _plugin_models():
    """(plugin name, its model's class, typical parameters) for every Dr.Jit twin of a model."""
    from brdfs.render.mitsuba.variant import use_variant
    from brdfs.render.mitsuba.plugins import PREFIX, plugin_classes

    try:
        use_variant("llvm_ad_rgb")
    except Exception:          # no libllvm19: the fixture skips the tests with the reason
        return []
    out = []
    for name in sorted(plugin_classes()):
        model_name = name[len(PREFIX):]
        if model_name in MODELS:
            out.append((name, model_name, dict(MODELS[model_name].examples["typical"])))
    return out


PLUGIN_MODELS = _plugin_models()


def _isotropic(model, pairs=256, seed=0):
    """f(L, V) = f(turned L, turned V) for turns about N at random pairs (else a(θ_V) depends on φ_V)."""
    rng = np.random.default_rng(seed)
    L, V = (v / np.linalg.norm(v, axis=1, keepdims=True) for v in (rng.normal(size=(pairs, 3)) * [1, 1, 0] + [0, 0, 1.2]
                                                                    for _ in range(2)))
    c, s = np.cos(0.7), np.sin(0.7)
    turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return np.allclose(model(L, V), model(L @ turn.T, V @ turn.T), rtol=1e-9, atol=0.0)


ISOTROPIC_PLUGIN_MODELS = [p for p in PLUGIN_MODELS if _isotropic(brdfs.model(p[1], **p[2]))]


def _ortho(mi, origin, target, half, pixels, up=(0.0, 0.0, 1.0)):
    """An orthographic camera seeing the square of half-size ``half`` around ``target``."""
    T = mi.ScalarTransform4f
    return {"type": "orthographic",
            "to_world": T().look_at(origin=list(origin), target=list(target), up=list(up)) @ T().scale([half, half, 1.0]),
            "film": {"type": "hdrfilm", "width": pixels, "height": pixels, "pixel_format": "rgb",
                     "rfilter": {"type": "box"}},
            "sampler": {"type": "independent"}}


def _passes(mi, scene, spp=SPP, passes=PASSES):
    """(passes, H, W) of the red channel of ``passes`` independent renders of ``spp`` samples a pixel,
    all from one launch: the integrator's ``passes`` AOVs (each sample's radiance in its pass's AOV,
    which the box filter averages over the pixel's spp · passes samples: passes × the AOV is the
    pass; test_the_passes_of_one_launch_are_independent_unbiased_renders_averaging_to_the_film holds
    them independent and unbiased).  ``scene``: a scene dictionary, ``brdfs_path``, box filter."""
    scene = mi.load_dict({**scene, "integrator": {**scene["integrator"], "passes": passes}})
    image = np.asarray(mi.render(scene, spp=spp * passes, seed=17))
    names = scene.integrator().aov_names()
    red = [3 + names.index(f"p{k}_R") for k in range(passes)]     # the film: R, G, B, then the AOVs
    return passes * np.moveaxis(image[..., red], -1, 0)


def _mean_and_error(values):
    """Mean over passes of a per-pass scalar and its standard error."""
    values = np.asarray(values, float)
    return values.mean(), values.std(ddof=1) / np.sqrt(values.size)


def _light(position, radius, radiance):
    return {"type": "sphere", "center": list(position), "radius": radius,
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [radiance] * 3}}}


def _plate(bsdf, half=2.0):
    import mitsuba as mi

    return {"type": "rectangle", "to_world": mi.ScalarTransform4f().scale([half, half, 1.0]), "bsdf": bsdf}


def _direct_radiance(mi, bsdf, L, V, blocker=False, depth=1, distance=40.0, radius=0.4, passes=PASSES, spp=16):
    """Mean radiance of the plate's centre (|x|, |y| ≤ 0.01) seen from V, lit by a sphere of
    ``radius`` at ``distance`` along L, and the irradiance E = L_e π r² cos θ_L / D² that sphere gives
    there (exact while the sphere is above the horizon).  Where the radiance must be exactly 0, two
    ``passes`` are enough (every sample must give 0)."""
    radiance = 50.0
    L, V = np.asarray(L, float) / np.linalg.norm(L), np.asarray(V, float) / np.linalg.norm(V)
    scene = {"type": "scene", "integrator": {"type": "brdfs_path", "max_depth": depth, "hide_emitters": True},
             "sensor": _ortho(mi, 10.0 * V, (0.0, 0.0, 0.0), 0.01, 4,
                              up=(0.0, 1.0, 0.0) if abs(V[1]) < 0.9 else (1.0, 0.0, 0.0)),
             "plate": _plate(bsdf), "light": _light(distance * L, radius, radiance)}
    if blocker:
        scene["blocker"] = {"type": "sphere", "center": list(0.5 * distance * L), "radius": 2.0,
                            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5] * 3}}}
    image = _passes(mi, scene, spp=spp, passes=passes)
    E = radiance * np.pi * radius ** 2 * L[2] / distance ** 2
    return _mean_and_error(image.mean(axis=(1, 2))), E


def test_a_blocker_between_light_and_plate_leaves_the_plate_unlit(mi):
    """Fault ``no_shadow_rays``: without the shadow ray the blocked light still lights the plate."""
    lambert = {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
    L, V = (0.3, 0.2, 1.0), (-0.4, 0.1, 1.0)
    (lit, lit_err), E = _direct_radiance(mi, lambert, L, V)
    (shadowed, _), _ = _direct_radiance(mi, lambert, L, V, blocker=True, passes=2)
    assert abs(lit - 0.8 / np.pi * E) <= 5 * lit_err + 2e-3 * lit
    assert shadowed == 0.0, f"blocked light gives {shadowed} (unblocked {lit})"


def test_a_large_near_light_over_a_lambert_plate_gives_rho_e_over_pi(mi):
    """A sphere light subtending a wide cone (sin α = 2/3): light and cosine samples share the
    work (MIS), so the fault ``uniform_claims_cosine`` (uniform directions weighted as cosine ones)
    biases the plate's radiance ρ E / π."""
    lambert = {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
    L, V = (0.2, 0.1, 1.0), (-1.0, 0.1, 0.6)          # V passes the light at 1.4 > its radius
    (got, err), E = _direct_radiance(mi, lambert, L, V, distance=1.5, radius=1.0)
    expected = 0.8 / np.pi * E
    assert abs(got - expected) <= 5 * err + 1e-3 * expected, (got, expected, err)


def test_the_lobe_mis_density_leaves_a_wide_light_on_a_patch_plate_unbiased(mi):
    """A wide sphere light (sin α = 2/3) over an exponential patch plate, s = 4: light and BSDF
    samples share the work, so MIS weights that did not sum to one would bias it.  Normal sampling
    with the lobe density in the MIS weights (``mis_density = "lobe"``) agrees with the exact density
    and with cosine sampling (three estimators, one expectation).  Fault ``mis_weights_apart``
    (next-event estimation weighted by the exact density, ``bs.pdf`` by the lobe's) biases it.  256
    spp a pass: a pass's relative standard deviation is 4.5 % at 16 spp (measured over 64 passes), so
    eight passes of 16 gave a 1.6 % standard error, and the 1 % below held only by a low estimate."""
    L, V = (0.2, 0.1, 1.0), (-1.0, 0.1, 0.6)
    plate = {"type": "brdfs_patch_exponential", "s": 4.0}
    got = {name: _direct_radiance(mi, {**plate, **extra}, L, V, distance=1.5, radius=1.0, spp=256)[0]
           for name, extra in (("lobe", {"strategy": "normal", "mis_density": "lobe"}),
                               ("exact", {"strategy": "normal"}), ("cosine", {"strategy": "cosine"}))}
    (lobe, lobe_err) = got["lobe"]
    for name in ("exact", "cosine"):
        value, err = got[name]
        assert abs(lobe - value) <= 5 * np.hypot(lobe_err, err), (name, lobe, value)
    assert lobe_err < 0.01 * lobe


@pytest.mark.parametrize("plugin, model_name, params", PLUGIN_MODELS, ids=[p[0] for p in PLUGIN_MODELS])
def test_a_far_spherical_light_gives_f_cos_e_for_every_plugin(mi, plugin, model_name, params):
    """One bounce from a far sphere of irradiance E: radiance = f(L, V) E (f cos θ_L E_⊥). L and V are
    off the plane of incidence of the tangent, so ``frame_rotated_90`` moves an anisotropic f."""
    model = brdfs.model(model_name, **params)
    L = np.array([0.35, 0.25, 1.0]) / np.linalg.norm([0.35, 0.25, 1.0])
    V = np.array([-0.5, 0.1, 1.0]) / np.linalg.norm([-0.5, 0.1, 1.0])
    (got, err), E = _direct_radiance(mi, {"type": plugin, **params}, L, V)
    expected = float(model(L, V)) * E
    assert abs(got - expected) <= 5 * err + 3e-3 * expected, (got, expected, err)


def _mean_albedo(model, nodes=24):
    """ā = ∫₀¹ a(θ(μ)) 2μ dμ (μ = cos θ_V) by Gauss–Legendre, with its quadrature error bound."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    mu = 0.5 * (x + 1.0)
    albedo = brdfs.albedo(model, np.degrees(np.arccos(mu)), rtol=1e-8)
    return float(np.sum(0.5 * w * albedo.value * 2 * mu)), float(np.sum(0.5 * w * albedo.error * 2 * mu))


@pytest.mark.parametrize("plugin, model_name, params", ISOTROPIC_PLUGIN_MODELS,
                         ids=[p[0] for p in ISOTROPIC_PLUGIN_MODELS])
def test_a_sphere_under_a_constant_sky_returns_sky_times_its_mean_albedo_for_every_plugin(mi, plugin, model_name, params):
    """White furnace with the plugins' own (glossy) samplers: a lone sphere of radius r under a
    constant sky S, seen by an orthographic camera, reflects S a(θ_V) at each point, so the image
    integral is S ā π r² (eq. 3.32; ā = 2∫ a(θ) cos θ sin θ dθ; isotropic models: a anisotropic
    one's a depends on φ_V). Faults ``pdf_scale`` and
    ``uniform_claims_cosine`` bias it."""
    model = brdfs.model(model_name, **params)
    sky, half = 1.0, 1.05
    scene = {"type": "scene", "integrator": {"type": "brdfs_path", "hide_emitters": True},
             "sensor": _ortho(mi, (0.0, -5.0, 0.0), (0.0, 0.0, 0.0), half, 12),
             "sphere": {"type": "sphere", "radius": 1.0, "bsdf": {"type": plugin, **params}},
             "sky": {"type": "constant", "radiance": {"type": "rgb", "value": [sky] * 3}}}
    image = _passes(mi, scene)
    got, err = _mean_and_error(image.mean(axis=(1, 2)) * (2 * half) ** 2 / np.pi)
    expected, quad_err = _mean_albedo(model)
    assert err < 0.01 * expected, (err, expected)      # the passes' spread (held: a broken split inflates it)
    assert abs(got - sky * expected) <= 5 * err + quad_err + 1e-4, (got, expected, err)


def test_inside_a_glowing_diffuse_sphere_the_radiance_is_the_geometric_series(mi):
    """Multi-bounce: inside a closed sphere whose wall emits L_e and reflects ρ (Lambert), every
    direction sees L_e (1 + ρ + ρ² + ...) = L_e / (1 − ρ). Faults ``depth3`` (L_e (1 + ρ + ρ²)),
    ``nee_first_vertex`` (MIS weights that assume a light sample that was not taken) and
    ``uniform_claims_cosine`` bias it."""
    rho, emitted = 0.6, 1.0
    scene = {
        "type": "scene", "integrator": {"type": "brdfs_path"},
        "sensor": {"type": "perspective", "fov": 60,
                   "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 0], target=[1, 0.3, 0.2], up=[0, 0, 1]),
                   "film": {"type": "hdrfilm", "width": 8, "height": 8, "pixel_format": "rgb", "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent"}},
        "wall": {"type": "sphere", "radius": 1.0, "flip_normals": True,
                 "bsdf": {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [rho] * 3}},
                 "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [emitted] * 3}}}}
    image = _passes(mi, scene, spp=32)
    got, err = _mean_and_error(image.mean(axis=(1, 2)))
    expected = emitted / (1.0 - rho)
    assert err < 0.01 * expected
    assert abs(got - expected) <= 5 * err, (got, expected, err)


def test_the_passes_of_one_launch_are_independent_unbiased_renders_averaging_to_the_film(mi):
    """``passes = P``: each sample's radiance goes to the AOVs of its pass (the film averages them
    over the pixel's spp samples, so a pass is P × its AOV); inside the glowing sphere every pass
    alone covers every pixel (each sample sees L ≥ L_e) and is L_e / (1 − ρ) within 5 standard
    errors of the pass-to-pass spread, the passes differ (independent streams) and their mean is the
    film's radiance."""
    rho, emitted, pixels = 0.6, 1.0, 8
    scene = mi.load_dict({
        "type": "scene", "integrator": {"type": "brdfs_path", "passes": PASSES},
        "sensor": {"type": "perspective", "fov": 60,
                   "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 0], target=[1, 0.3, 0.2], up=[0, 0, 1]),
                   "film": {"type": "hdrfilm", "width": pixels, "height": pixels, "pixel_format": "rgb",
                            "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent"}},
        "wall": {"type": "sphere", "radius": 1.0, "flip_normals": True,
                 "bsdf": {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [rho] * 3}},
                 "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [emitted] * 3}}}})
    image = np.asarray(mi.render(scene, spp=32 * PASSES, seed=3))
    per_pass = PASSES * np.moveaxis(image[..., 5:5 + 3 * PASSES].reshape(pixels, pixels, PASSES, 3), 2, 0)
    got, err = _mean_and_error(per_pass[..., 0].mean(axis=(1, 2)))
    expected = emitted / (1.0 - rho)
    assert np.all(per_pass >= emitted * (1 - 1e-5))          # every pass has samples in every pixel
    assert np.allclose(per_pass.mean(axis=0), image[..., :3], rtol=1e-5, atol=1e-6)
    pass_means = per_pass[..., 0].mean(axis=(1, 2))
    assert np.all(np.abs(pass_means - expected) <= 5 * err * np.sqrt(PASSES)), pass_means
    assert 0 < err < 0.01 * expected and abs(got - expected) <= 5 * err, (got, expected, err)


def _about_n(degrees):
    """The turn by ``degrees`` about N = z (counter-clockwise seen from above: x toward y)."""
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_an_elliptical_patch_highlight_turns_the_right_way_with_the_tangent(mi):
    """Anisotropy, ``patch_elliptical`` at B/A < 1 with its major axis u at +30° from the tangent
    x = dp/du toward y = N × x: the plugin's direct lighting follows the model where (L + V)_P lies
    along u (lit), along u mirrored to −30° (dark: fault ``tangent_flipped``, the frame's y
    reversed, puts the highlight there) and along u turned 90° (dark: fault ``frame_rotated_90``)."""
    params = {"b": 0.3, "ratio": 0.4, "u_angle_deg": 30.0}
    model = brdfs.model("patch_elliptical", **params)
    L = np.array([0.4, 0.0, 1.0]) / np.linalg.norm([0.4, 0.0, 1.0])
    V = np.array([-L[0] + 0.55, 0.0, L[2]]) / np.linalg.norm([-L[0] + 0.55, 0.0, L[2]])   # (L + V)_P along x
    for angle, lit in ((30.0, True), (-30.0, False), (120.0, False)):
        l, v = _about_n(angle) @ L, _about_n(angle) @ V
        (got, err), E = _direct_radiance(mi, {"type": "brdfs_patch_elliptical", **params}, l, v,
                                         passes=PASSES if lit else 2)
        expected = float(model(l, v)) * E
        assert (expected > 0) == lit, (angle, expected)
        assert abs(got - expected) <= 5 * err + 3e-3 * expected, (angle, got, expected, err)
        assert lit or got == 0.0, (angle, got)


GOLD_AT_555NM = (0.35, 2.7)           # n, k of a gold-like metal (one value for all three channels)


def _metal_plugin(n):
    eta, k = GOLD_AT_555NM
    return {"type": "brdfs_phong_cosmin", "n": n, "eta": {"type": "rgb", "value": [eta] * 3},
            "k": {"type": "rgb", "value": [k] * 3}}


def test_a_metal_sphere_under_a_constant_sky_returns_sky_times_its_fresnel_reduced_mean_albedo(mi):
    """White furnace with Fresnel (eq. 3.29, F at Θ_min): the image integral is S ā π r² with ā
    of the metal model, below the F = 1 model's ā."""
    from brdfs.physics.models.metal import PhongCosminMetal

    n, half = 20.0, 1.05
    eta, k = GOLD_AT_555NM
    scene = {"type": "scene", "integrator": {"type": "brdfs_path", "hide_emitters": True},
             "sensor": _ortho(mi, (0.0, -5.0, 0.0), (0.0, 0.0, 0.0), half, 12),
             "sphere": {"type": "sphere", "radius": 1.0, "bsdf": _metal_plugin(n)},
             "sky": {"type": "constant", "radiance": {"type": "rgb", "value": [1.0] * 3}}}
    got, err = _mean_and_error(_passes(mi, scene).mean(axis=(1, 2)) * (2 * half) ** 2 / np.pi)
    expected, quad_err = _mean_albedo(PhongCosminMetal(n, ior_re=eta, ior_im=k))
    plain, _ = _mean_albedo(brdfs.model("phong_cosmin", n=n))
    assert expected < 0.9 * plain
    assert err < 0.01 * expected, (err, expected)
    assert abs(got - expected) <= 5 * err + quad_err + 1e-4, (got, expected, err)


#: Plates of one render, one per angle a model may read its Fresnel factor at (Θ_min, L·H, θ').
FRESNEL_PLATES = ({"type": "brdfs_phong_cosmin", "n": 4.0}, {"type": "brdfs_ggx", "alpha": 0.3},
                  {"type": "brdfs_patch_exponential", "s": 4.0})


def test_far_light_on_dielectric_coated_plates_gives_f_times_fresnel_at_each_models_angle_times_e(mi):
    """Direct lighting of plates with eta = 1.5, k = 0 (F from 0.04 to 1), with θ_L = 70° the larger
    angle and θ_V = 20°: radiance = f(L, V) F(the model's angle) E, the angle being Θ_min = θ_V
    (phong_cosmin, eq. 3.29), L·H (ggx) and θ' (patch_exponential, eq. 4.53).  F at θ_L would be
    about four times larger on each plate (fault ``fresnel_at_theta_l``).  The three plates lie side
    by side across the light's plane, in one orthographic view (one render; a square film, whose
    columns span 0.02 along x)."""
    from brdfs.physics.fresnel import unpolarised_reflectance

    eta, radiance, radius, distance, half = 1.5, 50.0, 0.4, 40.0, 0.1
    L = np.array([np.sin(np.radians(70.0)), 0.0, np.cos(np.radians(70.0))])
    V = np.array([-np.sin(np.radians(20.0)), 0.0, np.cos(np.radians(20.0))])
    T = mi.ScalarTransform4f
    rows, count = 5, len(FRESNEL_PLATES)
    centres = [2.0 * half * (k - (count - 1) / 2) for k in range(count)]        # y of each plate
    scene = {"type": "scene", "integrator": {"type": "brdfs_path", "max_depth": 1, "hide_emitters": True},
             "sensor": {"type": "orthographic",
                        "to_world": T().look_at(origin=list(10.0 * V), target=[0, 0, 0], up=[0, 1, 0])
                        @ T().scale([0.01, half * count, 1.0]),
                        "film": {"type": "hdrfilm", "width": rows * count, "height": rows * count, "pixel_format": "rgb",
                                 "rfilter": {"type": "box"}},
                        "sampler": {"type": "independent"}},
             "light": _light(distance * L, radius, radiance)}
    for k, (plugin, y) in enumerate(zip(FRESNEL_PLATES, centres)):
        scene[f"plate{k}"] = {"type": "rectangle", "to_world": T().translate([0.0, y, 0.0]) @ T().scale(0.8 * half),
                              "bsdf": {**plugin, "eta": eta, "k": 0.0}}
    image = _passes(mi, scene, spp=16)
    for k, (plugin, y) in enumerate(zip(FRESNEL_PLATES, centres)):
        band = image[:, (count - 1 - k) * rows + 1:(count - k) * rows - 1]      # the film's rows run down y
        got, err = _mean_and_error(band.mean(axis=(1, 2)))
        light = distance * L - [0.0, y, 0.0]
        l = light / np.linalg.norm(light)
        E = radiance * np.pi * radius ** 2 * l[2] / np.linalg.norm(light) ** 2
        model = brdfs.model(plugin["type"].removeprefix("brdfs_"), **{p: v for p, v in plugin.items() if p != "type"})
        at_model_angle = unpolarised_reflectance(model.fresnel_cosine(l, V), eta)
        expected = float(model(l, V) * at_model_angle) * E
        assert unpolarised_reflectance(l[2], eta) > 3 * at_model_angle
        assert abs(got - expected) <= 5 * err + 3e-3 * expected, (plugin["type"], got, expected, err)


def test_every_light_is_sampled_at_every_vertex_so_a_blocked_light_leaves_the_others_lit(mi):
    """Next-event estimation takes one sample of every light at every vertex (no random choice of
    one): with two far sphere lights and a blocker in front of the first, the plate shows exactly
    the second light's ρ E₂ / π, with no noise from a light choice."""
    lambert = {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
    radiance, radius, distance = 50.0, 0.4, 40.0
    first, second = (np.array(d) / np.linalg.norm(d) for d in ((0.3, 0.2, 1.0), (-0.5, 0.3, 1.0)))
    V = np.array([0.1, -0.4, 1.0]) / np.linalg.norm([0.1, -0.4, 1.0])
    scene = {"type": "scene", "integrator": {"type": "brdfs_path", "max_depth": 1, "hide_emitters": True},
             "sensor": _ortho(mi, 10.0 * V, (0.0, 0.0, 0.0), 0.01, 4),
             "plate": _plate(lambert), "first": _light(distance * first, radius, radiance),
             "second": _light(distance * second, radius, radiance),
             "blocker": {"type": "sphere", "center": list(0.5 * distance * first), "radius": 2.0,
                         "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5] * 3}}}}
    image = _passes(mi, scene, spp=16, passes=PASSES)
    got, err = _mean_and_error(image.mean(axis=(1, 2)))
    expected = 0.8 / np.pi * radiance * np.pi * radius ** 2 * second[2] / distance ** 2
    assert abs(got - expected) <= 5 * err + 2e-3 * expected, (got, expected, err)
    assert np.ptp(image) <= 0.02 * expected, np.ptp(image)       # no light-choice noise


def _caustic_scene(mi, caustics: bool):
    """A small Lambert plate (z = 0) that only a glossy metal mirror above it lights: a black ball
    hides the low light from the plate, the mirror (phong_cosmin, n = 20, at z = 2, facing down)
    reflects it onto the plate (a scene dictionary)."""
    return {**_caustic_scene_dict(mi), "integrator": {"type": "brdfs_path", "caustics": caustics, "hide_emitters": True}}


def _caustic_scene_dict(mi):
    """:func:`_caustic_scene`'s scene dictionary (its integrator to be set)."""
    lambert = {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
    black = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0] * 3}}
    T = mi.ScalarTransform4f
    mirror = T().translate([0.0, 0.0, 2.0]) @ T().rotate([1, 0, 0], 180) @ T().scale([3.0, 3.0, 1.0])
    return {
        "type": "scene",
        "sensor": _ortho(mi, (0.0, 0.0, 0.5), (0.0, 0.0, 0.0), 0.2, 4, up=(0.0, 1.0, 0.0)),
        "plate": _plate(lambert, half=0.25),
        "mirror": {"type": "rectangle", "to_world": mirror, "bsdf": {"type": "brdfs_phong_cosmin", "n": 20.0}},
        "light": {**_light((1.5, 0.0, 0.5), 0.15, 500.0), "bsdf": black},
        "blocker": {"type": "sphere", "center": [0.9, 0.0, 0.3], "radius": 0.25, "bsdf": black}}


def test_without_caustics_a_plate_lit_only_through_a_metal_mirror_is_black(mi):
    """``caustics = False`` drops the paths diffuse → glossy metal → light (the stated treatment of
    the caustics): the plate that only the mirror's reflection of the light reaches is black, and
    lit when caustics are on."""
    lit = _passes(mi, _caustic_scene(mi, True), spp=64, passes=PASSES)
    dark = _passes(mi, _caustic_scene(mi, False), spp=32, passes=2)            # must be exactly 0
    assert lit.mean() > 5 * lit.mean(axis=(1, 2)).std(ddof=1) / np.sqrt(PASSES) > 0, lit.mean()
    assert dark.max() == 0.0, dark.max()


def _colour_group_scene(mi, groups, bsdf_of):
    """A metal sphere on a gray floor under a sky and a spherical light, with depth 4 and no Russian
    roulette (so that a path does not depend on its colour); ``bsdf_of(groups)`` its material."""
    T = mi.ScalarTransform4f
    return mi.load_dict({
        "type": "scene",
        "integrator": {"type": "brdfs_path", "max_depth": 4, "rr_depth": 100, "colour_groups": len(groups)},
        "sensor": {"type": "perspective", "fov": 40, "to_world": T().look_at([0, -4, 2], [0, 0, 0], [0, 0, 1]),
                   "film": {"type": "hdrfilm", "width": 24, "height": 16, "pixel_format": "rgb"},
                   "sampler": {"type": "independent", "sample_count": 8}},
        "sky": {"type": "constant", "radiance": 1.0},
        "light": _light((2.0, -2.0, 3.0), 0.1, 500.0),
        "sphere": {"type": "sphere", "radius": 1.0, "bsdf": bsdf_of(groups)},
        "floor": {"type": "rectangle", "to_world": T().translate([0, 0, -1]).scale(10),
                  "bsdf": {"type": "diffuse", "reflectance": 0.5}}})


@pytest.mark.parametrize("material", [{"model": "phong_cosmin", "n": 20.0},
                                      {"model": "patch_exponential", "s": 8.0, "strategy": "normal", "mis_density": "lobe"}])
def test_each_colour_group_of_a_spectral_path_is_the_render_of_that_group_alone(mi, material):
    """A spectral panel's eight wavelengths ride one path as three colour groups (group g's
    throughput is group 0's times f_g / f_0 at every vertex): with the same seed and no Russian
    roulette, every group's image equals, to float rounding, the render of that group's metal alone."""
    from brdfs.artifacts import _render_figures as rf
    from brdfs.render.mitsuba.spectral import WAVELENGTH_PASSES as groups

    def metal(chosen):
        return rf.bsdf({**material, "metal": "copper"}, chosen)
    together = rf.panel_channels(np.asarray(mi.render(_colour_group_scene(mi, groups, metal), seed=3)), groups)
    for g, group in enumerate(groups):
        alone = rf.panel_channels(np.asarray(mi.render(_colour_group_scene(mi, groups[g:g + 1], metal), seed=3)),
                                  groups[g:g + 1])
        channels = list(dict.fromkeys(group))
        assert alone[..., channels].max() > 1.0                  # lit, and the groups differ in colour
        assert np.allclose(together[..., channels], alone[..., channels], rtol=2e-6, atol=1e-6), g
    assert not np.allclose(together[..., 0], together[..., 6], rtol=0.05)


def _clamp_scene(mi, caustics_plate: bool, clamp: float):
    """The caustic scene (a plate lit through a metal mirror) or a plate lit directly by a near light,
    rendered by ``brdfs_path`` with ``clamp``."""
    if caustics_plate:
        scene = mi.load_dict({**_caustic_scene_dict(mi), "integrator": {"type": "brdfs_path", "hide_emitters": True,
                                                                         "clamp": clamp}})
    else:
        lambert = {"type": "brdfs_lambert", "reflectance": {"type": "rgb", "value": [0.8] * 3}}
        scene = mi.load_dict({"type": "scene", "integrator": {"type": "brdfs_path", "hide_emitters": True, "clamp": clamp},
                              "sensor": _ortho(mi, (0.0, 0.0, 5.0), (0.0, 0.0, 0.0), 0.2, 4, up=(0.0, 1.0, 0.0)),
                              "plate": _plate(lambert), "light": _light((0.3, 0.2, 1.5), 0.5, 500.0)})
    return [np.asarray(mi.render(scene, spp=16, seed=5 + k)) for k in range(4)]


def test_the_clamp_keeps_what_it_takes_in_its_aov_and_never_touches_direct_light(mi):
    """``clamp`` (the stated caustic treatment, issue 42): with the same seeds the clamped image plus
    the light the clamp took (AOVs ``k0_*``) is the unclamped image to float precision, the clamp
    bites where light arrives indirectly (a plate lit only through a mirror), and a plate lit only
    directly is untouched by even a tiny clamp (nothing taken, the same image)."""
    free = _clamp_scene(mi, True, 0.0)
    clamped = _clamp_scene(mi, True, 0.5)
    for image, unclamped in zip(clamped, free):
        kept, taken = image[..., :3], image[..., 5:8]
        assert np.allclose(kept + taken, unclamped[..., :3], rtol=1e-5, atol=1e-6)
    taken = np.mean([image[..., 5:8].mean() for image in clamped])
    assert taken > 0.05 * np.mean([image[..., :3].mean() for image in free]), taken
    direct_free, direct_clamped = _clamp_scene(mi, False, 0.0), _clamp_scene(mi, False, 1e-3)
    for image, unclamped in zip(direct_clamped, direct_free):
        assert image[..., :3].max() > 1e-3 and np.array_equal(image[..., :3], unclamped[..., :3])
        assert not image[..., 5:8].any()
