"""One angle at a time (issue 24, "Fast on one angle and at loose tolerances"): what a single-angle
call saves is decided once per call, not paid for once per round, and its first partition is fine
enough that a loose tolerance needs no refinement round at all.  Counts, not times (the times are
``benchmarks/bench_engine_speed.py``'s ratios)."""
import numpy as np
import pytest

from brdfs.core import compiled
from brdfs.numerics import albedo as front_door
from brdfs.numerics.arguments import method_options
from brdfs.numerics.integrate import azimuthal, hemisphere
from brdfs.physics.models import model

CASES = [("phong", {"n": 150}), ("blinn_cosmin", {"n": 2}), ("ward", {"m": 0.1})]


def _rounds(monkeypatch, brdf, theta, rtol):
    """The estimate of one angle by the 1-D route and the number of times it evaluated its integrand."""
    calls = []
    integrate = azimuthal.integrate

    def counting(integrand, bp, **kwargs):
        return integrate(lambda t, elem: (calls.append(t.shape[0]), integrand(t, elem))[1], bp, **kwargs)

    monkeypatch.setattr(azimuthal, "integrate", counting)
    with compiled.numpy_only():      # the numpy path's rounds (the compiled one's evaluations are the same:
        est = azimuthal.albedo_many([brdf], np.array([theta]), rtol=rtol)     # test_azimuthal_compiled)
    return est, len(calls)


def _assert_converges_on_its_first_partition(monkeypatch, name, params, rtol, theta=48.5):
    """One driver round at ``rtol`` (at ``theta``), converged, within its error of a 1e-13 answer."""
    brdf = model(name, **params)
    tight = azimuthal.albedo_many([brdf], np.array([theta]), rtol=1e-13)
    est, rounds = _rounds(monkeypatch, brdf, theta, rtol)
    assert rounds == 1
    assert est.status[0] == "converged"
    assert abs(est.value[0] - tight.value[0]) <= est.error[0] + tight.error[0]


@pytest.mark.parametrize("name, params", CASES)
def test_one_angle_meets_a_loose_tolerance_on_its_first_partition(monkeypatch, name, params):
    _assert_converges_on_its_first_partition(monkeypatch, name, params, 1e-6)


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
    _assert_converges_on_its_first_partition(monkeypatch, name, params, 1e-10)


@pytest.mark.parametrize("theta", [8.09, 24.27, 40.45, 64.73, 72.82])
def test_a_wide_lobes_level_onsets_are_graded_for_a_tight_tolerance(monkeypatch, theta):
    """Corrected Blinn, n = 2: its N·V = N·L level touches the circles where its layer is as wide as
    its radius, and the radial integrand closes onto that radius like (β_c − β)^(3/2); the range ends
    short of t = 1 and the horizon onset lies 1.1 t0 from the next breakpoint.  Graded toward all
    three (``radial_breakpoints_many(graded=True)``, ``horizon_onset(min_span=1)``), its first partition
    meets rtol 1e-10 where it took a second round at these angles."""
    _assert_converges_on_its_first_partition(monkeypatch, "blinn_cosmin", {"n": 2}, 1e-10, theta)


@pytest.mark.parametrize("name, params", [("phong", {"n": 150}), ("blinn_cosmin", {"n": 2}), ("ward", {"m": 0.1}),
                                          ("cook_torrance", {"m": 0.1}), ("ggx", {"alpha": 0.3})])
@pytest.mark.parametrize("theta", [0.0, 48.5, 89.99999, 90.0])
def test_one_float_angle_answers_as_an_array_of_one_angle_does(name, params, theta):
    """One float angle takes the general path an array of one angle takes (there is no special door
    for it any more), to the bit: value, error, status, route and evaluations, and 0-d shapes."""
    brdf = model(name, **params)
    one, array = front_door.albedo(brdf, theta, rtol=1e-8), front_door.albedo(brdf, [theta], rtol=1e-8)
    assert np.shape(one.value) == np.shape(one.status) == np.shape(one.route) == ()
    assert (float(one.value), float(one.error), str(one.status), str(one.route), one.evaluations) == (
        float(array.value[0]), float(array.error[0]), str(array.status[0]), str(array.route[0]), array.evaluations)


@pytest.mark.parametrize("theta", [48.5, np.linspace(0.0, 89.0, 30)])
def test_the_front_door_decides_what_depends_on_the_model_once_per_call(monkeypatch, theta):
    """Whether a model has its own route, which scheme integrates it and its Dirac part are asked once
    per distinct model, for one angle as for a curve: no per-element bookkeeping in the plan."""
    brdf = model("phong", n=150)
    asked = {"own": 0, "delta": 0}
    cls = type(brdf)
    own, delta = cls.albedo_estimate, cls.delta_albedo
    monkeypatch.setattr(cls, "albedo_estimate", lambda self, *a: (asked.__setitem__("own", asked["own"] + 1), own(self, *a))[1])
    monkeypatch.setattr(cls, "delta_albedo", lambda self, *a: (asked.__setitem__("delta", asked["delta"] + 1), delta(self, *a))[1])
    front_door.albedo(brdf, theta, rtol=1e-6)
    assert asked == {"own": 1, "delta": 1}


def _section_rounds(monkeypatch, rtol, single=True):
    """Rounds of the multisection that places the Torrance–Sparrow switch radii (Cook–Torrance,
    m = 0.1, 48°) in one 1-D albedo call: of one angle, or of the same angle twice (a batch)."""
    rounds = [0]
    multisection = hemisphere._multisection

    def counted(fn, *args):
        return multisection(lambda x: (rounds.__setitem__(0, rounds[0] + 1), fn(x))[1], *args)

    monkeypatch.setattr(hemisphere, "_multisection", counted)
    brdf = model("cook_torrance", m=0.1)
    azimuthal.albedo_many([brdf] * (1 if single else 2), np.full(1 if single else 2, 48.0), rtol=rtol)
    return rounds[0]


def test_a_loose_single_angle_places_its_kink_radii_no_finer_than_its_tolerance_needs(monkeypatch):
    """At rtol 1e-6 a single angle narrows the switch radii to 1e-5 of their distance from the ends
    (``single_angle_root_rtol``), in fewer multisection rounds than a batch's ``ROOT_RTOL`` takes."""
    assert azimuthal.single_angle_root_rtol(1e-6) == pytest.approx(1e-5)
    assert _section_rounds(monkeypatch, 1e-6) < _section_rounds(monkeypatch, 1e-6, single=False)


@pytest.mark.parametrize("m, theta", [(0.05, 89.5), (0.3, 81.82)])
def test_a_kink_radius_found_coarsely_carries_its_misplacement_cost_in_the_error(monkeypatch, m, theta):
    """A switch radius found to 1e-2 of its distance from the ends leaves a kink up to half a bracket
    inside an interval whose nodes may not see it: without the bound J w² of ``_KinkProbes`` the
    reported error was 10.6× (m = 0.05, 89.5°) and 5.4× (m = 0.3, 81.82°) short of the true one at
    rtol 1e-12.  With it the answer is honest against the batch's (radii to ``ROOT_RTOL``)."""
    monkeypatch.setattr(azimuthal, "single_angle_root_rtol", lambda rtol: 1e-2)
    brdf = model("cook_torrance", m=m)
    reference = azimuthal.albedo_many([brdf, brdf], np.array([theta, theta]), rtol=1e-13)
    coarse = azimuthal.albedo_many([brdf], np.array([theta]), rtol=1e-12)
    assert abs(coarse.value[0] - reference.value[0]) <= coarse.error[0] + reference.error[0]


def test_one_angles_breakpoints_on_python_floats_are_the_array_versions_row_to_the_bit(monkeypatch):
    """``hemisphere._radial_breakpoints_of_one`` (a single angle of a model without kink radii found
    numerically) against the array version it stands in for, forced: every example of every model
    with a lobe in the mirror or half frame, Cook–Torrance with a cone kink at N (Smith's G) and without
    masking, and two pumped models, at 40 angles from 0° to 90° − 1e-9, with the 2-D route's tail and
    layer cuts and the single angle's tails, the tight one also graded (``graded``): the same row and
    touch radius to the bit."""
    from brdfs.numerics.tables import pump
    from brdfs.physics.geometry import cos_incidence, sin_incidence
    from brdfs.physics.models import MODELS

    angles = np.concatenate([np.linspace(0.0, 90.0, 31), 90.0 - np.logspace(-9, -1, 5), np.logspace(-9, -3, 4)])
    tails = (hemisphere.TAIL, azimuthal._single_angle_tail(1e-10), azimuthal._single_angle_tail(1e-10),
             azimuthal._single_angle_tail(1e-6))
    brdfs = [cls(**params) for cls in MODELS.values() for params in cls.examples.values()]
    brdfs += [model("cook_torrance", m=0.1, G="smith"), model("cook_torrance", m=0.3, G="none"),
              pump(model("phong", n=20), "g1", target_rtol=1e-6), pump(model("blinn", n=20), "g2", target_rtol=1e-6)]
    assert any(b.kink_at_normal for b in brdfs)
    compared = 0
    for brdf in brdfs:
        if brdf.lobe is None or brdf.lobe.frame not in (hemisphere.HALF, hemisphere.MIRROR):
            continue
        for theta in angles:
            th = np.array([theta])
            mu, st = cos_incidence(th), sin_incidence(th)
            if hemisphere.has_searched_kinks(brdf, mu):
                continue
            for tail, layer_max, graded in zip(tails, (hemisphere.TANGENCY_LAYER_MAX_2D, None, None, None),
                                               (False, False, True, False)):
                one = hemisphere._radial_breakpoints(brdf, mu, st, th, tail, layer_max=layer_max, graded=graded)
                with monkeypatch.context() as forced:
                    forced.setattr(hemisphere, "has_searched_kinks", lambda *args: True)
                    array = hemisphere._radial_breakpoints(brdf, mu, st, th, tail, layer_max=layer_max,
                                                           graded=graded)
                assert np.array_equal(one[0][0], array[0][0]), (brdf, theta)
                assert np.array_equal(one[2], array[2], equal_nan=True), (brdf, theta)
                compared += 1
    assert compared > 2500
