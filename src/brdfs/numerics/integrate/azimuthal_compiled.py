"""The 1-D azimuthal route of a single angle, compiled (numba): kernel, onset map and driver in one call.

A replica of :func:`.azimuthal.albedo_many`'s single-element path for the kernels ``"nv"`` and
``"nv/max"`` in both frames (:data:`~brdfs.physics.lobes.MIRROR`, :data:`~brdfs.physics.lobes.HALF`) and
Ward's ``"sqrt(nv/nl)"`` (:mod:`.ward_azimuth`'s elliptic moments, with Carlson's R_D by duplication
where numpy calls scipy's ``elliprd``)
with a cosine-power lobe (:class:`~brdfs.physics.lobes.PowerCosine`) or a Beckmann microfacet lobe
(:class:`~brdfs.physics.lobes.MicrofacetLobe`), and a radial weight c cos^k β / d declared by the model
(:attr:`~brdfs.physics.models.base.BRDF.azimuth_weight_form`).  Python keeps the front door, the settings
and the transcendental functions of the breakpoints (numpy's); compiled helpers do their arithmetic, sort
and onset split (:func:`breakpoints_of_one`: :func:`.hemisphere.radial_breakpoints_many` and
:func:`.hemisphere.horizon_onset` of one angle, to the bit), and one compiled call does the rest:
:func:`.hemisphere.square_root_onset`'s substitution,
the kernel with its rounding bounds (``_RadialKernel``: the lobe's ``angle`` and ``rounding``, the
weight, the frame kernels) and the adaptive driver (:mod:`brdfs.core.gauss_kronrod_compiled`, a replica
of :func:`brdfs.core.gauss_kronrod.integrate`'s single-element path).

The formulas are those of :mod:`.azimuthal`, :mod:`.mean` and :mod:`brdfs.physics.lobes`, node by
node, in the same order of operations; the transcendental functions are libm's where numpy's are its
own SIMD ones, and the driver's sums loops where numpy's are BLAS products, so values differ in the
last ulps (``tests/numerics/test_azimuthal_compiled.py`` holds the two together).  Kink radii found
numerically (``_KinkProbes``) are not needed by these kernels' models and send a call to numpy.

Import only where :func:`brdfs.core.compiled.available` says numba is there.
"""
from __future__ import annotations

import math

import sys

import numba
import numpy as np

from brdfs.core import compiled, gauss_kronrod_compiled as gkc
from brdfs.numerics.integrate import azimuthal, hemisphere, ward_azimuth
from brdfs.physics.lobes import HALF, MIRROR

_EPS = float(np.finfo(float).eps)
_TWO_PI = 2.0 * math.pi
#: The lobes' and kernels' codes, :mod:`.azimuthal`'s (constants of the compiled code).
POWER_COSINE = azimuthal.COMPILED_POWER_COSINE
MIRROR_NV, MIRROR_NV_OVER_MAX, HALF_NV, HALF_SQRT = (azimuthal.COMPILED_KERNELS[k] for k in (
    (MIRROR, "nv"), (MIRROR, "nv/max"), (HALF, "nv"), (HALF, "sqrt(nv/nl)")))

_jit = numba.njit(cache=True, error_model="numpy", nogil=True)


@_jit
def _angle(t, lobe, p):
    """(cos β, sin β) at t of the lobe (``p``: n, or Beckmann's α): :meth:`PowerCosine.angle`,
    :meth:`MicrofacetLobe.angle` with :meth:`Beckmann.tan_of_cdf`."""
    if lobe == POWER_COSINE:
        y = math.log1p(-t) / (p + 1.0)
        c = math.exp(y)
        s = math.sqrt(max(-math.expm1(y) * (1.0 + c), 0.0))
        return c, s
    tan_b = p * math.sqrt(-math.log1p(-t))
    c = 1.0 / math.sqrt(1.0 + tan_b * tan_b)
    return c, tan_b * c


@_jit
def _positive_part(a, b):
    """J(a, b) = ∫₀^{2π} [a + b cos φ]₊ dφ (:func:`.mean.positive_part_azimuth`)."""
    if a >= b:
        return _TWO_PI * a
    if a <= -b:
        return 0.0
    phi0 = math.acos(min(max(-a / b, -1.0), 1.0))
    return 2.0 * (a * phi0 + b * math.sin(phi0))


@_jit
def _level_azimuth(a, b, c):
    """φ where a + b cos φ = c (:func:`.hemisphere.level_azimuth`)."""
    if b > 0:
        x = (c - a) / b
    elif a >= c:
        x = -1.0
    else:
        x = 1.0
    return math.acos(min(max(x, -1.0), 1.0))


@_jit
def _i2(p, q, a, b, phi, sin_phi):
    return p * a * phi + (p * b + q * a) * sin_phi + q * b * (0.5 * phi + 0.25 * math.sin(2 * phi))


@_jit
def _i2_rounding(p, q, a, b):
    return (abs(p * a) + abs(p * b + q * a) + abs(q * b)) * math.pi


@_jit
def _kernel(kernel, cb, sb, mu, st):
    """(value, rounding) of the frame kernel (:data:`.azimuthal.KERNELS`) at cos β, sin β."""
    if kernel == MIRROR_NV:
        full = _positive_part(cb * mu, sb * st)
        return full, 4 * _EPS * abs(full)
    if kernel == MIRROR_NV_OVER_MAX:
        a, b = cb * mu, sb * st
        full, low = _positive_part(a, b), _positive_part(a - mu, b)
        if mu > 0:
            return (full - low) / mu, 8 * _EPS * (abs(full) + abs(low)) / mu
        grazing = 2 * _level_azimuth(a, b, 0.0)
        return grazing, 4 * _EPS * grazing
    p, q, a, b = cb * mu, sb * st, (cb - sb) * (cb + sb) * mu, 2 * sb * cb * st
    if kernel == HALF_SQRT:
        w, rounding = _sqrt_moment(p, q, a, b)
        root = math.sqrt(mu)
        return 8 * w / root, 8 * (rounding + _EPS * abs(w)) / root
    if kernel == HALF_NV:
        phi = _level_azimuth(a, b, 0.0)
        return 8 * _i2(p, q, a, b, phi, math.sin(phi)), 64 * _EPS * _i2_rounding(p, q, a, b)
    # the half frame's "nv/max" (the last code)
    phi_h, phi_mu = _level_azimuth(a, b, 0.0 * mu), _level_azimuth(a, b, mu)
    sin_h, sin_mu = math.sin(phi_h), math.sin(phi_mu)
    if mu > 0:
        band = (_i2(p, q, a, b, phi_h, sin_h) - _i2(p, q, a, b, phi_mu, sin_mu)) / mu
        i1_mu = p * phi_mu + q * sin_mu
        rounding = 16 * _EPS * _i2_rounding(p, q, a, b) / mu
        return 8 * (i1_mu + band), 8 * (rounding + 4 * _EPS * abs(i1_mu))
    value = p * phi_h + q * sin_h
    return 8 * value, 8 * (4 * _EPS * abs(value))


# --- Ward's kernel, "sqrt(nv/nl)": :mod:`.ward_azimuth`'s complete elliptic moments ---------------

#: Carlson's stopping constant of the duplication for R_D: (ε/4)^(−1/6) (Carlson 1995, eq. 2.19).
_RD_Q = (_EPS / 4.0) ** (-1.0 / 6.0)
#: eq. (6)'s coefficients g_n (a constant array of the compiled code).
_G_COEFFS = ward_azimuth._G_COEFFS.copy()


@_jit
def _rd(x, y, z):
    """Carlson's symmetric R_D(x, y, z) (DLMF 19.16.5) by the duplication algorithm (Carlson 1995,
    Algorithm 4 with its fifth-order series), x, y ≥ 0, z > 0: the integral scipy's ``elliprd`` computes
    for :mod:`.ward_azimuth`, to a few ulps (``test_azimuthal_compiled`` measures it against mpmath)."""
    a0 = (x + y + 3.0 * z) / 5.0
    q = _RD_Q * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    dx, dy = a0 - x, a0 - y
    a, fac, total = a0, 1.0, 0.0
    while fac * q >= abs(a):
        sx, sy, sz = math.sqrt(x), math.sqrt(y), math.sqrt(z)
        lam = sx * sy + sx * sz + sy * sz
        total += fac / (sz * (z + lam))
        fac *= 0.25
        x, y, z, a = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam), 0.25 * (a + lam)
    xx, yy = dx * fac / a, dy * fac / a
    zz = -(xx + yy) / 3.0
    xy, z2 = xx * yy, zz * zz
    e2 = xy - 6.0 * z2
    e3 = (3.0 * xy - 8.0 * z2) * zz
    e4 = 3.0 * (xy - z2) * z2
    e5 = xy * z2 * zz
    series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0 + 3.0 * e5 / 26.0
    return fac * series / (a * math.sqrt(a)) + 3.0 * total


@_jit
def _scaled_rd_pair(s, c):
    """T(s, c) = s R_D(0, c, s) and t(s, c) = s R_D(0, s, c) (:func:`.ward_azimuth._scaled_rd_pair`)."""
    if s <= ward_azimuth._LIMIT_RATIO * c:
        return 3.0 / math.sqrt(c), 0.0
    return s * _rd(0.0, c, s), s * _rd(0.0, s, c)


@_jit
def _far_moment(a, b):
    """W₁ of eq. (6) for a ≥ 2b and its bound (:func:`.ward_azimuth._far_moment`)."""
    coeffs = _G_COEFFS
    r = b / a
    z = r * r
    g = coeffs[coeffs.size - 1]
    for i in range(coeffs.size - 2, -1, -1):
        g *= z
        g += coeffs[i]
    w1 = (b / math.sqrt(a)) * g * (math.pi / 4.0)
    return w1, ward_azimuth._SERIES_REL * w1


@_jit
def _sqrt_moment(p, q, a, b):
    """W(p, q, a, b) and its rounding bound (:func:`.ward_azimuth.sqrt_positive_part_moment`, with its
    constants: R_D's relative error, the switch to the series and the series' coefficients and bound)."""
    rd_rel, u = ward_azimuth._RD_REL, ward_azimuth._U
    if not a > -b:
        w0 = w1 = e0 = e1 = 0.0
        if a != a or b != b:
            w0 = w1 = e0 = e1 = math.nan
    else:
        alpha = a + b
        full = a >= b
        big, small = _scaled_rd_pair(a - b if full else b - a, alpha if full else 2.0 * b)
        w0 = 2.0 * alpha * (big + small if full else big) / 3.0
        w1 = 2.0 * alpha * (big - small if full else big + 2.0 * small) / 9.0
        e0 = (rd_rel + 8.0 * u) * w0
        if full:
            e1 = (rd_rel + 4.0 * u) * 2.0 * alpha * (big + small) / 9.0 + 4.0 * u * abs(w1)
        else:
            e1 = (rd_rel + 8.0 * u) * w1
        if a >= ward_azimuth._SERIES_SWITCH * b:
            w1, e1 = _far_moment(a, b)
    pw0, qw1 = p * w0, q * w1
    return pw0 + qw1, abs(p) * e0 + abs(q) * e1 + _EPS * (abs(pw0) + abs(qw1))


@_jit
def _radial(t, mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd):
    """(value, rounding) of w(β) K(β, θ) at t (``_RadialKernel.__call__``); the weight c cos^k β / d."""
    cb, sb = _angle(min(t, 1.0 - _EPS), lobe, p)
    value, rounding = _kernel(kernel, cb, sb, mu, st)
    weight = wc / wd if wk == 0 else wc * cb ** wk / wd
    value = weight * (value if t < 1.0 else 0.0)
    return value, weight * rounding + (lobe_rounding + 3) * _EPS * abs(value)


@_jit
def nodes(x, mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd, onset_lo, onset_hi, onset_scale):
    """Values and rounding bounds at the nodes ``x`` (m, 21): those of an interval inside the onset
    interval [lo, hi] (its middle node says which) mapped by t = lo cosh² w (:func:`.hemisphere.square_root_onset`,
    W/(hi − lo) = ``onset_scale``) and scaled by the Jacobian; no interval mapped where lo is NaN."""
    m, k = x.shape
    value, rounding = np.empty((m, k)), np.empty((m, k))
    for i in range(m):
        middle = x[i, k // 2]
        mapped = middle > onset_lo and middle < onset_hi
        for j in range(k):
            s = x[i, j]
            if mapped:
                w = (s - onset_lo) * onset_scale
                sh = math.sinh(w)
                t = onset_lo + onset_lo * (sh * sh)
                jac = onset_lo * math.sinh(2.0 * w) * onset_scale
                v, r = _radial(t, mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd)
                value[i, j], rounding[i, j] = v * jac, r * jac
            else:
                value[i, j], rounding[i, j] = _radial(s, mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd)
    return value, rounding


@_jit
def albedo_one(breakpoints, mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd, onset_lo, onset_hi, onset_scale,
               rtol, atol, fill):
    """One angle's albedo: (value, error, evaluations, status code) of the driver
    (:mod:`brdfs.core.gauss_kronrod_compiled`) on :func:`nodes`."""
    state = gkc.start(breakpoints, rtol, atol, fill)
    while not gkc.finished(state):
        value, rounding = nodes(gkc.pending(state), mu, st, lobe, p, lobe_rounding, kernel, wc, wk, wd,
                                onset_lo, onset_hi, onset_scale)
        state = gkc.absorb(state, value, value, rounding)
    value, error, evaluations, status, _ = gkc.result(state)
    return value, error, evaluations, status


# --- one angle's breakpoints: :func:`.hemisphere._radial_breakpoints_of_one`, :func:`.hemisphere.horizon_onset` ---

#: :mod:`.hemisphere`'s gradings and thresholds (constants of the compiled code).
_LEVEL_GRADING = tuple(float(g) for g in hemisphere.LEVEL_GRADING)
_TANGENCY_LAYER = tuple(float(g) for g in hemisphere.TANGENCY_LAYER)
_BEFORE_END = np.array(hemisphere._BEFORE_END)
_HEAD = np.array(hemisphere._HEAD)
_FIRST_TAIL_END = 1.0 - float(hemisphere.TAIL[0])
_ONSET_MIN_T, _ONSET_SPLIT = float(hemisphere.ONSET_MIN_T), float(hemisphere.ONSET_SPLIT)
_NO_SINES = np.empty(0)
_NO_SINES.flags.writeable = False


def breakpoints_of_one(model, mu, st, theta_deg, tail, graded, min_span):
    """The breakpoint row of one angle with its onset split and the onset interval (lo, hi), as
    :func:`.hemisphere.radial_breakpoints_many` (``touch``, one element of a model without kinks found
    numerically) and :func:`.hemisphere.horizon_onset` give them, to the bit (``test_azimuthal_compiled``).

    numpy computes every transcendental function (the levels' arccos, the tangency layers' sines and
    the lobe's ``t_of``, SIMD where libm would differ by an ulp), the compiled stages the arithmetic,
    the sort and the onset in between, on the same numbers in the same order."""
    theta = math.radians(float(theta_deg[0]))
    scale = 0.5 if model.lobe.frame is HALF else 1.0
    declared, through_centre = hemisphere.declared_levels_of_one(model, mu)
    angles = hemisphere.level_angles_of_one([0.0] + declared)
    sines = np.sin(_layer_arguments(angles, theta)) if declared else _NO_SINES
    radii = _radii(angles, sines, theta, float(st[0]), scale, graded, model.kink_at_normal,
                   hemisphere.TANGENCY_LAYER_MAX)
    frame = model.lobe.frame
    return _row_and_onset(radii, model.lobe.t_of(radii), angles.size, tail, through_centre, graded,
                          frame is HALF or frame is MIRROR, min_span)


@_jit
def _layer_arguments(angles, theta):
    """x = a + θ, θ − a, a − θ of the declared levels' angles a, then a: the arguments of the sines of
    :func:`.hemisphere._tangency_layer_radii`."""
    a = angles[1:]
    n = a.size
    out = np.empty(4 * n)
    for i in range(n):
        out[i], out[n + i], out[2 * n + i], out[3 * n + i] = a[i] + theta, theta - a[i], a[i] - theta, a[i]
    return out


@_jit
def _radii(angles, sines, theta, st, scale, graded, kink_at_normal, layer_max):
    """β of :func:`.hemisphere._radial_breakpoints_of_one`'s ``t_of`` call, in its order: β_max, the
    candidates, the points before the end, the graded points, the cone and the tangency layers."""
    n = angles.size
    beta_max = scale * (math.pi / 2 + theta)
    n_graded = 3 * (n - 1) * len(_LEVEL_GRADING) if graded else 0
    out = np.empty(1 + 3 * n + 1 + _BEFORE_END.size + n_graded + 1 + 3 * (n - 1) * 2 * len(_TANGENCY_LAYER))
    out[0] = beta_max
    k = 1
    for group in range(3):
        for i in range(n):
            x = angles[i]
            c = scale * (x - theta) if group == 0 else (scale * (theta - x) if group == 1 else scale * (x + theta))
            out[k] = c if 0.0 < c <= beta_max else beta_max
            k += 1
    out[k] = beta_max                               # the last candidate, β_max, is kept as it is
    k += 1
    for f in _BEFORE_END:
        out[k] = beta_max * f
        k += 1
    if graded:
        for g in _LEVEL_GRADING:
            for group in range(3):
                for i in range(1, n):
                    c = out[1 + group * n + i]
                    out[k] = c * (1.0 - g) if c < beta_max else beta_max
                    k += 1
    if kink_at_normal:
        out[k] = scale * theta
        k += 1
    m = 3 * (n - 1)
    for j in range(m):
        sa = sines[m + j % (n - 1)]
        if sa == 0.0:                               # w = ±inf or NaN: never thin
            continue
        xi = angles[1 + j % (n - 1)] + theta if j < n - 1 else (
            theta - angles[1 + j % (n - 1)] if j < 2 * (n - 1) else angles[1 + j % (n - 1)] - theta)
        beta_c = scale * xi
        w = scale * abs(sines[j]) * st / sa
        if not (0.0 < beta_c < beta_max and layer_max * beta_c > w > 64 * _EPS * beta_c):
            continue
        for s in (-1.0, 1.0):
            for g in _TANGENCY_LAYER:
                p = beta_c + s * g * w
                if 0.0 < p < beta_max:
                    out[k] = p
                    k += 1
    return out[:k]


@_jit
def _insert(row, size, p, distinct):
    """Insert ``p`` into the ascending ``row[:size]`` after the points equal to it (``bisect.insort``), or
    with ``distinct`` not at all where one is there (the first kept, as a set keeps it); the new size."""
    i = size
    while i > 0 and row[i - 1] > p:
        i -= 1
    if distinct and i > 0 and row[i - 1] == p:
        return size
    for j in range(size, i, -1):
        row[j] = row[j - 1]
    row[i] = p
    return size + 1


@_jit
def _row_and_onset(radii, t, n_levels, tail, through_centre, graded, onset_frame, min_span):
    """The distinct points in [0, t_max] ascending (``t``: the lobe's t of ``radii``), taken in the numpy
    path's order, and the onset split of :func:`.hemisphere.horizon_onset`: (row, lo, hi), lo = hi = NaN
    where there is no onset interval."""
    n_cand, n_ends = 3 * n_levels + 1, _BEFORE_END.size
    t_max = t[0]
    row = np.empty(t.size + tail.size + _HEAD.size + 1)
    size = _within(row, 0, 0.0, t_max)
    for i in range(n_cand):
        size = _within(row, size, t[1 + i], t_max)
    for x in tail:
        size = _within(row, size, 1.0 - x, t_max)
    for i in range(1 + n_cand + n_ends, t.size):
        size = _within(row, size, t[i], t_max)
    if through_centre:
        for h in _HEAD:
            size = _within(row, size, t_max * h, t_max)
    if (graded or _FIRST_TAIL_END < t_max) and t_max < 1.0:
        for i in range(n_ends):
            size = _within(row, size, t[1 + n_cand + i], t_max)
    lo = hi = math.nan
    t0 = t[1] if onset_frame and radii[1] < radii[0] else math.nan
    for i in range(size):
        if row[i] == t0:
            end = row[i + 1] if i + 1 < size else math.nan
            if t0 > _ONSET_MIN_T and math.isfinite(end) and end > min_span * t0:
                lo, hi = t0, end
            break
    if math.isfinite(lo) and hi > _ONSET_SPLIT * lo:
        hi = 0.5 * (lo + hi)
        size = _insert(row, size, hi, False)
    return row[:size].copy(), lo, hi


@_jit
def _within(row, size, p, t_max):
    """:func:`_insert` of ``p`` as a distinct point where it lies in [0, ``t_max``] (NaN does not)."""
    return _insert(row, size, p, True) if 0.0 <= p <= t_max else size


# numba keys its cache on this file alone: drop it when a module this one depends on has changed
compiled.drop_stale_cache(sys.modules[__name__])
