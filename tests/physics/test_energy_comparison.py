"""The white-furnace comparison's helpers and the claims its caption rests on."""
import numpy as np
import pytest

from brdfs import albedo, model
from brdfs.artifacts import _microfacet_energy as mf


def test_roughness_mapping_is_walters_for_blinn_and_four_times_for_phong():
    assert float(mf.alpha_of_n("blinn", 20)) == pytest.approx(np.sqrt(2 / 22), rel=1e-15)
    assert float(mf.alpha_of_n("phong", 20)) == pytest.approx(np.sqrt(2 / 82), rel=1e-15)
    for family in ("phong", "blinn"):
        assert float(mf.n_of_alpha(family, mf.alpha_of_n(family, 7.5))) == pytest.approx(7.5, rel=1e-13)


def test_the_new_model_creates_energy_at_the_roughest_swept_lobe():
    """phong_cosmin with n = 0.52 (α = 0.7) has a(30°) > 1 (the overshoot of sec. 3.2.2): an exceedance,
    asserted, not hidden; at n = 20 it stays ≤ 1."""
    n = float(mf.n_of_alpha("phong", 0.7))
    est = albedo(model("phong_cosmin", n=n), [0.0, 30.0], rtol=1e-9)
    assert est.value[1] - est.error[1] > 1.005
    assert abs(est.value[0] - 1.0) <= est.error[0] + 1e-12
    tame = albedo(model("phong_cosmin", n=20.0), np.arange(0.0, 91.0, 10.0), rtol=1e-9)
    assert np.all(tame.value <= 1.0 + tame.error)


def test_blinn_new_model_constant_makes_its_largest_albedo_one():
    brdf = mf.new_model("blinn", 20.0)
    est = albedo(brdf, np.arange(0.0, 91.0, 15.0), rtol=1e-9)
    assert est.value.max() == pytest.approx(1.0, abs=1e-7)
