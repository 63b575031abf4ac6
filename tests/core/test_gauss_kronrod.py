"""The vectorised Gauss–Kronrod driver (integrate.gauss_kronrod): its error estimate against exact integrals."""
import numpy as np

import pytest

from brdfs.core.gauss_kronrod import KRONROD_WEIGHTS, GAUSS_WEIGHTS, NODES, NodeValues, integrate


def _rule_error(f, exact):
    """(K − G, G − exact) of the 10/21-point pair on [0, 1]."""
    v = f(0.5 * (NODES + 1))
    k, g = 0.5 * v @ KRONROD_WEIGHTS, 0.5 * v @ GAUSS_WEIGHTS
    return k - g, g - exact


def test_error_is_the_sum_of_interval_errors_not_the_error_of_the_sum():
    """√x on [0, 1] (K only ~20 times better than G at the singular end) beside c (2x − 3)³⁰ on
    [1, 2] (K exact, G not) with c chosen so that the two K − G cancel: |ΣK − ΣG| is then zero
    while the Gauss sum is still off by K's own error on the first interval."""
    d1, _ = _rule_error(np.sqrt, 2 / 3)
    d2, _ = _rule_error(lambda x: (2 * x - 1) ** 30, 1 / 31)
    c = -d1 / d2

    def f(x, elem):
        return np.where(x < 1, np.sqrt(np.minimum(x, 1)), c * (2 * x - 3) ** 30)

    exact = 2 / 3 + c / 31
    est = integrate(f, np.array([[0.0, 1.0, 2.0]]), rtol=1e-1, atol=1e-1)   # no refinement
    true = abs(est.value[0] - exact)
    assert true > 1e-7                                  # the case is real: K − G cancel, the error does not
    assert true <= est.error[0] <= 1000 * true


def test_error_brackets_the_truth_on_a_refined_singular_integral():
    """x log x on [0, 1] refined to 1e-10: honest, and not inflated beyond the contract's 1000."""
    est = integrate(lambda x, e: x * np.log(np.where(x > 0, x, 1.0)), np.array([[0.0, 1.0]]), rtol=1e-10, atol=0)
    true = abs(est.value[0] + 0.25)
    assert true <= est.error[0] <= max(1000 * true, 1e-13)
    assert est.status[0] == "converged"


def test_an_integrand_returning_node_values_reports_their_gauss_value_and_carries_their_known_error():
    """The two kinds of integrand: a plain array (high = low, nothing known) and ``NodeValues`` of an
    inner estimate.  Its Gauss values ``low`` are what the driver sums (x² + 1e-6 x⁴ against x²: the
    value moves by 6.4e-6), and its known error (1e-9 per unit length, rules agreeing) enters the
    reported error, so no split brings it to 1e-12 and the element is not converged."""
    plain = integrate(lambda x, e: x * x, np.array([[0.0, 2.0]]), rtol=1e-12, atol=0)
    assert abs(plain.value[0] - 8 / 3) <= plain.error[0] <= 1e-13 and plain.status[0] == "converged"
    shifted = integrate(lambda x, e: NodeValues(x * x, x * x + 1e-6 * x ** 4, None), np.array([[0.0, 2.0]]),
                        rtol=1e-3, atol=0)
    assert shifted.value[0] == pytest.approx(8 / 3 + 1e-6 * 32 / 5, rel=1e-14)
    known = integrate(lambda x, e: NodeValues(x * x, x * x, np.full_like(x, 1e-9)), np.array([[0.0, 2.0]]),
                      rtol=1e-12, atol=0)
    assert 2e-9 <= known.error[0] <= 3e-9 and known.status[0] != "converged"
