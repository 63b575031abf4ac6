"""The patch plugins (:mod:`brdfs.render.mitsuba.plugins.patch`) are twins of the numpy models of
chapter 4: the same f and pdf at 10⁴ random pairs (the exponential model's "normal" pdf included: the
exact marginal density of the model's ``exact`` strategy), samplers whose directions follow the
plugin's pdf (Mitsuba's ``mi.chi2.ChiSquareTest`` through ``mi.chi2.BSDFAdapter``, on a chart of the
base plane), weights equal to f cos/pdf, an anisotropic ellipse whose frame matters, and the costs
(samples, tries, evaluations — next-event estimation's included) and the "normal" loop's give-up
probability.

Twin tolerance |f32 − f64| ≤ 2⁻²⁰ (1 + n)|f64| + 2⁻²⁴ max f, with n the amplification of the
relative error of m (and of the inputs) in the formula: 0 for the indicator functions (basic,
elliptical), s for e^{−s m} (δf/f = s δm, m ≤ 2, δm ≤ 2⁻²³ m), 1 + d m_clip²/(4 − m_clip²) for the
generalized Lambertian ((1 − m²/4)^{−d/2}: δf/f = (d m²/2)/(4 − m²) δm/m), and 4 for pdfs that divide
by a lens area (float64 in the plugin, then one rounding).  Where f jumps (m = R, the ellipse), a pair
whose f64 distance to the jump is within 2⁻¹⁸ of it is left out and counted: float32 may put it on
the other side.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.special import gammainc, gammaincinv

from _chi2 import incidence

from brdfs.physics import patch_geometry as patch
from brdfs.physics.models import model as numpy_model

PAIRS = 10_000
ANGLES = (30.0, 75.0)
#: The examples every plugin is tested at (the models' ``examples``).
KINDS = ("narrowest", "typical")


def _plugin(name, strategy=None, **params):
    d = {"type": f"brdfs_{name}", **{k: float(v) for k, v in params.items()}}
    if strategy is not None:
        d["strategy"] = strategy
    return d


def _tolerance_n(brdf):
    """n of the twin tolerance (module docstring)."""
    p = brdf.params
    if "s" in p:
        return float(p["s"])
    if "d" in p:
        return 1.0 + p["d"] * p["m_clip"] ** 2 / (4.0 - p["m_clip"] ** 2)
    return 0.0


def _distance_to_jump(brdf, L, V):
    """|m − R| (basic), the elliptic distance − b (elliptical), inf where f has no jump."""
    p = brdf.params
    z = L[..., :2] + V[..., :2]
    if "R" in p:
        return np.abs(np.hypot(z[..., 0], z[..., 1]) - p["R"])
    if "ratio" in p:
        phi = np.radians(p["u_angle_deg"])
        along_u = np.cos(phi) * z[..., 0] + np.sin(phi) * z[..., 1]
        along_v = -np.sin(phi) * z[..., 0] + np.cos(phi) * z[..., 1]
        return np.abs(np.hypot(p["ratio"] * along_u, along_v) - p["b"])
    return np.full(L.shape[:-1], np.inf)


PLUGIN_MODELS = ("patch_basic", "patch_exponential", "patch_elliptical", "generalized_lambertian")
CASES = [(name, kind) for name in PLUGIN_MODELS for kind in KINDS]


def _pairs(brdf, rng):
    """L uniform over the hemisphere; V half uniform, half from the model's own sampler (so that a
    narrow patch is hit); all rounded to float32 (the plugin's inputs)."""
    def uniform(n):
        u = rng.random((n, 2))
        z = u[:, 0]
        r = np.sqrt(1 - z * z)
        return np.stack([r * np.cos(2 * np.pi * u[:, 1]), r * np.sin(2 * np.pi * u[:, 1]), z], -1)
    L = uniform(2 * PAIRS)
    strategy = brdf.strategies[0]
    V_own = brdf.sample_direction(L[:PAIRS], rng.random((PAIRS, brdf.sample_dimension(strategy))), strategy)
    V = np.concatenate([V_own, uniform(PAIRS)])
    own, other = np.flatnonzero(V[:PAIRS, 2] > 1e-3), PAIRS + np.flatnonzero(V[PAIRS:, 2] > 1e-3)
    keep = np.concatenate([own[:PAIRS // 2], other[:PAIRS - min(own.size, PAIRS // 2)]])
    L, V = L[keep].astype(np.float32), V[keep].astype(np.float32)
    return L.astype(np.float64), V.astype(np.float64)


def _np(x):
    """A Dr.Jit array as a float64 numpy array (``.numpy()``: no element-wise conversion)."""
    return np.asarray(x.numpy(), np.float64)


def _call(mi, plugin, verb, L, V):
    import drjit as dr
    si = dr.zeros(mi.SurfaceInteraction3f, len(L))
    si.wi = mi.Vector3f(*(mi.Float(L[:, k].astype(np.float32)) for k in range(3)))
    wo = mi.Vector3f(*(mi.Float(V[:, k].astype(np.float32)) for k in range(3)))
    out = getattr(plugin, verb)(mi.BSDFContext(), si, wo)
    arr = _np(out)
    return arr[0] if arr.ndim == 2 else arr


def _assert_twin(computed, exact, n, where, what):
    bound = 2.0 ** -20 * (1.0 + n) * np.abs(exact) + 2.0 ** -24 * np.max(np.abs(exact))
    err = np.abs(computed - exact)
    bad = where & (err > bound)
    assert not bad.any(), (f"{what}: {bad.sum()} of {where.sum()} pairs off, worst |f32 − f64| = "
                           f"{err[bad].max():.3g} at f64 = {exact[bad][np.argmax(err[bad])]:.6g}")


@pytest.mark.parametrize("name, kind", CASES)
def test_plugin_eval_and_pdf_agree_with_the_numpy_model_at_ten_thousand_pairs(mitsuba, name, kind):
    mi = mitsuba
    from brdfs.physics.models import MODELS
    brdf = MODELS[name].example(kind)
    L, V = _pairs(brdf, np.random.default_rng(7))
    n = _tolerance_n(brdf)
    clear = _distance_to_jump(brdf, L, V) > 2.0 ** -18
    assert (~clear).sum() <= 5, f"{(~clear).sum()} pairs in the rounding band of the jump"
    assert clear.sum() >= PAIRS - 5
    f64 = brdf(V, L) * V[:, 2]                          # Mitsuba's eval: f cos θ_o, o = V
    plugin_params = brdf.params
    for strategy in _plugin_strategies(mi, name):
        plugin = mi.load_dict(_plugin(name, strategy, **plugin_params))
        if strategy == _plugin_strategies(mi, name)[0]:
            _assert_twin(_call(mi, plugin, "eval", L, V), f64, n, clear, f"{name} {kind} eval")
            assert (f64 > 0).sum() > PAIRS / 4, "too few pairs inside the patch"
        pdf64 = brdf.pdf(L, V, _model_strategy(strategy))
        n_pdf = n + (4.0 if strategy == "normal" else 0.0)
        _assert_twin(_call(mi, plugin, "pdf", L, V), pdf64, n_pdf, clear, f"{name} {kind} pdf {strategy}")


def _model_strategy(strategy):
    """The numpy model's name of the plugin's strategy (``patch.MODEL_STRATEGY``)."""
    from brdfs.render.mitsuba.plugins import patch as plugins
    return plugins.MODEL_STRATEGY[strategy]


def _plugin_strategies(mi, name):
    from brdfs.render.mitsuba.plugins import patch as plugins
    return plugins.PLUGINS[name].strategies


# --- chi-square on charts of the base plane ------------------------------------------------------------

@dataclass(frozen=True)
class BasePlaneChart:
    """(φ, t) ∈ [−π, π] × [0, 1] ↔ points x of the base plane (V = (x, √(1 − |x|²))), polar about c:
    x = c + A r (cos φ, sin φ) with r = √t (a disk, or through A an ellipse, filled evenly; its rim is
    the chart's edge t = 1), or, given ``s``, A = 1 and r = m = G⁻¹(t G(m_max)), G(m) = P(2, s m), the
    radial law of e^{−s m} m, so that e^{−s m} fills the chart evenly.  :meth:`jacobian` is dA_x/(dφ dt)."""

    centre: tuple
    axes: tuple = ((1.0, 0.0), (0.0, 1.0))
    s: float | None = None
    m_max: float = 2.0

    def bounds(self):
        import mitsuba as mi
        return mi.ScalarBoundingBox2f([-np.pi, 0.0], [np.pi, 1.0])

    def aspect(self):
        return 1.0                        # (ChiSquareTest: res / aspect columns, res rows)

    def _radius(self, t):
        t = np.clip(t, 0.0, 1.0)
        if self.s is None:
            return np.sqrt(t)
        return np.interp(t, *_inverse_table(self.s, self.m_max))

    def _to_plane(self, phi, t):
        r = self._radius(t)
        ex, ey = r * np.cos(phi), r * np.sin(phi)
        A, c = np.asarray(self.axes), self.centre
        return c[0] + A[0, 0] * ex + A[0, 1] * ey, c[1] + A[1, 0] * ex + A[1, 1] * ey

    def _from_plane(self, x, y):
        ex, ey = np.linalg.solve(np.asarray(self.axes), np.stack([x - self.centre[0], y - self.centre[1]]))
        r = np.hypot(ex, ey)
        t = r * r if self.s is None else gammainc(2.0, self.s * r) / gammainc(2.0, self.s * self.m_max)
        # a point beyond the rim is on the rim: the rejected samples (V = −N, weight 0, which the
        # adapter keeps) land there; a wrong sample with weight there still meets a density of 0
        return np.arctan2(ey, ex), np.minimum(t, 1.0)

    def jacobian(self, x, y):
        """dA_x/(dφ dt) at x: |det A|/2, or G(m_max) e^{s m}/s² for the e^{−s m} chart."""
        det = abs(np.linalg.det(np.asarray(self.axes)))
        if self.s is None:
            return np.full(np.shape(x), 0.5 * det)
        m = np.hypot(x - self.centre[0], y - self.centre[1])
        return gammainc(2.0, self.s * self.m_max) * np.exp(np.minimum(self.s * m, 700.0)) / self.s ** 2

    def map_forward(self, p):
        import mitsuba as mi
        x, y = self._to_plane(_np(p.x), _np(p.y))
        z = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
        return mi.Vector3f(*(mi.Float(a.astype(np.float32)) for a in (x, y, z)))

    def map_backward(self, v):
        import mitsuba as mi
        phi, t = self._from_plane(_np(v.x), _np(v.y))
        return mi.Vector2f(mi.Float(phi.astype(np.float32)), mi.Float(t.astype(np.float32)))


@functools.lru_cache(maxsize=None)
def _inverse_table(s, m_max):
    """(t, m) on 2·10⁴ points: G⁻¹ by interpolation (its slope off by O(10⁻⁴), far below the test's
    noise), as scipy's gammaincinv costs microseconds a point."""
    m = np.minimum(gammaincinv(2.0, np.linspace(0.0, 1.0, 20_001) * gammainc(2.0, s * m_max)) / s, m_max)
    return gammainc(2.0, s * m) / gammainc(2.0, s * m_max), m


def _chart(brdf, strategy, L):
    """The chart that resolves ``strategy``'s points at L (a lens, an ellipse, e^{−s m}, or the disk)."""
    c = (-L[0], -L[1])
    p = brdf.params
    if strategy == "cosine":
        return BasePlaneChart((0.0, 0.0))
    if "s" in p:
        return BasePlaneChart(c, s=p["s"], m_max=min(2.0, 60.0 / p["s"]))
    if "R" in p and p["R"] < 1.0:
        r = (1 + 2 ** -20) * p["R"]
        return BasePlaneChart(c, ((r, 0.0), (0.0, r)))
    if "ratio" in p and np.pi * p["b"] ** 2 / p["ratio"] <= np.pi:
        phi = np.radians(p["u_angle_deg"])
        a, b = (1 + 2 ** -20) * p["b"] / p["ratio"], (1 + 2 ** -20) * p["b"]
        return BasePlaneChart(c, ((a * np.cos(phi), -b * np.sin(phi)), (a * np.sin(phi), b * np.cos(phi))))
    return BasePlaneChart((0.0, 0.0))


def _chi2(mi, brdf, strategy, theta_deg, sample_count=50_000, res=16, ires=16, diffuse=None):
    """Mitsuba's ``mi.chi2.ChiSquareTest`` of the plugin's sampler against the plugin's own pdf, both
    from ``mi.chi2.BSDFAdapter`` (``wi`` opaque: one kernel for every angle), on :func:`_chart`.

    The adapter's pdf is per solid angle; the chart's density is per (φ, t), so it is multiplied by
    dA_x/(dφ dt) / cos θ_V (dω = dA_x / cos θ_V on the base plane).  A rejected sample has weight 0
    (the adapter drops it; the accept/reject pdf is a sub-probability of that mass).  ``ires`` 16:
    cells cut by the unit circle (where the density per area jumps to 0) need it.  That the plugin's
    pdf is the numpy model's is the twin test's claim (above)."""
    import drjit as dr
    wi = incidence(theta_deg)
    bsdf = _plugin(brdf.name, strategy, **brdf.params)
    if diffuse is not None:
        bsdf["diffuse_reflectance"] = float(diffuse)
    sample_func, pdf_func = mi.chi2.BSDFAdapter(bsdf["type"], bsdf, wi=dr.opaque(mi.Vector3f, wi))
    chart = _chart(brdf, strategy if diffuse is None else "cosine", np.array(wi))

    def chart_pdf(v):
        x, y, z = _np(v.x), _np(v.y), _np(v.z)
        with np.errstate(divide="ignore", invalid="ignore"):
            per_area = np.where(z > 0, _np(pdf_func(v)) / z, 0.0)
        return mi.Float(np.nan_to_num(per_area * chart.jacobian(x, y)).astype(np.float32))

    test = mi.chi2.ChiSquareTest(domain=chart, sample_func=sample_func, pdf_func=chart_pdf, sample_dim=3,
                                 sample_count=sample_count, res=res, ires=ires, seed=0)
    test.passed = bool(test.run(0.01, quiet=True))
    return test


#: Every plugin's strategies (collected before Mitsuba's variant is set; checked against the plugins
#: by test_the_chi_square_cases_cover_every_strategy_of_every_plugin).
STRATEGIES = {"patch_basic": ("normal", "accept_reject", "cosine"),
              "patch_exponential": ("accept_reject", "normal", "cosine"),
              "patch_elliptical": ("accept_reject", "cosine"),
              "generalized_lambertian": ("cosine",)}


#: Parameters where f > 0 over the whole disk, for the cosine strategy: its draws where f = 0 have weight
#: 0 and the adapter drops them, while its pdf is the cosine's over the disk (the sampler ignores f).
FULL_SUPPORT = {"patch_basic": {"R": 2.0}, "patch_exponential": {"s": 4.0},
                "patch_elliptical": {"b": 2.0, "ratio": 0.5}, "generalized_lambertian": {"d": 0.5}}


def _chi2_cases():
    cases = []
    from brdfs.physics.models import MODELS
    for name, strategies in STRATEGIES.items():
        params = [MODELS[name].examples[k] for k in KINDS] + ([{"R": 1.5}] if name == "patch_basic" else [])
        for strategy in strategies:
            runs = [(FULL_SUPPORT[name], ANGLES[-1])] if strategy == "cosine" else \
                [(p, theta) for p in params for theta in ANGLES]
            for p, theta in runs:
                cases.append(pytest.param(name, p, strategy, theta, id=f"{name}-{strategy}-{p}-{theta:g}"))
    return cases


def test_the_chi_square_cases_cover_every_strategy_of_every_plugin(mitsuba):
    from brdfs.render.mitsuba.plugins import patch as plugins
    assert {name: cls.strategies for name, cls in plugins.PLUGINS.items()} == STRATEGIES
    assert tuple(STRATEGIES) == PLUGIN_MODELS


@pytest.mark.parametrize("name, params, strategy, theta", _chi2_cases())
def test_plugin_samplers_pass_mitsubas_chi_square_test_through_its_bsdf_adapter(mitsuba, name, params, strategy, theta):
    brdf = numpy_model(name, **params)
    test = _chi2(mitsuba, brdf, strategy, theta)
    assert test.passed, f"p = {test.p_value}: {test.messages}"


def test_exponential_normal_sampler_mixed_with_a_diffuse_lobe_passes_the_chi_square_test(mitsuba):
    """One-sample MIS over the lobes needs the lobes' true pdfs: the exact Q(m, d) cos θ_V of "normal"."""
    test = _chi2(mitsuba, numpy_model("patch_exponential", s=4.0), "normal", 60.0, diffuse=0.5)
    assert test.passed, f"p = {test.p_value}: {test.messages}"


# --- weights, costs, the give-up probability ------------------------------------------------------------

def _sample(mi, plugin, theta_deg, n, seed):
    import drjit as dr
    rng = np.random.default_rng(seed)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = dr.opaque(mi.Vector3f, incidence(theta_deg))
    s1 = mi.Float(rng.random(n, dtype=np.float32))
    s2 = mi.Point2f(mi.Float(rng.random(n, dtype=np.float32)), mi.Float(rng.random(n, dtype=np.float32)))
    bs, weight = plugin.sample(mi.BSDFContext(), si, s1, s2)
    wo = _np(bs.wo).T
    return si, bs, wo, _np(weight)[0]


@pytest.mark.parametrize("name, strategy", [("patch_basic", "normal"), ("patch_basic", "accept_reject"),
                                            ("patch_exponential", "accept_reject"),
                                            ("patch_elliptical", "accept_reject"),
                                            ("generalized_lambertian", "cosine")])
def test_each_strategys_own_weight_is_f_cos_over_its_pdf(mitsuba, name, strategy):
    mi = mitsuba
    from brdfs.physics.models import MODELS
    params = MODELS[name].examples["typical"]
    plugin = mi.load_dict(_plugin(name, strategy, **params))
    si, bs, wo, weight = _sample(mi, plugin, 60.0, 20_000, 3)
    kept = weight > 0
    assert kept.mean() > 0.3
    value = _np(plugin.eval(mi.BSDFContext(), si, bs.wo))[0]
    pdf = _np(bs.pdf)
    np.testing.assert_allclose(weight[kept], value[kept] / pdf[kept], rtol=2e-5)


def test_exponential_normal_weights_average_to_the_models_albedo(mitsuba):
    mi = mitsuba
    brdf = numpy_model("patch_exponential", s=10.0)
    plugin = mi.load_dict(_plugin("patch_exponential", "normal", s=10.0))
    _, _, _, weight = _sample(mi, plugin, 60.0, 20_000, 11)
    albedo = float(brdf.albedo_estimate(60.0, 1e-10, 1e-14).value)
    assert (weight > 0).all()
    assert abs(weight.mean() - albedo) < 5 * weight.std() / np.sqrt(weight.size) + 1e-6, (weight.mean(), albedo)


def test_the_lobe_mis_density_changes_the_mis_weights_only_not_the_samples_weights_or_pdf(mitsuba):
    """``mis_density = "lobe"``: ``eval_pdf`` and ``bs.pdf`` report f cos θ_V / W (the MIS weights'
    density), while ``pdf`` stays the exact marginal density of normal sampling (the chi-square
    tests) and the directions and weights are those of the exact sampler, bit for bit."""
    mi = mitsuba
    brdf = numpy_model("patch_exponential", s=10.0)
    exact = mi.load_dict(_plugin("patch_exponential", "normal", s=10.0))
    lobe = mi.load_dict({**_plugin("patch_exponential", "normal", s=10.0), "mis_density": "lobe"})
    si, bs_e, wo_e, w_e = _sample(mi, exact, 60.0, 20_000, 5)
    _, bs_l, wo_l, w_l = _sample(mi, lobe, 60.0, 20_000, 5)
    np.testing.assert_array_equal(wo_e, wo_l)
    np.testing.assert_array_equal(w_e, w_l)
    kept = w_l > 0
    f_cos = _np(lobe.eval(mi.BSDFContext(), si, bs_l.wo))[0]
    np.testing.assert_allclose(_np(bs_l.pdf)[kept], f_cos[kept] / brdf.total_weight, rtol=2e-6)
    np.testing.assert_array_equal(_np(lobe.pdf(mi.BSDFContext(), si, bs_l.wo)), _np(bs_e.pdf))
    value, pdf = lobe.eval_pdf(mi.BSDFContext(), si, bs_l.wo)
    np.testing.assert_allclose(_np(pdf)[kept], f_cos[kept] / brdf.total_weight, rtol=2e-6)
    assert not np.allclose(_np(bs_e.pdf)[kept], _np(bs_l.pdf)[kept], rtol=1e-3)


def test_the_lens_area_in_float64_is_the_numpy_geometrys_to_1e_12(mitsuba):
    """lens_area64 (sin 2φ from the triangle, no call of sin) against patch_geometry.circle_intersection at
    random (d, R), near both tangencies and nested/apart: the normal weight a_R(L) carries no error a
    float32 image could see (a float32 π in the nested case was 2.8e-8 off)."""
    mi = mitsuba
    from brdfs.render.mitsuba.plugins import patch as plugins
    rng = np.random.default_rng(17)
    n = 20_000
    d = np.concatenate([rng.random(n), 1 - 10.0 ** rng.uniform(-12, 0, n), 10.0 ** rng.uniform(-12, 0, n), rng.random(2 * n)])
    near = 10.0 ** rng.uniform(-12, -1, 2 * n) * rng.choice([-1.0, 1.0], 2 * n)
    R = np.concatenate([2 * rng.random(n), 10.0 ** rng.uniform(-6, 0.3, 2 * n),
                        np.abs(np.abs(1 - d[3 * n:4 * n]) + near[:n]), 1 + d[4 * n:] + near[n:]])
    exact = patch.circle_intersection(d, R).area
    area = np.asarray(plugins.lens_area64(mi.Float64(d), mi.Float64(R)))
    np.testing.assert_array_equal(area[exact == 0], 0.0)
    np.testing.assert_allclose(area, exact, rtol=1e-12, atol=0)


def test_the_normal_loop_gives_up_with_a_probability_below_float32_resolution(mitsuba):
    from brdfs.render.mitsuba.plugins import patch as plugins
    d, R = np.meshgrid(np.linspace(0.0, 1.0, 201), np.linspace(0.01, 2.0, 200))
    acceptance = patch.circle_intersection(d, R).area / (np.pi * np.minimum(R, 1.0) ** 2)
    assert acceptance.min() >= plugins.MIN_ACCEPTANCE * (1 - 1e-12)
    assert (1.0 - plugins.MIN_ACCEPTANCE) ** plugins.MAX_TRIES < 2.0 ** -40


def test_costs_count_samples_tries_and_evaluations_as_the_thesis_does(mitsuba):
    mi = mitsuba
    n, theta = 40_000, 85.0
    normal = mi.load_dict({**_plugin("patch_basic", "normal", R=0.9), "count": True})
    _sample(mi, normal, theta, n, 5)
    costs = normal.cost_counts()
    d = np.sin(np.radians(theta))
    acceptance = patch.circle_intersection(d, 0.9).area / (np.pi * 0.81)
    expected, sigma = n / acceptance, np.sqrt(n * (1 - acceptance)) / acceptance
    assert costs["samples"] == n and costs["evaluations"] == n and costs["failures"] == 0
    assert abs(costs["tries"] - expected) < 5 * sigma, (costs, expected)
    roulette = mi.load_dict({**_plugin("patch_exponential", "accept_reject", s=2.0), "count": True})
    _, _, _, weight = _sample(mi, roulette, theta, n, 6)
    assert roulette.cost_counts() == {"samples": n, "tries": n, "evaluations": 0, "failures": 0}
    assert 0.2 < (weight == 0).mean() < 0.8


def test_costs_count_the_evaluations_of_next_event_estimation(mitsuba):
    """eval and eval_pdf (what next-event estimation calls per light sample) add one evaluation per
    active lane, sample's own evaluations aside; without ``count`` nothing is recorded."""
    import drjit as dr
    mi = mitsuba
    plugin = mi.load_dict({**_plugin("patch_exponential", "accept_reject", s=4.0), "count": True})
    n = 1000
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = dr.opaque(mi.Vector3f, incidence(40.0))
    wo = mi.Vector3f(0.0, 0.0, 1.0) + dr.zeros(mi.Vector3f, n)
    active = mi.Bool(np.arange(n) % 4 != 0)
    plugin.eval_pdf(mi.BSDFContext(), si, wo, active)
    plugin.eval(mi.BSDFContext(), si, wo)
    assert plugin.cost_counts() == {"samples": 0, "tries": 0, "evaluations": 750 + n, "failures": 0}


def test_exponential_radius_is_the_models_inverse_cdf(mitsuba):
    mi = mitsuba
    for s in (512.0, 4.0, 0.5):
        plugin = mi.load_dict(_plugin("patch_exponential", s=s))
        ends = [0.0, 1e-7, 1e-4, 0.5, 0.999, 1 - 2 ** -20, 1 - 2 ** -24]
        u = np.concatenate([np.random.default_rng(1).random(4096), ends]).astype(np.float32)
        R = _np(plugin.radius(mi.Float(u)))
        exact = numpy_model("patch_exponential", s=s).radius_of_cdf(u.astype(np.float64))
        np.testing.assert_allclose(R, exact, rtol=2.0 ** -21, atol=2.0 ** -30)


def _independent_radius(s, u):
    """F⁻¹(u) of the exponential mixture without the model's bisection: x = P(3, ·)⁻¹(u P(2, s)) (scipy's
    ``gammaincinv``), R = x/s below F(1), the closed form R = −ln(e^{−2s} + (1 − u − p_Diffuse) 2P(2, s)/s²)/s
    above it, 2 from 1 − p_Diffuse on."""
    brdf = numpy_model("patch_exponential", s=s)
    norm, p_diffuse = gammainc(2.0, s), brdf.C / brdf.total_weight * np.pi * np.exp(-2.0 * s)
    at_one = gammainc(3.0, s) / norm
    inner = gammaincinv(3.0, np.minimum(u, at_one) * norm) / s
    with np.errstate(divide="ignore", invalid="ignore"):
        outer = -np.log(np.exp(-2.0 * s) + ((1.0 - u) - p_diffuse) * 2.0 * norm / (s * s)) / s
    return np.where(u >= 1.0 - p_diffuse, 2.0, np.where(u <= at_one, inner, outer))


@pytest.mark.parametrize("s", [0.01, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 15.0, 20.0, 64.0, 512.0, 1e5, 1e7, 1e9])
def test_exponential_radius_is_within_its_stated_bound_of_an_independent_inverse(mitsuba, s):
    """R = F⁻¹(u) of the plugin (table start, Newton steps, float64) within RADIUS_RTOL R of scipy's
    inverse, at 2·10⁴ uniform u, 10⁴ toward 0 and 10⁴ toward 1 (float32 u, as the sampler's): far below
    float32's 2⁻²⁴, so the radii sample the model's weight (with the 5 Newton steps of the linear start
    before, or 1 step now, 4e-6 at s ≥ 15, this fails)."""
    mi = mitsuba
    from brdfs.render.mitsuba.plugins import patch as plugins
    rng = np.random.default_rng(int(s * 100))
    u = np.concatenate([rng.random(20_000), 10.0 ** rng.uniform(-9, 0, 10_000), 1 - 10.0 ** rng.uniform(-7.2, 0, 10_000),
                        [2.0 ** -24, 1 - 2.0 ** -24]]).astype(np.float32)
    u = u[u < 1].astype(np.float64)
    R = np.asarray(mi.load_dict(_plugin("patch_exponential", s=s)).radius64(mi.Float(u.astype(np.float32))))
    exact = _independent_radius(s, u)
    worst = np.max(np.abs(R - exact) / exact)
    assert worst <= plugins.RADIUS_RTOL, worst
    assert plugins.RADIUS_RTOL <= 2.0 ** -30


# --- anisotropy: patch_elliptical at B/A < 1 -----------------------------------------------------------------

def _spread(mi, u_angle_deg):
    plugin = mi.load_dict(_plugin("patch_elliptical", "accept_reject", b=0.1, ratio=0.25, u_angle_deg=u_angle_deg))
    _, _, wo, weight = _sample(mi, plugin, 40.0, 20_000, 9)
    kept = weight > 0
    return np.std(wo[kept, 0]), np.std(wo[kept, 1])


def test_elliptical_highlight_stretches_along_the_major_axis_of_the_shading_frame(mitsuba):
    sx, sy = _spread(mitsuba, 0.0)
    assert sx / sy == pytest.approx(4.0, rel=0.05)          # a/b = 1/ratio, along x = dp/du
    sx, sy = _spread(mitsuba, 90.0)
    assert sy / sx == pytest.approx(4.0, rel=0.05)


def test_a_frame_turned_ninety_degrees_fails_the_elliptical_chi_square_test(mitsuba, monkeypatch):
    from brdfs.render.mitsuba.plugins import _common
    brdf = numpy_model("patch_elliptical", b=0.1, ratio=0.25)
    monkeypatch.setattr(_common, "FRAME_ROTATED_90", True)
    test = _chi2(mitsuba, brdf, "accept_reject", 40.0, sample_count=20_000, res=16)
    assert not test.passed


def test_the_exponential_plugin_refuses_an_s_beyond_its_radius_bound_with_one_line(mitsuba):
    from brdfs.render.mitsuba.plugins import patch as plugins

    with pytest.raises(Exception, match=r"s = 2000000000\.0: at most 1e\+09") as error:
        mitsuba.load_dict(_plugin("patch_exponential", s=2.0 * plugins.MAX_S))
    assert "at most" in str(error.value)
