"""Albedo integrals a(L) = ∫ f(L, V) cos θ_V dω_V (eq. 1.18 / 2.2) in lobe-following coordinates.

Coordinates.  V is written in a frame whose pole is the lobe's axis — the mirror direction R
(β = α, dω_V = sin α dα dφ) or the normal for the half vector H (β = δ, dω_V = 4 (L·H) dω_H) —
and the radial angle β is replaced by the lobe's cumulative weight t (:mod:`.lobes`).

Azimuth.  In both frames N·V = A + B cos φ with B ≥ 0 (mirror: A = cos α cos θ, B = sin α sin θ;
half: A = cos 2δ cos θ, B = sin 2δ sin θ), and L·H is likewise linear in cos φ.  Every kink the
models declare (the horizon N·V = 0, N·V = N·L of max(N·L, N·V), the switches of the
Torrance–Sparrow G) is therefore a level of a linear function of cos φ, found in closed form;
between these breakpoints the integrand is smooth and a Gauss–Kronrod pair integrates it.  The
piece that ends at the horizon uses φ = φ_h − (φ_h − φ_0)(1 − u)², which removes the square-root
endpoint behaviour of √(N·V) (Ward) at the horizon.

Radial breakpoints.  A level set N·V = c enters or leaves the circle of radius β at
β = arccos c ∓ θ and β = θ − arccos c (half frame: 2δ instead of β); these are passed to the
adaptive driver so that the outer integrand is smooth on every interval.

Half-planes through N.  A model may declare kinks on half-planes φ_V = const (``azimuth_levels``,
none for the thesis's models, whose breakpoints are therefore unchanged by them): on each circle the
φ where V crosses one are found by a scan and bisection (:func:`_azimuth_cuts`), with cuts graded
toward the half-planes' common edge N, and the radii where a half-plane starts or stops cutting the
circles are radial breakpoints (:func:`_azimuth_radial_breakpoints`).

The lobe's :class:`~brdfs.physics.lobes.Frame` (mirror or half) chooses the coordinates; a model
symmetric about the plane of incidence (``symmetric_about_incidence_plane``, every model the engine
integrates) has φ run over [0, π] and the result doubled.
"""
from __future__ import annotations

import bisect
import math
from typing import NamedTuple

import numpy as np

from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.physics.lobes import HALF, MIRROR
from brdfs.core.gauss_kronrod import GAUSS_WEIGHTS, KRONROD_WEIGHTS, NODES, NodeValues, integrate, node_values
from brdfs.numerics.integrate.grouping import first_of_model, indices_by_model
from brdfs.numerics.integrate.mean import QUIET

_U = 0.5 * (NODES + 1.0)            # Kronrod nodes on [0, 1]
_WK = 0.5 * KRONROD_WEIGHTS
_WG = 0.5 * GAUSS_WEIGHTS
SUBPIECES = 2
#: cos θ below which the azimuthal rule also bounds the rounding noise of f (θ > 88.85°).
GRAZING_MU = 0.02
# Ward (√(N·V) at the horizon): with 2 sub-pieces its φ-rule left a bias of 2.4e-13 (m = 0.1, 76°) that
# the Kronrod–Gauss pair did not show (reported 1.5e-13; the disk reference and scipy's quad agree on
# the value); 8 sub-pieces remove it.
SUBPIECES_SQRT = 8
#: φ/φ_h of the graded cuts for a model with a kink at V = N (``kink_at_normal``).
KINK_GRADING = 10.0 ** -np.arange(1.0, 7.0)
#: Multiples of the cone's φ-width at the radius of a node (half frame), cut as well.
KINK_LAYER = 4.0 ** np.arange(-1.0, 4.0)
_EPS = np.finfo(float).eps


def albedo_many(models, theta_deg, rtol=1e-10, atol=1e-14):
    """Albedo of ``models[i]`` at ``theta_deg[i]`` for every i, in one adaptive run."""
    theta_deg = np.asarray(theta_deg, float).ravel()
    models = list(models)
    if len(models) != theta_deg.size:
        raise ValueError("albedo_many needs one model per angle")
    index = first_of_model(models)   # the same model object at many angles is evaluated together
    mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    bp, t0 = radial_breakpoints_many(models, mu, st, theta_deg, touch=True, layer_max=TANGENCY_LAYER_MAX_2D)

    def integrand(t, elem):
        high = np.empty_like(t)
        low = np.empty_like(t)
        rounding = np.empty_like(t)     # the lobe's evaluation error, which no rule refines away
        for k in np.unique(index[elem]):
            rows = index[elem] == k
            e = elem[rows]
            high[rows], low[rows], noise = _azimuthal(models[k], t[rows], mu[e, None], st[e, None])
            rounding[rows] = models[k].lobe.rounding * _EPS * np.abs(high[rows]) + noise
        return NodeValues(high, low, rounding)

    bp, *onset = horizon_onset(bp, t0)
    return integrate(square_root_onset(integrand, *onset), bp, rtol=rtol, atol=atol, chunk=192)


class Kinks(NamedTuple):
    """The kink radii found numerically (:func:`_lh_radial_brackets`) as brackets [lo, hi] in t,
    flattened over the elements (``element``: the element of each): the breakpoint sits at their
    midpoint, the kink anywhere in between."""

    element: np.ndarray
    lo: np.ndarray
    hi: np.ndarray


def radial_breakpoints_many(models, mu, st, theta_deg, tail=None, root_rtol=None, kinks=False, touch=False,
                            layer_max=None, graded=False):
    """Breakpoints in t of ``models[i]`` at incidence ``theta_deg[i]`` (cos ``mu``, sin ``st``), one
    row per element, ascending and NaN-padded (:func:`.gauss_kronrod.integrate`'s ragged form):
    the range ends, the radii where N·V level sets touch the circles (closed form), the radii where
    L·H levels change how they cut the circles (found numerically, :func:`_lh_radial_brackets`),
    the lobe's tail 1 − t = ``tail`` (:data:`TAIL` by default), and graded points at the two ends of
    the range where an endpoint singularity sits (:data:`HEAD`, :data:`END`).  The elements of one
    model are handled together, and the 1-D route (:mod:`.azimuthal`) uses the same rows.

    ``root_rtol`` (:data:`ROOT_RTOL` by default) is the precision of the kink radii found
    numerically; with ``kinks`` True, also returns their brackets (:class:`Kinks`), from which a
    caller that loosens ``root_rtol`` bounds what a misplaced kink costs; with ``touch`` True, last,
    the radius t0 where the circles first reach below the horizon, as it stands in each row (NaN where
    :func:`horizon_onset` has none), so that :func:`horizon_onset` need not compute it again;
    ``layer_max`` (:data:`TANGENCY_LAYER_MAX` by default) the widest tangency layer, relative to its
    radius, that is cut (:func:`_tangency_layers`); with ``graded`` True, the first partition is graded
    toward the radii where the declared N·V levels touch the circles (:data:`LEVEL_GRADING`) and
    toward the range's end wherever it lies (:data:`END`), for a single angle at a tight tolerance."""
    tail = TAIL if tail is None else tail
    layer_max = TANGENCY_LAYER_MAX if layer_max is None else layer_max
    root_rtol = ROOT_RTOL if root_rtol is None else root_rtol
    groups = [range(1)] if len(models) == 1 else indices_by_model(models)
    if len(groups) == 1:                   # one model (a curve, or a single angle): no regrouping
        rows, brackets, t0 = _radial_breakpoints(models[0], mu, st, theta_deg, tail, root_rtol, layer_max, graded)
    else:
        rows, brackets, t0 = [None] * len(models), [None] * len(models), np.full(len(models), np.nan)
        for members in groups:
            idx = np.array(members)
            found = _radial_breakpoints(models[idx[0]], mu[idx], st[idx], theta_deg[idx], tail, root_rtol, layer_max,
                                        graded)
            for i, row, bracket in zip(members, *found[:2]):
                rows[i], brackets[i] = row, bracket
            t0[idx] = found[2]
    if len(rows) == 1:
        out = rows[0][None]
    else:
        out = np.full((len(rows), max(r.size for r in rows)), np.nan)
        for out_row, row in zip(out, rows):
            out_row[:row.size] = row
    result = (out,)
    if kinks and len(brackets) == 1:
        lo, hi = brackets[0]
        result += (Kinks(np.zeros(lo.size, np.intp) if lo.size else _NO_ELEMENTS, lo, hi),)
    elif kinks:
        element = np.concatenate([np.full(lo.size, i) for i, (lo, _) in enumerate(brackets)]).astype(np.intp)
        result += (Kinks(element, np.concatenate([lo for lo, _ in brackets]), np.concatenate([hi for _, hi in brackets])),)
    if touch:
        result += (t0,)
    return result[0] if len(result) == 1 else result


#: The elements of no kinks (read only: a single angle without kinks found numerically shares it).
_NO_ELEMENTS = np.zeros(0, np.intp)
_NO_ELEMENTS.flags.writeable = False


def horizon_onset(bp, t0, min_span=None):
    """The breakpoint rows ``bp`` with the onset interval split, and per element that interval
    (lo, hi): it starts at the radius where the circles first reach below the horizon (β = π/2 − θ
    mirror frame, δ = (π/2 − θ)/2 half frame) and ends at the next breakpoint, or halfway to it where
    that lies beyond 4 lo (the new breakpoint); NaN where there is none (θ = 0, the radius past the
    lobe's range, or the next breakpoint within 2 lo).

    Beyond that radius the cut-off part of the circle grows like √(t − lo): the radial integrand of an
    indicator kernel (Cook–Torrance with G = 1) rises like arccos √(lo / t), a square-root onset and a
    knee of width ≈ lo.  Near grazing lo is tiny (1.4e-7 for m = 0.23 at 89.99°) and the interval
    [lo, hi] long, and on the pieces bisection made of it K − G understated the error (1.28× at rtol
    1e-10).  :func:`square_root_onset` integrates the onset interval in w, t = lo cosh² w, which grades
    it geometrically; the split keeps that grading away from what lies beyond the next breakpoint
    (the lobe's tail at 1 − t = 1e-3: Blinn n = 12.46 at 84.56°, graded up to it, was 2.4×
    over-confident at rtol 1e-4).

    ``t0`` is that radius per element, as :func:`radial_breakpoints_many` returns it with ``touch``
    (the row holds it exactly); ``min_span`` (:data:`ONSET_MIN_SPAN` by default) the shortest onset
    interval, relative to its start, that is mapped."""
    min_span = ONSET_MIN_SPAN if min_span is None else min_span
    if bp.shape[0] == 1:
        return _horizon_onset_of_one(bp, float(t0[0]), min_span)
    rows = np.concatenate([bp, np.full((bp.shape[0], 1), np.nan)], axis=1)
    at = rows == t0[:, None]
    end = rows[np.arange(bp.shape[0]), np.argmax(at, axis=1) + 1]
    ok = at.any(axis=1) & (t0 > ONSET_MIN_T) & np.isfinite(end) & (end > min_span * t0)   # NaN compares False
    lo, hi = np.where(ok, t0, np.nan), np.where(ok, end, np.nan)
    split = np.isfinite(lo) & (hi > ONSET_SPLIT * lo)
    if not split.any():
        return bp, lo, hi
    hi = np.where(split, 0.5 * (lo + hi), hi)
    extra = np.where(split, hi, np.nan)[:, None]
    return np.sort(np.concatenate([bp, extra], axis=1), axis=1), lo, hi


def _horizon_onset_of_one(bp, t0, min_span):
    """:func:`horizon_onset` of a single row, on Python floats (the same arithmetic: a single angle's
    handful of array operations cost more than their work)."""
    row = bp[0].tolist()
    lo = hi = math.nan
    if t0 in row:                                       # NaN is in no row
        end = row[row.index(t0) + 1] if row.index(t0) + 1 < len(row) else math.nan
        if t0 > ONSET_MIN_T and math.isfinite(end) and end > min_span * t0:
            lo, hi = t0, end
    if math.isfinite(lo) and hi > ONSET_SPLIT * lo:
        hi = 0.5 * (lo + hi)
        if row[-1] == row[-1]:                          # no NaN padding (ascending rows keep it last)
            bisect.insort(row, hi)
            bp = np.array([row])
        else:
            bp = np.sort(np.concatenate([bp, [[hi]]], axis=1), axis=1)
    return bp, np.array([lo]), np.array([hi])


#: An onset interval longer than this many times its start is split in half (:func:`horizon_onset`).
ONSET_SPLIT = 4.0
#: Only an onset interval that ends beyond this many times its start is mapped: on a shorter one the
#: knee (width ≈ lo) fills the interval, whose √ endpoint bisection resolves as before (a single angle
#: at moderate incidence, where the onset lies in the lobe's tail near t = 1, keeps its cost).
ONSET_MIN_SPAN = 2.0


def square_root_onset(integrand, lo, hi):
    """``integrand`` with its interval [lo, hi] of each element (:func:`horizon_onset`) integrated in
    w, t = lo cosh² w = lo + lo sinh² w, w ∈ [0, W], sinh² W = (hi − lo) / lo (written on s ∈ [lo, hi],
    w = W (s − lo) / (hi − lo), so the breakpoints stay; Jacobian lo sinh 2w · W / (hi − lo)).

    Near the onset t − lo = lo sinh² w, so a √(t − lo) onset becomes sinh w, and the knee of width
    ≈ lo that follows it, arccos √(lo / t) = arccos(1 / cosh w), the Gudermannian gd w: analytic in the
    strip |Im w| < π/2, whatever lo.  Further out t ≈ lo e^{2w} / 4 grades the interval geometrically.
    (A plain t = lo + (hi − lo) u² removes the onset but leaves the knee at u ≈ √(lo / hi), unseen
    by the nodes of one interval: Phong n = 512 at 89.9995° was 1.7× over-confident with it.)
    Unchanged where every ``lo`` is NaN."""
    if lo.size == 1:
        return _square_root_onset_of_one(integrand, float(lo[0]), float(hi[0]))
    if not np.isfinite(lo).any():
        return integrand
    with np.errstate(invalid="ignore"):
        # sinh² W = (hi − lo) / lo from the difference, which is exact next to t = 1 (hi / lo is not)
        span = np.arcsinh(np.sqrt((hi - lo) / lo))

    def substituted(s, elem):
        # an interval lies inside [lo, hi] or outside it (lo and hi are breakpoints): its middle node says which
        start, stop = lo[elem], hi[elem]
        middle = s[:, s.shape[1] // 2]
        rows = np.flatnonzero((middle > start) & (middle < stop))
        if not rows.size:
            return integrand(s, elem)
        a, b = start[rows, None], stop[rows, None]
        return _mapped(integrand, s, elem, rows, a, span[elem[rows], None] / (b - a))
    return substituted


def _mapped(integrand, s, elem, rows, a, scale):
    """``integrand`` at the nodes ``s``, those of the intervals ``rows`` mapped by t = a cosh² w,
    w = (s − a) · ``scale`` (:func:`square_root_onset`), with the Jacobian."""
    w = (s[rows] - a) * scale
    t = s.copy()
    t[rows] = a + a * np.sinh(w) ** 2
    jac = a * np.sinh(2.0 * w) * scale
    out = node_values(integrand(t, elem))

    def scaled(values):
        values = np.array(values, float)
        values[rows] *= jac
        return values
    high = scaled(out.high)
    low = high if out.low is out.high else scaled(out.low)
    return NodeValues(high, low, None if out.extra_err is None else scaled(out.extra_err))


def _square_root_onset_of_one(integrand, lo, hi):
    """:func:`square_root_onset` of a single element (``lo``, ``hi`` as Python floats): the same
    arithmetic, with the element's numbers as numbers instead of gathered per interval (IEEE operations
    give the same bits either way, ``math.sqrt`` and ``np.sqrt`` are both correctly rounded, and W is
    numpy's ``arcsinh``), in fewer numpy calls and without a ``np.errstate``: :func:`horizon_onset`
    gives one element either no interval (NaN) or 0 < lo < hi, where nothing can warn."""
    if 0.0 < lo < hi:                                   # NaN (no onset interval) compares False
        return _square_root_onset_of_one_with(integrand, lo, hi, float(np.arcsinh(math.sqrt((hi - lo) / lo))))
    if not math.isfinite(lo):
        return integrand
    with np.errstate(invalid="ignore"):                 # not from horizon_onset: the arrays' way
        span = float(np.arcsinh(np.sqrt((np.float64(hi) - lo) / lo)))
    return _square_root_onset_of_one_with(integrand, lo, hi, span)


def _square_root_onset_of_one_with(integrand, lo, hi, span):
    """:func:`_square_root_onset_of_one` once W = ``span`` is known."""
    scale = span / (hi - lo)

    def substituted(s, elem):
        middle = s[:, s.shape[1] // 2]
        rows = np.flatnonzero((middle > lo) & (middle < hi))
        if not rows.size:
            return integrand(s, elem)
        if rows[-1] - rows[0] == rows.size - 1:         # consecutive (the onset interval, or its pieces)
            rows = slice(int(rows[0]), int(rows[-1]) + 1)    # a view, where an index array gathers and scatters
        return _mapped(integrand, s, elem, rows, lo, scale)
    return substituted


#: Smallest onset radius t that :func:`square_root_onset` maps (cosh² w then stays far from overflow).
ONSET_MIN_T = 1e-200


def _radial_breakpoints(model, mu, st, theta_deg, tail=None, root_rtol=None, layer_max=None, graded=False):
    """Breakpoints of one model at the angles ``theta_deg`` (arrays): a list of ascending rows, a
    list of the brackets (lo, hi) of each row's numerically found kinks, and the touch radii of
    :func:`horizon_onset` (the candidate of the level N·V = 0, the first; NaN outside the half and
    mirror frames and where the circles never reach below the horizon)."""
    tail = TAIL if tail is None else tail
    layer_max = TANGENCY_LAYER_MAX if layer_max is None else layer_max
    lobe = model.lobe
    if mu.size == 1 and not has_searched_kinks(model, mu):
        return _radial_breakpoints_of_one(model, mu, st, theta_deg, tail, layer_max, graded)
    theta = np.radians(theta_deg)[:, None]
    scale = 0.5 if lobe.frame is HALF else 1.0
    beta_max = scale * (np.pi / 2 + theta)
    declared = model.nv_levels(np.asarray(mu, float))
    # np.full, np.array and np.minimum(np.maximum(...)): np.broadcast_to, np.stack and np.clip cost
    # several times their work on the few values of a single angle
    levels = [np.zeros(mu.shape)] + [np.full(mu.shape, c, float) for c in declared]
    # N·V = N·L passes through R, the lobe's centre
    through_centre = any(c is mu or np.array_equal(level, mu) for c, level in zip(declared, levels[1:]))
    a = np.arccos(np.minimum(np.maximum(np.array(levels).T, -1.0), 1.0))
    cand = np.concatenate([scale * (a - theta), scale * (theta - a), scale * (a + theta), beta_max], axis=1)
    cand = np.where((cand > 0) & (cand <= beta_max), cand, beta_max)
    # t of the range's end, of the candidates, of the END points and of the graded points, in one call of the lobe
    t_all = lobe.t_of(np.concatenate([beta_max, cand, beta_max * (1.0 - END),
                                      _level_grading(cand, beta_max, len(levels), graded)], axis=1))
    t_max, t_cand = t_all[:, :1], t_all[:, 1:1 + cand.shape[1]]
    t_end, t_graded = t_all[:, 1 + cand.shape[1]:1 + cand.shape[1] + END.size], t_all[:, 1 + cand.shape[1] + END.size:]
    head = t_max * HEAD if through_centre else np.empty((mu.size, 0))
    squeezed = ((t_max > 1.0 - TAIL[0]) | graded) & (t_max < 1.0)
    end = np.where(squeezed, t_end, np.nan)
    ends_of_tail = (1.0 - tail)[None] if mu.size == 1 else np.repeat((1.0 - tail)[None], mu.size, 0)
    t_pts = np.concatenate([np.zeros((mu.size, 1)), t_cand, ends_of_tail, head, end, t_graded,
                            _cone_radius(model, theta, scale),
                            _tangency_layers(lobe, a[:, 1:], theta, st, scale, beta_max, layer_max)],
                           axis=1)
    brackets = _lh_radial_brackets(model, mu, st, levels, t_max[:, 0], ROOT_RTOL if root_rtol is None else root_rtol)
    az = _azimuth_radial_breakpoints(model, mu, st, theta, beta_max)
    out = []
    for i in range(mu.size):
        row = np.concatenate([t_pts[i], 0.5 * (brackets[i][0] + brackets[i][1]), az[i]])
        out.append(_sorted_distinct(row[(row >= 0) & (row <= t_max[i, 0])]))
    onset_frame = lobe.frame is HALF or lobe.frame is MIRROR
    t0 = np.where(onset_frame & (cand[:, 0] < beta_max[:, 0]), t_cand[:, 0], np.nan)
    return out, brackets, t0


def has_searched_kinks(model, mu):
    """Whether ``model`` has kink radii found numerically (:func:`_lh_radial_brackets`) or half-planes
    through N (:func:`_azimuth_radial_breakpoints`) at the angles of cosine ``mu``."""
    lh = model.lobe.frame is HALF and len(model.lh_levels(mu, _ONE if mu.size == 1 else np.ones_like(mu))) > 0
    return lh or len(model.azimuth_levels(mu)) > 0


#: cos δ = 1 of a single angle's :func:`has_searched_kinks` (read only: np.ones_like cost it ~1 µs).
_ONE = np.ones(1)
_ONE.flags.writeable = False


def _level_grading(cand, beta_max, n_levels, graded):
    """β of the :data:`LEVEL_GRADING` points before each radius in ``cand`` (columns: the three
    tangency radii of each of ``n_levels`` levels, the horizon's first, then β_max) where a declared
    level touches the circles inside the range; β_max (a point already there) elsewhere."""
    if not graded or n_levels == 1:
        return np.empty((cand.shape[0], 0))
    declared = np.concatenate([cand[:, k * n_levels + 1:(k + 1) * n_levels] for k in range(3)], axis=1)
    inside = declared < beta_max
    return np.concatenate([np.where(inside, declared * (1.0 - g), beta_max) for g in LEVEL_GRADING], axis=1)


def _radial_breakpoints_of_one(model, mu, st, theta_deg, tail, layer_max, graded=False):
    """:func:`_radial_breakpoints` of a single angle of a model without kinks found numerically
    (:func:`has_searched_kinks`), on Python floats: its handful of values cost the array version
    some sixty numpy calls.  The same arithmetic in the same order, and the same transcendental
    functions (numpy's, each once on all of its few arguments, so that no libm ulp differs), give
    the same row to the bit (``test_single_angle``).  Its compiled twin, with :func:`horizon_onset`, is
    :func:`.azimuthal_compiled.breakpoints_of_one` (``test_azimuthal_compiled`` holds the two together)."""
    lobe = model.lobe
    theta = math.radians(float(theta_deg[0]))           # x (π/180), as np.radians: the same bits
    scale = 0.5 if lobe.frame is HALF else 1.0
    beta_max = scale * (np.pi / 2 + theta)
    declared, through_centre = declared_levels_of_one(model, mu)
    levels = [0.0] + declared
    a = level_angles_of_one(levels).tolist()
    cand = ([scale * (x - theta) for x in a] + [scale * (theta - x) for x in a] + [scale * (x + theta) for x in a]
            + [beta_max])
    cand = [c if 0.0 < c <= beta_max else beta_max for c in cand]
    n = len(levels)
    touching = [c for k in range(3) for c in cand[k * n + 1:(k + 1) * n]] if graded else []
    graded_pts = [c * (1.0 - g) if c < beta_max else beta_max for g in LEVEL_GRADING for c in touching]
    layers = _tangency_layer_radii(a[1:], theta, float(st[0]), scale, beta_max, layer_max)
    cone = [scale * theta] if model.kink_at_normal else []
    ends = [beta_max * f for f in _BEFORE_END]
    t_all = lobe.t_of(np.array([beta_max] + cand + ends + graded_pts + cone + layers)).tolist()
    t_max, t_cand = t_all[0], t_all[1:1 + len(cand)]
    t_end, t_rest = t_all[1 + len(cand):1 + len(cand) + len(ends)], t_all[1 + len(cand) + len(ends):]
    points = [0.0] + t_cand + _ends_of_tail(tail) + t_rest
    if through_centre:
        points += [t_max * h for h in _HEAD]
    if (graded or 1.0 - TAIL[0] < t_max) and t_max < 1.0:
        points += t_end
    row = np.array(_sorted_distinct_within(points, t_max))
    onset_frame = lobe.frame is HALF or lobe.frame is MIRROR
    t0 = t_cand[0] if onset_frame and cand[0] < beta_max else math.nan
    return [row], [(np.empty(0), np.empty(0))], np.array([t0])


def declared_levels_of_one(model, mu):
    """The N·V levels ``model`` declares at a single angle (cos θ ``mu``, an array of one), as Python
    floats, and whether one of them is N·V = N·L (it passes through R, the lobe's centre)."""
    m = float(mu[0])
    declared = [float(c) if isinstance(c, float) else float(np.ravel(c)[0])
                for c in model.nv_levels(np.asarray(mu, float))]
    return declared, any(c == m for c in declared)


def level_angles_of_one(levels):
    """arccos c of a single angle's levels (the horizon's 0 first, then the declared ones), numpy's
    arccos on all of them at once; the horizon's alone kept (it is every angle's)."""
    if len(levels) == 1:
        return _HORIZON_ANGLE
    return np.arccos(np.array([min(max(c, -1.0), 1.0) for c in levels]))


_HORIZON_ANGLE = np.arccos(np.array([0.0]))
_HORIZON_ANGLE.flags.writeable = False


def _sorted_distinct_within(points, t_max) -> list:
    """The distinct ``points`` (Python floats) in [0, ``t_max``], ascending: ``sorted({p for p in points
    if 0.0 <= p <= t_max})``, by ``set``, ``sorted`` and two bisections (C loops, where the comprehension
    tests each point in Python) wherever no point is NaN (their sum is not: a NaN would not sort)."""
    total = sum(points)
    if total != total:
        return sorted({p for p in points if 0.0 <= p <= t_max})
    found = sorted(set(points))
    return found[bisect.bisect_left(found, 0.0):bisect.bisect_right(found, t_max)]


def _ends_of_tail(tail) -> list:
    """t = 1 − x of the tail breakpoints ``tail`` as Python floats (the subtraction is the arrays', to
    the bit), kept for the module's tails (:data:`TAIL` and the 1-D route's), which every single angle
    passes: their ~40 subtractions cost a call ~2 µs."""
    kept = _TAIL_ENDS.get(id(tail))
    if kept is not None and kept[0] is tail:
        return kept[1]
    ends = [1.0 - x for x in tail.tolist()]
    if not tail.flags.writeable:             # a constant: kept (with it, so that its id is not reused)
        _TAIL_ENDS[id(tail)] = (tail, ends)
    return ends


_TAIL_ENDS: dict = {}


def _tangency_layer_radii(a, theta, st, scale, beta_max, layer_max):
    """β of the cuts :func:`_tangency_layers` keeps, for one angle on Python floats (``a``: arccos c of
    the declared levels), in no particular order."""
    if not a:
        return []
    x = [y + theta for y in a] + [theta - y for y in a] + [y - theta for y in a]
    sines = np.sin(np.array(x + a)).tolist()
    sin_x, sin_a = sines[:len(x)], sines[len(x):] * 3
    out = []
    for xi, sx, sa in zip(x, sin_x, sin_a):
        beta_c = scale * xi
        if sa == 0.0:                      # w = ±inf or NaN: never thin
            continue
        w = scale * abs(sx) * st / sa
        if not (0.0 < beta_c < beta_max and layer_max * beta_c > w > 64 * _EPS * beta_c):
            continue
        out += [p for p in (beta_c + s * g * w for s in (-1.0, 1.0) for g in TANGENCY_LAYER) if 0.0 < p < beta_max]
    return out


#: Cuts at β_c ± w g (g of this tuple) about a radius β_c where a declared level N·V = c touches the
#: circles (φ = 0 or π), w = B / |∂(A ± B)/∂β| there (N·V = A + B cos φ): the distance from β_c
#: over which the cut circles' φ-range of the level's far side grows to O(1) (√(2 ε B' / B) at
#: β_c − ε).  Where w is small the φ-integral changes over that layer only, next to the
#: breakpoint β_c, unseen by the nodes of one interval that ends there.  Half frame, c = N·L:
#: δ_c = θ (V = L), w = sin 2θ / 2 ≈ cos θ at grazing incidence; Oren–Nayar, whose slope in N·V
#: jumps by tan θ_L there, was 465× over-confident at 89.6° (σ = 0.1, rtol 1e-4 … 1e-8).
TANGENCY_LAYER = (1.0, 0.125)
#: Layers at most this wide relative to their radius β_c are cut (wider ones, e.g. every layer near
#: normal incidence, where w ≈ β_c, are resolved by the first partition and the driver's bisection).
TANGENCY_LAYER_MAX = 0.05
#: The same for the two-dimensional route (:func:`albedo_many`), whose φ-integral is numerical: every
#: layer narrower than its radius is cut.  There the radial integrand's (β_c − β)^(3/2) onset on an
#: interval that ends at β_c but spans a layer of w = 0.17 β_c was under-reported by K − G (Oren–Nayar
#: integrated, ρ = 0.870136, σ = 0.139879, 76.455833°, rtol 1e-4 and 1e-6: 3.0e-8 off at 2.1e-8, the
#: sweep's family ``oren_nayar_integrated``; 0.36× with the cuts, for 23 % more evaluations there).
TANGENCY_LAYER_MAX_2D = 1.0


def _tangency_layers(lobe, a, theta, st, scale, beta_max, layer_max=TANGENCY_LAYER_MAX):
    """t of the cuts of :data:`TANGENCY_LAYER` about the tangency radii of the declared N·V levels
    (``a`` = arccos c, one column per level; the horizon is :data:`END`'s), NaN where none.  With
    x = β / scale (2δ half frame, α mirror frame), N·V = cos(x − θ) at φ = 0 and cos(x + θ) at φ = π,
    so the circles touch the level at x = θ ± a and x = a − θ, where |∂(A ± B)/∂x| = sin a and
    B = sin x sin θ."""
    if a.shape[1] == 0:
        return np.empty((a.shape[0], 0))
    x = np.concatenate([a + theta, theta - a, a - theta], axis=1)
    beta_c = scale * x
    with np.errstate(divide="ignore", invalid="ignore"):
        w = scale * np.abs(np.sin(x)) * st[:, None] / np.sin(np.concatenate([a, a, a], axis=1))
    thin = (beta_c > 0) & (beta_c < beta_max) & (w < layer_max * beta_c) & (w > 64 * _EPS * beta_c)
    pts = np.concatenate([beta_c + s * g * w for s in (-1.0, 1.0) for g in TANGENCY_LAYER], axis=1)
    keep = np.concatenate([thin] * (2 * len(TANGENCY_LAYER)), axis=1) & (pts > 0) & (pts < beta_max)
    return np.where(keep, lobe.t_of(np.where(keep, pts, 0.0)), np.nan)


def _sorted_distinct(points):
    """``np.unique`` of finite points (ascending, each once), without its general-purpose wrapper."""
    points = np.sort(points)
    return points[np.concatenate([[True], points[1:] != points[:-1]])]


def _cone_radius(model, theta, scale):
    """t of the circle through N (β = θ mirror frame, δ = θ/2 half frame) for a model with a
    cone-shaped kink at V = N (``kink_at_normal``), else none: the φ-integral, smooth in t elsewhere,
    has a singular point there that one Gauss–Kronrod interval over it under-reports (Cook–Torrance
    with Smith's G, m = 0.1, 26.25°: K − G 8.6e-11 for a 2.5e-10 error)."""
    if not model.kink_at_normal:
        return np.empty((theta.shape[0], 0))
    return model.lobe.t_of(scale * theta)


#: Initial breakpoints 1 − t = 10^(−k) in the lobe's tail.  The tail (the lobe's far flank, e.g.
#: δ ≈ 15°–25° for a Beckmann lobe of m = 0.1) is squeezed into 1 − t < 1e-3, where a single
#: Gauss–Kronrod interval ending at t = 1 places none of its nodes: a kink or a dip there was
#: accepted as flat (Cook–Torrance, m = 0.1, 22°–48°: 6e-6 missed at a reported 2e-12).
TAIL = 10.0 ** -np.arange(3.0, 13.0, 3.0)
TAIL.flags.writeable = False
#: Initial breakpoints t = 10^(−k) t_max at the lobe's centre, for a model with the kink level
#: N·V = N·L (``nv_levels``): it passes through the mirror direction, the lobe's centre, so
#: the φ-integral carries odd powers of sin β ∝ √t and the radial integrand a √t endpoint
#: singularity, on which one interval's K − G understated the error 2.3 times at loose tolerances
#: (corrected Ward, m = 0.1, 65.5°, rtol 1e-6: 2.4e-7 off at a reported 1.0e-7).
HEAD = 10.0 ** -np.arange(1.0, 9.0, 1.0)
_HEAD = HEAD.tolist()
#: Initial breakpoints β = β_max (1 − 10^(−k)) before the radius where the circle leaves the upper
#: hemisphere, where that radius lies in the lobe's far flank (1 − 1e-3 < t_max < 1, the TAIL
#: points beyond t_max dropped).  There the cap N·V > 0 closes like (β_max − β)^(3/2) and t
#: squeezes that layer into 1e-6 of t: one interval [0.999, t_max] saw a 3/2 power only in its
#: last 1e-7 and its K − G understated the error 110 times (Blinn, n = 8, 64°: 5.4e-11 off at
#: rtol 1e-10).
END = 10.0 ** -np.arange(1.0, 7.0, 1.0)
#: 1 − :data:`END` as Python floats (the arrays' subtraction, to the bit), for a single angle's breakpoints:
#: the same products on numpy scalars cost it ~1.5 µs.
_BEFORE_END = (1.0 - END).tolist()
#: Initial breakpoints β = β_c (1 − g) before each radius β_c where a declared N·V level touches the
#: circles, for a single angle at a tight tolerance (``graded``).  Where the level's layer is wide
#: (w ≈ β_c, :data:`TANGENCY_LAYER`) the radial integrand closes onto β_c like (β_c − β)^(3/2), and the
#: interval of the first partition that ends there kept K − G of 4e-10 to 3e-9 (corrected Blinn, n = 2,
#: 8°–73°, its N·V = N·L level), a second round at rtol 1e-10 in 10 of 12 angles; graded by 4², 4⁴ the
#: first evaluation meets it (1.83 → 1.08 rounds, with :data:`END` wherever the range ends short of
#: t = 1 and every horizon onset mapped, ``horizon_onset(min_span=1)``).
LEVEL_GRADING = (4.0 ** -2, 4.0 ** -4)
_SCAN = 1024
#: The scan of :func:`_lh_radial_brackets` on [0, 1], sorted: uniform in t (the lobe's core) and
#: geometric in 1 − t (its tail, where the switches sit); built once (it cost a third of a call's setup).
_UNIT_SCAN = np.sort(np.concatenate([np.linspace(0.0, 1.0, _SCAN), 1.0 - np.geomspace(1e-16, 1.0, _SCAN)]))


def _lh_radial_brackets(model, mu, st, nv_levels, t_max, root_rtol):
    """Radii t (half frame) where an L·H level of ``model`` starts or stops cutting the circle
    (the level reaches φ = 0 or φ = π) or crosses an N·V level (the horizon included), per angle:
    a list of arrays, one per element of ``mu``.

    There the φ-integral — which the azimuthal breakpoints make smooth in φ — has a kink as a
    function of t (Torrance–Sparrow's masking and shadowing switches of eq. 2.10).  The levels
    depend on δ, so the radii are found numerically: sign changes on a scan uniform in t and in
    log(1 − t), then multisection to ``root_rtol`` of their distance from the ends of [0, 1], all
    angles at once.  A list, per element, of the brackets (lo, hi) of its radii."""
    lobe = model.lobe
    none = [(np.empty(0), np.empty(0))] * mu.size
    if lobe.frame is not HALF or len(model.lh_levels(mu, np.ones_like(mu))) == 0:
        return none
    # uniform in t (the lobe's core) and geometric in 1 − t (its tail, where the switches sit)
    scan = t_max[:, None] * _UNIT_SCAN

    def gaps(t, mu, st, nv_levels):
        with np.errstate(divide="ignore", invalid="ignore"):
            cb, sb = lobe.angle(np.minimum(t, np.nextafter(1.0, 0)))
        a_lh, b_lh = cb * mu, sb * st
        cos2, sin2 = (cb - sb) * (cb + sb), 2 * sb * cb
        a_nv, b_nv = cos2 * mu, sin2 * st
        out = []
        with np.errstate(divide="ignore", invalid="ignore"):
            x_nv = [(c_nv - a_nv) / b_nv for c_nv in nv_levels]
            nv_inside = [np.abs(x) <= 1 for x in x_nv]
            for c in model.lh_levels(mu, cb):
                c = c if np.shape(c) == t.shape else np.broadcast_to(c, t.shape)
                out += [a_lh + b_lh - c, a_lh - b_lh - c]
                x_lh = (c - a_lh) / b_lh
                lh_inside = np.abs(x_lh) <= 1
                for x, inside in zip(x_nv, nv_inside):
                    out.append(np.where(lh_inside & inside, x_lh - x, np.nan))
        return np.stack(out)

    def selected_gap(t, mu, st, nv_levels, which):
        """Row r of ``gaps(...)[which[r]]`` only, by the same formulas (the multisection evaluates
        one function per bracket, not all of them)."""
        width = 2 + len(nv_levels)
        j, kind = (which // width)[:, None], (which % width)[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            cb, sb = lobe.angle(np.minimum(t, np.nextafter(1.0, 0)))
            a_lh, b_lh = cb * mu, sb * st
            c = np.take_along_axis(np.stack(np.broadcast_arrays(*model.lh_levels(mu, cb), t))[:-1], j[None], 0)[0]
            tangent = np.where(kind == 0, a_lh + b_lh - c, a_lh - b_lh - c)
            if not nv_levels:
                return tangent
            cos2, sin2 = (cb - sb) * (cb + sb), 2 * sb * cb
            a_nv, b_nv = cos2 * mu, sin2 * st
            c_nv = np.stack(np.broadcast_arrays(*nv_levels, t))[:-1]
            c_nv = np.take_along_axis(c_nv, np.broadcast_to(np.maximum(kind - 2, 0), t.shape)[None], 0)[0]
            x_lh = (c - a_lh) / b_lh
            x_nv = (c_nv - a_nv) / b_nv
            inside = (np.abs(x_lh) <= 1) & (np.abs(x_nv) <= 1)
            return np.where(kind < 2, tangent, np.where(inside, x_lh - x_nv, np.nan))

    levels = [c[:, None] for c in nv_levels]
    g = gaps(scan, mu[:, None], st[:, None], levels)
    sign = np.sign(g)
    which, row, idx = np.nonzero(sign[..., :-1] * sign[..., 1:] < 0)
    if idx.size == 0:
        return none
    a, b = scan[row, idx], scan[row, idx + 1]
    sign_a = np.sign(g[which, row, idx])
    levels = [c[row, None] for c in nv_levels]
    if which.size <= _FEW_BRACKETS:
        # all gap functions on every bracket, then each bracket's own: for a few brackets the
        # functions' points cost less than selected_gap's gathering (the same values to the bit)
        brackets = np.arange(which.size)
        section = lambda x: gaps(x, mu[row, None], st[row, None], levels)[which, brackets]     # noqa: E731
    else:
        section = lambda x: selected_gap(x, mu[row, None], st[row, None], levels, which)     # noqa: E731
    a, b = _multisection(section, a, b, sign_a, root_rtol)
    return [(a[row == i], b[row == i]) for i in range(mu.size)]


#: Brackets up to which :func:`_lh_radial_brackets` evaluates every gap function in each round of the
#: multisection (a single angle: one or two brackets) rather than gathering each bracket's own.
_FEW_BRACKETS = 16
#: Points per bracket and round of :func:`_multisection` (each round narrows a bracket 2^6-fold:
#: the 60 bisections of one bracket, one call of the gap functions each, became ~8 calls).
_SECTIONS = 64
_SECTION_ROUNDS = 12
#: Precision of a kink radius, relative to its distance from either end of [0, 1] (t and 1 − t).  A
#: breakpoint off the kink by δ leaves the interval next to it a kink of slope jump J at distance δ
#: from its end, an error of order J δ², about 1e-18 of the integral at this precision: far below the
#: rounding floor of every estimate.  Narrowing to 4 ulps instead cost 7–9 rounds of the gap functions
#: per call (Cook–Torrance, m = 0.1, 48°–89°) for nothing the integral can see.
ROOT_RTOL = 1e-9


def _multisection(fn, a, b, sign_a, root_rtol=ROOT_RTOL):
    """Brackets [a, b] (arrays) of a sign change of ``fn`` narrowed to ``root_rtol`` of their
    distance from the ends of [0, 1] (or to 4 ulps): each round evaluates ``fn`` on ``_SECTIONS − 1``
    interior points of every bracket at once (shape (r, k) in, (r, k) out) and keeps the first piece
    where the sign leaves ``sign_a`` (a NaN counts as a change, as in bisection)."""
    frac = np.arange(1, _SECTIONS) / _SECTIONS
    for _ in range(_SECTION_ROUNDS):
        wanted = np.maximum(4 * np.spacing(np.maximum(np.abs(a), np.abs(b))), root_rtol * np.minimum(a, 1.0 - b))
        if np.all(b - a <= wanted):
            break
        pts = a[:, None] + (b - a)[:, None] * frac
        changed = np.sign(fn(pts)) != sign_a[:, None]
        first = np.where(changed.any(1), np.argmax(changed, 1), frac.size)   # index of the first change
        rows = np.arange(a.size)
        a_new = np.where(first > 0, pts[rows, np.maximum(first - 1, 0)], a)
        b_new = np.where(first < frac.size, pts[rows, np.minimum(first, frac.size - 1)], b)
        a, b = a_new, b_new
    return a, b


def level_cos(A, B, c, quiet=False):
    """cos φ, φ in [0, π], where A + B cos φ = c (B ≥ 0): the set A + B cos φ > c is [0, φ);
    −1 (φ = π) if the level is never reached from above, 1 (φ = 0) if always below.  ``quiet``: the
    caller already ignores numpy's divide and invalid errors (:data:`.mean.QUIET`)."""
    with QUIET if quiet else np.errstate(divide="ignore", invalid="ignore"):
        x = (c - A) / B
    x = np.where(B > 0, x, np.where(A >= c, -1.0, 1.0))
    return np.minimum(np.maximum(x, -1.0), 1.0)        # np.clip, without its dispatch cost (a hot path)


def level_azimuth(A, B, c, quiet=False):
    """φ of :func:`level_cos`."""
    return np.arccos(level_cos(A, B, c, quiet))


def _azimuthal(model, t, mu, st):
    """Inner φ-integral at radial nodes t (m, 21): returns its Kronrod and Gauss values."""
    lobe = model.lobe
    with np.errstate(divide="ignore", invalid="ignore"):
        cb, sb = lobe.angle(np.minimum(t, 0.5 + 0.5 * np.nextafter(1.0, 0)))
        jac = lobe.solid_angle_per_t(t, cb, sb)
    if lobe.frame is MIRROR:
        A_nv, B_nv = cb * mu, sb * st
        phis = []
    else:
        cos2, sin2 = (cb - sb) * (cb + sb), 2 * sb * cb
        A_nv, B_nv = cos2 * mu, sin2 * st
        phis = [level_azimuth(cb * mu, sb * st, c) for c in model.lh_levels(mu, cb)]    # L·H = cb μ + sb st cos φ
    phi_h = level_azimuth(A_nv, B_nv, 0.0)
    phis = phis + [level_azimuth(A_nv, B_nv, A_nv * 0 + c) for c in model.nv_levels(mu)]
    if model.kink_at_normal:
        # A cone-shaped kink at V = N (φ = 0 on the circle through it): graded cuts resolve the layer
        # of width ~ the circle's distance from N, which a fixed rule on [0, φ₁] cannot.
        phis = phis + [phi_h * k for k in KINK_GRADING]
        if lobe.frame is HALF:
            # and cuts at multiples of the layer's own width: the circle of radius δ passes the cone
            # point (δ = θ/2, φ = 0) at φ-distance |δ − θ/2| / sin δ, narrower than the finest fixed
            # cut for radial nodes next to θ/2 (m = 0.5, 38°–46°: stalled at 1.2–2.1 × 1e-10)
            with np.errstate(divide="ignore", invalid="ignore"):
                width = np.abs(np.arctan2(sb, cb) - 0.5 * np.arctan2(st, mu)) / sb
            phis = phis + [np.minimum(width * k, phi_h) for k in KINK_LAYER]
    if len(model.azimuth_levels(mu)):
        # the half-planes' roots, and graded cuts toward their common edge N (φ = 0 on the circle
        # through it), where φ_V turns through π within φ-distance |β − β_N| / sin β: without them a
        # half-plane at φ_V = 2.5 stalled at 3e-10 (15°, 35°); cuts at multiples of that width as
        # well (as for kink_at_normal) cost 50 % more evaluations and gained nothing
        phis = phis + _azimuth_cuts(model, cb, sb, mu, st) + [phi_h * k for k in KINK_GRADING]
    cuts = np.sort(np.stack([np.zeros_like(phi_h)] + [np.minimum(p, phi_h) for p in phis] + [phi_h], -1), -1)
    cuts = _split_pieces(cuts, SUBPIECES_SQRT if model.sqrt_at_horizon else SUBPIECES)
    lo, hi = cuts[..., :-1, None], cuts[..., 1:, None]                      # (m, 21, P, 1)
    u = _U
    phi, dphi = lo + (hi - lo) * u, (hi - lo) + 0 * u
    if model.sqrt_at_horizon:
        # last piece ends at the horizon where the integrand behaves like sqrt(N·V): cluster nodes there
        cut = (phi_h < np.pi)[..., None, None]
        lo_l, hi_l = lo[..., -1:, :], hi[..., -1:, :]
        phi[..., -1:, :] = np.where(cut, hi_l - (hi_l - lo_l) * (1 - u) ** 2, phi[..., -1:, :])
        dphi[..., -1:, :] = np.where(cut, 2 * (hi_l - lo_l) * (1 - u), dphi[..., -1:, :])
    V, extra = _directions(lobe.frame, cb, sb, mu, st, phi)
    L = np.stack(np.broadcast_arrays(st, 0.0 * st, mu), -1)[..., None, None, :]
    f = model.unchecked(L, V)
    g = f * V[..., 2] * extra * dphi
    g = np.where(f == 0, 0.0, g)          # NaN (an undefined BRDF) propagates; zero stays zero
    inside = t < 1.0                       # t = 1 is the lobe's far end, where its weight vanishes
    high = np.where(inside, 2 * np.sum(g @ _WK, axis=-1) * jac, 0.0)
    low = np.where(inside, 2 * np.sum(g @ _WG, axis=-1) * jac, 0.0)
    noise = np.zeros_like(high)
    grazing = np.broadcast_to(mu < GRAZING_MU, high.shape)[:, 0]
    if grazing.any():
        # Near grazing L + V cancels in x and f carries far more than its lobe's rounding (1e-10
        # relative and worse for narrow Beckmann lobes at 89.9999°); the rules then disagree by noise
        # that no split removes, and the driver refined it for minutes.  Bound it: a quarter of f's
        # change when V_x moves by 2 ulp (V_x carries ½ ulp), summed without cancellation.
        Vg = V[grazing].copy()
        Vg[..., 0] += 2 * np.spacing(Vg[..., 0])
        Lg = np.broadcast_to(L, V.shape)[grazing]
        df = 0.25 * np.abs(model.unchecked(Lg, Vg) - f[grazing])
        dg = np.where(np.isfinite(df), df * np.abs(V[grazing][..., 2] * np.broadcast_to(extra * dphi, f.shape)[grazing]), 0.0)
        noise[grazing] = np.where(inside[grazing], 2 * np.sum(dg @ _WK, axis=-1) * jac[grazing], 0.0)
    return high, low, noise


def _split_pieces(cuts, k):
    """Split every φ-piece into k equal parts (a shorter piece makes the 10-point Gauss rule exact
    to rounding for the trigonometric polynomials met here)."""
    lo, hi = cuts[..., :-1, None], cuts[..., 1:, None]
    parts = lo + (hi - lo) * (np.arange(k) / k)
    return np.concatenate([parts.reshape(*cuts.shape[:-1], -1), cuts[..., -1:]], -1)


def _directions(frame, cb, sb, mu, st, phi):
    """V at azimuth φ (m, 21, P, 21) on the circle of radius β; returns V and the extra Jacobian."""
    cb, sb, mu, st = (x[..., None, None] for x in (cb, sb, mu, st))
    sin_cos, sin_sin = sb * np.cos(phi), sb * np.sin(phi)
    V = np.empty(phi.shape + (3,))
    if frame is MIRROR:
        # V = cos α R + sin α (cos φ i + sin φ j), R = (−sin θ, 0, cos θ), i = (cos θ, 0, sin θ)
        V[..., 0] = sin_cos * mu - cb * st
        V[..., 1] = sin_sin
        V[..., 2] = cb * mu + sin_cos * st
        return V, 1.0
    # V = 2 (L·H) H − L, H = (sin δ cos φ, sin δ sin φ, cos δ)
    lh = st * sin_cos + mu * cb
    V[..., 0] = 2 * lh * sin_cos - st
    V[..., 1] = 2 * lh * sin_sin
    V[..., 2] = 2 * lh * cb - mu
    return V, 4 * lh


# --- kinks on half-planes through N (``azimuth_levels``) ---------------------------------------

#: φ-scan of :func:`_azimuth_cuts`: sign changes of the half-plane's equation on this many points
#: of [0, π], then bisection to rounding.
_AZIMUTH_SCAN = 128


def _half_plane_azimuths(model, mu):
    """The declared azimuths φ_V of the model's kinks, folded into [0, π] (the integrators take the
    half V_y ≥ 0 of a model symmetric about the plane of incidence), per angle: a list of arrays."""
    out = []
    for c in model.azimuth_levels(mu):
        phi = np.mod(np.broadcast_to(np.asarray(c, float), mu.shape), 2 * np.pi)
        out.append(np.minimum(phi, 2 * np.pi - phi))
    return out


def _azimuth_radial_breakpoints(model, mu, st, theta, beta_max):
    """Radii t where a half-plane φ_V = φ₀ through N starts or stops cutting the circle of radius β:
    the circle through N (its edge: β = θ mirror frame, δ = θ/2 half frame), the circle through the
    point e = (cos φ₀, sin φ₀, 0) where the half-plane meets the horizon, and (mirror frame) the circle
    tangent to the plane of N and e, β = arcsin(sin θ |sin φ₀|).  A list of arrays, one per angle;
    empty for a model that declares no ``azimuth_levels``."""
    levels = _half_plane_azimuths(model, mu)
    if not levels:
        return [np.empty(0)] * mu.size
    lobe = model.lobe
    theta = theta[:, 0]
    cand = []
    for phi0 in levels:
        if lobe.frame is MIRROR:
            # R = (−sin θ, 0, cos θ): R·e = −sin θ cos φ₀
            cand += [theta, np.arccos(np.clip(-st * np.cos(phi0), -1, 1)),
                     np.arcsin(np.clip(st * np.abs(np.sin(phi0)), 0, 1))]
        else:
            # H ∝ L + e: cos δ = cos θ / |L + e|, |L + e|² = 2 + 2 sin θ cos φ₀
            cand += [0.5 * theta, np.arccos(np.clip(mu / np.sqrt(np.maximum(2 + 2 * st * np.cos(phi0), 1e-300)), -1, 1))]
    cand = np.stack(cand, 1)
    cand = np.where((cand > 0) & (cand < beta_max), cand, beta_max)
    t = lobe.t_of(cand)
    return [row for row in t]


def _azimuth_cuts(model, cb, sb, mu, st):
    """φ in [0, π] on the circles of radius β (cos ``cb``, sin ``sb``, shape (m, 21)) where V crosses a
    declared half-plane φ_V = φ₀ (``model.azimuth_levels``): the roots of V_y cos φ₀ − V_x sin φ₀ = 0
    with V·(cos φ₀, sin φ₀, 0) ≥ 0, found by a scan and bisection (at most four per half-plane in the
    half frame, two in the mirror frame).  A list of arrays of shape (m, 21); π where there is none."""
    frame = model.lobe.frame
    grid = np.linspace(0.0, np.pi, _AZIMUTH_SCAN + 1)
    mu_b, st_b = np.broadcast_to(mu, cb.shape), np.broadcast_to(st, cb.shape)
    out = []
    for phi0 in _half_plane_azimuths(model, mu[..., 0]):
        c0, s0 = np.cos(phi0)[:, None, None], np.sin(phi0)[:, None, None]

        def gap(phi):
            V, _ = _directions(frame, cb, sb, mu_b, st_b, phi[..., None, :])
            V = V[..., 0, :, :]
            return V[..., 1] * c0 - V[..., 0] * s0, V[..., 0] * c0 + V[..., 1] * s0

        g, along = gap(np.broadcast_to(grid, cb.shape + grid.shape))
        below = g < 0                     # a root on a scan point is bracketed once, from its left
        change = (below[..., :-1] != below[..., 1:]) & (along[..., :-1] + along[..., 1:] > 0)
        for _ in range(min(4, int(change.sum(-1).max(initial=0)))):
            first = np.argmax(change, -1)
            has = np.take_along_axis(change, first[..., None], -1)[..., 0]
            a, b = grid[first], grid[first + 1]
            below_a = np.take_along_axis(below, first[..., None], -1)[..., 0]
            for _ in range(52):
                mid = 0.5 * (a + b)
                same = (gap(mid[..., None])[0][..., 0] < 0) == below_a
                a, b = np.where(same, mid, a), np.where(same, b, mid)
            out.append(np.where(has, 0.5 * (a + b), np.pi))
            np.put_along_axis(change, first[..., None], False, -1)
    return out
