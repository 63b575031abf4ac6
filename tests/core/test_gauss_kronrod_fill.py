"""The driver's ``fill`` (several levels of bisection per round for cheap integrands) and the
multisection root finder of the Torrance–Sparrow breakpoints: fewer rounds, the same honesty."""
import numpy as np
import pytest

from brdfs.core.gauss_kronrod import FILL_CHEAP, integrate
from brdfs.numerics.integrate import hemisphere
from brdfs.physics.models import model

#: (integrand, breakpoints, exact): an endpoint singularity, a narrow peak, a kink inside an interval.
PROBLEMS = [
    (lambda x: np.sqrt(x), [0.0, 1.0], 2.0 / 3.0),
    (lambda x: 1.0 / (1e-4 + (x - 0.3) ** 2), [0.0, 1.0], 100.0 * (np.arctan(70.0) + np.arctan(30.0))),
    (lambda x: np.abs(x - 1.0 / 3.0) ** 1.5, [0.0, 1.0], ((1 / 3) ** 2.5 + (2 / 3) ** 2.5) / 2.5),
]


def _rounds(f, bp, rtol, fill):
    calls = []

    def counted(x, elem):
        calls.append(x.shape[0])
        return f(x)

    est = integrate(counted, np.array([bp]), rtol=rtol, atol=1e-300, fill=fill)
    return est, len(calls)


@pytest.mark.parametrize("index", range(len(PROBLEMS)))
@pytest.mark.parametrize("rtol", [1e-10, 1e-6])
def test_fill_cuts_the_rounds_of_a_single_element_and_keeps_the_error_honest(index, rtol):
    f, bp, exact = PROBLEMS[index]
    plain, plain_rounds = _rounds(f, bp, rtol, fill=0)
    filled, filled_rounds = _rounds(f, bp, rtol, fill=FILL_CHEAP)
    for est in (plain, filled):
        assert est.status[0] == "converged"
        assert abs(est.value[0] - exact) <= est.error[0] <= rtol * exact
    assert filled_rounds <= max(2, plain_rounds // 2)


def test_fill_zero_is_plain_bisection():
    """√x on [0, 1] to 1e-10 by bisection: 31 intervals (651 nodes), one new pair per round."""
    est, rounds = _rounds(np.sqrt, [0.0, 1.0], 1e-10, fill=0)
    assert (est.evaluations, rounds) == (651, 16)


def test_multisection_finds_the_torrance_sparrow_switch_radii_bisection_finds():
    """The radii where eq. 2.10's switches start or stop cutting the circles, by multisection,
    against bisection of the same gap functions to rounding (60 halvings)."""
    brdf = model("cook_torrance", m=0.1)
    theta = np.linspace(0.0, 89.99, 40)
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    levels = [np.zeros_like(mu)] + [np.broadcast_to(c, mu.shape) for c in brdf.nv_levels(mu)]
    t_max = brdf.lobe.t_of(0.5 * (np.pi / 2 + np.radians(theta)))

    def bisection(fn, a, b, sign_a):
        for _ in range(60):
            mid = 0.5 * (a + b)
            same = np.sign(fn(mid[:, None])[:, 0]) == sign_a
            a, b = np.where(same, mid, a), np.where(same, b, mid)
        return a, b

    found = hemisphere._lh_radial_breakpoints(brdf, mu, st, levels, t_max)
    original = hemisphere._multisection
    try:
        hemisphere._multisection = bisection
        bisected = hemisphere._lh_radial_breakpoints(brdf, mu, st, levels, t_max)
    finally:
        hemisphere._multisection = original
    assert sum(r.size for r in found) > 40
    for a, b in zip(found, bisected):
        np.testing.assert_allclose(a, b, rtol=8 * np.finfo(float).eps, atol=0)
