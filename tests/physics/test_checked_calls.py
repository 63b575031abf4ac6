"""A model's public call checks its directions (shape, finiteness, unit length within 1e-6) and its
sampler's random numbers ([0, 1)), refusing with one line; the package's own paths skip the check
(``unchecked``) and give the same values."""
from __future__ import annotations

import numpy as np
import pytest

import brdfs
from brdfs.physics.models import MODELS
from brdfs.physics.models import base

N = [0.0, 0.0, 1.0]
L45 = [np.sqrt(0.5), 0.0, np.sqrt(0.5)]

BAD_DIRECTIONS = [
    # (L, V, text the one line contains)
    (N, [0.0, 0.0, 0.5], "V must be a unit vector"),                   # was 0.442 instead of 0.884
    (N, [0.0, 0.0, 1.0 + 2e-6], "|V| = 1.000002"),
    ([0.0, 0.0, 2.0], N, "L must be a unit vector"),
    (N, [np.nan, 0.0, 1.0], "V must be finite"),                       # was 0
    (N, [[0.0, 0.0, 1.0], [0.0, np.inf, 1.0]], "at index (1,)"),
    (N, [0.0, 1.0], "V must have shape (..., 3)"),                     # was a bare IndexError
    (N, 1.0, "V must have shape (..., 3)"),
    ([N, N], [N, N, N], "do not broadcast"),
]


@pytest.mark.parametrize("L, V, named", BAD_DIRECTIONS, ids=[t for *_, t in BAD_DIRECTIONS])
def test_the_public_call_refuses_a_bad_direction_with_one_line_naming_it(L, V, named):
    f = brdfs.model("phong", n=20)
    with pytest.raises(ValueError) as info:
        f(L, V)
    message = str(info.value)
    assert message.startswith("phong: ") and named in message and "\n" not in message, message


def test_a_direction_within_the_tolerance_is_accepted_and_the_unchecked_path_gives_the_same_values():
    f = brdfs.model("ggx", alpha=0.3)
    V = np.array([0.3, 0.1, np.sqrt(1 - 0.1)]) * (1 + 0.9e-6)
    assert f(L45, V) == f.unchecked(L45, V) > 0
    rng = np.random.default_rng(4)
    Vs = rng.normal(size=(50, 3))
    Vs /= np.linalg.norm(Vs, axis=-1, keepdims=True)
    np.testing.assert_array_equal(f(L45, Vs), f.unchecked(L45, Vs))


@pytest.mark.parametrize("u, shown", [([[0.5, 1.0]], "1.0"), ([[0.5, 1.2]], "1.2"), ([[-0.1, 0.5]], "-0.1"),
                                      ([[np.nan, 0.5]], "nan")])
def test_a_sampler_refuses_random_numbers_outside_zero_one(u, shown):
    f = brdfs.model("phong", n=20)
    for call in (f.sample, f.sample_direction):
        with pytest.raises(ValueError, match=rf"phong.sample: random numbers u must lie in \[0, 1\), got {shown}"):
            call(L45, u)
    V, weight, pdf = f.sample(L45, [[0.0, 0.999999]])       # 0 itself and numbers just below 1 are fine
    assert np.all(np.isfinite(weight))


def test_the_integrators_and_samplers_do_not_pay_for_the_check(monkeypatch):
    """Albedo (engine, disk, Monte Carlo), sample and pdf run no check of the directions."""
    calls = []
    monkeypatch.setattr(base, "check_directions", lambda *a, **k: calls.append(a))
    f = brdfs.model("phong", n=20)
    brdfs.albedo(f, [0.0, 60.0])
    brdfs.albedo(f, [30.0], method="disk")
    brdfs.albedo(f, [30.0], method="monte_carlo", n_samples=1000, warn=False)
    f.sample(L45, np.random.default_rng(0).random((100, 2)))
    assert calls == []
    f(L45, N)
    assert len(calls) == 1


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_models_typical_example_checks_its_directions(name):
    f = MODELS[name].example()
    with pytest.raises(ValueError, match=f"^{name}: V must be a unit vector"):
        f(L45, [0.0, 0.0, 0.5])
