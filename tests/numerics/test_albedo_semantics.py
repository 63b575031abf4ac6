"""What albedo() means at the ends and how loudly it says so: divergence at grazing incidence, the
grazing limit models, the pumped models' own error, the warning and ``strict``, the ``auto`` route,
and ``Estimate.route``/``DIVERGED`` alongside the old positional Estimate."""
import warnings

import numpy as np
import pytest

import brdfs
from brdfs import Estimate, NotConvergedError, NotConvergedWarning, albedo, model
from brdfs.core.estimate import CONVERGED, DIVERGED, STALLED
from brdfs.numerics import albedo as albedo_module
from brdfs.numerics import pumping
from brdfs.physics.models import MODELS

#: Every registered model whose example declares that its albedo diverges at grazing incidence,
#: and the one whose divergence depends on a choice (Cook–Torrance with G = 1).
DIVERGENT = [(name, cls.examples["typical"]) for name, cls in MODELS.items()
             if cls.example().diverges_at_grazing] + [("cook_torrance", {"m": 0.1, "G": "none"})]
#: Every method, with cheap options.
METHODS = [("auto", {}), ("engine", {}), ("engine_2d", {}), ("disk", {}), ("product_grid", {"n": 8}),
           ("midpoint_grid", {"n_theta": 4, "n_phi": 8}), ("dblquad", {}),
           ("monte_carlo", {"n_samples": 100})]


def test_the_divergent_models_are_found_by_their_declaration():
    names = {name for name, _ in DIVERGENT}
    assert {"ward", "phong_original", "blinn_original", "cook_torrance"} <= names
    assert not model("cook_torrance", m=0.1).diverges_at_grazing          # G of eq. 2.10: a(90°) = 1


@pytest.mark.parametrize("name, params", DIVERGENT, ids=[f"{n}-{p.get('G', '')}" for n, p in DIVERGENT])
@pytest.mark.parametrize("method, options", METHODS, ids=[m for m, _ in METHODS])
def test_a_divergent_albedo_at_90_degrees_is_plus_infinity_with_status_diverged_and_no_warning(
        name, params, method, options):
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotConvergedWarning)
        est = albedo(model(name, **params), [90.0], method, rtol=1e-6, **options)
    assert est.value[0] == np.inf and est.error[0] == 0.0
    assert list(est.status) == [DIVERGED] and list(est.route) == ["declared"]


def test_below_90_degrees_a_divergent_model_is_integrated_as_before():
    est = albedo(model("ward", m=0.1), [60.0, 90.0], rtol=1e-8)
    assert np.isfinite(est.value[0]) and est.status[0] == CONVERGED and est.route[0] == "engine/azimuthal"
    assert est.status[1] == DIVERGED


@pytest.mark.parametrize("method", ["engine", "disk", "auto"])
def test_cook_torrance_with_eq_2_10_has_albedo_one_at_90_degrees_by_engine_and_disk_alike(method):
    # G of eq. 2.10: a(90°) = C (the grazing law); f itself is 0/0 at N·L = 0, its limit model is not
    est = albedo(model("cook_torrance", m=0.1), [90.0], method, rtol=1e-10)
    assert abs(est.value[0] - 1.0) <= est.error[0] <= 1e-10
    assert est.route[0].endswith(":grazing_limit") and est.status[0] == CONVERGED


def test_cook_torrance_with_smiths_g_at_90_degrees_is_the_albedo_of_its_grazing_limit_model_by_every_route():
    brdf = model("cook_torrance", m=0.3, G="smith")
    limit = brdf.grazing_limit_model()
    engine = albedo(brdf, [90.0], "engine", rtol=1e-8)
    disk = albedo(brdf, [90.0], "disk", rtol=1e-8)
    direct = albedo(limit, [90.0], "disk", rtol=1e-8)
    assert np.all(np.isfinite([engine.value, disk.value]))
    assert abs(engine.value[0] - disk.value[0]) <= engine.error[0] + disk.error[0]
    assert disk.value[0] == direct.value[0] and disk.route[0] == "disk:grazing_limit"
    assert 0.2 < disk.value[0] < 0.3


def test_a_pumped_models_albedo_includes_its_tables_error():
    """Phong n = 20 pumped once with a coarse table (degree 8, 1e-3), against the same model pumped
    with a table at 1e-11: the albedo of the coarse one is off by 3.5e-6, its table's doing, which the
    front door must report (the integration error alone is 1.3e-11)."""
    base = model("phong", n=20)
    table = pumping.tabulate_albedo(base, target_rtol=1e-3, engine_rtol=1e-9, degree=2)
    coarse = pumping.pumped_models(base, [table], "g1")[-1]
    fine = pumping.pumped_models(base, [pumping.tabulate_albedo(base, target_rtol=1e-11, engine_rtol=1e-12)], "g1")[-1]
    with pytest.warns(NotConvergedWarning, match="1 stalled.*carry an error of"):
        a = albedo(coarse, [30.0])                     # 1e-10 asked of a model known to 2e-3
    b = albedo(fine, [30.0], rtol=1e-9)
    true_error = abs(a.value[0] - b.value[0])
    assert true_error > 1e4 * 1e-10 * abs(a.value[0])                   # the table's error, not the integration's
    assert true_error <= a.error[0] - b.error[0]
    assert a.error[0] >= coarse.evaluation_rtol * a.value[0] and list(a.status) == [STALLED]
    assert list(b.status) == [CONVERGED]


# --- loud when not converged -----------------------------------------------------------------

def _short_of_its_tolerance(**kwargs):
    """A product grid of 2 × 2 points asked for 1e-10: always short of it (budget_exhausted)."""
    return albedo(model("phong", n=20), [10.0, 30.0, 50.0], "product_grid", rtol=1e-10, n=2, **kwargs)


def test_a_value_short_of_its_tolerance_warns_with_count_worst_error_tolerance_and_advice():
    with pytest.warns(NotConvergedWarning) as record:
        est = _short_of_its_tolerance()
    (warning,) = record
    message = str(warning.message)
    assert "\n" not in message and "3 of 3 values did not converge" in message and "budget_exhausted" in message
    worst = int(np.argmax(est.error / np.maximum(1e-10 * np.abs(est.value), 1e-14)))
    assert f"{est.error[worst]:.3g}" in message and f"{1e-10 * abs(est.value[worst]):.3g}" in message
    assert "Try method='disk'" in message
    assert warning.filename == __file__              # points at the caller's line
    assert issubclass(NotConvergedWarning, RuntimeWarning)


def test_strict_raises_instead_and_keeps_the_estimate():
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotConvergedWarning)
        with pytest.raises(NotConvergedError, match="did not converge") as info:
            _short_of_its_tolerance(strict=True)
    assert list(info.value.estimate.status) == ["budget_exhausted"] * 3


def test_warn_false_is_quiet_and_a_converged_call_never_warns():
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotConvergedWarning)
        est = _short_of_its_tolerance(warn=False)
        albedo(model("phong", n=20), [10.0, 30.0])
    assert set(est.status) == {"budget_exhausted"}


# --- auto, route -----------------------------------------------------------------------------

def test_auto_is_the_default_and_is_the_engine_to_the_bit_where_the_engine_converges():
    brdf, theta = model("ward_cosmin", m=0.1), np.array([0.0, 33.0, 71.0, 89.9])
    default, engine = albedo(brdf, theta, rtol=1e-8), albedo(brdf, theta, "engine", rtol=1e-8)
    assert np.array_equal(default.value, engine.value) and np.array_equal(default.error, engine.error)
    assert list(default.route) == list(engine.route) == ["engine/azimuthal"] * 4


def test_auto_takes_the_disk_where_the_engine_stalled_and_records_it_per_value(monkeypatch):
    def stalling_at_60(route):
        def run(models, theta, rtol, atol):
            est = route(models, theta, rtol=rtol, atol=atol)
            status = np.where(theta == 60.0, STALLED, est.status)
            error = np.where(theta == 60.0, 1e-3, est.error)
            return Estimate(est.value, error, est.evaluations, status, est.route)
        return run

    # the 1-D route and its second try in two dimensions both stall at 60 degrees
    monkeypatch.setitem(albedo_module.ENGINE_ROUTES, "azimuthal", stalling_at_60(albedo_module.ENGINE_ROUTES["azimuthal"]))
    monkeypatch.setattr(albedo_module, "albedo_many", stalling_at_60(albedo_module.albedo_many))
    est = albedo(model("phong", n=20), [30.0, 60.0], rtol=1e-8)
    assert list(est.route) == ["engine/azimuthal", "disk"] and list(est.status) == [CONVERGED] * 2
    assert est.error[1] <= 1e-8 * est.value[1]


def test_auto_takes_the_disk_for_a_model_the_engine_cannot_integrate():
    brdf = model("patch_elliptical", b=0.5, ratio=0.5)
    with pytest.raises(ValueError, match="method='disk'"):
        albedo(brdf, [30.0], "engine")
    est = albedo(brdf, [30.0], rtol=1e-6)
    assert list(est.route) == ["disk"] and list(est.status) == [CONVERGED]


def test_every_method_reports_a_route_per_value_shaped_like_the_angles():
    theta = np.array([[0.0], [60.0]])
    for method, options in METHODS:
        est = albedo(model("phong_cosmin", n=5), theta, method, rtol=1e-4, warn=False, **options)
        assert est.route.shape == theta.shape and est.status.shape == theta.shape
        expected = method if method not in ("auto", "engine", "engine_2d") else "engine/"
        assert all(str(r).startswith(expected) for r in est.route.ravel()), (method, est.route)


def test_estimate_keeps_its_positional_form_and_indexes_its_route():
    old = Estimate(np.array([1.0, 2.0]), np.array([0.1, 0.2]), 7, np.array(["converged", "stalled"]))
    assert old.route is None and old[1].status == "stalled" and tuple(old) == (old.value, old.error)
    new = Estimate(old.value, old.error, 7, old.status, np.array(["engine/azimuthal", "disk"]))
    assert new[1].route == "disk" and list(new.converged) == [True, False]
    with pytest.raises(AttributeError):
        new.route = None                                    # still frozen


def test_the_public_names_are_exported():
    assert brdfs.NotConvergedWarning is NotConvergedWarning and brdfs.NotConvergedError is NotConvergedError
    assert issubclass(brdfs.ArgumentError, ValueError) and issubclass(brdfs.ArgumentError, TypeError)
    assert "auto" in brdfs.ALBEDO_METHODS


# --- a run that stops early says why -----------------------------------------------------------

def test_a_run_stopped_on_its_budget_says_budget_exhausted_and_one_that_cannot_gain_says_stalled():
    from brdfs.core.gauss_kronrod import NodeValues, integrate
    spiky = lambda x, elem: 1.0 / np.sqrt(np.abs(x - 0.3) + 1e-12)          # a cusp off the breakpoints
    assert list(integrate(spiky, np.array([[0.0, 1.0]]), rtol=1e-12, max_rounds=2).status) == ["budget_exhausted"]
    # an inner integral known only to 1e-6: no split of the outer one can help
    vague = lambda x, elem: NodeValues(np.cos(x), np.cos(x), np.full(x.shape, 1e-6))
    assert list(integrate(vague, np.array([[0.0, 1.0]]), rtol=1e-10).status) == ["stalled"]


def test_the_disk_keeps_its_drivers_reason_for_stopping_short(monkeypatch):
    def stalled_disk(models, theta, rtol, atol):
        return Estimate(np.full(len(models), 0.5), np.full(len(models), 1e-3), status=np.full(len(models), STALLED))

    monkeypatch.setattr(albedo_module, "disk_albedo_many", stalled_disk)
    est = albedo(model("phong", n=20), [30.0], "disk", warn=False)
    assert list(est.status) == [STALLED]                                    # not "budget_exhausted"


def test_a_models_own_route_without_a_status_is_judged_by_its_error():
    from dataclasses import dataclass

    @dataclass(frozen=True)
    class Rough(type(model("phong", n=1))):
        def albedo_estimate(self, theta_deg, rtol, atol):                   # an own route, 1e-3 off
            theta = np.asarray(theta_deg, float)
            return Estimate(np.full(theta.shape, 0.5), np.full(theta.shape, 1e-3))

    with pytest.warns(NotConvergedWarning):
        est = albedo(Rough(n=1.0), [30.0], "engine")
    assert list(est.status) != [CONVERGED] and list(est.route) == ["engine/own"]


# --- the tables' error of a compensated model, and the batch doors' meaning -------------------------

def _shifted(table, delta):
    """The same Chebyshev table with every node raised by ``delta`` (the interpolant is raised by
    exactly delta) and its error bound widened by it: an honest, coarser E table."""
    return type(table)(table.edges, np.asarray(table.values) + delta, table.error + delta, table.model_rtol)


def test_a_kulla_conty_albedo_includes_its_e_tables_error():
    """With F = 1 the exact compensated albedo is E + (1 − E) = 1 at every angle; a model built with
    E + δ (δ = 1e-6, inside the table's declared error) has albedo 1 − δ(1 − …) ≈ 1 − δ, which the reported
    error must cover (before: the integration's 1e-11 alone, 1e5 times short)."""
    exact = model("ggx", alpha=0.3, compensation="kulla_conty")
    built = type(exact)(alpha=0.3, compensation="kulla_conty", energy=_shifted(exact.energy, 1e-6))
    est = albedo(built, [0.0, 60.0, 89.0], rtol=1e-10, warn=False)
    true_error = np.abs(est.value - 1.0)
    assert np.all(true_error > 5e-7)                              # the table's doing, not the integration's
    assert np.all(true_error <= est.error), (true_error, est.error)
    assert list(est.status) == [STALLED] * 3                       # no refinement of the integral helps


#: A divergent model, one with a grazing limit model, a pumped one (its tables' error) and a plain one.
def _batch_models():
    base = model("phong", n=20)
    table = pumping.tabulate_albedo(base, target_rtol=1e-3, engine_rtol=1e-9, degree=2)
    return [model("ward", m=0.1), model("cook_torrance", m=0.3, G="smith"),
            pumping.pumped_models(base, [table], "g1")[-1], base]


def test_albedo_table_and_albedo_pairs_answer_as_albedo_does_elementwise_on_a_grid_including_90_degrees():
    """One code path (``_answer``): +inf/0/diverged, the grazing limit's albedo and the tables'
    error at the same elements, with the same statuses and routes, by all three doors."""
    models, grid = _batch_models(), np.array([0.0, 45.0, 89.99, 90.0])
    table = albedo_module.albedo_table(models, grid, rtol=1e-8)
    pairs = albedo_module.albedo_pairs([m for m in models for _ in grid], np.tile(grid, len(models)), rtol=1e-8)
    for i, m in enumerate(models):
        one = albedo(m, grid, "engine", rtol=1e-8, warn=False)
        for est in (table[i], Estimate(pairs.value[4 * i:4 * i + 4], pairs.error[4 * i:4 * i + 4], 0,
                                       pairs.status[4 * i:4 * i + 4], pairs.route[4 * i:4 * i + 4])):
            assert list(est.status) == list(one.status) and list(est.route) == list(one.route), m.name
            finite = np.isfinite(one.value)
            assert np.array_equal(np.isfinite(est.value), finite) and np.all(est.error[~finite] == 0)
            assert np.all(np.abs(est.value[finite] - one.value[finite]) <= est.error[finite] + one.error[finite])
            assert np.all(est.error[finite] >= m.evaluation_error(grid[finite], est.value[finite]))
    assert table.value[0, 3] == np.inf and table.status[0, 3] == DIVERGED
    assert table.route[1, 3].endswith(":grazing_limit") and np.isfinite(table.value[1, 3])
    assert table.status[2, 0] == STALLED                          # 1e-8 asked of a model known to ~1e-3
