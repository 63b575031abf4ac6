"""``integrate(..., return_rounds=True)`` says how many refinement rounds it ran: 0 exactly when its first
evaluation stopped it (the patch mixtures' second pass is skipped on that, ``patch_geometry``)."""
import numpy as np
import pytest

from brdfs.core import gauss_kronrod


@pytest.mark.parametrize("breakpoints", [[[0.0, 1.0]], [[0.0, 0.5, 1.0], [0.0, 1.0, np.nan]]])
def test_the_rounds_reported_are_the_evaluations_after_the_first(breakpoints, monkeypatch):
    calls = []
    evaluate = gauss_kronrod._evaluate
    monkeypatch.setattr(gauss_kronrod, "_evaluate", lambda *a: (calls.append(1), evaluate(*a))[1])
    for integrand, smooth in ((lambda x, e: np.cos(x), True), (lambda x, e: np.sqrt(np.abs(x - 0.3)), False)):
        calls.clear()
        est, rounds = gauss_kronrod.integrate(integrand, breakpoints, rtol=1e-10, return_rounds=True)
        assert rounds == len(calls) - 1 and (rounds == 0) == smooth
        plain = gauss_kronrod.integrate(integrand, breakpoints, rtol=1e-10)
        assert np.array_equal(plain.value, est.value) and np.array_equal(plain.error, est.error)
