"""The exponential patch model's ``"exact"`` sampler (section 4.2.4's "normal" importance sampling
applied to the mixture of section 4.4): its density Q(m, d) is the adaptive-quadrature value of
∫_m² q(R)/A(d, R) dR + p_Diffuse/π, and its directions follow that density with mass 1 (chi-square; weights
f cos/pdf and ∫ pdf = 1 are the property tests' claims, tests/physics/test_model_properties.py)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import gammainc

from brdfs.numerics.chi2 import chi2_test
from brdfs.physics import patch_geometry as patch
from brdfs.physics.models import model


def _reference_density(brdf, d, m):
    """Q(m, d) by scipy's adaptive quadrature in R, split where q or A has a kink."""
    profile = patch.ExponentialProfile(brdf.s)
    q_scale = brdf.s ** 3 / (2.0 * gammainc(2.0, brdf.s))

    def integrand(R):
        return q_scale * min(R, 1.0) ** 2 * np.exp(-brdf.s * R) / float(patch.circle_intersection(d, R).area)

    points = [p for p in (1.0 - d, 1.0, 1.0 + d) if m < p < 2.0]
    value, _ = quad(integrand, m, 2.0, points=points or None, limit=400, epsabs=0.0, epsrel=1e-12)
    return value + (1.0 - float(profile.cdf(2.0))) / np.pi


@pytest.mark.parametrize("s", [0.5, 40.0, 512.0])
def test_exact_density_is_the_adaptive_quadrature_of_the_lens_mixture(s):
    brdf = model("patch_exponential", s=s)
    rng = np.random.default_rng(3)
    d = rng.random(4) ** 0.3                                   # toward grazing, where lenses are general
    m = rng.random(4) * min(2.0, 20.0 / s)
    exact = np.array([_reference_density(brdf, dd, mm) for dd, mm in zip(d, m)])
    np.testing.assert_allclose(brdf.exact_area_density(d, m), exact, rtol=5e-5)


def test_exact_sampler_passes_the_chi_square_test_with_mass_one():
    result = chi2_test(model("patch_exponential", s=40.0), 75.0, "exact", n_samples=20_000, seed=2, rtol=1e-3,
                       n_pilot=5_000)
    assert result.p_value > 1e-3, result
    assert abs(result.pdf_mass - 1.0) < 1e-3 and result.accepted_fraction == 1.0, result

