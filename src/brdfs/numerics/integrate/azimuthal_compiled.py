"""The 1-D azimuthal route of a single angle, compiled (numba): kernel, onset map and driver in one call.

A replica of :func:`.azimuthal.albedo_many`'s single-element path for the kernels ``"nv"`` and
``"nv/max"`` in both frames (:data:`~brdfs.physics.lobes.MIRROR`, :data:`~brdfs.physics.lobes.HALF`)
with a cosine-power lobe (:class:`~brdfs.physics.lobes.PowerCosine`) or a Beckmann microfacet lobe
(:class:`~brdfs.physics.lobes.MicrofacetLobe`), and a radial weight c cos^k β / d declared by the model
(:attr:`~brdfs.physics.models.base.BRDF.azimuth_weight_form`).  Python keeps what is cheap and shared
(the front door, the breakpoints :func:`.hemisphere.radial_breakpoints_many`, :func:`.hemisphere.horizon_onset`,
the settings); one compiled call does the rest: :func:`.hemisphere.square_root_onset`'s substitution,
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

import numba
import numpy as np

from brdfs.core import gauss_kronrod_compiled as gkc

_EPS = 2.220446049250313e-16
_TWO_PI = 2.0 * math.pi
#: The lobes (:attr:`LOBES` of :mod:`.azimuthal`'s compiled spec): t = 1 − cos^(n+1) β, or Beckmann's CDF.
POWER_COSINE, BECKMANN = 0, 1
#: The kernels: (frame, kernel) of ``closed_form_azimuth``.
MIRROR_NV, MIRROR_NV_OVER_MAX, HALF_NV, HALF_NV_OVER_MAX = 0, 1, 2, 3

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
    if kernel == HALF_NV:
        phi = _level_azimuth(a, b, 0.0)
        return 8 * _i2(p, q, a, b, phi, math.sin(phi)), 64 * _EPS * _i2_rounding(p, q, a, b)
    phi_h, phi_mu = _level_azimuth(a, b, 0.0 * mu), _level_azimuth(a, b, mu)
    sin_h, sin_mu = math.sin(phi_h), math.sin(phi_mu)
    if mu > 0:
        band = (_i2(p, q, a, b, phi_h, sin_h) - _i2(p, q, a, b, phi_mu, sin_mu)) / mu
        i1_mu = p * phi_mu + q * sin_mu
        rounding = 16 * _EPS * _i2_rounding(p, q, a, b) / mu
        return 8 * (i1_mu + band), 8 * (rounding + 4 * _EPS * abs(i1_mu))
    value = p * phi_h + q * sin_h
    return 8 * value, 8 * (4 * _EPS * abs(value))


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
