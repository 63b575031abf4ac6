"""The BRDF protocol: a model defined outside the package works through the public API alone."""
from dataclasses import dataclass

import numpy as np
import pytest
import yaml

from brdfs import albedo, model
from brdfs.numerics.grazing import asymptotic_law
from brdfs.physics.geometry import n_dot_h, r_dot_v
from brdfs.physics.lobes import HALF, MIRROR, PowerCosine
from brdfs.physics.models import MODELS, BRDF, register
from brdfs.physics import sampling
from brdfs.physics.models.base import Interval, positive_power
from brdfs.pipeline.config import CONFIG_YAML, ConfigError, check_config

ANGLES = np.linspace(0.0, 89.0, 10)


@dataclass(frozen=True)
class Lambert(BRDF):
    """f = ρ/π, defined here only: the package knows nothing of it."""

    rho: float = 1.0
    name = "lambert_in_a_test"

    def _eval(self, L, V, nl, nv):
        return np.full(np.broadcast_shapes(nl.shape, nv.shape), self.rho / np.pi)

    @property
    def lobe(self):
        return PowerCosine(0.0, HALF)


def _cos_relative_azimuth(L, V, where_undefined):
    """cos(φ_V − φ_L), with φ_L = 0 at normal incidence (the integrators' convention, L in the plane
    φ = 0): rotation-invariant about N, so the model is isotropic wherever a renderer puts its frame."""
    L, V = np.broadcast_arrays(L, V)
    lx, ly = L[..., 0], L[..., 1]
    rho_l = np.hypot(lx, ly)
    lx, ly = np.where(rho_l > 0, lx / np.where(rho_l > 0, rho_l, 1.0), 1.0), np.where(rho_l > 0, ly / np.where(rho_l > 0, rho_l, 1.0), 0.0)
    rho_v = np.hypot(V[..., 0], V[..., 1])
    return np.where(rho_v > 0, (lx * V[..., 0] + ly * V[..., 1]) / np.where(rho_v > 0, rho_v, 1.0), where_undefined)


@dataclass(frozen=True)
class KinkedLobe(BRDF):
    """f = c (R·V)ⁿ⁺ / max(N·L, N·V) · (1 + ½ max(0, cos φ_V − cos φ₀)), c = (n+2)/2π, defined here only:
    the new model's lobe (eq. 3.10) times a factor with one azimuthal kink, on the half-planes
    φ_V = ±φ₀ (φ_V the azimuth of V about N, L in the plane φ = 0 as the integrators put it).  It
    declares its kinks: the N·V = N·L of the max, and the half-plane.  φ_V is measured from L's
    azimuth (:func:`_cos_relative_azimuth`), so the model is isotropic and reciprocal.

    At θ = 0, R = N = L and max(N·L, N·V) = 1, so
    a(0) = c ∫ cos^(n+1)θ_V sin θ_V dθ_V · ∫ (1 + ½ max(0, cos φ − cos φ₀)) dφ = c (2π + sin φ₀ − φ₀ cos φ₀)/(n + 2)
    = 1 + (sin φ₀ − φ₀ cos φ₀)/(2π): 1 + 1/(2π) for φ₀ = π/2 ((1/2π) ∫ max(0, cos φ) dφ = 1/π)."""

    n: float = 8.0
    phi0: float = np.pi / 2
    name = "kinked_lobe_in_a_test"
    param_ranges = {"n": Interval(1.0, 1e3), "phi0": Interval(0.1, 3.0)}
    accuracy_families = {"kinked_lobe_n": ("n", {})}
    #: its own sampler: V from the cosine-power lobe about R, (n+1)/2π (R·V)ⁿ (below the horizon: rejected)
    strategies = ("lobe", "cosine")
    #: (R·V)⁺ⁿ: nothing where R·V < 0, beyond the reach of its lobe about R (the engine integrates it)
    zero_beyond_lobe = True

    def _eval(self, L, V, nl, nv):
        cos_phi = _cos_relative_azimuth(L, V, np.cos(self.phi0))
        lobe = (self.n + 2) / (2 * np.pi) * positive_power(r_dot_v(L, V), self.n) / np.maximum(nl, nv)
        return lobe * (1.0 + 0.5 * np.maximum(cos_phi - np.cos(self.phi0), 0.0))

    def normal_incidence_albedo(self):
        return 1.0 + (np.sin(self.phi0) - self.phi0 * np.cos(self.phi0)) / (2 * np.pi)

    @property
    def lobe(self):
        return PowerCosine(self.n, MIRROR)

    def nv_levels(self, nl):
        return (nl,)

    def azimuth_levels(self, nl):
        return (self.phi0,)

    def _sample_direction(self, L, u, strategy):
        cos_a, sin_a = sampling.power_cosine(u[..., 0], self.n)
        V = sampling.around_axis(sampling.mirror_direction(L), cos_a, sin_a, 2.0 * np.pi * u[..., 1])
        return np.where((V[..., 2] > 0)[..., None], V, sampling.REJECTED)

    def _pdf(self, L, V, strategy):
        return sampling.power_cosine_pdf(r_dot_v(L, V), self.n)


@dataclass(frozen=True)
class KinkedHalfLobe(KinkedLobe):
    """The same azimuthal factor on a Blinn lobe, f = (N·H)ⁿ⁺ / max(N·L, N·V) · (1 + ½ max(0, cos φ_V − cos φ₀)),
    integrated in the half-vector frame: at θ = 0 the factor decouples as well, a(0) = a_Blinn(0) ·
    (1 + (sin φ₀ − φ₀ cos φ₀)/(2π)) with a_Blinn(0) = 8π [2 (1 − 2^(−(n+4)/2))/(n+4) − (1 − 2^(−(n+2)/2))/(n+2)]
    (Table 3.1's closed form)."""

    name = "kinked_half_lobe_in_a_test"

    def _eval(self, L, V, nl, nv):
        cos_phi = _cos_relative_azimuth(L, V, np.cos(self.phi0))
        lobe = positive_power(n_dot_h(L, V), self.n) / np.maximum(nl, nv)
        return lobe * (1.0 + 0.5 * np.maximum(cos_phi - np.cos(self.phi0), 0.0))

    def normal_incidence_albedo(self):
        n = self.n
        blinn = 8 * np.pi * (2 * (1 - 2 ** (-(n + 4) / 2)) / (n + 4) - (1 - 2 ** (-(n + 2) / 2)) / (n + 2))
        return blinn * super().normal_incidence_albedo()

    @property
    def lobe(self):
        return PowerCosine(self.n, HALF)

    accuracy_families = {"kinked_half_lobe_n": ("n", {})}
    strategies = ("cosine",)


KINKED_ANGLES = np.array([15.0, 35.0, 55.0, 70.0, 85.0])


@pytest.fixture(params=[(KinkedLobe, np.pi / 2), (KinkedLobe, 2.5), (KinkedHalfLobe, 2.5)],
                ids=["mirror-phi0=pi/2", "mirror-phi0=2.5", "half-phi0=2.5"])
def kinked(request):
    cls, phi0 = request.param
    register(cls)
    yield model(cls.name, phi0=phi0)
    del MODELS[cls.name]


def test_a_model_with_an_azimuthal_kink_meets_its_closed_form_at_normal_incidence(kinked):
    est, truth = albedo(kinked, [0.0]), kinked.normal_incidence_albedo()
    assert abs(est.value[0] - truth) <= est.error[0] and est.error[0] <= 1e-10 * truth
    assert list(est.status) == ["converged"]


def test_disk_reference_honours_a_models_declared_azimuthal_kink(kinked):
    """At θ = 0 the half-plane φ_V = φ₀ is the ray ψ = φ₀ from the disk's centre; elsewhere every ray
    crosses it at r = sin θ sin φ₀ / sin(φ₀ − ψ) (the angles of the next test)."""
    est, truth = albedo(kinked, [0.0], "disk"), kinked.normal_incidence_albedo()
    assert abs(est.value[0] - truth) <= est.error[0] and list(est.status) == ["converged"]


def test_a_model_with_an_azimuthal_kink_agrees_with_the_disk_reference_at_five_angles(kinked):
    """The engine's 2-D route (cuts where the half-plane meets each lobe circle, radial breakpoints where
    it starts to) against the disk reference (radial breakpoints where each ray crosses it): both
    converged to 1e-10 and within their combined reported errors."""
    engine, disk = albedo(kinked, KINKED_ANGLES), albedo(kinked, KINKED_ANGLES, "disk")
    assert set(engine.status) == {"converged"} and set(disk.status) == {"converged"}
    assert np.all(np.abs(engine.value - disk.value) <= engine.error + disk.error), (engine, disk)


@pytest.fixture
def lambert():
    register(Lambert)
    yield model(Lambert.name)
    del MODELS[Lambert.name]


def test_a_model_defined_in_a_test_has_albedo_one_at_ten_angles(lambert):
    est = albedo(lambert, ANGLES)
    assert np.all(np.abs(est.value - 1.0) <= est.error) and np.all(est.error < 1e-9)
    assert set(est.status.ravel()) == {"converged"} and est.evaluations > 0


def test_a_model_defined_in_a_test_has_a_grazing_limit_of_one(lambert):
    law = asymptotic_law(lambert)
    assert law.exponent == 0 and abs(law.constant.value - 1.0) <= law.constant.error + 1e-12


def test_the_config_schema_accepts_a_registered_model_and_rejects_an_unknown_one(lambert):
    config = yaml.safe_load(CONFIG_YAML.read_text())
    config["grazing"]["fig_2_1_models"].append({"model": Lambert.name})
    check_config(config)
    config["grazing"]["fig_2_1_models"].append({"model": "lambertt"})
    with pytest.raises(ConfigError, match="'lambertt'"):
        check_config(config)


def test_parameter_columns_come_from_the_dataclass_fields():
    assert Lambert.param_columns() == ("rho",)
    assert model("cook_torrance", m=0.1).param_columns() == ("m", "C", "G")
    assert model("phong", n=4).params == {"n": 4, "C": pytest.approx(6 / (2 * np.pi))}


@pytest.mark.parametrize("name, params", [("phong", {"n": 7}), ("blinn", {"n": 30}), ("ward", {"m": 0.2}),
                                          ("cook_torrance", {"m": 0.3}), ("patch_basic", {"R": 1.0})])
def test_default_cosine_sampling_draws_the_cosine_law_and_its_weights_average_to_the_albedo(name, params):
    """Malley's method draws sin²θ_V and φ_V uniform (Kolmogorov–Smirnov at 1e-3), its pdf is a
    density (∫ pdf dω = 1 on a product grid), and the mean weight f cos θ_V / pdf is the albedo of the
    engine within five standard errors: an estimator, not a restated formula."""
    from scipy.stats import kstest

    brdf = model(name, **params)
    L = np.array([np.sin(0.6), 0.0, np.cos(0.6)])
    u = np.random.default_rng(5).random((200_000, 2))
    V, weight, pdf = brdf.sample(L, u, strategy="cosine")
    assert np.allclose(np.linalg.norm(V, axis=-1), 1.0) and np.all(V[:, 2] >= 0)
    sin2 = V[:20_000, 0] ** 2 + V[:20_000, 1] ** 2
    assert kstest(sin2, "uniform").pvalue > 1e-3
    assert kstest(np.mod(np.arctan2(V[:20_000, 1], V[:20_000, 0]), 2 * np.pi) / (2 * np.pi), "uniform").pvalue > 1e-3
    x, w = np.polynomial.legendre.leggauss(64)
    mu_v, phi = np.meshgrid(0.5 * (x + 1), np.pi * (x + 1), indexing="ij")
    s_v = np.sqrt((1 - mu_v) * (1 + mu_v))
    grid = np.stack([s_v * np.cos(phi), s_v * np.sin(phi), mu_v], -1)
    mass = np.einsum("i,j,ij->", 0.5 * w, np.pi * w, brdf.pdf(L, grid, strategy="cosine"))
    assert mass == pytest.approx(1.0, abs=1e-12)
    exact = float(albedo(brdf, np.degrees(0.6)).value)
    assert abs(weight.mean() - exact) <= 5 * weight.std(ddof=1) / np.sqrt(weight.size)


def _example(name):
    """The model at its typical example: the parameters the class declares, no table kept here."""
    return MODELS[name].example("typical")


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_models_closed_forms_agree_with_its_integrated_albedo(name):
    """What a model states in closed form is what the engine integrates: ``exact_albedo`` wherever it
    is finite (θ = 0°, 10°, 45°, 90°), a finite ``grazing_law`` against the albedo of
    ``grazing_limit_model()`` at 90°, a divergent one against a(θ) at cos θ = 1e-6, and
    ``exact_mean_albedo`` against the mean albedo integrated."""
    from brdfs.numerics.quantities import mean_albedo_nested

    brdf = _example(name)
    theta = np.array([0.0, 10.0, 45.0, 90.0])
    exact = brdf.exact_albedo(theta)
    known = np.isfinite(exact)
    if known.any():
        est = albedo(brdf, theta[known])
        assert np.all(np.abs(exact[known] - est.value) <= est.error + 1e-12 * np.abs(exact[known])), (exact, est)
    law = brdf.grazing_law()
    if law is not None and law.exponent == 0:
        limit = albedo(brdf.grazing_limit_model(), 90.0)
        assert abs(law.constant.value - float(limit.value)) <= law.constant.error + float(limit.error) + 1e-12
    elif law is not None:
        mu = 1e-6
        a = albedo(brdf, np.degrees(np.arccos(mu)), rtol=1e-8)
        assert float(law(mu)) == pytest.approx(float(a.value), rel=1e-3)
    mean = brdf.exact_mean_albedo()
    if mean is not None:
        nested = mean_albedo_nested([brdf], rtol=1e-9)
        assert abs(mean.value - nested.value[0]) <= mean.error + nested.error[0]


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_declares_its_lobe_and_kinks_with_values_the_integrators_can_use(name):
    """A lobe is None (a model with its own albedo route, or one only the disk reference integrates)
    or has a :class:`~brdfs.physics.lobes.Frame`; N·V levels lie in [0, 1], radii r = |L_xy + V_xy|
    in (0, 2]; the Dirac part's albedo lies in [0, 1] and is zero unless the model describes a
    mirror reflection."""
    from brdfs.physics.lobes import Frame

    brdf = _example(name)
    assert brdf.lobe is None or isinstance(brdf.lobe.frame, Frame)
    mu = np.array([0.2, 0.7, 1.0])
    for c in brdf.nv_levels(mu):
        assert np.all((np.asarray(c) >= 0) & (np.asarray(c) <= 1))
    psi = np.linspace(0.0, np.pi, 7)
    for r in brdf.scattering_radius_kinks(np.cos(psi), np.sin(psi)):
        assert np.shape(r) == psi.shape and np.all((r > 0) & (r <= 2.0))
    if brdf.chapter is not None:                      # no model of the thesis has a half-plane kink
        assert len(brdf.azimuth_levels(mu)) == 0
    for phi in brdf.azimuth_levels(mu):               # Oren–Nayar's cos(φ_L − φ_V) = 0 (beyond the thesis)
        assert np.all((np.asarray(phi) >= 0) & (np.asarray(phi) < 2 * np.pi))
    delta = brdf.delta_albedo(np.array([0.0, 45.0]))
    assert np.all((delta.value >= 0) & (delta.value <= 1))
    if brdf.mirror_albedo(0.0) is None:
        assert np.all(delta.value == 0)
    assert set(brdf.params) == set(MODELS[name].param_columns())


# --- the rest of the pipeline, for the same model defined here only ------------------------------

@pytest.fixture
def kinked_lobe():
    register(KinkedLobe)
    yield model(KinkedLobe.name, n=8.0, phi0=2.5)
    del MODELS[KinkedLobe.name]


@pytest.mark.parametrize("theta", [0.0, 40.0, 75.0])
def test_a_user_models_own_sampler_passes_the_chi_square_test(kinked_lobe, theta):
    """Its sampler draws the density its pdf declares (chi-square on the sphere chart, at the
    Šidák-corrected level of the three angles), the pdf's mass is the accepted fraction and every
    weight is f cos θ_V / pdf."""
    from brdfs.numerics.chi2 import chi2_test, sidak_level

    result = chi2_test(kinked_lobe, theta, strategy="lobe", n_samples=50_000, seed=7)
    assert result.p_value >= sidak_level(3), result
    assert abs(result.pdf_mass - result.accepted_fraction) <= 5 * np.sqrt(result.accepted_fraction / result.n_samples)
    assert result.weight_error <= 1e-9


def test_a_user_models_sampler_that_lies_about_its_pdf_fails_the_chi_square_test(kinked_lobe):
    """The check above can fail: the same sampler with n + 1 in the pdf is rejected."""
    from brdfs.numerics.chi2 import chi2_test, sidak_level

    @dataclass(frozen=True)
    class Lying(KinkedLobe):
        name = "kinked_lobe_lying_in_a_test"

        def _pdf(self, L, V, strategy):
            return sampling.power_cosine_pdf(r_dot_v(L, V), self.n + 1.0)

    result = chi2_test(Lying(n=8.0, phi0=2.5), 40.0, strategy="lobe", n_samples=50_000, seed=7)
    assert result.p_value < sidak_level(3)


def test_a_user_model_gets_honest_rows_from_the_accuracy_maps_compute_function(kinked_lobe):
    """The accuracy map's compute function builds the model from its declared family and compares the
    engine with the disk reference: no cell dishonest or failed, each within 1e-10."""
    from brdfs.artifacts import extra_accuracy_map as accuracy_map

    section = {"grid": "reduced", "reference_rtol": 1e-12, "pumping_table_rtol": 1e-6, "pumping_engine_rtol": 1e-9,
               "reduced": {"theta_deg": [0.0, 30.0, 60.0, 85.0], "families": {"kinked_lobe_n": [8.0, 40.0]}},
               "full": {"theta_deg": [0.0], "families": {"kinked_lobe_n": [8.0]}}}
    df = accuracy_map.accuracy_map(section, {"rtol": 1e-10, "atol": 1e-14})
    assert set(df["model"]) == {KinkedLobe.name} and len(df) == 8
    assert not (df["dishonest"] | df["failed"]).any(), df
    assert df["meets_tolerance"].all(), df


def test_the_config_schema_accepts_a_user_model_within_its_declared_ranges(kinked_lobe):
    config = yaml.safe_load(CONFIG_YAML.read_text())
    """Its parameters are known to the schema from the class: phi0, which no hand-written entry
    describes, is bounded by the model's declared range."""
    config = yaml.safe_load(CONFIG_YAML.read_text())
    config["grazing"]["fig_2_1_models"].append({"model": KinkedLobe.name, "n": 20.0, "phi0": 2.5})
    check_config(config)
    config["grazing"]["fig_2_1_models"][-1]["phi0"] = 3.5
    with pytest.raises(ConfigError, match="phi0"):
        check_config(config)


def test_a_user_model_renders_as_a_material_and_shows_sky_times_albedo(kinked_lobe):
    """A 16 × 12 image of a sphere of the model under a uniform sky S: the renderer draws from the
    model's own sampler, and the pixels' mean over the sphere is S times the mean of a(θ_V) over
    the same pixels (eq. 3.32) within five standard errors."""
    from brdfs.render import materials, shapes, tracer

    S = 1.5
    material = materials.specular(kinked_lobe, 1)
    assert [p.strategy for p in material.proposals][0] == "lobe"
    scene = tracer.Scene([tracer.SceneObject(shapes.Sphere((0, 0, 0), 1.0), material, "s")], sky=np.full(1, S))
    camera = tracer.Camera((0, -10, 0), (0, 0, 0), 16, 12, fov_deg=14)
    image = tracer.render(scene, camera, spp=512, depth=2, seed=3, jitter=False)
    assert image.radiance.shape == (12, 16, 1) and np.isfinite(image.radiance).all()
    o, d = camera.rays(np.full((12, 16, 2), 0.5))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    t, index = scene.intersect(o, d)
    hit = index >= 0
    normal = o[hit] + t[hit, None] * d[hit]
    # the sphere's local frame: the renderer's tangent frame; the model's azimuthal factor makes
    # a(θ_V) depend on that frame only through φ, which the albedo integrates out
    theta_v = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normal, -d[hit]), 0, 1)))
    # rtol 1e-4: the relative Monte Carlo error of the mean is 2e-3 (a 2 % error fails at 512 spp, a 3 % one passed
    # at 64), and the albedos' own error joins the bound; the image's mirror symmetries give its 76 sphere
    # pixels 10 distinct θ_V, each integrated once
    angles, pixel_angle = np.unique(np.round(theta_v, 9), return_inverse=True)
    a = albedo(kinked_lobe, np.minimum(angles, 89.9), rtol=1e-4)
    expected, expected_err = S * a.value[pixel_angle].mean(), S * a.error[pixel_angle].mean()
    got = image.radiance.reshape(-1)[hit]
    err = np.sqrt(image.variance_of_mean.reshape(-1)[hit].sum()) / hit.sum()
    assert hit.sum() >= 60
    assert abs(got.mean() - expected) <= 5 * err + expected_err, (got.mean(), expected, err, expected_err)
