"""One angle at a time (issue 24, "Fast on one angle and at loose tolerances"): what a single-angle
call saves is decided once per call, not paid for once per round, and its first partition is fine
enough that a loose tolerance needs no refinement round at all.  Counts, not times (the times are
``benchmarks/bench_engine_speed.py``'s ratios)."""
import numpy as np
import pytest

from brdfs.numerics import albedo as front_door
from brdfs.numerics.arguments import method_options
from brdfs.numerics.integrate import azimuthal
from brdfs.physics.models import model

CASES = [("phong", {"n": 150}), ("blinn_cosmin", {"n": 2}), ("ward", {"m": 0.1})]


def _rounds(monkeypatch, brdf, theta, rtol):
    """The estimate of one angle by the 1-D route and the number of times it evaluated its integrand."""
    calls = []
    integrate = azimuthal.integrate

    def counting(integrand, bp, **kwargs):
        return integrate(lambda t, elem: (calls.append(t.shape[0]), integrand(t, elem))[1], bp, **kwargs)

    monkeypatch.setattr(azimuthal, "integrate", counting)
    est = azimuthal.albedo_many([brdf], np.array([theta]), rtol=rtol)
    return est, len(calls)


@pytest.mark.parametrize("name, params", CASES)
def test_one_angle_meets_a_loose_tolerance_on_its_first_partition(monkeypatch, name, params):
    brdf = model(name, **params)
    tight = azimuthal.albedo_many([brdf], np.array([48.5]), rtol=1e-13)
    loose, rounds = _rounds(monkeypatch, brdf, 48.5, 1e-6)
    assert rounds == 1
    assert loose.status[0] == "converged"
    assert abs(loose.value[0] - tight.value[0]) <= loose.error[0] + tight.error[0]


@pytest.mark.parametrize("name, params", CASES)
def test_a_loose_tolerance_costs_at_most_half_the_evaluations_of_a_tight_one(name, params):
    brdf = model(name, **params)
    theta = np.linspace(0.0, 89.0, 6)
    cost = {rtol: sum(front_door.albedo(brdf, float(t), rtol=rtol).evaluations for t in theta) for rtol in (1e-6, 1e-10)}
    assert cost[1e-6] <= 0.5 * cost[1e-10]


def test_a_methods_options_are_read_once_per_method():
    """``inspect.signature`` of the method on every call cost a single-angle call more than its
    integration's bookkeeping: the options are read once and shared."""
    method = front_door.ALBEDO_METHODS["product_grid"]
    assert method_options(method) is method_options(method)
    assert list(method_options(method)) == ["n"]


@pytest.mark.parametrize("name, params", [("phong", {"n": 150}), ("phong_cosmin", {"n": 128}), ("ward", {"m": 0.1})])
def test_one_angle_meets_a_tight_tolerance_on_its_first_partition(monkeypatch, name, params):
    """At rtol 1e-10 the tail graded by half decades (``TIGHT_SINGLE_ANGLE_TAIL``) leaves no interval
    to refine: one evaluation of the integrand, and a value within its error of a 1e-13 one."""
    brdf = model(name, **params)
    tight = azimuthal.albedo_many([brdf], np.array([48.5]), rtol=1e-13)
    est, rounds = _rounds(monkeypatch, brdf, 48.5, 1e-10)
    assert rounds == 1
    assert est.status[0] == "converged"
    assert abs(est.value[0] - tight.value[0]) <= est.error[0] + tight.error[0]


@pytest.mark.parametrize("name, params", [("phong", {"n": 150}), ("blinn_cosmin", {"n": 2}), ("ward", {"m": 0.1}),
                                          ("cook_torrance", {"m": 0.1}), ("ggx", {"alpha": 0.3})])
@pytest.mark.parametrize("theta", [0.0, 48.5, 89.99999, 90.0])
def test_one_float_angle_answers_as_an_array_of_one_angle_does(name, params, theta):
    """The lean single-angle door (``_one_angle_in_closed_form``) gives what the general path gives
    an array of one angle, to the bit: value, error, status, route and evaluations."""
    brdf = model(name, **params)
    one, array = front_door.albedo(brdf, theta, rtol=1e-8), front_door.albedo(brdf, [theta], rtol=1e-8)
    assert np.shape(one.value) == np.shape(one.status) == np.shape(one.route) == ()
    assert (float(one.value), float(one.error), str(one.status), str(one.route), one.evaluations) == (
        float(array.value[0]), float(array.error[0]), str(array.status[0]), str(array.route[0]), array.evaluations)
