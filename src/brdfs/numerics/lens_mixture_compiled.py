"""The compiled twin of a single angle's lens-mixture albedo (eqs. 4.8, 4.9, 4.22, 4.24): the lens
areas a_R(d) with their rounding bounds, node by node (:func:`lens_values`), for the rounds of the compiled
driver (:mod:`brdfs.core.gauss_kronrod_compiled`), which Python runs round by round, p(R) in between.  The
functions here that start a pass or absorb a round call the driver's ``start``, ``absorb``, ``pending`` and
``finished`` themselves, so that a round is one crossing from Python; numba compiles its own copy of those
into this module's cache (about 10 s for the module on a cold cache, ``make compiled``).

A replica, operation for operation (but for two, where they are: the series's higher powers, the error
terms' sines), of :func:`brdfs.physics.patch_geometry._basic_albedo_of_one` (itself
the one-value form of :func:`~brdfs.physics.patch_geometry.basic_albedo_at`'s array formulas:
:func:`~brdfs.physics.patch_geometry.circle_intersection`, ``_lens_rounding``, ``_angle_rounding``,
``_segment``, ``_segment_series``, ``_four_triangle_area(_near_unit)``, ``basic_constant``) with
``cos θ`` known, and of the integrand of ``_weighted_mixture_integral``: p(R) a_R, p(R) (a_R − [R ≥ 1])
with a covered weight, and p(R) times the lens's rounding bound as the known error.  Python's ``max`` and
``min`` keep their argument order (a NaN first stays).  The transcendental functions are libm's, where
numpy's arrays take SIMD loops: a value can differ in its last ulps (the tests measure it).

The weight p(R) is the model's (a profile's closed form or a user's callable): the caller evaluates it in
numpy on each round's nodes, between the compiled rounds (:mod:`brdfs.numerics.lens_mixture`).  Imports
numba: import it only where :func:`brdfs.core.compiled.available` says so.
"""
from __future__ import annotations

import math

import sys

import numba
import numpy as np

from brdfs.core import compiled, gauss_kronrod_compiled as gkc
from brdfs.physics.patch_geometry import (_LAYERS, _SEGMENT_TERMS, _UNDERFLOWING, LENS_KINK_GRADING,
                                          WEIGHT_LAYER_GRADING, WEIGHT_LAYER_TRIGGER, WEIGHT_POINT_GRADING)

_EPS = float(np.finfo(float).eps)
_SIGNS = np.array([float(sign) for sign, _, _ in _SEGMENT_TERMS])
_POWERS = np.array([float(power) for _, power, _ in _SEGMENT_TERMS])
_FACTORIALS = np.array([factorial for _, _, factorial in _SEGMENT_TERMS])
_TINY = float(_UNDERFLOWING)
_LAYER_FACTORS = np.array(_LAYERS)
_KINK_GRADING = np.array(LENS_KINK_GRADING)
_POINT_GRADING = np.array(WEIGHT_POINT_GRADING)
_WEIGHT_LAYER = np.array(WEIGHT_LAYER_GRADING)
_TRIGGER = float(WEIGHT_LAYER_TRIGGER)


_larger = gkc._larger            # Python's max(a, b), as the driver takes it


@numba.njit(cache=True)
def _smaller(a, b):
    """Python's ``min(a, b)``."""
    return b if b < a else a


@numba.njit(cache=True, error_model="numpy")
def _segment(t):
    """``_segment`` of one angle: (x − sin x)/2, x = 2t, by its series (summed term by term) for 0 < |x| < 1/4.
    x³ is ``pow``'s, as numpy's; the higher powers x³ (x²)^k are products (7 ``pow`` calls cost 150 ns an
    angle): they are ≤ 2.6e-4 of x³ (x < 1/4), so their ulps move the sum by less than one of its own."""
    x = 2.0 * t
    if abs(x) < 0.25 and x != 0.0:
        square = x * x
        power = x ** _POWERS[0]
        total = 0.0
        for k in range(_SIGNS.size):
            total += _SIGNS[k] * power / _FACTORIALS[k]
            power *= square
        return 0.5 * total
    return 0.5 * (x - math.sin(x))


#: The segments and sines of the lens's special angles 0 and π (nested or apart circles), once.
_SEGMENT_PI = 0.5 * (2.0 * math.pi - math.sin(2.0 * math.pi))
_SIN_PI = math.sin(math.pi)


@numba.njit(cache=True, error_model="numpy")
def _four_triangle_area(a, b, c):
    """``_four_triangle_area_of_one``: Kahan's Heron formula on the sides sorted descending."""
    if a < b:
        a, b = b, a
    if b < c:
        b, c = c, b
    if a < b:
        a, b = b, a
    f0, f1, f2, f3 = (a + (b + c)), (c - (a - b)), (c + (a - b)), (a + (b - c))
    prod = f0 * f1 * f2 * f3
    if prod < _TINY:
        return (math.sqrt(_larger(f0, 0.0)) * math.sqrt(_larger(f1, 0.0))
                * math.sqrt(_larger(f2, 0.0)) * math.sqrt(_larger(f3, 0.0)))
    return math.sqrt(_larger(prod, 0.0))


@numba.njit(cache=True, error_model="numpy")
def _spread(y_rel, x, x_abs, y):
    """``_spread``: the first term of the angle's rounding (0 where not finite)."""
    denominator = x * x + y * y
    if denominator == 0.0:
        return 0.0
    spread = (abs(x) * y_rel * y + y * (4 * _EPS) * x_abs) / denominator
    return spread if math.isfinite(spread) else 0.0


@numba.njit(cache=True, error_model="numpy")
def _sin_of_atan2(y, square, angle):
    """sin(atan2(y, x)) = y / √(x² + y²) for y ≥ 0, ``square`` = x² + y² (the error terms' sines, a few ulps
    from libm's sin of the rounded angle: a bound needs no more, and two sines cost a fifth of a node);
    libm's sin where x² + y² is near underflow or not finite."""
    if square > 1e-280 and square < math.inf:
        return y / math.sqrt(square)
    return math.sin(angle)


@numba.njit(cache=True, error_model="numpy")
def basic_albedo_of_one(d, R, mu):
    """(value, error) of a_R at |L'_P| = d with cos θ = ``mu`` (eq. 4.8): ``_basic_albedo_of_one(d, R, mu)``."""
    d2, one_minus_r, one_plus_r = d * d, 1.0 - R, 1.0 + R
    product, gap = one_minus_r * one_plus_r, abs(one_minus_r)
    x_alpha, alpha_abs = d2 + product, d2 + gap * one_plus_r
    if d <= gap or d >= one_plus_r:          # nested or apart: the angles 0 and π, the area's rounding ε area
        if d >= one_plus_r:
            seg_alpha = seg_beta = sin_alpha = 0.0
        elif R <= 1.0:
            seg_alpha, seg_beta, sin_alpha = 0.0, _SEGMENT_PI, 0.0
        else:
            seg_alpha, seg_beta, sin_alpha = _SEGMENT_PI, 0.0, _SIN_PI
        area = seg_alpha + R * R * seg_beta
        area_error = _EPS * area
    else:                                    # the triangle O, Q, P of the chord's end P
        if d > 0.5:
            mu2 = mu * mu
            u = mu2 / (1.0 + d)
            last = d - (R - 1.0) if R >= 0.5 else d + (1.0 - R)
            four_delta = math.sqrt(_larger((R + u) * (1.0 + R + d) * (R - u) * last, 0.0))
            x_beta, beta_abs = (R - mu) * (R + mu), R * R + mu2
            y_rel = 16 * _EPS + (4 * _EPS * u / abs(R - u) if R != u else math.inf)
        else:
            four_delta = _four_triangle_area(1.0, R, d)
            x_beta, beta_abs, y_rel = d2 - product, alpha_abs, 16 * _EPS
        alpha, beta = math.atan2(four_delta, x_alpha), math.atan2(four_delta, x_beta)
        seg_alpha, seg_beta = _segment(alpha), _segment(beta)
        area = seg_alpha + R * R * seg_beta
        y2 = four_delta * four_delta
        square_alpha, square_beta = x_alpha * x_alpha + y2, x_beta * x_beta + y2
        sin_alpha = _sin_of_atan2(four_delta, square_alpha, alpha)
        sin_beta = _sin_of_atan2(four_delta, square_beta, beta)
        d_alpha = _spread(y_rel, x_alpha, alpha_abs, four_delta) + _EPS * abs(alpha)
        d_beta = _spread(y_rel, x_beta, beta_abs, four_delta) + _EPS * abs(beta)
        rounding_alpha = 4 * _EPS * (seg_alpha if abs(alpha) < 0.125 else abs(alpha))
        rounding_beta = 4 * _EPS * (seg_beta if abs(beta) < 0.125 else abs(beta))
        propagated = 2 * (sin_alpha * sin_alpha) * d_alpha + 2 * R * R * (sin_beta * sin_beta) * d_beta
        area_error = propagated + rounding_alpha + R * R * rounding_beta + 2 * _EPS * area
    area_of_patch = math.pi * _smaller(1.0, R * R)
    c = 1.0 / area_of_patch if area_of_patch else math.inf
    value = area * c
    moved = _smaller(d, mu * mu / d if d else math.inf)
    from_input = abs(sin_alpha) * (4 * _EPS) * moved
    return value, c * (area_error + from_input) + 3 * _EPS * value


@numba.njit(cache=True, error_model="numpy")
def lens_values(x, w, d, mu, covered):
    """The integrand at the nodes ``x`` (m, 21) with the weight ``w`` = p(x): p a_R (p (a_R − [R ≥ 1]) with a
    ``covered`` weight) and p times a_R's rounding bound."""
    m = x.shape[0]
    high, extra = np.empty((m, 21)), np.empty((m, 21))
    for i in range(m):
        for j in range(21):
            value, error = basic_albedo_of_one(d, x[i, j], mu)
            if covered and x[i, j] >= 1.0:
                value = value - 1.0
            high[i, j] = w[i, j] * value
            extra[i, j] = w[i, j] * error
    return high, extra


@numba.njit(cache=True)
def _distinct(values, count):
    """The first ``count`` of ``values`` that lie in [0, 2], distinct and ascending (a zero's sign dropped, as
    a set of floats that holds 0.0 first)."""
    kept = np.empty(count)
    n = 0
    for k in range(count):
        if 0.0 <= values[k] <= 2.0:
            kept[n] = values[k] + 0.0
            n += 1
    for k in range(1, n):                  # insertion sort: a few dozen points
        value, j = kept[k], k - 1
        while j >= 0 and kept[j] > value:
            kept[j + 1] = kept[j]
            j -= 1
        kept[j + 1] = value
    m = 0
    for k in range(n):
        if m == 0 or kept[k] != kept[m - 1]:
            kept[m] = kept[k]
            m += 1
    return kept[:m]


@numba.njit(cache=True)
def _last_below(row, value):
    """The largest point of the ascending ``row`` below ``value``, NaN if none."""
    out = math.nan
    for p in row:
        if p < value:
            out = p
    return out


@numba.njit(cache=True)
def _copied(row, values):
    """``row`` copied to the start of ``values``; its length."""
    for k in range(row.size):
        values[k] = row[k]
    return row.size


@numba.njit(cache=True)
def single_element_partition(points, d, steep, end, pole, levels):
    """``_single_element_partition(points, d, (end, pole) if steep else None, rtol)`` with ``levels`` =
    ``lens_kink_levels(rtol)``: the same points, the same arithmetic (a single angle's first partition, graded
    toward the lens's kinks by ``levels`` levels and toward the weight's points)."""
    lo, hi = 1.0 - d, 1.0 + d
    values = np.empty(5 + points.size + _LAYER_FACTORS.size + _WEIGHT_LAYER.size + 2 * _KINK_GRADING.size
                      + points.size * _POINT_GRADING.size)
    values[0], values[1], values[2], values[3], values[4] = 0.0, 1.0, 2.0, lo, hi
    n = 5
    for p in points:
        values[n] = p
        n += 1
    for g in _LAYER_FACTORS:
        if lo * g < 1.0:
            values[n] = lo * g
            n += 1
    row = _distinct(values, n)
    if steep:                              # the weight's layer below min(1 + d, end): weight_layer_cuts
        r_end = end if end < hi else hi
        prev = _last_below(row, r_end)
        r = pole - r_end
        n = _copied(row, values)
        if r > 0.0 and r_end - prev > _TRIGGER * r:
            for g in _WEIGHT_LAYER:
                cut = r_end - r * g
                if cut > prev:
                    values[n] = cut
                    n += 1
        row = _distinct(values, n)
    n = _copied(row, values)
    if lo < hi:
        above = math.nan
        for k in range(row.size - 1, -1, -1):
            if row[k] > lo:
                above = row[k]
        below = _last_below(row, hi)
        if not math.isnan(above):
            for g in _KINK_GRADING[:levels]:
                values[n] = lo + (above - lo) * g
                n += 1
        if not math.isnan(below):
            for g in _KINK_GRADING[:levels]:
                values[n] = hi - (hi - below) * g
                n += 1
    for point in points:                   # the weight's own features inside (0, 2], graded toward from below
        before = _last_below(row, point)
        if 0.0 < point <= 2.0 and not math.isnan(before):
            for g in _POINT_GRADING:
                values[n] = point - (point - before) * g
                n += 1
    return _distinct(values, n)


@numba.njit(cache=True)
def _next_round(st):
    """(finished, the pending nodes (m, 21)) of state ``st``: the driver's ``finished`` and ``pending`` in one."""
    if gkc.finished(st):
        return True, np.empty((0, 21))
    return False, gkc.pending(st)


@numba.njit(cache=True)
def start_rough_pass(points, d, steep, end, pole, levels, rtol, atol):
    """A single angle's first partition (:func:`single_element_partition`, ``levels`` levels toward the lens's
    kinks) and the driver's state on it
    (:func:`.gauss_kronrod_compiled.start`, ``fill`` 0), with its pending nodes: one crossing from Python
    where four cost a boxing of the driver's state each.  Returns (partition, state, finished, nodes)."""
    partition = single_element_partition(points, d, steep, end, pole, levels)
    st = gkc.start(partition, rtol, atol, 0)
    done, x = _next_round(st)
    return partition, st, done, x


@numba.njit(cache=True)
def start_final_pass(partition, target, high, extra):
    """The final pass's state: the driver started on ``partition`` at absolute tolerance ``target``, its first
    evaluation the rough pass's (``high``, ``extra``), and its pending nodes.  Returns (state, finished, nodes)."""
    st = gkc.absorb(gkc.start(partition, 0.0, target, 0), high, high, extra)
    done, x = _next_round(st)
    return st, done, x


@numba.njit(cache=True, error_model="numpy")
def absorb_lens_round(st, x, w, d, mu, covered):
    """One round of the driver from state ``st``: the integrand at its pending nodes ``x`` with the weight
    ``w`` = p(x) (:func:`lens_values`), absorbed (:func:`.gauss_kronrod_compiled.absorb`), and the next round's
    nodes.  Returns (state, high, extra, finished, nodes)."""
    high, extra = lens_values(x, w, d, mu, covered)
    st = gkc.absorb(st, high, high, extra)
    done, nodes = _next_round(st)
    return st, high, extra, done, nodes


# numba keys its cache on this file alone: drop it when a module this one depends on has changed
compiled.drop_stale_cache(sys.modules[__name__])
