"""Fresnel reflectance (eqs. 1.40-1.43) against closed forms and limits."""

from fractions import Fraction

import numpy as np
import pytest

from brdfs.physics import fresnel

INDICES = [(0.93, 6.33), (0.331, 2.324), (2.97, 4.58), (1.5, 0.0), (1.0001, 0.0), (0.2, 0.0), (3.0, 30.0)]


@pytest.mark.parametrize(("n", "k"), INDICES)
def test_a0_is_the_full_fresnel_reflectance_at_normal_incidence(n, k):
    a0 = fresnel.normal_incidence_reflectance(n, k)
    assert fresnel.unpolarised_reflectance(1.0, n, k) == pytest.approx(a0, rel=1e-14, abs=1e-16)


@pytest.mark.parametrize(("n", "k"), INDICES)
def test_reflectance_tends_to_one_at_grazing_incidence(n, k):
    cos_theta = np.array([1e-3, 1e-6, 0.0])
    f = fresnel.unpolarised_reflectance(cos_theta, n, k)
    assert f[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.all(np.diff(f) > -1e-15) and np.all(f <= 1.0 + 1e-15)  # n < 1: total reflection, F = 1


def test_dielectric_glass_reflects_four_percent_at_normal_incidence():
    assert fresnel.normal_incidence_reflectance(1.5, 0.0) == pytest.approx(0.04, abs=1e-17)
    assert fresnel.unpolarised_reflectance(1.0, 1.5) == pytest.approx(0.04, abs=1e-16)


@pytest.mark.parametrize("theta_deg", [10.0, 35.0, 60.0, 85.0])
def test_dielectric_matches_the_real_fresnel_formulae_with_snell(theta_deg):
    n, theta = 1.5, np.radians(theta_deg)
    theta_t = np.arcsin(np.sin(theta) / n)
    r_s = np.sin(theta - theta_t) / np.sin(theta + theta_t)
    r_p = np.tan(theta - theta_t) / np.tan(theta + theta_t)
    assert fresnel.unpolarised_reflectance(np.cos(theta), n) == pytest.approx((r_s**2 + r_p**2) / 2, rel=1e-13)


def test_parallel_reflectance_vanishes_at_the_brewster_angle():
    n = 1.5
    cos_b = np.cos(np.arctan(n))
    r_s2 = ((n**2 - 1) / (n**2 + 1)) ** 2  # |r_perp|^2 at Brewster's angle
    assert fresnel.unpolarised_reflectance(cos_b, n) == pytest.approx(r_s2 / 2, rel=1e-13)


def test_sign_convention_of_k_does_not_matter():
    cos_theta = np.linspace(0, 1, 11)
    assert np.allclose(fresnel.unpolarised_reflectance(cos_theta, 2.97, 4.58),
                       fresnel.unpolarised_reflectance(cos_theta, 2.97, -4.58), rtol=1e-13)


def exact_a0(n: str, k: str) -> Fraction:
    """Eq. 1.40 in exact rational arithmetic at the decimal inputs."""
    n, k = Fraction(n), Fraction(k)
    return ((n - 1) ** 2 + k**2) / ((n + 1) ** 2 + k**2)


@pytest.mark.parametrize(("n", "k"), [("0.93", "6.33"), ("0.331", "2.324"), ("2.97", "4.58"), ("1.0000001", "0"),
                                      ("0.999", "0.001"), ("12.3", "0.07"), ("0.05", "51.8")])
def test_error_bound_holds_and_is_tight(n, k):
    value = fresnel.normal_incidence_reflectance(float(n), float(k))
    err = fresnel.normal_incidence_reflectance_err(float(n), float(k))
    true_err = abs(Fraction(float(value)) - exact_a0(n, k))
    assert true_err <= Fraction(float(err))
    assert err <= 50 * np.finfo(float).eps * max(value, 1e-3)


def test_vectorised_over_arrays():
    n, k = np.array([0.93, 1.5]), np.array([6.33, 0.0])
    assert fresnel.normal_incidence_reflectance(n, k).shape == (2,)
    assert fresnel.unpolarised_reflectance(np.array([[1.0], [0.5]]), n, k).shape == (2, 2)
