"""The front doors refuse bad arguments before any work, each with one line naming the argument and
its value: every argument of albedo() and model(), every option of every albedo method (read from
the method's signature) and every declared parameter of every model (read from its class)."""
import doctest
import inspect
import math

import numpy as np
import pytest

import brdfs
from brdfs import ALBEDO_METHODS, ArgumentError, albedo, model
from brdfs.numerics import albedo as albedo_module
from brdfs.numerics import arguments
from brdfs.physics.models import MODELS
from brdfs.physics.models.base import counting_evaluations

PHONG = model("phong", n=20)


def _refused(call, argument, value):
    """``call`` raises an ArgumentError (a ValueError and a TypeError), before any BRDF value is
    computed, with one line that names ``argument`` and the repr of ``value``."""
    with counting_evaluations() as count, pytest.raises(ArgumentError) as info:
        call()
    message = str(info.value)
    assert "\n" not in message, message
    assert f"{argument} = {value}" in message, message
    assert count[0] == 0, "work was done before the argument was checked"
    return message


# --- albedo(): every argument ------------------------------------------------------------------

ALBEDO_CALLS = [
    ("model", "'phong'", lambda: albedo("phong", 45.0)),
    ("model", "3", lambda: albedo(3, 45.0)),
    ("model", "None", lambda: albedo(None, 45.0)),
    ("model", "<class", lambda: albedo(type(PHONG), 45.0)),
    ("theta_deg", "[95.]", lambda: albedo(PHONG, 95.0)),
    ("theta_deg", "[-1.]", lambda: albedo(PHONG, [-1.0, 30.0])),
    ("theta_deg", "[nan]", lambda: albedo(PHONG, [30.0, math.nan])),
    ("theta_deg", "[inf]", lambda: albedo(PHONG, math.inf)),
    ("theta_deg", "'45'", lambda: albedo(PHONG, "45")),
    ("theta_deg", "[]", lambda: albedo(PHONG, [])),
    ("theta_deg", "True", lambda: albedo(PHONG, True)),
    ("theta_deg", "[95.]", lambda: albedo(PHONG, [[0.0, 95.0]])),
    ("method", "'engin'", lambda: albedo(PHONG, 45.0, "engin")),
    ("method", "3", lambda: albedo(PHONG, 45.0, 3)),
    ("rtol", "-1", lambda: albedo(PHONG, 45.0, rtol=-1)),
    ("rtol", "0.0", lambda: albedo(PHONG, 45.0, rtol=0.0)),
    ("rtol", "nan", lambda: albedo(PHONG, 45.0, rtol=math.nan)),
    ("rtol", "inf", lambda: albedo(PHONG, 45.0, rtol=math.inf)),
    ("rtol", "'1e-6'", lambda: albedo(PHONG, 45.0, rtol="1e-6")),
    ("rtol", "True", lambda: albedo(PHONG, 45.0, rtol=True)),
    ("rtol", "1000000000", lambda: albedo(PHONG, 45.0, rtol=10 ** 400)),       # an int beyond the floats
    ("atol", "-1e-14", lambda: albedo(PHONG, 45.0, atol=-1e-14)),
    ("atol", "nan", lambda: albedo(PHONG, 45.0, atol=math.nan)),
    ("atol", "[1e-14]", lambda: albedo(PHONG, 45.0, atol=[1e-14])),
    ("strict", "'yes'", lambda: albedo(PHONG, 45.0, strict="yes")),
    ("warn", "1", lambda: albedo(PHONG, 45.0, warn=1)),
]


@pytest.mark.parametrize("argument, shown, call", ALBEDO_CALLS, ids=[f"{a}={s}" for a, s, _ in ALBEDO_CALLS])
def test_albedo_refuses_a_bad_argument_with_one_line_naming_it(argument, shown, call):
    _refused(call, argument, shown)


def test_a_model_name_passed_to_albedo_gets_the_hint_to_build_the_model():
    message = _refused(lambda: albedo("phong", 45.0), "model", "'phong'")
    assert "brdfs.model('phong', n=..., C=...)" in message


def test_an_unknown_method_lists_the_methods():
    message = _refused(lambda: albedo(PHONG, 45.0, "engin"), "method", "'engin'")
    assert all(name in message for name in ALBEDO_METHODS)


# --- albedo(): every method's options, from its signature ----------------------------------------

def _options(method):
    """The method's options as its function's signature declares them (independently of the checker)."""
    params = list(inspect.signature(ALBEDO_METHODS[method]).parameters.values())[4:]
    return {p.name: p.default for p in params}


def test_the_methods_options_are_their_functions_keyword_parameters():
    assert _options("product_grid") == {"n": 64}
    assert _options("monte_carlo") == {"n_samples": 100_000, "sampler": "cosine", "seed": 0}
    assert _options("auto") == _options("engine") == _options("disk") == {}


@pytest.mark.parametrize("method", list(ALBEDO_METHODS))
def test_an_unknown_option_is_refused_and_the_methods_own_options_are_listed(method):
    message = _refused(lambda: albedo(PHONG, 45.0, method, bogus=1), "bogus", "1")
    listed = message.rsplit(":", 1)[1]
    assert all(name in listed for name in _options(method)), message
    if not _options(method):
        assert "none" in listed


def _wrong_values(default):
    """Values of the wrong type or out of range for an option with this default."""
    if isinstance(default, str):
        return [3, "no_such_choice"]
    if isinstance(default, int):
        return ["3", 2.5, True, -1]
    return ["x", True, -1.0]                                   # None: an optional positive float


OPTION_CASES = [(method, option, value) for method in ALBEDO_METHODS for option, default in _options(method).items()
                for value in _wrong_values(default)]


@pytest.mark.parametrize("method, option, value", OPTION_CASES, ids=[f"{m}-{o}={v!r}" for m, o, v in OPTION_CASES])
def test_every_option_of_every_method_refuses_a_wrong_type_or_range(method, option, value):
    _refused(lambda: albedo(PHONG, 45.0, method, **{option: value}), option, repr(value))


def test_good_options_are_accepted():
    assert albedo(PHONG, 45.0, "product_grid", n=16, warn=False).status.shape == ()
    est = albedo(PHONG, [0.0], "monte_carlo", n_samples=100, seed=[1, 2], sampler="model", warn=False)
    assert np.isfinite(est.value[0])
    assert np.isfinite(albedo(PHONG, np.float32(45), "dblquad", epsrel=1e-6, warn=False).value)
    assert np.isfinite(albedo(PHONG, 45, rtol=np.float64(1e-8), atol=1e-12, strict=True).value)


# --- model(): every argument, every declared parameter of every model ----------------------------

MODEL_CALLS = [
    ("name", "'phongg'", lambda: model("phongg", n=1)),
    ("name", "3", lambda: model(3)),
    ("name", "Phong(", lambda: model(PHONG)),
    ("m", "0.1", lambda: model("phong", n=20, m=0.1)),
    ("n", "'20'", lambda: model("phong", n="20")),
    ("n", "True", lambda: model("phong", n=True)),
    ("n", "inf", lambda: model("phong", n=math.inf)),
    ("n", "nan", lambda: model("phong", n=math.nan)),
    ("G2", "'bad'", lambda: model("ggx", alpha=0.3, compensation="kulla_conty", G2="bad")),
    ("G", "'torrance'", lambda: model("cook_torrance", m=0.1, G="torrance")),
    ("G", "1", lambda: model("cook_torrance", m=0.1, G=1)),
]


@pytest.mark.parametrize("argument, shown, call", MODEL_CALLS, ids=[f"{a}={s}" for a, s, _ in MODEL_CALLS])
def test_model_refuses_a_bad_argument_with_one_line_naming_it(argument, shown, call):
    _refused(call, argument, shown)


def test_infinity_is_not_finite_rather_than_negative():
    assert "must be finite" in _refused(lambda: model("phong", n=math.inf), "n", "inf")


def test_an_int_beyond_the_floats_is_not_finite():
    """numpy's isnan raised its own TypeError on 10**400 before the check could name the argument."""
    assert "must be finite" in _refused(lambda: albedo(PHONG, 45.0, atol=10 ** 400), "atol", "1000000000")
    assert "must be finite" in _refused(lambda: model("phong", n=-(10 ** 400)), "n", "-1000000000")


def test_a_missing_parameter_is_named():
    with pytest.raises(ArgumentError, match=r"model\('ward'\): m is missing"):
        model("ward")


def _outside(interval):
    """Values just outside a declared Interval (its finite ends), then NaN, inf, a string, a bool."""
    out = []
    if np.isfinite(interval.lo):
        out.append(interval.lo if interval.lo_open else interval.lo - 1.0)
    if np.isfinite(interval.hi):
        out.append(interval.hi if interval.hi_open else interval.hi + 1.0)
    return out + [math.nan, -math.inf, "1", True]


PARAMETER_CASES = [(name, key, value) for name, cls in MODELS.items() for key, interval in cls.param_ranges.items()
                   for value in _outside(interval)]
CHOICE_CASES = [(name, key, "no_such_choice") for name, cls in MODELS.items() for key in cls.param_choices]


@pytest.mark.parametrize("name, key, value", PARAMETER_CASES + CHOICE_CASES,
                         ids=[f"{n}-{k}={v!r}" for n, k, v in PARAMETER_CASES + CHOICE_CASES])
def test_every_declared_parameter_of_every_model_refuses_values_outside_its_range(name, key, value):
    params = {**MODELS[name].examples["typical"], key: value}
    _refused(lambda: model(name, **params), key, repr(value))


def test_the_edges_of_every_declared_range_pass_the_front_door():
    for name, cls in MODELS.items():
        for key, interval in cls.param_ranges.items():
            for end, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open)):
                if np.isfinite(end) and not is_open:
                    arguments.check_model_call(name, {**cls.examples["typical"], key: end})   # no ArgumentError
                    try:
                        built = model(name, **{**cls.examples["typical"], key: end})
                    except ArgumentError:
                        raise
                    except ValueError as exc:     # a constraint between parameters, the model's own
                        assert "ior_re" in str(exc), exc          # He–Torrance: ior_im needs ior_re
                        continue
                    assert built.params[key] == end


def test_at_least_thirty_bad_calls_are_tried():
    assert len(ALBEDO_CALLS) + len(OPTION_CASES) + len(MODEL_CALLS) + len(PARAMETER_CASES) >= 30
    assert {name for name, _, _ in PARAMETER_CASES} == {n for n, c in MODELS.items() if c.param_ranges}


def test_the_error_class_is_a_value_error_and_a_type_error_and_is_exported():
    assert brdfs.ArgumentError is arguments.ArgumentError
    with pytest.raises(TypeError):
        model("phong", n="20")
    with pytest.raises(ValueError):
        albedo(PHONG, 45.0, rtol=-1)


def test_the_front_door_examples_still_hold():
    for module in (albedo_module, arguments):
        result = doctest.testmod(module)
        assert result.attempted > 0 and result.failed == 0


@pytest.mark.parametrize("argument, shown, call", [
    ("models", "'phong'", lambda: brdfs.albedo_table("phong", [0.0])),
    ("models[1]", "'ward'", lambda: brdfs.albedo_table([PHONG, "ward"], [0.0])),
    ("theta_deg", "[91.]", lambda: brdfs.albedo_table([PHONG], [0.0, 91.0])),
    ("rtol", "-1e-06", lambda: brdfs.albedo_table([PHONG], [0.0], rtol=-1e-6)),
    ("atol", "nan", lambda: brdfs.albedo_table([PHONG], [0.0], atol=math.nan)),
])
def test_albedo_table_refuses_a_bad_argument_with_one_line_naming_it(argument, shown, call):
    _refused(call, argument, shown)


@pytest.mark.parametrize("argument, shown, theta", [
    ("theta_deg", "[91.]", [0.0, 91.0]), ("theta_deg", "[nan]", [np.nan]), ("theta_deg", "'a'", "a")])
def test_albedo_pairs_refuses_bad_angles_with_one_line_naming_it(argument, shown, theta):
    from brdfs.numerics.albedo import albedo_pairs
    message = _refused(lambda: albedo_pairs([PHONG] * np.size(theta), theta), argument, shown)
    assert message.startswith("albedo_pairs()"), message
