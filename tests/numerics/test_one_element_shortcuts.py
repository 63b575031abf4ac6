"""The single-angle shortcuts on Python floats against the general code they stand in for, to the bit,
including the inputs the engine never gives them (where they fall back to the general code)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from brdfs.numerics.integrate import hemisphere
from brdfs.numerics.integrate.hemisphere import square_root_onset


def test_the_distinct_points_in_range_are_the_comprehensions_with_nan_signed_zeros_and_infinities():
    rng = np.random.default_rng(41)
    specials = [0.0, -0.0, math.nan, math.inf, -math.inf, 1.0, 0.5, 0.5, 1e-300, -1e-300]
    for k in range(300):
        points = [0.0] + rng.uniform(-0.2, 1.2, rng.integers(0, 40)).tolist()
        points += [specials[i] for i in rng.integers(0, len(specials), k % 4)]
        rng.shuffle(points[1:])
        t_max = float(rng.choice([1.0, 0.7, 0.5, 0.0]))
        expected = sorted({p for p in points if 0.0 <= p <= t_max})
        found = hemisphere._sorted_distinct_within(points, t_max)
        assert [math.copysign(1.0, p) for p in found] == [math.copysign(1.0, p) for p in expected]
        assert found == expected, (points, t_max)


def _nodes(lo, hi):
    """Kronrod-like nodes on a partition of [0, 1] with lo and hi among its points (rows of 21)."""
    edges = np.unique(np.concatenate([np.linspace(0.0, 1.0, 9), [v for v in (lo, hi) if 0.0 <= v <= 1.0]]))
    a, b = edges[:-1, None], edges[1:, None]
    return a + (b - a) * np.linspace(0.0, 1.0, 21)


def _integrand(t, elem):
    return np.sqrt(np.abs(t)) * (1.0 + t * t)


@pytest.mark.parametrize("lo, hi", [(1e-3, 0.25), (0.125, 0.5), (1e-150, 0.75), (0.3, math.nan), (math.nan, math.nan),
                                    (0.5, 0.25)])
def test_one_elements_substitution_is_the_batchs_to_the_bit(lo, hi):
    """``square_root_onset`` of one element (floats) against the same element beside another in a batch
    (arrays): the same mapped nodes, Jacobian and values, also where the engine gives no such interval."""
    s = _nodes(0.0 if math.isnan(lo) else lo, hi)
    elem = np.zeros(s.shape[0], np.intp)
    with np.errstate(invalid="ignore", divide="ignore"):
        one = square_root_onset(_integrand, np.array([lo]), np.array([hi]))(s.copy(), elem)
        batch = square_root_onset(_integrand, np.array([lo, 1e-2]), np.array([hi, 0.5]))(s.copy(), elem)
    assert type(one) is type(batch)
    one, batch = (v if isinstance(v, tuple) else (v,) for v in (one, batch))
    for a, b in zip(one, batch):
        assert (a is None and b is None) or np.array_equal(a, b, equal_nan=True), (lo, hi)
