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



def _kink_radii(brdf, mu, st, levels, t_max):
    """The L·H kink radii per angle, as the engine cuts them: the midpoints of their brackets."""
    return [0.5 * (lo + hi) for lo, hi in hemisphere._lh_radial_brackets(brdf, mu, st, levels, t_max,
                                                                         hemisphere.ROOT_RTOL)]

def test_multisection_finds_the_torrance_sparrow_switch_radii_bisection_finds():
    """The radii where eq. 2.10's switches start or stop cutting the circles, by multisection (to
    ``ROOT_RTOL`` of their distance from the ends of [0, 1]), against bisection of the same gap
    functions to rounding (60 halvings)."""
    brdf = model("cook_torrance", m=0.1)
    theta = np.linspace(0.0, 89.99, 40)
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    levels = [np.zeros_like(mu)] + [np.broadcast_to(c, mu.shape) for c in brdf.nv_levels(mu)]
    t_max = brdf.lobe.t_of(0.5 * (np.pi / 2 + np.radians(theta)))

    def bisection(fn, a, b, sign_a, root_rtol=None):
        for _ in range(60):
            mid = 0.5 * (a + b)
            same = np.sign(fn(mid[:, None])[:, 0]) == sign_a
            a, b = np.where(same, mid, a), np.where(same, b, mid)
        return a, b

    found = _kink_radii(brdf, mu, st, levels, t_max)
    original = hemisphere._multisection
    try:
        hemisphere._multisection = bisection
        bisected = _kink_radii(brdf, mu, st, levels, t_max)
    finally:
        hemisphere._multisection = original
    assert sum(r.size for r in found) > 40
    for a, b in zip(found, bisected):
        slack = np.maximum(8 * np.finfo(float).eps * b, hemisphere.ROOT_RTOL * np.minimum(b, 1.0 - b))
        assert np.all(np.abs(a - b) <= slack)


@pytest.mark.parametrize("index", range(len(PROBLEMS)))
@pytest.mark.parametrize("rtol", [1e-10, 1e-6])
def test_a_single_element_takes_the_batched_drivers_decisions(index, rtol):
    """Alone, an element's rounds are decided on Python floats (the single-element fast path); in a
    batch, on arrays.  Without ``fill`` the elements are refined independently, so the element must
    take the same intervals either way (its nodes counted), and its sums agree to rounding (the
    rules' dot products may round differently in a larger batch, and K − G cancels)."""
    f, bp, _ = PROBLEMS[index]
    nodes = {}

    def counted(key):
        def integrand(x, elem):
            nodes[key] = nodes.get(key, 0) + int(np.sum(elem == 0)) * x.shape[1]
            return f(x)
        return integrand

    alone = integrate(counted("alone"), np.array([bp]), rtol=rtol, atol=1e-300)
    batch = integrate(counted("batch"), np.array([bp, [0.0, 0.5]]), rtol=rtol, atol=1e-300)
    assert nodes["alone"] == nodes["batch"] == alone.evaluations
    assert alone.status[0] == batch.status[0] == "converged"
    np.testing.assert_allclose(alone.value[0], batch.value[0], rtol=1e-14)
    np.testing.assert_allclose(alone.error[0], batch.error[0], rtol=1e-4)      # Σ|K − G| of near-equal sums


def test_few_brackets_take_the_roots_the_gathered_gap_functions_take():
    """A single angle's brackets (one or two) evaluate every gap function and pick their own; many
    brackets gather each one's own function (``selected_gap``): the same radii to the bit."""
    brdf = model("cook_torrance", m=0.1)
    theta = np.array([30.0, 61.0, 88.5])
    mu, st = np.cos(np.radians(theta)), np.sin(np.radians(theta))
    levels = [np.zeros_like(mu)] + [np.broadcast_to(c, mu.shape) for c in brdf.nv_levels(mu)]
    t_max = brdf.lobe.t_of(0.5 * (np.pi / 2 + np.radians(theta)))
    picked = _kink_radii(brdf, mu, st, levels, t_max)
    few = hemisphere._FEW_BRACKETS
    try:
        hemisphere._FEW_BRACKETS = 0
        gathered = _kink_radii(brdf, mu, st, levels, t_max)
    finally:
        hemisphere._FEW_BRACKETS = few
    assert sum(r.size for r in picked) >= 3
    for a, b in zip(picked, gathered):
        assert np.array_equal(a, b)
