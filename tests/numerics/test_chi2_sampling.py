"""Importance samplers of every model against their pdfs: chi-square tests (reduced set, fixed seed),
tests that a wrong pdf or a wrong lobe FAILS, the pdf's mass, and weight = f cos θ_V / pdf."""
import numpy as np
import pytest

from brdfs import model
from brdfs.artifacts.sampling_chi2 import build, cases, parameters
from brdfs.physics import patch_geometry as patch
from brdfs.numerics.chi2 import chi2_test, pooled_statistic, sidak_level
from brdfs.physics import sampling
from brdfs.physics.geometry import light_direction
from brdfs.physics.models import MODELS

SEED = 20010101
#: The family of tests in this file that must pass: one per model (grazing) + the mass checks.
LEVEL = sidak_level(len(MODELS))


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_sampler_passes_chi_square_at_its_narrowest_lobe_at_89_99_deg(name):
    brdf = build(name, parameters(name)[0])
    result = chi2_test(brdf, 89.99, n_samples=10_000, seed=SEED, n_radial=6, n_phi=6, n_pilot=3_000)
    assert result.dof >= 15
    assert result.p_value >= LEVEL, result
    assert result.weight_error < 1e-12


def test_reduced_check_lists_every_model_and_the_cosine_baseline():
    listed = {c[0] for c in cases(False)}
    assert listed == set(MODELS)
    assert any(c[2] == "cosine" for c in cases(False))
    assert max(c[3] for c in cases(True)) == 89.99


class Mismatched:
    """Samples with one model, claims the pdf of another (times ``factor``): a deliberately wrong sampler."""

    def __init__(self, sampler, claimed, factor=1.0):
        self.sampler, self.claimed, self.factor = sampler, claimed, factor

    def sample(self, L, u, strategy=None):
        V, _, _ = self.sampler.sample(L, u, strategy)
        pdf = self.pdf(L, V, strategy)
        with np.errstate(divide="ignore", invalid="ignore"):
            return V, np.where(pdf > 0, self(L, V) * V[..., 2] / pdf, 0.0), pdf

    def pdf(self, L, V, strategy=None):
        return self.factor * self.claimed.pdf(L, V, strategy)

    def sample_dimension(self, strategy=None):
        return self.sampler.sample_dimension(strategy)

    @property
    def sampling_domain(self):
        return self.claimed.sampling_domain

    def disk_boundaries(self):
        return self.claimed.disk_boundaries()

    def __call__(self, L, V):
        return self.claimed(L, V)


@pytest.mark.parametrize("sampler, claimed, factor, theta", [
    (model("phong", n=512 / 1.21), model("phong", n=512), 1.0, 45.0),          # 10 % wider lobe
    (model("ward", m=0.0055), model("ward", m=0.005), 1.0, 45.0),              # 10 % wider lobe
    (model("cook_torrance", m=0.0055), model("cook_torrance", m=0.005), 1.0, 89.99),
    (model("blinn", n=512), model("blinn", n=512), 1.1, 30.0),                  # pdf off by 10 %
    (model("patch_exponential", s=512), model("patch_exponential", s=512), 0.9, 45.0),
])
def test_a_wrong_pdf_or_a_wider_lobe_fails_the_chi_square_test(sampler, claimed, factor, theta):
    wrong = Mismatched(sampler, claimed, factor)
    result = chi2_test(wrong, theta, n_samples=10_000, seed=SEED, n_radial=6, n_phi=6, n_pilot=3_000)
    assert result.p_value < 1e-6, result


def test_a_flipped_lobe_fails():
    """Phong's lobe drawn about −R's horizontal mirror (L itself, a retro-reflective lobe)."""
    class Flipped(Mismatched):
        def sample(self, L, u, strategy=None):
            return super().sample(L * np.array([-1.0, -1.0, 1.0]), u, strategy)
    wrong = Flipped(model("phong", n=512), model("phong", n=512))
    assert chi2_test(wrong, 30.0, n_samples=5_000, seed=SEED, n_pilot=2_000, kind="sphere").p_value < 1e-6


@pytest.mark.parametrize("theta", [0.0, 40.0, 75.0, 89.99])
def test_exact_basic_patch_sampler_has_mass_one_and_russian_roulette_has_mass_the_albedo(theta):
    brdf = model("patch_basic", R=0.5)
    exact = chi2_test(brdf, theta, "exact", n_samples=2_000, seed=SEED, n_pilot=1_000)
    roulette = chi2_test(brdf, theta, "russian_roulette", n_samples=2_000, seed=SEED, n_pilot=1_000)
    assert exact.pdf_mass == pytest.approx(1.0, abs=1e-6)
    assert roulette.pdf_mass == pytest.approx(float(patch.basic_albedo(theta, 0.5).value), rel=1e-6)


def test_exponential_russian_roulette_mass_is_its_albedo_and_the_generic_mixture_agrees():
    theta = 70.0
    expo = model("patch_exponential", s=10.0)
    mixture = build("patch_mixture", {"s": 10.0})
    albedo = float(patch.mixture_albedo(patch.ExponentialProfile(10.0), theta).value)
    for brdf in (expo, mixture):
        assert chi2_test(brdf, theta, n_samples=2_000, seed=SEED, n_pilot=1_000).pdf_mass == pytest.approx(albedo, rel=1e-5)


def test_tabulated_inverse_cdf_of_a_mixture_matches_the_closed_form_bisection():
    r = np.linspace(0.0, 0.999, 200)
    mixture = build("patch_mixture", {"s": 10.0})
    closed = patch.inverse_cdf(patch.ExponentialProfile(10.0), r).value
    assert np.allclose(mixture.radius_of_cdf(r), closed, atol=1e-9)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_weight_is_f_cos_over_pdf_and_pdf_is_the_models_pdf(name):
    brdf = build(name, parameters(name)[-1])
    L = light_direction(63.0)
    for strategy in brdf.strategies:
        u = np.random.default_rng(3).random((2_000, brdf.sample_dimension(strategy)))
        V, weight, pdf = brdf.sample(L, u, strategy)
        ok = pdf > 0
        assert np.all(V[~ok, 2] <= 0) and np.all(weight[~ok] == 0)
        assert np.allclose(np.linalg.norm(V, axis=-1), 1.0)
        assert np.allclose(pdf[ok], brdf.pdf(L, V[ok], strategy), rtol=1e-12)
        assert np.allclose(weight[ok], brdf(L, V[ok]) * V[ok, 2] / pdf[ok], rtol=1e-12)


class RejectionLens:
    """The basic patch's "normal" sampler as the thesis draws it (section 4.2.4): points of the lens
    C(V'_P, R) ∩ unit disk by the rejection loop :func:`~brdfs.physics.sampling.lens_point_by_rejection`
    (Figure 4.9), claiming the exact strategy's pdf cos θ_V / Area(lens); the loop draws from a
    generator that the harness's uniform numbers seed."""

    sampling_domain = "disk"

    def __init__(self, R):
        self.brdf = model("patch_basic", R=R)

    def disk_boundaries(self):
        return self.brdf.disk_boundaries()

    def sample_dimension(self, strategy=None):
        return 2

    def __call__(self, L, V):
        return self.brdf(L, V)

    def pdf(self, L, V, strategy=None):
        return self.brdf.pdf(L, V, "exact")

    def sample(self, L, u, strategy=None):
        rng = np.random.default_rng(int(u[0, 0] * 2 ** 53))
        L = np.asarray(L, float)
        x, y, _ = sampling.lens_point_by_rejection(-L[0], -L[1], np.full(len(u), self.brdf.R), rng)
        V = sampling.disk_to_direction(x, y)
        pdf = self.pdf(L, V)
        return V, np.where(pdf > 0, self(L, V) * V[..., 2] / pdf, 0.0), pdf


@pytest.mark.parametrize("R, theta", [(0.05, 89.99), (0.5, 40.0), (0.5, 89.99), (1.5, 60.0)])
def test_the_thesis_rejection_loop_draws_the_lens_uniformly_chi_square(R, theta):
    result = chi2_test(RejectionLens(R), theta, n_samples=10_000, seed=SEED, n_radial=6, n_phi=6, n_pilot=3_000)
    assert result.dof >= 15 and result.pdf_mass == pytest.approx(1.0, abs=1e-6)
    assert result.accepted_fraction == 1.0
    assert result.p_value >= LEVEL, result


def test_uniform_points_in_a_lens_lie_in_both_circles_and_fill_them_evenly():
    rng = np.random.default_rng(1)
    cx, cy, R = 0.8, 0.0, 0.5
    x, y = sampling.uniform_in_lens(cx, cy, R, *rng.random((2, 40_000)))
    assert np.all(x * x + y * y <= 1 + 1e-12) and np.all(np.hypot(x - cx, y - cy) <= R + 1e-12)
    # the share right of x = 0.9 against its area, by the same closed-form lens of a smaller circle? use a
    # half-plane: the share above y = 0 is 1/2 by symmetry, within 4 standard errors
    assert abs(np.mean(y > 0) - 0.5) < 4 * 0.5 / np.sqrt(x.size)


def test_pooling_merges_cells_expecting_fewer_than_five():
    stat, dof, hits = pooled_statistic([3, 1, 0, 50, 46], [2.0, 2.0, 2.0, 47.0, 47.0])
    assert dof == 2 and hits == 0
    assert stat == pytest.approx((4 - 6) ** 2 / 6 + 9 / 47 + 1 / 47)
    assert pooled_statistic([1, 10], [0.0, 11.0])[2] == 1


def test_sidak_level_keeps_the_family_wise_level():
    assert sidak_level(1) == pytest.approx(0.01)
    assert 1 - (1 - sidak_level(500)) ** 500 == pytest.approx(0.01)


def test_unknown_strategy_is_one_clear_error():
    with pytest.raises(ValueError, match="unknown sampling strategy 'nope'"):
        model("phong", n=2).sample([0, 0, 1.0], np.zeros((1, 2)), "nope")


def test_the_check_is_registered_under_results_checks():
    from brdfs.pipeline.registry import get_artifact
    artifact = get_artifact("sampling_chi2")
    assert artifact.kind == "check" and artifact.csv == "results/checks/sampling_chi2.csv"


@pytest.mark.parametrize("name, params", [("patch_exponential", {"s": 10.0}), ("he_torrance", {"sigma0_um": 0.1, "tau_um": 1.7, "term": "dd"}),
                                          ("phong_cosmin", {"n": 100})])
def test_albedo_front_door_monte_carlo_with_the_models_sampler_agrees_with_the_integral(name, params):
    from brdfs import albedo
    brdf = model(name, **params)
    mc = albedo(brdf, 50.0, "monte_carlo", sampler="model", n_samples=20_000, seed=7)
    if name == "patch_exponential":
        reference = float(patch.mixture_albedo(patch.ExponentialProfile(10.0), 50.0).value)
    else:
        reference = float(albedo(brdf, 50.0).value)
    assert abs(float(mc.value) - reference) < 5 * float(mc.error) + 1e-12


def test_a_model_defined_here_is_tested_by_the_artifact_from_its_own_declarations():
    """A user's model (this file only) with its own sampler and examples, registered: the chi-square
    artifact lists it from its declarations (no edit of the artifact) and its sampler passes."""
    from dataclasses import dataclass

    from brdfs.physics.geometry import r_dot_v
    from brdfs.physics.models import register
    from brdfs.physics.models.base import BRDF

    @dataclass(frozen=True)
    class MirrorLobe(BRDF):
        """f = (n+2)/(2π) (R·V)^n / max(N·L, N·V), sampled about R by its own strategy."""

        n: float = 30.0
        name = "test_mirror_lobe"
        strategies = ("about_mirror", "cosine")
        examples = {"narrowest": {"n": 300.0}, "typical": {"n": 30.0}}
        lobe = None

        def _eval(self, L, V, nl, nv):
            return (self.n + 2) / (2 * np.pi) * np.maximum(r_dot_v(L, V), 0.0) ** self.n / np.maximum(nl, nv)

        def _sample_direction(self, L, u, strategy):
            cos_a, sin_a = sampling.power_cosine(u[..., 0], self.n)
            V = sampling.around_axis(sampling.mirror_direction(L), cos_a, sin_a, 2 * np.pi * u[..., 1])
            return np.where((V[..., 2] > 0)[..., None], V, sampling.REJECTED)

        def _pdf(self, L, V, strategy):
            return sampling.power_cosine_pdf(r_dot_v(L, V), self.n)

    register(MirrorLobe)
    try:
        listed = [c for c in cases(False) if c[0] == "test_mirror_lobe"]
        assert [(c[1], c[2]) for c in listed] == [({"n": 300.0}, "about_mirror")] * 2
        result = chi2_test(build("test_mirror_lobe", listed[0][1]), 60.0, n_samples=10_000, seed=SEED,
                           n_radial=6, n_phi=6, n_pilot=3_000)
        assert result.dof >= 15 and result.p_value >= LEVEL and result.weight_error < 1e-12, result
    finally:
        MODELS.pop("test_mirror_lobe")


@pytest.mark.parametrize("name, params", [("phong", {"n": 20}), ("patch_basic", {"R": 0.5})])
def test_the_uniform_reference_strategy_every_model_accepts_passes_chi_square_with_mass_one(name, params):
    """``"uniform"`` (1/(2π) per solid angle, Monte Carlo albedo's reference sampler) is the base
    class's, accepted by every model though not among its listed strategies."""
    brdf = model(name, **params)
    assert "uniform" not in brdf.strategies
    result = chi2_test(brdf, 50.0, "uniform", n_samples=10_000, seed=SEED, n_radial=6, n_phi=6, n_pilot=3_000)
    assert result.pdf_mass == pytest.approx(1.0, abs=1e-6) and result.accepted_fraction == 1.0
    assert result.p_value >= LEVEL and result.weight_error < 1e-12, result
