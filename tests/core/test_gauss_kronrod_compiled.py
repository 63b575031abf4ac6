"""The compiled single-element driver (core.gauss_kronrod_compiled) is a replica of the numpy driver:
the same decisions (evaluations, rounds, status), the same value to a few ulps, an error that is as
honest against exact integrals; and the switch that sends every route to numpy."""
import math

import numpy as np
import pytest

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import FILL_CHEAP, NodeValues, integrate

gkc = pytest.importorskip("brdfs.core.gauss_kronrod_compiled")

_EPS = np.finfo(float).eps

#: (integrand with a rounding bound per node, exact integral over [0, 1]): smooth, a kink off every
#: breakpoint, a √ end, a jump, a narrow peak, a logarithmic end.
INTEGRANDS = {
    "exp": (lambda x: (np.exp(x), 4 * _EPS * np.exp(x)), math.e - 1),
    "kink": (lambda x: (np.abs(x - 0.3141), 0 * x), (0.3141 ** 2 + 0.6859 ** 2) / 2),
    "sqrt": (lambda x: (np.sqrt(np.abs(x)), 0 * x), 2 / 3),
    "jump": (lambda x: (np.where(x > 0.7071, 1.0, 0.0), 0 * x), 1 - 0.7071),
    "peak": (lambda x: (1 / (1e-6 + (x - 0.5) ** 2), 0 * x), 2 * math.atan(0.5 / 1e-3) / 1e-3),
    "log": (lambda x: (np.log(np.abs(x) + 1e-300), 0 * x), -1.0),
    # two features of different strength (the factor-8 rule picks among them), and an oscillation
    # whose splits gain nothing for rounds (the stall counts)
    "two": (lambda x: (np.sqrt(np.abs(x)) + 1e-3 / (1e-4 + (x - 0.7) ** 2), 0 * x),
            2 / 3 + 1e-3 * (math.atan(0.3 / 1e-2) + math.atan(0.7 / 1e-2)) / 1e-2),
    "wiggle": (lambda x: (1 + 1e-9 * np.sin(3e3 * x), 0 * x), 1 + 1e-9 * (1 - math.cos(3e3)) / 3e3),
}
ROWS = ([0.0, 1.0], [0.0, 0.25, 0.5, 1.0], [0.0, 0.5, 0.5, np.nan, 1.0])


def compiled_integral(f, row, rtol, atol, fill):
    st = gkc.start(np.asarray(row, float), rtol, atol, fill)
    while not gkc.finished(st):
        value, rounding = f(gkc.pending(st))
        st = gkc.absorb(st, value, value, rounding)
    return gkc.result(st)


def numpy_integral(f, row, rtol, atol, fill):
    def integrand(x, elem):
        value, rounding = f(x)
        return NodeValues(value, value, rounding)
    return integrate(integrand, np.array([row], float), rtol=rtol, atol=atol, fill=fill, return_rounds=True)


@pytest.mark.parametrize("fill", [0, FILL_CHEAP])
@pytest.mark.parametrize("name", sorted(INTEGRANDS))
def test_the_compiled_driver_takes_the_numpy_drivers_decisions_and_values(name, fill):
    """Every row and rtol from 1e-3 to 1e-12: the same evaluations, rounds and status, the value within
    8 ulps (the Kronrod and Gauss sums are BLAS products in numpy, loops here), the error within 0.1 %
    or, where K − G is itself rounding, 8 ε |value|."""
    f, _ = INTEGRANDS[name]
    for row in ROWS:
        for rtol in (1e-3, 1e-6, 1e-8, 1e-10, 1e-12):
            value, error, evaluations, status, rounds = compiled_integral(f, row, rtol, 1e-14, fill)
            est, numpy_rounds = numpy_integral(f, row, rtol, 1e-14, fill)
            assert (evaluations, rounds, compiled.status_name(status)) == (est.evaluations, numpy_rounds, est.status[0])
            assert abs(value - est.value[0]) <= 8 * _EPS * abs(est.value[0])
            assert abs(error - est.error[0]) <= max(1e-3 * est.error[0], 8 * _EPS * abs(est.value[0]))


@pytest.mark.parametrize("name", sorted(set(INTEGRANDS) - {"jump", "wiggle"}))
def test_the_compiled_drivers_error_bounds_the_exact_integral(name):
    """Converged answers lie within their reported error of the exact integral, and not absurdly far
    inside it (the error is at most 1000 × the true error, or at the rounding floor).  Not the jump:
    off every breakpoint, once bisection has left it between two nodes of one interval, K = G there
    for both drivers (0.7071 at rtol 1e-10: 3.7e-13 off at a reported 3.3e-15), which is why the
    routes put their jumps and kinks on breakpoints; nor the wiggle, 477 periods that one interval's
    21 nodes alias at loose tolerances."""
    f, exact = INTEGRANDS[name]
    for row in ROWS[:2]:
        for rtol in (1e-4, 1e-7, 1e-10):
            value, error, _, status, _ = compiled_integral(f, row, rtol, 1e-14, FILL_CHEAP)
            assert status == gkc.CONVERGED
            true = abs(value - exact)
            assert true <= error
            assert error <= max(1000 * true, 1e3 * _EPS * abs(exact))


def test_an_empty_or_nan_row_integrates_to_zero_and_a_nan_integrand_is_not_converged():
    """An empty row is zero on both drivers (the numpy one raised IndexError on a single element: Ward,
    m = 1e200, whose radial range underflows to nothing)."""
    for row in ([0.5, 0.5], [np.nan, np.nan]):
        assert compiled_integral(INTEGRANDS["exp"][0], row, 1e-10, 1e-14, 0)[:4] == (0.0, 0.0, 0, gkc.CONVERGED)
        est, rounds = numpy_integral(INTEGRANDS["exp"][0], row, 1e-10, 1e-14, 0)
        assert (est.value[0], est.error[0], est.evaluations, est.status[0], rounds) == (0.0, 0.0, 0, "converged", 0)
    value, error, _, status, _ = compiled_integral(lambda x: (np.full_like(x, np.nan), 0 * x), [0.0, 1.0],
                                                   1e-10, 1e-14, FILL_CHEAP)
    est, _ = numpy_integral(lambda x: (np.full_like(x, np.nan), 0 * x), [0.0, 1.0], 1e-10, 1e-14, FILL_CHEAP)
    assert math.isnan(value) and math.isnan(error)
    assert compiled.status_name(status) == est.status[0] != "converged"


def test_numpy_only_switches_the_compiled_routes_off_and_back():
    before = compiled.available()
    with compiled.numpy_only():
        assert not compiled.available()
        with compiled.numpy_only():
            assert not compiled.available()
        assert not compiled.available()
    assert compiled.available() == before


@pytest.mark.parametrize("setting, off", [("0", True), ("off", True), (" False ", True), ("no", True),
                                          ("1", False), ("", False), (None, False)])
def test_the_environment_switches_the_compiled_routes_off(setting, off):
    assert compiled._switched_off(setting) is off


def test_status_codes_name_the_estimates_statuses():
    from brdfs.core.estimate import BUDGET_EXHAUSTED, CONVERGED, STALLED
    assert [compiled.status_name(c) for c in (gkc.CONVERGED, gkc.STALLED, gkc.BUDGET_EXHAUSTED)] == [
        CONVERGED, STALLED, BUDGET_EXHAUSTED]


@pytest.mark.parametrize("name", ["log", "peak", "sqrt", "two"])
def test_below_rounding_both_drivers_stall_alike(name):
    """At rtol 1e-15 the intervals stop gaining (stall counts, localised splits, rounding-width and
    unrefinable intervals decide): the same status, evaluations within a factor 1.5 (there the errors
    that decide are rounding, which the two sum orders round differently: 0.72–1.37× measured) and
    values within the reported errors."""
    f, _ = INTEGRANDS[name]
    for fill in (0, FILL_CHEAP):
        value, error, evaluations, status, _ = compiled_integral(f, ROWS[0], 1e-15, 1e-300, fill)
        est, _ = numpy_integral(f, ROWS[0], 1e-15, 1e-300, fill)
        assert compiled.status_name(status) == est.status[0]
        assert est.evaluations / 1.5 <= evaluations <= 1.5 * est.evaluations
        assert abs(value - est.value[0]) <= error + est.error[0]


def test_the_refinement_helpers_match_the_numpy_drivers_on_random_intervals():
    """The pieces of a round, each against its numpy counterpart on 200 random states: which intervals
    are unrefinable, which must be split (:func:`_needed`), the groups and their pieces' ends, and the
    pieces' stall counts (localised, no gain, reset on gain)."""
    from brdfs.core import gauss_kronrod as gk
    rng = np.random.default_rng(41)
    for _ in range(200):
        n = int(rng.integers(1, 40))
        lo = np.sort(rng.uniform(0, 1, n))
        hi = lo + rng.choice([1e-17, 1e-3, 0.1], n)
        err = rng.choice([1e-12, 1e-9, 1e-6, np.nan], n) * (rng.uniform(0.5, 2, n) if rng.uniform() < 0.5 else 1.0)  # ties too
        extra = rng.choice([0.0, 1e-9], n)
        assert (gkc._unrefinable(lo, hi, err, extra) == gk._unrefinable(lo, hi, err, extra)).all()
        err = np.nan_to_num(err)
        cand = rng.uniform(size=n) < 0.7
        total, budget = err.sum(), rng.uniform(0, 1) * err.sum()
        assert (gkc._needed(cand, err, total, budget)
                == gk._needed(cand, err, np.zeros(n, np.intp), 1, np.array([total]), np.array([budget]))).all()
        idx = np.flatnonzero(cand)
        if not idx.size:
            continue
        stalls = rng.choice([0, 0, 1, 3], n)
        fill = int(rng.choice([0, FILL_CHEAP]))
        g_idx, groups = gkc._split_groups(idx, stalls, lo, hi, fill)
        expected = gk._split_groups(idx, stalls, lo, hi, fill)
        assert [(int(s), int(c)) for s, c in groups if c] == [(s, g.size) for s, g in expected]
        assert (g_idx == np.concatenate([g for _, g in expected])).all()
        c_lo, c_hi = gkc._children(lo, hi, g_idx, groups)
        _, e_lo, e_hi = gk._children_of(np.zeros(n, np.intp), lo, hi, expected)
        assert (c_lo == e_lo).all() and (c_hi == e_hi).all()
        c_err = err[np.concatenate([np.tile(g, s) for s, g in expected])] * rng.uniform(0, 0.6, c_lo.size) ** 2
        assert (gkc._child_stalls(groups, g_idx, c_err, err, stalls)
                == gk._child_stalls(expected, c_err, err, stalls)).all()


def test_a_compiled_routes_fingerprint_covers_the_driver_and_the_constants_it_reads():
    """numba keys a cache on one file; the routes' caches are dropped when any brdfs module they
    import, directly or not, changes: the driver, and the modules whose constants they read."""
    closure = compiled.brdfs_imports("brdfs.numerics.integrate.polar_compiled")
    assert {"brdfs.core.gauss_kronrod_compiled", "brdfs.core.gauss_kronrod",
            "brdfs.numerics.integrate.polar"} <= closure
    assert "brdfs.numerics.albedo" not in closure and "brdfs.pipeline" not in {m[:14] for m in closure}


def test_a_changed_dependency_drops_the_compiled_modules_cache_once(tmp_path, monkeypatch):
    import shutil
    import types
    package = tmp_path / "brdfs"
    shutil.copytree(compiled._PACKAGE / "core", package / "core")
    (package / "__init__.py").write_text("")
    monkeypatch.setattr(compiled, "_PACKAGE", package)
    cache = tmp_path / "cache"
    cache.mkdir()
    module = types.ModuleType("brdfs.core.gauss_kronrod_compiled")
    module.__file__ = str(package / "core" / "gauss_kronrod_compiled.py")
    # first, a compiled function it imported from elsewhere: not where its own cache is
    module._larger = types.SimpleNamespace(_cache=types.SimpleNamespace(_cache_path=str(tmp_path / "elsewhere")),
                                           py_func=types.SimpleNamespace(__module__="brdfs.core.other"))
    module.start = types.SimpleNamespace(_cache=types.SimpleNamespace(_cache_path=str(cache)),
                                         py_func=types.SimpleNamespace(__module__=module.__name__))
    entries = [cache / "gauss_kronrod_compiled.start-70.py311.nbi", cache / "gauss_kronrod_compiled.start-70.py311.1.nbc"]
    other = cache / "polar_compiled.albedo_one-9.py311.nbi"

    def cached():
        for entry in [*entries, other]:
            entry.write_text("machine code")
    cached()
    assert compiled.drop_stale_cache(module)                    # no fingerprint yet: dropped
    assert not any(e.exists() for e in entries) and other.exists()
    cached()
    assert not compiled.drop_stale_cache(module)                # nothing changed: kept
    assert all(e.exists() for e in entries)
    source = package / "core" / "gauss_kronrod.py"               # a constant the driver reads changes
    source.write_text(source.read_text().replace("SAFETY = 2.0", "SAFETY = 3.0"))
    assert compiled.drop_stale_cache(module)
    assert not any(e.exists() for e in entries) and other.exists()


def test_numpy_only_holds_in_its_own_thread_only():
    import threading
    inside, outside = threading.Event(), threading.Event()
    seen = {}

    def numpy_thread():
        with compiled.numpy_only():
            seen["inside"] = compiled.available()
            inside.set()
            outside.wait(5)

    worker = threading.Thread(target=numpy_thread)
    worker.start()
    inside.wait(5)
    seen["other thread"] = compiled.available()
    outside.set()
    worker.join()
    assert seen == {"inside": False, "other thread": compiled._state["available"]}
