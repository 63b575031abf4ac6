"""Gold's spectral albedo (Fig. 3.7, eq. 3.29) and the colour conversion."""
import numpy as np
import pytest

from brdfs import albedo
from brdfs.physics import optical_constants as oc
from brdfs.physics import spectral_colour as sc
from brdfs.physics.fresnel import normal_incidence_reflectance, unpolarised_reflectance
from brdfs.physics.geometry import direction, light_direction
from brdfs.physics.models.metal import PhongCosminMetal
from brdfs.physics.models.phong import PhongCosmin
from brdfs.pipeline import registry
from brdfs.pipeline.config import load_config

GOLD_550 = complex(oc.complex_index("gold", 550.0))
METAL = PhongCosminMetal(8.0, ior_re=GOLD_550.real, ior_im=GOLD_550.imag)


def test_metal_model_is_reciprocal_and_below_the_new_model():
    rng = np.random.default_rng(1)
    L = direction(rng.uniform(0, 89, 200), rng.uniform(0, 360, 200))
    V = direction(rng.uniform(0, 89, 200), rng.uniform(0, 360, 200))
    np.testing.assert_allclose(METAL(L, V), METAL(V, L), rtol=1e-13)
    assert np.all(METAL(L, V) <= PhongCosmin(8.0)(L, V))


def test_albedo_at_normal_incidence_is_f0_since_theta_min_is_zero():
    est = albedo(METAL, 0.0)
    f0 = float(normal_incidence_reflectance(GOLD_550.real, GOLD_550.imag))
    assert abs(est.value - f0) <= est.error + 1e-12


@pytest.mark.parametrize("theta", [45.0, 80.0])
def test_engine_albedo_matches_an_independent_product_quadrature(theta):
    """a(θ) by Gauss–Legendre in (θ_V, φ), split at the kink θ_V = θ and at the lobe's edge."""
    x, w = np.polynomial.legendre.leggauss(400)
    lo, hi = [0.0, theta], [theta, 90.0]
    tv = np.concatenate([(a + b) / 2 + (b - a) / 2 * x for a, b in zip(lo, hi)])
    wt = np.concatenate([(b - a) / 2 * w for a, b in zip(lo, hi)]) * np.pi / 180
    phi = 180.0 + 180.0 * x  # φ in (0, 360); the lobe is around φ = 180
    wp = 180.0 * w * np.pi / 180
    T, P = np.meshgrid(tv, phi, indexing="ij")
    V = direction(T, P)
    f = METAL(np.broadcast_to(light_direction(theta), V.shape), V)
    integrand = f * V[..., 2] * np.sin(np.radians(T))
    reference = float(np.einsum("i,j,ij->", wt, wp, integrand))
    est = albedo(METAL, theta, rtol=1e-9)
    assert abs(float(est.value) - reference) < 1e-6


def test_f_at_theta_min_does_not_factor_out_of_the_albedo():
    """a(θ) ≠ F(θ) a_new(θ) at 60°: the chosen route (integrating eq. 3.29) matters."""
    metal, new = albedo(METAL, 60.0), albedo(PhongCosmin(8.0), 60.0)
    f60 = float(unpolarised_reflectance(0.5, GOLD_550.real, GOLD_550.imag))
    assert abs(metal.value - f60 * new.value) > 1000 * (metal.error + new.error) + 1e-5


def test_white_reflector_is_white_and_constant_reflectance_has_that_luminance():
    wl = sc.VISIBLE_NM
    np.testing.assert_allclose(sc.reflectance_to_linear_srgb(wl, np.ones(wl.size)), 1.0, atol=3e-4)
    assert sc.reflectance_to_xyz(wl, np.full(wl.size, 0.37))[1] == pytest.approx(0.37, rel=1e-12)


def test_f0_table_gold_is_yellow_silver_neutral_and_luminance_matches_the_spectrum():
    cfg = load_config()
    df = registry.get_artifact("extra_metal_f0_rgb").compute(cfg, {}).set_index("metal")
    gold = df.loc["gold"]
    assert gold.r > gold.g > gold.b
    silver = df.loc["silver", ["r", "g", "b"]].to_numpy(float)
    assert np.ptp(silver) < 0.02
    for metal, row in df.iterrows():
        eta = oc.complex_index(metal, sc.VISIBLE_NM, row.dataset)
        y = sc.reflectance_to_xyz(sc.VISIBLE_NM, normal_incidence_reflectance(eta.real, eta.imag))[1]
        luminance = 0.2126 * row.r + 0.7152 * row.g + 0.0722 * row.b  # sRGB Y row (IEC 61966-2-1)
        assert luminance == pytest.approx(y, abs=2e-4)


def test_fig_3_7_rows_agree_with_f0_at_normal_incidence_and_stay_below_one():
    cfg = load_config()
    cfg["gold_spectral"] = dict(cfg["gold_spectral"], wavelength_nm={"start": 380.0, "stop": 780.0, "step": 200.0},
                                theta_deg={"start": 0.0, "stop": 90.0, "step": 45.0})
    df = registry.get_artifact("fig_3_7_gold_spectral_albedo").compute(cfg, {})
    a = df[df.quantity == "albedo"]
    assert np.all((a.value > 0) & (a.value + a.value_err < 1))
    normal = a[a.theta_deg == 0.0]
    f0 = normal_incidence_reflectance(normal.ior_re.to_numpy(), normal.ior_im.to_numpy())
    assert np.all(np.abs(normal.value.to_numpy() - f0) <= normal.value_err.to_numpy() + 1e-9)
    compared = df[df.quantity == "a0"]
    assert compared.dataset.iloc[0] == cfg["gold_spectral"]["dataset"] and len(compared) == 5
    assert set(df.quantity) >= {f"albedo_linear_srgb_{c}" for c in "rgb"}
