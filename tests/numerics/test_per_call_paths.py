"""The short ways of a single call (issue 41, "per-call cost") give the answers of the long ways, to the
bit: a single angle on an engine route without the plan, the polar route's breakpoints of one row, the
lens of one element, a patch mixture's second pass that takes its first intervals' values from the
rough pass or is not run where the rough pass met the target at once.  Their speed is
``benchmarks/bench_engine_speed.py --models``'s; here only their answers."""
import numpy as np
import pytest

import brdfs
from brdfs.numerics import albedo as front_door
from brdfs.numerics.arguments import Tolerance
from brdfs.numerics.integrate import polar
from brdfs.physics import patch_geometry as patch
from brdfs.physics.models import BRDF

ANGLES = (0.0, 1e-6, 45.0, 89.9)


def _engine_routed():
    """The typical example of every registered model whose single angles take an engine route."""
    out = []
    for name, cls in brdfs.MODELS.items():
        brdf = cls.example("typical")
        if type(brdf).albedo_estimate is BRDF.albedo_estimate and front_door._refusal(brdf) is None:
            out.append(pytest.param(brdf, id=name))
    return out


@pytest.mark.parametrize("brdf", _engine_routed())
@pytest.mark.parametrize("rtol", [1e-10, 1e-6])
def test_a_single_angle_on_an_engine_route_answers_as_the_plan_does(brdf, rtol):
    tol = Tolerance(rtol)
    dirac = type(brdf).delta_albedo is not BRDF.delta_albedo         # added by the plan's merge
    for theta in ANGLES:
        short = front_door._by_its_engine_route(brdf, np.asarray(theta), tol, "auto")
        planned = front_door._answer([brdf], np.array([theta]), tol, "auto")
        if dirac:
            assert short is None
            continue
        for field in ("value", "error", "status", "route"):
            np.testing.assert_array_equal(getattr(short, field), getattr(planned, field), err_msg=field)
        assert short.evaluations == planned.evaluations
        public = brdfs.albedo(brdf, theta, rtol=rtol)
        assert float(public.value) == short.value[0] and public.evaluations == short.evaluations


def test_a_single_angle_its_route_leaves_short_goes_on_as_the_plan_does():
    """The first model and angle whose engine route stalls: the short way runs the route once and
    goes on to the disk as the plan does (not from the start again)."""
    tol = Tolerance(1e-10)
    for brdf in (p.values[0] for p in _engine_routed()):
        route = front_door.ENGINE_ROUTES[front_door._engine_route(brdf)]
        for theta in (89.0, 89.9):
            if route([brdf], np.array([theta]), rtol=tol.rtol, atol=tol.atol).status[0] == "converged":
                continue
            calls = []
            front_door.ENGINE_ROUTES[front_door._engine_route(brdf)] = lambda *a, **k: (calls.append(1), route(*a, **k))[1]
            try:
                short = front_door._by_its_engine_route(brdf, np.asarray(theta), tol, "auto")
            finally:
                front_door.ENGINE_ROUTES[front_door._engine_route(brdf)] = route
            planned = front_door._answer([brdf], np.array([theta]), tol, "auto")
            assert len(calls) == 1 and np.ravel(short.route)[0] == np.ravel(planned.route)[0]
            for field in ("value", "error", "status"):
                np.testing.assert_array_equal(getattr(short, field), getattr(planned, field), err_msg=field)
            assert short.evaluations == planned.evaluations
            return
    pytest.fail("no registered model's engine route stalls at 89° or 89.9° at rtol 1e-10")


def test_the_short_way_leaves_to_the_plan_what_it_cannot_answer_alone():
    ward = brdfs.model("ward", m=0.1)             # +inf at 90°, declared
    assert front_door._by_its_engine_route(ward, np.asarray(90.0), Tolerance(), "auto") is None
    phong = brdfs.model("phong", n=20)
    assert front_door._by_its_engine_route(phong, np.asarray([10.0, 20.0]), Tolerance(), "auto") is None
    assert front_door._by_its_engine_route(phong, np.asarray(10.0), Tolerance(), "disk") is None
    reported = []
    with front_door.reporting_progress(lambda done, total: reported.append((done, total))):
        brdfs.albedo(phong, 10.0)
    assert reported == [(1, 1)]


@pytest.mark.parametrize("name, params", [("ggx", {"alpha": 0.3}), ("ggx", {"alpha": 0.01}),
                                          ("beckmann", {"alpha": 1.0}), ("cook_torrance", {"m": 0.3, "G": "smith"})])
def test_the_polar_breakpoints_of_one_row_are_those_of_a_batch(name, params):
    brdf, other = brdfs.model(name, **params), brdfs.model("ggx", alpha=0.05)
    for theta in (0.0, 1e-9, 30.0, 80.0, 89.9, 90.0 - 1e-7, 90.0):
        one = polar.breakpoints([brdf], np.radians([theta]))
        batch = polar.breakpoints([brdf, other], np.radians([theta, 60.0]))[0]
        np.testing.assert_array_equal(one[0], batch[np.isfinite(batch)])


def test_the_lens_of_one_element_is_its_lens_in_a_batch():
    theta = np.array([0.0, 1e-6, 20.0, 31.0, 45.0, 75.0, 89.9, 90.0 - 1e-9, 90.0])
    d, mu = np.sin(np.radians(theta)), patch._cos_incidence_near_grazing(theta)
    for R in (1e-9, 0.05, 0.5, 1.0, 1.7, 2.0):       # nested, apart, near and general forms mixed
        for cos in (None, mu):
            batch = patch.circle_intersection(d, R, cos)
            for k in range(theta.size):
                one = patch.circle_intersection(d[k:k + 1], R, None if cos is None else cos[k:k + 1])
                for field, a, b in zip(patch.Lens._fields, one, batch):
                    assert a[0] == b[k], (field, R, theta[k], cos is None)


def test_a_mixtures_second_pass_takes_the_values_it_would_compute(monkeypatch):
    profile = patch.ExponentialProfile(4.0)
    theta = np.array([30.0])
    est = patch.mixture_albedo(profile, theta, rtol=1e-10)
    calls = []
    basic = patch.basic_albedo_at
    monkeypatch.setattr(patch, "basic_albedo_at", lambda *a: (calls.append(1), basic(*a))[1])
    monkeypatch.setattr(patch.np, "array_equal", lambda *a: False)          # never the same intervals
    again = patch.mixture_albedo(profile, theta, rtol=1e-10)
    assert again.value[0] == est.value[0] and again.error[0] == est.error[0]
    monkeypatch.undo()
    kept = []
    monkeypatch.setattr(patch, "basic_albedo_at", lambda *a: (kept.append(1), basic(*a))[1])
    patch.mixture_albedo(profile, theta, rtol=1e-10)
    assert len(kept) == len(calls) - 1


def test_a_mixtures_single_angle_met_at_once_skips_the_second_pass_with_its_answer(monkeypatch):
    """A graded single angle that meets its target on the first evaluation runs the driver once, and
    answers what the second pass (forced: the rough pass reported as refined) would have, to the bit."""
    profile = patch.ExponentialProfile(4.0)
    runs = []
    integrate = patch.integrate
    monkeypatch.setattr(patch, "integrate", lambda *a, **k: (runs.append(1), integrate(*a, **k))[1])

    def refined(*args, **kwargs):        # the rough pass reported as refined: the second pass runs
        runs.append(1)
        out = integrate(*args, **kwargs)
        return (out[0], out[1] + 1) if kwargs.get("return_rounds") else out

    for rtol in (1e-10, 1e-6):
        for theta in (0.0, 30.0, 89.9):
            runs.clear()
            once = patch.mixture_albedo(profile, np.array([theta]), rtol=rtol, single_graded=True)
            assert len(runs) == 1
            with monkeypatch.context() as forced:
                forced.setattr(patch, "integrate", refined)
                twice = patch.mixture_albedo(profile, np.array([theta]), rtol=rtol, single_graded=True)
            assert len(runs) == 3
            assert once.value[0] == twice.value[0] and once.error[0] == twice.error[0]


def test_a_model_changed_after_building_is_checked_again_by_the_front_door():
    """The facts kept per model object are kept for its values: a parameter set after building (a
    plain user class can, a frozen one through object.__setattr__) is refused by albedo() as if the
    model had been built with it, even after a call that found the model within its ranges."""
    m = brdfs.model("phong", n=20)
    assert brdfs.albedo(m, 30.0).status == "converged"
    object.__setattr__(m, "n", -5.0)
    with pytest.raises(brdfs.ArgumentError, match=r"model\.n = -5\.0"):
        brdfs.albedo(m, 30.0)


def test_facts_kept_per_model_object_are_its_own_and_go_with_it():
    """The front doors keep a model object's facts (its declared ranges checked, its single angle's
    route) by identity while it lives: an equal model is another object, a dead one's facts are gone,
    and a fact whose finding raised is looked for again."""
    import gc

    from brdfs.numerics.arguments import PerModel

    kept, found = PerModel(), []
    first, second = brdfs.model("phong", n=20), brdfs.model("phong", n=20)
    assert kept.get(first, "k", lambda: found.append(1) or "first") == "first"
    assert kept.get(first, "k", lambda: found.append(2) or "again") == "first"
    assert kept.get(second, "k", lambda: found.append(3) or "second") == "second" and found == [1, 3]

    def refused():
        found.append(4)
        raise ValueError("bad")
    for _ in range(2):
        with pytest.raises(ValueError):
            kept.get(second, "bad", refused)
    assert found == [1, 3, 4, 4]
    del first
    gc.collect()
    assert [at[0] for at in kept._kept] == [id(second)]
