"""The polar route's radial integrand where the distribution's azimuthal integral underflows to 0 and
the masking is infinite: the value is 0 (not 0 · ∞ = NaN) and its rounding bound is finite, for a
batch's θ_L column and for a single angle's numbers alike (issue 41: both zeroed in place)."""
import numpy as np

from brdfs.numerics.integrate import polar
from brdfs.physics.distributions import Beckmann


def _infinite_masking(mu_l, mu_v):
    return np.full(np.shape(mu_v), np.inf)


def test_a_vanishing_lobe_under_infinite_masking_integrates_as_zero_with_a_finite_bound():
    narrow = Beckmann(0.01)
    theta_v = np.linspace(0.7, 1.5, 21)[None, :]                 # far from θ_L = 0: e^(−q/α²) underflows
    theta_l = 0.0
    with np.errstate(invalid="ignore"):                          # ∞ · 0 in the bound, before it is zeroed
        batch = polar.radial_integrand(narrow, _infinite_masking, np.array([[theta_l]]), theta_v)
        single = polar.radial_integrand(narrow, _infinite_masking, theta_l, theta_v, np.cos(theta_l), np.sin(theta_l))
    for value, rounding in (batch, single):
        assert narrow.azimuthal_integral(np.tan(0.5 * theta_v) ** 2, 0.0 * theta_v)[0].max() == 0.0
        np.testing.assert_array_equal(value, 0.0)
        np.testing.assert_array_equal(rounding, 0.0)
