"""A model says everything about itself: the declarations every registered model carries (parameter
ranges and choices, narrowest and typical examples, chapter, reciprocity and energy claims) hold of
the model itself, and a model that needs a table is not built by the physics layer without it."""
from __future__ import annotations

import numpy as np
import pytest

from brdfs import albedo
from brdfs.physics.geometry import direction
from brdfs.physics.models import MODELS
from brdfs.physics.models import model as physics_model
from brdfs.physics.models.base import BRDF, Interval, counting_evaluations
from brdfs.physics.tables import MissingTable

KINDS = ("typical", "narrowest")


def _rng_directions(seed, n=400):
    rng = np.random.default_rng(seed)
    cos_t, phi = rng.random(n), 2 * np.pi * rng.random(n)
    s = np.sqrt(1 - cos_t ** 2)
    return np.stack([s * np.cos(phi), s * np.sin(phi), cos_t], -1)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_declares_a_typical_and_a_narrowest_example_inside_its_ranges(name):
    cls = MODELS[name]
    assert set(KINDS) <= set(cls.examples), f"{name} declares {sorted(cls.examples)}"
    for kind in KINDS:
        for key, value in cls.examples[kind].items():
            assert key in cls.param_columns(), f"{name} {kind}: {key} is no parameter"
            if key in cls.param_choices:
                assert value in cls.param_choices[key], (name, kind, key, value)
            elif not callable(value):
                assert key in cls.param_ranges, f"{name}: no range declared for {key}"
                assert cls.param_ranges[key].contains(value), (name, kind, key, value, cls.param_ranges[key])


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_declared_range_and_choice_names_a_parameter(name):
    cls = MODELS[name]
    for key, interval in cls.param_ranges.items():
        assert key in cls.param_columns() and isinstance(interval, Interval), (name, key)
        assert interval.lo < interval.hi
    for key, choices in cls.param_choices.items():
        assert key in cls.param_columns() and len(choices) >= 1, (name, key)
    for key, text in cls.param_texts.items():          # words for what is neither a range nor a choice
        assert key in cls.param_columns() and key not in cls.param_ranges and key not in cls.param_choices
        assert isinstance(text, str) and text, (name, key)


def _outside(interval: Interval):
    """Values just outside a range, at its finite bounds (the open bound itself where it is open)."""
    out = []
    if np.isfinite(interval.lo):
        out.append(interval.lo if interval.lo_open else interval.lo - max(1e-3, 1e-3 * abs(interval.lo)))
    if np.isfinite(interval.hi):
        out.append(interval.hi if interval.hi_open else interval.hi + max(1e-3, 1e-3 * abs(interval.hi)))
    return out


@pytest.mark.parametrize("name", sorted(MODELS))
def test_the_model_rejects_a_value_just_outside_each_declared_range_and_accepts_the_closed_bounds(name):
    """The ranges are the ones ``__post_init__`` validates: a value beyond a bound raises ValueError,
    a closed finite bound builds."""
    cls = MODELS[name]
    base = dict(cls.examples["typical"])
    for key, interval in cls.param_ranges.items():
        extra = {"ior_im": 0.0} if key == "ior_re" else {"ior_re": 1.5} if key == "ior_im" else {}
        for bad in _outside(interval):
            with pytest.raises(ValueError):
                cls(**{**base, **extra, key: bad})
        for bound, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open)):
            if np.isfinite(bound) and not is_open:
                cls(**{**base, **extra, key: bound})
    for key, choices in cls.param_choices.items():
        with pytest.raises(ValueError):
            cls(**{**base, key: "no_such_choice"})


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_models_examples_build_and_evaluate_finite_and_non_negative(name, kind):
    brdf = MODELS[name].example(kind)
    assert isinstance(brdf, MODELS[name])
    L = _rng_directions(1, 64)
    mirror = L * np.array([-1.0, -1.0, 1.0])                # V = R: inside every lobe, however narrow
    V = np.concatenate([_rng_directions(2, 64), mirror])
    f = brdf(np.concatenate([L, L]), V)
    assert f.shape == (128,) and np.all(np.isfinite(f)) and np.all(f >= 0), (name, kind)
    assert np.all(f[64:] > 0), f"{name} {kind}: zero at the mirror direction"


def test_an_unknown_example_kind_is_named_in_the_error():
    with pytest.raises(ValueError, match="no example 'widest'"):
        MODELS["phong"].example("widest")


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_declares_its_chapter_and_its_claims(name):
    cls = MODELS[name]
    assert cls.chapter is None or cls.chapter in (1, 2, 3, 4), (name, cls.chapter)
    assert isinstance(cls.reciprocal, bool) and isinstance(cls.conserves_energy, bool)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_the_reciprocity_claim_holds_of_the_typical_example(name):
    """reciprocal = True: f(L, V) = f(V, L); False: a pair of directions where they differ."""
    brdf = MODELS[name].example()
    L, V = _rng_directions(3), _rng_directions(4)
    forward, backward = brdf(L, V), brdf(V, L)
    if MODELS[name].reciprocal:
        np.testing.assert_allclose(forward, backward, rtol=1e-9, atol=1e-12 * np.max(forward))
    else:
        assert np.max(np.abs(forward - backward)) > 1e-6 * np.max(forward)


@pytest.mark.parametrize("name", sorted(n for n, c in MODELS.items() if c.conserves_energy))
def test_the_energy_conservation_claim_holds_of_the_typical_example(name):
    """conserves_energy = True: a(θ) ≤ 1 within the reported error at angles up to 89.9°."""
    brdf = MODELS[name].example()
    theta = np.array([0.0, 30.0, 60.0, 80.0, 89.0, 89.9])
    try:
        est = albedo(brdf, theta, rtol=1e-7)
    except ValueError:          # a model with neither lobe nor own route: the projected-disk route
        est = albedo(brdf, theta, method="disk", rtol=1e-7)
    assert np.all(est.value <= 1.0 + est.error + 1e-12), (name, est.value)


def test_the_energy_claims_that_are_false_are_false_for_a_reason_the_engine_sees():
    """Spot checks of declared False: the original Phong's albedo exceeds 1 toward grazing incidence,
    Ward's grazing law diverges (a ~ K/√cos θ), and He–Torrance's exceeds 1 at 80°."""
    assert not MODELS["phong_original"].conserves_energy
    assert float(albedo(MODELS["phong_original"].example(), 89.9, rtol=1e-6).value) > 1.0
    assert not MODELS["ward"].conserves_energy and MODELS["ward"].example().grazing_law().exponent > 0
    assert not MODELS["he_torrance"].conserves_energy
    assert float(albedo(MODELS["he_torrance"].example(), 80.0, rtol=1e-6).value) > 1.0


def test_the_base_class_claims_nothing_and_needs_no_table():
    assert BRDF.conserves_energy is False and BRDF.chapter is None
    assert BRDF.examples == {} and BRDF.param_ranges == {}
    assert BRDF.table_requests(n=1.0) == {}


@pytest.mark.parametrize("name", ["ggx", "beckmann"])
def test_a_compensated_model_built_in_physics_without_its_table_raises_and_computes_nothing(name):
    with counting_evaluations() as count, pytest.raises(MissingTable, match="needs its E table"):
        physics_model(name, alpha=0.5, compensation="kulla_conty")
    assert count[0] == 0
    assert physics_model(name, alpha=0.5).energy is None      # single scattering needs none
    assert MODELS[name].table_requests(alpha=0.5) == {}
    assert set(MODELS[name].table_requests(alpha=0.5, compensation="kulla_conty")) == {"energy"}


def test_evaluation_counters_nest_reenter_survive_a_raise_and_leave_nothing_behind():
    from brdfs.physics.models import base

    brdf = physics_model("phong", n=2)
    light, views = [0.0, 0.0, 1.0], [[0.0, 0.0, 1.0]] * 3
    counter = counting_evaluations()
    with counter as outer:
        brdf(light, views)
        with counter as inner:                       # the same instance, entered again
            brdf(light, views[:2])
        with pytest.raises(RuntimeError), counting_evaluations() as failed:
            brdf(light, views[:1])
            raise RuntimeError
    assert (outer[0], inner[0], failed[0]) == (6, 2, 1)
    assert base._COUNTERS.boxes == []


def test_evaluation_counts_are_per_call_under_threads():
    """Four He–Torrance albedo calls at once, in four threads, each report the serial count: every
    thread counts in its own boxes (at e0ba585 the counters were shared, 605k–739k against 184,863)."""
    import threading

    from brdfs import albedo, model

    he = model("he_torrance", sigma0_um=0.1, tau_um=1.7)
    angles = [10.0, 50.0, 80.0]
    serial = albedo(he, angles, rtol=1e-6).evaluations
    start, counts = threading.Barrier(4), [None] * 4

    def run(k):
        start.wait()
        counts[k] = albedo(he, angles, rtol=1e-6).evaluations

    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert counts == [serial] * 4


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_numeric_parameter_has_a_bounded_test_range_inside_its_declared_range(name):
    """The generic tests draw every parameter from the class's own declarations: each declared range
    has a test range (bounded, lo ≤ hi), and its ends (and 0 where it adds it) lie in the declared range."""
    cls = MODELS[name]
    for key, interval in cls.param_ranges.items():
        for energy in (False, True):
            draw = cls.test_range(key, energy=energy)
            assert draw is not None, f"{name}: {key} has the unbounded range {interval.text()} and no test range"
            assert np.isfinite(draw.lo) and np.isfinite(draw.hi) and draw.lo <= draw.hi, (name, key, draw)
            for end in (draw.lo, draw.hi) + ((0.0,) if draw.zero else ()):
                assert interval.contains(end), (name, key, end, interval)
    for key in set(cls.test_ranges) | set(cls.energy_test_ranges):
        assert key in cls.param_ranges, f"{name}: test range for {key}, which declares no range"


def test_a_bounded_declared_range_is_its_own_test_range_and_an_unbounded_one_needs_one():
    from dataclasses import dataclass

    from brdfs.physics.models.base import DrawRange, positive

    @dataclass(frozen=True)
    class Declared(BRDF):
        rho: float = 0.5
        k: float = 1.0
        name = "declared_in_a_test"
        param_ranges = {"rho": Interval(0.0, 1.0), "k": positive()}

    assert Declared.test_range("rho") == DrawRange(0.0, 1.0)
    assert Declared.test_range("k") is None


def test_the_base_class_refuses_a_parameter_outside_its_declared_range_or_choices():
    """The recipe's model declares its ranges and writes no check: the constructor refuses for it,
    naming the model, the parameter and the value; the check runs before a subclass's own ``__post_init__``, which still runs."""
    from dataclasses import dataclass

    @dataclass(frozen=True)
    class Plain(BRDF):
        n: float = 1.0
        kind: str = "a"
        name = "plain_in_a_test"
        param_ranges = {"n": Interval(0.0, 10.0, lo_open=True)}
        param_choices = {"kind": ("a", "b")}

    @dataclass(frozen=True)
    class WithOwnInit(Plain):
        name = "own_init_in_a_test"

        def __post_init__(self):
            object.__setattr__(self, "n", float(self.n))

    for cls in (Plain, WithOwnInit):
        assert cls(n=10.0).n == 10.0
        for bad in (0.0, 10.5, float("nan")):
            with pytest.raises(ValueError, match=rf"{cls.name}: n must lie in \(0, 10\], got"):
                cls(n=bad)
        with pytest.raises(ValueError, match="kind must be one of"):
            cls(kind="c")
    assert WithOwnInit(n=3).n == 3.0 and isinstance(WithOwnInit(n=3).n, float)


def _class_body_names_assigned_twice(cls) -> list[str]:
    import ast
    import inspect
    import textwrap
    body = ast.parse(textwrap.dedent(inspect.getsource(cls))).body[0].body
    names = [t.id for node in body if isinstance(node, (ast.Assign, ast.AnnAssign))
             for t in (node.targets if isinstance(node, ast.Assign) else [node.target]) if isinstance(t, ast.Name)]
    return sorted({n for n in names if names.count(n) > 1})


@pytest.mark.parametrize("name", sorted(MODELS))
def test_a_model_class_declares_each_fact_once(name):
    """A second ``param_ranges`` (or any attribute) in one class body silently overrides the first."""
    assert _class_body_names_assigned_twice(MODELS[name]) == []


def test_a_declared_number_given_as_a_numpy_scalar_is_kept_as_the_python_number_it_equals():
    """A float32 n stayed float32 in n + 1.0 (NEP 50): Phong n = float32(0.1) was 2.6e6 of its reported
    errors off at 30°, and a long double reached the compiled routes as a type they cannot take.  Every
    registered model's typical example, each declared parameter given as float32, long double and a
    0-d array: kept as the float it equals, and the albedo that of the model built with that float."""
    import brdfs
    from brdfs.physics.models import MODELS
    checked = 0
    for cls in MODELS.values():
        typical = cls.examples["typical"]
        for key in cls.param_ranges:
            value = typical.get(key)
            if type(value) is not float:
                continue
            for given in (np.float32(value), np.longdouble(value), np.array(value)):
                try:
                    brdf = cls(**{**typical, key: given})
                except ValueError:              # float32's rounding can leave an open range's end
                    continue
                kept = getattr(brdf, key)
                assert type(kept) is float and kept == float(given), (cls.name, key, type(given))
                checked += 1
        brdf = cls(**{**typical, **{k: np.float32(v) for k, v in typical.items()
                                    if k in cls.param_ranges and type(v) is float}})
        plain = cls(**{**typical, **{k: float(np.float32(v)) for k, v in typical.items()
                                     if k in cls.param_ranges and type(v) is float}})
        assert brdfs.albedo(brdf, 30.0).value == brdfs.albedo(plain, 30.0).value, cls.name
    assert checked >= 60
