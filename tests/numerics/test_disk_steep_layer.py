"""The disk route honest where a generalized Lambertian's ξ(m) = (1 − m²/4)^{−d/2} nearly reaches its pole
m = 2 (issue 41): m_clip → 2 at grazing incidence, where the longest ray, ψ = 0, ends 2 − (1 + sin θ) ≈ cos²θ/2
from the pole and its integral carries a layer of width ~cos θ in ψ (:func:`brdfs.numerics.integrate.disk.
_steep_layer_rays`, from the model's ``scattering_radius_steep_layer``).

Truths: ``sweep.patch_mp.radial_albedo`` with ``generalized_lambert_phi`` (mpmath at 40 digits, tanh-sinh
over ψ of the closed-form radial integral Φ(ρ_max(ψ)); the model's constant C as the package computes it),
rounded to the nearest double; the first also in ``tests/data/sweep_truths.csv``.  Old code (main ed5d6ea):
true error / reported error 1.03, 1.10, 1.39, 1.70 on the four cells below (the default route falls back to
the disk at 2 − 1e-12, 89.999°, rtol 1e-8 and 1e-9, with the same values).
"""
from functools import lru_cache

import numpy as np
import pytest

import brdfs
from brdfs.numerics.integrate import disk

TRUTHS = {  # (d, m_clip, θ): albedo
    (1.0, 2 - 1e-9, 89.99): 0.9999998807926656,
    (1.0, 2 - 1e-12, 89.999): 1.079073276194011,
}
CELLS = [  # (d, m_clip, θ, rtol, method): None is the front door's default, which falls back to the disk here
    (1.0, 2 - 1e-9, 89.99, 1e-6, "disk"),
    (1.0, 2 - 1e-9, 89.99, 1e-7, "disk"),
    (1.0, 2 - 1e-12, 89.999, 1e-8, "disk"),
    (1.0, 2 - 1e-12, 89.999, 1e-9, "disk"),
    (1.0, 2 - 1e-12, 89.999, 1e-8, None),
    (1.0, 2 - 1e-12, 89.999, 1e-9, None),
]


#: The models' default C = 1/max albedo (a double, as the package computes it; the truths are for it), given
#: as a literal: computing it near m_clip = 2 takes a second.
DEFAULT_C = {(1.0, 2 - 1e-9): 0.2189922990934326, (1.0, 2 - 1e-12): 0.23630873815008444}


@lru_cache(maxsize=None)
def _model(d, m_clip):
    return brdfs.model("generalized_lambertian", d=d, m_clip=m_clip, C=DEFAULT_C.get((d, m_clip)))


@pytest.mark.parametrize("d, m_clip, theta, rtol, method", CELLS)
def test_disk_albedo_is_honest_when_a_generalized_lambertian_nearly_reaches_its_pole_at_grazing(
        d, m_clip, theta, rtol, method):
    m = _model(d, m_clip)
    kwargs = {} if method is None else {"method": method}
    est = brdfs.albedo(m, theta, rtol=rtol, **kwargs)
    value, error = float(est.value), float(est.error)
    truth = TRUTHS[(d, m_clip, theta)]
    assert abs(value - truth) <= error, (value, truth, abs(value - truth) / error)
    assert error <= rtol * abs(value), (error, rtol * abs(value))


def test_disk_grades_psi_toward_the_longest_ray_only_near_the_pole():
    """The graded rays lie about ψ = 0 at ~2^k √(cos²θ/2) for m_clip = 2 − 1e-9 at 89.99°, and there are none at
    the default m_clip = 1.9 (any angle) nor for models without a pole."""
    theta = 89.99
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    rays = np.array(disk._steep_layer_rays(_model(1.0, 2 - 1e-9), mu, st))
    width = mu / np.sqrt(2.0)
    assert rays.size > 10 and width < rays.min() < 4 * width, (rays.min(), width)
    assert disk._steep_layer_rays(_model(1.0, 1.9), mu, st) == []
    assert disk._steep_layer_rays(brdfs.model("patch_exponential", s=1.0), mu, st) == []


def test_a_pumped_model_keeps_its_bases_steep_layer():
    """Pumping divides f by g(N·L, N·V), a function of the angles alone: the pole of f in r = |L_xy + V_xy|
    stays, and the disk grades a pumped generalized Lambertian's rays as its base's."""
    from brdfs.numerics import pumping

    base = _model(1.0, 2 - 1e-9)
    table = pumping.AlbedoTable(np.array([0.0, 1.0]), np.full((1, 3), 0.9), 0.0)   # any table: g does not move r
    pumped = pumping.Pumped(base, table)
    assert pumped.scattering_radius_steep_layer() == base.scattering_radius_steep_layer() is not None
    mu, st = np.cos(np.radians(89.99)), np.sin(np.radians(89.99))
    assert disk._steep_layer_rays(pumped, mu, st) == disk._steep_layer_rays(base, mu, st)
