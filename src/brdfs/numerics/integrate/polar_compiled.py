"""The polar route's single angle compiled (numba): :func:`.polar.radial_integrand` of the distributions
and maskings it knows, their rounding bounds, the breakpoints of :func:`.polar._breakpoints_of_one` and
the driver (:mod:`brdfs.core.gauss_kronrod_compiled`) in one compiled call (issue 41, per-call cost).

Import only where :func:`brdfs.core.compiled.available` (it imports numba).  What it knows follows from
the factors a model declares (:meth:`BRDF.half_vector_factors`), never from a model's name:

* the distribution, by its exact type (a subclass may change any formula): :class:`GGX` (the rational
  ∫D dφ) and :class:`Beckmann` (Kummer's functions, :func:`kummer_half_integers`: its series, its
  asymptotic series, Cephes' i0e and the bounds, with the tables of :mod:`brdfs.physics.distributions`);
* the masking S, by the exact type of the form the model declares (:mod:`brdfs.physics.masking`,
  :data:`_MASKINGS`), whose fields it reads: Smith's G2/(4 N·L N·V) (:class:`SmithG2`: separable or
  height-correlated, λ of its own distribution, GGX or Beckmann, and roughness) and C G*(N·L) G*(N·V)/(4 N·L N·V)
  with the thesis's G* (:class:`ThesisSmith`: its roughness m and scale C).  The masking's roughness is its
  own, which need not be the distribution's.  A model whose S is not such a form (a user's function, a
  subclass that overrides the model's masking by a method) takes the numpy path.

Anything else (a user's distribution or S, a float32 or 0-d array α) goes to the numpy path, which stays
the reference: every formula here is a replica of its numpy twin, operation by operation, and
``tests/numerics/test_polar_compiled.py`` holds the two together.  They differ in the last bits where
numpy's SIMD exp, tan, arccos and log and scipy's erfc differ from the C library's by an ulp, and where
BLAS sums the Kummer series in another order than a loop.
"""
from __future__ import annotations

import math

import sys

import numba
import numpy as np

from brdfs.core import compiled, gauss_kronrod_compiled as gkc
from brdfs.numerics.integrate.polar import S_ROUNDING
from brdfs.physics import distributions as _dist
from brdfs.physics.distributions import GGX, Beckmann
from brdfs.physics.masking import G2_FORMS, SmithG2, ThesisSmith

_EPS = float(np.finfo(float).eps)
_TINY = float(np.finfo(float).smallest_subnormal)
_HALF_PI = 0.5 * np.pi

#: Distribution codes of the kernel.
GGX_CODE, BECKMANN_CODE = 0, 1
#: Masking codes of the kernel: Smith's G2/(4 N·L N·V), separable and height-correlated, and
#: C G*(N·L) G*(N·V)/(4 N·L N·V) with the thesis's G* (eq. 1.38).
SEPARABLE_CODE, HEIGHT_CORRELATED_CODE, THESIS_SMITH_CODE = 0, 1, 2
_DISTRIBUTIONS = {GGX: GGX_CODE, Beckmann: BECKMANN_CODE}
_G2_CODES = {"separable": SEPARABLE_CODE, "height_correlated": HEIGHT_CORRELATED_CODE}
assert set(_G2_CODES) == set(G2_FORMS)

# the Kummer tables of the numpy path (frozen into the compiled code as constants)
_SERIES = np.ascontiguousarray(_dist._SERIES)
_ASYMPTOTIC = np.ascontiguousarray(_dist._ASYMPTOTIC)
_ASYMPTOTIC_LOG_SCALE = np.ascontiguousarray(_dist._ASYMPTOTIC_LOG_SCALE[:, 0])
_ASYMPTOTIC_POWER = np.ascontiguousarray(_dist._ASYMPTOTIC_POWER[:, 0])
_KUMMER_SWITCH = float(_dist._KUMMER_SWITCH)
_SERIES_TERMS = int(_dist._KUMMER_SERIES_TERMS)
_ASYMPTOTIC_TERMS = int(_dist._KUMMER_ASYMPTOTIC_TERMS)
_TWO_SQRT_PI = float(_dist._TWO_SQRT_PI)

#: Cephes' Chebyshev coefficients of e^(−x) I₀(x) on [0, 8] and of e^(−x) √x I₀(x) on (8, ∞)
#: (i0e, as scipy.special and numpy's i0 carry them; the port is scipy's i0e to the bit).
_I0E_A = np.array([
    -4.41534164647933937950E-18, 3.33079451882223809783E-17, -2.43127984654795469359E-16,
    1.71539128555513303061E-15, -1.16853328779934516808E-14, 7.67618549860493561688E-14,
    -4.85644678311192946090E-13, 2.95505266312963983461E-12, -1.72682629144155570723E-11,
    9.67580903537323691224E-11, -5.18979560163526290666E-10, 2.65982372468238665035E-9,
    -1.30002500998624804212E-8, 6.04699502254191894932E-8, -2.67079385394061173391E-7,
    1.11738753912010371815E-6, -4.41673835845875056359E-6, 1.64484480707288970893E-5,
    -5.75419501008210370398E-5, 1.88502885095841655729E-4, -5.76375574538582365885E-4,
    1.63947561694133579842E-3, -4.32430999505057594430E-3, 1.05464603945949983183E-2,
    -2.37374148058994688156E-2, 4.93052842396707084878E-2, -9.49010970480476444210E-2,
    1.71620901522208775349E-1, -3.04682672343198398683E-1, 6.76795274409476084995E-1])
_I0E_B = np.array([
    -7.23318048787475395456E-18, -4.83050448594418207126E-18, 4.46562142029675999901E-17,
    3.46122286769746109310E-17, -2.82762398051658348494E-16, -3.42548561967721913462E-16,
    1.77256013305652638360E-15, 3.81168066935262242075E-15, -9.55484669882830764870E-15,
    -4.15056934728722208663E-14, 1.54008621752140982691E-14, 3.85277838274214270114E-13,
    7.18012445138366623367E-13, -1.79417853150680611778E-12, -1.32158118404477131188E-11,
    -3.14991652796324136454E-11, 1.18891471078464383424E-11, 4.94060238822496958910E-10,
    3.39623202570838634515E-9, 2.26666899049817806459E-8, 2.04891858946906374183E-7,
    2.89137052083475648297E-6, 6.88975834691682398426E-5, 3.36911647825569408990E-3,
    8.04490411014108831608E-1])


#: Intervals per call of the kernel, as :func:`brdfs.core.gauss_kronrod.integrate`'s ``chunk`` (the Kummer
#: series' terms follow each call's nodes).
CHUNK = 4096


def kernel_of(distribution, S):
    """``(distribution code, α, masking code, the masking's distribution code, its roughness, its scale)``
    of the factors ``(distribution, S)`` a model declares, or None where the compiled kernel does not
    know them (the numpy path takes those): a distribution or a masking form not exactly of a known
    type, or a number of theirs not a float (np.float64 is one; a float32, an int, a 0-d array are not)."""
    code = _DISTRIBUTIONS.get(type(distribution))
    reader = _MASKINGS.get(type(S))
    if code is None or reader is None or not isinstance(distribution.alpha, float):
        return None
    masking = reader(S)
    return None if masking is None else (code, float(distribution.alpha), *masking)


def _smith_g2(S):
    """:class:`SmithG2`: its G2 form, and λ of its own distribution (GGX or Beckmann, exactly)."""
    form, code = _G2_CODES.get(S.form), _DISTRIBUTIONS.get(type(S.distribution))
    if form is None or code is None or not isinstance(S.distribution.alpha, float):
        return None
    return form, code, float(S.distribution.alpha), 1.0


def _thesis_smith(S):
    """:class:`ThesisSmith`: the thesis's G* of its roughness m, and its scale C."""
    if not (isinstance(S.m, float) and isinstance(S.C, float)):
        return None
    return THESIS_SMITH_CODE, BECKMANN_CODE, float(S.m), float(S.C)


#: The masking forms the kernel knows, by exact type, and what it reads of them.
_MASKINGS = {SmithG2: _smith_g2, ThesisSmith: _thesis_smith}


# --- the kernel --------------------------------------------------------------------------------

@numba.njit(cache=True)
def i0e(x):
    """scipy.special.i0e (Cephes), x ≥ 0."""
    x = abs(x)
    if x <= 8.0:
        return _chbevl(x / 2.0 - 2.0, _I0E_A)
    return _chbevl(32.0 / x - 2.0, _I0E_B) / math.sqrt(x)


@numba.njit(cache=True)
def _chbevl(x, coefficients):
    b0, b1, b2 = coefficients[0], 0.0, 0.0
    for i in range(1, coefficients.size):
        b2 = b1
        b1 = b0
        b0 = x * b1 - b2 + coefficients[i]
    return 0.5 * (b0 - b2)


@numba.njit(cache=True)
def _powers(y, count, out):
    """y⁰ … y^(count − 1) into ``out`` by :func:`brdfs.physics.distributions._powers`' doubling (the same
    products: y^(m + j) = y^j y^m, y^m = y^(m − 1) y)."""
    out[0] = 1.0
    m = 1
    while m < count:
        k = min(m, count - m)
        out[m] = out[m - 1] * y
        for j in range(1, k):
            out[m + j] = out[j] * out[m]
        m *= 2


@numba.njit(cache=True)
def series_terms(x, n):
    """The series' terms T of :func:`kummer_half_integers` for the call's ``x[:n]`` (its largest x < 40)."""
    top = -1.0
    for i in range(n):
        if x[i] < _KUMMER_SWITCH and x[i] > top:
            top = x[i]
    if top < 0.0:
        return 0
    return int(min(float(_SERIES_TERMS), math.ceil(top + 10 * math.sqrt(top) + 25)))


@numba.njit(cache=True)
def kummer(x, terms, powers, out):
    """:func:`kummer_half_integers` at one x into ``out`` (F₀, F₁, F₂ and their bounds), ``terms`` the
    call's series terms (:func:`series_terms`), ``powers`` a scratch row of ≥ 42 doubles."""
    if x < _KUMMER_SWITCH:
        f0 = i0e(0.5 * x)
        out[0] = f0
        out[3] = 8 * _EPS * f0
        _powers(x, terms, powers)
        scale = math.exp(-x)
        for k in range(2):
            total = 0.0
            for n in range(terms):
                total += _SERIES[k, n] * powers[n]
            out[1 + k] = scale * total
            out[4 + k] = (2 * terms + 4) * _EPS * out[1 + k]
        return
    n_terms = _ASYMPTOTIC_TERMS
    y = 1.0 / x
    _powers(y, n_terms + 2, powers)
    log_x = math.log(x)
    for k in range(3):
        total = 0.0
        for s in range(n_terms + 1):
            total += _ASYMPTOTIC[k, s] * powers[s]
        omitted = _ASYMPTOTIC[k, n_terms + 1] * powers[n_terms + 1]
        high = math.exp(_ASYMPTOTIC_LOG_SCALE[k] - _ASYMPTOTIC_POWER[k] * log_x) * total
        out[k] = high
        rounding = n_terms + 8 + 2 * _ASYMPTOTIC_POWER[k] * abs(log_x)
        if high > 0:
            out[3 + k] = high * (rounding * _EPS + omitted / total)
        elif math.isinf(log_x):
            out[3 + k] = 0.0
        else:
            out[3 + k] = _TINY


@numba.njit(cache=True)
def smith_lambda_cos(dist, alpha, c):
    """λ(μ) = Λ μ of the distribution (:meth:`GGX.smith_lambda_cos`, :meth:`Beckmann.smith_lambda_cos`)."""
    c = min(max(c, 0.0), 1.0)
    if dist == GGX_CODE:
        s2 = (1.0 - c) * (1.0 + c)
        a2 = alpha ** 2
        return 0.5 * a2 * s2 / (math.sqrt(c * c + a2 * s2) + c)
    s = math.sqrt((1.0 - c) * (1.0 + c))
    alpha_s = alpha * s
    if not alpha_s > 0:
        return 0.0
    a = c / alpha_s
    return alpha_s * math.exp(-a * a) / _TWO_SQRT_PI - 0.5 * c * math.erfc(a)


@numba.njit(cache=True)
def thesis_g1(alpha, x):
    """The thesis's G* (eq. 1.38, :meth:`Beckmann.smith_g1_thesis`)."""
    if x >= 1.0:
        return 1.0
    h = x * x / (2 * alpha ** 2 * (1 - x * x))
    g = math.sqrt(math.pi * h) * (2 - math.erfc(math.sqrt(h)))
    return g / (g + 1)


@numba.njit(cache=True)
def light_factor(form, dist, alpha, nl):
    """The masking's factor of N·L alone, computed once per call: λ(N·L), or G*(N·L) (``dist`` and
    ``alpha``: the masking's)."""
    if form == THESIS_SMITH_CODE:
        return thesis_g1(alpha, nl)
    return smith_lambda_cos(dist, alpha, nl)


@numba.njit(cache=True)
def masking(form, dist, alpha, scale, nl, light, nv):
    """S(N·L, N·V), ``light`` its factor of N·L (:func:`light_factor`): Smith's G2/(4 N·L N·V)
    (:class:`SmithG2`) or C G*(N·L) G*(N·V)/(4 N·L N·V) (:class:`ThesisSmith`)."""
    if form == THESIS_SMITH_CODE:
        return scale * (light * thesis_g1(alpha, nv)) / (4 * nl * nv)
    lam_v = smith_lambda_cos(dist, alpha, nv)
    if form == HEIGHT_CORRELATED_CODE:
        return 1.0 / (4.0 * (nl * nv + nv * light + nl * lam_v))
    return 1.0 / (4.0 * (nl + light) * (nv + lam_v))


@numba.njit(cache=True)
def radial_integrand(dist, alpha, form, s_dist, s_alpha, scale, theta_l, mu_l, s_l, theta_v, value, rounding,
                     start, stop):
    """:func:`.polar.radial_integrand` (D of ``dist`` and ``alpha``, S of the masking ``form`` with its
    ``s_dist``, ``s_alpha`` and ``scale``) at the nodes ``theta_v[start:stop]`` (rows of 21) into ``value`` and
    ``rounding`` (same rows): 2 sin θ_V cos θ_V S Φ and its rounding bound.  The rows are one call of
    the numpy integrand (the Kummer series' terms follow the call's largest x)."""
    width = theta_v.shape[1]
    n = (stop - start) * width
    q, b, mu, s = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    for i in range(n):
        tv = theta_v[start + i // width, i % width]
        mu[i], s[i] = math.cos(tv), math.sin(tv)
        h_z = mu_l + mu[i]
        q[i] = math.tan(0.5 * (theta_l - tv)) ** 2
        b[i] = 2.0 * s_l * s[i] / (h_z * h_z)
    a2 = alpha ** 2
    terms = 0
    if dist == BECKMANN_CODE:
        x = np.empty(n)
        for i in range(n):
            x[i] = 2.0 * b[i] / a2
        terms = series_terms(x, n)
    powers = np.empty(max(terms, _ASYMPTOTIC_TERMS + 2))
    f = np.empty(6)
    light = light_factor(form, s_dist, s_alpha, mu_l)
    for i in range(n):
        mu_v, s_v = mu[i], s[i]
        if dist == GGX_CODE:
            phi, phi_err = _ggx_azimuthal(a2, q[i], b[i])
        else:
            kummer(2.0 * b[i] / a2, terms, powers, f)
            phi, phi_err = _beckmann_azimuthal(a2, q[i], b[i], f)
        weight = 2.0 * s_v * mu_v * masking(form, s_dist, s_alpha, scale, mu_l, light, mu_v)
        v = weight * phi
        if phi == 0:
            v = 0.0                      # D vanishes (e^−q/α² underflows): zero, not 0·∞
        r = abs(weight) * phi_err + S_ROUNDING * _EPS * abs(v)
        row, col = start + i // width, i % width
        value[row, col] = v
        rounding[row, col] = r if math.isfinite(r) else 0.0


@numba.njit(cache=True)
def _ggx_azimuthal(a2, q, b):
    """:meth:`GGX.azimuthal_integral` at one node."""
    k = 1.0 - a2
    near = a2 + q
    far = near + 2.0 * b
    r = math.sqrt(near * far)
    c = near + b
    second, third = 2.0 * k / r, k * k * c / (r * r * r)
    total = 1.0 + second + third
    magnitudes = total if k >= 0 else 1.0 + abs(second) + third
    return a2 * total, 16 * _EPS * a2 * magnitudes


@numba.njit(cache=True)
def _beckmann_azimuthal(a2, q, b, f):
    """:meth:`Beckmann.azimuthal_integral` at one node, F and bounds ``f`` (:func:`kummer`)."""
    p = 1.0 + q
    exponent = q / a2
    scale = math.exp(-exponent) / a2
    w0, w1, w2 = p * p, 2 * p * b, 1.5 * b * b
    value = scale * (w0 * f[0] + w1 * f[1] + w2 * f[2])
    rounding = scale * (w0 * f[3] + w1 * f[4] + w2 * f[5]) + (2 * exponent + 16) * _EPS * value
    return value, rounding


# --- the breakpoints ---------------------------------------------------------------------------

@numba.njit(cache=True)
def breakpoints_of_one(theta_l, lobe_offsets, level_angles):
    """:func:`.polar._breakpoints_of_one` as one ascending row: 0, π/2 and, inside, θ_L plus the lobe's
    offsets and the angles of the levels (the model's and the graded ones toward the horizon, as the
    numpy path computes them: :func:`.polar._compiled_level_angles`)."""
    cand = np.empty(2 + lobe_offsets.size + level_angles.size)
    cand[0], cand[1] = 0.0, _HALF_PI
    n = 2
    for offset in lobe_offsets:
        n = _keep(cand, n, theta_l + offset)
    for angle in level_angles:
        n = _keep(cand, n, angle)
    row = np.sort(cand[:n])
    out = np.empty(n)
    out[0] = row[0]
    m = 1
    for i in range(1, n):
        if row[i] != out[m - 1]:
            out[m] = row[i]
            m += 1
    return out[:m]


@numba.njit(cache=True)
def _keep(cand, n, c):
    """Append ``c`` if it lies inside (0, π/2) (NaN does not); the new count."""
    if 0.0 < c < _HALF_PI:
        cand[n] = c
        return n + 1
    return n


# --- one angle, one call -----------------------------------------------------------------------

@numba.njit(cache=True)
def albedo_one(dist, alpha, form, s_dist, s_alpha, scale, theta_l, mu_l, s_l, lobe_offsets, level_angles, rtol,
               atol, fill):
    """The polar route's albedo at one angle (:func:`.polar._albedo_one`): its breakpoints, the radial
    integrand and the driver's single-element path, compiled.  (value, error, evaluations, status code)."""
    st = gkc.start(breakpoints_of_one(theta_l, lobe_offsets, level_angles), rtol, atol, fill)
    while not gkc.finished(st):
        x = gkc.pending(st)
        value, rounding = np.empty_like(x), np.empty_like(x)
        for start in range(0, x.shape[0], CHUNK):
            radial_integrand(dist, alpha, form, s_dist, s_alpha, scale, theta_l, mu_l, s_l, x, value, rounding,
                             start, min(start + CHUNK, x.shape[0]))
        st = gkc.absorb(st, value, value, rounding)
    value, error, evaluations, status, _ = gkc.result(st)
    return value, error, evaluations, status


# numba keys its cache on this file alone: drop it when a module this one depends on has changed
compiled.drop_stale_cache(sys.modules[__name__])
