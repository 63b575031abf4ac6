"""W(p, q, a, b) = ∫₀^π (p + q cos φ) √[a + b cos φ]₊ dφ in closed form (integrate.ward_azimuth).

mpmath is not in the project's environment, so the sweep's reference is scipy's QUADPACK on the lit
arc, with N·V written without cancellation (α − 2b sin²(φ/2), β + 2b cos²(φ/2)), W₁ rationalised
(b cos²φ / (√N·V + √a)) when the whole circle is lit, and breakpoints graded geometrically
towards φ = π where the circle nearly touches the horizon: ≈ 10⁻¹⁵ relative to each moment.

That is not fine enough to test a rounding bound of a few ulps, so the bound is tested against
_TABLE: (a, b, W₀ hi, W₀ lo, W₁ hi, W₁ lo), each moment a double-double rounded from 50 digits,
computed with mpmath 1.3.0 (outside this environment) from eqs. (5a–d) with mpmath.elliprd and
eq. (6) with mpmath.hyp2f1 where a ≥ 2b, and checked against mpmath.quad over the lit arc at
40 digits (agreement better than 10⁻²⁵ relative; for b = 10⁻³⁰⁰ against πb/(4√a)).
"""
import math
import warnings
from fractions import Fraction

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad

from brdfs.numerics.integrate.ward_azimuth import sqrt_positive_part_moment, sqrt_positive_part_moments

EPS = np.finfo(float).eps
PQ = [(1.0, 0.0), (0.0, 1.0), (1.0, 0.5), (1.0, -0.5), (-0.3, 1.0), (0.7, -1.0), (0.25, 0.75)]

_TABLE = np.array([
    (-0.999999999999999, 1.0, 1.1098329600729789e-15, 6.979334317901939e-33, 1.1098329600729787e-15, -7.30419131730506e-32),
    (-0.999999999999, 1.0, 1.1106961634864384e-12, -9.358426663527731e-29, 1.1106961634861608e-12, -8.244387304889247e-29),
    (-0.999999, 1.0, 1.11072080399159e-06, 1.0028406683213896e-22, 1.1107205263113716e-06, 6.991106220946769e-23),
    (-0.5, 1.0, 0.5745933956087621, -4.9453653571473896e-17, 0.500237187703014, -2.7236302981167164e-17),
    (0.0, 1.0, 1.1981402347355923, -7.250663635457894e-17, 0.87401918476404, -1.0133836326017169e-17),
    (0.5, 1.0, 1.9004968798801045, 1.0291962465495202e-16, 1.0791928990209654, 9.842408246879235e-17),
    (0.999999, 1.0, 2.828420661349171, -1.8914597033462798e-16, 0.9428140907640371, -4.987896605388243e-17),
    (0.999999999999, 1.0, 2.8284271247348425, -5.5823260925113e-17, 0.9428090415919969, 2.877171681154171e-18),
    (0.9999999999999999, 1.0, 2.8284271247461885, -3.428382172078428e-17, 0.9428090415820648, 2.6561863189553114e-17),
    (1.0, 1.0, 2.8284271247461903, -1.9334586626905827e-16, 0.9428090415820634, 9.566246218657683e-18),
    (1.0000000000000002, 1.0, 2.8284271247461934, -1.2179600356329823e-16, 0.9428090415820605, 2.9990270324621177e-17),
    (1.000000000001, 1.0, 2.828427124757539, 1.5713889241446327e-18, 0.9428090415721289, -4.8152996859242707e-17),
    (1.000001, 1.0, 2.8284335881425116, -2.0678595931968967e-16, 0.9428039923978211, 1.489437230990912e-17),
    (1.5, 1.0, 3.7267123604354477, -1.1159252535592149e-16, 0.673704516981282, -7.30199704364799e-18),
    (1.9999999999999996, 1.0, 4.3688762854924015, 3.716897894449274e-16, 0.5697440220347286, -2.57936412125479e-17),
    (2.0, 1.0, 4.368876285492402, 3.726389316035123e-18, 0.5697440220347285, 1.4884030886000737e-17),
    (3.0, 1.0, 5.402575524190702, -7.307973241574571e-17, 0.4583763847203769, -5.975118572083847e-19),
    (10.0, 1.0, 9.928364531484812, -5.551253711898288e-16, 0.2485984018641972, 2.4843618398606235e-18),
    (1000000.0, 1.0, 3141.592653589597, -3.201597141449819e-14, 0.0007853981633975219, -3.3384188388057446e-21),
    (-9.99999999999e-13, 1e-12, 1.110774533275361e-18, 3.5657588856258707e-35, 1.1107745332750832e-18, 4.767191526579325e-35),
    (-3e-13, 1e-12, 8.170286383324139e-07, 4.5173710181601655e-23, 6.665853653795466e-07, -1.0403736547837568e-23),
    (9.99999999e-13, 1e-12, 2.8284271158405333e-06, 3.0449976518089913e-23, 9.428090490735066e-07, -4.2384936345465365e-23),
    (1.0000000010000002e-12, 1e-12, 2.8284271336518486e-06, -6.14880602812531e-23, 9.428090340906187e-07, 2.3711532355990915e-23),
    (2.5e-12, 1e-12, 4.915615073007876e-06, 5.0127369016135646e-23, 5.046547721706447e-07, 4.0758421315049585e-23),
    (-999.9, 1000.0, 0.003512429318478817, 1.2018674759425108e-19, 0.003512341507197026, 9.89655362914749e-20),
    (999.999, 1000.0, 89.44251470943156, 3.116540720921103e-15, 29.814399369150763, 2.279738396190931e-16),
    (2500.0, 1000.0, 155.44539731359762, 3.753823156069361e-15, 15.95858512132593, -2.7644100342592354e-16),
    (1.0, 1e-300, 3.141592653589793, 1.2246467991473532e-16, 7.853981633974484e-301, -6.5479133e-317),
    (1.0, 1e-08, 3.141592653589793, 1.0282972582979911e-16, 7.853981633974483e-09, 6.11817294410192e-25),
    (7.0, 0.0, 8.311872882066082, -1.658882539110552e-17, 0.0, 0.0),
    (1e-12, 1e-20, 3.1415926535897933e-06, -1.399126272852496e-22, 7.853981633974484e-15, -7.441917239412634e-31),
    (0.37, 0.3699999999999963, 1.7204650534085961, -9.651837604898305e-17, 0.5734883511361015, 2.3285418261611466e-17),
])


def _quad_moments(a, b):
    """W₀, W₁ by QUADPACK (epsrel 1e-14) over the lit arc [0, φ_e]."""
    if a <= -b:
        return 0.0, 0.0
    alpha, beta = a + b, a - b
    if a >= b:
        end = math.pi
    elif alpha <= b:                                   # φ_e = arccos(−a/b), from its smaller half-angle
        end = 2.0 * math.asin(math.sqrt(alpha / (2.0 * b)))
    else:
        end = math.pi - 2.0 * math.asin(math.sqrt((b - a) / (2.0 * b)))

    def nv(phi):
        if phi < math.pi / 2:
            return alpha - 2.0 * b * math.sin(phi / 2) ** 2
        return beta + 2.0 * b * math.cos(phi / 2) ** 2

    def f0(phi):
        return math.sqrt(max(nv(phi), 0.0))

    if a >= b:          # ∫₀^π cos φ dφ = 0: W₁ = ∫ cos φ (√N·V − √a) dφ, without the cancellation
        def f1(phi):
            return b * math.cos(phi) ** 2 / (math.sqrt(nv(phi)) + math.sqrt(a))
    else:
        def f1(phi):
            return math.cos(phi) * math.sqrt(max(nv(phi), 0.0))

    points = [0.0, end / 2]
    if 0 < abs(beta) < 0.01 * b:        # nearly touching: the kink at π − √(|β|/b), graded
        width, graded = math.sqrt(abs(beta) / b), []
        while width < end / 4:
            graded.append(end - width)
            width *= 2.0
        points += graded[::-1]
    points.append(end)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        return tuple(sum(quad(f, lo, hi, epsabs=1e-300, epsrel=1e-14, limit=200)[0]
                         for lo, hi in zip(points, points[1:])) for f in (f0, f1))


def _sweep():
    ratios = [-1.5, -1 - 1e-6, -1 - 1e-12, -1.0, -1 + 1e-12, -1 + 1e-6, -0.5, 0.0, 0.5, 1 - 1e-6, 1 - 1e-12,
              1.0, 1 + 1e-12, 1 + 1e-6, 1.5, 2.0, 3.0, 10.0, 1e4]
    ab = [(r * b, b) for b in (1e-12, 1e-6, 1e-3, 0.37, 1.0) for r in ratios]
    ab += [(1.0, b) for b in (0.0, 1e-300, 1e-12, 1e-6)]
    return np.array(ab)


def test_matches_quad_over_a_sweep_of_regimes():
    """a/b from −1.5 to 1e4 (±1e-12, ±1e-6 around ∓1, exactly 0), b from 1e-12 to 1 and b ≪ a,
    p and q of both signs: within 1e-13 of the scale S = (|p| + |q|) √(|a| + b) π, and within 1e-13
    of |p| W₀ + |q| W₁ (relative to W itself wherever p W₀ and q W₁ do not cancel)."""
    ab = _sweep()
    ref = np.array([_quad_moments(a, b) for a, b in ab])
    p, q = (np.array(PQ)[:, k, None] for k in (0, 1))
    value, bound = sqrt_positive_part_moment(p, q, ab[:, 0], ab[:, 1])
    expected = p * ref[:, 0] + q * ref[:, 1]
    scale = (np.abs(p) + np.abs(q)) * np.sqrt(np.abs(ab[:, 0]) + ab[:, 1]) * np.pi
    componentwise = np.abs(p) * ref[:, 0] + np.abs(q) * ref[:, 1]
    assert np.all(np.abs(value - expected) <= 1e-13 * scale)
    assert np.all(np.abs(value - expected) <= 1e-13 * componentwise)
    assert np.all(bound <= 1e-14 * np.maximum(componentwise, 1e-300))     # bounds are ulps, not quad's


def _table_errors(p, q):
    """Exact |computed − reference| of W over _TABLE, with the reported bound."""
    a, b, h0, l0, h1, l1 = _TABLE.T
    value, bound = sqrt_positive_part_moment(p, q, a, b)
    fp, fq = Fraction(p), Fraction(q)
    err = [abs(Fraction(v) - fp * (Fraction(x0) + Fraction(y0)) - fq * (Fraction(x1) + Fraction(y1)))
           for v, x0, y0, x1, y1 in zip(value, h0, l0, h1, l1)]
    return np.array([float(e) for e in err]), bound


@pytest.mark.parametrize("p, q", PQ)
def test_true_error_never_exceeds_the_reported_bound(p, q):
    err, bound = _table_errors(p, q)
    assert np.all(err <= bound)


def test_bound_is_within_100_times_the_typical_error():
    ratios = []
    for p, q in PQ:
        err, bound = _table_errors(p, q)
        ratios.extend(bound[err > 0] / err[err > 0])
    assert np.median(ratios) <= 100.0


def test_moments_are_accurate_to_a_few_ulps_of_themselves():
    """Both moments, tiny caps, touching circles and b ≪ a included: ≤ 4 ε relative to W₀ and W₁
    (measured ≤ 2.7 ε and ≤ 3.8 ε over 2·10⁴ random (a, b) against mpmath)."""
    a, b, h0, l0, h1, l1 = _TABLE.T
    w0, w1, _, _ = sqrt_positive_part_moments(a, b)
    for w, h, l in ((w0, h0, l0), (w1, h1, l1)):
        assert np.all(np.abs((w - h) - l) <= 4 * EPS * np.abs(h))


def test_zero_below_the_horizon():
    """a ≤ −b (the circle entirely below, touching from below, a = b = 0, b = 0 with a < 0): exactly
    zero, with a zero bound."""
    a = np.array([-1.5, -1.0, -1.0 - 1e-12, np.nextafter(-1.0, -2.0), 0.0, -0.0, -3.0, -1e-300])
    b = np.array([1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1e-300])
    value, bound = sqrt_positive_part_moment(0.8, -0.6, a, b)
    assert np.all(value == 0.0) and np.all(bound == 0.0)
    just_above, _ = sqrt_positive_part_moment(1.0, 0.0, np.nextafter(-1.0, 0.0), 1.0)
    assert 0.0 < just_above < 1e-15


def test_small_b_limit_is_pi_p_sqrt_a():
    """b = 0 gives π p √a to rounding (W₁ exactly 0); b ≪ a adds W₁ = π b / (4√a) (1 + O(b²/a²)).
    The float comparison values carry up to 2 ulps of their own."""
    a = np.array([1e-12, 0.3, 1.0, 7.0, 1e6])
    value, bound = sqrt_positive_part_moment(1.3, -0.7, a, 0.0)
    assert np.all(np.abs(value - 1.3 * np.pi * np.sqrt(a)) <= 4 * EPS * value)
    assert np.all(bound <= 10 * EPS * value)
    for ratio in (1e-290, 1e-20, 1e-9):
        w0, w1, _, _ = sqrt_positive_part_moments(a, ratio * a)
        assert np.all(np.abs(w0 - np.pi * np.sqrt(a)) <= 4 * EPS * w0)
        assert np.all(np.abs(w1 - np.pi * ratio * a / (4 * np.sqrt(a))) <= 4 * EPS * w1)


def test_continuous_across_a_equals_b():
    """The two cases (whole circle a ≥ b, cap |a| < b) meet at a = b with W₀ = 2√(2b), W₁ = (2/3)√(2b),
    and approach it from either side like δ log(1/δ), a few ulps from the neighbouring floats."""
    for b in (1e-12, 0.37, 1.0, 1e3):
        w0, w1, _, _ = sqrt_positive_part_moments(b, b)
        root = math.sqrt(2 * b)
        assert abs(w0 - 2 * root) <= 2 * EPS * w0 and abs(w1 - 2 * root / 3) <= 2 * EPS * w1
        for delta in (2 * EPS, 1e-12, 1e-6):
            for a in (b * (1 - delta), b * (1 + delta)):
                v0, v1, _, _ = sqrt_positive_part_moments(a, b)
                step = 2 * abs(a - b) / root * (1 + math.log(b / abs(a - b)))   # ≥ |∂W/∂a| |a − b|
                assert abs(v0 - w0) <= step + 4 * EPS * w0
                assert abs(v1 - w1) <= step + 4 * EPS * w1
        below, above = np.nextafter(b, 0.0), np.nextafter(b, 2 * b)
        trio = sqrt_positive_part_moments(np.array([below, b, above]), b)[0]
        assert np.all(np.diff(trio) >= -4 * EPS * w0) and np.ptp(trio) <= 16 * EPS * w0


def test_series_and_elliptic_forms_of_w1_agree_at_the_switch():
    """W₁ switches from eq. (5b) to the series (6) at a = 2b: the neighbouring floats agree."""
    for b in (1e-6, 1.0, 50.0):
        a = np.array([np.nextafter(2 * b, 0.0), 2 * b, np.nextafter(2 * b, 4 * b)])
        w1 = sqrt_positive_part_moments(a, b)[1]
        assert np.ptp(w1) <= 6 * EPS * w1[1]


def test_broadcasts_propagates_nan_and_rejects_negative_b():
    value, bound = sqrt_positive_part_moment(np.array([1.0, 2.0])[:, None, None], 0.5,
                                             np.linspace(-2, 3, 4)[:, None], np.array([0.0, 0.5, 1.0]))
    assert value.shape == bound.shape == (2, 4, 3)
    single, _ = sqrt_positive_part_moment(2.0, 0.5, np.linspace(-2, 3, 4)[2], 0.5)
    assert value[1, 2, 1] == single and np.ndim(single) == 0
    nan_value, nan_bound = sqrt_positive_part_moment(1.0, 1.0, [np.nan, 1.0], [1.0, np.nan])
    assert np.all(np.isnan(nan_value)) and np.all(np.isnan(nan_bound))
    with pytest.raises(ValueError):
        sqrt_positive_part_moment(1.0, 1.0, 1.0, -1e-3)
