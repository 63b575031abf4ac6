"""The substitution t = t0 cosh² w on the interval after the horizon-touch radius t0
(hemisphere.horizon_onset / square_root_onset), checked on integrals known in closed form."""
from __future__ import annotations

import numpy as np
import pytest

from brdfs.core.gauss_kronrod import integrate
from brdfs.numerics.integrate.hemisphere import (ONSET_MIN_SPAN, ONSET_SPLIT, horizon_onset, radial_breakpoints_many,
                                                 square_root_onset)
from brdfs.numerics.integrate.grouping import indices_by_model
from brdfs.physics.lobes import HALF, MIRROR
from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.physics.models import model


def _knee(t0):
    """arccos √(t0 / t) on [t0, 1] (0 before): the radial shape past the horizon touch, and its
    integral t arccos √(t0/t) − √(t0 (t − t0)) from t0 to 1."""
    def f(t, elem):
        with np.errstate(invalid="ignore"):
            return np.where(t > t0[elem, None], np.arccos(np.sqrt(np.minimum(t0[elem, None] / t, 1.0))), 0.0)
    exact = np.arccos(np.sqrt(t0)) - np.sqrt(t0 * (1.0 - t0))
    return f, exact


T0 = 10.0 ** -np.arange(2.0, 16.0, 1.0)


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8, 1e-10])
def test_the_substitution_integrates_the_square_root_knee_honestly_at_every_onset_radius(rtol):
    f, exact = _knee(T0)
    bp = np.stack([np.zeros_like(T0), T0, np.full_like(T0, 0.5), np.ones_like(T0)], axis=1)
    est = integrate(square_root_onset(f, T0, np.full_like(T0, 0.5)), bp, rtol=rtol, atol=1e-300)
    assert np.all(np.abs(est.value - exact) <= est.error)
    assert np.all(est.error <= rtol * np.abs(exact))


def test_the_substitution_resolves_the_knee_in_a_few_intervals_at_every_onset_radius():
    """Without it the driver bisects toward t0 (up to 987 nodes an element at rtol 1e-10, t0 = 1e-8);
    with it at most 7 intervals of 21 nodes."""
    for t0 in T0:
        f, exact = _knee(np.array([t0]))
        est = integrate(square_root_onset(f, np.array([t0]), np.array([0.5])), np.array([[0.0, t0, 0.5, 1.0]]),
                        rtol=1e-10, atol=1e-300)
        assert est.evaluations <= 7 * 21, t0


def test_the_substitution_leaves_a_smooth_integral_unchanged():
    t0 = np.array([1e-9, 1e-3, 0.3])
    bp = np.stack([np.zeros(3), t0, np.full(3, 0.6), np.ones(3)], axis=1)
    plain = integrate(lambda t, e: np.exp(t), bp, rtol=1e-12)
    mapped = integrate(square_root_onset(lambda t, e: np.exp(t), t0, np.full(3, 0.6)), bp, rtol=1e-12)
    assert np.all(np.abs(mapped.value - (np.e - 1.0)) <= mapped.error + 4e-16)
    assert np.all(np.abs(mapped.value - plain.value) <= mapped.error + plain.error)


def test_the_onset_interval_starts_at_the_horizon_touch_radius_and_ends_at_or_halfway_to_the_next_breakpoint():
    f = model("cook_torrance", m=0.230153, G="none")
    theta = np.array([0.0, 45.0, 80.0, 89.99])
    bp, t0 = radial_breakpoints_many([f] * 4, cos_incidence(theta), sin_incidence(theta), theta, touch=True)
    split, lo, hi = horizon_onset(bp, t0)
    assert np.isnan(lo[0]) and np.isnan(hi[0])              # normal incidence: the circle ends at the horizon
    touch = f.lobe.t_of(0.5 * np.radians(90.0 - theta))
    start = np.where(np.isnan(lo), touch, lo)           # lo: the row's own value of the touch radius
    following = [next(iter(row[np.isfinite(row) & (row > t * (1 + 1e-12))]), np.nan) for row, t in zip(bp, start)]
    assert following[1] < ONSET_MIN_SPAN * touch[1] and np.isnan(lo[1])      # the knee fills a short interval
    for k in (2, 3):
        assert np.isclose(lo[k], touch[k], rtol=1e-10, atol=0)               # π/2 − θ against 90° − θ: last digits
        assert hi[k] == following[k] or (following[k] > ONSET_SPLIT * lo[k] and hi[k] == 0.5 * (lo[k] + following[k]))
        old, new = bp[k][np.isfinite(bp[k])], split[k][np.isfinite(split[k])]
        assert set(new) == set(old) | {hi[k]}               # the split adds one breakpoint, or none


def test_no_substitution_where_no_element_has_an_onset():
    f = lambda t, e: t
    assert square_root_onset(f, np.full(2, np.nan), np.full(2, np.nan)) is f



def _touch_radii(models, theta_deg):
    """t0 computed anew, as horizon_onset did before the breakpoints carried it: β = π/2 − θ (mirror
    frame), δ = (π/2 − θ)/2 (half frame), NaN for another frame or θ = 90°."""
    theta_deg = np.asarray(theta_deg, float)
    t0 = np.full(theta_deg.size, np.nan)
    for members in indices_by_model(models):
        idx = np.array(members)
        lobe = models[idx[0]].lobe
        if lobe.frame is HALF or lobe.frame is MIRROR:
            touch = (0.5 if lobe.frame is HALF else 1.0) * (np.pi / 2 - np.radians(theta_deg[idx]))
            t0[idx] = np.where(touch > 0, lobe.t_of(np.maximum(touch, 0.0)), np.nan)
    return t0


def test_the_touch_radii_the_breakpoints_carry_are_those_horizon_onset_would_compute():
    """``radial_breakpoints_many(touch=True)`` hands ``horizon_onset`` the radius t0 it found as the
    candidate of the level N·V = 0; the onset intervals are the same as from t0 computed anew
    (:func:`_touch_radii`), for every example of every model at random angles, 0°, 90° and 90° − 1e-9."""
    from brdfs.physics.models import MODELS

    rng = np.random.default_rng(1)
    theta = np.concatenate([rng.uniform(0.0, 90.0, 24), [0.0, 45.0, 89.9, 90.0 - 1e-9, 90.0]])
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    onsets = 0
    for name, cls in MODELS.items():
        for params in cls.examples.values():
            m = model(name, **params)
            if not hasattr(m.lobe, "t_of"):           # no radial coordinate: not the engine's routes
                continue
            bp, t0 = radial_breakpoints_many([m] * theta.size, mu, st, theta, touch=True)
            carried = horizon_onset(bp, t0)
            anew = horizon_onset(bp, _touch_radii([m] * theta.size, theta))
            for a, b in zip(carried, anew):
                assert np.array_equal(a, b, equal_nan=True), (name, params)
            onsets += int(np.isfinite(carried[1]).sum())
    assert onsets > 100              # the comparison saw onset intervals, not only NaN


def test_a_single_row_gets_the_onset_interval_the_batch_gives_it():
    """``horizon_onset`` on one row (Python floats) against the same row inside a batch (arrays): the
    same split row, lo and hi to the bit, for every example of every model at random angles."""
    from brdfs.physics.models import MODELS

    rng = np.random.default_rng(2)
    theta = np.concatenate([rng.uniform(0.0, 90.0, 16), [0.0, 89.9, 90.0 - 1e-9, 90.0]])
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    splits = 0
    for name, cls in MODELS.items():
        for params in cls.examples.values():
            m = model(name, **params)
            if not hasattr(m.lobe, "t_of"):
                continue
            bp, t0 = radial_breakpoints_many([m] * theta.size, mu, st, theta, touch=True)
            batch = horizon_onset(bp, t0)
            for i in range(theta.size):
                one = horizon_onset(bp[i:i + 1], t0[i:i + 1])
                width = one[0].shape[1]
                assert np.array_equal(one[0][0], batch[0][i, :width], equal_nan=True), (name, params, theta[i])
                assert np.all(np.isnan(batch[0][i, width:]))
                assert np.array_equal(one[1], batch[1][i:i + 1], equal_nan=True)
                assert np.array_equal(one[2], batch[2][i:i + 1], equal_nan=True)
                splits += one[0].shape[1] > bp.shape[1]
    assert splits > 20               # the comparison saw rows that were split
