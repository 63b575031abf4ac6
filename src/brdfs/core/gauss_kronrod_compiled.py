"""A compiled replica of :func:`.gauss_kronrod.integrate` for one element (a single angle).

The numpy driver spends a single element's call mostly on the overhead of its numpy calls; this
module does the same arithmetic in numba-compiled loops.  It is a replica, decision for decision:
the same initial intervals (a breakpoint row, empty and non-finite pieces dropped), the same
21-point rule, the same global refinement (intervals within a factor 8 of the largest error,
``fill`` with :func:`_needed`, up to :data:`.MAX_PIECES` pieces, stall counts with
:data:`.LOCALISED`, :func:`_unrefinable`, the budget and :func:`_still_open`), the same interval
order (the kept ones, then the pieces, piece-major per group), the same error (``SAFETY`` Σ|K − G|
plus the known errors plus 50 ε Σ|f|) and the same statuses.  Sums run left to right, as the
numpy driver's ``cumsum`` and ``bincount`` do; its Kronrod and Gauss sums are BLAS products, whose
order differs, so values can differ in the last ulps, and a decision that sits exactly on a
threshold can rarely go the other way (the routes' tests count both).

Use, from a route's own compiled function (numba cannot cache a compiled function that takes
another as an argument, so the kernel is called in the route's loop, not passed in)::

    st = start(breakpoints, rtol, atol, fill)
    while not finished(st):
        x = pending(st)                        # (m, 21) nodes
        st = absorb(st, high, low, extra)      # the kernel's values at x, each (m, 21)
    value, error, evaluations, status, rounds = result(st)

Status codes: :data:`CONVERGED` 0, :data:`STALLED` 1, :data:`BUDGET_EXHAUSTED` 2
(:func:`brdfs.core.compiled.status_name`).
"""
from __future__ import annotations

import math

import sys

import numba
import numpy as np

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import (GAUSS_WEIGHTS, KRONROD_WEIGHTS, LOCALISED, MAX_PIECES, NODES, SAFETY,
                                      STALL_LIMIT)

CONVERGED, STALLED, BUDGET_EXHAUSTED = 0, 1, 2
#: :func:`.gauss_kronrod.integrate`'s defaults.
MAX_INTERVALS = 100_000
MAX_ROUNDS = 200

_EPS = float(np.finfo(float).eps)
_X = NODES.copy()
_WK = KRONROD_WEIGHTS.copy()
_WG = GAUSS_WEIGHTS.copy()
_SAFETY = float(SAFETY)
_STALL_LIMIT = int(STALL_LIMIT)
_LOCALISED = float(LOCALISED)
_MAX_PIECES = int(MAX_PIECES)

# the state's integers and floats, by index
_FILL, _EVALUATIONS, _ROUNDS, _EXHAUSTED, _FINISHED, _STATUS, _FIXED_READY, _FIRST = range(8)
_RTOL, _ATOL, _VALUE, _ERROR = range(4)


@numba.njit(cache=True)
def _larger(a, b):
    """Python's ``max(a, b)``: ``a`` unless ``b`` is greater (a NaN first stays)."""
    return b if b > a else a


@numba.njit(cache=True)
def start(breakpoints, rtol, atol, fill):
    """The state before the first evaluation: the pieces of ``breakpoints`` pending."""
    row = np.asarray(breakpoints, np.float64)
    count = 0
    for i in range(row.size - 1):
        if _kept_piece(row[i], row[i + 1]):
            count += 1
    p_lo, p_hi = np.empty(count), np.empty(count)
    count = 0
    for i in range(row.size - 1):
        if _kept_piece(row[i], row[i + 1]):
            p_lo[count], p_hi[count] = row[i], row[i + 1]
            count += 1
    ints = np.zeros(8, np.int64)
    ints[_FILL] = fill
    ints[_EXHAUSTED] = 1
    ints[_FIRST] = 1
    floats = np.array([float(rtol), float(atol), 0.0, 0.0])
    empty_f, empty_i = np.zeros(0), np.zeros(0, np.int64)
    groups = np.zeros((2, 2), np.int64)          # (pieces, count) of at most two groups
    return (empty_f, empty_f, np.zeros((4, 0)), empty_f, np.zeros(0, np.bool_), empty_i,
            p_lo, p_hi, empty_i, groups, np.zeros(0, np.bool_), ints, floats)


@numba.njit(cache=True)
def _kept_piece(a, b):
    """Whether the numpy driver keeps the piece [a, b] of a breakpoint row: not empty, both ends finite."""
    return b > a and math.isfinite(a) and math.isfinite(b)


@numba.njit(cache=True)
def finished(st):
    return st[11][_FINISHED] == 1


@numba.njit(cache=True)
def pending(st):
    """The 21 nodes of every pending interval, (m, 21): mid + half · x, as the numpy driver forms them."""
    p_lo, p_hi = st[6], st[7]
    m = p_lo.size
    x = np.empty((m, 21))
    for i in range(m):
        half = 0.5 * (p_hi[i] - p_lo[i])
        mid = 0.5 * (p_lo[i] + p_hi[i])
        for j in range(21):
            x[i, j] = mid + half * _X[j]
    return x


@numba.njit(cache=True)
def _rows(high, low, extra, p_lo, p_hi):
    """Kronrod sum, Gauss sum, known error and Kronrod sum of |f| per interval, each times its half-width."""
    m = p_lo.size
    out = np.empty((4, m))
    for i in range(m):
        k = g = e = a = 0.0
        for j in range(21):
            k += high[i, j] * _WK[j]
            g += low[i, j] * _WG[j]
            e += abs(extra[i, j]) * _WK[j]
            a += abs(high[i, j]) * _WK[j]
        half = 0.5 * (p_hi[i] - p_lo[i])
        out[0, i], out[1, i], out[2, i], out[3, i] = k * half, g * half, e * half, a * half
    return out


@numba.njit(cache=True)
def _unrefinable(lo, hi, err, extra):
    out = np.empty(lo.size, np.bool_)
    for i in range(lo.size):
        tiny = (hi[i] - lo[i]) <= 64 * _EPS * max(abs(lo[i]), abs(hi[i]))
        out[i] = tiny or not math.isfinite(err[i]) or err[i] <= extra[i]
    return out


@numba.njit(cache=True)
def absorb(st, high, low, extra):
    """The state after the kernel's values ``high``, ``low``, ``extra`` at :func:`pending`'s nodes."""
    lo, hi, vals, err, fixed, stalls, p_lo, p_hi, g_idx, groups, split, ints, floats = st
    c_vals = _rows(high, low, extra, p_lo, p_hi)
    m = p_lo.size
    c_err = np.empty(m)
    for i in range(m):
        c_err[i] = abs(c_vals[0, i] - c_vals[1, i])
    ints[_EVALUATIONS] += m * 21
    if ints[_FIRST] == 1:
        ints[_FIRST] = 0
        lo, hi, vals, err = p_lo, p_hi, c_vals, c_err
    else:
        ints[_ROUNDS] += 1
        c_stalls = _child_stalls(groups, g_idx, c_err, err, stalls)
        c_fixed = _unrefinable(p_lo, p_hi, c_err, c_vals[2])
        lo, hi, vals, err, fixed, stalls = _merged(split, lo, hi, vals, err, fixed, stalls,
                                                   p_lo, p_hi, c_vals, c_err, c_fixed, c_stalls)
        if ints[_ROUNDS] >= MAX_ROUNDS:
            _finish_from_intervals(vals, err, ints, floats)
            return (lo, hi, vals, err, fixed, stalls, p_lo, p_hi, g_idx, groups, split, ints, floats)
    return _decide(lo, hi, vals, err, fixed, stalls, ints, floats)


@numba.njit(cache=True)
def _merged(split, lo, hi, vals, err, fixed, stalls, c_lo, c_hi, c_vals, c_err, c_fixed, c_stalls):
    """The intervals not split, in order, then the pieces: the numpy driver's order."""
    kept = 0
    for i in range(split.size):
        if not split[i]:
            kept += 1
    n = kept + c_lo.size
    n_lo, n_hi, n_vals, n_err = np.empty(n), np.empty(n), np.empty((4, n)), np.empty(n)
    n_fixed, n_stalls = np.empty(n, np.bool_), np.empty(n, np.int64)
    j = 0
    for i in range(split.size):
        if not split[i]:
            _copy_interval(lo, hi, vals, err, fixed, stalls, i, n_lo, n_hi, n_vals, n_err, n_fixed, n_stalls, j)
            j += 1
    for i in range(c_lo.size):
        _copy_interval(c_lo, c_hi, c_vals, c_err, c_fixed, c_stalls, i, n_lo, n_hi, n_vals, n_err, n_fixed, n_stalls, j)
        j += 1
    return n_lo, n_hi, n_vals, n_err, n_fixed, n_stalls


@numba.njit(cache=True)
def _copy_interval(lo, hi, vals, err, fixed, stalls, i, n_lo, n_hi, n_vals, n_err, n_fixed, n_stalls, j):
    n_lo[j], n_hi[j], n_err[j], n_fixed[j], n_stalls[j] = lo[i], hi[i], err[i], fixed[i], stalls[i]
    for r in range(4):
        n_vals[r, j] = vals[r, i]


@numba.njit(cache=True)
def _child_stalls(groups, g_idx, c_err, err, stalls):
    out = np.empty(c_err.size, np.int64)
    start = 0
    first = 0
    for k in range(2):
        s, count = groups[k, 0], groups[k, 1]
        if count == 0:
            continue
        levels = int(math.log2(s) + 0.5)
        for i in range(count):
            parent = g_idx[first + i]
            kept = 0.0
            largest = -np.inf
            for piece in range(s):
                e = c_err[start + piece * count + i]
                kept += e
                largest = max(largest, e)
            localised = largest >= _LOCALISED * kept
            no_gain = kept > 0.8 * err[parent]
            level = (stalls[parent] + (0 if localised else levels)) if no_gain else 0
            for piece in range(s):
                out[start + piece * count + i] = level
        start += s * count
        first += count
    return out


@numba.njit(cache=True)
def _sums(vals, err):
    high = low = extra = absval = total = 0.0
    for i in range(err.size):
        high += vals[0, i]
        low += vals[1, i]
        extra += vals[2, i]
        absval += vals[3, i]
        total += err[i]
    return high, low, extra, absval, total


@numba.njit(cache=True)
def _finish(low, extra, absval, total, ints, floats):
    error = _SAFETY * total + extra + 50 * _EPS * absval
    met = error <= _larger(floats[_RTOL] * abs(low), floats[_ATOL])
    ints[_STATUS] = CONVERGED if met else BUDGET_EXHAUSTED if ints[_EXHAUSTED] == 1 else STALLED
    ints[_FINISHED] = 1
    floats[_VALUE], floats[_ERROR] = low, error


@numba.njit(cache=True)
def _finish_from_intervals(vals, err, ints, floats):
    _, low, extra, absval, total = _sums(vals, err)
    _finish(low, extra, absval, total, ints, floats)


@numba.njit(cache=True)
def _budget(tol, floor):
    return _larger(tol - floor, 0.25 * tol) / _SAFETY


@numba.njit(cache=True)
def _still_open(total, movable, budget):
    return total > budget and movable > _larger(budget - (total - movable), 0.05 * total)


@numba.njit(cache=True)
def _decide(lo, hi, vals, err, fixed, stalls, ints, floats):
    """The top of the numpy driver's loop: stop (met, nothing to refine, too many intervals) or
    choose the intervals to split and their pieces, which become the pending ones."""
    high, low, extra, absval, total = _sums(vals, err)
    budget = _budget(_larger(floats[_RTOL] * abs(high), floats[_ATOL]), extra + 50 * _EPS * absval)
    n = err.size
    if not total > budget:                     # met (or NaN)
        ints[_EXHAUSTED] = 0
        _finish(low, extra, absval, total, ints, floats)
        return _stopped(lo, hi, vals, err, fixed, stalls, ints, floats)
    if ints[_FIXED_READY] == 0:
        fixed = _unrefinable(lo, hi, err, vals[2])
        stalls = np.zeros(n, np.int64)
        ints[_FIXED_READY] = 1
    movable = 0.0
    for i in range(n):
        if not (fixed[i] or stalls[i] >= _STALL_LIMIT):
            movable += err[i]
    open_ = _still_open(total, movable, budget)
    cand = np.zeros(n, np.bool_)
    worst = -np.inf
    if open_:
        open_ = False
        for i in range(n):
            cand[i] = not (fixed[i] or stalls[i] >= _STALL_LIMIT)
            if cand[i]:
                open_ = True
                worst = max(worst, err[i])
    if not open_:
        ints[_EXHAUSTED] = 0
        _finish(low, extra, absval, total, ints, floats)
        return _stopped(lo, hi, vals, err, fixed, stalls, ints, floats)
    if n > MAX_INTERVALS:
        _finish(low, extra, absval, total, ints, floats)
        return _stopped(lo, hi, vals, err, fixed, stalls, ints, floats)
    split = np.empty(n, np.bool_)
    for i in range(n):
        split[i] = cand[i] and err[i] >= worst / 8
    fill = ints[_FILL]
    if fill:
        needed = _needed(cand, err, total, budget)
        for i in range(n):
            split[i] = split[i] or needed[i]
    idx = _indices(split)
    g_idx, groups = _split_groups(idx, stalls, lo, hi, fill)
    p_lo, p_hi = _children(lo, hi, g_idx, groups)
    return (lo, hi, vals, err, fixed, stalls, p_lo, p_hi, g_idx, groups, split, ints, floats)


@numba.njit(cache=True)
def _stopped(lo, hi, vals, err, fixed, stalls, ints, floats):
    """The state of a finished run (:func:`_finish` called): its intervals, nothing pending."""
    empty_f, empty_i = np.zeros(0), np.zeros(0, np.int64)
    return (lo, hi, vals, err, fixed, stalls, empty_f, empty_f, empty_i, np.zeros((2, 2), np.int64),
            np.zeros(err.size, np.bool_), ints, floats)


@numba.njit(cache=True)
def _needed(cand, err, total, budget):
    """The numpy driver's :func:`.gauss_kronrod._needed` for one element: the candidates by descending
    error (ties in index order, as a stable sort), taken until the rest is within ``budget``."""
    order = _by_descending_error(_indices(cand), err)
    out = np.zeros(cand.size, np.bool_)
    cum = 0.0
    for i in order:
        cum += err[i]
        out[i] = total - (cum - err[i]) > budget
    return out


@numba.njit(cache=True)
def _indices(mask):
    """``np.flatnonzero(mask)``."""
    count = 0
    for i in range(mask.size):
        if mask[i]:
            count += 1
    out = np.empty(count, np.int64)
    count = 0
    for i in range(mask.size):
        if mask[i]:
            out[count] = i
            count += 1
    return out


@numba.njit(cache=True)
def _by_descending_error(idx, err):
    """``idx`` ordered by descending ``err[idx]``, equal errors in their order (a stable merge sort;
    the candidates' errors are finite)."""
    order = idx.copy()
    scratch = np.empty_like(order)
    width = 1
    n = order.size
    while width < n:
        for left in range(0, n, 2 * width):
            mid, right = min(left + width, n), min(left + 2 * width, n)
            i, j, k = left, mid, left
            while i < mid and j < right:
                if err[order[j]] > err[order[i]]:        # strictly larger moves ahead: stable
                    scratch[k] = order[j]
                    j += 1
                else:
                    scratch[k] = order[i]
                    i += 1
                k += 1
            while i < mid:
                scratch[k] = order[i]
                i += 1
                k += 1
            while j < right:
                scratch[k] = order[j]
                j += 1
                k += 1
        order, scratch = scratch, order
        width *= 2
    return order


@numba.njit(cache=True)
def _split_groups(idx, stalls, lo, hi, fill):
    """The numpy driver's groups: (indices, [[pieces, count], ...]), pieces ascending."""
    groups = np.zeros((2, 2), np.int64)
    k = idx.size
    if 2 * k >= fill:
        groups[0, 0], groups[0, 1] = 2, k
        return idx, groups
    s = int(min(_MAX_PIECES, 2.0 ** math.ceil(math.log2(fill / k))))
    many = np.empty(k, np.bool_)
    for i in range(k):
        j = idx[i]
        wide = (hi[j] - lo[j]) > s * 64 * _EPS * max(abs(lo[j]), abs(hi[j]))
        many[i] = stalls[j] == 0 and wide
    n_many = 0
    for i in range(k):
        if many[i]:
            n_many += 1
    if n_many == k:
        groups[0, 0], groups[0, 1] = s, k
        return idx, groups
    ordered = np.empty(k, np.int64)
    j = 0
    for want in (False, True):               # two pieces first, then s
        for i in range(k):
            if many[i] == want:
                ordered[j] = idx[i]
                j += 1
    row = 0
    if n_many < k:
        groups[row, 0], groups[row, 1] = 2, k - n_many
        row += 1
    if n_many:
        groups[row, 0], groups[row, 1] = s, n_many
    return ordered, groups


@numba.njit(cache=True)
def _children(lo, hi, g_idx, groups):
    """The pieces of every group, piece-major, with the numpy driver's cuts: 0.5 a + 0.5 b for two,
    a (1 − j/s) + b j/s for s."""
    size = groups[0, 0] * groups[0, 1] + groups[1, 0] * groups[1, 1]
    c_lo, c_hi = np.empty(size), np.empty(size)
    start = first = 0
    for k in range(2):
        s, count = groups[k, 0], groups[k, 1]
        if count == 0:
            continue
        for i in range(count):
            a, b = lo[g_idx[first + i]], hi[g_idx[first + i]]
            if s == 2:
                mid = a * 0.5 + b * 0.5
                c_lo[start + i], c_hi[start + i] = a, mid
                c_lo[start + count + i], c_hi[start + count + i] = mid, b
            else:
                previous = a
                for piece in range(s):
                    if piece == s - 1:
                        cut = b
                    else:
                        f = (piece + 1) / s
                        cut = a * (1.0 - f) + b * f
                    c_lo[start + piece * count + i], c_hi[start + piece * count + i] = previous, cut
                    previous = cut
        start += s * count
        first += count
    return c_lo, c_hi


@numba.njit(cache=True)
def result(st):
    """(value, error, evaluations, status code, refinement rounds) of a finished state."""
    ints, floats = st[11], st[12]
    return floats[_VALUE], floats[_ERROR], ints[_EVALUATIONS], ints[_STATUS], ints[_ROUNDS]


# numba keys its cache on this file alone: drop it when a module this one depends on has changed
compiled.drop_stale_cache(sys.modules[__name__])
