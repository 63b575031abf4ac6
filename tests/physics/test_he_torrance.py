"""He–Torrance: the specification's check values, its errata, the series' truncation, reciprocity,
physical limits, and the albedo against an independent integration.

Check values are those of the project's specification of the model (independent computation,
cross-checked there against Westin's reference code ``heBRDF``), printed to 7 significant digits.
"""
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erfc, gammaln, lambertw

from brdfs import model
from brdfs import albedo
from brdfs.physics.geometry import direction
from brdfs.physics.models.he_torrance import (
    HeTorrance,
    effective_roughness,
    kirchhoff_series,
    lambert_w,
    shadowing,
)

ALBEDO_HT = dict(sigma0_um=0.1, tau_um=1.7)                       # Figs. 2.1 / 3.4, F = 1
LOBE_HT = dict(sigma0_um=0.1, tau_um=1.4, ior_re=0.8, ior_im=6.0)  # Fig. 3.3


def rad(deg):
    return np.radians(deg)


def assert_honest(value, error, truth, rel_floor=1e-13):
    """True error within the reported one; reported at most 1000× the true error where measurable."""
    true_err = np.abs(np.asarray(value) - truth)
    assert np.all(true_err <= error), (value, error, truth)
    measurable = true_err > rel_floor * np.abs(truth)
    assert np.all(np.asarray(error)[measurable] <= 1000 * true_err[measurable]), (error, true_err)


# (θ_i, θ_r, φ, f_dd with F = 1, f_dd with n = 0.8 + 6i), σ0 = 0.1, τ = 1.7, λ = 0.55 (spec §8.1)
SPEC_FDD = [
    (0, 0, 180, 7.318721, 6.721884),
    (30, 30, 180, 9.913383, 9.098267),
    (30, 40, 180, 4.651307, 4.266020),
    (30, 30, 170, 7.182406, 6.591924),
    (60, 60, 180, 15.39980, 13.92933),
    (80, 80, 180, 4.014911, 3.506991),
    (45, 20, 90, 3.027600e-4, 2.779862e-4),
    (89, 60, 180, 0.9055722, None),
    (70, 25, 140, 3.661069e-4, None),
]


@pytest.mark.parametrize("theta_i, theta_r, phi, f_one, f_metal", SPEC_FDD)
def test_directional_diffuse_matches_the_check_values(theta_i, theta_r, phi, f_one, f_metal):
    L, V = direction(theta_i, 0.0), direction(theta_r, phi)
    assert float(model("he_torrance", **ALBEDO_HT, term="dd")(L, V)) == pytest.approx(f_one, rel=2e-7)
    if f_metal is not None:
        metal = model("he_torrance", **ALBEDO_HT, ior_re=0.8, ior_im=6.0, term="dd")
        assert float(metal(L, V)) == pytest.approx(f_metal, rel=2e-7)


def test_figure_3_3_lobe_matches_the_check_values():
    theta_r = [0, 20, 30, 38, 42, 46, 50, 60, 80]
    printed = [0.015929, 0.71340, 3.0389, 6.8199, 7.8695, 7.4233, 5.8979, 2.1680, 0.31759]
    f = HeTorrance(**LOBE_HT, term="dd")
    values = f(direction(42.0, 0.0), direction(np.array(theta_r, float), 180.0))
    np.testing.assert_allclose(values, printed, rtol=5e-5)
    assert float(HeTorrance(**LOBE_HT).delta_albedo(42.0).value) == pytest.approx(0.051247, rel=1e-5)


@pytest.mark.parametrize("theta, rho", [(0, 5.405779e-3), (30, 1.993626e-2), (60, 0.2711531),
                                        (80, 0.8215241), (85, 0.6204486), (89, 5.695098e-2)])
def test_specular_albedo_matches_the_check_values(theta, rho):
    total = HeTorrance(**ALBEDO_HT)
    assert float(total.delta_albedo(theta).value) == pytest.approx(rho, rel=2e-7)
    assert float(HeTorrance(**ALBEDO_HT, term="dd").delta_albedo(theta).value) == 0.0


@pytest.mark.parametrize("theta_i, theta_r, sigma", [(80, 80, 0.0997064630), (89, 60, 0.0481613555),
                                                     (89.9, 89.9, 0.0321576597)])
def test_lambert_w_roughness_matches_newton_iteration(theta_i, theta_r, sigma):
    """The closed form σ = σ0/√(1 + W₀(f0²)) against the spec's Newton values, and against a
    direct check of the fixed-point equation √(π/2) z0 = σ0/4 (K_i + K_r) exp(−z0²/(2σ0²))."""
    ci, si, cr, sr = np.cos(rad(theta_i)), np.sin(rad(theta_i)), np.cos(rad(theta_r)), np.sin(rad(theta_r))
    s = float(effective_roughness(ci, si, cr, sr, 0.1, 1.7))
    assert s == pytest.approx(sigma, abs=1e-10)
    z0 = 0.1 * np.sqrt(0.1 ** 2 / s ** 2 - 1)
    k = sum(t * erfc(1.7 / (2 * 0.1 * t)) for t in (si / ci, sr / cr))
    assert np.sqrt(np.pi / 2) * z0 == pytest.approx(0.1 / 4 * k * np.exp(-z0 ** 2 / (2 * 0.1 ** 2)), rel=1e-12)


def test_lambert_w_is_the_principal_branch_to_rounding_from_zero_to_overflow(rng=np.random.default_rng(5)):
    """The real iteration against scipy's complex lambertw (within 4 ulps) and against its defining
    equation w e^w = x (in logs: ln w + w = ln x, within 4 ulps of ln x + 1), from 1e-8 to 1e300,
    plus its ends W(0) = 0 and W(inf) = inf."""
    x = np.concatenate([np.logspace(-8, 300, 20001), rng.uniform(0.0, 10.0, 20000)])
    w = lambert_w(x)
    reference = lambertw(x).real
    assert np.all(np.abs(w - reference) <= 4 * np.spacing(reference))
    big = x > 1e-3
    assert np.all(np.abs(np.log(w[big]) + w[big] - np.log(x[big])) <= 4 * np.spacing(np.abs(np.log(x[big])) + 1.0))
    assert lambert_w(0.0) == 0.0 and lambert_w(np.inf) == np.inf


def test_shadowing_includes_the_erratum_of_eq_25():
    """With exp(−c²) in Λ, S₁ is 1 to six digits up to 60° (the printed eq. 25 gives 0.981 at 30°)."""
    theta = np.array([0.0, 30.0, 60.0, 80.0, 85.0, 89.0])
    s1 = shadowing(np.cos(rad(theta)), np.sin(rad(theta)), 0.1, 1.7)
    np.testing.assert_allclose(s1, [1, 1, 1, 0.980147, 0.796405, 0.238679], atol=6e-7)


def test_geometry_factor_equals_the_printed_polarisation_form(rng=np.random.default_rng(3)):
    """G of eq. 76 written with the s/p frames of k_i = −L and k_r = V equals (|v|²/v_z)², the form
    f_dd uses: f_dd / (G F S D / (π cos cos)) computed both ways agree to 1e-13."""
    L = direction(rng.uniform(1, 89, 200), rng.uniform(0, 360, 200))
    V = direction(rng.uniform(1, 89, 200), rng.uniform(0, 360, 200))
    n = np.array([0.0, 0.0, 1.0])
    ki, kr = -L, V
    v = kr - ki

    def frame(k):
        s = np.cross(k, n)
        s /= np.linalg.norm(s, axis=-1, keepdims=True)
        return s, np.cross(s, k)

    (si, pi), (sr, pr) = frame(ki), frame(kr)
    dot = lambda a, b: np.sum(a * b, -1)  # noqa: E731
    printed = ((dot(v, v) / v[:, 2]) ** 2 * (dot(sr, ki) ** 2 + dot(pr, ki) ** 2)
               * (dot(si, kr) ** 2 + dot(pi, kr) ** 2) / np.linalg.norm(np.cross(ki, kr), axis=-1) ** 4)
    reduced = (np.sum((L + V) ** 2, -1) / (L[:, 2] + V[:, 2])) ** 2
    np.testing.assert_allclose(printed, reduced, rtol=1e-12)


def _long_series(g, h, terms=2000):
    m = np.arange(1.0, terms + 1)
    log_t = m * np.log(g) - g - gammaln(m + 1) - np.log(m) - h / m
    return np.sort(np.exp(log_t)).sum()          # smallest first


@pytest.mark.parametrize("g", [0.01, 1.0, 5.22, 20.0, 100.0])
@pytest.mark.parametrize("h", [0.0, 10.0, 100.0, 377.0, 1000.0])
def test_series_truncation_is_bounded_and_below_the_engine_tolerance(g, h):
    """The adaptive sum's tail bound holds against a 2000-term sum and is < 1e-14 relative (engine:
    1e-10); the specification's fixed count M(g) = ⌈g + 12√g + 30⌉ is also good to 1e-10."""
    reference = _long_series(g, h)
    value, tail = kirchhoff_series(g, h)
    assert tail <= 1e-14 * value
    assert abs(reference - value) <= tail + 1e-13 * reference      # rounding of log-space terms ~ 400 ulp
    m_rule = int(np.ceil(g + 12 * np.sqrt(g) + 30))
    assert reference - _long_series(g, h, m_rule) <= 1e-10 * reference


def test_series_at_normal_incidence_and_its_limits():
    g = (4 * np.pi * 0.1 / 0.55) ** 2
    assert float(kirchhoff_series(g, 0.0)[0]) == pytest.approx(0.2438445, rel=5e-7)   # spec §8.1
    assert float(kirchhoff_series(0.0, 3.0)[0]) == 0.0
    small = 1e-6
    assert float(kirchhoff_series(small, 2.0)[0]) == pytest.approx(small * np.exp(-2.0), rel=1e-5)


def test_series_at_non_finite_arguments_ends_with_nan_or_its_limit():
    """T(g, +inf) = 0 (every term e^(−h/m) vanishes); NaN or infinite g, or NaN h, give NaN with an
    infinite tail bound, at once (they used to keep the adaptive sum looping)."""
    value, tail = kirchhoff_series(np.array([1.0, np.nan, np.inf, 1.0, 2.0]), np.array([np.inf, 1.0, 1.0, np.nan, 3.0]))
    assert value[0] == 0.0 and tail[0] == 0.0
    assert np.all(np.isnan(value[1:4])) and np.all(tail[1:4] == np.inf)
    assert value[4] == kirchhoff_series(2.0, 3.0)[0] > 0


@pytest.mark.parametrize("theta_i, theta_r, phi, ratio", [(0, 5, 180, 1.0002), (30, 35, 180, 1.0003),
                                                          (50, 45, 170, 0.9999), (60, 60, 180, 1.0010)])
def test_geometric_optics_limit_is_cook_torrance_beckmann(theta_i, theta_r, phi, ratio):
    """At λ = 0.02 µm (g ~ 10³) f_dd tends to F S D_B / (4 cos θ_i cos θ_r) with Beckmann slope m = 2σ/τ."""
    L, V = direction(theta_i, 0.0), direction(theta_r, phi)
    f = float(HeTorrance(**ALBEDO_HT, lambda_um=0.02, term="dd")(L, V))
    sin = lambda w: np.hypot(w[0], w[1])  # noqa: E731
    sigma = effective_roughness(L[2], sin(L), V[2], sin(V), 0.1, 1.7)
    m = 2 * sigma / 1.7
    h = (L + V) / np.linalg.norm(L + V)
    d_b = np.exp(-(1 - h[2] ** 2) / h[2] ** 2 / m ** 2) / (np.pi * m ** 2 * h[2] ** 4)
    s = shadowing(L[2], sin(L), 0.1, 1.7) * shadowing(V[2], sin(V), 0.1, 1.7)
    assert f / (s * d_b / (4 * L[2] * V[2])) == pytest.approx(ratio, abs=1.5e-4)


def test_reciprocity(rng=np.random.default_rng(11)):
    L = direction(rng.uniform(0, 89.9, 500), rng.uniform(0, 360, 500))
    V = direction(rng.uniform(0, 89.9, 500), rng.uniform(0, 360, 500))
    for params in (ALBEDO_HT, LOBE_HT):
        f = HeTorrance(**params, term="dd")
        np.testing.assert_allclose(f(L, V), f(V, L), rtol=1e-13, atol=0)


def test_specular_term_has_no_density_and_total_density_is_dd():
    L, V = direction(42.0, 0.0), direction(np.array([0.0, 42.0, 60.0]), 180.0)
    assert np.all(HeTorrance(**LOBE_HT, term="specular")(L, V) == 0.0)
    np.testing.assert_array_equal(HeTorrance(**LOBE_HT)(L, V), HeTorrance(**LOBE_HT, term="dd")(L, V))


@pytest.mark.parametrize("kwargs, match", [
    (dict(sigma0_um=-0.1, tau_um=1.7), "sigma0_um"),
    (dict(sigma0_um=0.1, tau_um=0.0), "tau_um"),
    (dict(sigma0_um=0.1, tau_um=1.7, term="diffuse"), "diffuse"),
    (dict(sigma0_um=0.1, tau_um=1.7, ior_re=0.8), "ior_im"),
    (dict(sigma0_um=0.1, tau_um=1.7, lambda_um=float("nan")), "lambda_um"),
])
def test_bad_parameters_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        model("he_torrance", **kwargs)


# --- albedo -------------------------------------------------------------------------------------

def independent_dd_albedo(f, theta_deg):
    """∫ f_dd cos θ_V dω_V with the pole of the spherical coordinates on the surface's y axis:
    V = (cos v sin u, sin v, cos v cos u), cos θ_V dω_V = cos v · cos v cos u du dv, v ∈ [0, π/2] doubled.
    Outer: scipy ``quad`` in v; inner: composite Gauss–Legendre in u on panels cut where the lobe's
    scales (0.1 × 2^k in x = V_x around the mirror) are crossed and geometrically towards the horizon
    u = ±π/2, at two orders whose difference bounds its error."""
    L = direction(theta_deg, 0.0)
    scales = 0.1 * 2.0 ** np.arange(-6, 5)
    horizon = 0.5 * 4.0 ** -np.arange(0, 13)
    x_lobe = -np.sin(rad(theta_deg)) + np.concatenate([-scales, scales, [0.0]])
    rules = [np.polynomial.legendre.leggauss(order) for order in (16, 24)]
    inner_errors = []

    def inner(v):
        cuts = np.concatenate([np.arcsin(np.clip(x_lobe / np.cos(v), -1, 1)), -np.pi / 2 + horizon,
                               np.pi / 2 - horizon, [-np.pi / 2, np.pi / 2]])
        a, b = np.unique(cuts)[:-1, None], np.unique(cuts)[1:, None]
        values = []
        for x, w in rules:
            u = 0.5 * (a + b) + 0.5 * (b - a) * x
            V = np.stack(np.broadcast_arrays(np.cos(v) * np.sin(u), np.sin(v), np.cos(v) * np.cos(u)), -1)
            values.append(np.sum(0.5 * (b - a)[:, 0] * ((f(L, V) * V[..., 2]) @ w)) * np.cos(v))
        inner_errors.append(abs(values[1] - values[0]))
        return values[1]

    points = np.unique(np.concatenate([np.arcsin(scales[scales < 1]), np.pi / 2 - horizon]))
    value, err = quad(inner, 0.0, np.pi / 2, points=points, epsabs=0, epsrel=1e-12, limit=500)
    return 2 * value, 2 * (err + np.pi / 2 * max(inner_errors))


@pytest.mark.parametrize("params, theta", [(ALBEDO_HT, 0.0), (ALBEDO_HT, 60.0), (ALBEDO_HT, 85.0),
                                           (ALBEDO_HT, 89.5), (LOBE_HT, 42.0)])
def test_dd_albedo_agrees_with_an_independent_integration(params, theta):
    f = HeTorrance(**params, term="dd")
    reference, reference_err = independent_dd_albedo(f, theta)
    assert reference_err < 1e-11
    tight = albedo(f, theta)
    assert abs(float(tight.value) - reference) <= float(tight.error) + reference_err
    assert float(tight.error) <= 1e-10 * reference
    for tol in (1e-5, 1e-7):
        loose = albedo(f, theta, rtol=tol)
        assert_honest(float(loose.value), float(loose.error), reference, rel_floor=1e-11)


def test_albedo_of_each_term_and_their_sum():
    """dd matches the spec's table (5 digits), the specular albedo is ρ_s, and total = dd + ρ_s."""
    theta = np.array([0.0, 30.0, 60.0, 75.0, 80.0, 89.0, 89.9])
    dd = albedo(HeTorrance(**ALBEDO_HT, term="dd"), theta)
    spec = albedo(HeTorrance(**ALBEDO_HT, term="specular"), theta)
    total = albedo(HeTorrance(**ALBEDO_HT), theta)
    np.testing.assert_allclose(dd.value, [.99467, .98018, .71229, .30497, .21932, .03066, .01474], atol=6e-6)
    np.testing.assert_allclose(spec.value, HeTorrance(**ALBEDO_HT).delta_albedo(theta).value, rtol=1e-14)
    np.testing.assert_allclose(total.value, dd.value + spec.value, rtol=1e-14)
    assert np.all(total.error <= 1e-10 * total.value)
    assert total.value[4] == pytest.approx(1.04084, abs=6e-6)      # overshoot above 1 at 80°
    assert float(albedo(HeTorrance(**LOBE_HT, term="dd"), 42.0).value) == pytest.approx(0.86211, abs=6e-6)


@pytest.mark.parametrize("lam, low, high", [(0.45, 1.00005, 1.00011), (0.55, 1.000075, 1.000085),
                                            (0.65, 1.00005, 1.00011)])
def test_energy_closure_at_normal_incidence(lam, low, high):
    a = float(albedo(HeTorrance(**ALBEDO_HT, lambda_um=lam), 0.0).value)
    assert low <= a <= high


# --- artifacts ----------------------------------------------------------------------------------

def test_figure_3_3_calibration_and_lobes():
    from brdfs.pipeline.registry import get_artifact
    from brdfs.artifacts.fig_3_3_specular_lobes import NORMAL, lobe_models
    from brdfs.pipeline.config import load_config

    cfg = load_config()
    df = get_artifact("fig_3_3_specular_lobes").compute(cfg, {})
    models = lobe_models(cfg["he_torrance"]["fig_3_3"], cfg["he_torrance"]["lambda_um"])
    phong_peak = float(models[0][2](NORMAL, NORMAL))
    scales = df.groupby("model")["scale"].first()
    for name, _, brdf in models:       # calibrated: every f(N, N) equals Phong's
        assert scales[name] * float(brdf(NORMAL, NORMAL)) == pytest.approx(phong_peak, rel=1e-13)
    lobes = df[(df["quantity"] == "brdf") & (df["phi_deg"] == 180.0)]
    peaks = lobes.loc[lobes.groupby("model")["value"].idxmax()].set_index("model")["theta_v_deg"]
    assert peaks["phong"] == 42.0 and abs(peaks["he_torrance"] - 42.0) <= 1.0
    rho = df[df["quantity"] == "specular_albedo"]
    assert float(rho["value"].iloc[0]) == pytest.approx(scales["he_torrance"] * 0.051247, rel=1e-5)
    assert np.all(df["value_err"].dropna() <= 1e-11 * np.abs(df["value"].dropna()) + 1e-300)


# --- the azimuthal integral in closed form (issue 41: the albedo as a 1-D integral) ----------------

def azimuth_integral_by_gauss_legendre(f, theta_l, theta_v, order):
    """∫₀^{2π} f cos θ_V sin θ_V dφ of the BRDF's own values, composite Gauss–Legendre in φ ∈ [0, π]
    (doubled) on panels graded geometrically towards the mirror azimuth φ = π (the lobe)."""
    cuts = np.concatenate([[0.0], np.pi - np.pi * 2.0 ** -np.arange(1.0, 30.0), [np.pi]])
    x, w = np.polynomial.legendre.leggauss(order)
    a, b = cuts[:-1, None], cuts[1:, None]
    phi = 0.5 * (a + b) + 0.5 * (b - a) * x
    tl, tv = np.asarray(theta_l, float)[:, None, None], np.asarray(theta_v, float)[:, None, None]
    L = np.stack(np.broadcast_arrays(np.sin(tl), 0.0 * phi, np.cos(tl)), -1)
    V = np.stack(np.broadcast_arrays(np.sin(tv) * np.cos(phi), np.sin(tv) * np.sin(phi), np.cos(tv)), -1)
    values = f.unchecked(L, V) @ w
    return 2.0 * np.sin(tv[:, 0, 0]) * np.cos(tv[:, 0, 0]) * np.sum(0.5 * (b - a)[None, :, 0] * values, -1)


@pytest.mark.parametrize("params", [ALBEDO_HT, dict(sigma0_um=0.1, tau_um=4.0),
                                    dict(sigma0_um=0.01, tau_um=10.0, lambda_um=0.38),
                                    dict(sigma0_um=1.0, tau_um=0.5, lambda_um=0.78)])
def test_closed_form_azimuthal_integral_equals_the_brdfs_own_values_integrated(params):
    """The kernel the engine integrates in θ_V (Kummer functions, term by term) against the BRDF's own
    values integrated over φ, from the pole to the horizon and incidence to 90° − 1e-4°, within its bound."""
    f = HeTorrance(**params, term="dd")
    theta_l, theta_v = (rad(x).ravel() for x in np.meshgrid([0.0, 1e-6, 10.0, 45.0, 80.0, 89.9999],
                                                            [1e-6, 5.0, 30.0, 44.0, 45.0, 60.0, 79.0, 85.0, 89.0,
                                                             89.9999, 90.0]))
    kernel = f.scattering_azimuth_kernel()
    value, bound = kernel(np.cos(theta_l), np.sin(theta_l), np.cos(theta_v), np.sin(theta_v))
    reference = azimuth_integral_by_gauss_legendre(f, theta_l, theta_v, 40)
    reference_err = np.abs(reference - azimuth_integral_by_gauss_legendre(f, theta_l, theta_v, 30))
    assert np.all(np.abs(value - reference) <= bound + reference_err + 1e-14 * np.abs(reference))
    assert np.all(bound <= 1e-12 * np.abs(value) + 1e-300)         # far below the engine's 1e-10
    assert np.all(value[np.cos(theta_v) == np.cos(rad(90.0))] >= 0)


def test_albedo_by_the_closed_form_azimuth_agrees_with_the_two_dimensional_route(monkeypatch):
    """F = 1 takes the 1-D route (its kernel nodes counted); the 2-D route of the same lobe (the model
    without its kernel, as with a Fresnel term) agrees within the two errors, at rtol 1e-10 and 1e-6."""
    f = HeTorrance(sigma0_um=0.1, tau_um=4.0)                # the narrowest example, delta included
    theta = np.array([0.0, 1e-6, 45.0, 89.9999])
    one_d = {rtol: albedo(f, theta, rtol=rtol) for rtol in (1e-10, 1e-6)}
    monkeypatch.setattr(HeTorrance, "scattering_azimuth_kernel", lambda self: None)
    two_d = albedo(f, theta, rtol=1e-10)
    assert np.all(two_d.evaluations > 20 * one_d[1e-10].evaluations)
    for rtol, est in one_d.items():
        assert est.evaluations > 0 and est.evaluations % 21 == 0       # one count per Kronrod node
        assert np.all(est.route == "engine/scattering") and np.all(est.status == "converged")
        assert np.all(np.abs(est.value - two_d.value) <= est.error + two_d.error)
        assert np.all(est.error <= rtol * est.value)
