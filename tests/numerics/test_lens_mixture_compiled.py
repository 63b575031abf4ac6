"""A single angle of a lens mixture's own route, compiled (:mod:`brdfs.numerics.lens_mixture`), answers as
the numpy route does: over every lens-mixture model's examples and the ends of its declared parameters,
a box and a triangle weight with declared points, angles from 0 through 1e-6° to 90° − 1e-9° and 90°,
and rtol 1e-3 … 1e-12, through the front door: the same status, route, warning and evaluations, the same
nodes of p(R) evaluated (bar threshold flips, counted), the value within a few ε |value| and far inside
the reported error, the error within a small fraction of itself."""
import contextlib
import functools
import itertools
import warnings

import numpy as np
import pytest

import brdfs
from brdfs.core import compiled
from brdfs.physics.models import MODELS
from brdfs.physics.models.patch import BoxWeight, LensMixtureAlbedo

pytest.importorskip("numba")
if not compiled.available():
    pytest.skip("the compiled routes are switched off", allow_module_level=True)

from brdfs.numerics import lens_mixture  # noqa: E402  (after the skip: it compiles)

from front_door_cells import answer, calls  # noqa: E402

_EPS = np.finfo(float).eps
ANGLES = (0.0, 1e-6, 1e-3, 30.0, 60.0, 89.0, 89.9999, 90.0 - 1e-9, 90.0)
RTOLS = (1e-3, 1e-6, 1e-8, 1e-10, 1e-12)
#: |Δ value| ≤ VALUE_ULPS ε |value| (libm's sin, atan2 and pow where numpy's arrays take SIMD loops; the
#: Kronrod and Gauss sums BLAS products there, loops here; measured: 1.5 over 1,080 cells), and ≤ INSIDE_ERROR of
#: the smaller error (measured: 2.5 %, where the error is itself a few ulps of the value).
VALUE_ULPS = 4
INSIDE_ERROR = 0.05
#: |Δ error| ≤ ERROR_SHARE of the error: its Σ|K − G| sums differences that are rounding where an interval
#: is resolved (measured: 5 %, at 1e-6°).
ERROR_SHARE = 0.1
#: Cells whose evaluations may differ (a refinement decision on a threshold: the sums' last ulps).
MOST_FLIPS = 3


def _lens_mixture_models():
    """Every registered model whose own albedo route is the lens mixture's (a fact of its class)."""
    return {name: cls for name, cls in MODELS.items() if cls.albedo_estimate is LensMixtureAlbedo.albedo_estimate}


def _ends(cls):
    """Parameter sets: the examples (and feature examples), and the typical one at each finite closed end of a
    declared range and at the ends of the generic tests' draw ranges (a zero they add included)."""
    typical = cls.examples["typical"]
    sets = [dict(example) for example in (*cls.examples.values(), *getattr(cls, "feature_examples", {}).values())]
    for key, interval in cls.param_ranges.items():
        ends = [end for end, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open))
                if np.isfinite(end) and not is_open]
        draw = cls.test_ranges.get(key)
        if draw is not None:
            ends += [draw.lo, draw.hi] + ([0.0] if draw.zero else [])
        sets += [{**typical, key: end} for end in ends]
    return [dict(items) for items in dict.fromkeys(tuple(s.items()) for s in sets)]


def _user_weighted():
    """The lens mixture that takes a user's weight p(R) (with its ``weight_points``)."""
    return next(cls for cls in _lens_mixture_models().values() if "weight_points" in cls.__dataclass_fields__)


def _triangle(R):
    """A triangle of width 0.2 at R = 0.6: kinks at 0.5, 0.6, 0.7."""
    return np.maximum(0.0, 1.0 - np.abs(np.asarray(R, float) - 0.6) / 0.1) / 0.1


def _models():
    out = []
    for name, cls in sorted(_lens_mixture_models().items()):
        for params in _ends(cls):
            out.append((f"{name} {params}", cls(**params)))
    mixture = _user_weighted()
    box = BoxWeight(0.3, 0.45)
    out.append(("patch_mixture box", mixture(weight=box, p_diffuse=0.25, weight_points=box.points)))
    out.append(("patch_mixture triangle", mixture(weight=_triangle, weight_points=(0.5, 0.6, 0.7))))
    return out


class _Counted:
    """A weight that counts the nodes it is evaluated at."""

    def __init__(self, weight):
        self.weight, self.nodes = weight, 0

    def __call__(self, R):
        self.nodes += np.size(R)
        return self.weight(R)


def _counting(brdf):
    """``brdf`` whose declared lens mixture's weight counts its nodes (both routes read the declaration)."""
    mixture = brdf.lens_mixture()
    counted = _Counted(mixture.weight)
    object.__setattr__(brdf, "lens_mixture", lambda: mixture._replace(weight=counted))
    return brdf, counted


def _call(brdf, counted, theta, rtol):
    counted.nodes = 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        est = brdfs.albedo(brdf, theta, rtol=rtol)
    return est, len(caught), counted.nodes


@functools.cache
def _grid():
    """Every cell: (label, θ, rtol, numpy's (Estimate, warnings, nodes), the compiled route's)."""
    cells = []
    for label, brdf in _models():
        brdf, counted = _counting(brdf)
        for theta in ANGLES:
            for rtol in RTOLS:
                with compiled.numpy_only():
                    reference = _call(brdf, counted, theta, rtol)
                cells.append((label, theta, rtol, reference, _call(brdf, counted, theta, rtol)))
    return cells


def test_the_grid_covers_every_lens_mixture_model_at_its_examples_and_ends():
    labels = {label.split()[0] for label, *_ in _grid()}
    assert labels == set(_lens_mixture_models())
    assert len(labels) >= 3
    assert len(_grid()) >= 1000 and any(brdf.has_evaluation_error for _, brdf in _models())


def test_the_compiled_route_answers_with_the_numpy_routes_status_route_and_warnings():
    for label, theta, rtol, (a, warned_a, _), (b, warned_b, _) in _grid():
        cell = (label, theta, rtol)
        facts = [(str(e.status), str(e.route), warned, e.evaluations) for e, warned in ((a, warned_a), (b, warned_b))]
        assert facts[1] == facts[0], cell
        assert str(b.route) == "engine/own" and np.shape(b.value) == ()


def test_the_compiled_routes_value_is_the_numpy_routes_within_a_few_ulps_and_far_inside_its_error():
    worst = 0.0
    for label, theta, rtol, (a, *_), (b, *_) in _grid():
        delta = abs(float(b.value) - float(a.value))
        scale = _EPS * abs(float(a.value))
        worst = max(worst, delta / scale if scale else (0.0 if delta == 0 else np.inf))
        assert delta <= VALUE_ULPS * scale, (label, theta, rtol, float(a.value), float(b.value))
        assert delta <= INSIDE_ERROR * min(float(a.error), float(b.error)), (label, theta, rtol)
        assert abs(float(b.error) - float(a.error)) <= ERROR_SHARE * float(a.error), (label, theta, rtol)
    print(f"worst |Δ value| / ε |value| = {worst:.3g} over {len(_grid())} cells")


def test_the_compiled_route_evaluates_p_on_the_same_nodes_but_for_rare_threshold_flips():
    flips = [(label, theta, rtol, na, nb) for label, theta, rtol, (_, _, na), (_, _, nb) in _grid() if na != nb]
    print(f"{len(flips)} threshold flips: {flips}")
    assert len(flips) <= MOST_FLIPS, flips
    assert all(nb > 0 for *_, (_, _, nb) in _grid())


def test_the_front_doors_stored_single_angle_cells_of_lens_mixtures_hold_compiled():
    """The stored front-door cells (``front_door_cells.npz``, held to the bit on the numpy route) that take the
    compiled route, single angles of the lens-mixture models: the same status, route, warning, evaluations
    and shape, the value within the tolerances above."""
    with np.load(front_door_cells_data()) as data:
        stored = {k: data[k] for k in data.files}
    models = _lens_mixture_models()
    checked = 0
    for k, (label, name, call) in enumerate(calls()):
        if name not in models or not label.startswith("single"):
            continue
        rows = stored["call"] == k
        value, error, status, route, evaluations, warned, shape = answer(call)
        assert list(status) == list(stored["status"][rows])
        assert list(route) == list(stored["route"][rows]) == ["engine/own"]
        assert (evaluations, warned) == (stored["per_call"][k, 0], bool(stored["per_call"][k, 1])) and shape == ()
        delta = np.abs(value - stored["value"][rows])
        assert np.all(delta <= VALUE_ULPS * _EPS * np.abs(stored["value"][rows])), label
        assert np.all(delta <= INSIDE_ERROR * stored["error"][rows]), label
        checked += 1
    assert checked >= 3 * len(models)


def front_door_cells_data():
    from front_door_cells import DATA
    return DATA


def test_the_compiled_route_is_the_models_own_and_leaves_batches_and_overrides_to_numpy():
    """A batch of angles, a subclass with its own ``albedo_estimate``, and numpy_only() take the model's
    ``albedo_estimate``; a single angle the compiled route."""
    brdf = MODELS["patch_exponential"].example("typical")
    taken = []
    original = lens_mixture.compiled_lens_albedo

    def spy(*args, **kwargs):
        taken.append(args[1])
        return original(*args, **kwargs)

    class Declining(type(brdf)):
        def albedo_estimate(self, theta_deg, rtol, atol):
            return None

    lens_mixture.compiled_lens_albedo = spy
    try:
        lens_mixture.own_albedo_estimate(brdf, np.array([30.0]), 1e-8, 1e-14)
        assert len(taken) == 1
        lens_mixture.own_albedo_estimate(brdf, np.array([30.0, 40.0]), 1e-8, 1e-14)
        with compiled.numpy_only():
            lens_mixture.own_albedo_estimate(brdf, np.array([30.0]), 1e-8, 1e-14)
        assert lens_mixture.own_albedo_estimate(Declining(s=4.0), np.array([30.0]), 1e-8, 1e-14) is None
        assert len(taken) == 1
    finally:
        lens_mixture.compiled_lens_albedo = original


def _node_cases():
    """(d, R, cos θ) at random angles and radii, and at and next to the lens's kinks R = 1 ∓ d, 1 − cos²θ/(1 + d)
    (where the near-unit form's y_rel grows), R = 1, a tiny R and 2: rows of 42 radii."""
    rng = np.random.default_rng(41)
    theta = np.concatenate([rng.uniform(0.0, 90.0, 120), [0.0, 1e-6, 1e-3, 89.9999, 90.0 - 1e-9, 90.0]])
    d, mu = np.sin(np.radians(theta)), np.sin(np.radians(90.0 - theta))
    u = mu * mu / (1.0 + d)
    kinks = np.stack([1.0 - d, 1.0 + d, u, np.ones_like(d), np.full_like(d, 1e-150), np.full_like(d, 2.0)], 1)
    R = np.concatenate([rng.uniform(0.0, 2.0, (theta.size, 24)), kinks, kinks * (1 + 1e-9), kinks * (1 - 1e-9)], 1)
    return d, mu, np.where((R > 0.0) & (R <= 2.0), R, 1.0)


def test_the_compiled_lens_area_is_the_numpy_one_node_by_node():
    """a_R(d) and its rounding bound node by node against :func:`basic_albedo_at`'s arrays: the value within
    VALUE_ULPS ε |value|, the bound within 1e-12 of itself (its sines are y/√(x² + y²), not libm's)."""
    from brdfs.numerics import lens_mixture_compiled as lmc
    from brdfs.physics.patch_geometry import basic_albedo_at

    d, mu, R = _node_cases()
    for k in range(d.size):
        expected = basic_albedo_at(np.full(R.shape[1], d[k]), R[k], np.full(R.shape[1], mu[k]))
        value, error = lmc.lens_values(R[k].reshape(-1, 21), np.ones((R.shape[1] // 21, 21)), d[k], mu[k], False)
        bound = VALUE_ULPS * _EPS * np.abs(expected.value)
        assert np.all(np.abs(value.ravel() - expected.value) <= bound), (d[k], R[k])
        assert np.all(np.abs(error.ravel() - expected.error) <= 1e-12 * expected.error), (d[k], R[k])


def test_the_compiled_first_partition_is_the_numpy_one_to_the_bit():
    """``single_element_partition`` against ``patch_geometry._single_element_partition`` over the declared points
    of every example (and points at and past the ends of [0, 2]), steep layers, angles to 90° and the
    tolerances of every grading level: equal arrays."""
    from brdfs.numerics import lens_mixture_compiled as lmc
    from brdfs.physics.patch_geometry import _single_element_partition, lens_kink_levels

    declared = {(brdf.lens_mixture().points, brdf.lens_mixture().steep_layer) for _, brdf in _models()}
    cases = declared | {((0.0, 2.0), None), ((1e-3, 1.0 + 1e-12), None), ((), (2.0 - 1e-6, 2.0)), ((0.3,), (0.05, 2.0))}
    rng = np.random.default_rng(7)
    d = np.concatenate([np.sin(np.radians(ANGLES)), rng.uniform(0.0, 1.0, 40)])
    for points, layer in cases:
        for k, rtol in zip(d, itertools.cycle((1e-10, 1e-9, 1e-8, 1e-6, 1e-4, 1e-2))):
            expected = _single_element_partition(points, float(k), layer, rtol)
            got = lmc.single_element_partition(np.array(points, float), float(k), layer is not None,
                                               *(layer or (0.0, 0.0)), lens_kink_levels(rtol))
            assert got.shape == expected.shape and np.array_equal(got, expected), (points, layer, k, rtol)


def _both_paths(brdf, theta=30.0, rtol=1e-10):
    """(numpy's answer, the compiled route's), each an Estimate or the type of what it raised."""
    out = []
    for switch in (compiled.numpy_only, contextlib.nullcontext):
        with switch(), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                out.append(brdfs.albedo(brdf, theta, rtol=rtol))
            except Exception as exc:  # noqa: BLE001
                out.append(type(exc))
    return out


def test_parameters_given_as_float32_or_0d_arrays_answer_alike_on_both_paths():
    """A float32 p_diffuse summed on the compiled route rounded value and error to float32 (4.1e-8 off at a
    reported 4e-13, "converged"); a 0-d array parameter crashed the numpy route (unhashable) and not the
    compiled one.  Every numeric parameter of every lens mixture's typical example, as float32 and 0-d."""
    cases = 0
    for cls in _lens_mixture_models().values():
        typical = cls.examples["typical"]
        for key, value in typical.items():
            if not isinstance(value, float):
                continue
            for given in (np.float32(value), np.array(value), np.float16(value)):
                numpy_answer, compiled_answer = _both_paths(cls(**{**typical, key: given}))
                assert isinstance(numpy_answer, brdfs.Estimate), (cls.name, key, given, numpy_answer)
                assert abs(float(compiled_answer.value) - float(numpy_answer.value)) <= 4 * _EPS * abs(
                    float(numpy_answer.value)), (cls.name, key, type(given))
                cases += 1
    mixture = _user_weighted()
    for given in (np.float32(0.25), np.float16(0.25)):
        numpy_answer, compiled_answer = _both_paths(mixture(weight=lambda R: 0.5 + 0 * np.asarray(R), p_diffuse=given))
        assert abs(float(compiled_answer.value) - float(numpy_answer.value)) <= 4 * _EPS * float(numpy_answer.value)
        assert compiled_answer.error.dtype == np.float64
        cases += 1
    assert cases >= 8


def test_a_complex_weight_is_refused_in_one_line_when_the_model_is_built():
    """It was an error on the numpy route and a value (its real part) on the compiled one."""
    with pytest.raises(ValueError, match="weight p.R. must be real"):
        _user_weighted()(weight=lambda R: np.full(np.shape(R), 0.5 + 0j))
