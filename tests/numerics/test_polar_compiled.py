"""The polar route's compiled single angle (:mod:`brdfs.numerics.integrate.polar_compiled`) is a replica
of its numpy path (:func:`brdfs.numerics.integrate.polar._albedo_one`, the reference): the same
breakpoints, integrand, rounding bounds and driver decisions, so that the honesty the sweep verifies for
the numpy route carries over.  The two differ in the last bits only: numpy's SIMD exp, tan, arccos and
log and scipy's erfc round differently from the C library's by an ulp, and BLAS sums the Kummer series
in another order than a loop.  Which models it covers follows from their declared factors, enumerated
here from every registered model's examples, the finite ends of its declared ranges and its choices."""
import math

import numpy as np
import pytest

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import NODES
from brdfs.numerics.integrate import polar
from brdfs.physics.distributions import GGX
from brdfs.physics.models import MODELS
from brdfs.physics.models.base import BRDF
from brdfs.physics.tables import MissingTable

pytestmark = pytest.mark.skipif(not compiled.available(), reason="numba missing or BRDFS_COMPILED=0")
if compiled.available():
    from brdfs.numerics.integrate import polar_compiled

EPS = np.finfo(float).eps
ANGLES = (0.0, 1e-6, 1e-3, 30.0, 60.0, 89.0, 89.9999, 90.0 - 1e-9, 90.0)
RTOLS = (1e-3, 1e-6, 1e-8, 1e-10, 1e-12)
#: |compiled − numpy| of a node's value in ulps of the numpy one (measured: ≤ 4.5; the Kummer series
#: summed by BLAS against a loop, tan, exp and erfc an ulp apart), or within the node's own rounding
#: bound where Beckmann's e^(−q/α²) multiplies an ulp of q by q/α² (measured: 257 ulps at α = 0.01,
#: 0.57 of the bound), and of its rounding bound relatively.
NODE_ULPS = 8
ROUNDING_RTOL = 1e-12
#: |compiled − numpy| of an albedo that took the same refinement decisions, in ulps of its value
#: (measured over the grid's 630 cells: ≤ 2.1), in parts of its reported error (measured: ≤ 0.017, GGX
#: α = 1, whose error is the rounding floor), and the errors' relative difference (measured: ≤ 0.022; the
#: error sums |K − G|, which cancel to rounding where the rule has resolved the integrand).
VALUE_ULPS = 8
WITHIN_ERROR = 0.05
ERROR_RTOL = 0.1
#: Cells whose refinement decisions may differ (a threshold met by one path, missed by the other by
#: ulps): at most this share of the grid, each still within the numpy value ± both errors.
FLIP_SHARE = 0.02


#: Values far inside an open-ended declared range (a scale C tiny and huge, a roughness m far above 1):
#: each, where a declared range holds it, on every declared choice of the typical parameters.  A kernel
#: that ignored a scale or a roughness the examples leave at 1 or below would pass the grid without them.
FAR = (1e-100, 1e-3, 10.0, 1e3, 1e100)


def _variants(cls):
    """The parameter sets of a model class: its examples, each declared choice (the others typical) and,
    on each of those, each finite closed end of a declared range; on each choice, the :data:`FAR` values
    inside a declared range."""
    typical = cls.examples.get("typical", next(iter(cls.examples.values()), {}))
    out = [dict(p) for p in cls.examples.values()]
    choices = [{**typical, key: c} for key, values in getattr(cls, "param_choices", {}).items() for c in values]
    out += choices
    for base in list(out):
        for key, interval in cls.param_ranges.items():
            for bound, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open)):
                if np.isfinite(bound) and not is_open:
                    out.append({**base, key: float(bound)})
    for base in choices or [typical]:
        for key, interval in cls.param_ranges.items():
            out += [{**base, key: v} for v in FAR if interval.contains(v)]
    return out


def _covered():
    """Every registered model variant whose declared factors the compiled kernel knows, once each."""
    seen, out = set(), []
    for name, cls in sorted(MODELS.items()):
        for params in _variants(cls):
            try:
                brdf = cls(**params)
            except (MissingTable, ValueError, TypeError):
                continue
            factors = brdf.half_vector_factors()
            if factors is None or polar_compiled.kernel_of(*factors) is None or brdf in seen:
                continue
            seen.add(brdf)
            out.append(brdf)
    return out


def test_the_covered_models_include_both_distributions_every_masking_and_the_ends_of_the_roughness():
    covered = _covered()
    kernels = {polar_compiled.kernel_of(*b.half_vector_factors())[0:3:2] for b in covered}
    assert kernels == {(d, f) for d in (polar_compiled.GGX_CODE, polar_compiled.BECKMANN_CODE)
                       for f in (polar_compiled.SEPARABLE_CODE, polar_compiled.HEIGHT_CORRELATED_CODE)} | {
        (polar_compiled.BECKMANN_CODE, polar_compiled.THESIS_SMITH_CODE)}
    alphas = {b.half_vector_factors()[0].alpha for b in covered}
    assert {0.005, 0.01, 1.0, 10.0, 1e3} <= alphas
    scales = {polar_compiled.kernel_of(*b.half_vector_factors())[-1] for b in covered}
    assert {1e-100, 1.0, 1e100} <= scales


def test_the_compiled_i0e_is_scipys_to_the_bit():
    from scipy.special import i0e
    x = np.concatenate([np.linspace(0.0, 40.0, 4001), np.geomspace(1e-12, 1e6, 2000), [7.999999, 8.0, 8.000001]])
    assert np.array_equal(np.array([polar_compiled.i0e(v) for v in x]), i0e(x))


def _nodes(theta_l, rng):
    """Nodes of 6 random intervals of [0, π/2] and of one 2e-3 wide about the mirror angle, (7, 21)."""
    ends = np.sort(rng.uniform(0.0, 0.5 * np.pi, (6, 2)), axis=1)
    ends = np.vstack([ends, [[max(theta_l - 1e-3, 0.0), min(theta_l + 1e-3, 0.5 * np.pi)]]])
    return (0.5 * ends.sum(1))[:, None] + (0.5 * (ends[:, 1] - ends[:, 0]))[:, None] * NODES


def test_the_compiled_kernel_is_the_numpy_integrand_node_by_node():
    rng = np.random.default_rng(41)
    for brdf in _covered():
        factors = brdf.half_vector_factors()
        kernel = polar_compiled.kernel_of(*factors)
        for theta in ANGLES:
            theta_l = np.radians(np.array([theta]))
            t, mu_l, s_l = theta_l.item(), np.cos(theta_l).item(), np.sin(theta_l).item()
            x = _nodes(t, rng)
            value, rounding = polar.radial_integrand(*factors, t, x, mu_l, s_l)
            got_value, got_rounding = np.empty_like(x), np.empty_like(x)
            polar_compiled.radial_integrand(*kernel, t, mu_l, s_l, x, got_value, got_rounding, 0, x.shape[0])
            assert np.all(np.abs(got_value - value) <= np.maximum(NODE_ULPS * EPS * np.abs(value), rounding)), (brdf, theta)
            assert np.all(np.abs(got_rounding - rounding) <= ROUNDING_RTOL * rounding), (brdf, theta)


def test_the_compiled_breakpoints_are_the_numpy_rows():
    """To the bit, the graded levels toward the horizon included (their angles are numpy's: its SIMD
    arccos and the C library's are an ulp apart now and then)."""
    for brdf in _covered():
        distribution = brdf.half_vector_factors()[0]
        alpha = float(distribution.alpha)
        for theta in (*ANGLES, *np.linspace(0.0, 90.0, 19)):
            theta_l = np.radians(np.array([float(theta)]))
            t, mu_l = theta_l.item(), np.cos(theta_l).item()
            row = polar._breakpoints_of_one(brdf, distribution, t, mu_l)[0]
            got = polar_compiled.breakpoints_of_one(t, polar._lobe_offsets_of(alpha),
                                                    polar._compiled_level_angles(brdf, alpha, mu_l))
            np.testing.assert_array_equal(got, row, err_msg=f"{brdf} {theta}")


def _both(brdf, theta, rtol):
    with compiled.numpy_only():
        reference = polar.albedo_many([brdf], [theta], rtol=rtol)
    return reference, polar.albedo_many([brdf], [theta], rtol=rtol)


def test_the_compiled_single_angle_is_the_numpy_path_over_the_grid():
    """Every covered model, the angles from the pole through 1e-6° to 90° − 1e-9° and 90°, rtol 1e-3 …
    1e-12: the same status; where the evaluations agree the value within :data:`VALUE_ULPS` ulps and far
    inside the error; where a refinement decision sat on a threshold (rare) still honest against the
    numpy value ± its error."""
    cells, flips, worst = 0, [], 0.0
    for brdf in _covered():
        for theta in ANGLES:
            for rtol in RTOLS:
                reference, got = _both(brdf, theta, rtol)
                cells += 1
                value, error = float(reference.value[0]), float(reference.error[0])
                delta = abs(float(got.value[0]) - value)
                assert got.status[0] == reference.status[0], (brdf, theta, rtol)
                if got.evaluations != reference.evaluations:
                    flips.append((brdf, theta, rtol))
                    assert delta <= error + float(got.error[0]), (brdf, theta, rtol)
                    continue
                worst = max(worst, delta / (EPS * abs(value)) if EPS * abs(value) > 0 else delta)
                assert delta <= VALUE_ULPS * EPS * abs(value) and delta <= WITHIN_ERROR * error, (brdf, theta, rtol)
                assert abs(float(got.error[0]) - error) <= ERROR_RTOL * error, (brdf, theta, rtol)
    assert cells >= 300 and len(flips) <= FLIP_SHARE * cells, (cells, flips)
    print(f"{cells} cells, worst |Δ|/ε|value| {worst:.3g}, {len(flips)} decisions flipped")


def test_the_compiled_single_angle_is_honest_against_the_sweeps_independent_truths():
    """Every cell of ``tests/data/sweep_truths.csv`` (a third route, no code of brdfs) whose model the
    kernel covers, one front-door call per angle: |value − truth| ≤ error + truth error at each rtol
    (measured: 0 dishonest of 3,450 calls at rtol 1e-3 … 1e-12, worst 0.82 of the allowance)."""
    import json

    import pandas as pd

    from brdfs import albedo
    from sweep.cells import FAMILY, TRUTHS, build, needs_table

    truths = pd.read_csv(TRUTHS)
    calls = 0
    for (family, params), cells in truths.groupby(["family", "params"]):
        cls = MODELS[FAMILY[family].model]
        if (needs_table(FAMILY[family]) or FAMILY[family].model_class is not None
                or cls.half_vector_factors is BRDF.half_vector_factors):
            continue                     # tables, a user's classes, no factors: none the kernel covers
        brdf = build(family, json.loads(params))
        factors = brdf.half_vector_factors()
        if factors is None or polar_compiled.kernel_of(*factors) is None:
            continue
        for theta, truth, truth_err in zip(cells["theta_deg"], cells["truth"], cells["truth_err"]):
            for rtol in (1e-6, 1e-12):
                est = albedo(brdf, float(theta), rtol=rtol, warn=False)
                assert abs(float(est.value) - truth) <= float(est.error) + truth_err, (family, params, theta, rtol)
                calls += 1
    assert calls >= 1380, calls


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
def test_a_numpy_float_alpha_takes_the_compiled_route_as_its_python_float(name):
    """np.float64 is a float (the same arithmetic): a roughness drawn from numpy answers as the float."""
    plain, drawn = MODELS[name](alpha=0.3), MODELS[name](alpha=np.float64(0.3))
    assert polar_compiled.kernel_of(*drawn.half_vector_factors()) == polar_compiled.kernel_of(*plain.half_vector_factors())
    for theta in (0.0, 30.0, 89.9):
        reference, got = _both(drawn, theta, 1e-10)
        assert got.evaluations == reference.evaluations and got.status[0] == reference.status[0]
        assert abs(got.value[0] - reference.value[0]) <= VALUE_ULPS * EPS * reference.value[0]
        assert got.value[0] == polar.albedo_many([plain], [theta], rtol=1e-10).value[0]


class _OwnGGX(GGX):
    """A user's distribution: a subclass may change any formula."""


def test_only_the_factors_the_kernel_knows_take_it_the_rest_the_numpy_path():
    ggx = MODELS["ggx"](alpha=0.3)
    distribution, S = ggx.half_vector_factors()
    assert polar_compiled.kernel_of(distribution, S) is not None
    assert polar_compiled.kernel_of(_OwnGGX(0.3), S) is None                        # not its distribution
    assert polar_compiled.kernel_of(distribution, lambda nl, nv: S(nl, nv)) is None  # a user's S
    # a numpy α is kept as the Python float it equals (check_declared_parameters): the kernel of that float
    plain = polar_compiled.kernel_of(*MODELS["ggx"](alpha=float(np.float32(0.3))).half_vector_factors())
    assert polar_compiled.kernel_of(*MODELS["ggx"](alpha=np.float32(0.3)).half_vector_factors()) == plain
    assert polar_compiled.kernel_of(*MODELS["ggx"](alpha=np.array(0.3)).half_vector_factors()) == \
        polar_compiled.kernel_of(distribution, S)
    assert polar_compiled.kernel_of(*MODELS["cook_torrance"](m=0.3, G="smith", C=2).half_vector_factors()) is None

    class OwnMasking(MODELS["ggx"]):
        def g2_over_4_nl_nv(self, nl, nv):
            return 2.0 * super().g2_over_4_nl_nv(nl, nv)

    own = OwnMasking(alpha=0.3)
    assert polar_compiled.kernel_of(*own.half_vector_factors()) is None
    doubled = polar.albedo_many([own], [30.0]).value[0]
    assert math.isclose(doubled, 2.0 * polar.albedo_many([ggx], [30.0]).value[0], rel_tol=1e-9)


# --- the masking the model declares, and nothing else, is what the kernel computes ---------------------

def _same_on_both_paths(brdf, angles=(0.0, 30.0, 60.0, 89.9), rtol=1e-8):
    """The single angle with the compiled route (where it takes it) and on numpy alone: the same status and
    evaluations, the values within :data:`VALUE_ULPS`."""
    for theta in angles:
        reference, got = _both(brdf, theta, rtol)
        assert got.status[0] == reference.status[0] and got.evaluations == reference.evaluations, (brdf, theta)
        assert abs(got.value[0] - reference.value[0]) <= VALUE_ULPS * EPS * reference.value[0], (
            brdf, theta, got.value[0], reference.value[0])


class _TwoRoughness(MODELS["cook_torrance"]):
    """A user's Cook–Torrance whose polar factors have facets of roughness ``m_d`` and the thesis's Smith
    G* of roughness m: the compiled polar route gave 0.93168 against the numpy polar route's 0.97578 at 0°
    (m = 0.1, m_d = 0.3).  Only the polar factors change: Cook–Torrance's own f (``_eval``, which the disk
    integrates) is not written from them, so the disk answers another BRDF (noticed, left: the note)."""

    @property
    def distribution(self):
        return type(super().distribution)(3.0 * self.m)


class _WiderFacets(MODELS["ggx"]):
    """A user's GGX whose facets are twice as rough as the λ of its Smith masking."""

    def half_vector_factors(self):
        return type(self.distribution)(2.0 * self.alpha), self.g2_over_4_nl_nv


@pytest.mark.parametrize("brdf", [_TwoRoughness(m=0.1, G="smith"), _TwoRoughness(m=0.1, G="smith", C=0.5),
                                  _WiderFacets(alpha=0.3), _WiderFacets(alpha=0.3, G2="separable")],
                         ids=["cook_torrance", "cook_torrance_C", "ggx", "ggx_separable"])
def test_a_masking_whose_roughness_is_not_the_facets_answers_as_numpy(brdf):
    """The masking's roughness is the masking's own (the form the model declares), not the distribution's."""
    _same_on_both_paths(brdf)


class _DoubledGGX(GGX):
    """A user's distribution: GGX's formulas, its azimuthal integral doubled."""

    def azimuthal_integral(self, q, b):
        value, rounding = super().azimuthal_integral(q, b)
        return 2.0 * value, 2.0 * rounding


class _DoubledLambdaGGX(GGX):
    """A user's distribution whose Smith λ is doubled."""

    def smith_lambda_cos(self, cos_theta):
        return 2.0 * super().smith_lambda_cos(cos_theta)


class _OwnFacets(MODELS["ggx"]):
    """A user's GGX model on :class:`_DoubledGGX` facets (its masking's λ of the same)."""

    distribution_type = _DoubledGGX


class _OwnMaskingDistribution(MODELS["ggx"]):
    """A user's GGX model: GGX's own facets, its masking's λ of :class:`_DoubledLambdaGGX`."""

    distribution_type = _DoubledLambdaGGX

    def half_vector_factors(self):
        return GGX(self.alpha), self.g2_over_4_nl_nv


@pytest.mark.parametrize("brdf", [_OwnFacets(alpha=0.3), _OwnMaskingDistribution(alpha=0.3)],
                         ids=["facets", "masking"])
def test_a_users_distribution_takes_the_numpy_path_even_as_a_subclass_of_a_known_one(brdf):
    """By exact type: a subclass of GGX may change any formula (here its Φ, or its λ), which the kernel
    does not know."""
    assert polar_compiled.kernel_of(*brdf.half_vector_factors()) is None
    _same_on_both_paths(brdf, angles=(0.0, 30.0))
    plain = MODELS["ggx"](alpha=0.3)
    with compiled.numpy_only():
        reference = polar.albedo_many([brdf], [30.0], rtol=1e-8).value[0]
    assert not math.isclose(reference, polar.albedo_many([plain], [30.0], rtol=1e-8).value[0], rel_tol=1e-3)
